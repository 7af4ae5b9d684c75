#pragma once
// Stage 4 of the batched narrow phase: the features' distance on the windows stage 3 left open.
// A pair that reaches it may have f = 0 in a window [w/16, (w+1)/16] where the features' boxes overlap: the
// planes (lines) meet there while the features are near. Most such pairs still never touch: edges whose lines
// cross beyond their ends, a vertex passing a face's plane beside it (docs/appendix-narrow-phase.md, "Stage 4").
//
// In stage 2's moving frame the relative motion is linear, and every point of a feature moves with a convex
// combination of its corners' velocities, so the distance d(t) between the features changes no faster than
//     S = the largest relative speed of two corners, one from each feature   (the norm is convex),
// and on a window with middle m and half-width h, d(t) ≥ d(m) − S·h. A lower bound of d(m) is the gap of the
// features along any direction v, the smallest projection of one minus the largest of the other, over |v|
// (|x − y| ≥ v·(x − y)/|v|). Nothing is assumed about v: a poor one only weakens the bound. The bound taken is
// the largest gap over a few directions, one of which joins the features' closest points whatever they are
// (Ericson, "Real-Time Collision Detection", §5.1.5 and §5.1.9):
//   VF (vertex a, face {0, b, c}): ±(b × c), the face's normal (closest point inside the face), and a minus its
//       closest point on each of the three edges (closest point on an edge or a corner);
//   EE (edge {0, b}, edge {a, a + c}): ±(b × c), the lines' common normal (both closest points inside), and each
//       of the four endpoints against the other edge (a closest point at an endpoint).
// So the bound is the distance itself up to rounding, with no branch: all lanes of a vector run the same
// operations, where a plain closest-point query per window branches on which feature is closest.
// A zero direction (parallel edges, a degenerate face) just offers no bound. When gap − S·h exceeds the
// reach, no contact is possible in the window; when every open window is proven, the pair is dropped.
// The gap n/|v| > need is decided as n > 0 and n² > need²·|v|², without a square root or a division per
// direction (they cost more than the rest of the test).
// Rounding: positions at m, the projections and the columns' own rounding are covered by 128u·M (M = the
// largest coordinate, as in stage 3), the speed and the reach by a factor 1 + 10⁻¹²; the squared comparison's own
// few ulps, relative, by both margins.
#include <cstdint>

#include "framework/narrow/plane_filter.hpp"
#include "framework/util/uninitialized_vector.hpp"

namespace ccdlab {

/// Stage 4's working memory: one item per undecided row and round (its window's middle, whether it was proven,
/// its open windows not yet tested); reused from batch to batch.
struct WindowDistanceItems {
  UninitializedVector<std::int64_t> row;
  UninitializedVector<double> time;  ///< the window's middle
  UninitializedVector<std::uint8_t> proven;
  UninitializedVector<std::uint16_t> left;
};

/// Rows [0, rows) of `plane` (filled by plane_filter; rows below `vf_rows` are VF, the others EE), each with
/// `open[i]` = the windows of 2^levels that stage 3 did not prove (split_filter): for every row whose keep[i] is
/// set, keep[i] = whether one of its open windows may still hold a contact within the reach. SIMD over the
/// (row, window) items, on the best target of this CPU.
void window_distance_filter(const PlaneBatch& plane, std::size_t vf_rows, std::size_t rows, const std::uint16_t* open,
                      int levels, std::uint8_t* keep, WindowDistanceItems& items);

/// The same test for one row, plain C++: the reference the SIMD targets are checked against.
[[nodiscard]] bool window_distance_filter_keeps(const PlaneBatch& plane, std::size_t row, bool vf, std::uint16_t open,
                                          int levels);

}  // namespace ccdlab
