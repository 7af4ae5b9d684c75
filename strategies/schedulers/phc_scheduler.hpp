#pragma once
// `phc`: parallel hierarchical computation, as in MCCD (Tang et al. 2009, the paper's ref [24]). The top of
// the BVTT is traversed breadth-first on one thread until a level holds at least c·threads nodes; those
// sub-tasks then run in parallel with dynamic scheduling. The serial top part limits scaling (the paper's
// T_phc = Ĉt + Ĉb + (Čt + Čb + Ce)/N) and is reported separately (traversal.serial_ms). From a pass's second
// step on, its tasks are handed out largest first, by their costs at the last step (TaskCosts, bvtt_tasks.hpp).
#include <map>

#include "framework/traversal/bvtt_tasks.hpp"
#include "framework/traversal/scheduler.hpp"

namespace ccdlab {

class PhcScheduler final : public TraversalScheduler {
 public:
  struct Params {
    int tasks_per_thread = 8;  ///< c: the breadth-first top stops at ≥ c·threads sub-tasks
  };
  PhcScheduler() = default;
  explicit PhcScheduler(Params p) : params_(p) {}
  [[nodiscard]] std::string_view name() const override { return "phc"; }
  void collect(const TraversalPass& pass, TraversalOutput& out, std::vector<PhaseTrace>& traces) override;
  [[nodiscard]] bool splits_by_threads() const override { return true; }
  void release(int pass_id) override { costs_.erase(pass_id); }

 private:
  Params params_{};
  std::map<int, TaskCosts> costs_;  ///< by TraversalPass::id
};

}  // namespace ccdlab
