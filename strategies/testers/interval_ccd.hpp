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
#include <functional>
#include <utility>

#include "framework/geometry/interval.hpp"
#include "framework/primitive/contact.hpp"

namespace ccdlab::interval_ccd {

/// A query as the three relative vectors A, B, C at t = 0 and t = 1, each a difference of two inputs
/// (one rounding; the error bounds of interval_ccd.cpp account for it).
struct RelativeMotion {
  bool edge_edge = false;
  Vec3 a0, a1, b0, b1, c0, c1;
  double extent = 0;  ///< bounding-box diagonal of the 8 points (the scale tolerances are relative to)
  double motion = 0;  ///< largest relative displacement |A1 − A0|, |B1 − B0|, |C1 − C0| (∞-norm; a heuristic)
};

/// Fast certified test, in plain double with a forward error bound: true when f(t) = A·(B×C) provably keeps
/// one sign on [0, 1] (then the features cannot touch). Much cheaper than `classify`; it decides most
/// non-colliding pairs of a cloth step, so every zero-thickness tester runs it first.
bool certainly_never_coplanar(const VertexFaceQuery& q);
bool certainly_never_coplanar(const EdgeEdgeQuery& q);

/// The same test, also telling apart queries whose f stays near zero over the whole step (coplanar motion,
/// e.g. neighbouring features of a flat sheet: |f| below 2⁻²⁰ of its terms' size), which `conservative`
/// settles best from the whole step (separating axes) rather than root by root.
enum class Coplanarity { never, flat, general };
Coplanarity screen_coplanarity(const VertexFaceQuery& q);
Coplanarity screen_coplanarity(const EdgeEdgeQuery& q);

RelativeMotion relative_motion(const VertexFaceQuery& q);
RelativeMotion relative_motion(const EdgeEdgeQuery& q);

enum class Verdict {
  separated,  ///< certainly no contact in the window
  contact,    ///< certainly a contact in the window (f changes sign, features strictly inside / crossing)
  unknown,    ///< neither could be proven at this window width
};

/// Classifies the window [tl, th]. With `coplanarity_only`, only the sign of f is examined, for a caller that
/// already knows the features are inside (crossing) throughout the window: separated, contact (f's end values
/// have certain, opposite signs: a root lies inside) or unknown.
Verdict classify(const RelativeMotion& m, double tl, double th, bool coplanarity_only = false);

/// Visits, earliest first, the sub-windows of [tl, th] at most `width` wide where f(t) may vanish (de Casteljau
/// subdivision of f's interval Bernstein coefficients: a few additions per level, much cheaper than
/// `classify`). `visit(a, b)` returns true to stop. Every contact needs f = 0, so contact times all lie in
/// the visited windows. Returns false when every window was visited without a stop.
bool for_each_coplanarity_window(const RelativeMotion& m, double tl, double th, double width,
                                 const std::function<bool(double, double)>& visit);

/// Narrows a window [a, b] that holds the earliest contact (none before a; classify(a, b) = contact) by
/// bisection, as far as f's sign can be proven: the contact verdict proved the features inside (crossing)
/// throughout [a, b], so its contact times are the roots of f there. The left half is dropped when f ≠ 0 on it
/// (proven), kept when f changes sign across it (a root, proven); it stops at adjacent doubles or where neither
/// can be proven. Each half is first decided from the window's coefficients subdivided (de Casteljau in
/// intervals: a few additions), and only where those bounds have grown too wide, by classify(m, a, mid, true)
/// from fresh ones. The two prove exclusive facts, so where both decide they agree: the result is the window
/// that bisection by classify alone reaches, or a narrower one within it.
std::pair<double, double> narrow_root(const RelativeMotion& m, double a, double b);

/// The start of the earliest such window (a lower bound on any contact time in [tl, th]); th if there is none.
double earliest_coplanarity(const RelativeMotion& m, double tl, double th, double width);

}  // namespace ccdlab::interval_ccd
