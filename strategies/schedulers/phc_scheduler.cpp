#include "strategies/schedulers/phc_scheduler.hpp"

namespace ccdlab {

void PhcScheduler::collect(const TraversalPass& pass, TraversalOutput& out, std::vector<PhaseTrace>& traces) {
  split_and_run(pass, params_.tasks_per_thread, Distribution::dynamic, "traverse", out, traces, &costs_[pass.id]);
}

}  // namespace ccdlab
