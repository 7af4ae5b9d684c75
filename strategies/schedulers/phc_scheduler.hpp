#pragma once
// `phc`: parallel hierarchical computation, as in MCCD (Tang et al. 2009, the paper's ref [24]). The top of
// the BVTT is traversed breadth-first on one thread until a level holds at least c·threads nodes; those
// sub-tasks then run in parallel with dynamic scheduling. The serial top part limits scaling (the paper's
// T_phc = Ĉt + Ĉb + (Čt + Čb + Ce)/N) and is reported separately (traversal.serial_ms).
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

 private:
  Params params_{};
};

}  // namespace ccdlab
