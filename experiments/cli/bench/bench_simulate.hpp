#pragma once
// `ccdlab bench`, step 4 of 4: the schedule simulator (framework/pipeline/schedule_sim.hpp) replays each
// scheduler's recorded 1-thread task costs on N cores — its speed-up curve, checked against the runs measured on
// that many threads — and says per phase where scaling stops (serial part, task inflation, Amdahl's bound).
#include <vector>

#include <nlohmann/json.hpp>

#include "experiments/cli/bench/bench_measure.hpp"
#include "framework/pipeline/schedule_sim.hpp"
#include "framework/util/files.hpp"

namespace ccdlab::cli {

struct BenchSimulation {
  const BenchPlan& plan;
  const std::vector<Measured>& measured;
  const MachineModel& machine;  ///< this machine's probe (fork/join cost)
  int probe_threads = 1;        ///< the threads the probe ran on
  int steps = 1;                ///< timed steps per run
  bool print = true;            ///< the tables on stdout (not with --json)

  /// Simulated ms per step of every scheduler's 1-thread run on each of the plan's core counts: scaling.csv's
  /// rows, printed, returned as JSON rows.
  nlohmann::json scaling(OutputFile& scaling_csv) const;
  /// Per phase, ms per step at 1 core and at the largest simulated core count ≤ 8: bench.jsonl's "phases" records.
  void phases(OutputFile& jsonl) const;

 private:
  /// The machine model of reported run i (a 1-thread run): the probe's fork/join cost, and each phase's task
  /// inflation between that run (split as the most threads measured would split it) and the run on that many threads.
  [[nodiscard]] MachineModel machine_of(std::size_t i) const;
};

}  // namespace ccdlab::cli
