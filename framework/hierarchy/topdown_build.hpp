#pragma once
// Shared skeleton of top-down builders: splits ranges of face items until one face per leaf, emitting nodes
// in pre-order. A builder supplies only the split rule.
#include <functional>
#include <span>

#include "framework/hierarchy/bvh.hpp"

namespace ccdlab {

/// One face to place: its id, bounding box and box centroid.
struct BuildItem {
  Index face;
  Box3 box;
  Vec3 centroid;
};

/// Reorders items[begin, end) (size ≥ 2) and returns mid with begin < mid < end: the left child gets
/// [begin, mid), the right child [mid, end).
using SplitRule = std::function<std::size_t(std::span<BuildItem> items)>;

BvhTopology build_top_down(std::span<const Index> faces, std::span<const Box3> face_boxes, const SplitRule& split);

}  // namespace ccdlab
