#pragma once
// Continuous normal-cone culling of self-tests (ICCD, Tang et al. 2009; star contours after Schvartzman et al.
// 2010). The self node (A, A) of the BVTT can be skipped for a step when the patch of A cannot touch itself
// during the step:
//   1. disk     : the faces under A form a connected, consistently oriented topological disk with one boundary
//                 loop (fixed by the topology; computed once);
//   2. cone     : one direction V has n(t)·V > 0 for every face normal at every t ∈ [0, 1]. A face normal is a
//                 quadratic in t whose Bernstein coefficients are n(t0), n(t1) and
//                 ((b0 − a0) × (c1 − a1) + (b1 − a1) × (c0 − a0)) / 2, so n(t) stays in the cone of those three;
//                 cones are merged bottom-up;
//   3. contour  : projected along V, the boundary loop is star-shaped around its moving centroid p(t): every
//                 boundary edge (u → w, in face winding order) keeps V·((u − p) × (w − p)) > 0 — a quadratic in
//                 t, checked through its 3 Bernstein coefficients.
// Then at every t the patch projects one-to-one onto the plane ⊥ V (a height field), so no two of its points
// coincide: no contact between its non-adjacent features is lost. Only for thickness 0 (with η > 0 a height
// field can still bring features within η). Margins are relative (1e-9), so rounding cannot flip a sign.
#include <cstdint>
#include <vector>

#include "framework/geometry/vec.hpp"
#include "framework/hierarchy/bvh.hpp"
#include "framework/mesh/tri_mesh.hpp"
#include "framework/util/parallel.hpp"

namespace ccdlab {

class NormalConeCuller {
 public:
  /// Precomputes, per node with ≥ kMinLeaves faces, whether its patch is a disk and its oriented boundary.
  /// `bvh` must outlive the culler, which is valid for its current topology version only.
  NormalConeCuller(const TriMesh& mesh, const BvhTopology& bvh, int threads = 1);

  /// Per step: face cones, merged bottom-up, then for every node the topmost ancestor-or-self whose self
  /// test can be skipped (or −1), evaluated top-down (no contour test below a skipped node). Parallel over a
  /// the tree's refit plan (its fixed cut of sub-trees); task costs go to `trace`. Returns the number of topmost skipped nodes.
  std::uint64_t update(const Positions& x_t0, const Positions& x_t1, int threads, PhaseTrace& trace);

  /// Topmost skipped ancestor-or-self of each node this step, −1 if none (what traversals read).
  [[nodiscard]] const std::vector<Index>& skip_root() const { return skip_root_; }
  [[nodiscard]] std::uint64_t contour_edge_tests() const { return contour_edge_tests_; }

  static constexpr Index kMinLeaves = 8;  ///< smaller patches are not worth a contour test

 private:
  struct Cone {
    Vec3 axis = Vec3::Zero();
    double half_angle = 10;  ///< radians; ≥ π/2 means "no cone"
  };
  [[nodiscard]] bool contour_is_star(Index node, const Vec3& axis, const Positions& x0, const Positions& x1) const;
  /// Can node i skip its self test (disk, narrow cone, star contour)? Counts contour edges tested.
  [[nodiscard]] bool passes(Index i, const Positions& x0, const Positions& x1, std::uint64_t& edges) const;
  void merge_children(Index i);

  const TriMesh& mesh_;
  const BvhTopology& bvh_;
  std::vector<char> is_disk_;
  Adjacency boundary_;  ///< per node: boundary edges as (u, w) vertex pairs, flattened u0 w0 u1 w1 …
  std::vector<Cone> cone_;
  std::vector<Index> skip_root_;
  std::uint64_t contour_edge_tests_ = 0;
};

}  // namespace ccdlab
