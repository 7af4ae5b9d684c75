// Highway compiles this file once per SIMD target (foreach_target.h) and picks one at run time. The SIMD kernel
// and the plain reference below evaluate the same expressions in the same order (-ffp-contract=off).
#include "framework/narrow/split_filter.hpp"

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "framework/narrow/split_filter.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

#ifndef CCDLAB_SPLIT_FILTER_CONSTANTS
#define CCDLAB_SPLIT_FILTER_CONSTANTS
namespace ccdlab::split_detail {
constexpr int kMaxWindows = 1 << kSplitLevels;
constexpr std::uint16_t kFirstHalf = (1u << (kMaxWindows / 2)) - 1;  // the sixteenths of [0, 1/2]
constexpr double kU = 0x1p-53;
constexpr double kCoefSlack = 18 * kU;     // ÷3 and four halvings, relative to max|b|
constexpr double kThresholdSlack = 1 + 4 * kU;
constexpr double kPadSlack = 32 * kU;      // positions at k/16 in the moving frame, relative to M
}  // namespace ccdlab::split_detail
#endif

HWY_BEFORE_NAMESPACE();
namespace ccdlab {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;
using namespace split_detail;

/// One vector of rows: the relative points at t0 (p) and their motion (m), f's whole-step Bernstein coefficients
/// (b), the sign test's threshold (t) and the boxes' pad.
template <class D, class V = hn::Vec<D>>
struct SplitRows {
  V p[9], m[9], b[4], t, neg_t, pad;

  HWY_INLINE SplitRows(D d, const double* const* col, const double* const* res, std::size_t i) {
    auto load = [&](int c) { return hn::LoadU(d, col[c] + i); };
    for (int k = 0; k < 3; ++k) {  // A, B, C of stage 2
      const V a0 = load(PlaneBatch::A0x + k), a1 = load(PlaneBatch::A1x + k);
      const V b0 = load(PlaneBatch::B0x + k), b1 = load(PlaneBatch::B1x + k);
      const V c0 = load(PlaneBatch::C0x + k), c1 = load(PlaneBatch::C1x + k);
      p[k] = a0, p[3 + k] = b0, p[6 + k] = c0;
      m[k] = hn::Sub(a1, a0), m[3 + k] = hn::Sub(b1, b0), m[6 + k] = hn::Sub(c1, c0);
    }
    const V zero = hn::Zero(d), third = hn::Set(d, 3.0);
    V M = zero;
    for (int k = 0; k < 9; ++k) M = hn::Max(M, hn::Max(hn::Abs(p[k]), hn::Abs(hn::Add(p[k], m[k]))));
    b[0] = hn::LoadU(d, res[PlaneBatch::Q0] + i), b[1] = hn::Div(hn::LoadU(d, res[PlaneBatch::Q1x3] + i), third);
    b[2] = hn::Div(hn::LoadU(d, res[PlaneBatch::Q2x3] + i), third), b[3] = hn::LoadU(d, res[PlaneBatch::Q3] + i);
    const V bmax = hn::Max(hn::Max(hn::Abs(b[0]), hn::Abs(b[1])), hn::Max(hn::Abs(b[2]), hn::Abs(b[3])));
    t = hn::Add(hn::Mul(hn::LoadU(d, res[PlaneBatch::Threshold] + i), hn::Set(d, kThresholdSlack)),
                hn::Mul(hn::Set(d, kCoefSlack), bmax));
    neg_t = hn::Neg(t);
    pad = hn::Add(hn::Add(hn::Mul(hn::LoadU(d, res[PlaneBatch::Reach] + i), hn::Set(d, 1 + 1e-12)),
                          hn::Mul(hn::Set(d, kPadSlack), M)),
                  hn::Set(d, 1e-300));
  }

  /// The points at time s (per lane): p + s·m.
  HWY_INLINE void at(V s, V (&x)[9]) const {
    for (int k = 0; k < 9; ++k) x[k] = hn::Add(p[k], hn::Mul(s, m[k]));
  }

  /// Whether the window with coefficients c, from points `prev` to `next`, is proven apart.
  template <bool kVf>
  HWY_INLINE auto apart(D d, const V (&c)[4], const V (&prev)[9], const V (&next)[9]) const {
    const V zero = hn::Zero(d);
    auto sign = hn::Or(hn::And(hn::And(hn::Gt(c[0], t), hn::Gt(c[1], t)), hn::And(hn::Gt(c[2], t), hn::Gt(c[3], t))),
                       hn::And(hn::And(hn::Lt(c[0], neg_t), hn::Lt(c[1], neg_t)),
                               hn::And(hn::Lt(c[2], neg_t), hn::Lt(c[3], neg_t))));
    for (int k = 0; k < 3; ++k) {
      const V a0 = prev[k], a1 = next[k], b0 = prev[3 + k], b1 = next[3 + k], c0 = prev[6 + k], c1 = next[6 + k];
      V lo1, hi1, lo2, hi2;
      if constexpr (kVf) {  // vertex A against face {0, B, C}
        lo1 = hn::Min(a0, a1), hi1 = hn::Max(a0, a1);
        lo2 = hn::Min(zero, hn::Min(hn::Min(b0, b1), hn::Min(c0, c1)));
        hi2 = hn::Max(zero, hn::Max(hn::Max(b0, b1), hn::Max(c0, c1)));
      } else {  // edge {0, B} against edge {A, A + C}
        const V e0 = hn::Add(a0, c0), e1 = hn::Add(a1, c1);
        lo1 = hn::Min(zero, hn::Min(b0, b1)), hi1 = hn::Max(zero, hn::Max(b0, b1));
        lo2 = hn::Min(hn::Min(a0, a1), hn::Min(e0, e1)), hi2 = hn::Max(hn::Max(a0, a1), hn::Max(e0, e1));
      }
      sign = hn::Or(sign, hn::Or(hn::Gt(hn::Sub(lo1, pad), hi2), hn::Gt(hn::Sub(lo2, pad), hi1)));
    }
    return sign;
  }
};

/// De Casteljau at the middle: the coefficients of the left and right halves of the window with coefficients b.
template <class V>
HWY_INLINE void Halve(V half, const V (&b)[4], V (&left)[4], V (&right)[4]) {
  const V b01 = hn::Mul(half, hn::Add(b[0], b[1])), b12 = hn::Mul(half, hn::Add(b[1], b[2])),
          b23 = hn::Mul(half, hn::Add(b[2], b[3]));
  const V b012 = hn::Mul(half, hn::Add(b01, b12)), b123 = hn::Mul(half, hn::Add(b12, b23));
  const V mid = hn::Mul(half, hn::Add(b012, b123));
  const V b3 = b[3];
  left[0] = b[0], left[1] = b01, left[2] = b012, left[3] = mid;
  right[0] = mid, right[1] = b123, right[2] = b23, right[3] = b3;
}

/// Writes the vector's verdicts: keep[i + j] = 0 where every window was proven; open[i + j] = the open bits.
template <class D, class M, class V = hn::Vec<D>>
HWY_INLINE void StoreVerdicts(D d, M all_apart, V open_bits, std::size_t i, std::size_t end, std::uint8_t* keep,
                              std::uint16_t* open) {
  const std::size_t N = hn::Lanes(d);
  std::uint8_t bits[8] = {};
  hn::StoreMaskBits(d, all_apart, bits);
  for (std::size_t j = 0; j < N && i + j < end; ++j)
    if ((bits[j / 8] >> (j % 8)) & 1) keep[i + j] = 0;
  if (open) {
    double o[HWY_MAX_BYTES / sizeof(double)];
    hn::StoreU(open_bits, d, o);
    for (std::size_t j = 0; j < N && i + j < end; ++j) open[i + j] = std::uint16_t(o[j]);
  }
}

/// All 2^kLevels windows of one vector of rows, in order; the coefficients by kLevels rounds of halving.
template <bool kVf, int kLevels, class D, class V = hn::Vec<D>>
HWY_INLINE void AllWindows(D d, const SplitRows<D>& r, std::size_t i, std::size_t end, std::uint8_t* keep,
                           std::uint16_t* open) {
  constexpr int kWindows = 1 << kLevels;
  const V half = hn::Set(d, 0.5), zero = hn::Zero(d);
  V c[kWindows][4];
  for (int j = 0; j < 4; ++j) c[0][j] = r.b[j];
  for (int level = 0, count = 1; level < kLevels; ++level, count *= 2)
    for (int w = count - 1; w >= 0; --w) {
      V left[4], right[4];
      Halve(half, c[w], left, right);
      for (int j = 0; j < 4; ++j) c[2 * w][j] = left[j], c[2 * w + 1][j] = right[j];
    }
  auto all_apart = hn::Eq(zero, zero);  // all true
  V open_bits = zero;                   // bit w (as an exact integer in a double): window w not proven
  V prev[9];
  for (int k = 0; k < 9; ++k) prev[k] = r.p[k];
  for (int w = 0; w < kWindows; ++w) {
    V next[9];
    r.at(hn::Set(d, double(w + 1) / kWindows), next);
    const auto apart = r.template apart<kVf>(d, c[w], prev, next);
    all_apart = hn::And(all_apart, apart);
    open_bits = hn::Add(open_bits, hn::IfThenZeroElse(apart, hn::Set(d, double(1u << w))));
    for (int k = 0; k < 9; ++k) prev[k] = next[k];
  }
  StoreVerdicts(d, all_apart, open_bits, i, end, keep, open);
}

/// The sixteenths of one open half per lane (`second`: the lanes whose open half is [1/2, 1]); the windows of
/// the other half are closed, as the halves pass proved. Each window's coefficients and points are those
/// AllWindows computes for it (the same halvings, the same p + s·m), the halvings depth first.
template <bool kVf, class D, class M, class V = hn::Vec<D>>
HWY_INLINE void OneHalf(D d, const SplitRows<D>& r, M second, std::size_t i, std::size_t end, std::uint8_t* keep,
                        std::uint16_t* open) {
  constexpr int kWindows = 1 << kSplitLevels, kHalf = kWindows / 2, kDepth = kSplitLevels - 1;
  const V half = hn::Set(d, 0.5), zero = hn::Zero(d);
  V cur[4], pending[kDepth][4];  // pending[l]: the right half left for later at depth l + 1 below the half
  {
    V left[4], right[4];
    Halve(half, r.b, left, right);
    for (int j = 0; j < 4; ++j) cur[j] = hn::IfThenElse(second, right[j], left[j]);
  }
  const auto descend = [&](int from_level) {  // to the leftmost window below cur
    for (int l = from_level; l < kDepth; ++l) {
      V left[4];
      Halve(half, cur, left, pending[l]);
      for (int j = 0; j < 4; ++j) cur[j] = left[j];
    }
  };
  descend(0);
  auto all_apart = hn::Eq(zero, zero);
  V open_bits = zero;
  V prev[9];
  r.at(hn::Set(d, 0.5), prev);
  for (int k = 0; k < 9; ++k) prev[k] = hn::IfThenElse(second, prev[k], r.p[k]);  // the first half starts at p itself
  for (int k = 0; k < kHalf; ++k) {
    if (k > 0) {  // the next window: the pending right half where the path last turned left, then leftmost
      const int level = kDepth - 1 - hwy::Num0BitsBelowLS1Bit_Nonzero32(std::uint32_t(k));
      for (int j = 0; j < 4; ++j) cur[j] = pending[level][j];
      descend(level + 1);
    }
    V next[9];
    r.at(hn::IfThenElse(second, hn::Set(d, double(kHalf + k + 1) / kWindows), hn::Set(d, double(k + 1) / kWindows)),
         next);
    const auto apart = r.template apart<kVf>(d, cur, prev, next);
    all_apart = hn::And(all_apart, apart);
    const V bit = hn::IfThenElse(second, hn::Set(d, double(1u << (kHalf + k))), hn::Set(d, double(1u << k)));
    open_bits = hn::Add(open_bits, hn::IfThenZeroElse(apart, bit));
    for (int j = 0; j < 9; ++j) prev[j] = next[j];
  }
  StoreVerdicts(d, all_apart, open_bits, i, end, keep, open);
}

template <bool kVf, int kLevels>
void SplitRange(const double* const* col, const double* const* res, std::size_t begin, std::size_t end,
                std::uint8_t* keep, std::uint16_t* open, const std::uint16_t* halves) {
  using D = hn::ScalableTag<double>;
  const D d;
  const std::size_t N = hn::Lanes(d);
  for (std::size_t i = begin; i < end; i += N) {
    const SplitRows<D> r(d, col, res, i);
    if constexpr (kLevels == kSplitLevels) {
      if (halves) {
        double second[HWY_MAX_BYTES / sizeof(double)] = {};
        std::uint16_t within[HWY_MAX_BYTES / sizeof(double)];  // each lane's windows inside its open halves
        bool one_half = true;
        for (std::size_t j = 0; j < N && i + j < end; ++j) {
          const std::uint16_t h = halves[i + j];
          one_half &= h == 1 || h == 2;
          second[j] = h == 2 ? 1.0 : 0.0;
          within[j] = h == 1 ? kFirstHalf : h == 2 ? std::uint16_t(~kFirstHalf) : std::uint16_t(0xFFFF);
        }
        if (one_half) {  // one open half in every lane: its eight windows only
          OneHalf<kVf>(d, r, hn::Eq(hn::LoadU(d, second), hn::Set(d, 1.0)), i, end, keep, open);
        } else {  // all sixteen, then the windows of closed halves closed
          AllWindows<kVf, kLevels>(d, r, i, end, keep, open);
          for (std::size_t j = 0; j < N && i + j < end; ++j)
            if ((open[i + j] &= within[j]) == 0) keep[i + j] = 0;
        }
        continue;
      }
    }
    AllWindows<kVf, kLevels>(d, r, i, end, keep, open);
  }
}

void SplitFilter(const double* const* col, const double* const* res, std::size_t begin, std::size_t end, bool vf,
                 int levels, std::uint8_t* keep, std::uint16_t* open, const std::uint16_t* halves) {
  if (levels == kSplitCoarseLevels) {
    if (vf) SplitRange<true, kSplitCoarseLevels>(col, res, begin, end, keep, open, nullptr);
    else SplitRange<false, kSplitCoarseLevels>(col, res, begin, end, keep, open, nullptr);
  } else {
    if (vf) SplitRange<true, kSplitLevels>(col, res, begin, end, keep, open, halves);
    else SplitRange<false, kSplitLevels>(col, res, begin, end, keep, open, halves);
  }
}

}  // namespace HWY_NAMESPACE
}  // namespace ccdlab
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
#include <algorithm>
#include <cmath>

#include "framework/util/error.hpp"

namespace ccdlab {

HWY_EXPORT(SplitFilter);

void split_filter(const PlaneBatch& plane, std::size_t begin, std::size_t end, bool vf, std::uint8_t* keep,
                  int levels, std::uint16_t* open, const std::uint16_t* halves) {
  if (levels != kSplitCoarseLevels && levels != kSplitLevels) fail("split_filter: {} levels not compiled", levels);
  if (halves && (levels != kSplitLevels || !open))
    fail("split_filter: the halves' windows refine only into sixteenths, with their open bits written");
  const double* cols[PlaneBatch::kColumns];
  for (int c = 0; c < PlaneBatch::kColumns; ++c) cols[c] = plane.column(c);
  const double* res[PlaneBatch::kResults];
  for (int r = 0; r < PlaneBatch::kResults; ++r) res[r] = plane.result_column(r);
  HWY_DYNAMIC_DISPATCH(SplitFilter)(cols, res, begin, end, vf, levels, keep, open, halves);
}

bool split_filter_keeps(const PlaneBatch& plane, std::size_t i, bool vf, int levels) {
  return split_filter_open(plane, i, vf, levels) != 0;
}

std::uint16_t split_filter_open(const PlaneBatch& plane, std::size_t i, bool vf, int levels, std::uint16_t halves) {
  const std::uint16_t all = split_filter_open(plane, i, vf, levels);
  if (levels != kSplitLevels || (halves != 1 && halves != 2)) return all;
  return all & (halves == 1 ? split_detail::kFirstHalf : std::uint16_t(~split_detail::kFirstHalf));
}

std::uint16_t split_filter_open(const PlaneBatch& plane, std::size_t i, bool vf, int levels) {
  using namespace split_detail;
  const int windows = 1 << levels;
  auto col = [&](int c) { return plane.column(c)[i]; };
  double p[9], m[9];
  for (int k = 0; k < 3; ++k) {
    p[k] = col(PlaneBatch::A0x + k), p[3 + k] = col(PlaneBatch::B0x + k), p[6 + k] = col(PlaneBatch::C0x + k);
    m[k] = col(PlaneBatch::A1x + k) - p[k], m[3 + k] = col(PlaneBatch::B1x + k) - p[3 + k];
    m[6 + k] = col(PlaneBatch::C1x + k) - p[6 + k];
  }
  double M = 0;
  for (int k = 0; k < 9; ++k) M = std::max(M, std::max(std::abs(p[k]), std::abs(p[k] + m[k])));
  const double b[4] = {plane.result(PlaneBatch::Q0, i), plane.result(PlaneBatch::Q1x3, i) / 3.0,
                       plane.result(PlaneBatch::Q2x3, i) / 3.0, plane.result(PlaneBatch::Q3, i)};
  const double bmax = std::max(std::max(std::abs(b[0]), std::abs(b[1])), std::max(std::abs(b[2]), std::abs(b[3])));
  const double t = plane.result(PlaneBatch::Threshold, i) * kThresholdSlack + kCoefSlack * bmax;
  const double pad = (plane.result(PlaneBatch::Reach, i) * (1 + 1e-12) + kPadSlack * M) + 1e-300;
  double c[kMaxWindows][4];
  for (int j = 0; j < 4; ++j) c[0][j] = b[j];
  for (int level = 0, count = 1; level < levels; ++level, count *= 2)
    for (int w = count - 1; w >= 0; --w) {
      const double b0 = c[w][0], b1 = c[w][1], b2 = c[w][2], b3 = c[w][3];
      const double b01 = 0.5 * (b0 + b1), b12 = 0.5 * (b1 + b2), b23 = 0.5 * (b2 + b3);
      const double b012 = 0.5 * (b01 + b12), b123 = 0.5 * (b12 + b23), mid = 0.5 * (b012 + b123);
      c[2 * w][0] = b0, c[2 * w][1] = b01, c[2 * w][2] = b012, c[2 * w][3] = mid;
      c[2 * w + 1][0] = mid, c[2 * w + 1][1] = b123, c[2 * w + 1][2] = b23, c[2 * w + 1][3] = b3;
    }
  double prev[9];
  std::copy(p, p + 9, prev);
  std::uint16_t open = 0;
  for (int w = 0; w < windows; ++w) {
    const double s = double(w + 1) / windows;
    double next[9];
    for (int k = 0; k < 9; ++k) next[k] = p[k] + s * m[k];
    bool apart = (c[w][0] > t && c[w][1] > t && c[w][2] > t && c[w][3] > t) ||
                 (c[w][0] < -t && c[w][1] < -t && c[w][2] < -t && c[w][3] < -t);
    for (int k = 0; k < 3; ++k) {
      const double a0 = prev[k], a1 = next[k], b0 = prev[3 + k], b1 = next[3 + k], c0 = prev[6 + k], c1 = next[6 + k];
      double lo1, hi1, lo2, hi2;
      if (vf) {
        lo1 = std::min(a0, a1), hi1 = std::max(a0, a1);
        lo2 = std::min(0.0, std::min(std::min(b0, b1), std::min(c0, c1)));
        hi2 = std::max(0.0, std::max(std::max(b0, b1), std::max(c0, c1)));
      } else {
        const double e0 = a0 + c0, e1 = a1 + c1;
        lo1 = std::min(0.0, std::min(b0, b1)), hi1 = std::max(0.0, std::max(b0, b1));
        lo2 = std::min(std::min(a0, a1), std::min(e0, e1)), hi2 = std::max(std::max(a0, a1), std::max(e0, e1));
      }
      apart = apart || (lo1 - pad > hi2) || (lo2 - pad > hi1);
    }
    open |= std::uint16_t(!apart) << w;
    std::copy(next, next + 9, prev);
  }
  return open;
}

}  // namespace ccdlab
#endif  // HWY_ONCE
