#pragma once
// The executor: every parallel loop of ccdlab (pipeline stages, schedulers) runs through parallel_tasks. Every parallel phase records a PhaseTrace —
// its serial part and the cost of each task — so a run can be replayed on N simulated cores
// (framework/pipeline/schedule_sim.hpp). Results never depend on the thread count: workers write to
// thread-local buffers that are merged, and contacts are sorted at the end of a step.
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstddef>
#include <exception>
#include <mutex>
#include <string>
#include <vector>

#include <omp.h>

namespace ccdlab {

/// How a phase's tasks were distributed, for the simulator.
///   dynamic         : one at a time to whichever thread is free
///   static_chunks   : `threads` equal-count contiguous ranges, fixed before the start
///   static_balanced : fixed before the start by costs known beforehand (a step's costs at the last step):
///                     largest first, each to the least loaded thread (assign_largest_first)
enum class Distribution { dynamic, static_chunks, static_balanced };

/// The thread of each task when tasks go, largest `cost` first, to the thread with the least cost so far (ties:
/// the lower index; the longest-processing-time rule). What `static` does with its tasks' last costs, and what
/// the simulator replays for a static_balanced phase.
inline std::vector<int> assign_largest_first(const std::vector<double>& cost, int threads) {
  std::vector<std::size_t> by_cost(cost.size());
  for (std::size_t i = 0; i < by_cost.size(); ++i) by_cost[i] = i;
  std::stable_sort(by_cost.begin(), by_cost.end(), [&](std::size_t x, std::size_t y) { return cost[x] > cost[y]; });
  std::vector<double> load(std::size_t(std::max(threads, 1)), 0.0);
  std::vector<int> thread_of(cost.size(), 0);
  for (std::size_t i : by_cost) {
    const std::size_t t = std::size_t(std::min_element(load.begin(), load.end()) - load.begin());
    thread_of[i] = int(t);
    load[t] += cost[i];
  }
  return thread_of;
}

struct PhaseTrace {
  std::string phase;
  Distribution distribution = Distribution::dynamic;
  double serial_ms = 0;          ///< time spent outside the parallel loops (splitting, merging)
  std::vector<double> task_ms;   ///< cost of each task, in the order tasks were handed out, region after region
  std::vector<double> thread_ms; ///< busy time of each thread, over all regions
  /// Where each parallel region's tasks start in task_ms: the regions of a phase run one after the other, each
  /// ending at a barrier (and each paying the machine's fork/join cost: schedule_sim.hpp).
  std::vector<std::size_t> region_begin = {};
};

/// Per-thread state padded to its own cache lines: neighbours' counters and vector headers written on every
/// iteration would otherwise share a line and serialise the threads (false sharing).
template <class T>
struct alignas(64) PerThread {
  T value{};
};

inline double ms_between(std::chrono::steady_clock::time_point a, std::chrono::steady_clock::time_point b) {
  return std::chrono::duration<double, std::milli>(b - a).count();
}
inline double ms_since(std::chrono::steady_clock::time_point t) { return ms_between(t, std::chrono::steady_clock::now()); }

/// The most threads any stage may use (YAML `threads`, CLI `--threads`): far more than a machine has cores, far
/// fewer than the OpenMP runtime can create before it fails (100,000 threads crash it).
constexpr int kMaxThreads = 1024;

/// The first exception thrown by any task of a parallel region, rethrown on the calling thread once the region
/// is over: an exception escaping an OpenMP region would end the program through std::terminate. Tasks that
/// start after a failure are skipped, so a failing region ends quickly.
class TaskErrors {
 public:
  template <class F>
  void run(F&& f) noexcept {
    if (failed_.load(std::memory_order_relaxed)) return;
    try {
      f();
    } catch (...) {
      std::lock_guard<std::mutex> lock(mutex_);
      if (!first_) first_ = std::current_exception();
      failed_.store(true, std::memory_order_relaxed);
    }
  }
  void rethrow_if_failed() const {
    if (first_) std::rethrow_exception(first_);
  }

 private:
  std::atomic<bool> failed_{false};
  std::mutex mutex_;
  std::exception_ptr first_;
};

/// Runs task(i, thread) for i in [0, n) on `threads` threads: handed out one at a time to whichever thread is
/// free (Distribution::dynamic), as `threads` equal-count contiguous ranges fixed before the start
/// (Distribution::static_chunks), or task i on thread `thread_of[i]`, each thread in index order
/// (Distribution::static_balanced). Appends a region to `trace`: each task's cost, each thread's busy time. The
/// one place ccdlab opens an OpenMP region: exceptions come back to the caller (TaskErrors).
template <class Task>
void parallel_tasks(std::size_t n, int threads, Distribution dist, PhaseTrace& trace, Task&& task,
                    const std::vector<int>* thread_of = nullptr) {
  using Clock = std::chrono::steady_clock;
  trace.distribution = dist;
  const std::size_t first = trace.task_ms.size();
  trace.region_begin.push_back(first);
  trace.task_ms.resize(first + n, 0.0);
  double* const task_ms = trace.task_ms.data() + first;
  if (trace.thread_ms.size() < std::size_t(threads)) trace.thread_ms.resize(std::size_t(threads), 0.0);
  TaskErrors errors;
  auto timed = [&](std::size_t i, int tid) {
    const auto t0 = Clock::now();
    errors.run([&] { task(i, tid); });
    const double ms = ms_between(t0, Clock::now());
    task_ms[i] = ms;
    trace.thread_ms[std::size_t(tid)] += ms;
  };
  if (dist == Distribution::dynamic) {
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads)
    for (std::ptrdiff_t i = 0; i < std::ptrdiff_t(n); ++i) timed(std::size_t(i), omp_get_thread_num());
  } else if (dist == Distribution::static_balanced && thread_of) {
#pragma omp parallel num_threads(threads)
    {
      const int tid = omp_get_thread_num();
      for (std::size_t i = 0; i < n; ++i)
        if ((*thread_of)[i] == tid) timed(i, tid);
    }
  } else {
#pragma omp parallel num_threads(threads)
    {
      const int tid = omp_get_thread_num(), nt = omp_get_num_threads();
      const std::size_t begin = n * std::size_t(tid) / std::size_t(nt), end = n * std::size_t(tid + 1) / std::size_t(nt);
      for (std::size_t i = begin; i < end; ++i) timed(i, tid);
    }
  }
  errors.rethrow_if_failed();
}

/// Runs body(begin, end, thread) over [0, n) in chunks of `chunk`, handed out dynamically to `threads` threads;
/// records each chunk's cost and each thread's busy time in `trace`.
template <class Body>
void parallel_chunks(std::size_t n, std::size_t chunk, int threads, PhaseTrace& trace, Body&& body) {
  const std::size_t chunks = (n + chunk - 1) / chunk;
  parallel_tasks(chunks, threads, Distribution::dynamic, trace, [&](std::size_t c, int tid) {
    const std::size_t begin = c * chunk;
    body(begin, std::min(n, begin + chunk), tid);
  });
}

}  // namespace ccdlab
