#pragma once
// The 4-wide view of a binary BVH (issue 9, item 4): every inner node lists its (up to) four grandchildren —
// a child that is a leaf stands for itself — and keeps their k-DOPs side by side, one SIMD lane per child, so a
// traversal tests one k-DOP against all four with a compare per axis instead of walking two levels of the
// binary tree (the collapse of a binary BVH into a 4-ary one, as in Embree's BVH4; Wald et al., "Getting rid
// of packets", 2008).
//
// Exactness: refit makes every parent's k-DOP the exact float union of its children's, so if two leaves'
// k-DOPs overlap then so do those of any two of their ancestors. Skipping the middle level therefore changes
// which BV tests are made, never which leaf pairs become candidates (tests/framework/traversal).
//
// Layout: WideLayout (from the topology, cut once per topology version like the refit plan) gives each inner
// node a slot and its lanes' node ids; WideBvs<BV> (refit every step from the binary volumes) gives each slot
// its lanes' bounds, min and max per axis × 4 lanes. Empty lanes hold an empty k-DOP, which overlaps nothing.
#include <array>
#include <limits>
#include <vector>

#include "framework/hierarchy/bvh.hpp"

namespace ccdlab {

/// bv.width when a config does not say: binary. The 4-wide view pays only on large trees whose volumes miss the
/// cache (n-body 146K triangles, 1 thread: traversal −21%, step −3%) and costs a second refit and ~300 bytes per triangle;
/// on 18K–80K-triangle steps it is even (docs/wide-bvh.md).
inline constexpr int kDefaultBvhWidth = 2;

struct WideLayout {
  static constexpr int kWidth = 4;
  /// One wide node's lanes: node ids (−1 pads) and their slots (see `slot`), so a traversal that pushes a lane
  /// knows where to continue, or which face it holds, without reading the binary node.
  struct Lanes {
    std::array<Index, kWidth> node;
    std::array<Index, kWidth> slot;
  };
  std::uint64_t version = ~0ull;  ///< the topology version it was cut from
  std::vector<Index> slot;        ///< per node: its wide node, or ~face (< 0) for a leaf
  std::vector<Lanes> lanes;       ///< per wide node: the grandchildren (a leaf child stands for itself)

  /// Cuts the layout of `bvh` (every inner node gets a slot, in node order).
  static WideLayout of(const BvhTopology& bvh);
  [[nodiscard]] std::size_t memory_bytes() const {
    return slot.size() * sizeof(Index) + lanes.size() * sizeof(Lanes);
  }
};

/// The lanes' bounds of one wide node: lo[axis][lane], hi[axis][lane].
template <class BV>
struct alignas(16) WideBounds {
  using Volume = BV;
  static constexpr int kAxes = BV::num_axes;
  float lo[kAxes][WideLayout::kWidth];
  float hi[kAxes][WideLayout::kWidth];
};

template <class BV>
using WideBvs = std::vector<WideBounds<BV>>;

/// Copies the binary volumes of wide node w's lanes into its bounds (after the binary refit).
template <class BV>
void refit_wide_node(const WideLayout& layout, const BvArray<BV>& bvs, Index w, WideBounds<BV>& out) {
  for (int j = 0; j < WideLayout::kWidth; ++j) {
    const Index c = layout.lanes[w].node[j];
    for (int i = 0; i < BV::num_axes; ++i) {
      out.lo[i][j] = c >= 0 ? bvs[c].min(i) : std::numeric_limits<float>::infinity();
      out.hi[i][j] = c >= 0 ? bvs[c].max(i) : -std::numeric_limits<float>::infinity();
    }
  }
}

}  // namespace ccdlab
