#pragma once
// Interval: a closed interval of doubles that encloses the exact result of every operation on it.
//
// Each operation is computed in the default round-to-nearest mode and its bounds are then pushed outward by
// at least one ulp (`widen_down` / `widen_up`; an underflowing product by the smallest subnormal). The exact result lies within half an ulp of the rounded one,
// so the widened interval contains it — without switching the FPU rounding mode, so it is safe under
// -march=native, FMA contraction (which only makes the rounded value more accurate) and OpenMP threads.
// Overflow gives ±inf bounds and inf − inf gives NaN; every `certainly_*` predicate is false on NaN, so an
// overflowing computation is "uncertain", never a wrong certainty.
#include <algorithm>
#include <cmath>
#include <limits>

namespace ccdlab {

namespace detail {
constexpr double kUlpFactor = 0x1p-52;  // ≥ ulp(x) / |x| for every normal x
/// A double ≤ x − ulp(x) for normal x (the rounding error of an operation is at most ulp(x) / 2). Subnormal
/// sums and differences are exact, so they need no widening; products that underflow are handled in
/// operator*. (Adding a constant "tiny" here instead would make exact zeros subnormal-sized intervals, and
/// arithmetic on subnormals costs ~100× on x86.)
inline double widen_down(double x) { return x - std::abs(x) * kUlpFactor; }
/// A double ≥ x + ulp(x) for normal x.
inline double widen_up(double x) { return x + std::abs(x) * kUlpFactor; }
/// Absolute error bound of a product p = a·b that may have underflowed: p is exact when a or b is zero;
/// otherwise a result below the normal range can be off by up to half the smallest subnormal.
inline double underflow_slack(double p, double a, double b) {
  return (std::abs(p) < std::numeric_limits<double>::min() && a != 0 && b != 0) ? std::numeric_limits<double>::denorm_min() : 0.0;
}
}  // namespace detail

struct Interval {
  double lo = 0, hi = 0;

  constexpr Interval() = default;
  constexpr Interval(double x) : lo(x), hi(x) {}  // NOLINT: an exact double is a point interval
  constexpr Interval(double l, double h) : lo(l), hi(h) {}

  [[nodiscard]] bool certainly_positive() const { return lo > 0; }
  [[nodiscard]] bool certainly_negative() const { return hi < 0; }
  [[nodiscard]] bool certainly_nonnegative() const { return lo >= 0; }
  [[nodiscard]] bool certainly_nonpositive() const { return hi <= 0; }
  [[nodiscard]] bool contains(double x) const { return lo <= x && x <= hi; }
};

inline Interval operator+(Interval a, Interval b) {
  return {detail::widen_down(a.lo + b.lo), detail::widen_up(a.hi + b.hi)};
}
inline Interval operator-(Interval a, Interval b) {
  return {detail::widen_down(a.lo - b.hi), detail::widen_up(a.hi - b.lo)};
}
inline Interval operator-(Interval a) { return {-a.hi, -a.lo}; }  // exact
inline Interval operator*(Interval a, Interval b) {
  const double p0 = a.lo * b.lo, p1 = a.lo * b.hi, p2 = a.hi * b.lo, p3 = a.hi * b.hi;
  const double lo = std::min(std::min(p0, p1), std::min(p2, p3)), hi = std::max(std::max(p0, p1), std::max(p2, p3));
  // Underflow can only occur where some product is tiny; then widen by the subnormal step (rare path).
  const double slack = std::max({detail::underflow_slack(p0, a.lo, b.lo), detail::underflow_slack(p1, a.lo, b.hi),
                                 detail::underflow_slack(p2, a.hi, b.lo), detail::underflow_slack(p3, a.hi, b.hi)});
  return {detail::widen_down(lo) - slack, detail::widen_up(hi) + slack};
}
/// Hull of two intervals.
inline Interval hull(Interval a, Interval b) { return {std::min(a.lo, b.lo), std::max(a.hi, b.hi)}; }

}  // namespace ccdlab
