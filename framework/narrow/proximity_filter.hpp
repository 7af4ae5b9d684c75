#pragma once
// Stage 4 of the batched narrow phase: the features' distance on the windows stage 3 left open.
// A pair that reaches it may have f = 0 in a window [w/16, (w+1)/16] where the features' boxes overlap: the
// planes (lines) meet there while the features are near. Most such pairs still never touch: edges whose lines
// cross beyond their ends, a vertex passing a face's plane beside it — on rod-twist 32K of the 40K pairs that
// reached the tester after stage 3 (docs/narrow-phase.md, "Stage 4").
//
// In stage 2's moving frame the relative motion is linear, and every point of a feature moves with a convex
// combination of its corners' velocities, so the distance d(t) between the features changes no faster than
//     S = the largest relative speed of two corners, one from each feature   (the norm is convex),
// and on a window with middle m and half-width h, d(t) ≥ d(m) − S·h. A lower bound of d(m) is the gap of the
// features along any unit direction û, the smallest projection of one minus the largest of the other
// (|x − y| ≥ û·(x − y)); û is taken through the closest points geometry/distance.hpp finds, where the gap is the
// distance itself. When gap − S·h exceeds the reach, no contact is possible in the window (nothing is assumed
// about how accurate those closest points are: a poor û only weakens the bound). When every open window is
// proven, the pair is dropped. Rounding: positions at m, the projections and the columns' own rounding are
// covered by 128u·M (M = the largest coordinate, as in stage 3), the speed and the reach by a factor 1 + 10⁻¹².
#include <cstdint>

#include "framework/narrow/plane_filter.hpp"

namespace ccdlab {

/// Row `row` of `plane` (filled by plane_filter; `vf` or EE), with `open` = the windows of 2^levels that stage 3
/// did not prove (split_filter_open): whether one of them may still hold a contact within the reach. Plain C++
/// (one distance per open window, branchy; few rows get here).
[[nodiscard]] bool proximity_filter_keeps(const PlaneBatch& plane, std::size_t row, bool vf, std::uint16_t open,
                                          int levels);

}  // namespace ccdlab
