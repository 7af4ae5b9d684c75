#pragma once
// The BVTT front (the seed paper's contribution): the BVTT nodes where the last step's traversal stopped —
// pair nodes whose volumes did not overlap, and leaf pairs. Kept across steps as one flat array, processed in
// parallel chunks each step:
//   - a node that now overlaps SPROUTS: a depth-first traversal below it; its stopping nodes replace it;
//   - two carried-over sibling nodes that still do not overlap, and whose parent does not either, are PRUNED:
//     collapsed back into the parent (one more BV test), so the front does not only grow;
//   - the front is REBUILT from the root when it has grown past `rebuild_growth` × its size after the last
//     rebuild (or every `rebuild_every` steps).
// Exactness: the nodes of a front cover disjoint sets of leaf pairs whose union is all leaf pairs (a "cut" of
// the BVTT). Sprouting and pruning keep that property whatever the descent rule, and every leaf pair whose
// volumes overlap lies below exactly one front node, all of whose descendants on the way overlap too: the
// candidate set equals the sequential traversal's. Self nodes never stop a traversal, so a self pass starts
// from the root-level pair nodes (A.left, A.right) of every inner node A. Adjacent leaf pairs (faces sharing a
// vertex) always overlap and never yield a candidate: they are dropped from the front instead of being
// re-tested every step, so a self-pass front covers every NON-adjacent leaf pair.
#include <cstdint>
#include <vector>

#include "framework/traversal/bvtt.hpp"
#include "framework/util/uninitialized_vector.hpp"

namespace ccdlab {

struct FrontNode {
  Index a;
  Index b;
  std::uint8_t flags;  ///< kOverlapped, kFresh
  static constexpr std::uint8_t kOverlapped = 1;  ///< the last test found the volumes overlapping (leaf pairs)
  static constexpr std::uint8_t kFresh = 2;       ///< created this step (by a rebuild or a sprout)
};
static_assert(sizeof(FrontNode) == 12, "front nodes are 3 words: keep the front compact");
/// A piece of the front, written in place (uninitialized growth).
using FrontPiece = UninitializedVector<FrontNode>;

struct FrontCounters {
  std::uint64_t bv_tests = 0, visited = 0, sprouted = 0, pruned = 0;
  /// The one merge of two walks' counters (a walk's local ones into its caller's, the threads' into the pass's).
  FrontCounters& operator+=(const FrontCounters& o) {
    bv_tests += o.bv_tests, visited += o.visited, sprouted += o.sprouted, pruned += o.pruned;
    return *this;
  }
};

/// The front a rebuild starts from, covering the BVTT below `root` (the whole BVTT, or one slice of a
/// memory-bounded step): (A.left, A.right) for every inner node A under a self node (r, r), the node itself
/// otherwise — each split (without a BV test; its children cover the same leaf pairs) until it covers at most
/// 1/`granularity` of the pass's leaf pairs (and no fewer than `min_pairs`), so the first step's sprouting is
/// spread over many balanced tasks. Depth-first, left first: siblings stay adjacent for pruning. All fresh.
std::vector<FrontNode> initial_front(const BvhTopology& a, const BvhTopology& b, bool self, BvttNode root = {0, 0},
                                     double granularity = 512, double min_pairs = 4096);

/// Processes front nodes [begin, end): appends their replacements to `next` and candidates to `pairs`. The
/// nodes of `next` before `piece_begin` are other pieces': none is pruned with them.
/// As in traverse_bvtt_binary, the arrays are read through raw pointers held in locals (a front node's `flags`
/// is a byte, and a store through a byte may alias anything, so through the vectors every push reloaded
/// them), and a sprout visits the first child next without a push and a pop.
template <class BV>
void process_front(const BvttView<BV>& v, const FrontNode* begin, const FrontNode* end, bool prune,
                   FrontPiece& next, std::size_t piece_begin, FacePairs& pairs, std::vector<BvttNode>& stack,
                   FrontCounters& counters) {
  FrontCounters c;  // local: the caller's counters are written once, at the end
  const BvhNode* const na = v.side_a.bvh->nodes.data();
  const BvhNode* const nb = v.side_b.bvh->nodes.data();
  const BV* const bva = v.side_a.bv->data();
  const BV* const bvb = v.side_b.bv->data();
  const BvhTopology& tree_a = *v.side_a.bvh;
  const bool self = v.self;
  // An overlapping leaf pair: a candidate, and it stays on the front — unless adjacent (then neither).
  auto emit = [&](const BvhNode& A, const BvhNode& B, Index a, Index b, std::uint8_t flags) {
    if (v.emit_leaf_pair(A, B, pairs)) next.push_back(FrontNode{a, b, flags});
  };
  // Is `p` an ancestor of (or equal to) `q` in tree a? Sub-tree of p = pre-order range [p, p + 2·leaves − 1).
  auto contains = [&](Index p, Index q) { return q >= p && q < tree_a.subtree_end(p); };
  // Appends a stopping node; then collapses the last two entries into their parent while they are carried-over,
  // non-overlapping siblings and the parent does not overlap either.
  auto push_stop = [&](FrontNode n) {
    next.push_back(n);
    while (prune && next.size() >= piece_begin + 2) {
      const FrontNode x = next[next.size() - 2], y = next.back();
      if ((x.flags | y.flags) != 0) break;  // both carried over and not overlapping
      Index pa = -1, pb = -1;
      if (x.b == y.b && x.a != y.a) {
        const Index p = na[x.a].parent;
        if (p < 0 || na[p].left != x.a || na[p].right != y.a || (self && contains(p, x.b))) break;
        pa = p, pb = x.b;
      } else if (x.a == y.a && x.b != y.b) {
        const Index p = nb[x.b].parent;
        if (p < 0 || nb[p].left != x.b || nb[p].right != y.b || (self && contains(p, x.a))) break;
        pa = x.a, pb = p;
      } else {
        break;
      }
      ++c.bv_tests;
      if (v.nodes_overlap(pa, pb)) break;
      next.pop_back();
      next.back() = FrontNode{pa, pb, 0};
      ++c.pruned;
    }
  };
  for (const FrontNode* f = begin; f != end; ++f) {
    const Index fa = f->a, fb = f->b;
    const std::uint8_t fflags = f->flags;
    if (v.in_skipped_patch(fa, fb)) {
      // Inside a patch that cannot touch itself this step: kept, untested, and not merged this step.
      next.push_back(FrontNode{fa, fb, std::uint8_t(fflags | FrontNode::kFresh)});
      continue;
    }
    ++c.visited;
    ++c.bv_tests;
    const BvhNode& A = na[fa];
    const BvhNode& B = nb[fb];
    const bool fresh = fflags & FrontNode::kFresh;
    if (!v.nodes_overlap(fa, fb)) {
      push_stop(FrontNode{fa, fb, std::uint8_t(fresh ? FrontNode::kFresh : 0)});
      continue;
    }
    if (A.is_leaf() && B.is_leaf()) {
      emit(A, B, fa, fb, FrontNode::kOverlapped);
      continue;
    }
    // Sprout: depth-first below f; every stopping node joins the front, marked fresh (no prune attempts:
    // its parent overlaps by construction).
    ++c.sprouted;
    stack.clear();
    BvttNode n{fa, fb};
    bool first = true;
    for (;;) {
      const BvhNode& X = na[n.a];
      const BvhNode& Y = nb[n.b];
      bool stop = false;
      if (!first) {
        ++c.bv_tests;
        if (!v.nodes_overlap(n.a, n.b)) {
          next.push_back(FrontNode{n.a, n.b, FrontNode::kFresh});
          stop = true;
        } else if (X.is_leaf() && Y.is_leaf()) {
          emit(X, Y, n.a, n.b, FrontNode::kOverlapped | FrontNode::kFresh);
          stop = true;
        }
      }
      first = false;
      if (!stop) {
        const auto children = v.pair_children(n, X, Y, bva[n.a], bvb[n.b]);
        stack.push_back(children.node[1]);
        n = children.node[0];
        continue;
      }
      if (stack.empty()) break;
      n = stack.back();
      stack.pop_back();
    }
  }
  counters += c;
}

}  // namespace ccdlab
