#pragma once
// PrimitiveTester: the elementary continuous tests (vertex–face, edge–edge) under linear motion over one
// step. Implementations form the accuracy ladder (float, filtered, additive, conservative, inclusion, exact);
// strategies/testers/.
#include <cstddef>
#include <optional>
#include <span>
#include <string_view>

#include "framework/primitive/contact.hpp"

namespace ccdlab {

/// A distance beyond which a tester never reports a hit: abs + rel·L, L = the query's bounding-box diagonal.
struct CullReach {
  double abs = 0;
  double rel = 0;
};

/// The resolution tighten_toi narrows a time to (2.3e-10 of the step): within 1e-9 of the truth, with room for the
/// last window.
inline constexpr double kTightToiWidth = 0x1p-32;

class PrimitiveTester {
 public:
  virtual ~PrimitiveTester() = default;
  [[nodiscard]] virtual std::string_view name() const = 0;
  /// Contact distance η ≥ 0: features closer than η count as touching. The broad phase inflates by it too.
  [[nodiscard]] virtual double thickness() const = 0;
  /// What the thickness is called where a message names it to the user.
  [[nodiscard]] virtual std::string_view thickness_name() const { return "the tester's thickness"; }
  [[nodiscard]] virtual CcdHit vertex_face(const VertexFaceQuery& q) const = 0;
  [[nodiscard]] virtual CcdHit edge_edge(const EdgeEdgeQuery& q) const = 0;
  /// Many queries at once: out[i] = vertex_face(q[i]), and the same answers bit for bit. Testers with a batched
  /// kernel override these (`float`); the narrow phase hands its survivors over in blocks.
  virtual void vertex_faces(std::span<const VertexFaceQuery> q, CcdHit* out) const {
    for (std::size_t i = 0; i < q.size(); ++i) out[i] = vertex_face(q[i]);
  }
  virtual void edge_edges(std::span<const EdgeEdgeQuery> q, CcdHit* out) const {
    for (std::size_t i = 0; i < q.size(); ++i) out[i] = edge_edge(q[i]);
  }
  /// For the earliest-time query: a lower bound on the time of contact of a pair reported colliding at `toi`
  /// (a lower bound itself), at least `toi` and as late as the tester can prove — for `conservative` and
  /// `inclusion` within 1e-9 of the step of the true time where it is certified. Never later than the truth.
  /// The narrow phase asks it only of hits that can still be the step's earliest (earliest_cut.hpp).
  [[nodiscard]] virtual double tighten_toi(const VertexFaceQuery&, double toi) const { return toi; }
  [[nodiscard]] virtual double tighten_toi(const EdgeEdgeQuery&, double toi) const { return toi; }
  /// The farthest two features can stay apart over the whole step and still be reported as a hit: the
  /// promise that lets the batched narrow phase drop pairs proven farther (plane_filter.hpp). None (the
  /// default) when the tester cannot bound it; the plane stage is then skipped for it.
  [[nodiscard]] virtual std::optional<CullReach> cull_reach() const { return std::nullopt; }
};

}  // namespace ccdlab
