#include "strategies/testers/interval_ccd.hpp"

#include <algorithm>
#include <cmath>

#include "framework/geometry/vec.hpp"

namespace ccdlab::interval_ccd {
namespace {

// Scaled Bernstein coefficients ĉ_k = C(n, k)·c_k of a degree-n polynomial on the window. Products are plain
// convolutions in this basis (no division), and ĉ_k has the sign of c_k, which is all the tests need.
template <int N>
struct Poly {
  std::array<Interval, N + 1> c;
  Interval& operator[](int k) { return c[k]; }
  const Interval& operator[](int k) const { return c[k]; }
  [[nodiscard]] auto begin() const { return c.begin(); }
  [[nodiscard]] auto end() const { return c.end(); }
};

template <int M, int N>
Poly<M + N> mul(const Poly<M>& a, const Poly<N>& b) {
  Poly<M + N> c;
  for (int k = 0; k <= M + N; ++k) {
    const int i0 = std::max(0, k - N), i1 = std::min(k, M);
    c[k] = a[i0] * b[k - i0];
    for (int i = i0 + 1; i <= i1; ++i) c[k] = c[k] + a[i] * b[k - i];
  }
  return c;
}

template <int N>
Poly<N> operator+(const Poly<N>& a, const Poly<N>& b) {
  Poly<N> c;
  for (int k = 0; k <= N; ++k) c[k] = a[k] + b[k];
  return c;
}
template <int N>
Poly<N> operator-(const Poly<N>& a, const Poly<N>& b) {
  Poly<N> c;
  for (int k = 0; k <= N; ++k) c[k] = a[k] - b[k];
  return c;
}

template <int N>
bool all_positive(const Poly<N>& p) {
  return std::all_of(p.begin(), p.end(), [](Interval x) { return x.certainly_positive(); });
}
template <int N>
bool all_negative(const Poly<N>& p) {
  return std::all_of(p.begin(), p.end(), [](Interval x) { return x.certainly_negative(); });
}

using LinVec = std::array<Poly<1>, 3>;
using QuadVec = std::array<Poly<2>, 3>;

QuadVec cross(const LinVec& a, const LinVec& b) {
  return {mul(a[1], b[2]) - mul(a[2], b[1]), mul(a[2], b[0]) - mul(a[0], b[2]), mul(a[0], b[1]) - mul(a[1], b[0])};
}
template <int M, int N>
Poly<M + N> dot(const std::array<Poly<M>, 3>& a, const std::array<Poly<N>, 3>& b) {
  return mul(a[0], b[0]) + mul(a[1], b[1]) + mul(a[2], b[2]);
}

/// The vector X0 + t·dX at the window's two ends: its (degree-1) Bernstein coefficients.
LinVec on_window(const IVec3& x0, const IVec3& dx, double tl, double th) {
  LinVec out;
  for (int i = 0; i < 3; ++i) out[i] = Poly<1>{{x0[i] + Interval(tl) * dx[i], x0[i] + Interval(th) * dx[i]}};
  return out;
}

Interval range(const Poly<1>& p) { return hull(p[0], p[1]); }

/// Axis-aligned separation of the two features over the window (a cheap test that also handles the
/// degenerate configurations, parallel edges and zero-area faces, where the sign tests are uncertain).
bool boxes_separated(const RelativeMotion& m, const LinVec& A, const LinVec& B, const LinVec& C) {
  for (int i = 0; i < 3; ++i) {
    const Interval a = range(A[i]), b = range(B[i]), c = range(C[i]);
    Interval first, second;  // the two features' coordinate ranges
    if (m.edge_edge) {
      first = hull(Interval(0.0), b);                           // edge a: {0, B}
      second = hull(a, range(Poly<1>{{A[i][0] + C[i][0], A[i][1] + C[i][1]}}));  // edge b: {A, A + C}
    } else {
      first = a;                                                // the vertex
      second = hull(Interval(0.0), hull(b, c));                 // the face: {0, B, C}
    }
    if (first.lo > second.hi || second.lo > first.hi) return true;
  }
  return false;
}

IVec3 diff(const Vec3& a, const Vec3& b) { return {Interval(a.x()) - b.x(), Interval(a.y()) - b.y(), Interval(a.z()) - b.z()}; }
IVec3 diff(const IVec3& a, const IVec3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
double norm_inf(const IVec3& v) {
  double m = 0;
  for (const Interval& x : v) m = std::max({m, std::abs(x.lo), std::abs(x.hi)});
  return m;
}

RelativeMotion finish(bool ee, const IVec3& A0, const IVec3& A1, const IVec3& B0, const IVec3& B1, const IVec3& C0,
                      const IVec3& C1, double extent) {
  RelativeMotion m;
  m.edge_edge = ee;
  m.A0 = A0, m.B0 = B0, m.C0 = C0;
  m.dA = diff(A1, A0), m.dB = diff(B1, B0), m.dC = diff(C1, C0);
  m.extent = extent;
  m.motion = std::max({norm_inf(m.dA), norm_inf(m.dB), norm_inf(m.dC)});
  return m;
}

template <std::size_t N>
double extent_of(const std::array<const Vec3*, N>& pts) {
  Box3 box;
  for (const Vec3* p : pts) box.grow(*p);
  return box.extent().norm();
}

}  // namespace

RelativeMotion relative_motion(const VertexFaceQuery& q) {
  const double L = extent_of<8>({&q.v_t0, &q.f0_t0, &q.f1_t0, &q.f2_t0, &q.v_t1, &q.f0_t1, &q.f1_t1, &q.f2_t1});
  return finish(false, diff(q.v_t0, q.f0_t0), diff(q.v_t1, q.f0_t1), diff(q.f1_t0, q.f0_t0), diff(q.f1_t1, q.f0_t1),
                diff(q.f2_t0, q.f0_t0), diff(q.f2_t1, q.f0_t1), L);
}

RelativeMotion relative_motion(const EdgeEdgeQuery& q) {
  const double L = extent_of<8>({&q.ea0_t0, &q.ea1_t0, &q.eb0_t0, &q.eb1_t0, &q.ea0_t1, &q.ea1_t1, &q.eb0_t1, &q.eb1_t1});
  return finish(true, diff(q.eb0_t0, q.ea0_t0), diff(q.eb0_t1, q.ea0_t1), diff(q.ea1_t0, q.ea0_t0),
                diff(q.ea1_t1, q.ea0_t1), diff(q.eb1_t0, q.eb0_t0), diff(q.eb1_t1, q.eb0_t1), L);
}

Verdict classify(const RelativeMotion& m, double tl, double th, bool coplanarity_only) {
  const LinVec A = on_window(m.A0, m.dA, tl, th), B = on_window(m.B0, m.dB, tl, th), C = on_window(m.C0, m.dC, tl, th);
  const QuadVec n = cross(B, C);
  const Poly<3> f = dot(A, n);
  if (all_positive(f) || all_negative(f)) return Verdict::separated;
  if (coplanarity_only) return Verdict::unknown;
  if (boxes_separated(m, A, B, C)) return Verdict::separated;
  const Poly<4> u = dot(n, cross(B, A)), w = dot(n, cross(A, C)), nn = dot(n, n);
  // A root of f certainly lies in the window when f's end values (its first and last Bernstein coefficients)
  // have certain, opposite signs.
  const bool root = (f[0].certainly_negative() && f[3].certainly_positive()) ||
                    (f[0].certainly_positive() && f[3].certainly_negative());
  if (!m.edge_edge) {
    const Poly<4> r = nn - u - w;
    if (all_negative(u) || all_negative(w) || all_negative(r)) return Verdict::separated;
    if (root && all_positive(u) && all_positive(w) && all_positive(r)) return Verdict::contact;
    return Verdict::unknown;
  }
  const Poly<4> u_end = u + nn, w_end = w - nn;
  // b0, b1 strictly on one side of edge a's line (u and u + nn of one sign; nn ≥ 0), or a0, a1 of edge b's.
  if (all_positive(u) || all_negative(u_end) || all_negative(w) || all_positive(w_end)) return Verdict::separated;
  if (root && all_negative(u) && all_positive(u_end) && all_positive(w) && all_negative(w_end)) return Verdict::contact;
  return Verdict::unknown;
}

}  // namespace ccdlab::interval_ccd
