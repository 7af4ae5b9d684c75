// Highway compiles this file once per SIMD target (foreach_target.h) and picks one at run time.
#include "strategies/testers/float_roots.hpp"

#include <algorithm>

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "strategies/testers/float_roots.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

HWY_BEFORE_NAMESPACE();
namespace ccdlab {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

template <class V>
struct Xyz {
  V x, y, z;
};

// Eigen's Vector3d arithmetic, written out in its order: cross by the textbook formula, dot left to right.
template <class V>
HWY_INLINE Xyz<V> Cross(const Xyz<V>& y, const Xyz<V>& z) {
  return {hn::Sub(hn::Mul(y.y, z.z), hn::Mul(y.z, z.y)), hn::Sub(hn::Mul(y.z, z.x), hn::Mul(y.x, z.z)),
          hn::Sub(hn::Mul(y.x, z.y), hn::Mul(y.y, z.x))};
}
template <class V>
HWY_INLINE V Dot(const Xyz<V>& x, const Xyz<V>& y) {
  return hn::Add(hn::Add(hn::Mul(x.x, y.x), hn::Mul(x.y, y.y)), hn::Mul(x.z, y.z));
}

/// A moving vector x0 + t·dx (Moving::at).
template <class V>
struct MovingV {
  Xyz<V> x0, dx;
  HWY_INLINE Xyz<V> at(V t) const {
    return {hn::Add(x0.x, hn::Mul(t, dx.x)), hn::Add(x0.y, hn::Mul(t, dx.y)), hn::Add(x0.z, hn::Mul(t, dx.z))};
  }
};

template <class V>
struct Cubic {
  MovingV<V> A, B, C;
  /// f(t) from the positions at t, as the scalar tester evaluates it.
  HWY_INLINE V operator()(V t) const { return Dot(A.at(t), Cross(B.at(t), C.at(t))); }
};

/// Roots in [0, 1] of a t² + b t + c (quadratic_roots in float_tester.cpp): r1, r2 with their validity masks.
template <class D, class V = hn::Vec<D>, class M = hn::Mask<D>>
HWY_INLINE void QuadraticRoots(D d, V a, V b, V c, V& r1, M& ok1, V& r2, M& ok2) {
  const V zero = hn::Zero(d);
  const V scale = hn::Max(hn::Max(hn::Abs(a), hn::Abs(b)), hn::Abs(c));
  const M any = hn::Ne(scale, zero);
  const V tiny = hn::Mul(hn::Set(d, 1e-14), scale);
  const M linear = hn::Le(hn::Abs(a), tiny);
  // Linear: one root −c/b when b is not negligible.
  const V lin_root = hn::Div(hn::Neg(c), b);
  const M lin_ok = hn::And(linear, hn::Gt(hn::Abs(b), tiny));
  // Quadratic: a slightly negative discriminant counts as zero.
  V disc = hn::Sub(hn::Mul(b, b), hn::Mul(hn::Mul(hn::Set(d, 4.0), a), c));
  const M negative = hn::Lt(disc, zero);
  const M clamp = hn::And(negative, hn::Gt(disc, hn::Mul(hn::Mul(hn::Set(d, -1e-12), b), b)));
  disc = hn::IfThenElse(clamp, zero, disc);
  const M quad_ok = hn::AndNot(linear, hn::Or(hn::Not(negative), clamp));
  const V q = hn::Mul(hn::Set(d, -0.5), hn::Add(b, hn::CopySign(hn::Sqrt(hn::IfThenElse(quad_ok, disc, zero)), b)));
  const V q_root1 = hn::Div(q, a), q_root2 = hn::Div(c, q);
  const M in1 = hn::Or(lin_ok, quad_ok), in2 = hn::AndNot(linear, hn::And(quad_ok, hn::Ne(q, zero)));
  r1 = hn::IfThenElse(linear, lin_root, q_root1);
  r2 = q_root2;
  const auto in_unit = [&](V r) { return hn::And(hn::Ge(r, zero), hn::Le(r, hn::Set(d, 1.0))); };
  ok1 = hn::And(any, hn::And(in1, in_unit(r1)));
  ok2 = hn::And(any, hn::And(in2, in_unit(r2)));
}

template <class V>
HWY_INLINE void SortPair(V& a, V& b) {
  const V lo = hn::Min(a, b);
  b = hn::Max(a, b), a = lo;
}

/// One vector of queries between the setup and the refinement: the cubic and the interval the Illinois loop
/// narrows, with the lane masks of the answer.
template <class D>
struct RootSearch {
  using V = hn::Vec<D>;
  using M = hn::Mask<D>;
  Cubic<V> f;
  V lo, hi, flo, fhi, side;  // side: −1 the last step moved lo; +1 hi
  M scalar, root, more, active, coplanar;
};

/// The cubic of rows [i, i + lanes) and what is decided before any breakpoint: coplanar motion, a NaN (left to
/// the scalar tester), and the Bernstein early out (no root, no touching point: `none`).
template <class D>
struct Coefficients {
  using V = hn::Vec<D>;
  using M = hn::Mask<D>;
  Cubic<V> f;
  V a, b, c, tol;
  M coplanar, scalar, decided;
};

template <class D>
HWY_INLINE Coefficients<D> CubicOf(D d, const double* columns, std::size_t stride, std::size_t i, double rel_tolerance) {
  using V = hn::Vec<D>;
  using M = hn::Mask<D>;
  const auto col = [&](int k) { return hn::LoadU(d, columns + stride * std::size_t(k) + i); };
  const auto xyz = [&](int k) { return Xyz<V>{col(k), col(k + 1), col(k + 2)}; };
  Coefficients<D> r;
  r.f = Cubic<V>{{xyz(CubicColumns::A0x), xyz(CubicColumns::dAx)},
                 {xyz(CubicColumns::B0x), xyz(CubicColumns::dBx)},
                 {xyz(CubicColumns::C0x), xyz(CubicColumns::dCx)}};
  const Cubic<V>& f = r.f;
  const V f_scale = col(CubicColumns::f_scale);
  const Xyz<V>&A0 = f.A.x0, &dA = f.A.dx, &B0 = f.B.x0, &dB = f.B.dx, &C0 = f.C.x0, &dC = f.C.dx;
  // The coefficients of f(t) = a t³ + b t² + c t + dd, in earliest_hit's order.
  const Xyz<V> B0C0 = Cross(B0, C0);
  const V dd = Dot(A0, B0C0);
  const V c = hn::Add(hn::Add(Dot(dA, B0C0), Dot(A0, Cross(dB, C0))), Dot(A0, Cross(B0, dC)));
  const V b = hn::Add(hn::Add(Dot(dA, Cross(dB, C0)), Dot(dA, Cross(B0, dC))), Dot(A0, Cross(dB, dC)));
  const V a = Dot(dA, Cross(dB, dC));
  const V big = hn::Max(hn::Max(hn::Abs(a), hn::Abs(b)), hn::Max(hn::Abs(c), hn::Abs(dd)));
  // Coplanar motion (its own search), or a NaN anywhere (the scalar tester decides).
  const M finite = hn::IsFinite(hn::Add(hn::Add(a, b), hn::Add(c, dd)));
  r.coplanar = hn::And(finite, hn::Le(big, hn::Mul(hn::Set(d, 1e-12), f_scale)));
  r.scalar = hn::Or(r.coplanar, hn::Not(finite));
  const V tol = hn::Mul(hn::Set(d, rel_tolerance), f_scale);
  const V neg_tol = hn::Neg(tol);
  // Bernstein early out: all four coefficients beyond ±tol on one side.
  const V three = hn::Set(d, 3.0);
  const V b0 = dd, b1 = hn::Add(dd, hn::Div(c, three)),
          b2 = hn::Add(dd, hn::Div(hn::Add(hn::Mul(hn::Set(d, 2.0), c), b), three)),
          b3 = hn::Add(hn::Add(hn::Add(dd, c), b), a);
  const M above = hn::And(hn::And(hn::Gt(b0, tol), hn::Gt(b1, tol)), hn::And(hn::Gt(b2, tol), hn::Gt(b3, tol)));
  const M below =
      hn::And(hn::And(hn::Lt(b0, neg_tol), hn::Lt(b1, neg_tol)), hn::And(hn::Lt(b2, neg_tol), hn::Lt(b3, neg_tol)));
  r.decided = hn::Or(r.scalar, hn::Or(above, below));
  r.a = a, r.b = b, r.c = c, r.tol = tol;
  return r;
}

/// The setup of rows [i, i + lanes): coefficients, early outs, breakpoints and the first event among them.
template <class D>
HWY_INLINE RootSearch<D> StartSearch(D d, const double* columns, std::size_t stride, std::size_t i, double rel_tolerance,
                                     hn::Vec<D> skip) {
  using V = hn::Vec<D>;
  using M = hn::Mask<D>;
  const V zero = hn::Zero(d), one = hn::Set(d, 1.0), inf = hn::Set(d, HUGE_VAL), three = hn::Set(d, 3.0);
  const Coefficients<D> cubic = CubicOf(d, columns, stride, i, rel_tolerance);
  RootSearch<D> r;
  r.f = cubic.f;
  r.coplanar = cubic.coplanar;
  const Cubic<V>& f = r.f;
  const V a = cubic.a, b = cubic.b, c = cubic.c, tol = cubic.tol;
  M scalar = cubic.scalar;
  const M decided = cubic.decided;
  const M none = hn::Ne(zero, zero);
  if (hn::AllTrue(d, decided)) {  // no lane needs its breakpoints (resting contacts tested with thickness, often)
    r.lo = r.hi = r.flo = r.fhi = r.side = zero;
    r.scalar = scalar, r.root = r.more = r.active = none;
    return r;
  }
  // Breakpoints: 0, 1 and the roots of f′ = 3a t² + 2b t + c in [0, 1], sorted; a missing root sorts last as +∞.
  V r1, r2;
  M ok1, ok2;
  QuadraticRoots(d, hn::Mul(three, a), hn::Mul(hn::Set(d, 2.0), b), c, r1, ok1, r2, ok2);
  // A root at ±0 ties with the breakpoint 0 but may differ from it in sign; which one std::sort puts first is
  // not worth mirroring: such a lane goes to the scalar tester.
  scalar = hn::Or(scalar, hn::Or(hn::And(ok1, hn::Eq(r1, zero)), hn::And(ok2, hn::Eq(r2, zero))));
  V s[4] = {zero, one, hn::IfThenElse(ok1, r1, inf), hn::IfThenElse(ok2, r2, inf)};
  SortPair(s[0], s[1]), SortPair(s[2], s[3]), SortPair(s[0], s[2]), SortPair(s[1], s[3]), SortPair(s[1], s[2]);
  M exists[4];
  V value[4];
  for (int k = 0; k < 4; ++k) {
    exists[k] = hn::Ne(s[k], inf);
    value[k] = f(hn::IfThenElse(exists[k], s[k], zero));
  }
  // The events in order, as the scalar loop meets them: at each breakpoint, f touching zero there (the candidate
  // is the breakpoint itself: lo = hi, nothing to refine), then a sign change up to the next one (a root, refined).
  // The lane's candidate is its event number `skip` (0: the first); any event after it sets `more`.
  const M open = hn::Not(hn::Or(decided, scalar));
  M chosen = none, more = none;
  V seen = zero;  // events met so far
  V lo = zero, hi = zero, flo = zero, fhi = zero;
  for (int k = 0; k < 4; ++k) {
    const M touch = hn::And(open, hn::And(exists[k], hn::Le(hn::Abs(value[k]), tol)));
    more = hn::Or(more, hn::And(chosen, touch));
    const M touch_chosen = hn::And(touch, hn::Eq(seen, skip));
    lo = hn::IfThenElse(touch_chosen, s[k], lo), hi = hn::IfThenElse(touch_chosen, s[k], hi);
    chosen = hn::Or(chosen, touch_chosen);
    seen = hn::Add(seen, hn::IfThenElseZero(touch, one));
    if (k + 1 == 4) break;
    const V u = value[k], w = value[k + 1];
    const M sign = hn::Or(hn::And(hn::Lt(u, zero), hn::Gt(w, zero)), hn::And(hn::Gt(u, zero), hn::Lt(w, zero)));
    const M change = hn::And(open, hn::And(exists[k + 1], sign));
    more = hn::Or(more, hn::And(chosen, change));
    const M change_chosen = hn::And(change, hn::Eq(seen, skip));
    lo = hn::IfThenElse(change_chosen, s[k], lo), hi = hn::IfThenElse(change_chosen, s[k + 1], hi);
    flo = hn::IfThenElse(change_chosen, value[k], flo), fhi = hn::IfThenElse(change_chosen, value[k + 1], fhi);
    chosen = hn::Or(chosen, change_chosen);
    seen = hn::Add(seen, hn::IfThenElseZero(change, one));
  }
  const M root = chosen;
  r.lo = lo, r.hi = hi, r.flo = flo, r.fhi = fhi, r.side = zero;
  r.scalar = scalar, r.root = root, r.more = more;
  r.active = hn::And(root, hn::Gt(hn::Sub(hi, lo), hn::Set(d, kIllinoisWidth)));
  return r;
}

/// One Illinois false-position step on the active lanes, as the scalar loop takes it.
template <class D>
HWY_INLINE void IllinoisStep(D d, RootSearch<D>& r) {
  using V = hn::Vec<D>;
  using M = hn::Mask<D>;
  const V zero = hn::Zero(d), one = hn::Set(d, 1.0), half = hn::Set(d, 0.5), minus_one = hn::Set(d, -1.0);
  V t = hn::Div(hn::Sub(hn::Mul(r.lo, r.fhi), hn::Mul(r.hi, r.flo)), hn::Sub(r.fhi, r.flo));
  t = hn::IfThenElse(hn::And(hn::Ge(t, r.lo), hn::Le(t, r.hi)), t, hn::Mul(half, hn::Add(r.lo, r.hi)));
  const V guard = hn::Set(d, kIllinoisGuard);
  t = hn::Min(hn::Max(t, hn::Add(r.lo, guard)), hn::Sub(r.hi, guard));
  const V ft = r.f(t);
  const M exact = hn::And(r.active, hn::Eq(ft, zero));
  const M moves = hn::AndNot(exact, r.active);
  const M same = hn::Not(hn::Xor(hn::Lt(ft, zero), hn::Lt(r.flo, zero)));
  const M move_lo = hn::And(moves, same), move_hi = hn::AndNot(same, moves);
  // lo side: lo = t, flo = ft, and fhi halves when lo moved last time too.
  r.fhi = hn::IfThenElse(hn::And(move_lo, hn::Eq(r.side, minus_one)), hn::Mul(r.fhi, half), r.fhi);
  // hi side: hi = t, fhi = ft, and flo (the old one) halves when hi moved last time too.
  r.flo = hn::IfThenElse(hn::And(move_hi, hn::Eq(r.side, one)), hn::Mul(r.flo, half), r.flo);
  r.lo = hn::IfThenElse(hn::Or(move_lo, exact), t, r.lo), r.flo = hn::IfThenElse(move_lo, ft, r.flo);
  r.hi = hn::IfThenElse(hn::Or(move_hi, exact), t, r.hi), r.fhi = hn::IfThenElse(move_hi, ft, r.fhi);
  r.side = hn::IfThenElse(move_lo, minus_one, hn::IfThenElse(move_hi, one, r.side));
  r.active = hn::AndNot(exact, hn::And(r.active, hn::Gt(hn::Sub(r.hi, r.lo), hn::Set(d, kIllinoisWidth))));
}

void FirstCoplanarRoots(const double* columns, std::size_t stride, std::size_t n, double rel_tolerance,
                        const std::uint8_t* skip, FirstRoot* kind, double* t_out, std::uint8_t* more_out) {
  using D = hn::ScalableTag<double>;
  const D d;
  const std::size_t N = hn::Lanes(d);
  // kGroup vectors refine side by side: a step's divide and cubic form one long dependency chain, and
  // independent chains fill its latency. Every lane runs the same operations as alone, so the answers do not
  // depend on the grouping.
  constexpr std::size_t kGroup = 2;
  for (std::size_t i = 0; i < n; i += kGroup * N) {
    const std::size_t group = std::min(kGroup, (n - i + N - 1) / N);
    RootSearch<D> r[kGroup];
    for (std::size_t g = 0; g < kGroup; ++g) {
      const std::size_t base = i + (g < group ? g : 0) * N;
      HWY_ALIGN double skip_lanes[HWY_MAX_BYTES / sizeof(double)] = {};
      if (skip)
        for (std::size_t j = 0; j < N && base + j < n; ++j) skip_lanes[j] = skip[base + j];
      r[g] = StartSearch(d, columns, stride, base, rel_tolerance, hn::Load(d, skip_lanes));
    }
    for (std::size_t g = group; g < kGroup; ++g) r[g].active = hn::Ne(hn::Zero(d), hn::Zero(d));
    for (int it = 0; it < kIllinoisSteps; ++it) {
      bool any = false;
      for (std::size_t g = 0; g < kGroup; ++g) any |= !hn::AllFalse(d, r[g].active);
      if (!any) break;
      for (std::size_t g = 0; g < kGroup; ++g) IllinoisStep(d, r[g]);
    }
    // Per lane: scalar wins over everything, then root; the rest has no candidate at all.
    for (std::size_t g = 0; g < group; ++g) {
      const auto zero = hn::Zero(d), one = hn::Set(d, 1.0);
      HWY_ALIGN double t_lanes[HWY_MAX_BYTES / sizeof(double)];
      HWY_ALIGN double kind_lanes[HWY_MAX_BYTES / sizeof(double)];
      HWY_ALIGN double more_lanes[HWY_MAX_BYTES / sizeof(double)];
      hn::Store(hn::Mul(hn::Set(d, 0.5), hn::Add(r[g].lo, r[g].hi)), d, t_lanes);
      const auto kind_of = hn::IfThenElse(r[g].scalar, hn::Set(d, 2.0), hn::IfThenElse(r[g].root, one, zero));
      hn::Store(hn::IfThenElse(r[g].coplanar, hn::Set(d, 3.0), kind_of), d, kind_lanes);
      hn::Store(hn::IfThenElse(r[g].more, one, zero), d, more_lanes);
      const std::size_t base = i + g * N;
      for (std::size_t j = 0; j < N && base + j < n; ++j) {
        kind[base + j] = FirstRoot(int(kind_lanes[j]));
        t_out[base + j] = t_lanes[j];
        more_out[base + j] = std::uint8_t(more_lanes[j] != 0);
      }
    }
  }
}

template <class V>
HWY_INLINE Xyz<V> Minus(const Xyz<V>& a, const Xyz<V>& b) { return {hn::Sub(a.x, b.x), hn::Sub(a.y, b.y), hn::Sub(a.z, b.z)}; }
/// a + s·b, Eigen's `a + s * b`.
template <class V>
HWY_INLINE Xyz<V> PlusScaled(const Xyz<V>& a, V s, const Xyz<V>& b) {
  return {hn::Add(a.x, hn::Mul(s, b.x)), hn::Add(a.y, hn::Mul(s, b.y)), hn::Add(a.z, hn::Mul(s, b.z))};
}
/// std::clamp(x, 0, 1).
template <class D, class V = hn::Vec<D>>
HWY_INLINE V Clamp01(D d, V x) {
  const V zero = hn::Zero(d), one = hn::Set(d, 1.0);
  return hn::IfThenElse(hn::Lt(x, zero), zero, hn::IfThenElse(hn::Lt(one, x), one, x));
}

/// Point k of rows [i, i + lanes) of PointColumns, moving: Pk + t·dPk.
template <class D, class V = hn::Vec<D>>
HWY_INLINE MovingV<V> MovingPoint(D d, const double* columns, std::size_t stride, std::size_t i, int k) {
  const auto col = [&](int c) { return hn::LoadU(d, columns + stride * std::size_t(c) + i); };
  const int c = PointColumns::P0x + 6 * k;
  return {{col(c), col(c + 1), col(c + 2)}, {col(c + 3), col(c + 4), col(c + 5)}};
}

/// One vector of rows' four points at their time, and what the verdicts need.
template <class D, class V = hn::Vec<D>>
struct PointsAt {
  Xyz<V> p[4];
  V reach;
  HWY_INLINE PointsAt(D d, const double* columns, std::size_t stride, std::size_t i) {
    const auto col = [&](int k) { return hn::LoadU(d, columns + stride * std::size_t(k) + i); };
    const V t = col(PointColumns::t);
    for (int k = 0; k < 4; ++k) p[k] = MovingPoint(d, columns, stride, i, k).at(t);
    reach = col(PointColumns::reach);
  }
};

/// One vector of rows' closest points: squared distance, coordinates (CcdHit::coords) and the lanes left to the
/// scalar function.
template <class D, class V = hn::Vec<D>, class M = hn::Mask<D>>
struct ClosestAt {
  M scalar;
  V distance_sq, u, v;
};

/// closest_point_triangle (distance.cpp) of p[0] and the triangle p[1] p[2] p[3]: every Voronoi region of the
/// triangle (Ericson 5.1.5) computed and the first that holds, in the scalar code's order, taken per lane.
template <class D, class V = hn::Vec<D>>
HWY_INLINE ClosestAt<D> PointTriangle(D d, const Xyz<V> (&pts)[4]) {
  const V zero = hn::Zero(d), one = hn::Set(d, 1.0);
  const Xyz<V>&p = pts[0], &a = pts[1], &b = pts[2], &c = pts[3];
  const Xyz<V> ab = Minus(b, a), ac = Minus(c, a), bc = Minus(c, b);
  const Xyz<V> nrm = Cross(ab, ac);
  const V scale = hn::Max(hn::Max(Dot(ab, ab), Dot(ac, ac)), Dot(bc, bc));
  ClosestAt<D> out;
  out.scalar = hn::Le(Dot(nrm, nrm), hn::Mul(hn::Mul(hn::Set(d, 1e-24), scale), scale));  // degenerate triangle
  out.scalar = hn::Or(out.scalar, hn::Not(hn::IsFinite(scale)));  // std::max's NaN order is not Max's
  const Xyz<V> ap = Minus(p, a), bp = Minus(p, b), cp = Minus(p, c);
  const V d1 = Dot(ab, ap), d2 = Dot(ac, ap), d3 = Dot(ab, bp), d4 = Dot(ac, bp), d5 = Dot(ab, cp), d6 = Dot(ac, cp);
  const V vc = hn::Sub(hn::Mul(d1, d4), hn::Mul(d3, d2)), vb = hn::Sub(hn::Mul(d5, d2), hn::Mul(d1, d6)),
          va = hn::Sub(hn::Mul(d3, d6), hn::Mul(d5, d4));
  // The face's interior, then each region above it in reverse order, so that the first that holds wins.
  const V denom = hn::Div(one, hn::Add(hn::Add(va, vb), vc));
  V& u = out.u;
  V& v = out.v;
  V& dist = out.distance_sq;
  u = hn::Mul(vb, denom), v = hn::Mul(vc, denom);
  dist = [&] { const Xyz<V> q = Minus(p, PlusScaled(PlusScaled(a, u, ab), v, ac)); return Dot(q, q); }();
  const auto take = [&](auto holds, V dist_k, V u_k, V v_k) {
    dist = hn::IfThenElse(holds, dist_k, dist), u = hn::IfThenElse(holds, u_k, u), v = hn::IfThenElse(holds, v_k, v);
  };
  const V d43 = hn::Sub(d4, d3), d56 = hn::Sub(d5, d6);
  {  // edge bc
    const V w = hn::Div(d43, hn::Add(d43, d56));
    const Xyz<V> q = Minus(p, PlusScaled(b, w, bc));
    take(hn::And(hn::Le(va, zero), hn::And(hn::Ge(d43, zero), hn::Ge(d56, zero))), Dot(q, q), hn::Sub(one, w), w);
  }
  {  // edge ac
    const V w = hn::Div(d2, hn::Sub(d2, d6));
    const Xyz<V> q = Minus(p, PlusScaled(a, w, ac));
    take(hn::And(hn::Le(vb, zero), hn::And(hn::Ge(d2, zero), hn::Le(d6, zero))), Dot(q, q), zero, w);
  }
  take(hn::And(hn::Ge(d6, zero), hn::Le(d5, d6)), Dot(cp, cp), zero, one);  // vertex c
  {  // edge ab
    const V w = hn::Div(d1, hn::Sub(d1, d3));
    const Xyz<V> q = Minus(p, PlusScaled(a, w, ab));
    take(hn::And(hn::Le(vc, zero), hn::And(hn::Ge(d1, zero), hn::Le(d3, zero))), Dot(q, q), w, zero);
  }
  take(hn::And(hn::Ge(d3, zero), hn::Le(d4, d3)), Dot(bp, bp), one, zero);  // vertex b
  take(hn::And(hn::Le(d1, zero), hn::Le(d2, zero)), Dot(ap, ap), zero, zero);  // vertex a
  return out;
}

/// closest_segment_segment (distance.cpp) of p[0] p[1] and p[2] p[3] where both segments have length, parallel
/// ones included (edges of stacked cloth layers often are); point-like segments are left to it.
template <class D, class V = hn::Vec<D>>
HWY_INLINE ClosestAt<D> SegmentSegment(D d, const Xyz<V> (&pts)[4]) {
  using M = hn::Mask<D>;
  const V zero = hn::Zero(d), one = hn::Set(d, 1.0);
  const Xyz<V>&p0 = pts[0], &p1 = pts[1], &q0 = pts[2], &q1 = pts[3];
  const Xyz<V> d1 = Minus(p1, p0), d2 = Minus(q1, q0), rr = Minus(p0, q0);
  const V a = Dot(d1, d1), e = Dot(d2, d2), f = Dot(d2, rr), c = Dot(d1, rr), b = Dot(d1, d2);
  const V denom = hn::Sub(hn::Mul(a, e), hn::Mul(b, b));
  const M parallel = hn::Not(hn::Gt(denom, hn::Mul(hn::Mul(hn::Set(d, 1e-14), a), e)));
  ClosestAt<D> out;
  out.scalar = hn::Or(hn::Or(hn::Eq(a, zero), hn::Eq(e, zero)), hn::Not(hn::IsFinite(denom)));  // and NaN, overflow
  V s = hn::IfThenElse(parallel, zero, Clamp01(d, hn::Div(hn::Sub(hn::Mul(b, f), hn::Mul(c, e)), denom)));
  V t = hn::Div(hn::Add(hn::Mul(b, s), f), e);
  const auto below = hn::Lt(t, zero), above = hn::AndNot(below, hn::Gt(t, one));
  s = hn::IfThenElse(below, Clamp01(d, hn::Div(hn::Neg(c), a)), hn::IfThenElse(above, Clamp01(d, hn::Div(hn::Sub(b, c), a)), s));
  t = hn::IfThenElse(below, zero, hn::IfThenElse(above, one, t));
  const auto gap_sq = [&](V s_, V t_) {
    const Xyz<V> q = Minus(PlusScaled(p0, s_, d1), PlusScaled(q0, t_, d2));
    return Dot(q, q);
  };
  if (!hn::AllFalse(d, parallel)) {
    // Parallel: each end point against the other segment too, in the scalar function's order; a candidate
    // replaces the best only when strictly closer.
    V best = gap_sq(s, t);
    const auto try_point = [&](const Xyz<V>& p, const Xyz<V>& o, const Xyz<V>& dir, V dd, bool on_p, V fixed) {
      const V u = Clamp01(d, hn::Div(Dot(Minus(p, o), dir), dd));
      const Xyz<V> g = Minus(PlusScaled(o, u, dir), p);
      const M closer = hn::And(parallel, hn::Lt(Dot(g, g), best));
      best = hn::IfThenElse(closer, Dot(g, g), best);
      s = hn::IfThenElse(closer, on_p ? u : fixed, s);
      t = hn::IfThenElse(closer, on_p ? fixed : u, t);
    };
    try_point(q0, p0, d1, a, true, zero);
    try_point(q1, p0, d1, a, true, one);
    try_point(p0, q0, d2, e, false, zero);
    try_point(p1, q0, d2, e, false, one);
  }
  out.distance_sq = gap_sq(s, t), out.u = s, out.v = t;
  return out;
}

/// The verdicts and coordinates of rows [0, n): `closest` per vector of rows, compared with the reach.
template <class Closest>
HWY_INLINE void AtTimes(const double* columns, std::size_t stride, std::size_t n, AtTime* verdict, double* coords,
                        Closest closest) {
  using D = hn::ScalableTag<double>;
  const D d;
  const std::size_t N = hn::Lanes(d);
  for (std::size_t i = 0; i < n; i += N) {
    const PointsAt<D> r(d, columns, stride, i);
    const ClosestAt<D> c = closest(d, r.p);
    const auto hit = hn::AndNot(c.scalar, hn::Le(c.distance_sq, hn::Mul(r.reach, r.reach)));
    HWY_ALIGN double k[HWY_MAX_BYTES / sizeof(double)], u[HWY_MAX_BYTES / sizeof(double)], v[HWY_MAX_BYTES / sizeof(double)];
    hn::Store(hn::IfThenElse(c.scalar, hn::Set(d, 2.0), hn::IfThenElseZero(hit, hn::Set(d, 1.0))), d, k);
    hn::Store(c.u, d, u), hn::Store(c.v, d, v);
    for (std::size_t j = 0; j < N && i + j < n; ++j) {
      verdict[i + j] = AtTime(int(k[j]));
      coords[2 * (i + j)] = u[j], coords[2 * (i + j) + 1] = v[j];
    }
  }
}

/// Roots in [0, 1] of g(t) = n · ((p − a) × (b − a)): where point p crosses the line (a, b) in the plane of normal
/// n (crossing_times in float_tester.cpp, its operations in its order).
template <class D, class V = hn::Vec<D>, class M = hn::Mask<D>>
HWY_INLINE void CrossingTimes(D d, const MovingV<V>& p, const MovingV<V>& a, const MovingV<V>& b, const Xyz<V>& n, V& r1,
                              M& ok1, V& r2, M& ok2) {
  const Xyz<V> r0 = Minus(p.x0, a.x0), dr = Minus(p.dx, a.dx), e0 = Minus(b.x0, a.x0), de = Minus(b.dx, a.dx);
  const Xyz<V> drxe0 = Cross(dr, e0), r0xde = Cross(r0, de);
  const V c = Dot(n, Cross(r0, e0));
  const V bq = Dot(n, Xyz<V>{hn::Add(drxe0.x, r0xde.x), hn::Add(drxe0.y, r0xde.y), hn::Add(drxe0.z, r0xde.z)});
  const V aq = Dot(n, Cross(dr, de));
  QuadraticRoots(d, aq, bq, c, r1, ok1, r2, ok2);
}

void CoplanarTimes(const double* points, std::size_t stride, std::size_t n, PointPairing pairing, double* times,
                   std::uint8_t* scalar_out) {
  using D = hn::ScalableTag<double>;
  using V = hn::Vec<D>;
  using M = hn::Mask<D>;
  const D d;
  // Which point crosses which line (PointColumns' point numbers), as VfMotion::crossings and EeMotion::crossings.
  constexpr int kVf[3][3] = {{0, 1, 2}, {0, 2, 3}, {0, 3, 1}}, kEe[4][3] = {{0, 2, 3}, {1, 2, 3}, {2, 0, 1}, {3, 0, 1}};
  const bool vf = pairing == PointPairing::vertex_face;
  const int crossings = vf ? 3 : 4;
  const V zero = hn::Zero(d), one = hn::Set(d, 1.0), inf = hn::Set(d, HUGE_VAL);
  for (std::size_t i = 0; i < n; i += hn::Lanes(d)) {
    MovingV<V> P[4];
    for (int k = 0; k < 4; ++k) P[k] = MovingPoint(d, points, stride, i, k);
    int slot = 0;
    const auto put = [&](V t) { hn::StoreU(t, d, times + stride * std::size_t(slot++) + i); };
    put(zero), put(one);
    M scalar = hn::Ne(zero, zero);
    for (const double end : {0.0, 1.0}) {
      const V t = hn::Set(d, end);
      Xyz<V> at[4];
      for (int k = 0; k < 4; ++k) at[k] = P[k].at(t);
      // plane_normal: the largest of the three cross products of differences from the first point, the first
      // of equals; none (all collinear) is the scalar tester's to handle.
      Xyz<V> normal{zero, zero, zero};
      V normal_sq = zero;
      constexpr int kPairs[3][2] = {{1, 2}, {1, 3}, {2, 3}};
      for (const auto& pair : kPairs) {
        const Xyz<V> c = Cross(Minus(at[pair[0]], at[0]), Minus(at[pair[1]], at[0]));
        const V c_sq = Dot(c, c);
        const M larger = hn::Gt(c_sq, normal_sq);
        normal = {hn::IfThenElse(larger, c.x, normal.x), hn::IfThenElse(larger, c.y, normal.y),
                  hn::IfThenElse(larger, c.z, normal.z)};
        normal_sq = hn::IfThenElse(larger, c_sq, normal_sq);
      }
      scalar = hn::Or(scalar, hn::Eq(normal_sq, zero));
      const auto& lines = vf ? kVf : kEe;
      for (int c = 0; c < crossings; ++c) {
        V r1, r2;
        M ok1, ok2;
        CrossingTimes(d, P[lines[c][0]], P[lines[c][1]], P[lines[c][2]], normal, r1, ok1, r2, ok2);
        scalar = hn::Or(scalar, hn::Or(hn::And(ok1, hn::Eq(r1, zero)), hn::And(ok2, hn::Eq(r2, zero))));
        put(hn::IfThenElse(ok1, r1, inf)), put(hn::IfThenElse(ok2, r2, inf));
      }
    }
    while (slot < kCoplanarSlots) put(inf);
    HWY_ALIGN double flag[HWY_MAX_BYTES / sizeof(double)];
    hn::Store(hn::IfThenElseZero(scalar, one), d, flag);
    for (std::size_t j = 0; j < hn::Lanes(d) && i + j < n; ++j) scalar_out[i + j] = std::uint8_t(flag[j] != 0);
  }
}

void CubicColumnsFromPoints(const double* points, std::size_t stride, std::size_t n, PointPairing pairing, double* cubic) {
  using D = hn::ScalableTag<double>;
  const D d;
  // Each vector of the cubic: which point minus which (PointColumns' point numbers).
  constexpr int kVf[3][2] = {{0, 1}, {2, 1}, {3, 1}}, kEe[3][2] = {{2, 0}, {1, 0}, {3, 2}};
  const auto& from = pairing == PointPairing::vertex_face ? kVf : kEe;
  for (std::size_t i = 0; i < n; i += hn::Lanes(d)) {
    const auto col = [&](int k) { return hn::LoadU(d, points + stride * std::size_t(k) + i); };
    const auto put = [&](int k, hn::Vec<D> v) { hn::StoreU(v, d, cubic + stride * std::size_t(k) + i); };
    for (int vec = 0; vec < 3; ++vec)
      for (int c = 0; c < 6; ++c)  // x0 then dx, each x y z
        put(CubicColumns::A0x + 6 * vec + c,
            hn::Sub(col(PointColumns::P0x + 6 * from[vec][0] + c), col(PointColumns::P0x + 6 * from[vec][1] + c)));
    const auto L = col(PointColumns::extent);
    put(CubicColumns::f_scale, hn::Mul(hn::Mul(L, L), L));
  }
}

void VertexFacesAt(const double* columns, std::size_t stride, std::size_t n, AtTime* verdict, double* coords) {
  AtTimes(columns, stride, n, verdict, coords, [](auto d, const auto& p) { return PointTriangle(d, p); });
}

void EdgeEdgesAt(const double* columns, std::size_t stride, std::size_t n, AtTime* verdict, double* coords) {
  AtTimes(columns, stride, n, verdict, coords, [](auto d, const auto& p) { return SegmentSegment(d, p); });
}

}  // namespace HWY_NAMESPACE
}  // namespace ccdlab
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace ccdlab {

HWY_EXPORT(FirstCoplanarRoots);

void first_coplanar_roots(const double* columns, std::size_t stride, std::size_t n, double rel_tolerance,
                          FirstRoot* kind, double* t, std::uint8_t* more, const std::uint8_t* skip) {
  if (n == 0) return;
  HWY_DYNAMIC_DISPATCH(FirstCoplanarRoots)(columns, stride, n, rel_tolerance, skip, kind, t, more);
}

HWY_EXPORT(CubicColumnsFromPoints);
HWY_EXPORT(CoplanarTimes);
HWY_EXPORT(VertexFacesAt);
HWY_EXPORT(EdgeEdgesAt);

void cubic_columns(const double* points, std::size_t stride, std::size_t n, PointPairing pairing, double* cubic) {
  if (n > 0) HWY_DYNAMIC_DISPATCH(CubicColumnsFromPoints)(points, stride, n, pairing, cubic);
}

void coplanar_times(const double* points, std::size_t stride, std::size_t n, PointPairing pairing, double* times,
                    std::uint8_t* scalar) {
  if (n > 0) HWY_DYNAMIC_DISPATCH(CoplanarTimes)(points, stride, n, pairing, times, scalar);
}

void vertex_faces_at(const double* columns, std::size_t stride, std::size_t n, AtTime* verdict, double* coords) {
  if (n > 0) HWY_DYNAMIC_DISPATCH(VertexFacesAt)(columns, stride, n, verdict, coords);
}

void edge_edges_at(const double* columns, std::size_t stride, std::size_t n, AtTime* verdict, double* coords) {
  if (n > 0) HWY_DYNAMIC_DISPATCH(EdgeEdgesAt)(columns, stride, n, verdict, coords);
}

}  // namespace ccdlab
#endif  // HWY_ONCE
