#pragma once
// Stage 0 of the batched narrow phase: candidate face pairs proven apart as whole triangles, before their
// feature pairs (up to 15; ~3.6 under the fixed rule) are gathered and culled one by one.
//
// Separating axes, at both ends of the step. Along a fixed axis n, at any time t the projections of face f's
// points lie between the least and the greatest of its corners' projections f_i(t)·n, and the same for g. The
// gap min_k g_k(t)·n − max_i f_i(t)·n is the least of nine functions linear in t (linear motion), so it is
// concave and least at t0 or t1: when it exceeds r·|n| at both ends, g stays beyond f along n, farther than r,
// over the whole step (and the same with f beyond g). Then no feature pair of (f, g) can be reported by a tester
// whose reach is r, whatever the representative rule assigned to it. Both ends must show the same side: faces
// that swap sides pass through each other's slab in between.
//
// The axes, cheapest first: the 26-DOP's thirteen (x, y, z, x ± y, x ± z, y ± z, x + y ± z, x − y + z,
// −x + y + z: the projections are sums of coordinates), then each face's normal at both ends, B0×C0 + B1×C1
// (B, C its edges from its first corner). Any axis is valid. The swept volumes the traversal tested are unions
// over the step; at each end the two faces are often far apart (docs/appendix-narrow-phase.md counts how often). x, y and z run first on every candidate, from each face's box at both
// ends (FloatFaceBoxes: a line a face); the other axes only on what they leave. On x, y and z a projection is a
// coordinate, exact; on the others points are taken relative to one corner (f's first at t0), so the rounding
// scales with the pair's size, not with the scene's.
//
// The reach's relative part uses the twelve points' (both faces, both frames) bounding-box extent in the 1-norm,
// L̄: it bounds the box diagonal of every feature pair's query (CullReach's L), so r is never below any of them.
//
// In float (FloatFrames: the frames moved to the centre of their box, each coordinate within ε of the exact
// translated value). The test runs on the float points, exactly as above, and allows for two things:
// - The float points. Every point of either face at any t is a convex combination of its corners at the two
//   ends, so it lies within ε per coordinate of its float counterpart, and relative to the reference corner
//   within 2ε: each projection moves by at most 2ε‖n‖₁, and each gap by 4ε‖n‖₁. The exact points' L̄ is at most
//   the float points' + 6ε.
// - The rounding (u = 2⁻²⁴). Each relative coordinate is one subtraction, then n is used as given (any axis is
//   valid): a projection errs by at most 4u·L̄·‖n‖₁ (a dot product; a sum of two or three coordinates errs less;
//   a coordinate not at all).
// A pair is dropped when a gap exceeds ‖n‖₁·(r·s + 16u·L̄ + 8ε) + 10⁻³⁰ with r = abs + rel·(L̄ + 8ε): twice each
// error, the slack s = 1 + 2⁻¹⁸ for the rounding of r, ‖n‖₁ and the gap itself (≥ 10u), and a floor above any
// error of an underflowed product. ‖n‖₁ ≥ |n|. Pairs that share a vertex are never dropped (their gap is 0); a
// non-finite value never drops one (its comparisons are false).
#include <cstdint>
#include <span>

#include "framework/geometry/vec.hpp"
#include "framework/swept/frame_points.hpp"
#include "framework/mesh/tri_mesh.hpp"
#include "framework/primitive/tester.hpp"
#include "framework/traversal/candidates.hpp"

namespace ccdlab {

/// keep[i] = 0 when candidate i's triangles are proven to stay farther apart than the reach, 1 otherwise. SIMD
/// (Highway, run-time dispatch, as plane_filter); the six corners of a block of candidates are staged in L1,
/// eight at a time where 256-bit vectors exist (one load a corner, both frames), from the step's float frames;
/// a vector stops at the first axis that culls all its lanes. Returns how many candidates x, y and z (from the
/// faces' boxes) left for the second pass, the costly one (NarrowPhase's stage-0 rule counts it). Without
/// `box_pass` every candidate goes to the second pass (x, y and z untested, which only culls less): for
/// candidates the traversal's end boxes have already tested on x, y and z (framework/swept/end_boxes.hpp),
/// where the box pass culls next to nothing and `frames` need no face boxes.
std::size_t triangle_filter(std::span<const FacePair> candidates, const Face* faces, const FloatFrames& frames,
                            CullReach reach, std::uint8_t* keep, bool box_pass = true);

/// The same test for one candidate, plain C++: the reference every SIMD target is checked against.
[[nodiscard]] bool triangle_pair_keeps(const Face& f, const Face& g, const FloatFrames& frames, CullReach reach);

}  // namespace ccdlab
