// The executor (framework/util/parallel.hpp): every task runs once on some thread, traces are filled, and an
// exception thrown by a task inside the OpenMP region comes back to the caller instead of ending the program.
#include <gtest/gtest.h>

#include <atomic>
#include <stdexcept>

#include "framework/util/error.hpp"
#include "framework/util/parallel.hpp"

namespace ccdlab {
namespace CCDLAB_UNITY_ID {  // a namespace of this file's own (tests/CMakeLists.txt)

TEST(Executor, EveryTaskRunsOnceUnderBothDistributions) {
  for (Distribution dist : {Distribution::dynamic, Distribution::static_chunks})
    for (int threads : {1, 2, 5}) {
      std::vector<std::atomic<int>> runs(1000);
      PhaseTrace trace;
      parallel_tasks(runs.size(), threads, dist, trace, [&](std::size_t i, int tid) {
        ASSERT_GE(tid, 0);
        ASSERT_LT(tid, threads);
        runs[i].fetch_add(1);
      });
      for (const auto& r : runs) EXPECT_EQ(r.load(), 1);
      EXPECT_EQ(trace.task_ms.size(), runs.size());
      EXPECT_EQ(trace.thread_ms.size(), std::size_t(threads));
      EXPECT_EQ(trace.distribution, dist);
    }
}

TEST(Executor, StaticBalancedRunsEachTaskOnItsAssignedThread) {
  for (int threads : {1, 2, 5}) {
    std::vector<int> thread_of(1000);
    for (std::size_t i = 0; i < thread_of.size(); ++i) thread_of[i] = int((i * 7) % std::size_t(threads));
    std::vector<std::atomic<int>> ran_on(thread_of.size());
    for (auto& r : ran_on) r.store(-1);
    PhaseTrace trace;
    parallel_tasks(
        thread_of.size(), threads, Distribution::static_balanced, trace,
        [&](std::size_t i, int tid) { ran_on[i].store(tid); }, &thread_of);
    for (std::size_t i = 0; i < thread_of.size(); ++i) EXPECT_EQ(ran_on[i].load(), thread_of[i]) << i;
    EXPECT_EQ(trace.distribution, Distribution::static_balanced);
  }
}

TEST(Executor, RegionsAppendToTheirPhasesTrace) {
  PhaseTrace trace;
  parallel_tasks(5, 2, Distribution::dynamic, trace, [](std::size_t, int) {});
  parallel_chunks(10, 4, 3, trace, [](std::size_t, std::size_t, int) {});
  EXPECT_EQ(trace.task_ms.size(), 5u + 3u);
  EXPECT_EQ(trace.region_begin, (std::vector<std::size_t>{0, 5}));
  EXPECT_EQ(trace.thread_ms.size(), 3u);  // the most threads any region had
}

TEST(Executor, ChunksCoverTheRangeExactly) {
  std::vector<std::atomic<int>> hits(1001);
  PhaseTrace trace;
  parallel_chunks(hits.size(), 64, 3, trace, [&](std::size_t b, std::size_t e, int) {
    for (std::size_t i = b; i < e; ++i) hits[i].fetch_add(1);
  });
  for (const auto& h : hits) EXPECT_EQ(h.load(), 1);
  EXPECT_EQ(trace.task_ms.size(), (hits.size() + 63) / 64);
}

TEST(Executor, AnExceptionInATaskIsRethrownOnTheCaller) {
  for (Distribution dist : {Distribution::dynamic, Distribution::static_chunks})
    for (int threads : {1, 4}) {
      PhaseTrace trace;
      try {
        parallel_tasks(200, threads, dist, trace, [&](std::size_t i, int) {
          if (i == 17) fail("task {} failed", i);
        });
        ADD_FAILURE() << "no exception";
      } catch (const Error& e) {
        EXPECT_STREQ(e.what(), "task 17 failed");
      }
      // Other exception types come back too (bad_alloc, logic errors: internal errors for main to report).
      EXPECT_THROW(parallel_tasks(8, threads, dist, trace, [](std::size_t i, int) {
                     if (i == 3) throw std::logic_error("bug");
                   }),
                   std::logic_error);
    }
}

}  // namespace
}  // namespace ccdlab
