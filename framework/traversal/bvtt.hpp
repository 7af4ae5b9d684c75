#pragma once
// BVTT (bounding volume traversal tree) kernels, templated on the bounding volume so the hot loop has no
// virtual calls. A BVTT node is a pair of BVH nodes (a, b); a == b is a self node.
//   self node (A, A)  → children (L, L), (R, R), (L, R)        — the "ternary" BVTT of the paper
//   pair node (A, B)  → one BV overlap test; if they overlap, descend the larger node (by size_measure;
//                       the other one if the larger is a leaf); two overlapping leaves give a candidate.
// (The rule's one home is bvtt_rule.hpp; BvttView applies it to nodes: self_opens, self_children, pair_children.)
// Adjacent faces (sharing a vertex) are never candidates: ICCD handles their features in the orphan set.
#include <algorithm>
#include <bit>
#include <cstdint>
#include <utility>
#include <vector>

#include "framework/traversal/bvtt_view.hpp"
#include "framework/traversal/bvtt_wide.hpp"

namespace ccdlab {

/// Depth-first traversal of the binary BVTT below `start`: each pair node visited is one BV test.
/// The first child of a node is visited next without going through the stack (the others are pushed in
/// reverse order, so the visiting order is plain pre-order DFS): a push and a pop per node were on the
/// loop's critical path. The loop is bound by its instruction count, so the arrays are read through raw pointers held in registers (through the vectors, every
/// store to the stack or the output made the compiler reload them) and the stack's end is a plain pointer.
template <class BV>
void traverse_bvtt_binary(const BvttView<BV>& v, BvttNode start, std::vector<BvttNode>& stack, FacePairs& pairs,
                          std::uint64_t& bv_tests_out) {
  const BvhNode* const na = v.side_a.bvh->nodes.data();
  const BvhNode* const nb = v.side_b.bvh->nodes.data();
  const BV* const bva = v.side_a.bv->data();
  const BV* const bvb = v.side_b.bv->data();
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
      if (v.self_opens(A, n.a)) {
        const auto c = v.self_children(A);
        *top++ = c.node[2];
        *top++ = c.node[1];
        n = c.node[0];
        continue;
      }
    } else {
      ++bv_tests;
      if (v.nodes_overlap(n.a, n.b)) {
        const BvhNode& B = nb[n.b];
        if (A.is_leaf() && B.is_leaf()) {
          if (pout == pend) [[unlikely]] {
            emitted = std::size_t(pout - pairs.data());
            pairs.resize(2 * pairs.size());
            pout = pairs.data() + emitted;
            pend = pairs.data() + pairs.size();
          }
          pout = v.write_face_pair(pout, A.face, B.face);
        } else {
          const auto c = v.pair_children(n, A, B, bva[n.a], bvb[n.b]);
          *top++ = c.node[1];
          n = c.node[0];
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


/// Scratch space of one traversal (one per thread): each walk keeps its own stack.
struct BvttStack {
  std::vector<BvttNode> binary;
  std::vector<WideBvttEntry> wide;
  LanePairStack lane_pairs;
};

/// Depth-first traversal of the BVTT below `start`, appending candidate face pairs (ordered min, max for
/// self passes; (face of a, face of b) otherwise) to `pairs` and adding the BV tests to `bv_tests`: over the
/// 4-wide view when the view has one (in AVX-512 or AVX2 where the CPU has it). `stack` is scratch space.
template <class BV>
void traverse_bvtt(const BvttView<BV>& v, BvttNode start, BvttStack& stack, FacePairs& pairs, std::uint64_t& bv_tests) {
#if defined(CCDLAB_HAS_LANE_PAIR_WALKS)
  if (v.wide() && v.lane_pairs != LanePairWalk::none)
    return traverse_bvtt_lane_pairs(v.lane_pairs, v, start, stack.lane_pairs, pairs, bv_tests);
#endif
  if (v.wide())
    traverse_bvtt_wide(v, start, stack.wide, pairs, bv_tests);
  else
    traverse_bvtt_binary(v, start, stack.binary, pairs, bv_tests);
}

}  // namespace ccdlab
