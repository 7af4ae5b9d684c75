#pragma once
// `filtered`: a certified non-penetration filter in front of `float` (after Tang, Manocha & Tong 2010,
// "Fast continuous collision detection using deforming non-penetration filters"). On the whole step it
// bounds, in Bernstein form with interval arithmetic (interval_ccd.hpp), the coplanarity cubic f(t) and the
// quartics that say whether the vertex projects into the face / the edges' ends straddle each other's line.
// When f keeps one sign, the swept boxes are disjoint, or one of those quartics keeps the wrong sign, the
// features cannot touch, proven, and `float` is skipped (counted as route = filter). Zero thickness only.
#include "strategies/testers/float_tester.hpp"

namespace ccdlab {

class FilteredTester final : public PrimitiveTester {
 public:
  [[nodiscard]] std::string_view name() const override { return "filtered"; }
  [[nodiscard]] double thickness() const override { return 0.0; }
  [[nodiscard]] CcdHit vertex_face(const VertexFaceQuery& q) const override;
  [[nodiscard]] CcdHit edge_edge(const EdgeEdgeQuery& q) const override;
  /// The filter per query, then `float`'s batched search on the queries it leaves.
  void vertex_faces(std::span<const VertexFaceQuery> q, CcdHit* out) const override;
  void edge_edges(std::span<const EdgeEdgeQuery> q, CcdHit* out) const override;
  [[nodiscard]] std::optional<CullReach> cull_reach() const override { return CullReach{0, 2 * FloatTester::rel_tolerance}; }

 private:
  FloatTester float_{};
};

}  // namespace ccdlab
