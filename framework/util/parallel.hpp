#pragma once
// OpenMP helpers shared by the pipeline stages and the schedulers. Every parallel phase records a PhaseTrace —
// its serial part and the cost of each task — so a run can be replayed on N simulated cores
// (framework/pipeline/schedule_sim.hpp). Results never depend on the thread count: workers write to
// thread-local buffers that are merged, and contacts are sorted at the end of a step.
#include <chrono>
#include <cstddef>
#include <string>
#include <vector>

#include <omp.h>

namespace ccdlab {

/// How a phase's tasks were distributed, for the simulator.
enum class Distribution { dynamic, static_chunks };

struct PhaseTrace {
  std::string phase;
  Distribution distribution = Distribution::dynamic;
  double serial_ms = 0;          ///< time spent outside the parallel loop (splitting, merging)
  std::vector<double> task_ms;   ///< cost of each task, in the order tasks were handed out
  std::vector<double> thread_ms; ///< busy time of each thread
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

/// Runs body(begin, end, thread) over [0, n) in chunks of `chunk`, handed out dynamically to `threads` threads;
/// records each chunk's cost and each thread's busy time in `trace`.
template <class Body>
void parallel_chunks(std::size_t n, std::size_t chunk, int threads, PhaseTrace& trace, Body&& body) {
  using Clock = std::chrono::steady_clock;
  const std::ptrdiff_t chunks = std::ptrdiff_t((n + chunk - 1) / chunk);
  trace.task_ms.assign(std::size_t(chunks), 0.0);
  trace.thread_ms.assign(std::size_t(threads), 0.0);
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads)
  for (std::ptrdiff_t c = 0; c < chunks; ++c) {
    const auto t0 = Clock::now();
    const std::size_t begin = std::size_t(c) * chunk;
    body(begin, std::min(n, begin + chunk), omp_get_thread_num());
    const double ms = ms_between(t0, Clock::now());
    trace.task_ms[std::size_t(c)] = ms;
    trace.thread_ms[std::size_t(omp_get_thread_num())] += ms;
  }
}

}  // namespace ccdlab
