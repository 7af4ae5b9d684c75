#include "framework/traversal/front/binary_front.hpp"

#include "framework/traversal/bvtt_rule.hpp"

namespace ccdlab {

std::vector<FrontNode> initial_front(const BvhTopology& a, const BvhTopology& b, bool self, BvttNode root,
                                     double granularity, double min_pairs) {
  std::vector<FrontNode> front;
  if (a.nodes.empty() || b.nodes.empty()) return front;
  const double max_pairs = bvtt_rule::seed_max_pairs(a.num_leaves(), b.num_leaves(), self, granularity, min_pairs);
  std::vector<BvttNode> stack;
  auto split_into_front = [&](BvttNode root) {
    stack.assign(1, root);
    while (!stack.empty()) {
      BvttNode n = stack.back();
      stack.pop_back();
      const double na = a.leaf_count[n.a], nb = b.leaf_count[n.b];
      if (bvtt_rule::seed_is_piece(na, nb, max_pairs)) {
        front.push_back(FrontNode{n.a, n.b, FrontNode::kFresh});
      } else if (bvtt_rule::seed_splits_a(na, nb)) {
        stack.push_back({a.nodes[n.a].right, n.b});
        stack.push_back({a.nodes[n.a].left, n.b});
      } else {
        stack.push_back({n.a, b.nodes[n.b].right});
        stack.push_back({n.a, b.nodes[n.b].left});
      }
    }
  };
  if (!self || root.a != root.b) {
    split_into_front(root);
    return front;
  }
  // A self node: the pair of children of every inner node below it.
  for (Index i = root.a; i < a.subtree_end(root.a); ++i)
    if (const BvhNode& n = a.nodes[i]; !n.is_leaf()) split_into_front({n.left, n.right});
  return front;
}

}  // namespace ccdlab
