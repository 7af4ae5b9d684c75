#pragma once
// Flat BVH storage. The topology (which node is whose child) is built once, top-down, by a HierarchyBuilder;
// the bounding volumes are refit bottom-up every step (cloth topology never changes; paper §2).
//
// Layout: nodes[0] is the root; nodes are in pre-order, so every child has a larger index than its parent
// and a reverse sweep over the array is a valid bottom-up order. One triangle per leaf. Bounding volumes live
// in a separate array (structure of arrays) indexed like the nodes, so the topology is shared by every K.
#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

#include "framework/geometry/kdop.hpp"
#include "framework/geometry/vec.hpp"
#include "framework/mesh/tri_mesh.hpp"

namespace ccdlab {

struct BvhNode {
  Index left = -1;   ///< child index, -1 for a leaf
  Index right = -1;  ///< child index, -1 for a leaf
  Index parent = -1; ///< -1 for the root
  Index face = -1;   ///< mesh face id of a leaf, -1 for an inner node
  [[nodiscard]] bool is_leaf() const { return left < 0; }
};
static_assert(sizeof(BvhNode) == 16, "BvhNode is 4 indices; keep it compact for traversal");

struct BvhTopology {
  std::vector<BvhNode> nodes;  ///< pre-order, nodes[0] = root; 2·leaves − 1 nodes
  std::vector<Index> leaf_count;  ///< number of leaves under each node
  std::uint64_t version = 0;      ///< bumped whenever the topology changes (adaptive restructuring)

  [[nodiscard]] Index size() const { return Index(nodes.size()); }
  [[nodiscard]] Index num_leaves() const { return (size() + 1) / 2; }
  [[nodiscard]] std::size_t memory_bytes() const { return nodes.size() * (sizeof(BvhNode) + sizeof(Index)); }
};

/// Builds the tree topology over a set of faces from their bounding boxes (one per face, in the order of
/// `faces`). Implementations: strategies/builders/.
class HierarchyBuilder {
 public:
  virtual ~HierarchyBuilder() = default;
  [[nodiscard]] virtual std::string_view name() const = 0;
  [[nodiscard]] virtual BvhTopology build(std::span<const Index> faces, std::span<const Box3> face_boxes) const = 0;
};

/// Checks the structural invariants (pre-order, parent links, every face in exactly one leaf); throws Error.
void validate_bvh(const BvhTopology& bvh, std::span<const Index> faces);

/// Fills leaf_count bottom-up from the node links.
void compute_leaf_counts(BvhTopology& bvh);

/// Replaces the sub-tree rooted at `root` by `sub` (a tree over the same faces, pre-order from 0): a pre-order
/// sub-tree is the contiguous range [root, root + 2·leaves − 1), so every node outside keeps its id.
void replace_subtree(BvhTopology& bvh, Index root, const BvhTopology& sub);

/// Faces under a node (pre-order range scan).
std::vector<Index> subtree_faces(const BvhTopology& bvh, Index root);

/// Bottom-up refit: leaves take leaf_bv(face), inner nodes the merge of their children.
template <class BV, class LeafBv>
void refit(const BvhTopology& bvh, std::vector<BV>& bvs, LeafBv&& leaf_bv) {
  bvs.resize(bvh.nodes.size());
  for (Index i = bvh.size() - 1; i >= 0; --i) {
    const BvhNode& n = bvh.nodes[i];
    if (n.is_leaf()) {
      bvs[i] = leaf_bv(n.face);
    } else {
      bvs[i] = bvs[n.left];
      bvs[i].merge(bvs[n.right]);
    }
  }
}

}  // namespace ccdlab
