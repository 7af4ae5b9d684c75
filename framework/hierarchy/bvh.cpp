#include "framework/hierarchy/bvh.hpp"

#include <algorithm>
#include <atomic>

#include "framework/util/error.hpp"

namespace ccdlab {

std::uint64_t next_topology_version() {
  static std::atomic<std::uint64_t> counter{0};
  return counter.fetch_add(1, std::memory_order_relaxed);
}

const RefitPlan& BvhTopology::refit_plan() const {
  if (plan_.version == version) return plan_;
  plan_ = RefitPlan{};
  plan_.version = version;
  if (nodes.empty()) return plan_;
  // Open nodes level by level until the level holds kSubtrees nodes (or only leaves).
  std::vector<Index> level{0};
  while (level.size() < RefitPlan::kSubtrees) {
    std::vector<Index> next;
    for (Index n : level) {
      const BvhNode& node = nodes[n];
      if (node.is_leaf()) {
        next.push_back(n);
      } else {
        plan_.top.push_back(n);
        next.push_back(node.left);
        next.push_back(node.right);
      }
    }
    if (next.size() == level.size()) break;  // all leaves
    level = std::move(next);
  }
  plan_.subtrees = std::move(level);
  std::sort(plan_.top.rbegin(), plan_.top.rend());
  return plan_;
}

void compute_leaf_counts(BvhTopology& bvh) {
  bvh.leaf_count.assign(bvh.nodes.size(), 1);
  for (Index i = bvh.size() - 1; i >= 0; --i) {
    const BvhNode& n = bvh.nodes[i];
    if (!n.is_leaf()) bvh.leaf_count[i] = bvh.leaf_count[n.left] + bvh.leaf_count[n.right];
  }
}

void validate_bvh(const BvhTopology& bvh, std::span<const Index> faces) {
  if (faces.empty()) {
    if (!bvh.nodes.empty()) fail("bvh: non-empty tree over no faces");
    return;
  }
  if (bvh.size() != 2 * Index(faces.size()) - 1)
    fail("bvh: {} nodes for {} faces, expected {}", bvh.size(), faces.size(), 2 * faces.size() - 1);
  std::vector<int> seen_face;
  Index max_face = 0;
  for (Index f : faces) max_face = std::max(max_face, f);
  seen_face.assign(max_face + 1, 0);
  if (bvh.nodes[0].parent != -1) fail("bvh: root has a parent");
  for (Index i = 0; i < bvh.size(); ++i) {
    const BvhNode& n = bvh.nodes[i];
    if (n.is_leaf()) {
      if (n.right != -1 || n.face < 0 || n.face > max_face) fail("bvh: leaf {} malformed", i);
      ++seen_face[n.face];
    } else {
      if (n.left <= i || n.right <= i || n.left >= bvh.size() || n.right >= bvh.size())
        fail("bvh: node {} children {} {} not after it (pre-order)", i, n.left, n.right);
      if (bvh.nodes[n.left].parent != i || bvh.nodes[n.right].parent != i)
        fail("bvh: node {} children do not point back", i);
    }
  }
  for (Index f : faces)
    if (seen_face[f] != 1) fail("bvh: face {} appears in {} leaves", f, seen_face[f]);
}

void replace_subtree(BvhTopology& bvh, Index root, const BvhTopology& sub) {
  const Index size = bvh.subtree_end(root) - root;
  if (sub.size() != size) fail("bvh: replacement sub-tree has {} nodes, expected {}", sub.size(), size);
  const Index parent = bvh.nodes[root].parent;
  for (Index i = 0; i < size; ++i) {
    BvhNode n = sub.nodes[i];
    if (!n.is_leaf()) n.left += root, n.right += root;
    n.parent = i == 0 ? parent : n.parent + root;
    bvh.nodes[root + i] = n;
    bvh.leaf_count[root + i] = sub.leaf_count[i];
  }
  bvh.version = next_topology_version();
}

std::vector<Index> subtree_faces(const BvhTopology& bvh, Index root) {
  std::vector<Index> faces;
  for (Index i = root; i < bvh.subtree_end(root); ++i)
    if (bvh.nodes[i].is_leaf()) faces.push_back(bvh.nodes[i].face);
  return faces;
}

}  // namespace ccdlab

#include "framework/hierarchy/wide_bvh.hpp"

namespace ccdlab {

WideLayout WideLayout::of(const BvhTopology& bvh, const std::vector<Face>& faces) {
  WideLayout w;
  w.version = bvh.version;
  w.slot.assign(bvh.nodes.size(), -1);
  Index inner = 0;
  for (Index i = 0; i < bvh.size(); ++i) w.slot[i] = bvh.nodes[i].is_leaf() ? ~bvh.nodes[i].face : inner++;
  w.lanes.reserve(std::size_t(inner));
  std::vector<Index> owner;
  owner.reserve(std::size_t(inner) + 1);
  for (Index i = 0; i < bvh.size(); ++i) {
    const BvhNode& n = bvh.nodes[i];
    if (n.is_leaf()) continue;
    owner.push_back(i);
    Lanes l;
    l.node.fill(-1);
    l.slot.fill(kNoSlot);
    int k = 0;
    const auto add = [&](Index c) {
      l.node[k] = c;
      l.slot[k++] = w.slot[c];
    };
    for (Index c : {n.left, n.right}) {
      const BvhNode& cn = bvh.nodes[c];
      if (cn.is_leaf()) {
        add(c);
      } else {
        add(cn.left);
        add(cn.right);
      }
    }
    w.lanes.push_back(l);
  }
  if (bvh.size() > 0) {
    Lanes top{};
    top.node.fill(-1);
    top.slot.fill(kNoSlot);
    top.node[0] = 0;
    if (!bvh.nodes[0].is_leaf()) top.node[1] = bvh.nodes[0].left, top.node[2] = bvh.nodes[0].right;
    for (int j = 0; j < kWidth; ++j)
      if (top.node[j] >= 0) top.slot[j] = w.slot[top.node[j]];
    w.lanes.push_back(top);
    owner.push_back(-1);
  }
  for (Lanes& l : w.lanes)
    for (int j = 0; j < kWidth; ++j)
      for (int p = 0; p < 3; ++p)
        l.vert[p][j] = l.node[j] >= 0 && l.slot[j] < 0 ? faces[std::size_t(~l.slot[j])][std::size_t(p)] : -1;
  w.home.assign(bvh.nodes.size(), -1);
  for (Index r = 0; r < Index(w.lanes.size()); ++r)
    for (int j = 0; j < kWidth; ++j) {
      const Index c = w.lanes[r].node[j];
      if (c >= 0 && w.home[c] < 0) w.home[c] = r * kWidth + j;
    }
  w.owner_home.resize(owner.size());
  for (std::size_t r = 0; r < owner.size(); ++r) w.owner_home[r] = owner[r] >= 0 ? w.home[std::size_t(owner[r])] : -1;
  return w;
}

}  // namespace ccdlab
