// Stage 1's vertex bounds in SIMD (feature_bounds.hpp): every vertex's swept 26-DOP, the axes in lanes, and its
// coarse 16-bit copy. Highway compiles this file once per target and picks one at run time; every target computes
// the plain version's floats (swept_vertex_dop, compiled here with the same -ffp-contract=off).
#include "framework/swept/feature_bounds.hpp"

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "framework/swept/vertex_dops_simd.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

HWY_BEFORE_NAMESPACE();
namespace ccdlab {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// The largest float ≤ x, per lane (detail::round_down in kdop.hpp, the same steps): x rounded to the nearest
// float, and where that lies above x, the next float towards −∞ (bits − 1 above zero, + 1 below, −denorm_min at 0).
template <class D>
hn::Vec<hn::Rebind<float, D>> RoundDown(D d, hn::Vec<D> x) {
  const hn::Rebind<float, D> df;
  const hn::RebindToSigned<decltype(df)> di;
  const auto f = hn::DemoteTo(df, x);
  const auto bits = hn::BitCast(di, f);
  auto below = hn::IfThenElse(hn::RebindMask(di, hn::Gt(f, hn::Zero(df))), hn::Sub(bits, hn::Set(di, 1)),
                              hn::Add(bits, hn::Set(di, 1)));
  below = hn::IfThenElse(hn::RebindMask(di, hn::Eq(f, hn::Zero(df))), hn::Set(di, std::int32_t(0x80000001u)), below);
  const auto chosen = hn::IfThenElse(hn::Gt(hn::PromoteTo(d, f), x), hn::PromoteTo(d, hn::BitCast(df, below)),
                                     hn::PromoteTo(d, f));
  return hn::DemoteTo(df, chosen);  // a float already: exact
}
// The smallest float ≥ x: −RoundDown(−x) (detail::round_up, the same float).
template <class D>
hn::Vec<hn::Rebind<float, D>> RoundUp(D d, hn::Vec<D> x) {
  return hn::Neg(RoundDown(d, hn::Neg(x)));
}

// swept_vertex_dop (feature_bounds.hpp) of vertices [0, n), the axes in lanes: KDop<26>::grow's projections
// a·x + b·y + c·z (same order, products exact), min and max of the two frames, padded by err = 4u·max‖p‖₁ and
// rounded outward; then inflate's r·len·(1 + 10⁻¹⁵), rounded outward again. The same floats, lane for lane (this
// file is compiled with -ffp-contract=off). Vertices with a non-finite coordinate take the plain version (the
// min and max of a NaN depend on operand order), and so do bounds that could leave the float range (Highway's
// scalar target demotes them to ±FLT_MAX, not ±∞).
void SweptVertexDops(const Vec3* x_t0, const Vec3* x_t1, std::size_t n, double r, PaddedDop* out) {
  constexpr int L = PaddedDop::kLanes;
  constexpr double kFloatSafe = 1e37;  // ‖p‖₁ and r below this keep every bound below FLT_MAX ≈ 3.4·10³⁸
  alignas(64) static const auto axes = [] {
    std::array<std::array<double, L>, 4> t{};  // a, b, c, len per lane; padding lanes 0
    for (int i = 0; i < PaddedDop::kAxes; ++i) {
      const auto& d = KDopAxes<26>::axes[std::size_t(i)];
      for (int j = 0; j < 3; ++j) t[std::size_t(j)][std::size_t(i)] = double(d[std::size_t(j)]);
      t[3][std::size_t(i)] = std::sqrt(double(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]));
    }
    return t;
  }();
  const hn::ScalableTag<double> d;
  const hn::Rebind<float, decltype(d)> df;
  const std::size_t N = hn::Lanes(d);
  for (std::size_t v = 0; v < n; ++v) {
    const Vec3 &p = x_t0[v], &q = x_t1[v];
    const double mag = std::max(std::abs(p.x()) + std::abs(p.y()) + std::abs(p.z()),
                                std::abs(q.x()) + std::abs(q.y()) + std::abs(q.z()));
    if (!p.allFinite() || !q.allFinite() || !(mag < kFloatSafe && r < kFloatSafe)) [[unlikely]] {
      out[v] = swept_vertex_dop(p, q, r);
      continue;
    }
    const auto err = hn::Set(d, 4.440892098500626e-16 * mag);  // KDop::grow's pad
    for (std::size_t k = 0; k < std::size_t(L); k += N) {
      const auto a = hn::Load(d, axes[0].data() + k), b = hn::Load(d, axes[1].data() + k),
                 c = hn::Load(d, axes[2].data() + k);
      const auto project = [&](const Vec3& x) {
        return hn::Add(hn::Add(hn::Mul(a, hn::Set(d, x.x())), hn::Mul(b, hn::Set(d, x.y()))), hn::Mul(c, hn::Set(d, x.z())));
      };
      const auto sp = project(p), sq = project(q);
      auto lo = RoundDown(d, hn::Sub(hn::Min(sp, sq), err));
      auto hi = RoundUp(d, hn::Add(hn::Max(sp, sq), err));
      if (r > 0) {  // KDop::inflate
        const auto pad = hn::Mul(hn::Mul(hn::Set(d, r), hn::Load(d, axes[3].data() + k)), hn::Set(d, 1 + 1e-15));
        lo = RoundDown(d, hn::Sub(hn::PromoteTo(d, lo), pad));
        hi = RoundUp(d, hn::Add(hn::PromoteTo(d, hi), pad));
      }
      hn::Store(lo, df, out[v].min + k);
      hn::Store(hi, df, out[v].max + k);
    }
    for (int i = PaddedDop::kAxes; i < L; ++i) out[v].min[i] = out[v].max[i] = 0.0f;
  }
}

// The coarse copy of vertices [0, n): q(x) = floor((x − lo)·scale − offset) per lane, in float (each operation
// rounds monotonically, so q is monotone: all CoarseDop's argument needs), clamped to ±kClamp, a NaN sent to the
// clamp that never separates; maxima stored negated.
void QuantizeDops(const PaddedDop* in, CoarseDop* out, std::size_t n, const float* lo, const float* scale,
                  const float* offset) {
  const hn::CappedTag<float, CoarseDop::kLanes> df;
  const hn::Rebind<std::int32_t, decltype(df)> di;
  const hn::Rebind<std::int16_t, decltype(df)> d16;
  const std::size_t N = hn::Lanes(df);
  const auto clamp_hi = hn::Set(df, float(CoarseDop::kClamp)), clamp_lo = hn::Neg(clamp_hi);
  const auto grid = [&](auto x, std::size_t k, auto if_nan) {
    const auto g = hn::Sub(hn::Mul(hn::Sub(x, hn::Load(df, lo + k)), hn::Load(df, scale + k)), hn::Load(df, offset + k));
    return hn::Floor(hn::Min(hn::Max(hn::IfThenElse(hn::IsNaN(g), if_nan, g), clamp_lo), clamp_hi));
  };
  for (std::size_t v = 0; v < n; ++v)
    for (std::size_t k = 0; k < std::size_t(CoarseDop::kLanes); k += N) {
      const auto q_min = grid(hn::Load(df, in[v].min + k), k, clamp_lo);
      const auto q_max = grid(hn::Load(df, in[v].max + k), k, clamp_hi);
      hn::Store(hn::DemoteTo(d16, hn::ConvertTo(di, q_min)), d16, out[v].min + k);
      hn::Store(hn::DemoteTo(d16, hn::ConvertTo(di, hn::Neg(q_max))), d16, out[v].neg_max + k);
    }
}

}  // namespace HWY_NAMESPACE
}  // namespace ccdlab
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace ccdlab {

PaddedDop swept_vertex_dop(const Vec3& p, const Vec3& q, double r) {
  KDop<26> dop;
  dop.grow(std::array<const Vec3*, 2>{&p, &q});
  dop.inflate(r);
  PaddedDop out;
  for (int i = 0; i < PaddedDop::kLanes; ++i) {
    out.min[i] = i < PaddedDop::kAxes ? dop.min(i) : 0.0f;
    out.max[i] = i < PaddedDop::kAxes ? dop.max(i) : 0.0f;
  }
  return out;
}

HWY_EXPORT(QuantizeDops);
HWY_EXPORT(SweptVertexDops);

namespace detail {
void swept_vertex_dops(const Vec3* x_t0, const Vec3* x_t1, std::size_t n, double r, PaddedDop* out) {
  HWY_DYNAMIC_DISPATCH(SweptVertexDops)(x_t0, x_t1, n, r, out);
}
void quantize_dops(const PaddedDop* in, CoarseDop* out, std::size_t n, const float* lo, const float* scale,
                   const float* offset) {
  HWY_DYNAMIC_DISPATCH(QuantizeDops)(in, out, n, lo, scale, offset);
}
}  // namespace detail
}  // namespace ccdlab
#endif  // HWY_ONCE
