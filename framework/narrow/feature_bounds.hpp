#pragma once
// Stage 1 of the narrow phase: the swept 26-DOP of every vertex over the step, inflated by η/2. An edge's and a
// face's are the union of their vertices' (exact: min/max of floats). A feature pair goes on only when the
// two features' 26-DOPs overlap.
//
// Why this cull never changes the answer (the invariant that makes every representative rule, mode,
// scheduler and K report the same contacts):
//   1. A pair whose features come within η during the step passes: the 26-DOPs contain the swept features
//      (rounded outward as in kdop.hpp), and the midpoint of two points within η lies within η/2 of each.
//   2. A pair that passes has overlapping LEAF volumes for every face g incident to the first feature and h to
//      the second, whatever K the hierarchy uses: the 26 axes contain the axes of K = 6, 14, 18 and 26 (checked
//      below); a vertex's k-DOP lies inside the k-DOP of each incident face (same projections and padding,
//      fewer points), and the leaves are inflated by η ≥ η/2 (inflation is monotone). So every non-adjacent
//      (g, h) is a candidate, and the pair reaches the tester whichever face pair represents it.
// Contacts are thus {tester hit} ∩ {feature 26-DOPs overlap}, a set no choice of strategy can change.
//
// Layout: 13 minima then 13 maxima, each padded with zeros to 16 floats (zero lanes never separate), 128 bytes
// aligned to a cache line, so one pair is a few full-width SIMD loads (kdop_filter.cpp).
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "framework/geometry/kdop.hpp"
#include "framework/mesh/tri_mesh.hpp"
#include "framework/primitive/feature_pairs.hpp"
#include "framework/util/parallel.hpp"
#include "framework/util/uninitialized_vector.hpp"

namespace ccdlab {

namespace detail {
template <int K>
constexpr bool axes_within_26() {
  for (const auto& d : KDopAxes<K>::axes) {
    bool found = false;
    for (const auto& e : KDopAxes<26>::axes) found |= d == e;
    if (!found) return false;
  }
  return true;
}
}  // namespace detail
static_assert(detail::axes_within_26<6>() && detail::axes_within_26<14>() && detail::axes_within_26<18>(),
              "point 2 above: the feature 26-DOP must hold every axis of every hierarchy's k-DOP, same sign");

/// A vertex's swept 26-DOP, padded for SIMD.
struct alignas(64) PaddedDop {
  static constexpr int kAxes = KDop<26>::num_axes;  // 13
  static constexpr int kLanes = 16;
  float min[kLanes];
  float max[kLanes];
};
static_assert(sizeof(PaddedDop) == 128 && PaddedDop::kAxes <= PaddedDop::kLanes);

class FeatureBounds {
 public:
  /// Swept 26-DOP of every vertex between the two frames, inflated by thickness / 2.
  void update(const Positions& x_t0, const Positions& x_t1, double thickness, int threads, PhaseTrace& trace);

  /// Plain versions (scalar mode, tests).
  [[nodiscard]] bool vf_may_touch(Index v, const Face& f) const {
    const PaddedDop &p = vertex_[v], &a = vertex_[f[0]], &b = vertex_[f[1]], &c = vertex_[f[2]];
    bool apart = false;
    for (int i = 0; i < PaddedDop::kAxes; ++i) {
      const float lo = std::min(std::min(a.min[i], b.min[i]), c.min[i]);
      const float hi = std::max(std::max(a.max[i], b.max[i]), c.max[i]);
      apart |= int(p.min[i] > hi) | int(lo > p.max[i]);
    }
    return !apart;
  }
  [[nodiscard]] bool ee_may_touch(const Edge& ea, const Edge& eb) const {
    const PaddedDop &a0 = vertex_[ea[0]], &a1 = vertex_[ea[1]], &b0 = vertex_[eb[0]], &b1 = vertex_[eb[1]];
    bool apart = false;
    for (int i = 0; i < PaddedDop::kAxes; ++i) {
      apart |= int(std::min(a0.min[i], a1.min[i]) > std::max(b0.max[i], b1.max[i])) |
               int(std::min(b0.min[i], b1.min[i]) > std::max(a0.max[i], a1.max[i]));
    }
    return !apart;
  }

  /// SIMD over a batch (best target of this CPU): keep[i] = whether pair i passes; same answers as above.
  void vf_keep(const TriMesh& mesh, std::span<const VertexFacePair> pairs, std::uint8_t* keep) const;
  void ee_keep(const TriMesh& mesh, std::span<const EdgeEdgePair> pairs, std::uint8_t* keep) const;

  [[nodiscard]] std::size_t memory_bytes() const { return vertex_.size() * sizeof(PaddedDop); }

 private:
  UninitializedVector<PaddedDop> vertex_;  // update() writes every entry: growing it zeroes nothing
};

}  // namespace ccdlab
