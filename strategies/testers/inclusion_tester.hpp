#pragma once
// `inclusion`: inclusion-based CCD in the manner of Wang et al., "A Large Scale Benchmark and an Inclusion-Based
// Algorithm for Continuous Collision Detection" (TOG 2021) — the method barrier-solver codes call
// Tight-Inclusion. Never misses.
//
// Contact is a root of the gap F(t, u, v) between a point of each feature (gap_boxes.hpp), or — with a minimum
// separation ms > 0 — a point where every coordinate of F is within ms. F is linear in each of t, u, v, so the
// axis-aligned box of its 8 corner values is an inclusion function: it holds F over the whole (t, u, v) box.
// Each corner value carries a floating-point error bound (the error filter), so a box is discarded only when
// some coordinate is certainly beyond ±ms over all of it: a box holding a root is never discarded.
//
// Boxes are visited earliest first (a heap on their start time), so the box popped starts no later than any
// contact not yet discarded. A box whose inclusion is at most δ·L wide in every coordinate (L = the query's
// bounding-box diagonal; δ is relative, as `conservative`'s) is accepted: the pair is reported colliding at the
// box's start, a lower bound on the time of contact. Otherwise it is halved along the variable that moves F
// most. A query that examines `max_boxes` boxes is reported colliding at the start of the box it stopped at
// (route `fallback`): never a miss.
//
// So a hit means: some point of the accepted box has every coordinate of F within ms + δ·L (+ rounding) — the
// features come within √3·(ms + δ·L) — and false hits are near misses of about that distance. The reported time
// is a lower bound; for the earliest-time query it is narrowed to within 1e-9 of the step (tighten_toi).
#include "framework/primitive/tester.hpp"

namespace ccdlab {

class InclusionTester final : public PrimitiveTester {
 public:
  struct Params {
    double delta = 1e-6;            ///< accept a box whose inclusion is at most δ·L wide (≥ 0, relative)
    int max_boxes = 100000;         ///< boxes per query before the fallback (a hit at the box's start)
    double min_separation = 0;      ///< ms ≥ 0: contact when every coordinate of F is within ms (scene units)
  };
  InclusionTester() = default;
  explicit InclusionTester(Params p);
  [[nodiscard]] std::string_view name() const override { return "inclusion"; }
  /// The broad phase inflates by ms·√3: a pair reported within ms per coordinate is within that distance.
  [[nodiscard]] double thickness() const override { return params_.min_separation * 1.7320508075688774; }
  [[nodiscard]] std::string_view thickness_name() const override { return "the tester's min_separation (times sqrt(3))"; }
  [[nodiscard]] CcdHit vertex_face(const VertexFaceQuery& q) const override;
  [[nodiscard]] CcdHit edge_edge(const EdgeEdgeQuery& q) const override;
  [[nodiscard]] double tighten_toi(const VertexFaceQuery& q, double toi) const override;
  [[nodiscard]] double tighten_toi(const EdgeEdgeQuery& q, double toi) const override;

 private:
  Params params_{};
};

}  // namespace ccdlab
