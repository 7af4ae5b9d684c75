#pragma once
// Stage 3 of the batched narrow phase: the plane test again, on halves, then sixteenths of the step, with the
// features' boxes; SIMD over the rows stage 2 kept (Highway, like plane_filter.cpp).
// A pair that reaches it has a coplanarity cubic f that may vanish somewhere in [0, 1]. Most such pairs are
// features whose planes cross while they are far apart: the vertex passes the face's plane beside the face, the
// edges' lines cross beyond their ends. On each window [k/n, (k+1)/n] (n = 2, then 16):
//   - f's Bernstein coefficients there (de Casteljau halvings of the whole-step ones) may all keep one sign
//     beyond stage 2's threshold plus the rounding of the halvings, or
//   - the two features' boxes over the window may be apart by more than the reach on some axis. The boxes are
//     taken in the frame of the pair's first point (f0 for VF, a0 for EE) — the vectors A, B, C of stage 2 —
//     where the relative motion is still linear, so a feature stays between its positions at the window's ends.
// Either proves that no contact within the reach happens in that window; when all n are proven, the pair is
// dropped. (The finest windows cull at least what coarser ones would: sub-window coefficients are convex
// combinations, sub-window boxes are inside; so halves first only saves work.) Rounding (bounds for four halvings,
// used at any depth): positions at t are padded by 32u·M (M = the largest
// coordinate of A, B, C), the division of b1, b2 by 3 and the halvings by 18u·max|b|, on top of stage 2's bound.
#include <cstdint>

#include "framework/narrow/plane_filter.hpp"

namespace ccdlab {

/// 2^levels windows: sixteenths for the final word; halves first, as a cheap pass that settles most pairs at a
/// fraction of the sixteenths' cost (docs/appendix-narrow-phase.md); the sixteenths then see only the rest. Only these two
/// are compiled.
constexpr int kSplitLevels = 4;
constexpr int kSplitCoarseLevels = 1;

/// Rows [begin, end) of `plane`, all VF (`vf`) or all EE, filled by plane_filter: keep[i] = 0 for rows proven
/// apart on every one of the 2^levels windows, untouched otherwise; with `open`, open[i] = the windows not
/// proven (bit w: window w), what stage 4 (window_distance_filter.hpp) looks at. Runs on the best SIMD target of this CPU.
/// `halves` (sixteenths only, with `open`; may be `open` itself): the open bits the halves pass left for each
/// row. The sixteenths of a half it proved stay closed (a proof for a window holds on every part of it), and a
/// vector whose rows each have one open half computes that half's eight windows only (most rows that
/// reach the sixteenths have one open half).
void split_filter(const PlaneBatch& plane, std::size_t begin, std::size_t end, bool vf, std::uint8_t* keep,
                  int levels = kSplitLevels, std::uint16_t* open = nullptr, const std::uint16_t* halves = nullptr);

/// The same test for one row, plain C++: the reference the SIMD targets are checked against. _open gives the
/// windows not proven, _keeps whether there is one; with the halves pass's bits `halves` (1 or 2: one open
/// half), the sixteenths of the other half are closed.
[[nodiscard]] std::uint16_t split_filter_open(const PlaneBatch& plane, std::size_t row, bool vf, int levels = kSplitLevels);
[[nodiscard]] std::uint16_t split_filter_open(const PlaneBatch& plane, std::size_t row, bool vf, int levels,
                                              std::uint16_t halves);
[[nodiscard]] bool split_filter_keeps(const PlaneBatch& plane, std::size_t row, bool vf, int levels = kSplitLevels);

}  // namespace ccdlab
