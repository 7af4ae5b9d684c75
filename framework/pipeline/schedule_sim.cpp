#include "framework/pipeline/schedule_sim.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <functional>
#include <numeric>
#include <queue>


namespace ccdlab {
namespace {

/// The makespan of one region's tasks on `cores` cores.
double region_makespan(const double* tasks, std::size_t n, Distribution dist, int cores, double scale) {
  if (n == 0) return 0;
  double makespan = 0;
  if (dist == Distribution::static_balanced) {
    const std::vector<int> thread_of = assign_largest_first(std::vector<double>(tasks, tasks + n), cores);
    std::vector<double> load(std::size_t(cores), 0.0);
    for (std::size_t i = 0; i < n; ++i) load[std::size_t(thread_of[i])] += tasks[i];
    makespan = *std::max_element(load.begin(), load.end());
  } else if (dist == Distribution::static_chunks) {
    for (int c = 0; c < cores; ++c) {
      const std::size_t b = n * std::size_t(c) / std::size_t(cores), e = n * std::size_t(c + 1) / std::size_t(cores);
      makespan = std::max(makespan, std::accumulate(tasks + b, tasks + e, 0.0));
    }
  } else {
    std::priority_queue<double, std::vector<double>, std::greater<>> free_at;
    for (int c = 0; c < cores; ++c) free_at.push(0.0);
    for (std::size_t i = 0; i < n; ++i) {
      const double start = free_at.top();
      free_at.pop();
      free_at.push(start + tasks[i]);
      makespan = std::max(makespan, start + tasks[i]);
    }
  }
  return makespan * scale;
}

template <class Fn>
double timed_ms(Fn&& fn) {
  const auto t = std::chrono::steady_clock::now();
  fn();
  return ms_between(t, std::chrono::steady_clock::now());
}

}  // namespace

double MachineModel::fork_join(int n) const {
  if (fork_join_ms.empty()) return 0;
  return fork_join_ms[std::size_t(std::clamp(n, 1, int(fork_join_ms.size())) - 1)];
}

double MachineModel::inflation(const std::string& phase, int n) const {
  if (n <= 1) return 1;
  const auto it = task_inflation.find(phase);
  return it == task_inflation.end() ? 1 : it->second;
}

MachineModel probe_machine(int max_threads) {
  MachineModel m;
  // The median of many regions of n trivial tasks on n threads.
  for (int n = 1; n <= max_threads; ++n) {
    std::vector<double> ms(15);
    for (double& x : ms)
      x = timed_ms([&] {
            for (int r = 0; r < 100; ++r) {
              PhaseTrace t;
              parallel_tasks(std::size_t(n), n, Distribution::dynamic, t, [](std::size_t, int) {});
            }
          }) / 100;
    std::nth_element(ms.begin(), ms.begin() + 7, ms.end());
    m.fork_join_ms.push_back(ms[7]);
  }
  return m;
}

std::map<std::string, double> measure_task_inflation(const std::vector<std::vector<PhaseTrace>>& alone,
                                                     const std::vector<std::vector<PhaseTrace>>& parallel) {
  std::map<std::string, std::array<double, 2>> total;
  for (const auto& step : alone)
    for (const PhaseTrace& t : step) total[t.phase][0] += std::accumulate(t.task_ms.begin(), t.task_ms.end(), 0.0);
  for (const auto& step : parallel)
    for (const PhaseTrace& t : step) total[t.phase][1] += std::accumulate(t.task_ms.begin(), t.task_ms.end(), 0.0);
  std::map<std::string, double> inflation;
  for (const auto& [phase, ms] : total)
    if (ms[0] > 0 && ms[1] > 0) inflation[phase] = ms[1] / ms[0];
  return inflation;
}

double simulate_phase(const PhaseTrace& trace, int cores, const MachineModel* machine) {
  const auto& tasks = trace.task_ms;
  const double scale = machine ? machine->inflation(trace.phase, cores) : 1.0;
  const double fork_join = machine ? std::max(0.0, machine->fork_join(cores) - machine->fork_join(1)) : 0.0;
  // Traces written by hand (tests) or before regions were recorded: one region.
  std::vector<std::size_t> begins = trace.region_begin;
  if (begins.empty() && !tasks.empty()) begins.push_back(0);
  double ms = trace.serial_ms;
  for (std::size_t r = 0; r < begins.size(); ++r) {
    const std::size_t b = begins[r], e = r + 1 < begins.size() ? begins[r + 1] : tasks.size();
    ms += region_makespan(tasks.data() + b, e - b, trace.distribution, cores, scale) + fork_join;
  }
  return ms;
}

double simulate_step(const std::vector<PhaseTrace>& traces, int cores, const MachineModel* machine) {
  double ms = 0;
  for (const PhaseTrace& t : traces) ms += simulate_phase(t, cores, machine);
  return ms;
}

double imbalance(const PhaseTrace& trace) {
  if (trace.thread_ms.empty()) return 0;
  const double mean = std::accumulate(trace.thread_ms.begin(), trace.thread_ms.end(), 0.0) / double(trace.thread_ms.size());
  return mean > 0 ? *std::max_element(trace.thread_ms.begin(), trace.thread_ms.end()) / mean : 0;
}

PhaseTrace untraced_time(const std::vector<PhaseTrace>& traces, double step_ms) {
  double accounted = 0;
  for (const PhaseTrace& t : traces) {
    accounted += t.serial_ms;
    if (!t.thread_ms.empty()) accounted += *std::max_element(t.thread_ms.begin(), t.thread_ms.end());
    else accounted += std::accumulate(t.task_ms.begin(), t.task_ms.end(), 0.0);
  }
  return PhaseTrace{"untraced", Distribution::dynamic, std::max(0.0, step_ms - accounted), {}, {}};
}

}  // namespace ccdlab
