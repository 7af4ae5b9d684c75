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
/// [begin, mid), the right child [mid, end). Called concurrently on disjoint ranges: no shared state.
using SplitRule = std::function<std::size_t(std::span<BuildItem> items)>;

/// The tree is the same for any exec.threads: a range's node id follows from the split alone (pre-order: the
/// left child is id + 1, the right child id + 2·(mid − begin), after the left sub-tree's 2·(mid − begin) − 1
/// nodes). The top splits run level by level, the ranges of a level in parallel, until ranges hold at most
/// 2,048 faces (or 1/256 of the tree; independent of the thread count, so the task trace is too); those
/// ranges are then built as whole sub-trees in parallel.
BvhTopology build_top_down(std::span<const Index> faces, std::span<const Box3> face_boxes, BuildExecution exec,
                           const SplitRule& split);

}  // namespace ccdlab
