#include "framework/hierarchy/topdown_build.hpp"

#include <utility>

namespace ccdlab {

BvhTopology build_top_down(std::span<const Index> faces, std::span<const Box3> face_boxes, const SplitRule& split) {
  BvhTopology bvh;
  if (faces.empty()) return bvh;
  std::vector<BuildItem> items(faces.size());
  for (std::size_t i = 0; i < faces.size(); ++i) items[i] = {faces[i], face_boxes[i], face_boxes[i].center()};
  bvh.nodes.reserve(2 * faces.size() - 1);

  struct Task {
    std::size_t begin, end;
    Index parent;
    bool is_right;
  };
  std::vector<Task> stack{{0, items.size(), -1, false}};
  while (!stack.empty()) {
    Task t = stack.back();
    stack.pop_back();
    Index id = bvh.size();
    bvh.nodes.push_back(BvhNode{});
    bvh.nodes[id].parent = t.parent;
    if (t.parent >= 0) (t.is_right ? bvh.nodes[t.parent].right : bvh.nodes[t.parent].left) = id;
    if (t.end - t.begin == 1) {
      bvh.nodes[id].face = items[t.begin].face;
      continue;
    }
    std::size_t mid = t.begin + split(std::span<BuildItem>(items.data() + t.begin, t.end - t.begin));
    // Right pushed first so the left subtree is emitted next: pre-order.
    stack.push_back({mid, t.end, id, true});
    stack.push_back({t.begin, mid, id, false});
  }
  compute_leaf_counts(bvh);
  return bvh;
}

}  // namespace ccdlab
