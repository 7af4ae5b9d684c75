#pragma once
// The 4-wide view of a binary BVH: every inner node lists its (up to) four grandchildren —
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
#include <algorithm>
#include <array>
#include <limits>
#include <vector>

#include "framework/hierarchy/bvh.hpp"
#include "framework/swept/end_boxes.hpp"
#include "framework/util/uninitialized_vector.hpp"

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace ccdlab {

/// bv.width when a config does not say: the 4-wide view. With 512-bit vectors its lane-pair walk is well ahead of the
/// binary walk; with SSE2 it costs about what the binary walk does (docs/wide-bvh.md). `bv.width: 2` is the binary BVTT.
inline constexpr int kDefaultBvhWidth = 4;
/// The widths a traversal can read: the one rule every config, CLI flag and binding checks bv.width against.
inline constexpr bool is_bvh_width(int w) { return w == 2 || w == 4; }
inline constexpr const char* kBvhWidths = "2 (binary) or 4 (wide)";

struct WideLayout {
  static constexpr int kWidth = 4;
  /// The slot of an empty lane (a wide node of 2 or 3 lanes pads the rest).
  static constexpr Index kNoSlot = std::numeric_limits<Index>::min();
  /// What a traversal reads of a wide node's lanes, copied into its record (WideBounds): their slots (see
  /// `slot`; kNoSlot pads), so a traversal that pushes a lane knows where to continue, or which face it holds,
  /// without reading the binary node; and a leaf lane's face's vertices, vert[corner][lane] (the lane-pair walk
  /// tests adjacency in SIMD; other lanes hold negative ids).
  struct LaneIds {
    std::array<Index, kWidth> slot;
    std::array<std::array<Index, kWidth>, 3> vert;
  };
  /// One wide node's lanes: the above and their node ids (−1 pads), which only the refit reads.
  struct Lanes : LaneIds {
    std::array<Index, kWidth> node;
  };
  // The arrays are large and cut on a run's first step: in huge pages (UninitializedVector), where their first
  // touches cost one fault per 2 MiB instead of one per 4 KiB.
  std::uint64_t version = ~0ull;  ///< the topology version it was cut from
  UninitializedVector<Index> slot;  ///< per node: its wide node, or ~face (< 0) for a leaf
  /// Per wide node: the grandchildren (a leaf child stands for itself). One more record follows the inner
  /// nodes' (index `top()`): the root and its children, never opened, so that every node is some record's lane.
  UninitializedVector<Lanes> lanes;
  /// Per node: a lane that holds it, as record · kWidth + lane. A traversal reads a node's k-DOP there, in a
  /// record it has just opened, instead of in the binary array (where the wide walk's reads missed the cache).
  UninitializedVector<Index> home;
  /// Per wide node: the home of the inner node it belongs to (the node n with slot[n] == r), −1 for the top
  /// record. The wide front (front/wide_front.hpp) prunes a record pair's lane pairs back into their owners' pair,
  /// whose k-DOPs it reads there.
  UninitializedVector<Index> owner_home;

  /// Cuts the layout of `bvh` (every inner node gets a slot, in node order); `faces` are the mesh's (the leaves'
  /// vertex ids).
  static WideLayout of(const BvhTopology& bvh, const std::vector<Face>& faces);
  /// The record of the root and its children (lanes.size() − 1); only their homes point into it.
  [[nodiscard]] Index top() const { return Index(lanes.size()) - 1; }
  [[nodiscard]] std::size_t memory_bytes() const {
    return (slot.size() + home.size() + owner_home.size()) * sizeof(Index) + lanes.size() * sizeof(Lanes);
  }
};

/// One wide node as a traversal reads it: the lanes' bounds, lo[axis][lane] and hi[axis][lane], followed by a copy
/// of their LaneIds, so that a visit touches one contiguous record (352 bytes at K = 18, 5.5 cache lines). The
/// node ids, which only the refit reads, stay in the layout.
template <class BV>
struct alignas(32) WideBounds {
  using Volume = BV;
  static constexpr int kAxes = BV::num_axes;
  float lo[kAxes][WideLayout::kWidth];
  float hi[kAxes][WideLayout::kWidth];
  WideLayout::LaneIds lanes;
};
static_assert(sizeof(WideBounds<KDop<18>>) == 352, "bounds and lane ids, no padding");

/// Lane j of a record, read as a k-DOP: the other side of a wide visit (overlapping_lanes' query).
template <class BV>
struct WideLane {
  const WideBounds<BV>* record;
  int j;
  [[nodiscard]] float min(int i) const { return record->lo[i][j]; }
  [[nodiscard]] float max(int i) const { return record->hi[i][j]; }
};

template <class BV>
using WideBvs = UnconstructedVector<WideBounds<BV>>;  // large: in huge pages, not value-initialized

/// A wide record's lanes' EndBoxes (end_boxes.hpp), lo[frame][axis][lane]: x, y, z only. Empty lanes hold the
/// empty boxes (apart from everything; the k-DOP test drops them anyway).
struct alignas(64) WideEnds {
  float lo[2][3][WideLayout::kWidth], hi[2][3][WideLayout::kWidth];
};
using WideEndsArray = UnconstructedVector<WideEnds>;

/// Copies the EndBoxes of wide node w's lanes into its WideEnds (empty lanes: lo = +inf, hi = −inf).
inline void refit_wide_ends(const WideLayout& layout, const UnconstructedVector<EndBoxes>& ends, Index w, WideEnds& out) {
  static const EndBoxes empty = EndBoxes::empty();
  const EndBoxes* lane[WideLayout::kWidth];
  for (int j = 0; j < WideLayout::kWidth; ++j) {
    const Index c = layout.lanes[w].node[j];
    lane[j] = c >= 0 ? &ends[c] : &empty;
  }
  for (int f = 0; f < 2; ++f) {
#if defined(__SSE2__)
    const auto transpose = [&](auto bound, float (*dst)[WideLayout::kWidth]) {
      __m128 r0 = _mm_load_ps(bound(*lane[0])), r1 = _mm_load_ps(bound(*lane[1])), r2 = _mm_load_ps(bound(*lane[2])),
             r3 = _mm_load_ps(bound(*lane[3]));
      _MM_TRANSPOSE4_PS(r0, r1, r2, r3);
      _mm_store_ps(dst[0], r0), _mm_store_ps(dst[1], r1), _mm_store_ps(dst[2], r2);
    };
    transpose([f](const EndBoxes& e) { return e.lo[f]; }, out.lo[f]);
    transpose([f](const EndBoxes& e) { return e.hi[f]; }, out.hi[f]);
#else
    for (int c = 0; c < 3; ++c)
      for (int j = 0; j < WideLayout::kWidth; ++j) out.lo[f][c][j] = lane[j]->lo[f][c], out.hi[f][c][j] = lane[j]->hi[f][c];
#endif
  }
}

/// Copies the binary volumes of wide node w's lanes into its bounds, once they are refit. (Its LaneIds change
/// only with the topology: the refit copies them when it cuts the layout.) Empty lanes take the empty k-DOP.
template <class BV>
void refit_wide_bounds(const WideLayout& layout, const BvArray<BV>& bvs, Index w, WideBounds<BV>& out) {
  static const BV empty;
  const BV* lane[WideLayout::kWidth];
  for (int j = 0; j < WideLayout::kWidth; ++j) {
    const Index c = layout.lanes[w].node[j];
    lane[j] = c >= 0 ? &bvs[c] : &empty;
  }
  int i = 0;
#if defined(__SSE2__)
  // Four axes × four lanes per 4 × 4 transpose: a branch-free copy, scalar only for the last num_axes % 4.
  for (; i + 4 <= BV::num_axes; i += 4) {
    const auto transpose = [&](auto bound, float (*dst)[WideLayout::kWidth]) {
      __m128 r0 = _mm_loadu_ps(bound(*lane[0]) + i), r1 = _mm_loadu_ps(bound(*lane[1]) + i),
             r2 = _mm_loadu_ps(bound(*lane[2]) + i), r3 = _mm_loadu_ps(bound(*lane[3]) + i);
      _MM_TRANSPOSE4_PS(r0, r1, r2, r3);
      _mm_storeu_ps(dst[i], r0), _mm_storeu_ps(dst[i + 1], r1), _mm_storeu_ps(dst[i + 2], r2), _mm_storeu_ps(dst[i + 3], r3);
    };
    transpose([](const BV& v) { return v.mins(); }, out.lo);
    transpose([](const BV& v) { return v.maxs(); }, out.hi);
  }
#endif
  for (; i < BV::num_axes; ++i)
    for (int j = 0; j < WideLayout::kWidth; ++j) {
      out.lo[i][j] = lane[j]->min(i);
      out.hi[i][j] = lane[j]->max(i);
    }
}

}  // namespace ccdlab
