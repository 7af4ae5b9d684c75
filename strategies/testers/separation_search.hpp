#pragma once
// Minimum-separation CCD that never misses: `conservative` at thickness η > 0. Does the pair come within
// distance η at some t ∈ [0, 1] — and when first, from below?
//
// The gap F(t, u, v) between a point of each feature, linear in each of t, u, v (gap_boxes.hpp): the pair is
// within η exactly where |F| ≤ η, and over a box of (t, u, v) every value of F is a convex combination of its
// 8 corner values.
//
// Boxes are visited earliest first (a heap on their start time tl). When a box is popped, every point of an
// earlier time lies in a box already excluded, so tl bounds the earliest contact time from below. A box is
//   excluded   when one direction c keeps all 8 corner values F_i beyond distance η: c·F_i > η·|c|. c is the
//              value at the box's centre, which makes the test first-order exact near a closest approach
//              (the gradient of |F| vanishes there), so a near miss is resolved with a few boxes per level;
//              the coordinate axes are tried too. Every rounding of the corner values is bounded (the .cpp);
//   a contact  at exactly tl when a corner at t = tl has |F| ≤ η (certified);
//   a contact  when the centre has |F| ≤ η (certified) and the box spans at most `toi_tolerance` in time;
//              when longer, it is split in time (the hit is known, its time is narrowed);
//   undecided  when the image is small: F moves by at most δ·L across the box (L = the query's bounding-box
//              diagonal). Its centre is then within η + √3·δ·L (it was not excluded), and it is reported as
//              a hit at tl. So is the box at which `max_boxes` runs out.
// Otherwise the box is halved along the variable that moves F most.
#include "framework/primitive/contact.hpp"

namespace ccdlab::separation {

/// The `conservative` tester's parameters (defaults there).
struct Params {
  double thickness;      ///< η > 0, scene units
  double delta;          ///< a box whose image is smaller than δ·L is undecided (a hit)
  int max_boxes;         ///< boxes examined per query before the fallback (a hit)
  double toi_tolerance;  ///< a hit's time is at most this much earlier than the true one, when certified
};

/// The earliest time in [0, 1] at which the features come within η, never later than the true one; hit =
/// false only when they provably stay farther apart all step. route = fallback for undecided hits.
CcdHit vertex_face(const VertexFaceQuery& q, const Params& p);
CcdHit edge_edge(const EdgeEdgeQuery& q, const Params& p);

}  // namespace ccdlab::separation
