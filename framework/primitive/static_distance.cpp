#include "framework/primitive/static_distance.hpp"

#include <CGAL/Gmpq.h>

#include <cmath>

#include "framework/geometry/distance.hpp"
#include "framework/geometry/interval.hpp"
#include "framework/util/error.hpp"

namespace ccdlab {
namespace {

using Q = CGAL::Gmpq;

/// A comparison's answer: certain either way, or (intervals only) not decided.
enum class Sure : std::int8_t { no, yes, unknown };

Sure less(const Interval& a, const Interval& b) {
  if (a.hi < b.lo) return Sure::yes;
  if (a.lo >= b.hi) return Sure::no;
  return Sure::unknown;  // overlapping, or NaN from an overflow
}
Sure less(const Q& a, const Q& b) { return a < b ? Sure::yes : Sure::no; }
Sure at_least(const auto& a, const auto& b) {
  const Sure s = less(a, b);
  return s == Sure::unknown ? s : s == Sure::yes ? Sure::no : Sure::yes;
}
Sure all(std::initializer_list<Sure> s) {
  Sure out = Sure::yes;
  for (const Sure x : s) {
    if (x == Sure::no) return Sure::no;
    if (x == Sure::unknown) out = Sure::unknown;
  }
  return out;
}

template <class T>
struct P3 {
  T x, y, z;
};
template <class T>
P3<T> operator-(const P3<T>& a, const P3<T>& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
template <class T>
T dot(const P3<T>& a, const P3<T>& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
template <class T>
P3<T> cross(const P3<T>& a, const P3<T>& b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
template <class T>
P3<T> lift(const Vec3& v) { return {T(v.x()), T(v.y()), T(v.z())}; }

/// The pieces' answers: a hit once one applicable piece is certainly below d̂²; unsure when one might be.
struct Pieces {
  bool hit = false;
  bool unsure = false;
  void offer(Sure applies, Sure below) {
    if (applies == Sure::no || below == Sure::no) return;
    if (applies == Sure::yes && below == Sure::yes) hit = true;
    else unsure = true;
  }
};

/// Point p to point s: |p − s|² < r2.
template <class T>
void corner(const P3<T>& p, const P3<T>& s, const T& r2, Pieces& out) {
  const P3<T> w = p - s;
  out.offer(Sure::yes, less(dot(w, w), r2));
}

/// Point p to the inside of segment (s0, s1), where its projection falls strictly between the ends:
/// |w|² − (w·d)² / d·d < r2, multiplied by d·d > 0.
template <class T>
void segment_inside(const P3<T>& p, const P3<T>& s0, const P3<T>& s1, const T& r2, Pieces& out) {
  const P3<T> w = p - s0, d = s1 - s0;
  const T dd = dot(d, d), wd = dot(w, d);
  out.offer(all({less(T(0), wd), less(wd, dd)}), less(dot(w, w) * dd - wd * wd, r2 * dd));
}

template <class T>
Pieces vertex_face_pieces(const P3<T>& p, const P3<T>& a, const P3<T>& b, const P3<T>& c, const T& r2) {
  Pieces out;
  // The face's plane, where p projects inside the face (on the front of each edge, seen along n).
  const P3<T> ab = b - a, ac = c - a, ap = p - a;
  const P3<T> n = cross(ab, ac);
  const T nn = dot(n, n), h = dot(n, ap);
  const Sure inside = all({less(T(0), nn), at_least(dot(n, cross(ab, ap)), T(0)),
                           at_least(dot(n, cross(c - b, p - b)), T(0)), at_least(dot(n, cross(a - c, p - c)), T(0))});
  out.offer(inside, less(h * h, r2 * nn));
  for (const P3<T>* s : {&a, &b, &c}) {
    if (out.hit) return out;
    corner(p, *s, r2, out);
  }
  const P3<T>* v[3] = {&a, &b, &c};
  for (int e = 0; e < 3 && !out.hit; ++e) segment_inside(p, *v[e], *v[(e + 1) % 3], r2, out);
  return out;
}

template <class T>
Pieces edge_edge_pieces(const P3<T>& a0, const P3<T>& a1, const P3<T>& b0, const P3<T>& b1, const T& r2) {
  Pieces out;
  // The lines' distance, where both closest points lie inside the edges.
  const P3<T> da = a1 - a0, db = b1 - b0, r = b0 - a0;
  const P3<T> n = cross(da, db);
  const T nn = dot(n, n), h = dot(r, n), s = dot(cross(r, db), n), t = dot(cross(r, da), n);
  const Sure inside = all({less(T(0), nn), at_least(s, T(0)), at_least(nn, s), at_least(t, T(0)), at_least(nn, t)});
  out.offer(inside, less(h * h, r2 * nn));
  for (const P3<T>* p : {&a0, &a1})
    for (const P3<T>* q : {&b0, &b1})
      if (!out.hit) corner(*p, *q, r2, out);
  if (!out.hit) segment_inside(a0, b0, b1, r2, out);
  if (!out.hit) segment_inside(a1, b0, b1, r2, out);
  if (!out.hit) segment_inside(b0, a0, a1, r2, out);
  if (!out.hit) segment_inside(b1, a0, a1, r2, out);
  return out;
}

/// Intervals first; rationals only for what they leave undecided.
template <class Pieces4>
DistanceVerdict decide(const std::array<const Vec3*, 4>& x, double dhat, Pieces4 pieces) {
  const Interval di(dhat);
  const Pieces in = pieces(lift<Interval>(*x[0]), lift<Interval>(*x[1]), lift<Interval>(*x[2]), lift<Interval>(*x[3]), di * di);
  if (in.hit || !in.unsure) return {in.hit, false};
  const Q dq(dhat);
  return {pieces(lift<Q>(*x[0]), lift<Q>(*x[1]), lift<Q>(*x[2]), lift<Q>(*x[3]), dq * dq).hit, true};
}

}  // namespace

DistanceVerdict vertex_face_closer(const Vec3& p, const Vec3& f0, const Vec3& f1, const Vec3& f2, double dhat) {
  return decide({&p, &f0, &f1, &f2}, dhat, [](const auto&... a) { return vertex_face_pieces(a...); });
}

DistanceVerdict edge_edge_closer(const Vec3& a0, const Vec3& a1, const Vec3& b0, const Vec3& b1, double dhat) {
  return decide({&a0, &a1, &b0, &b1}, dhat, [](const auto&... a) { return edge_edge_pieces(a...); });
}

ClosestFeatures closest_vertex_face(const Vec3& p, const Vec3& f0, const Vec3& f1, const Vec3& f2) {
  const PointTriangleClosest c = closest_point_triangle(p, f0, f1, f2);
  const std::array<double, 3>& w = c.bary;
  DistanceType type = DistanceType::p_t;
  const int zeros = int(w[0] == 0) + int(w[1] == 0) + int(w[2] == 0);
  if (zeros >= 2) type = w[0] != 0 ? DistanceType::p_t0 : w[1] != 0 ? DistanceType::p_t1 : DistanceType::p_t2;
  else if (zeros == 1) type = w[2] == 0 ? DistanceType::p_e0 : w[0] == 0 ? DistanceType::p_e1 : DistanceType::p_e2;
  return {std::sqrt(c.distance_sq), type, {w[1], w[2]}};
}

ClosestFeatures closest_edge_edge(const Vec3& a0, const Vec3& a1, const Vec3& b0, const Vec3& b1) {
  const SegmentSegmentClosest c = closest_segment_segment(a0, a1, b0, b1);
  // Row: edge a's end (0, 1) or its inside (2); column: the same for b.
  constexpr DistanceType kTypes[3][3] = {{DistanceType::ea0_eb0, DistanceType::ea0_eb1, DistanceType::ea0_eb},
                                         {DistanceType::ea1_eb0, DistanceType::ea1_eb1, DistanceType::ea1_eb},
                                         {DistanceType::ea_eb0, DistanceType::ea_eb1, DistanceType::ea_eb}};
  const auto where = [](double u) { return u == 0 ? 0 : u == 1 ? 1 : 2; };
  return {std::sqrt(c.distance_sq), kTypes[where(c.s)][where(c.t)], {c.s, c.t}};
}

StaticDistanceTester::StaticDistanceTester(double dhat) : dhat_(dhat) {
  if (!(dhat > 0) || !std::isfinite(dhat)) fail("dhat = {}: expected a finite distance > 0", dhat);
}

CcdHit StaticDistanceTester::vertex_face(const VertexFaceQuery& q) const {
  const DistanceVerdict v = vertex_face_closer(q.v_t0, q.f0_t0, q.f1_t0, q.f2_t0, dhat_);
  return {v.closer, 0.0, {}, v.in_rationals ? TestRoute::fallback : TestRoute::main};
}

CcdHit StaticDistanceTester::edge_edge(const EdgeEdgeQuery& q) const {
  const DistanceVerdict v = edge_edge_closer(q.ea0_t0, q.ea1_t0, q.eb0_t0, q.eb1_t0, dhat_);
  return {v.closer, 0.0, {}, v.in_rationals ? TestRoute::fallback : TestRoute::main};
}

}  // namespace ccdlab
