#pragma once
// `sequential`: one depth-first traversal of the whole BVTT from its root on one thread — the ICCD baseline
// (Tang et al. 2009) every parallel scheduler is measured against.
#include "framework/traversal/scheduler.hpp"

namespace ccdlab {

class SequentialScheduler final : public TraversalScheduler {
 public:
  [[nodiscard]] std::string_view name() const override { return "sequential"; }
  void collect(const TraversalPass& pass, TraversalOutput& out, std::vector<PhaseTrace>& traces) override;
};

}  // namespace ccdlab
