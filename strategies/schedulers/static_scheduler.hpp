#pragma once
// `static`: static partition (Grinberg & Wiseman, the paper's ref [10]). The BVTT top is split breadth-first
// into ≥ c·threads sub-tasks as in `phc`, and each thread is given its sub-tasks before the step starts; there is
// no rebalancing during the step. On a pass's first step (or when the top cuts other tasks) the threads get
// equal-count contiguous chunks, whose sub-trees differ wildly in cost; from then on the tasks go by their costs
// at the last step, largest first to the least loaded thread (TaskCosts::assignment, assign_largest_first) —
// a partition fixed in advance from what the last step measured, as a steady simulation allows.
#include <map>

#include "framework/traversal/bvtt_tasks.hpp"
#include "framework/traversal/scheduler.hpp"

namespace ccdlab {

class StaticScheduler final : public TraversalScheduler {
 public:
  struct Params {
    int tasks_per_thread = 8;  ///< c: sub-tasks per thread, assigned before the step starts
  };
  StaticScheduler() = default;
  explicit StaticScheduler(Params p) : params_(p) {}
  [[nodiscard]] std::string_view name() const override { return "static"; }
  void collect(const TraversalPass& pass, TraversalOutput& out, std::vector<PhaseTrace>& traces) override;
  [[nodiscard]] bool splits_by_threads() const override { return true; }
  void release(int pass_id) override { costs_.erase(pass_id); }

 private:
  Params params_{};
  std::map<int, TaskCosts> costs_;  ///< by TraversalPass::id
};

}  // namespace ccdlab
