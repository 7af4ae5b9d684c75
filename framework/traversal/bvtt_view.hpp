#pragma once
// What a BVTT traversal reads (framework/traversal/bvtt.hpp): a BVTT node is a pair of BVH nodes (a, b), a == b a
// self node; the view holds both hierarchies, their volumes, the wide views when bv.width is 4, and the
// candidate rule of two overlapping leaves.
#include "framework/hierarchy/bvh.hpp"
#include "framework/hierarchy/wide_bvh.hpp"
#include "framework/traversal/candidates.hpp"

namespace ccdlab {

struct BvttNode {
  Index a;
  Index b;
};

/// Two BVHs (or one, twice) with their refit volumes: what a traversal reads.
template <class BV>
struct BvttView {
  const BvhTopology* bvh_a;
  const BvArray<BV>* bv_a;
  const BvhTopology* bvh_b;  ///< == bvh_a for self-collision
  const BvArray<BV>* bv_b;
  const TriMesh* mesh;
  bool self;  ///< self-collision: skip adjacent face pairs
  /// Normal-cone culling (self passes): topmost ancestor-or-self of each node whose self test is skipped this
  /// step, −1 if none; nullptr when culling is off. See normal_cones.hpp.
  const Index* skip_root = nullptr;
  /// The 4-wide views of both hierarchies (bv.width: 4), or nullptr: traverse_bvtt then walks the binary tree.
  const WideLayout* wide_layout_a = nullptr;
  const WideBvs<BV>* wide_a = nullptr;
  const WideLayout* wide_layout_b = nullptr;
  const WideBvs<BV>* wide_b = nullptr;
  [[nodiscard]] bool wide() const { return wide_a && wide_b; }
  /// Walk the wide view in AVX-512 (traverse_bvtt_lane_pairs): set where the view is made, from
  /// lane_pairs_walk_available(), so that a traversal call does not ask again.
  bool lane_pairs = false;
  /// Appends the candidate of two overlapping leaves (ordered (min, max) in self passes; none when adjacent).
  /// Returns whether one was appended.
  bool emit_leaf_pair(const BvhNode& A, const BvhNode& B, FacePairs& out) const {
    return emit_face_pair(A.face, B.face, out);
  }
  bool emit_face_pair(Index fa, Index fb, FacePairs& out) const {
    const std::size_t n = out.size();
    out.resize(n + 1);
    out.resize(std::size_t(write_face_pair(out.data() + n, fa, fb) - out.data()));
    return out.size() > n;
  }
  /// The same rule, written at `at` (room for one): returns `at` + 1, or `at` when nothing is appended.
  /// Branch-free, for the hot walk: in self passes the adjacency answers are close to random.
  FacePair* write_face_pair(FacePair* at, Index fa, Index fb) const {
    if (!self) {
      *at = {fa, fb};
      return at + 1;
    }
    *at = fa < fb ? FacePair{fa, fb} : FacePair{fb, fa};
    return at + int(!mesh->faces_adjacent(fa, fb));
  }
  /// The descent rule of a pair node: split a (true) or b (false) — the larger by size_measure, never a leaf.
  [[nodiscard]] bool descend_a(Index a, Index b) const {
    return descend_a(bvh_a->nodes[a], bvh_b->nodes[b], (*bv_a)[a], (*bv_b)[b]);
  }
  /// The same rule on the nodes and volumes themselves (the walks that hold raw pointers).
  [[nodiscard]] static bool descend_a(const BvhNode& A, const BvhNode& B, const BV& va, const BV& vb) {
    return B.is_leaf() || (!A.is_leaf() && va.size_measure() >= vb.size_measure());
  }
  /// Is (a, b) a pair node inside a patch whose self test is skipped?
  [[nodiscard]] bool in_skipped_patch(Index a, Index b) const {
    if (!skip_root) return false;
    const Index q = skip_root[a];
    return q >= 0 && b >= q && b < bvh_a->subtree_end(q);
  }
};

}  // namespace ccdlab
