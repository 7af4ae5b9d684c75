#pragma once
// Stage 3 of the batched narrow phase: the plane test again, on parts of the step, with the features' boxes.
// A pair that reaches it has a coplanarity cubic f that may vanish somewhere in [0, 1] (stage 2 could not
// rule it out). Most such pairs are features whose planes cross while they are far apart: the vertex passes
// the face's plane beside the face, the edges' lines cross beyond their ends. The step is halved recursively
// (down to 1/16) and on each window:
//   - f's Bernstein coefficients there (de Casteljau halvings of the whole-step ones) may all keep one sign
//     beyond the threshold of plane_filter.hpp (plus the rounding of the halvings), or
//   - the two features' boxes over the window (a linearly moving point stays between its positions at the
//     window's ends), grown by the reach, may be disjoint on some axis.
// Either proves that no contact within the reach happens in that window, which is then not split further;
// when every window is proven, the pair is dropped. The whole-step coefficients, their threshold and the reach
// come from stage 2. Rounding: positions at t are padded by 8u·M (M = the pair's largest coordinate magnitude),
// the division of b1, b2 by 3 and the halvings by 18u·max|b|, on top of stage 2's bound.
#include <array>

#include "framework/geometry/vec.hpp"
#include "framework/narrow/plane_filter.hpp"

namespace ccdlab {

/// VF: p = (v, f0, f1, f2); EE: p = (a0, a1, b0, b1). `vf` says which. Returns false when proven apart.
/// Row `row` of `plane` holds what stage 2 computed for this pair (coefficients, threshold, reach).
[[nodiscard]] bool split_filter_keeps(bool vf, const std::array<const Vec3*, 4>& p_t0,
                                      const std::array<const Vec3*, 4>& p_t1, const PlaneBatch& plane, std::size_t row);

}  // namespace ccdlab
