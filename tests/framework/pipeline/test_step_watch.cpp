// A step's time limit and progress (step_watch.hpp): past time_limit the workers stop taking chunks and the step
// throws Error saying where it was and how far it got; without a limit it runs to the end; the progress report
// counts the candidate pairs tested, is called once per due time whatever the threads, and is silent before
// its first due time.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <limits>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "framework/pipeline/ccd_pipeline.hpp"
#include "framework/pipeline/step_watch.hpp"
#include "framework/util/error.hpp"
#include "framework/util/memory.hpp"
#include "strategies/registry.hpp"
#include "support/error_of.hpp"
#include "support/test_meshes.hpp"

namespace ccdlab {
namespace CCDLAB_UNITY_ID {  // a namespace of this file's own (tests/CMakeLists.txt)

PipelineStrategies strategies(double time_limit, int threads) {
  PipelineStrategies s = contact_strategies(18, threads > 1 ? "phc" : "sequential", threads, 0.0);
  s.time_limit = time_limit;
  return s;
}

/// The message of the Error a step throws; empty when it throws none.
std::string error_of(CcdPipeline& p, const Positions& x0, const Positions& x1) {
  return test::error_of([&] { (void)p.step(x0, x1); });
}

struct Crumpled {
  MeshData grid = test::grid(24, 24);
  TriMesh mesh = TriMesh(Index(grid.positions.size()), grid.faces);
  Positions x0, x1;
  Crumpled() {
    std::mt19937 rng(11);
    x0 = test::crumple(grid.positions, rng, 0.02);
    x1 = test::crumple(x0, rng, 0.02);
  }
};

TEST(StepWatch, AStepPastItsTimeLimitStopsAndSaysHowFarItGot) {
  const Crumpled c;
  for (const int threads : {1, 2}) {
    CcdPipeline p(c.mesh, single_cloth_body(c.mesh), strategies(1e-9, threads));
    const std::string message = error_of(p, c.x0, c.x1);
    EXPECT_NE(message.find("time_limit 1e-09 s: the step was stopped after"), std::string::npos) << message;
    EXPECT_NE(message.find("candidate pairs tested of about"), std::string::npos) << message;  // the first step's estimate
    EXPECT_NE(message.find("raise time_limit"), std::string::npos) << message;
    // With a limit far above the step it runs whole: the contacts of a pipeline without one.
    CcdPipeline limited(c.mesh, single_cloth_body(c.mesh), strategies(3600, threads));
    CcdPipeline free(c.mesh, single_cloth_body(c.mesh), strategies(0, threads));
    const StepResult a = limited.step(c.x0, c.x1), b = free.step(c.x0, c.x1);
    EXPECT_GT(a.contacts.size(), 0u);
    EXPECT_EQ(contact_set_hash(a.contacts), contact_set_hash(b.contacts));
  }
}

TEST(StepWatch, ReportsTheTestedPairsOncePerDueTime) {
  StepWatch watch;
  std::atomic<int> calls{0};
  std::atomic<std::uint64_t> last_done{0};
  const ProgressReport report = [&](const StepProgress& p) {
    ++calls;
    last_done = p.pairs_done;
    EXPECT_EQ(p.pairs_expected, 4000.0);
  };
  // Not due yet: silent.
  watch.start(0, 4000, &report, std::chrono::milliseconds(60'000));
  watch.advance(100, 5);
  EXPECT_EQ(calls, 0);
  EXPECT_EQ(watch.pairs_done(), 100u);
  EXPECT_FALSE(watch.expired());
  // Due at once: eight threads advancing together make one report in the first half second.
  watch.start(0, 4000, &report, std::chrono::milliseconds(0));
  std::vector<std::thread> threads;
  for (int t = 0; t < 8; ++t)
    threads.emplace_back([&] {
      for (int i = 0; i < 50; ++i) watch.advance(10, 1);
    });
  for (std::thread& t : threads) t.join();
  EXPECT_EQ(watch.pairs_done(), 4000u);
  EXPECT_EQ(watch.contacts(), 400u);
  EXPECT_FALSE(watch.out_of_room());  // no room limit
  EXPECT_GE(calls, 1);
  EXPECT_LE(calls, 2);  // a second only if the loop took longer than kReportEvery
  EXPECT_GT(last_done, 0u);
  // A limit already past: expired, and stays so.
  watch.start(1e-9, 0, nullptr);
  std::this_thread::sleep_for(std::chrono::milliseconds(1));
  EXPECT_TRUE(watch.expired());
  EXPECT_TRUE(watch.expired());
  // Room for 10 contacts: the 11th stops the step.
  watch.start(0, 0, nullptr);
  watch.set_max_contacts(10);
  watch.advance(1, 10);
  EXPECT_FALSE(watch.stopped());
  watch.advance(1, 1);
  EXPECT_TRUE(watch.out_of_room());
  EXPECT_TRUE(watch.stopped());
}

TEST(StepWatch, AStepWhoseContactsWouldNotFitStopsWhileTheyStillFit) {
  // A crumpled sheet with a thickness of several edges: ~2 × 10^5 contacts at 200 bytes, 40 MB, against 4 MiB of
  // room above what is resident.
  const Crumpled c;
  PipelineStrategies s = strategies(0, 1);
  ParamValues params = tester_registry().find("float")->defaults();
  params.set("thickness", 0.1);
  s.tester = tester_registry().make({"float", params});
  s.memory_limit_bytes = current_rss_bytes() + (8u << 20);
  CcdPipeline p(c.mesh, single_cloth_body(c.mesh), std::move(s));
  const std::string message = error_of(p, c.x0, c.x1);
  EXPECT_NE(message.find("the step's contacts would not fit"), std::string::npos) << message;
  EXPECT_NE(message.find("or lower the tester's thickness (0.1)"), std::string::npos) << message;
}

TEST(StepWatch, TheLimitIsChecked) {
  PipelineSettings settings;
  for (const double bad : {-1.0, std::numeric_limits<double>::infinity(), std::numeric_limits<double>::quiet_NaN()}) {
    settings.time_limit = bad;
    EXPECT_THROW(settings.validate(), Error) << bad;
  }
  settings.time_limit = 0.5;
  EXPECT_NO_THROW(settings.validate());
}

}  // namespace
}  // namespace ccdlab
