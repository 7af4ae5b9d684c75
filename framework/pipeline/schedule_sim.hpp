#pragma once
// Schedule simulator: predicts the wall time of a step on N cores from the task costs a run recorded
// (StepResult::traces). Each phase is replayed region by region (PhaseTrace::region_begin; a barrier ends each),
// as its scheduler would run it:
//   dynamic       : list scheduling — tasks in their recorded order, each to the core that frees up first
//                   (what OpenMP's schedule(dynamic) does)
//   static_chunks : N equal-count contiguous chunks, one per core, no rebalancing; the slowest chunk decides
//   static_balanced: the recorded costs assigned largest first to the least loaded of N cores, as `static`
//                   assigns a step's tasks by their costs at the last step (so the replay assumes the last
//                   step's costs were this step's: exact in a steady state)
// and the phase's serial part stays serial, as does the step's time outside every phase's tasks and serial
// parts (the "untraced" phase the pipeline adds: dispatch, allocation, clock reads).
//
// What the machine adds (MachineModel; none = the ideal machine):
//   fork/join       each region on N threads costs fork_join(N) − fork_join(1) more than on one (probe_machine)
//   task inflation  on more than one core, each task of a phase runs inflation(phase) times longer than it did
//                   alone: memory traffic, and data one core wrote read by another (docs/results-scheduling.md
//                   has the figures). Measured per phase by `ccdlab bench` as the tasks' total time in its
//                   multi-thread run ÷ in the 1-thread run split the same way.
// Beyond the core counts measured, both stay at their last measured value: a machine with more cores has its own
// caches and bandwidth, which this one cannot know. Where a scheduler's tasks depend on the thread count (phc,
// static: TraversalScheduler::splits_by_threads), the trace replayed on N cores must come from a run split for N
// threads.
#include <map>
#include <string>
#include <vector>

#include "framework/util/parallel.hpp"

namespace ccdlab {

struct MachineModel {
  std::vector<double> fork_join_ms;  ///< [n − 1]: ms to open and close a region of n threads, n = 1 … measured
  std::map<std::string, double> task_inflation;  ///< per phase name, on more than one core; absent = 1
  [[nodiscard]] double fork_join(int n) const;
  [[nodiscard]] double inflation(const std::string& phase, int n) const;
};

/// Measures the fork/join cost on this machine for 1 … max_threads threads (a fraction of a second).
MachineModel probe_machine(int max_threads);

/// The tasks' total ms per phase in `parallel` (a run on more than one thread) ÷ in `alone` (one thread, the same
/// split), over the steps of both: the task inflation of each phase that had tasks in both.
std::map<std::string, double> measure_task_inflation(const std::vector<std::vector<PhaseTrace>>& alone,
                                                     const std::vector<std::vector<PhaseTrace>>& parallel);

/// Predicted milliseconds of one phase on `cores` cores (on `machine` when given).
double simulate_phase(const PhaseTrace& trace, int cores, const MachineModel* machine = nullptr);

/// Predicted milliseconds of a step (the sum over its phases) on `cores` cores.
double simulate_step(const std::vector<PhaseTrace>& traces, int cores, const MachineModel* machine = nullptr);

/// max / mean of the threads' busy times in a phase (1 = perfectly balanced; 0 when there is no thread data).
double imbalance(const PhaseTrace& trace);

/// The trace of a step's time outside every phase's tasks and serial parts (`step_ms` is the step's wall time;
/// a phase's tasks count by their busiest thread): replayed as serial.
PhaseTrace untraced_time(const std::vector<PhaseTrace>& traces, double step_ms);

}  // namespace ccdlab
