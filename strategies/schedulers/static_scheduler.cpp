#include "strategies/schedulers/static_scheduler.hpp"

#include "framework/traversal/bvtt_tasks.hpp"

namespace ccdlab {

void StaticScheduler::collect(const TraversalPass& pass, TraversalOutput& out, std::vector<PhaseTrace>& traces) {
  split_and_run(pass, params_.tasks_per_thread, Distribution::static_balanced, "traverse", out, traces, &costs_[pass.id]);
}

}  // namespace ccdlab
