#pragma once
// Interval: a closed interval of doubles that encloses the exact result of every operation on it.
//
// Each operation is computed in the default round-to-nearest mode and its bounds are then pushed outward by
// at least one ulp (`widen_down` / `widen_up`; a product bound below the normal range by the smallest subnormal). The exact result lies within half an ulp of the rounded one,
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
/// arithmetic on subnormals is very slow on x86.)
inline double widen_down(double x) { return x - std::abs(x) * kUlpFactor; }
/// A double ≥ x + ulp(x) for normal x.
inline double widen_up(double x) { return x + std::abs(x) * kUlpFactor; }
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
  // An exact zero stays exact (coordinates that do not move give many of them).
  if ((a.lo == 0 && a.hi == 0) || (b.lo == 0 && b.hi == 0)) return {0.0, 0.0};
  const double p0 = a.lo * b.lo, p1 = a.lo * b.hi, p2 = a.hi * b.lo, p3 = a.hi * b.hi;
  const double lo = std::min(std::min(p0, p1), std::min(p2, p3)), hi = std::max(std::max(p0, p1), std::max(p2, p3));
  Interval r{detail::widen_down(lo), detail::widen_up(hi)};
  // A bound below the normal range may come from a product that underflowed (error up to half the smallest
  // subnormal); a normal bound cannot (every product beyond it is normal, or tiny and inside it). Rare path.
  constexpr double kMin = std::numeric_limits<double>::min(), kSub = std::numeric_limits<double>::denorm_min();
  if (std::abs(lo) < kMin) r.lo -= kSub;
  if (std::abs(hi) < kMin) r.hi += kSub;
  return r;
}
/// Hull of two intervals.
inline Interval hull(Interval a, Interval b) { return {std::min(a.lo, b.lo), std::max(a.hi, b.hi)}; }

}  // namespace ccdlab
