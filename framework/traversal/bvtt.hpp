#pragma once
// BVTT (bounding volume traversal tree) kernels, templated on the bounding volume so the hot loop has no
// virtual calls. A BVTT node is a pair of BVH nodes (a, b); a == b is a self node.
//   self node (A, A)  → children (L, L), (R, R), (L, R)        — the "ternary" BVTT of the paper
//   pair node (A, B)  → one BV overlap test; if they overlap, descend the larger node (by size_measure;
//                       the other one if the larger is a leaf); two overlapping leaves give a candidate.
// Adjacent faces (sharing a vertex) are never candidates: ICCD handles their features in the orphan set.
#include <algorithm>
#include <bit>
#include <cstdint>
#include <utility>
#include <vector>

#include "framework/hierarchy/bvh.hpp"
#include "framework/hierarchy/wide_bvh.hpp"
#include "framework/traversal/wide_overlap.hpp"
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

/// Depth-first traversal of the binary BVTT below `start`: each pair node visited is one BV test.
/// The first child of a node is visited next without going through the stack (the others are pushed in
/// reverse order, so the visiting order is plain pre-order DFS): a push and a pop per node were on the
/// loop's critical path. The loop is bound by its instruction count (~90 per BV test before, callgrind on
/// rod-twist), so the arrays are read through raw pointers held in registers (through the vectors, every
/// store to the stack or the output made the compiler reload them) and the stack's end is a plain pointer.
template <class BV>
void traverse_bvtt_binary(const BvttView<BV>& v, BvttNode start, std::vector<BvttNode>& stack, FacePairs& pairs,
                          std::uint64_t& bv_tests_out) {
  const BvhNode* const na = v.bvh_a->nodes.data();
  const BvhNode* const nb = v.bvh_b->nodes.data();
  const BV* const bva = v.bv_a->data();
  const BV* const bvb = v.bv_b->data();
  const Index* const skip_root = v.skip_root;
  const bool self = v.self;
  std::uint64_t bv_tests = 0;
  // The stack grows by at most 2 per visit; room for 2 more is checked before each visit. It starts small, so
  // that every test with a tree deeper than a few levels runs the growth path too (the vector is reused).
  if (stack.size() < 16) stack.resize(16);
  BvttNode* base = stack.data();
  BvttNode* top = base;  // one past the last pending node
  BvttNode* room = base + stack.size() - 2;  // top may not pass this before a visit
  // Candidates are written the same way: through a pointer, into room made ahead (uninitialized: the whole
  // capacity, or at least 1024 more; doubled when full), trimmed at the end. (Making room from the size alone,
  // e.g. 2·size, reallocated the list at every call: phc calls this once per task on the same thread's list.)
  std::size_t emitted = pairs.size();
  pairs.resize(std::max<std::size_t>(pairs.capacity(), emitted + 1024));
  FacePair* pout = pairs.data() + emitted;
  FacePair* pend = pairs.data() + pairs.size();
  BvttNode n = start;
  for (;;) {
    if (top > room) [[unlikely]] {
      const std::size_t used = std::size_t(top - base);
      stack.resize(2 * stack.size());
      base = stack.data();
      top = base + used;
      room = base + stack.size() - 2;
    }
    const BvhNode& A = na[n.a];
    if (self && n.a == n.b) {
      if (!A.is_leaf() && !(skip_root && skip_root[n.a] >= 0)) {
        *top++ = {A.left, A.right};
        *top++ = {A.right, A.right};
        n = {A.left, A.left};
        continue;
      }
    } else {
      ++bv_tests;
      if (bva[n.a].overlaps(bvb[n.b])) {
        const BvhNode& B = nb[n.b];
        if (A.is_leaf() && B.is_leaf()) {
          if (pout == pend) [[unlikely]] {
            emitted = std::size_t(pout - pairs.data());
            pairs.resize(2 * pairs.size());
            pout = pairs.data() + emitted;
            pend = pairs.data() + pairs.size();
          }
          pout = v.write_face_pair(pout, A.face, B.face);
        } else if (v.descend_a(A, B, bva[n.a], bvb[n.b])) {
          *top++ = {A.right, n.b};
          n.a = A.left;
          continue;
        } else {
          *top++ = {n.a, B.right};
          n.b = B.left;
          continue;
        }
      }
    }
    if (top == base) break;
    n = *--top;
  }
  pairs.resize(std::size_t(pout - pairs.data()));
  bv_tests_out += bv_tests;
}


/// A node on the wide traversal's stack, carrying what its visit needs so that it reads no binary node. A pair
/// node (known to overlap): each side's home (WideLayout::home: the lane that holds its k-DOP, record · 4 + lane),
/// wide slot (a wide node, or ~face for a leaf) and size measure. A self node (self passes only): ha == hb ==
/// the node's id (a pair node's sides are different lanes, so its homes differ).
struct WideBvttEntry {
  Index ha, hb;
  Index wa, wb;
  float sa, sb;
  [[nodiscard]] bool both_leaves() const { return (wa & wb) < 0; }  // slots ~face
  /// The descent rule of a pair node (the binary one): open a's record — the larger side, never a leaf.
  [[nodiscard]] bool descends_a() const { return wb < 0 || (wa >= 0 && sa >= sb); }
};

/// Lanes of a record that hold a node (BV tests when it is opened): 2, 3 or 4, the empty ones last.
template <class BV>
int used_lanes(const WideBounds<BV>& r) {
  constexpr int W = WideLayout::kWidth;
  return W - (r.lanes.node[W - 1] < 0) - (r.lanes.node[W - 2] < 0);
}

/// Scratch space of one traversal (one per thread): the binary and the wide walk keep different stacks.
struct BvttStack {
  std::vector<BvttNode> binary;
  std::vector<WideBvttEntry> wide;
};

/// Depth-first traversal over the 4-wide view: a pair node's larger side opens all its lanes at once and only
/// the lanes that overlap the other side are pushed (test before push). Self nodes still open into (L, L),
/// (R, R), (L, R) as in the binary BVTT, so normal-cone skips apply unchanged. The descent rule is the binary
/// one (the larger side by size_measure, never a leaf); the candidates are the same (see wide_bvh.hpp).
/// Written like the binary walk (raw pointers, candidates written in place). A pair visit reads the record it
/// opens and the other side's k-DOP from the lane that holds it, in a record opened a moment ago: reading it
/// from the binary array instead missed the cache (17% of the walk's samples, rod-twist). A hit lane whose own
/// visit would open the other side's record (the usual case: a lane is two levels smaller) is not pushed: that
/// test is made at once, while both records are in cache. Same BV tests as pushing it, in another order.
template <class BV>
void traverse_bvtt_wide(const BvttView<BV>& v, BvttNode start, std::vector<WideBvttEntry>& stack, FacePairs& pairs,
                        std::uint64_t& bv_tests_out) {
  constexpr int W = WideLayout::kWidth;
  const BvhNode* const na = v.bvh_a->nodes.data();
  const BV* const bva = v.bv_a->data();
  const BV* const bvb = v.bv_b->data();
  const Index* const slot_a = v.wide_layout_a->slot.data();
  const Index* const slot_b = v.wide_layout_b->slot.data();
  const Index* const home_a = v.wide_layout_a->home.data();
  const Index* const home_b = v.wide_layout_b->home.data();
  const WideBounds<BV>* const wide_a = v.wide_a->data();
  const WideBounds<BV>* const wide_b = v.wide_b->data();
  const Index* const skip_root = v.skip_root;
  const bool self = v.self;
  std::uint64_t bv_tests = 0;
  const auto pair_entry = [&](Index a, Index b) {
    return WideBvttEntry{home_a[a], home_b[b], slot_a[a], slot_b[b], bva[a].size_measure(), bvb[b].size_measure()};
  };
  // A visit pushes at most W · W pair nodes, or 2 entries for a self node; room is checked before each visit.
  if (stack.size() < 64) stack.resize(64);
  WideBvttEntry* base = stack.data();
  WideBvttEntry* top = base;
  WideBvttEntry* room = base + stack.size() - W * W;
  std::size_t emitted = pairs.size();
  pairs.resize(std::max<std::size_t>(pairs.capacity(), emitted + 1024));
  FacePair* pout = pairs.data() + emitted;
  FacePair* pend = pairs.data() + pairs.size();
  WideBvttEntry n{start.a, start.b, -1, -1, 0, 0};
  bool visit = true;
  if (!(self && start.a == start.b)) {
    ++bv_tests;
    visit = bva[start.a].overlaps(bvb[start.b]);
    if (visit) n = pair_entry(start.a, start.b);
  }
  const auto emit = [&](const WideBvttEntry& leaves) {  // the candidate of two overlapping leaves
    if (pout == pend) [[unlikely]] {
      emitted = std::size_t(pout - pairs.data());
      pairs.resize(2 * pairs.size());
      pout = pairs.data() + emitted;
      pend = pairs.data() + pairs.size();
    }
    pout = v.write_face_pair(pout, ~leaves.wa, ~leaves.wb);
  };
  alignas(16) float size[W];
  for (;;) {
    if (visit) {
      if (top > room) [[unlikely]] {
        const std::size_t used = std::size_t(top - base);
        stack.resize(2 * stack.size());
        base = stack.data();
        top = base + used;
        room = base + stack.size() - W * W;
      }
      if (self && n.ha == n.hb) {
        const BvhNode& A = na[n.ha];
        if (!A.is_leaf() && !(skip_root && skip_root[n.ha] >= 0)) {
          ++bv_tests;
          if (bva[A.left].overlaps(bva[A.right])) *top++ = pair_entry(A.left, A.right);
          *top++ = {A.right, A.right, -1, -1, 0, 0};
          n = {A.left, A.left, -1, -1, 0, 0};
          continue;
        }
      } else if (n.both_leaves()) {
        emit(n);
      } else {
        const bool down_a = n.descends_a();
        const auto side_of = [&](bool a_side) { return a_side ? wide_a : wide_b; };
        const Index rx = down_a ? n.wa : n.wb;  // the record opened
        const WideBounds<BV>& bx = side_of(down_a)[rx];
        const Index h = down_a ? n.hb : n.ha;  // the other side's home
        unsigned hit = overlapping_lanes(bx, WideLane<BV>{side_of(!down_a) + h / W, h % W});
        bv_tests += used_lanes(bx);
        if (hit) {
          lane_sizes(bx, size);
          const Index ry = down_a ? n.wb : n.wa;  // the other side's record, if it is inner
          alignas(16) float size_y[W];
          bool sized_y = false;
          const auto lane_child = [](WideBvttEntry c, bool a_side, Index record, const WideBounds<BV>& b,
                                     const float* sz, int j) {
            if (a_side) {
              c.ha = record * W + j, c.wa = b.lanes.slot[j], c.sa = sz[j];
            } else {
              c.hb = record * W + j, c.wb = b.lanes.slot[j], c.sb = sz[j];
            }
            return c;
          };
          // A pair node found to overlap: emitted if both are leaves, else pushed, its next record asked for.
          const auto settle = [&](const WideBvttEntry& c) {
            if (c.both_leaves()) {
              emit(c);
              return;
            }
            const char* r = reinterpret_cast<const char*>(c.descends_a() ? wide_a + c.wa : wide_b + c.wb);
            for (std::size_t line = 0; line < sizeof(WideBounds<BV>); line += 64) __builtin_prefetch(r + line);
            *top++ = c;
          };
          for (; hit; hit &= hit - 1) {
            const int j = std::countr_zero(hit);
            const WideBvttEntry c = lane_child(n, down_a, rx, bx, size, j);
            // The visit of c would open the other side's record with lane j as its query (the binary rule):
            // make that test now, while both records are in cache, instead of pushing c.
            if (c.both_leaves() || c.descends_a() == down_a) {
              settle(c);
              continue;
            }
            const WideBounds<BV>& by = side_of(!down_a)[ry];
            unsigned hit_y = overlapping_lanes(by, WideLane<BV>{&bx, j});
            bv_tests += used_lanes(by);
            if (hit_y && !sized_y) lane_sizes(by, size_y), sized_y = true;
            for (; hit_y; hit_y &= hit_y - 1) settle(lane_child(c, !down_a, ry, by, size_y, std::countr_zero(hit_y)));
          }
        }
      }
    }
    if (top == base) break;
    n = *--top;
    visit = true;
  }
  pairs.resize(std::size_t(pout - pairs.data()));
  bv_tests_out += bv_tests;
}

/// Depth-first traversal of the BVTT below `start`, appending candidate face pairs (ordered min, max for
/// self passes; (face of a, face of b) otherwise) to `pairs` and adding the BV tests to `bv_tests`: over the
/// 4-wide view when the view has one. `stack` is scratch space.
template <class BV>
void traverse_bvtt(const BvttView<BV>& v, BvttNode start, BvttStack& stack, FacePairs& pairs, std::uint64_t& bv_tests) {
  if (v.wide())
    traverse_bvtt_wide(v, start, stack.wide, pairs, bv_tests);
  else
    traverse_bvtt_binary(v, start, stack.binary, pairs, bv_tests);
}

}  // namespace ccdlab
