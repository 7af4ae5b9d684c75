#include "framework/pipeline/schedule_sim.hpp"

#include <algorithm>
#include <functional>
#include <numeric>
#include <queue>

namespace ccdlab {

double simulate_phase(const PhaseTrace& trace, int cores) {
  const auto& tasks = trace.task_ms;
  double makespan = 0;
  if (!tasks.empty()) {
    if (trace.distribution == Distribution::static_balanced) {
      const std::vector<int> thread_of = assign_largest_first(tasks, cores);
      std::vector<double> load(std::size_t(cores), 0.0);
      for (std::size_t i = 0; i < tasks.size(); ++i) load[std::size_t(thread_of[i])] += tasks[i];
      makespan = *std::max_element(load.begin(), load.end());
    } else if (trace.distribution == Distribution::static_chunks) {
      const std::size_t n = tasks.size();
      for (int c = 0; c < cores; ++c) {
        const std::size_t b = n * std::size_t(c) / std::size_t(cores), e = n * std::size_t(c + 1) / std::size_t(cores);
        makespan = std::max(makespan, std::accumulate(tasks.begin() + std::ptrdiff_t(b), tasks.begin() + std::ptrdiff_t(e), 0.0));
      }
    } else {
      std::priority_queue<double, std::vector<double>, std::greater<>> free_at;
      for (int c = 0; c < cores; ++c) free_at.push(0.0);
      for (double t : tasks) {
        const double start = free_at.top();
        free_at.pop();
        free_at.push(start + t);
        makespan = std::max(makespan, start + t);
      }
    }
  }
  return trace.serial_ms + makespan;
}

double simulate_step(const std::vector<PhaseTrace>& traces, int cores) {
  double ms = 0;
  for (const PhaseTrace& t : traces) ms += simulate_phase(t, cores);
  return ms;
}

double imbalance(const PhaseTrace& trace) {
  if (trace.thread_ms.empty()) return 0;
  const double mean = std::accumulate(trace.thread_ms.begin(), trace.thread_ms.end(), 0.0) / double(trace.thread_ms.size());
  return mean > 0 ? *std::max_element(trace.thread_ms.begin(), trace.thread_ms.end()) / mean : 0;
}

}  // namespace ccdlab
