#pragma once
// `static`: static partition (Grinberg & Wiseman, the paper's ref [10]). The BVTT top is split breadth-first
// into ≥ c·threads sub-tasks as in `phc`, but before the step starts each thread is given an equal-count
// contiguous chunk of them, and there is no rebalancing. Sub-trees differ wildly in cost, so threads finish at
// very different times (traces record each thread's busy time): the strawman that shows why dynamic balancing
// matters.
#include "framework/traversal/scheduler.hpp"

namespace ccdlab {

class StaticScheduler final : public TraversalScheduler {
 public:
  struct Params {
    int tasks_per_thread = 8;  ///< c: sub-tasks per thread, in one fixed chunk per thread
  };
  StaticScheduler() = default;
  explicit StaticScheduler(Params p) : params_(p) {}
  [[nodiscard]] std::string_view name() const override { return "static"; }
  void collect(const TraversalPass& pass, TraversalOutput& out, std::vector<PhaseTrace>& traces) override;
  [[nodiscard]] bool splits_by_threads() const override { return true; }

 private:
  Params params_{};
};

}  // namespace ccdlab
