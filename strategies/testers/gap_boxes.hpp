#pragma once
// The gap between a point of each feature of a CCD query as a function of time and of where on the features,
// and boxes of (t, u, v) over it: shared by the two box searches, `conservative`'s minimum-separation search
// (separation_search.hpp) and the `inclusion` tester (inclusion_tester.hpp).
//
//   vertex–face: F(t, u, v) = v(t) − [f0(t) + u (f1(t) − f0(t)) + u v (f2(t) − f1(t))]
//   edge–edge:   F(t, u, v) = [ea0(t) + u (ea1(t) − ea0(t))] − [eb0(t) + v (eb1(t) − eb0(t))]
// over (t, u, v) ∈ [0, 1]³ (for vertex–face the (u, v) square is folded onto the triangle: u = 0 is f0, u = 1
// the edge f1 f2). Under linear motion F is linear in each of t, u, v separately, so over a box every value is a
// convex combination of the 8 corner values (Wang et al. 2021 build their inclusion functions on this).
#include <array>

#include "framework/geometry/interval.hpp"
#include "framework/primitive/contact.hpp"

namespace ccdlab::gap {

/// The gap at one time as a function of (u, v): F = A + u·P + v·Q + u·v·R (Q = 0 for vertex–face, R = 0 for
/// edge–edge).
struct Bilinear {
  Vec3 A, P, Q, R;
  [[nodiscard]] Vec3 at(double u, double v) const { return A + u * P + v * Q + (u * v) * R; }
};

/// The query's four points at t = 0 and t = 1: (v, f0, f1, f2) or (ea0, ea1, eb0, eb1).
struct Motion {
  bool edge_edge = false;
  std::array<Vec3, 4> x0, x1;
  double M = 0;  ///< the largest |coordinate| of the 8 points: the scale of every rounding error
  double L = 0;  ///< the bounding-box diagonal of the 8 points: the scale relative tolerances refer to

  static Motion of(const VertexFaceQuery& q);
  static Motion of(const EdgeEdgeQuery& q);
  /// The gap at time t. Vertex–face: A = v − f0, P = f0 − f1, R = f1 − f2; edge–edge: A = ea0 − eb0,
  /// P = ea1 − ea0, Q = eb0 − eb1.
  [[nodiscard]] Bilinear at(double t) const;
};

/// A computed value of F (Motion::at(t).at(u, v) at doubles t, u, v in [0, 1]) is within this of the exact one.
double value_error(double M);

/// An interval around a computed value that holds the exact one.
Interval around(double x, double err);

/// Every value in the hull of the corner values F is farther than `reach` from the origin across a coordinate
/// axis, for certain (err: the corner values' error bound).
bool excluded_by_axes(const std::array<Vec3, 8>& F, double err, double reach);

struct Box {
  double t0, t1, u0, u1, v0, v1;
};

/// Below this a variable is not split further (about 50 of its 53 bits resolved).
constexpr double kMinWidth = 0x1p-50;

/// F at the 8 corners of a box; corner i: t1 if bit 0, u1 if bit 1, v1 if bit 2.
std::array<Vec3, 8> corners(const Motion& m, const Box& b);

/// How far F moves along each variable (t, u, v) across the box: the ∞-norm of the largest of the 4 parallel
/// edges of the corner values.
std::array<double, 3> movement(const std::array<Vec3, 8>& F);

}  // namespace ccdlab::gap
