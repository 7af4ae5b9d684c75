#include "strategies/testers/interval_ccd.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "framework/geometry/vec.hpp"

namespace ccdlab::interval_ccd {
namespace {

// Scaled Bernstein coefficients ĉ_k = C(n, k)·c_k of a degree-n polynomial on the window. Products are plain
// convolutions in this basis (no division), and ĉ_k has the sign of c_k, which is all the tests need.
// Two scalar types run the same polynomial code:
//  * Interval (framework/geometry/interval.hpp): outward-rounded bounds, used for de Casteljau subdivision
//    and the separating-axis and box tests;
//  * Bounded: a double and the sum of the absolute values of its terms, for the sign tests of `classify`.
//    Every quantity there is a polynomial in the 24 inputs evaluated by one straight-line program of +, −, ×
//    from differences of inputs (one rounding each); along any term at most 14 roundings occur (window ends
//    x0 + t·(x1 − x0): 4; a cross product in Bernstein form: 3; a quartic's products and Bernstein sums: 3;
//    the dot product's sums: 2; nn − u − w: 2), so |computed − exact| ≤ γ₁₄·Σ|terms| ≤ 15u·a (Higham,
//    "Accuracy and Stability of Numerical Algorithms", §3.1). The test uses 2⁻⁴⁷ = 64u·a, and treats
//    a < 1e-250 (possible underflow) or a non-finite a as unknown.
//    It is cheaper than interval arithmetic (two operations per operation, no min/max).
struct Bounded {
  double v = 0, a = 0;  // value; a ≥ Σ|terms| of the exact value (as computed)
  static constexpr double kError = 0x1p-47, kSmallest = 1e-250;
  [[nodiscard]] bool reliable() const { return a >= kSmallest && a <= std::numeric_limits<double>::max(); }
  [[nodiscard]] bool certainly_positive() const { return reliable() && v > kError * a; }
  [[nodiscard]] bool certainly_negative() const { return reliable() && v < -kError * a; }
};
inline Bounded operator+(Bounded x, Bounded y) { return {x.v + y.v, x.a + y.a}; }
inline Bounded operator-(Bounded x, Bounded y) { return {x.v - y.v, x.a + y.a}; }
inline Bounded operator*(Bounded x, Bounded y) { return {x.v * y.v, x.a * y.a}; }
/// An interval certainly holding the exact value of x.
Interval to_interval(Bounded x) {
  if (x.a == 0) return Interval(x.v);  // every term is zero: exact
  if (!x.reliable()) return {-std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
  const double e = Bounded::kError * x.a;
  return {detail::widen_down(x.v - e), detail::widen_up(x.v + e)};
}

// Scaled Bernstein coefficients ĉ_k = C(n, k)·c_k of a degree-n polynomial on the window. Products are plain
// convolutions in this basis (no division), and ĉ_k has the sign of c_k, which is all the tests need.
template <class T, int N>
struct Poly {
  std::array<T, N + 1> c;
  T& operator[](int k) { return c[k]; }
  const T& operator[](int k) const { return c[k]; }
  [[nodiscard]] auto begin() const { return c.begin(); }
  [[nodiscard]] auto end() const { return c.end(); }
};

template <class T, int M, int N>
Poly<T, M + N> mul(const Poly<T, M>& a, const Poly<T, N>& b) {
  Poly<T, M + N> c;
  for (int k = 0; k <= M + N; ++k) {
    const int i0 = std::max(0, k - N), i1 = std::min(k, M);
    c[k] = a[i0] * b[k - i0];
    for (int i = i0 + 1; i <= i1; ++i) c[k] = c[k] + a[i] * b[k - i];
  }
  return c;
}

template <class T, int N>
Poly<T, N> operator+(const Poly<T, N>& a, const Poly<T, N>& b) {
  Poly<T, N> c;
  for (int k = 0; k <= N; ++k) c[k] = a[k] + b[k];
  return c;
}
template <class T, int N>
Poly<T, N> operator-(const Poly<T, N>& a, const Poly<T, N>& b) {
  Poly<T, N> c;
  for (int k = 0; k <= N; ++k) c[k] = a[k] - b[k];
  return c;
}

template <class T, int N>
bool all_positive(const Poly<T, N>& p) {
  return std::all_of(p.begin(), p.end(), [](const T& x) { return x.certainly_positive(); });
}
template <class T, int N>
bool all_negative(const Poly<T, N>& p) {
  return std::all_of(p.begin(), p.end(), [](const T& x) { return x.certainly_negative(); });
}

template <class T>
using LinVecT = std::array<Poly<T, 1>, 3>;
template <class T>
using QuadVecT = std::array<Poly<T, 2>, 3>;
using LinVec = LinVecT<Interval>;

template <class T>
QuadVecT<T> cross(const LinVecT<T>& a, const LinVecT<T>& b) {
  return {mul(a[1], b[2]) - mul(a[2], b[1]), mul(a[2], b[0]) - mul(a[0], b[2]), mul(a[0], b[1]) - mul(a[1], b[0])};
}
template <class T, int M, int N>
Poly<T, M + N> dot(const std::array<Poly<T, M>, 3>& a, const std::array<Poly<T, N>, 3>& b) {
  return mul(a[0], b[0]) + mul(a[1], b[1]) + mul(a[2], b[2]);
}

/// The vector X(t) = X0 + t·(X1 − X0) at the window's two ends (its degree-1 Bernstein coefficients), as
/// Bounded values.
LinVecT<Bounded> on_window(const Vec3& x0, const Vec3& x1, double tl, double th) {
  LinVecT<Bounded> out;
  for (int i = 0; i < 3; ++i) {
    const Bounded a{x0[i], std::abs(x0[i])}, b{x1[i], std::abs(x1[i])}, d = b - a;
    out[i] = Poly<Bounded, 1>{{a + Bounded{tl, tl} * d, a + Bounded{th, th} * d}};
  }
  return out;
}
LinVec to_intervals(const LinVecT<Bounded>& v) {
  LinVec out;
  for (int i = 0; i < 3; ++i) out[i] = Poly<Interval, 1>{{to_interval(v[i][0]), to_interval(v[i][1])}};
  return out;
}

Interval range(const Poly<Interval, 1>& p) { return hull(p[0], p[1]); }

/// Axis-aligned separation of the two features over the window (a cheap test that also handles the
/// degenerate configurations, parallel edges and zero-area faces, where the sign tests are uncertain).
bool boxes_separated(const RelativeMotion& m, const LinVec& A, const LinVec& B, const LinVec& C) {
  for (int i = 0; i < 3; ++i) {
    const Interval a = range(A[i]), b = range(B[i]), c = range(C[i]);
    Interval first, second;  // the two features' coordinate ranges
    if (m.edge_edge) {
      first = hull(Interval(0.0), b);                           // edge a: {0, B}
      second = hull(a, range(Poly<Interval, 1>{{A[i][0] + C[i][0], A[i][1] + C[i][1]}}));  // edge b: {A, A + C}
    } else {
      first = a;                                                // the vertex
      second = hull(Interval(0.0), hull(b, c));                 // the face: {0, B, C}
    }
    if (first.lo > second.hi || second.lo > first.hi) return true;
  }
  return false;
}

RelativeMotion make_motion(bool ee, const Vec3& a0, const Vec3& a1, const Vec3& b0, const Vec3& b1, const Vec3& c0,
                           const Vec3& c1, double extent) {
  RelativeMotion m{ee, a0, a1, b0, b1, c0, c1, extent, 0.0};
  m.motion = std::max({(a1 - a0).lpNorm<Eigen::Infinity>(), (b1 - b0).lpNorm<Eigen::Infinity>(),
                       (c1 - c0).lpNorm<Eigen::Infinity>()});
  return m;
}

template <std::size_t N>
double extent_of(const std::array<const Vec3*, N>& pts) {
  Box3 box;
  for (const Vec3* p : pts) box.grow(*p);
  return box.extent().norm();
}

/// Separating-axis test over the window, for the configurations where the sign tests above degenerate:
/// parallel or collinear edges, zero-area faces, coplanar motion (there f ≡ 0 and n ≈ 0). The axes are
/// chosen in plain double at mid-window (any axis is valid); the projections are linear in t, so their range
/// over the window is the hull of the two ends, computed with intervals — the test itself is certified.
bool separated_along_axes(const RelativeMotion& m, const LinVec& A, const LinVec& B, const LinVec& C) {
  auto mid = [](const LinVec& v) {
    return Vec3(0.25 * (v[0][0].lo + v[0][0].hi + v[0][1].lo + v[0][1].hi), 0.25 * (v[1][0].lo + v[1][0].hi + v[1][1].lo + v[1][1].hi),
                0.25 * (v[2][0].lo + v[2][0].hi + v[2][1].lo + v[2][1].hi));
  };
  const Vec3 a = mid(A), b = mid(B), c = mid(C), n = b.cross(c);
  // Feature points relative to the reference point: edge–edge {0, B} vs {A, A + C}; vertex–face {A} vs {0, B, C}.
  auto project = [&](const Vec3& axis, const LinVec& v, int end) {
    return Interval(axis.x()) * v[0][end] + Interval(axis.y()) * v[1][end] + Interval(axis.z()) * v[2][end];
  };
  auto apart = [&](const Vec3& axis) {
    if (!(axis.squaredNorm() > 0) || !axis.allFinite()) return false;
    Interval first, second;  // ranges of the two features over the window
    bool init1 = false, init2 = false;
    auto add = [](Interval& range, bool& init, Interval x) { range = init ? hull(range, x) : x, init = true; };
    for (int end = 0; end < 2; ++end) {
      const Interval pa = project(axis, A, end), pb = project(axis, B, end), pc = project(axis, C, end);
      if (m.edge_edge) {
        add(first, init1, Interval(0.0)), add(first, init1, pb);
        add(second, init2, pa), add(second, init2, pa + pc);
      } else {
        add(first, init1, pa);
        add(second, init2, Interval(0.0)), add(second, init2, pb), add(second, init2, pc);
      }
    }
    return first.hi < second.lo || second.hi < first.lo;
  };
  if (m.edge_edge) {
    // Edge directions (collinear, end to end), the common normal, and the perpendicular from line a to b0.
    return apart(b) || apart(c) || apart(n) || apart(b.cross(b.cross(a))) || apart(c.cross(c.cross(a - b)));
  }
  // The face's edge directions, its in-plane edge normals, and for a flat face the perpendiculars to its edges.
  const Vec3 e = c - b;
  return apart(n.cross(b)) || apart(c.cross(n)) || apart(e.cross(n)) || apart(b) || apart(c) || apart(e) ||
         apart(b.cross(b.cross(a))) || apart(c.cross(c.cross(a)));
}

/// x / 2, enclosing the exact half even when it falls below the normal range.
Interval half(Interval x) {
  Interval r{x.lo * 0.5, x.hi * 0.5};
  constexpr double kMin = std::numeric_limits<double>::min(), kSub = std::numeric_limits<double>::denorm_min();
  if (r.lo != 0 && std::abs(r.lo) < kMin) r.lo -= kSub;
  if (r.hi != 0 && std::abs(r.hi) < kMin) r.hi += kSub;
  return r;
}

/// |a| ×' |b|: the cross product's terms in absolute value, summed (bounds |a × b| and its rounding).
Vec3 cross_abs(const Vec3& a, const Vec3& b) {
  const Vec3 x = a.cwiseAbs(), y = b.cwiseAbs();
  return {x.y() * y.z() + x.z() * y.y(), x.z() * y.x() + x.x() * y.z(), x.x() * y.y() + x.y() * y.x()};
}

/// Scaled Bernstein coefficients of f = A·(B×C) on [0, 1] from the vectors at t = 0 and t = 1, in double,
/// with an error bound. Each coefficient is a sum of ≤ 18 products of three differences of inputs; along any
/// term at most 10 roundings occur (3 input differences, 2 products, 5 sums), so the computed value is within
/// γ₁₀·Σ|terms| ≤ 11u·(the same sum evaluated on absolute values) of the exact one (Higham, "Accuracy and
/// Stability of Numerical Algorithms", §3.1). We use 2⁻⁴⁸ = 32u, a margin of 3×.
Coplanarity screen_step(const Vec3& A0, const Vec3& B0, const Vec3& C0, const Vec3& A1, const Vec3& B1, const Vec3& C1) {
  const Vec3 n0 = B0.cross(C0), n1 = B0.cross(C1) + B1.cross(C0), n2 = B1.cross(C1);
  const Vec3 m0 = cross_abs(B0, C0), m1 = cross_abs(B0, C1) + cross_abs(B1, C0), m2 = cross_abs(B1, C1);
  const Vec3 a0 = A0.cwiseAbs(), a1 = A1.cwiseAbs();
  const double f[4] = {A0.dot(n0), A0.dot(n1) + A1.dot(n0), A0.dot(n2) + A1.dot(n1), A1.dot(n2)};
  const double g[4] = {a0.dot(m0), a0.dot(m1) + a1.dot(m0), a0.dot(m2) + a1.dot(m1), a1.dot(m2)};
  constexpr double kRelative = 0x1p-48, kFlat = 0x1p-20;
  constexpr double kSmallest = 1e-250;  // below this, products may have underflowed: not certain
  bool pos = true, neg = true, flat = true;
  for (int k = 0; k < 4; ++k) {
    flat = flat && std::abs(f[k]) <= kFlat * g[k];
    if (!(g[k] >= kSmallest) || !std::isfinite(g[k])) {
      pos = neg = false;
      continue;
    }
    const double err = kRelative * g[k];
    pos = pos && f[k] > err;
    neg = neg && f[k] < -err;
  }
  return pos || neg ? Coplanarity::never : flat ? Coplanarity::flat : Coplanarity::general;
}

}  // namespace

Coplanarity screen_coplanarity(const VertexFaceQuery& q) {
  return screen_step(q.v_t0 - q.f0_t0, q.f1_t0 - q.f0_t0, q.f2_t0 - q.f0_t0, q.v_t1 - q.f0_t1, q.f1_t1 - q.f0_t1,
                     q.f2_t1 - q.f0_t1);
}

Coplanarity screen_coplanarity(const EdgeEdgeQuery& q) {
  return screen_step(q.eb0_t0 - q.ea0_t0, q.ea1_t0 - q.ea0_t0, q.eb1_t0 - q.eb0_t0, q.eb0_t1 - q.ea0_t1,
                     q.ea1_t1 - q.ea0_t1, q.eb1_t1 - q.eb0_t1);
}

bool certainly_never_coplanar(const VertexFaceQuery& q) { return screen_coplanarity(q) == Coplanarity::never; }
bool certainly_never_coplanar(const EdgeEdgeQuery& q) { return screen_coplanarity(q) == Coplanarity::never; }

RelativeMotion relative_motion(const VertexFaceQuery& q) {
  const double L = extent_of<8>({&q.v_t0, &q.f0_t0, &q.f1_t0, &q.f2_t0, &q.v_t1, &q.f0_t1, &q.f1_t1, &q.f2_t1});
  return make_motion(false, q.v_t0 - q.f0_t0, q.v_t1 - q.f0_t1, q.f1_t0 - q.f0_t0, q.f1_t1 - q.f0_t1, q.f2_t0 - q.f0_t0,
                     q.f2_t1 - q.f0_t1, L);
}

RelativeMotion relative_motion(const EdgeEdgeQuery& q) {
  const double L = extent_of<8>({&q.ea0_t0, &q.ea1_t0, &q.eb0_t0, &q.eb1_t0, &q.ea0_t1, &q.ea1_t1, &q.eb0_t1, &q.eb1_t1});
  return make_motion(true, q.eb0_t0 - q.ea0_t0, q.eb0_t1 - q.ea0_t1, q.ea1_t0 - q.ea0_t0, q.ea1_t1 - q.ea0_t1,
                     q.eb1_t0 - q.eb0_t0, q.eb1_t1 - q.eb0_t1, L);
}

Verdict classify(const RelativeMotion& m, double tl, double th, bool coplanarity_only) {
  using B = Bounded;
  const LinVecT<B> A = on_window(m.a0, m.a1, tl, th), Bv = on_window(m.b0, m.b1, tl, th), C = on_window(m.c0, m.c1, tl, th);
  const QuadVecT<B> n = cross(Bv, C);
  const Poly<B, 3> f = dot(A, n);
  if (all_positive(f) || all_negative(f)) return Verdict::separated;
  // A root of f certainly lies in the window when f's end values (its first and last Bernstein coefficients)
  // have certain, opposite signs.
  const bool root = (f[0].certainly_negative() && f[3].certainly_positive()) ||
                    (f[0].certainly_positive() && f[3].certainly_negative());
  if (coplanarity_only) return root ? Verdict::contact : Verdict::unknown;
  const LinVec Ai = to_intervals(A), Bi = to_intervals(Bv), Ci = to_intervals(C);
  if (boxes_separated(m, Ai, Bi, Ci)) return Verdict::separated;
  const Poly<B, 4> u = dot(n, cross(Bv, A)), w = dot(n, cross(A, C)), nn = dot(n, n);
  if (!m.edge_edge) {
    const Poly<B, 4> r = nn - u - w;
    if (all_negative(u) || all_negative(w) || all_negative(r)) return Verdict::separated;
    if (root && all_positive(u) && all_positive(w) && all_positive(r)) return Verdict::contact;
    // Only a (nearly) flat face makes the sign tests blind; then try separating axes.
    return !all_positive(nn) && separated_along_axes(m, Ai, Bi, Ci) ? Verdict::separated : Verdict::unknown;
  }
  const Poly<B, 4> u_end = u + nn, w_end = w - nn;
  // b0, b1 strictly on one side of edge a's line (u and u + nn of one sign; nn ≥ 0), or a0, a1 of edge b's.
  if (all_positive(u) || all_negative(u_end) || all_negative(w) || all_positive(w_end)) return Verdict::separated;
  if (root && all_negative(u) && all_positive(u_end) && all_positive(w) && all_negative(w_end)) return Verdict::contact;
  // Only (nearly) parallel or degenerate edges make the sign tests blind; then try separating axes.
  return !all_positive(nn) && separated_along_axes(m, Ai, Bi, Ci) ? Verdict::separated : Verdict::unknown;
}

namespace {

/// Three times f's Bernstein coefficients on [tl, th], as intervals (the scaled form's ĉ_1, ĉ_2 are already
/// C(3, k) = 3 times theirs; the ends are multiplied to match): one positive factor, so the same signs, and the
/// form de Casteljau subdivides. From classify's Bounded arithmetic, so as tight as its sign test.
Poly<Interval, 3> coplanarity_coefficients(const RelativeMotion& m, double tl, double th) {
  const LinVecT<Bounded> A = on_window(m.a0, m.a1, tl, th), B = on_window(m.b0, m.b1, tl, th), C = on_window(m.c0, m.c1, tl, th);
  const Poly<Bounded, 3> f = dot(A, cross(B, C));
  return Poly<Interval, 3>{
      {Interval(3.0) * to_interval(f[0]), to_interval(f[1]), to_interval(f[2]), Interval(3.0) * to_interval(f[3])}};
}

/// de Casteljau at the window's midpoint: the coefficients of its left and right halves (a few additions).
std::pair<Poly<Interval, 3>, Poly<Interval, 3>> halves(const Poly<Interval, 3>& b) {
  const Interval m01 = half(b[0] + b[1]), m12 = half(b[1] + b[2]), m23 = half(b[2] + b[3]);
  const Interval m012 = half(m01 + m12), m123 = half(m12 + m23), mid = half(m012 + m123);
  return {Poly<Interval, 3>{{b[0], m01, m012, mid}}, Poly<Interval, 3>{{mid, m123, m23, b[3]}}};
}

/// classify's coplanarity-only verdict, from coefficients: f keeps one sign (separated), or its end values have
/// certain, opposite signs (contact: a root inside), or neither is proven.
Verdict sign_verdict(const Poly<Interval, 3>& b) {
  if (all_positive(b) || all_negative(b)) return Verdict::separated;
  const bool root = (b[0].certainly_negative() && b[3].certainly_positive()) ||
                    (b[0].certainly_positive() && b[3].certainly_negative());
  return root ? Verdict::contact : Verdict::unknown;
}

}  // namespace

bool for_each_coplanarity_window(const RelativeMotion& m, double tl, double th, double width,
                                 const std::function<bool(double, double)>& visit) {
  // f's coefficients on [tl, th] in double with their error bound, as intervals; then subdivision in intervals.
  struct Node {
    Poly<Interval, 3> b;
    double tl, th;
  };
  std::array<Node, 64> stack;
  int n = 0;
  stack[n++] = {coplanarity_coefficients(m, tl, th), tl, th};
  while (n > 0) {
    const Node node = stack[--n];
    if (all_positive(node.b) || all_negative(node.b)) continue;
    if (node.th - node.tl <= width || n + 2 > int(stack.size())) {
      if (visit(node.tl, node.th)) return true;
      continue;
    }
    const auto [left, right] = halves(node.b);
    const double tm = 0.5 * (node.tl + node.th);
    stack[n++] = {right, tm, node.th};
    stack[n++] = {left, node.tl, tm};
  }
  return false;
}

std::pair<double, double> narrow_root(const RelativeMotion& m, double a, double b) {
  Poly<Interval, 3> coefficients = coplanarity_coefficients(m, a, b);
  while (true) {
    const double mid = 0.5 * (a + b);
    if (!(mid > a && mid < b)) return {a, b};
    auto [left, right] = halves(coefficients);
    Verdict v = sign_verdict(left);
    if (v == Verdict::unknown) {
      // The subdivided bounds have widened past what they can prove: classify the half afresh, and go on from
      // fresh coefficients of the half it keeps.
      v = classify(m, a, mid, true);
      if (v == Verdict::unknown) return {a, b};
      if (v == Verdict::separated) right = coplanarity_coefficients(m, mid, b);
      else left = coplanarity_coefficients(m, a, mid);
    }
    if (v == Verdict::separated) a = mid, coefficients = right;
    else b = mid, coefficients = left;
  }
}

double earliest_coplanarity(const RelativeMotion& m, double tl, double th, double width) {
  double first = th;
  for_each_coplanarity_window(m, tl, th, width, [&](double a, double) {
    first = a;
    return true;
  });
  return first;
}

}  // namespace ccdlab::interval_ccd
