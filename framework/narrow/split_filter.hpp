#pragma once
// Stage 3 of the batched narrow phase: the plane test again, on sixteenths of the step, with the features'
// boxes; SIMD over the rows stage 2 kept (Highway, like plane_filter.cpp).
// A pair that reaches it has a coplanarity cubic f that may vanish somewhere in [0, 1]. Most such pairs are
// features whose planes cross while they are far apart: the vertex passes the face's plane beside the face, the
// edges' lines cross beyond their ends. On each window [k/16, (k+1)/16]:
//   - f's Bernstein coefficients there (four de Casteljau halvings of the whole-step ones) may all keep one sign
//     beyond stage 2's threshold plus the rounding of the halvings, or
//   - the two features' boxes over the window may be apart by more than the reach on some axis. The boxes are
//     taken in the frame of the pair's first point (f0 for VF, a0 for EE) — the vectors A, B, C of stage 2 —
//     where the relative motion is still linear, so a feature stays between its positions at the window's ends.
// Either proves that no contact within the reach happens in that window; when all sixteen are proven, the pair is
// dropped. (Testing only the finest windows culls at least what coarser ones would: sub-window coefficients are
// convex combinations, sub-window boxes are inside.) Rounding: positions at t are padded by 32u·M (M = the largest
// coordinate of A, B, C), the division of b1, b2 by 3 and the halvings by 18u·max|b|, on top of stage 2's bound.
#include <cstdint>

#include "framework/narrow/plane_filter.hpp"

namespace ccdlab {

/// Rows [begin, end) of `plane`, all VF (`vf`) or all EE, filled by plane_filter: keep[i] = 0 for rows proven
/// apart, untouched otherwise. Runs on the best SIMD target of this CPU.
void split_filter(const PlaneBatch& plane, std::size_t begin, std::size_t end, bool vf, std::uint8_t* keep);

/// The same test for one row, plain C++: the reference the SIMD targets are checked against.
[[nodiscard]] bool split_filter_keeps(const PlaneBatch& plane, std::size_t row, bool vf);

}  // namespace ccdlab
