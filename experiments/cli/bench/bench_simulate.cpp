#include "experiments/cli/bench/bench_simulate.hpp"

#include <algorithm>
#include <array>
#include <map>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "experiments/cli/report.hpp"

namespace ccdlab::cli {

MachineModel BenchSimulation::machine_of(std::size_t i) const {
  MachineModel model = machine;
  const int most_threads = *std::max_element(plan.threads.begin(), plan.threads.end());
  if (plan.runs[i].threads != 1 || most_threads < 2) return model;
  const std::size_t parallel = plan.find(plan.runs[i].label(), most_threads);
  if (parallel == plan.measured) return model;  // no multi-thread run measured
  std::size_t alone = i;
  for (std::size_t j = plan.measured; j < plan.runs.size(); ++j)
    if (plan.runs[j].label() == plan.runs[i].label() && plan.runs[j].split == most_threads) alone = j;
  model.task_inflation = measure_task_inflation(measured[alone].median_traces(), measured[parallel].median_traces());
  return model;
}

nlohmann::json BenchSimulation::scaling(OutputFile& scaling_csv) const {
  const std::size_t ref = plan.reference;
  const double ref_ms = median(measured[ref].ms_per_step);
  nlohmann::json rows = nlohmann::json::array();
  if (print) {
    std::vector<std::string> fork_join_us;
    for (double ms : machine.fork_join_ms) fork_join_us.push_back(fmt::format("{:.1f}", 1e3 * ms));
    fmt::print("\nsimulated ms/step (speed-up vs {} x1) from 1-thread task costs, with this machine's fork/join ({} us on\n"
               "1..{} threads) and each phase's task inflation at {} threads; [measured, error (ideal machine's error)]:\n",
               plan.runs[ref].label(), fmt::join(fork_join_us, "/"), probe_threads,
               *std::max_element(plan.threads.begin(), plan.threads.end()));
  }
  for (std::size_t i = 0; i < plan.measured; ++i) {
    if (plan.runs[i].threads != 1) continue;
    const MachineModel model = machine_of(i);
    const std::string label = plan.runs[i].label();
    std::string line = fmt::format("{:>10}", label);
    for (int n : plan.cores) {
      double predicted = 0, ideal = 0;
      for (const auto& step_traces : measured[plan.recorded(i, n)].median_traces()) {
        predicted += simulate_step(step_traces, n, &model);
        ideal += simulate_step(step_traces, n);
      }
      predicted /= steps;
      ideal /= steps;
      const std::size_t at_n = plan.find(label, n);
      const double measured_ms = at_n < plan.measured ? median(measured[at_n].ms_per_step) : -1;
      scaling_csv << fmt::format("{},{},{:.4f},{:.4f},{},{:.4f}\n", label, n, predicted, ref_ms / predicted,
                                 measured_ms < 0 ? std::string() : fmt::format("{:.4f}", measured_ms), ideal);
      rows.push_back({{"scheduler", label}, {"cores", n}, {"predicted_ms_per_step", predicted},
                      {"predicted_speedup", ref_ms / predicted}, {"ideal_ms_per_step", ideal},
                      {"measured_ms_per_step", measured_ms < 0 ? nlohmann::json() : nlohmann::json(measured_ms)}});
      line += measured_ms < 0 ? fmt::format(" | {}: {:.2f} ({:.2f}x)", n, predicted, ref_ms / predicted)
                              : fmt::format(" | {}: {:.2f} ({:.2f}x) [{:.2f}, {:+.0f}% ({:+.0f}%)]", n, predicted,
                                            ref_ms / predicted, measured_ms, 100 * (predicted - measured_ms) / measured_ms,
                                            100 * (ideal - measured_ms) / measured_ms);
    }
    if (print) fmt::print("{}\n", line);
  }
  return rows;
}

void BenchSimulation::phases(OutputFile& jsonl) const {
  // Where scaling stops: the largest simulated core count ≤ 8 (or the smallest one).
  int probe = plan.cores.front();
  for (int n : plan.cores)
    if (n <= 8) probe = std::max(probe, n);
  if (print)
    fmt::print("\nper phase, ms/step at 1 core -> {} simulated cores (serial part, task inflation); the serial fraction of a step:\n", probe);
  for (std::size_t i = 0; i < plan.measured; ++i) {
    if (plan.runs[i].threads != 1) continue;
    std::map<std::string, std::array<double, 3>> phases;  // 1 core, N cores, serial
    for (const auto& step_traces : measured[i].median_traces())
      for (const PhaseTrace& t : step_traces) phases[t.phase][0] += simulate_phase(t, 1, &machine) / steps;
    for (const auto& step_traces : measured[plan.recorded(i, probe)].median_traces())
      for (const PhaseTrace& t : step_traces) {
        auto& acc = phases[t.phase];
        acc[1] += simulate_phase(t, probe, &machine) / steps;
        acc[2] += t.serial_ms / steps;
      }
    const MachineModel model = machine_of(i);
    nlohmann::json row = {{"type", "phases"}, {"scheduler", plan.runs[i].label()}, {"cores", probe},
                          {"task_inflation", model.task_inflation}};
    std::string line = fmt::format("{:>10}", plan.runs[i].label());
    double one_core = 0, serial = 0;
    for (const auto& [name, acc] : phases) {
      row["phases"][name] = {{"ms_1", acc[0]}, {"ms_n", acc[1]}, {"serial_ms", acc[2]}};
      const double inflation = model.inflation(name, probe);
      line += fmt::format(" | {} {:.1f}->{:.1f} ({:.1f}{})", name, acc[0], acc[1], acc[2],
                          inflation != 1 ? fmt::format(", tasks x{:.2f}", inflation) : std::string());
      one_core += acc[0], serial += acc[2];
    }
    // The serial fraction of a step (every phase's part outside its parallel loop, and the phases without one):
    // Amdahl's bound on the speed-up, whatever the cores.
    const double fraction = one_core > 0 ? serial / one_core : 0;
    row["serial_fraction"] = fraction;
    line += fmt::format(" || serial {:.2f} of {:.1f} ms = {:.1f}% (Amdahl bound {})", serial, one_core, 100 * fraction,
                        fraction > 0 ? fmt::format("{:.0f}x", 1 / fraction) : std::string("none"));
    jsonl << row.dump() << "\n";
    if (print) fmt::print("{}\n", line);
  }
}

}  // namespace ccdlab::cli
