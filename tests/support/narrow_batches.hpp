#pragma once
// Batches the narrow phase's stage tests share: random and near-contact rows of the SIMD stages, the rows of one
// VF and one EE query as the narrow phase stages them, and every feature pair of a mesh.
#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "framework/narrow/kdop_filter.hpp"
#include "framework/narrow/plane_filter.hpp"
#include "framework/primitive/feature_pairs.hpp"
#include "framework/primitive/tester.hpp"
#include "support/test_meshes.hpp"

namespace ccdlab::test {

/// Random moving pairs near each other at every scale, some exactly coplanar throughout, some degenerate.
inline PlaneBatch random_plane_batch(std::size_t n, std::mt19937& rng) {
  PlaneBatch b;
  b.resize(n);
  std::uniform_real_distribution<double> u(-1, 1), e(-6, 6);
  for (std::size_t i = 0; i < n; ++i) {
    const double s = std::pow(10.0, e(rng));
    auto v = [&]() -> Vec3 { return Vec3(u(rng), u(rng), u(rng)) * s; };
    std::array<Vec3, 7> p;
    for (Vec3& q : p) q = v();
    if (i % 7 == 0)  // coplanar motion: f ≡ 0
      for (int k = 0; k < 6; ++k) p[k].z() = 0;
    if (i % 11 == 0) {  // degenerate: B ∥ C
      p[4] = 2 * p[2];
      p[5] = 2 * p[3];
    }
    b.set(i, p[0], p[1], p[2], p[3], p[4], p[5], p[6]);
  }
  return b;
}


/// Row 0: the VF query, row 1: the EE query, as the narrow phase stages them (NarrowPhase::cull_plane).
inline PlaneBatch rows_of(const VertexFaceQuery& q, const EdgeEdgeQuery& r) {
  PlaneBatch b;
  b.resize(2);
  b.set(0, q.v_t0 - q.f0_t0, q.v_t1 - q.f0_t1, q.f1_t0 - q.f0_t0, q.f1_t1 - q.f0_t1, q.f2_t0 - q.f0_t0,
        q.f2_t1 - q.f0_t1, q.f0_t1 - q.f0_t0);
  b.set(1, r.eb0_t0 - r.ea0_t0, r.eb0_t1 - r.ea0_t1, r.ea1_t0 - r.ea0_t0, r.ea1_t1 - r.ea0_t1,
        r.eb1_t0 - r.eb0_t0, r.eb1_t1 - r.eb0_t1, r.ea0_t1 - r.ea0_t0);
  return b;
}


/// n rows of random points in a thin slab: many pairs near contact, many planes crossing.
inline PlaneBatch near_contact_rows(std::size_t n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  auto p = [&]() -> Vec3 { return Vec3(u(rng), u(rng), 0.1 * u(rng)); };
  PlaneBatch b;
  b.resize(n);
  for (std::size_t i = 0; i < n; ++i) b.set(i, p(), p(), p(), p(), p(), p(), p());
  return b;
}


/// Every VF pair (v ∉ f) and EE pair (no shared vertex) of a mesh.
struct AllFeaturePairs {
  std::vector<VertexFacePair> vf;
  std::vector<EdgeEdgePair> ee;
  explicit AllFeaturePairs(const TriMesh& mesh) {
    for (Index v = 0; v < mesh.num_vertices(); ++v)
      for (Index f = 0; f < mesh.num_faces(); ++f)
        if (!contains_vertex(mesh.face(f), v)) vf.push_back({v, f});
    for (Index a = 0; a < mesh.num_edges(); ++a)
      for (Index b = a + 1; b < mesh.num_edges(); ++b)
        if (!shares_vertex(mesh.edge(a), mesh.edge(b))) ee.push_back({a, b});
  }
  /// keep flags of the plain float or coarse test, VF then EE.
  std::vector<std::uint8_t> flags(const TriMesh& mesh, const FeatureBounds& bounds, bool coarse) const {
    std::vector<std::uint8_t> out;
    for (const auto& p : vf)
      out.push_back(coarse ? vf_may_touch_coarse(bounds, p.v, mesh.face(p.f)) : vf_may_touch(bounds, p.v, mesh.face(p.f)));
    for (const auto& p : ee) {
      const Edge &a = mesh.edge(p.a), &b = mesh.edge(p.b);
      out.push_back(coarse ? ee_may_touch_coarse(bounds, a, b) : ee_may_touch(bounds, a, b));
    }
    return out;
  }
};


}  // namespace ccdlab::test
