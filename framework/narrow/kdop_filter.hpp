#pragma once
// Stage 1 of the narrow phase: a feature pair goes on only when the two features' swept 26-DOPs overlap (the
// bounds and the argument that this cull defines the contact set: framework/swept/feature_bounds.hpp).
// Two tests of the same bounds: the coarse 16-bit one runs on every pair and keeps all the float one keeps (plus a
// few it drops); the float one, the definition, runs last, on the few pairs stages 2–4 leave (NarrowPhase::run).
#include <algorithm>
#include <cstdint>
#include <span>

#include "framework/mesh/tri_mesh.hpp"
#include "framework/primitive/feature_pairs.hpp"
#include "framework/swept/feature_bounds.hpp"

namespace ccdlab {

/// Whether vertex v's and face f's swept 26-DOPs overlap (plain: scalar mode, tests).
[[nodiscard]] inline bool vf_may_touch(const FeatureBounds& bounds, Index v, const Face& f) {
  const PaddedDop* dops = bounds.dops();
  const PaddedDop &p = dops[v], &a = dops[f[0]], &b = dops[f[1]], &c = dops[f[2]];
  bool apart = false;
  for (int i = 0; i < PaddedDop::kAxes; ++i) {
    const float lo = std::min(std::min(a.min[i], b.min[i]), c.min[i]);
    const float hi = std::max(std::max(a.max[i], b.max[i]), c.max[i]);
    apart |= int(p.min[i] > hi) | int(lo > p.max[i]);
  }
  return !apart;
}

/// Whether edges ea's and eb's swept 26-DOPs overlap (plain).
[[nodiscard]] inline bool ee_may_touch(const FeatureBounds& bounds, const Edge& ea, const Edge& eb) {
  const PaddedDop* dops = bounds.dops();
  const PaddedDop &a0 = dops[ea[0]], &a1 = dops[ea[1]], &b0 = dops[eb[0]], &b1 = dops[eb[1]];
  bool apart = false;
  for (int i = 0; i < PaddedDop::kAxes; ++i) {
    apart |= int(std::min(a0.min[i], a1.min[i]) > std::max(b0.max[i], b1.max[i])) |
             int(std::min(b0.min[i], b1.min[i]) > std::max(a0.max[i], a1.max[i]));
  }
  return !apart;
}

/// The coarse test, plain: true whenever the float test above is (and for a few of the pairs it drops).
[[nodiscard]] inline bool vf_may_touch_coarse(const FeatureBounds& bounds, Index v, const Face& f) {
  const CoarseDop* dops = bounds.coarse_dops();
  const CoarseDop &p = dops[v], &a = dops[f[0]], &b = dops[f[1]], &c = dops[f[2]];
  bool apart = false;
  for (int i = 0; i < PaddedDop::kAxes; ++i) {
    const int lo = std::min(std::min(a.min[i], b.min[i]), c.min[i]);
    const int neg_hi = std::min(std::min(a.neg_max[i], b.neg_max[i]), c.neg_max[i]);
    apart |= int(p.min[i] + neg_hi > 0) | int(lo + p.neg_max[i] > 0);
  }
  return !apart;
}
[[nodiscard]] inline bool ee_may_touch_coarse(const FeatureBounds& bounds, const Edge& ea, const Edge& eb) {
  const CoarseDop* dops = bounds.coarse_dops();
  const CoarseDop &a0 = dops[ea[0]], &a1 = dops[ea[1]], &b0 = dops[eb[0]], &b1 = dops[eb[1]];
  bool apart = false;
  for (int i = 0; i < PaddedDop::kAxes; ++i) {
    apart |= int(std::min(a0.min[i], a1.min[i]) + std::min(b0.neg_max[i], b1.neg_max[i]) > 0) |
             int(std::min(b0.min[i], b1.min[i]) + std::min(a0.neg_max[i], a1.neg_max[i]) > 0);
  }
  return !apart;
}

/// SIMD over a batch (best target of this CPU): keep[i] = whether pair i passes; the same answers as the plain
/// tests above, float (vf_keep, ee_keep) or coarse (the _coarse ones).
void vf_keep(const FeatureBounds& bounds, const TriMesh& mesh, std::span<const VertexFacePair> pairs, std::uint8_t* keep);
void ee_keep(const FeatureBounds& bounds, const TriMesh& mesh, std::span<const EdgeEdgePair> pairs, std::uint8_t* keep);
void vf_keep_coarse(const FeatureBounds& bounds, const TriMesh& mesh, std::span<const VertexFacePair> pairs,
                    std::uint8_t* keep);
void ee_keep_coarse(const FeatureBounds& bounds, const TriMesh& mesh, std::span<const EdgeEdgePair> pairs,
                    std::uint8_t* keep);
/// The coarse tests, and the smallest over the pairs of each pair's largest separation on an axis, in grid steps
/// (≤ 0: some pair overlaps; 32767 without pairs or where it saturates). Times FeatureBounds::coarse_step() less
/// two steps, a distance every pair keeps at least (OrphanCertificates).
int vf_keep_coarse_gap(const FeatureBounds& bounds, const TriMesh& mesh, std::span<const VertexFacePair> pairs,
                       std::uint8_t* keep);
int ee_keep_coarse_gap(const FeatureBounds& bounds, const TriMesh& mesh, std::span<const EdgeEdgePair> pairs,
                       std::uint8_t* keep);

}  // namespace ccdlab
