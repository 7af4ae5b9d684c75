#pragma once
// The elementary test of the proximity query (framework/pipeline/proximity/proximity_query.hpp): is a vertex–face or an
// edge–edge pair closer than d̂ at one set of positions? Decided exactly, and described for the report by its
// distance and the type of its closest features (what a barrier solver differentiates).
//
// The decision. The distance between two features is the least of a few pieces, each a squared distance that is a
// rational function of the coordinates (no square root, no rounding in the statement):
//   VF: the vertex to each of the face's three edges (segments, corners included), and to the face's plane when
//       the vertex projects inside the face:  (n·(p − a))² / n·n,  n = (b − a) × (c − a);
//   EE: each of the four endpoints to the other edge, and the two lines' distance when their closest points lie
//       inside both edges:  (r·n)² / n·n,  n = d_a × d_b,  r = b0 − a0  (parameters (r × d_b)·n / n·n, (r × d_a)·n / n·n).
// Each comparison "piece < d̂²" is multiplied out (denominators are n·n or an edge's squared length, both ≥ 0) and
// evaluated first in outward-rounded intervals (framework/geometry/interval.hpp); only when an interval cannot
// decide a sign — a pair at distance d̂ to within rounding, a face of almost no area, almost parallel edges — is it
// evaluated again in rationals (GMP), exactly. A pair is reported when any applicable piece is certainly below d̂²:
// the reported set is exactly {pairs whose exact distance is < d̂}. Degenerate features need no special case: a
// face of zero area has no interior piece (n·n = 0), a point-like edge is a point to its segments.
#include <array>
#include <cstdint>
#include <string_view>

#include "framework/geometry/vec.hpp"
#include "framework/primitive/tester.hpp"
#include "framework/util/named_values.hpp"

namespace ccdlab {

/// The closest features of a pair, named as barrier solvers name them (p the vertex; t0, t1, t2 the face's
/// corners; e0 = (f0, f1), e1 = (f1, f2), e2 = (f2, f0) its edges; t its interior; ea0, ea1 edge a's ends, ea its
/// interior; the same for b).
enum class DistanceType : std::uint8_t {
  p_t0, p_t1, p_t2, p_e0, p_e1, p_e2, p_t,
  ea0_eb0, ea0_eb1, ea1_eb0, ea1_eb1, ea_eb0, ea_eb1, ea0_eb, ea1_eb, ea_eb,
};
inline constexpr NamedValues<DistanceType, 16> kDistanceTypes{{{
    {"p_t0", DistanceType::p_t0}, {"p_t1", DistanceType::p_t1}, {"p_t2", DistanceType::p_t2},
    {"p_e0", DistanceType::p_e0}, {"p_e1", DistanceType::p_e1}, {"p_e2", DistanceType::p_e2}, {"p_t", DistanceType::p_t},
    {"ea0_eb0", DistanceType::ea0_eb0}, {"ea0_eb1", DistanceType::ea0_eb1}, {"ea1_eb0", DistanceType::ea1_eb0},
    {"ea1_eb1", DistanceType::ea1_eb1}, {"ea_eb0", DistanceType::ea_eb0}, {"ea_eb1", DistanceType::ea_eb1},
    {"ea0_eb", DistanceType::ea0_eb}, {"ea1_eb", DistanceType::ea1_eb}, {"ea_eb", DistanceType::ea_eb},
}}};
[[nodiscard]] inline std::string_view to_string(DistanceType t) { return kDistanceTypes.name_of(t); }

/// A pair's distance (in double: closest points by Ericson's regions, framework/geometry/distance.hpp), the type of
/// its closest features, and their coordinates: VF the barycentric weights of f1 and f2, EE the parameters along
/// edge a and edge b.
struct ClosestFeatures {
  double distance;
  DistanceType type;
  std::array<double, 2> coords;
};
[[nodiscard]] ClosestFeatures closest_vertex_face(const Vec3& p, const Vec3& f0, const Vec3& f1, const Vec3& f2);
[[nodiscard]] ClosestFeatures closest_edge_edge(const Vec3& a0, const Vec3& a1, const Vec3& b0, const Vec3& b1);

/// Whether a pair's exact distance is below d̂, and whether rationals had to decide it.
struct DistanceVerdict {
  bool closer = false;
  bool in_rationals = false;
};
[[nodiscard]] DistanceVerdict vertex_face_closer(const Vec3& p, const Vec3& f0, const Vec3& f1, const Vec3& f2, double dhat);
[[nodiscard]] DistanceVerdict edge_edge_closer(const Vec3& a0, const Vec3& a1, const Vec3& b0, const Vec3& b1, double dhat);

/// The proximity query's tester: a pair at positions x_t0 (the query passes x_t0 = x_t1) is a hit when its exact
/// distance is below d̂ (toi 0; the query describes its hits afterwards, ProximityPair). The pipeline's bounds and
/// culling stages take d̂ as the thickness and the reach: each drops only pairs proven farther than d̂ apart,
/// rounding included, so nothing closer is lost before the test (docs/proximity.md).
class StaticDistanceTester final : public PrimitiveTester {
 public:
  explicit StaticDistanceTester(double dhat);
  [[nodiscard]] std::string_view name() const override { return "static_distance"; }
  [[nodiscard]] double thickness() const override { return dhat_; }
  [[nodiscard]] std::string_view thickness_name() const override { return "the proximity query's dhat"; }
  [[nodiscard]] CcdHit vertex_face(const VertexFaceQuery& q) const override;
  [[nodiscard]] CcdHit edge_edge(const EdgeEdgeQuery& q) const override;
  [[nodiscard]] std::optional<CullReach> cull_reach() const override { return CullReach{dhat_, 0}; }

 private:
  double dhat_;
};

}  // namespace ccdlab
