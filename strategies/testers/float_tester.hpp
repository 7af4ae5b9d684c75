#pragma once
// `float`: the classic floating-point CCD test (Provot 1997; Bridson et al. 2002), in double precision.
// Four points are coplanar when the triple product f(t) = A(t) · (B(t) × C(t)) vanishes; under linear motion
// f is a cubic. Its roots in [0, 1] (plus t = 0 and t = 1) are the candidate times; at each, in increasing
// order, the features are checked for proximity (distance ≤ η + a relative tolerance). The first that passes
// is the time of contact. When the motion is coplanar throughout (f ≡ 0), the candidate times are those
// where a vertex crosses the line of an edge within the plane.
//
// It is fast, but rounding makes it miss some grazing contacts (the accuracy ladder measures how
// many): it is NOT conservative. All tolerances are relative to the query's extent (scale invariant).
#include "framework/primitive/tester.hpp"

namespace ccdlab {

class FloatTester final : public PrimitiveTester {
 public:
  struct Params {
    double thickness = 0.0;  ///< η ≥ 0, same units as positions
  };
  FloatTester() = default;
  explicit FloatTester(Params p) : params_(p) {}
  [[nodiscard]] std::string_view name() const override { return "float"; }
  [[nodiscard]] double thickness() const override { return params_.thickness; }
  [[nodiscard]] CcdHit vertex_face(const VertexFaceQuery& q) const override;
  [[nodiscard]] CcdHit edge_edge(const EdgeEdgeQuery& q) const override;
  /// The root search in SIMD for a block of queries (float_roots.hpp) at thickness 0; the same answers.
  void vertex_faces(std::span<const VertexFaceQuery> q, CcdHit* out) const override;
  void edge_edges(std::span<const EdgeEdgeQuery> q, CcdHit* out) const override;
  /// Hits are within η + rel_tolerance·L; twice the tolerance absorbs the rounding of the distances computed.
  [[nodiscard]] std::optional<CullReach> cull_reach() const override { return CullReach{params_.thickness, 2 * rel_tolerance}; }

  /// Distance tolerance relative to the query's extent: proximity holds when d ≤ η + rel_tolerance · extent.
  static constexpr double rel_tolerance = 1e-9;

 private:
  Params params_{};
};

}  // namespace ccdlab
