#pragma once
// Certified bounds for the elementary CCD tests (zero thickness) over a time window [tl, th] ⊆ [0, 1].
// Shared by the `filtered` tester (one window, [0, 1]) and the `conservative` tester (bisection in t).
//
// Every query is written relative to one of its points, with three moving vectors A, B, C:
//   vertex–face:  A = v − f0,   B = f1 − f0,  C = f2 − f0
//   edge–edge:    A = eb0 − ea0, B = ea1 − ea0, C = eb1 − eb0
// Contact needs coplanarity, f(t) = A·(B×C) = 0 — a cubic in t — and, at that time, the point in the
// triangle / the segments crossing. With n = B×C, u = n·(B×A), w = n·(A×C) and nn = n·n (quartics in t):
//   vertex–face:  v is in the (coplanar) triangle  ⇔  u ≥ 0, w ≥ 0, nn − u − w ≥ 0  (when n ≠ 0)
//   edge–edge:    the (coplanar) segments cross   ⇔  u ≤ 0 ≤ u + nn  and  w ≥ 0 ≥ w − nn  (when n ≠ 0)
// (u, w, nn − u − w are n·((fi − v)×(fj − v)), i.e. |n|² times the barycentric weights.) All five
// polynomials are computed on [tl, th] in scaled Bernstein form with interval coefficients (Interval rounds
// outward), so "all coefficients > 0" proves positivity on the whole window (Bernstein convex-hull property;
// Tang et al. 2010 use the same bound on f as a non-penetration filter).
#include <array>

#include "framework/geometry/interval.hpp"
#include "framework/primitive/contact.hpp"

namespace ccdlab::interval_ccd {

using IVec3 = std::array<Interval, 3>;

/// A query as the three relative vectors at t = 0 and their change over the step (exact inputs, rounded
/// outward once).
struct RelativeMotion {
  bool edge_edge = false;
  IVec3 A0, B0, C0;     ///< at t = 0
  IVec3 dA, dB, dC;     ///< (value at t = 1) − (value at t = 0)
  double extent = 0;    ///< bounding-box diagonal of the 8 points (the scale tolerances are relative to)
  double motion = 0;    ///< largest relative displacement |dA|, |dB|, |dC| (∞-norm)
};

RelativeMotion relative_motion(const VertexFaceQuery& q);
RelativeMotion relative_motion(const EdgeEdgeQuery& q);

enum class Verdict {
  separated,  ///< certainly no contact in the window
  contact,    ///< certainly a contact in the window (f changes sign, features strictly inside / crossing)
  unknown,    ///< neither could be proven at this window width
};

/// Classifies the window [tl, th]. With `coplanarity_only`, only the sign of f is examined (the caller
/// already knows the features are inside for the whole window): separated or unknown.
Verdict classify(const RelativeMotion& m, double tl, double th, bool coplanarity_only = false);

}  // namespace ccdlab::interval_ccd
