#pragma once
// What a BVTT traversal reads (framework/traversal/bvtt.hpp): a BVTT node is a pair of BVH nodes (a, b), a == b a
// self node; the view holds both hierarchies, their volumes, the wide views when bv.width is 4, and the
// candidate rule of two overlapping leaves.
#include "framework/hierarchy/bvh.hpp"
#include "framework/hierarchy/wide_bvh.hpp"
#include "framework/traversal/bvtt_rule.hpp"
#include "framework/traversal/candidates.hpp"
#include "framework/traversal/wide_overlap.hpp"

namespace ccdlab {

struct BvttNode {
  Index a;
  Index b;
};

/// One hierarchy as a walk reads it, at its static BV type.
template <class BV>
struct BvttSide {
  const BvhTopology* bvh = nullptr;
  const BvArray<BV>* bv = nullptr;
  /// The 4-wide view (bv.width: 4), or nullptr: traverse_bvtt then walks the binary tree.
  const WideLayout* wide_layout = nullptr;
  const WideBvs<BV>* wide = nullptr;
  /// End boxes of the nodes (framework/swept/end_boxes.hpp), or nullptr: then only the k-DOPs decide whether two
  /// nodes overlap; and the same per wide record (width 4 with end boxes).
  const EndBoxes* ends = nullptr;
  const WideEnds* wide_ends = nullptr;
};

/// One side's wide view as the 4-wide walks read it: raw pointers loaded once, so that the hot loop does not
/// reload them through the vectors.
template <class BV>
struct WideSideArrays {
  explicit WideSideArrays(const BvttSide<BV>& s)
      : slot(s.wide_layout->slot.data()), home(s.wide_layout->home.data()), records(s.wide->data()), ends(s.wide_ends) {}
  const Index* slot;  ///< WideLayout::slot: a node's record, or ~face for a leaf
  const Index* home;  ///< WideLayout::home: the lane that holds a node's k-DOP, record · 4 + lane
  const WideBounds<BV>* records;
  const WideEnds* ends;  ///< nullptr without end boxes
};

/// Two BVHs (or one, twice) with their refit volumes: what a traversal reads.
template <class BV>
struct BvttView {
  BvttSide<BV> side_a;
  BvttSide<BV> side_b;  ///< == side_a for self-collision
  const TriMesh* mesh = nullptr;
  bool self = true;  ///< self-collision: skip adjacent face pairs
  /// Normal-cone culling (self passes): topmost ancestor-or-self of each node whose self test is skipped this
  /// step, −1 if none; nullptr when culling is off. See normal_cones.hpp.
  const Index* skip_root = nullptr;
  [[nodiscard]] bool wide() const { return side_a.wide && side_b.wide; }
  /// The lane-pair walk of the wide view (traverse_bvtt_lane_pairs) to take, if any: set where the view is
  /// made, from lane_pair_walk(), so that a traversal call does not ask again.
  LanePairWalk lane_pairs = LanePairWalk::none;
  /// THE test of a pair node (a, b), every binary walk's: their k-DOPs overlap and, with end boxes, they are not
  /// apart at both ends. (The wide walks test the same on a record's lanes: wide_overlap.hpp.)
  [[nodiscard]] bool nodes_overlap(Index a, Index b) const {
    return (*side_a.bv)[a].overlaps((*side_b.bv)[b]) &&
           !(side_a.ends && apart_at_both_ends(side_a.ends[a], side_b.ends[b]));
  }
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
  /// The expansion rule (bvtt_rule.hpp) on this view's nodes. Children come in visiting order: a depth-first
  /// walk visits node[0] next and stacks the others in reverse.
  struct Children {
    BvttNode node[3];
    int count;
  };
  [[nodiscard]] bool self_opens(const BvhNode& A, Index a) const { return bvtt_rule::self_opens(A.is_leaf(), skip_root, a); }
  [[nodiscard]] static Children self_children(const BvhNode& A) {
    return {{{A.left, A.left}, {A.right, A.right}, {A.left, A.right}}, 3};
  }
  [[nodiscard]] static Children pair_children(BvttNode n, const BvhNode& A, const BvhNode& B, const BV& va, const BV& vb) {
    if (descend_a(A, B, va, vb)) return {{{A.left, n.b}, {A.right, n.b}, {}}, 2};
    return {{{n.a, B.left}, {n.a, B.right}, {}}, 2};
  }
  [[nodiscard]] Children pair_children(BvttNode n) const {
    return pair_children(n, side_a.bvh->nodes[n.a], side_b.bvh->nodes[n.b], (*side_a.bv)[n.a], (*side_b.bv)[n.b]);
  }
  [[nodiscard]] static bool descend_a(const BvhNode& A, const BvhNode& B, const BV& va, const BV& vb) {
    return bvtt_rule::descend_a(A.is_leaf(), B.is_leaf(), va.size_measure(), vb.size_measure());
  }
  /// Is (a, b) a pair node inside a patch whose self test is skipped?
  [[nodiscard]] bool in_skipped_patch(Index a, Index b) const {
    if (!skip_root) return false;
    const Index q = skip_root[a];
    return q >= 0 && b >= q && b < side_a.bvh->subtree_end(q);
  }
};

}  // namespace ccdlab
