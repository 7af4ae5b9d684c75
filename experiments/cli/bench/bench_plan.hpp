#pragma once
// `ccdlab bench`, step 1 of 4 (plan → measure → rows → simulate): which runs a bench times, from its options —
// every narrow mode × scheduler × thread count asked for, then the recording runs the schedule simulator replays.
#include <cstddef>
#include <string>
#include <vector>

#include "experiments/cli/commands.hpp"

namespace ccdlab::cli {

/// One configuration a bench times, in every round.
struct BenchRun {
  std::string scheduler;
  int threads = 1;
  NarrowMode narrow = NarrowMode::batched;
  /// > 0: a recording run — 1 thread, the BVTT split for `split` threads — whose task costs the simulator replays
  /// on `split` cores (phc and static cut c·threads tasks, so the 1-thread split would misrepresent them).
  /// Timed in the same alternating rounds, checked for the same hash, left out of the tables.
  int split = 0;
  /// How the configuration is named in tables and files: the scheduler, "/scalar" for the scalar narrow phase.
  [[nodiscard]] std::string label() const { return narrow == NarrowMode::batched ? scheduler : scheduler + "/scalar"; }
  [[nodiscard]] std::string name() const;
};

struct BenchPlan {
  std::vector<BenchRun> runs;  ///< the measured runs, then the recording runs
  std::size_t measured = 0;    ///< runs[0, measured) are reported; the rest feed the simulator only
  std::size_t reference = 0;   ///< what speed-ups are against: sequential at 1 thread, or the first run
  std::vector<int> threads;    ///< --threads
  std::vector<int> cores;      ///< --cores: the simulated core counts
  int rounds = 3;
  int untimed_steps = 0;
  /// The recording run of `measured_run`'s configuration split for `cores`, or `measured_run` itself where its
  /// scheduler's split does not depend on the thread count.
  [[nodiscard]] std::size_t recorded(std::size_t measured_run, int cores) const;
  /// The measured run of `label` at `threads`, or `measured` when there is none.
  [[nodiscard]] std::size_t find(const std::string& label, int threads) const;
};

/// The plan of `o`'s lists, checked against the registries; the scene's step count bounds --untimed-steps.
BenchPlan plan_bench(const BenchOptions& o, const Registries& reg, int scene_steps);

}  // namespace ccdlab::cli
