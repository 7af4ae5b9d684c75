#pragma once
// Shared skeleton of top-down builders: splits ranges of face items until one face per leaf, emitting nodes
// in pre-order. A builder supplies only the split rule.
#include <functional>
#include <span>

#include "framework/hierarchy/bvh.hpp"

namespace ccdlab {

/// One face to place: its box centroid, its id, and where its box is in the build's face_boxes. 32 bytes: the
/// splits move items around (median selection moves each item a few times per level), so an item stays small
/// and points at its box instead of carrying it.
struct BuildItem {
  Vec3 centroid;
  Index face;
  Index box;  ///< index into face_boxes
};
static_assert(sizeof(BuildItem) == 32);

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

/// The split shared by the builders: the median of the centroids along `axis`, ties broken by face id (so the
/// tree does not depend on the selection algorithm); returns items.size() / 2.
std::size_t median_split(std::span<BuildItem> items, int axis);

/// Bounding box of the items' centroids.
Box3 centroid_bounds(std::span<const BuildItem> items);

}  // namespace ccdlab
