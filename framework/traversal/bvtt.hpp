#pragma once
// BVTT (bounding volume traversal tree) kernels, templated on the bounding volume so the hot loop has no
// virtual calls. A BVTT node is a pair of BVH nodes (a, b); a == b is a self node.
//   self node (A, A)  → children (L, L), (R, R), (L, R)        — the "ternary" BVTT of the paper
//   pair node (A, B)  → one BV overlap test; if they overlap, descend the larger node (by size_measure;
//                       the other one if the larger is a leaf); two overlapping leaves give a candidate.
// Adjacent faces (sharing a vertex) are never candidates: ICCD handles their features in the orphan set.
#include <cstdint>
#include <utility>
#include <vector>

#include "framework/hierarchy/bvh.hpp"
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
  const std::vector<BV>* bv_a;
  const BvhTopology* bvh_b;  ///< == bvh_a for self-collision
  const std::vector<BV>* bv_b;
  const TriMesh* mesh;
  bool self;  ///< self-collision: skip adjacent face pairs
  /// Normal-cone culling (self passes): topmost ancestor-or-self of each node whose self test is skipped this
  /// step, −1 if none; nullptr when culling is off. See normal_cones.hpp.
  const Index* skip_root = nullptr;
  /// Appends the candidate of two overlapping leaves (ordered (min, max) in self passes; none when adjacent).
  /// Returns whether one was appended.
  bool emit_leaf_pair(const BvhNode& A, const BvhNode& B, std::vector<FacePair>& out) const {
    if (!self) {
      out.push_back({A.face, B.face});
      return true;
    }
    if (mesh->faces_adjacent(A.face, B.face)) return false;
    out.push_back(A.face < B.face ? FacePair{A.face, B.face} : FacePair{B.face, A.face});
    return true;
  }
  /// The descent rule of a pair node: split a (true) or b (false) — the larger by size_measure, never a leaf.
  [[nodiscard]] bool descend_a(Index a, Index b) const {
    const BvhNode& A = bvh_a->nodes[a];
    const BvhNode& B = bvh_b->nodes[b];
    return B.is_leaf() || (!A.is_leaf() && (*bv_a)[a].size_measure() >= (*bv_b)[b].size_measure());
  }
  /// Is (a, b) a pair node inside a patch whose self test is skipped?
  [[nodiscard]] bool in_skipped_patch(Index a, Index b) const {
    if (!skip_root) return false;
    const Index q = skip_root[a];
    return q >= 0 && b >= q && b < bvh_a->subtree_end(q);
  }
};

/// Depth-first traversal of the BVTT below `start`, appending candidate face pairs (ordered min, max for
/// self passes; (face of a, face of b) otherwise) to `out`. `stack` is scratch space.
template <class BV>
void traverse_bvtt(const BvttView<BV>& v, BvttNode start, std::vector<BvttNode>& stack, TraversalOutput& out) {
  const auto& na = v.bvh_a->nodes;
  const auto& nb = v.bvh_b->nodes;
  const auto& bva = *v.bv_a;
  const auto& bvb = *v.bv_b;
  std::uint64_t bv_tests = 0;
  stack.clear();
  stack.push_back(start);
  while (!stack.empty()) {
    BvttNode n = stack.back();
    stack.pop_back();
    const BvhNode& A = na[n.a];
    if (v.self && n.a == n.b) {
      if (A.is_leaf() || (v.skip_root && v.skip_root[n.a] >= 0)) continue;
      stack.push_back({A.left, A.right});
      stack.push_back({A.right, A.right});
      stack.push_back({A.left, A.left});
      continue;
    }
    ++bv_tests;
    if (!bva[n.a].overlaps(bvb[n.b])) continue;
    const BvhNode& B = nb[n.b];
    if (A.is_leaf() && B.is_leaf()) {
      v.emit_leaf_pair(A, B, out.pairs);
      continue;
    }
    if (v.descend_a(n.a, n.b)) {
      stack.push_back({A.right, n.b});
      stack.push_back({A.left, n.b});
    } else {
      stack.push_back({n.a, B.right});
      stack.push_back({n.a, B.left});
    }
  }
  out.bv_tests += bv_tests;
}

}  // namespace ccdlab
