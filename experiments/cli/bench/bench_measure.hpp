#pragma once
// `ccdlab bench`, step 2 of 4: every run of the plan in alternating rounds (A B C …, then … C B A) so drift hits
// all alike, after one untimed warm-up round; each run's contact hash checked to stay the same.
#include <cstdint>
#include <vector>

#include "experiments/cli/bench/bench_plan.hpp"
#include "framework/pipeline/ccd_pipeline.hpp"

namespace ccdlab::cli {

/// What the rounds of one run measured: its time per round, and the first round's counters.
struct Measured {
  std::vector<double> ms_per_step;  ///< one value per round: mean over the timed steps
  std::uint64_t hash = 0;
  std::uint64_t bv_tests = 0, candidates = 0, elementary_tests = 0;
  std::uint64_t front_max = 0, front_bytes_max = 0, sprouted = 0, pruned = 0, rebuilds = 0;
  double serial_ms = 0, traverse_ms = 0, imbalance_sum = 0;
  double spread = 0;  ///< (max − min) ÷ median of the rounds' ms per step
  int imbalance_n = 0;
  std::vector<std::vector<std::vector<PhaseTrace>>> traces;  ///< per round, per step
  /// Traces of the round whose time is the median: the simulator replays a typical run, not an outlier.
  [[nodiscard]] const std::vector<std::vector<PhaseTrace>>& median_traces() const;
};

/// Times every run of `plan` on the scene's frames (the config's settings, each run's scheduler, threads, split
/// and narrow mode); throws Error when a run's contacts change between rounds. Progress on stderr when asked.
std::vector<Measured> measure_bench(const BenchPlan& plan, const ExperimentConfig& config, const Registries& reg,
                                    const MeshSequence& scene, const std::vector<Positions>& frames, bool progress);

/// Sets each run's spread and warns (stderr) where a reported run's rounds differ by more than the noise threshold.
void check_round_spread(const BenchPlan& plan, std::vector<Measured>& measured);

}  // namespace ccdlab::cli
