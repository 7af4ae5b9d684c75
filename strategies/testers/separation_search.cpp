#include "strategies/testers/separation_search.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

#include "framework/geometry/distance.hpp"
#include "framework/geometry/interval.hpp"
#include "strategies/testers/gap_boxes.hpp"

namespace ccdlab::separation {
namespace {

using gap::around;
using gap::Bilinear;
using gap::Box;
using gap::corners;
using gap::excluded_by_axes;
using gap::kMinWidth;
using gap::Motion;
using gap::value_error;

/// |F| ≤ η for certain, F the exact value near the computed f.
bool certainly_within(const Vec3& f, double err, Interval eta2) {
  Interval sq = 0.0;
  for (int j = 0; j < 3; ++j) {
    const Interval x = around(f[j], err);
    sq = sq + x * x;
  }
  return sq.hi <= eta2.lo;
}

/// The same across the direction c: c·F_i > η·|c| at every corner, and a convex combination keeps the bound.
/// In plain double with a margin that covers every rounding (u = 2⁻⁵³): the true c·F_i is within |c|₁·err of
/// c·F̃_i, which the dot product computes within 3.01·u·a_i (a_i = Σ|c_j·F̃_ij|); the computed |c| is within 2.01·u
/// of the true one. The factor and the term 2⁻⁴⁸ = 32·u cover those and the roundings of the bound itself; 2⁻¹⁰⁰⁰
/// covers products that underflow. NaN or infinite values never exclude.
bool excluded_by(const std::array<Vec3, 8>& F, const Vec3& c, double err, double eta) {
  const double nc = c.norm(), c1 = c.cwiseAbs().sum();
  const double bound = (eta * nc + c1 * err) * (1 + 0x1p-48) + 0x1p-1000;
  for (const Vec3& f : F)
    if (!(c.dot(f) > bound + 0x1p-48 * c.cwiseAbs().dot(f.cwiseAbs()))) return false;
  return true;
}

/// The gap between the closest points of the features at time t, found in plain double (any (u, v) would do:
/// what matters is that the value is then computed, and bounded, as every other).
Vec3 closest_gap(const Motion& m, double t) {
  auto at = [&](int k) -> Vec3 { return m.x0[std::size_t(k)] + t * (m.x1[std::size_t(k)] - m.x0[std::size_t(k)]); };
  double u = 0, v = 0;
  if (m.edge_edge) {
    const SegmentSegmentClosest c = closest_segment_segment(at(0), at(1), at(2), at(3));
    u = c.s, v = c.t;
  } else {
    const PointTriangleClosest c = closest_point_triangle(at(0), at(1), at(2), at(3));
    u = c.bary[1] + c.bary[2];  // the folded square: f0 + u (f1 − f0) + u v (f2 − f1)
    v = u > 0 ? c.bary[2] / u : 0;
  }
  return m.at(t).at(std::clamp(u, 0.0, 1.0), std::clamp(v, 0.0, 1.0));
}

/// Conservative advancement of a box along the direction c (Mirtich 1996): F is linear in t at each (u, v)
/// corner, so c·F − η·|c| at the 4 corners reaches 0 first at a time found in closed form; a little before it,
/// [t0, next] × the box's (u, v) is excluded — proven with the certified corner test. Returns next (t0 when
/// the direction does not separate the corners at t0, or the proof fails twice).
double advance(const Motion& m, const Box& b, const Vec3& c, double err, double eta) {
  const Bilinear g0 = m.at(b.t0), g1 = m.at(b.t1);
  const double plane = eta * c.norm();
  double reach = b.t1;  // when the first corner reaches the plane
  for (int i = 0; i < 4; ++i) {
    const double u = i & 1 ? b.u1 : b.u0, v = i & 2 ? b.v1 : b.v0;
    const double lo = c.dot(g0.at(u, v)) - plane, hi = c.dot(g1.at(u, v)) - plane;
    if (!(lo > 0)) return b.t0;
    if (hi < 0) reach = std::min(reach, b.t0 + (b.t1 - b.t0) * (lo / (lo - hi)));
  }
  Box swept = b;
  swept.t1 = reach >= b.t1 ? b.t1 : b.t0 + (reach - b.t0) * (1 - 0x1p-12);
  for (int attempt = 0; attempt < 2; ++attempt, swept.t1 = b.t0 + 0.5 * (swept.t1 - b.t0))
    if (excluded_by(corners(m, swept), c, err, eta)) return swept.t1;
  return b.t0;
}

/// F at the start of a box, at the centre of its (u, v).
Vec3 g0_centre(const Motion& m, const Box& b) { return m.at(b.t0).at(0.5 * (b.u0 + b.u1), 0.5 * (b.v0 + b.v1)); }

/// Conservative advancement steps before the bisection takes over, and the least progress (a fraction of the
/// time left) a step must make to be worth the next.
constexpr int kMaxAdvances = 16;
constexpr double kStall = 1.0 / 64;

template <class Query>
CcdHit search(const Query& q, const Params& p) {
  const Motion m = Motion::of(q);
  const double err = value_error(m.M), eta = p.thickness;
  const Interval eta2 = Interval(eta) * eta;
  const double toi_tolerance = std::max(p.toi_tolerance, kMinWidth);
  auto hit = [&](double toi, TestRoute route) {
    CcdHit h;
    h.hit = true;
    h.toi = toi;
    h.coords = contact_coords(q, toi);
    h.route = route;
    return h;
  };
  const Box whole{0, 1, 0, 1, 0, 1};
  {
    const std::array<Vec3, 8> F = corners(m, whole);
    if (excluded_by_axes(F, err, eta) || excluded_by(F, m.at(0.5).at(0.5, 0.5), err, eta)) return {};
  }
  // Conservative advancement (Mirtich 1996; along the closest points' direction, as Tang et al. 2009). At time t
  // the gap n between the closest points separates all of F(t, ·, ·) from the origin (the features are convex:
  // n·F ≥ |n|² for every pair of points). While |n| > η, n keeps the corners of the (u, v) square — the
  // features' vertices, moving linearly — beyond η until the first reaches the plane n·F = η·|n|; the time up
  // to just before is excluded, with the same certified corner test as any box, and the search moves there.
  double t = 0;
  for (int step = 0; step < kMaxAdvances; ++step) {
    const Vec3 n = closest_gap(m, t);
    if (certainly_within(n, err, eta2)) return hit(t, TestRoute::main);  // [0, t) is excluded: the exact time
    Box rest = whole;
    rest.t0 = t;
    const double next = advance(m, rest, n, err, eta);
    if (next >= 1) return {};  // excluded up to the end of the step
    const double progress = next - t;
    t = next;
    // Just short of where a vertex reaches the plane: a contact a little later settles the time within tolerance.
    if (progress > 0 && certainly_within(closest_gap(m, std::min(1.0, t + 0.5 * toi_tolerance)), err, eta2))
      return hit(t, TestRoute::main);
    if (progress <= kStall * (1 - t + progress)) break;
  }
  // Bisection of what is left, [t, 1] × the (u, v) square, earliest box first.
  const double resolved = p.delta * m.L;
  thread_local std::vector<Box> heap;
  heap.clear();
  const auto later = [](const Box& a, const Box& b) { return a.t0 > b.t0; };
  auto push = [&](const Box& b) {
    heap.push_back(b);
    std::push_heap(heap.begin(), heap.end(), later);
  };
  push({t, 1, 0, 1, 0, 1});
  // The earliest time at which a contact is proven so far. The box popped starts no later than any contact, so
  // once it starts within toi_tolerance of this time, its start is the answer.
  double ceiling = std::numeric_limits<double>::infinity();
  auto contact_at = [&](double time) {
    if (certainly_within(closest_gap(m, time), err, eta2)) ceiling = std::min(ceiling, time);
  };
  double probed = -1;  // the start time whose closest points are in `gap`
  Vec3 gap = Vec3::Zero();
  for (int examined = 0; !heap.empty(); ++examined) {
    std::pop_heap(heap.begin(), heap.end(), later);
    const Box b = heap.back();
    heap.pop_back();
    if (b.t0 >= ceiling - toi_tolerance) return hit(std::min(b.t0, ceiling), TestRoute::main);
    if (examined == p.max_boxes) return hit(b.t0, TestRoute::fallback);
    // The closest points at t0: a contact there is the earliest, and their gap separates the whole of
    // F(t0, ·, ·) otherwise — a good direction for the boxes that start there.
    if (b.t0 != probed) {
      probed = b.t0;
      gap = closest_gap(m, b.t0);
      if (certainly_within(gap, err, eta2)) return hit(b.t0, TestRoute::main);
    }
    const std::array<Vec3, 8> F = corners(m, b);
    const double tm = 0.5 * (b.t0 + b.t1), um = 0.5 * (b.u0 + b.u1), vm = 0.5 * (b.v0 + b.v1);
    const Vec3 centre = m.at(tm).at(um, vm);
    if (excluded_by_axes(F, err, eta) || excluded_by(F, centre, err, eta) || excluded_by(F, gap, err, eta)) continue;
    const double tw = b.t1 - b.t0;
    if (certainly_within(centre, err, eta2)) ceiling = std::min(ceiling, tm);
    // Cut off the box's early part where a direction still separates (the gap at t0, or the value at the centre
    // of the box's start) and look again at the rest — first whether the features are within η just after it
    // (an advance stops short of a contact, so it would approach it forever).
    double next = advance(m, b, gap, err, eta);
    if (next - b.t0 < kStall * tw) next = std::max(next, advance(m, b, g0_centre(m, b), err, eta));
    if (next - b.t0 >= kStall * tw) {
      contact_at(std::min(b.t1, next + 0.5 * toi_tolerance));
      Box rest = b;
      rest.t0 = next;
      push(rest);
      continue;
    }
    const std::array<double, 3> move = gap::movement(F);
    if (move[0] + move[1] + move[2] <= resolved) return hit(b.t0, TestRoute::fallback);
    const int d = int(std::max_element(move.begin(), move.end()) - move.begin());
    Box lo = b, hi = b;
    switch (d) {
      case 0:
        if (tw <= kMinWidth) return hit(b.t0, TestRoute::fallback);
        lo.t1 = hi.t0 = tm;
        break;
      case 1:
        if (b.u1 - b.u0 <= kMinWidth) return hit(b.t0, TestRoute::fallback);
        lo.u1 = hi.u0 = um;
        break;
      default:
        if (b.v1 - b.v0 <= kMinWidth) return hit(b.t0, TestRoute::fallback);
        lo.v1 = hi.v0 = vm;
    }
    push(lo);
    push(hi);
  }
  return {};  // every box excluded: the pair stays farther than η all step
}

}  // namespace

CcdHit vertex_face(const VertexFaceQuery& q, const Params& p) { return search(q, p); }
CcdHit edge_edge(const EdgeEdgeQuery& q, const Params& p) { return search(q, p); }

}  // namespace ccdlab::separation
