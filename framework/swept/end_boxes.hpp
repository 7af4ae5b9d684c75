#pragma once
// End boxes: a node's axis-aligned box at each end of the step (its points at t0, and at t1), next to its swept
// k-DOP. The traversal drops a pair of nodes whose boxes are apart on one of x, y, z at t0 AND at t1, on the same
// side, even where their swept k-DOPs overlap (bv.end_boxes; docs/wide-bvh.md).
//
// Why that never loses a contact (the argument of the narrow phase's stage 0, triangle_filter.hpp, applied to
// whole nodes): every vertex moves linearly over the step, so along a fixed axis each vertex's coordinate is
// linear in t. The largest coordinate over A's vertices is then convex in t, the smallest over B's concave,
// and their gap g(t) = min_B(t) − max_A(t) is concave: g(t) ≥ (1 − t)·g(0) + t·g(1). Each box is inflated by
// η/2, so boxes apart at t0 and at t1 mean g(0) > η and g(1) > η, hence g(t) > η for every t: no point of A's
// triangles comes within η of one of B's during the step, and no feature pair under (A, B) is a contact.
// A parent's box holds its children's at each end, so a pair apart at both ends has every descendant pair apart:
// every walk drops the same leaf pairs, whichever level it tests them at.
//
// The union of the two boxes on an axis is the swept box, so boxes apart at both ends is a weaker condition than
// the swept k-DOP's x, y, z axes being apart: the test adds to the k-DOP's, never replaces it. It culls pairs that
// pass one another's positions during the step only on different axes, or not at all: bodies bouncing apart
// far more than a twisting rod, whose faces overlap their neighbours' at both ends.
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "framework/mesh/tri_mesh.hpp"
#include "framework/swept/frame_points.hpp"

namespace ccdlab {

/// A node's box at each end of the step: lo[f][c], hi[f][c] for frame f (0: t0, 1: t1) and axis c (x, y, z; [3]
/// pads). Each bound holds the exact bound moved out by η/2 (face_end_boxes). Empty: lo = +inf, hi = −inf.
struct alignas(16) EndBoxes {
  float lo[2][4];
  float hi[2][4];
  void merge(const EndBoxes& o) {
    for (int f = 0; f < 2; ++f)
      for (int c = 0; c < 4; ++c) lo[f][c] = std::min(lo[f][c], o.lo[f][c]), hi[f][c] = std::max(hi[f][c], o.hi[f][c]);
  }
  static EndBoxes empty() {
    EndBoxes e;
    for (int f = 0; f < 2; ++f)
      for (int c = 0; c < 4; ++c) e.lo[f][c] = std::numeric_limits<float>::infinity(), e.hi[f][c] = -e.lo[f][c];
    return e;
  }
};
static_assert(sizeof(EndBoxes) == 64, "one cache line a node");

/// Whether a and b are apart at both ends of the step on one of x, y, z, on the same side (strictly: boxes that
/// touch are not apart). NaN bounds compare false: never apart.
inline bool apart_at_both_ends(const EndBoxes& a, const EndBoxes& b) {
  bool apart = false;  // every axis tested, no branch
  for (int c = 0; c < 3; ++c) {
    apart |= (a.hi[0][c] < b.lo[0][c]) & (a.hi[1][c] < b.lo[1][c]);
    apart |= (b.hi[0][c] < a.lo[0][c]) & (b.hi[1][c] < a.lo[1][c]);
  }
  return apart;
}

/// The distance beyond which a tester of reach `reach` reports no pair of a scene whose box (both frames) has
/// 1-norm extent `scene_extent`: every feature pair's size (CullReach's L) is at most that. End boxes are inflated
/// by half of it. The factor covers this product's and sum's rounding.
inline double end_boxes_reach(double reach_abs, double reach_rel, double scene_extent) {
  return (reach_abs + reach_rel * scene_extent) * (1 + 0x1p-40);
}

/// The EndBoxes of a triangle from its corners' double coordinates (FramePoints), inflated by r = η/2. Each bound
/// is moved out by r + 2⁻²²·(|bound| + r) in double, then converted to float: the conversion errs by at most 2⁻²⁴
/// of the result and the double arithmetic by ~2⁻⁵² of it, both far inside the 2⁻²² margin, so the float lo is
/// below the exact lo − r and the float hi above hi + r. Branch-free (min, max, abs, conversions).
inline EndBoxes face_end_boxes(const FramePoints* points, const Face& face, double r) {
  constexpr double c = 0x1p-22;
  const FramePoints &p = points[face[0]], &q = points[face[1]], &s = points[face[2]];
  EndBoxes out;
  for (int j = 0; j < 4; ++j) {
    const double lo0 = std::min(std::min(p.t0[j], q.t0[j]), s.t0[j]), hi0 = std::max(std::max(p.t0[j], q.t0[j]), s.t0[j]);
    const double lo1 = std::min(std::min(p.t1[j], q.t1[j]), s.t1[j]), hi1 = std::max(std::max(p.t1[j], q.t1[j]), s.t1[j]);
    out.lo[0][j] = float(lo0 - r - c * (std::abs(lo0) + r)), out.hi[0][j] = float(hi0 + r + c * (std::abs(hi0) + r));
    out.lo[1][j] = float(lo1 - r - c * (std::abs(lo1) + r)), out.hi[1][j] = float(hi1 + r + c * (std::abs(hi1) + r));
  }
  return out;
}

}  // namespace ccdlab
