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
#include <type_traits>
#include <vector>

#include "framework/geometry/kdop.hpp"
#include "framework/geometry/vec.hpp"
#include "framework/mesh/tri_mesh.hpp"
#include "framework/util/parallel.hpp"
#include "framework/util/uninitialized_vector.hpp"

namespace ccdlab {

/// The bounding volumes of a hierarchy's nodes (or of a mesh's faces), indexed like them. Refit and the swept
/// volumes assign every element, so growing the array constructs nothing (an empty k-DOP per element, written
/// on one thread, would cost more than the parallel refit that overwrites it).
template <class BV>
using BvArray = UnconstructedVector<BV>;

struct BvhNode {
  Index left = -1;   ///< child index, -1 for a leaf
  Index right = -1;  ///< child index, -1 for a leaf
  Index parent = -1; ///< -1 for the root
  Index face = -1;   ///< mesh face id of a leaf, -1 for an inner node
  [[nodiscard]] bool is_leaf() const { return left < 0; }
};
static_assert(sizeof(BvhNode) == 16, "BvhNode is 4 indices; keep it compact for traversal");

/// A new topology version, never handed out before (process-wide): two different trees never share one, so
/// "same version" means "same tree" for everything cached per topology (refit plan, normal cones, fronts).
std::uint64_t next_topology_version();

/// How a refit sweeps the tree in parallel: disjoint sub-trees, each a contiguous pre-order range refit by one
/// backward sweep (in parallel), then the few nodes above them, bottom-up. The cut is a fixed number of
/// sub-trees whatever the thread count, so the work (and its trace) does not depend on it.
struct RefitPlan {
  static constexpr std::size_t kSubtrees = 256;
  std::uint64_t version = ~0ull;  ///< the topology version it was cut from
  std::vector<Index> subtrees;    ///< disjoint sub-tree roots (leaves where the tree is shallow)
  std::vector<Index> top;         ///< every inner node above the cut, in decreasing index order (bottom-up)
};

struct BvhTopology {
  UninitializedVector<BvhNode> nodes;  ///< pre-order, nodes[0] = root; 2·leaves − 1 nodes (large: huge pages)
  UninitializedVector<Index> leaf_count;  ///< number of leaves under each node
  /// Changes with every change of `nodes` (a build, replace_subtree): write nodes only through those two.
  std::uint64_t version = next_topology_version();

  [[nodiscard]] Index size() const { return Index(nodes.size()); }
  [[nodiscard]] Index num_leaves() const { return (size() + 1) / 2; }
  /// One past the last node of the sub-tree rooted at r: a pre-order sub-tree is [r, r + 2·leaves(r) − 1).
  [[nodiscard]] Index subtree_end(Index r) const { return r + 2 * leaf_count[r] - 1; }
  [[nodiscard]] std::size_t memory_bytes() const { return nodes.size() * (sizeof(BvhNode) + sizeof(Index)); }

  /// The refit plan of the current topology: cut again on the first call after the version changed, so a
  /// plan never outlives the tree it was cut from (a stale cut refits the wrong ranges and loses contacts).
  /// Not thread-safe on that first call: call it from the pipeline's thread, outside parallel regions.
  [[nodiscard]] const RefitPlan& refit_plan() const;

 private:
  mutable RefitPlan plan_;
};

/// How a build may run: threads for the sub-trees below the top splits, and where to record their costs. The
/// tree never depends on it.
struct BuildExecution {
  int threads = 1;
  PhaseTrace* trace = nullptr;
};

/// Builds the tree topology over a set of faces from their bounding boxes (one per face, in the order of
/// `faces`). Implementations: strategies/builders/.
class HierarchyBuilder {
 public:
  virtual ~HierarchyBuilder() = default;
  [[nodiscard]] virtual std::string_view name() const = 0;
  [[nodiscard]] virtual BvhTopology build(std::span<const Index> faces, std::span<const Box3> face_boxes,
                                          BuildExecution exec = {}) const = 0;
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

/// The leaf_bv of a refit whose leaves hold their volumes already (the pipeline writes the swept volumes of the
/// faces straight into the leaves, so that they are not stored twice): only inner nodes are refit.
struct LeavesInPlace {};

/// Refits node i from its children (inner node) or from leaf_bv(face) (leaf; kept as it is for LeavesInPlace).
template <class BV, class LeafBv>
void refit_node(const BvhTopology& bvh, BvArray<BV>& bvs, Index i, LeafBv&& leaf_bv) {
  const BvhNode& n = bvh.nodes[i];
  if (n.is_leaf()) {
    if constexpr (!std::is_same_v<std::remove_cvref_t<LeafBv>, LeavesInPlace>) bvs[i] = leaf_bv(n.face);
  } else {
    // Merged in a local: written into bvs[i] directly, the compiler must assume bvs[i] may alias bvs[n.right]
    // and stores each axis before reading the next (scalar min/max, one store per axis).
    BV merged = bvs[n.left];
    merged.merge(bvs[n.right]);
    bvs[i] = merged;
  }
}

/// Refits the sub-tree rooted at r (a backward sweep of its pre-order range).
template <class BV, class LeafBv>
void refit_subtree(const BvhTopology& bvh, BvArray<BV>& bvs, Index r, LeafBv&& leaf_bv) {
  for (Index i = bvh.subtree_end(r) - 1; i >= r; --i) refit_node(bvh, bvs, i, leaf_bv);
}

/// Serial bottom-up refit of the whole tree: leaves take leaf_bv(face), inner nodes the merge of their children.
template <class BV, class LeafBv>
void refit(const BvhTopology& bvh, BvArray<BV>& bvs, LeafBv&& leaf_bv) {
  bvs.resize(bvh.nodes.size());
  if (!bvh.nodes.empty()) refit_subtree(bvh, bvs, 0, leaf_bv);
}

}  // namespace ccdlab
