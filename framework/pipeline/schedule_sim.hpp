#pragma once
// Schedule simulator: predicts the wall time of a step on N cores from the task costs a run recorded
// (StepResult::traces). Each phase is replayed as its scheduler would run it:
//   dynamic       : list scheduling — tasks in their recorded order, each to the core that frees up first
//                   (what OpenMP's schedule(dynamic) does)
//   static_chunks : N equal-count contiguous chunks, one per core, no rebalancing; the slowest chunk decides
//   static_balanced: the recorded costs assigned largest first to the least loaded of N cores, as `static`
//                   assigns a step's tasks by their costs at the last step (so the replay assumes the last
//                   step's costs were this step's: exact in a steady state)
// and the phase's serial part stays serial. Where a scheduler's tasks depend on the thread count (phc, static:
// TraversalScheduler::splits_by_threads), the trace replayed on N cores must come from a run split for N threads. What it does not model: memory-bandwidth contention, cache
// effects of sharing, fork/join overhead — so it is an upper bound on speed-up, validated against real runs
// where they can be measured (`ccdlab bench`).
#include <vector>

#include "framework/util/parallel.hpp"

namespace ccdlab {

/// Predicted milliseconds of one phase on `cores` cores.
double simulate_phase(const PhaseTrace& trace, int cores);

/// Predicted milliseconds of a step (the sum over its phases) on `cores` cores.
double simulate_step(const std::vector<PhaseTrace>& traces, int cores);

/// max / mean of the threads' busy times in a phase (1 = perfectly balanced; 0 when there is no thread data).
double imbalance(const PhaseTrace& trace);

}  // namespace ccdlab
