#pragma once
// `embree`: the broad phase of the industry, side by side with ccdlab's own. Intel Embree's rtcCollide
// (Embree 3, Debian libembree-dev) intersects two BVHs that Embree builds over user primitives; here each
// primitive is a face, bounded by the axis-aligned box of its swept leaf k-DOP (the k-DOP's first three
// slabs). Embree rebuilds its BVH every step (its own build, counted in traversal time) and reports the
// face pairs whose boxes overlap; each is then checked against the leaf k-DOPs (and adjacency, in self
// passes), so the candidates are exactly those of `sequential` and the narrow phase sees the same input.
// BV tests counted are these leaf checks only (Embree does not report its box tests).
// A slice of a memory-bounded step, and a self pass with normal-cone culling, fall back to ccdlab's own
// depth-first traversal (Embree knows neither a BVTT slice nor a skipped patch).
#include <memory>

#include "framework/traversal/scheduler.hpp"

namespace ccdlab {

class EmbreeScheduler final : public TraversalScheduler {
 public:
  EmbreeScheduler();
  ~EmbreeScheduler() override;
  [[nodiscard]] std::string_view name() const override { return "embree"; }
  void collect(const TraversalPass& pass, TraversalOutput& out, std::vector<PhaseTrace>& traces) override;
  void release(int pass_id) override;

 private:
  struct State;
  std::unique_ptr<State> state_;
};

}  // namespace ccdlab
