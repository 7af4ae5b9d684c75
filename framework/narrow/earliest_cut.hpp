#pragma once
// The earliest time of contact found so far in a step, shared by every thread of the narrow phase, for the
// earliest-time-of-impact query (CcdPipeline::earliest_toi, `ccdlab step --earliest`, Detector::earliest_toi).
//
// Why the cut is exact: stage 3 leaves each surviving pair's open windows — sixteenths of the step where it
// could not prove the features farther apart than the tester's reach — so no contact of the pair happens before
// the start of its first open window, `from`, and a time the tester reports below it (a lower bound) is raised
// to it in the full step as here (NarrowPhase::record_vf). A pair is skipped only when from > best, a time
// already reported by some pair; then its own time, if any, is later and the minimum is unchanged. The pair
// holding the true earliest time has from ≤ that time ≤ best at every moment, so it is always tested: the answer
// is the same for every thread count and order. Pairs without windows (a tester without a reach, the
// scalar mode) have from = 0 and are never skipped.
//
// Tight times: a hit whose time is below best is narrowed by the tester (PrimitiveTester::tighten_toi, a later
// lower bound) before it is offered; one at or above best is offered as it is. The answer is then the minimum
// over every pair of its narrowed time, whatever the order: a time offered unnarrowed is at or above a time
// offered before it, so the least one offered is a narrowed one (the first offer of all always is). The same
// for every thread count; the narrowed time can depend on `from`, so the two narrow modes may differ within the
// tester's resolution.
#include <atomic>

namespace ccdlab {

class EarliestCut {
 public:
  /// The earliest time reported so far; above 1 while none is.
  [[nodiscard]] double best() const { return best_.load(std::memory_order_relaxed); }
  /// Lowers best to t when t is earlier.
  void offer(double t) {
    double seen = best_.load(std::memory_order_relaxed);
    while (t < seen && !best_.compare_exchange_weak(seen, t, std::memory_order_relaxed)) {
    }
  }

 private:
  std::atomic<double> best_{2.0};
};

}  // namespace ccdlab
