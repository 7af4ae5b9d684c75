#pragma once
// Stage 0 of the batched narrow phase: candidate face pairs proven apart as whole triangles, before their
// feature pairs (up to 15; ~3.6 under the fixed rule) are gathered and culled one by one.
//
// A separating axis in the moving frame of one face. For f = (o, b, c) and g = (p0, p1, p2), every point is
// taken relative to o at its own time: f's points are u·B(t) + v·C(t) (B = b − o, C = c − o, u, v ≥ 0,
// u + v ≤ 1), g's are Σ w_k·A_k(t) (A_k = p_k − o). Under linear motion A, B, C are linear in t, so along any
// axis n the projections of f's points lie in the hull of {0, B0·n, B1·n, C0·n, C1·n} and g's in that of
// {A_k0·n, A_k1·n} at every time of the step (subscripts 0, 1: t0, t1). When the two intervals are farther apart
// than r·|n|, every point of g stays farther than r from every point of f over the whole step: no feature pair
// of (f, g) can be reported by a tester whose reach is r, whatever the representative rule assigned to it.
// The axis is n = B0×C0 + B1×C1, f's normal at both ends (any axis is valid; this one follows a turning face);
// then the same with g's frame and normal. Either suffices.
//
// The reach's relative part uses the twelve points' (both faces, both frames) bounding-box extent in the 1-norm,
// L̄: it bounds the box diagonal of every feature pair's query (CullReach's L), so r is never below any of them.
//
// In float (FloatFrames: the frames moved to the centre of their box, each coordinate within ε of the exact
// translated value). The test runs on the float points, exactly as above, and allows for two things:
// - The float points. Every point of either face at any t is a convex combination of its corners at the two
//   ends, so it lies within ε per coordinate of its float counterpart, and a point taken relative to o within 2ε:
//   each projection moves by at most 2ε‖n‖₁, each interval widens by as much, and the gap by 4ε‖n‖₁. The exact
//   points' L̄ is at most the float points' + 6ε.
// - The rounding (u = 2⁻²⁴). Each difference is one subtraction and n is used as given (any axis is valid), so a
//   projection errs by at most 4u·‖p − o‖∞·‖n‖₁ ≤ 4u·L̄·‖n‖₁.
// A pair is dropped when the gap exceeds ‖n‖₁·(r·s + 16u·L̄ + 8ε) + 10⁻³⁰ with r = abs + rel·(L̄ + 8ε): twice each
// error, the slack s = 1 + 2⁻¹⁸ for the rounding of r, ‖n‖₁ and the gap itself (≥ 10u), and a floor above any
// error of an underflowed product. ‖n‖₁ ≥ |n|. Pairs that share a vertex are never dropped (0 lies in both
// intervals); a non-finite value never drops one (its comparisons are false).
#include <cstdint>
#include <span>

#include "framework/geometry/vec.hpp"
#include "framework/narrow/frame_points.hpp"
#include "framework/mesh/tri_mesh.hpp"
#include "framework/primitive/tester.hpp"
#include "framework/traversal/candidates.hpp"

namespace ccdlab {

/// keep[i] = 0 when candidate i's triangles are proven to stay farther apart than the reach, 1 otherwise. SIMD
/// (Highway, run-time dispatch, as plane_filter); the six corners of a block of candidates are staged in L1,
/// eight at a time where 256-bit vectors exist (one load a corner, both frames), from the step's float frames.
void triangle_filter(std::span<const FacePair> candidates, const Face* faces, const FloatFrames& frames,
                     CullReach reach, std::uint8_t* keep);

/// The same test for one candidate, plain C++: the reference every SIMD target is checked against.
[[nodiscard]] bool triangle_pair_keeps(const Face& f, const Face& g, const FloatFrames& frames, CullReach reach);

}  // namespace ccdlab
