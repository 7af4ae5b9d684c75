#include "framework/traversal/front/wide_front.hpp"

#include <algorithm>
#include <span>

#include "framework/traversal/bvtt_rule.hpp"

namespace ccdlab {

WideFrontPiece wide_front_seeds(const BvhTopology& a, const WideLayout& la, const BvhTopology& b,
                                const WideLayout& lb, bool self, BvttNode root, bool self_nodes, double granularity,
                                double min_pairs) {
  constexpr int W = WideLayout::kWidth;
  WideFrontPiece front;
  if (a.nodes.empty() || b.nodes.empty()) return front;
  const double max_pairs = bvtt_rule::seed_max_pairs(a.num_leaves(), b.num_leaves(), self, granularity, min_pairs);
  const auto add = [&](Index hx, Index hy) {  // node pair at homes hx, hy: one lane pair, merged when it can be
    const unsigned bit = 1u << (W * (hx % W) + hy % W);
    if (!front.empty() && front.back().ra == hx / W && front.back().rb == hy / W)
      front.back().cut = std::uint16_t(front.back().cut | bit);
    else
      front.push_back(WideFrontGroup{hx / W, hy / W, std::uint16_t(bit), 0, 0});
  };
  struct Side {
    Index node, home;
  };
  // The sides a visit opens: the lanes of an inner node's record, a leaf itself.
  const auto children = [&](const BvhTopology& t, const WideLayout& l, Side s, Side* out) {
    if (t.nodes[std::size_t(s.node)].is_leaf()) {
      out[0] = s;
      return 1;
    }
    const Index r = l.slot[std::size_t(s.node)];
    int n = 0;
    for (int j = 0; j < W; ++j)
      if (const Index c = l.lanes[std::size_t(r)].node[std::size_t(j)]; c >= 0) out[n++] = Side{c, r * W + j};
    return n;
  };
  std::vector<std::pair<Side, Side>> stack;
  const auto split = [&](Side x, Side y) {
    stack.assign(1, {x, y});
    while (!stack.empty()) {
      const auto [p, q] = stack.back();
      stack.pop_back();
      const double cp = a.leaf_count[std::size_t(p.node)], cq = b.leaf_count[std::size_t(q.node)];
      if (bvtt_rule::seed_is_piece(cp, cq, max_pairs)) {
        add(p.home, q.home);
        continue;
      }
      Side ca[W], cb[W];
      const int n = children(a, la, p, ca), m = children(b, lb, q, cb);
      for (int i = n - 1; i >= 0; --i)  // reversed: popped in lane order, so that a visit's lane pairs merge
        for (int j = m - 1; j >= 0; --j) stack.push_back({ca[i], cb[j]});
    }
  };
  if (!self || root.a != root.b) {
    split(Side{root.a, la.home[std::size_t(root.a)]}, Side{root.b, lb.home[std::size_t(root.b)]});
    return front;
  }
  if (!self_nodes) {
    for (Index i = root.a; i < a.subtree_end(root.a); ++i)
      if (const BvhNode& n = a.nodes[std::size_t(i)]; !n.is_leaf())
        split(Side{n.left, la.home[std::size_t(n.left)]}, Side{n.right, la.home[std::size_t(n.right)]});
    return front;
  }
  // Self nodes from the top, in pre-order: small enough, a seed; else (L, R) split as above, then L and R.
  std::vector<Index> selfs{root.a};
  while (!selfs.empty()) {
    const Index i = selfs.back();
    selfs.pop_back();
    const BvhNode& n = a.nodes[std::size_t(i)];
    if (n.is_leaf()) continue;
    const double c = a.leaf_count[std::size_t(i)];
    if (bvtt_rule::self_seed_is_piece(c, max_pairs)) {
      add(la.home[std::size_t(i)], la.home[std::size_t(i)]);
      continue;
    }
    split(Side{n.left, la.home[std::size_t(n.left)]}, Side{n.right, la.home[std::size_t(n.right)]});
    selfs.push_back(n.right);
    selfs.push_back(n.left);
  }
  return front;
}

void append_wide_front_nodes(const WideLayout& la, const WideLayout& lb, const WideFrontGroup* begin,
                             const WideFrontGroup* end, std::vector<FrontNode>& out) {
  constexpr int W = WideLayout::kWidth;
  for (const WideFrontGroup& g : std::span(begin, end))
    for (unsigned m = g.cut; m; m &= m - 1) {
      const int bit = std::countr_zero(m);
      out.push_back(FrontNode{la.lanes[std::size_t(g.ra)].node[std::size_t(bit / W)],
                              lb.lanes[std::size_t(g.rb)].node[std::size_t(bit % W)], 0});
    }
}

}  // namespace ccdlab
