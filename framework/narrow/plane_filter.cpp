// Highway compiles this file once per SIMD target (foreach_target.h) and picks one at run time.
#include "framework/narrow/plane_filter.hpp"

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "framework/narrow/plane_filter.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

HWY_BEFORE_NAMESPACE();
namespace ccdlab {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

/// Y×Z, componentwise.
template <class V>
struct Cross {
  V x, y, z;
  HWY_INLINE Cross(V yx, V yy, V yz, V zx, V zy, V zz)
      : x(hn::Sub(hn::Mul(yy, zz), hn::Mul(yz, zy))),
        y(hn::Sub(hn::Mul(yz, zx), hn::Mul(yx, zz))),
        z(hn::Sub(hn::Mul(yx, zy), hn::Mul(yy, zx))) {}
  /// X·(Y×Z): the same operations, in the same order, as plane_filter_keeps' det.
  HWY_INLINE V dot(V xx, V xy, V xz) const { return hn::Add(hn::Add(hn::Mul(xx, x), hn::Mul(xy, y)), hn::Mul(xz, z)); }
};

void PlaneFilter(const double* const* col, double* const* out, std::size_t n, double abs_reach, double rel_reach,
                 std::uint8_t* keep) {
  const hn::ScalableTag<double> d;
  using V = hn::Vec<decltype(d)>;
  const std::size_t N = hn::Lanes(d);
  const V reach_abs = hn::Set(d, abs_reach), reach_rel = hn::Set(d, rel_reach);
  const V err_factor = hn::Set(d, 32 * 0x1p-53), slack = hn::Set(d, 1 + 1e-12), tiny = hn::Set(d, 1e-290);
  const V three = hn::Set(d, 3.0), two = hn::Set(d, 2.0);
  for (std::size_t i = 0; i < n; i += N) {
    auto load = [&](int c) { return hn::LoadU(d, col[c] + i); };
    const V a0x = load(PlaneBatch::A0x), a0y = load(PlaneBatch::A0y), a0z = load(PlaneBatch::A0z);
    const V a1x = load(PlaneBatch::A1x), a1y = load(PlaneBatch::A1y), a1z = load(PlaneBatch::A1z);
    const V b0x = load(PlaneBatch::B0x), b0y = load(PlaneBatch::B0y), b0z = load(PlaneBatch::B0z);
    const V b1x = load(PlaneBatch::B1x), b1y = load(PlaneBatch::B1y), b1z = load(PlaneBatch::B1z);
    const V c0x = load(PlaneBatch::C0x), c0y = load(PlaneBatch::C0y), c0z = load(PlaneBatch::C0z);
    const V c1x = load(PlaneBatch::C1x), c1y = load(PlaneBatch::C1y), c1z = load(PlaneBatch::C1z);
    const V dx = load(PlaneBatch::Dx), dy = load(PlaneBatch::Dy), dz = load(PlaneBatch::Dz);
    // Bernstein coefficients (times 1 and 3): eight triple products over four cross products.
    const Cross<V> b0c0(b0x, b0y, b0z, c0x, c0y, c0z), b1c1(b1x, b1y, b1z, c1x, c1y, c1z);
    const Cross<V> b1c0(b1x, b1y, b1z, c0x, c0y, c0z), b0c1(b0x, b0y, b0z, c1x, c1y, c1z);
    const V q0 = b0c0.dot(a0x, a0y, a0z);
    const V q3 = b1c1.dot(a1x, a1y, a1z);
    const V q1 = hn::Add(hn::Add(b0c0.dot(a1x, a1y, a1z), b1c0.dot(a0x, a0y, a0z)), b0c1.dot(a0x, a0y, a0z));
    const V q2 = hn::Add(hn::Add(b1c1.dot(a0x, a0y, a0z), b0c1.dot(a1x, a1y, a1z)), b1c0.dot(a1x, a1y, a1z));
    // Threshold: reach·B̄·C̄ plus the forward error bound.
    auto norm1 = [&](V x, V y, V z) { return hn::Add(hn::Add(hn::Abs(x), hn::Abs(y)), hn::Abs(z)); };
    auto norm2sq = [&](V x, V y, V z) { return hn::Add(hn::Add(hn::Mul(x, x), hn::Mul(y, y)), hn::Mul(z, z)); };
    const V ma = hn::Max(norm1(a0x, a0y, a0z), norm1(a1x, a1y, a1z));
    const V mb = hn::Max(norm1(b0x, b0y, b0z), norm1(b1x, b1y, b1z));
    const V mc = hn::Max(norm1(c0x, c0y, c0z), norm1(c1x, c1y, c1z));
    const V bb = hn::Max(norm2sq(b0x, b0y, b0z), norm2sq(b1x, b1y, b1z));
    const V cc = hn::Max(norm2sq(c0x, c0y, c0z), norm2sq(c1x, c1y, c1z));
    const V ext = hn::Mul(two, hn::Add(hn::Add(norm1(dx, dy, dz), ma), hn::Add(mb, mc)));
    const V reach = hn::Add(reach_abs, hn::Mul(reach_rel, ext));
    const V t = hn::Add(hn::Add(hn::Mul(hn::Mul(reach, hn::Sqrt(hn::Mul(bb, cc))), slack),
                                hn::Mul(err_factor, hn::Mul(hn::Mul(ma, mb), mc))),
                        tiny);
    const V t3 = hn::Mul(three, t);
    const V neg_t = hn::Neg(t), neg_t3 = hn::Neg(t3);
    const auto above = hn::And(hn::And(hn::Gt(q0, t), hn::Gt(q3, t)), hn::And(hn::Gt(q1, t3), hn::Gt(q2, t3)));
    const auto below =
        hn::And(hn::And(hn::Lt(q0, neg_t), hn::Lt(q3, neg_t)), hn::And(hn::Lt(q1, neg_t3), hn::Lt(q2, neg_t3)));
    const auto culled = hn::Or(above, below);
    hn::StoreU(q0, d, out[PlaneBatch::Q0] + i);
    hn::StoreU(q1, d, out[PlaneBatch::Q1x3] + i);
    hn::StoreU(q2, d, out[PlaneBatch::Q2x3] + i);
    hn::StoreU(q3, d, out[PlaneBatch::Q3] + i);
    hn::StoreU(t, d, out[PlaneBatch::Threshold] + i);
    hn::StoreU(reach, d, out[PlaneBatch::Reach] + i);
    std::uint8_t bits[8] = {};
    hn::StoreMaskBits(d, culled, bits);
    for (std::size_t j = 0; j < N && i + j < n; ++j) keep[i + j] = std::uint8_t(((bits[j / 8] >> (j % 8)) & 1) ^ 1);
  }
}

}  // namespace HWY_NAMESPACE
}  // namespace ccdlab
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
#include <algorithm>
#include <cmath>

namespace ccdlab {

HWY_EXPORT(PlaneFilter);

void PlaneBatch::resize(std::size_t n) {
  size_ = n;
  const std::size_t padded = (n + kPad - 1) / kPad * kPad + kPad;
  for (auto& c : col_) {
    c.resize(padded);
    std::fill(c.begin() + std::ptrdiff_t(n), c.end(), 0.0);  // padding rows: zero, kept, never read back
  }
  for (auto& c : out_) {
    c.resize(padded);
    std::fill(c.begin() + std::ptrdiff_t(n), c.end(), 0.0);  // stage 3 may load a vector's worth past the end
  }
}

std::size_t PlaneBatch::compact(const std::uint8_t* keep) {
  // The kept rows' indices once, then the rows moved forward in place (index j ≤ kept[j]).
  kept_.resize(size_);
  std::size_t n = 0;
  for (std::size_t i = 0; i < size_; ++i) {  // branch-free: the flags are close to random
    kept_[n] = i;
    n += keep[i];
  }
  // Row by row, all columns at once (one pass over the indices; the rows before the first dropped one stay).
  double* cols[int(kColumns) + int(kResults)];
  for (int c = 0; c < kColumns; ++c) cols[c] = col_[c].data();
  for (int r = 0; r < kResults; ++r) cols[kColumns + r] = out_[r].data();
  std::size_t j = 0;
  while (j < n && kept_[j] == j) ++j;
  for (; j < n; ++j) {
    const std::size_t from = kept_[j];
    for (double* c : cols) c[j] = c[from];
  }
  size_ = n;
  return size_;
}

void plane_filter(PlaneBatch& batch, CullReach reach, std::uint8_t* keep) {
  const double* cols[PlaneBatch::kColumns];
  for (int c = 0; c < PlaneBatch::kColumns; ++c) cols[c] = batch.column(c);
  double* out[PlaneBatch::kResults];
  for (int r = 0; r < PlaneBatch::kResults; ++r) out[r] = batch.result_column(r);
  HWY_DYNAMIC_DISPATCH(PlaneFilter)(cols, out, batch.size(), reach.abs, reach.rel, keep);
}

bool plane_filter_keeps(const PlaneBatch& batch, std::size_t i, CullReach reach) {
  auto vec = [&](int c) { return Vec3(batch.column(c)[i], batch.column(c + 1)[i], batch.column(c + 2)[i]); };
  const Vec3 A0 = vec(PlaneBatch::A0x), A1 = vec(PlaneBatch::A1x), B0 = vec(PlaneBatch::B0x),
             B1 = vec(PlaneBatch::B1x), C0 = vec(PlaneBatch::C0x), C1 = vec(PlaneBatch::C1x);
  auto det = [](const Vec3& x, const Vec3& y, const Vec3& z) {
    const Vec3 c(y.y() * z.z() - y.z() * z.y(), y.z() * z.x() - y.x() * z.z(), y.x() * z.y() - y.y() * z.x());
    return (x.x() * c.x() + x.y() * c.y()) + x.z() * c.z();
  };
  const double q0 = det(A0, B0, C0), q3 = det(A1, B1, C1);
  const double q1 = (det(A1, B0, C0) + det(A0, B1, C0)) + det(A0, B0, C1);
  const double q2 = (det(A0, B1, C1) + det(A1, B0, C1)) + det(A1, B1, C0);
  auto n1 = [](const Vec3& x) { return (std::abs(x.x()) + std::abs(x.y())) + std::abs(x.z()); };
  const double ma = std::max(n1(A0), n1(A1)), mb = std::max(n1(B0), n1(B1)), mc = std::max(n1(C0), n1(C1));
  auto n2 = [](const Vec3& x) { return (x.x() * x.x() + x.y() * x.y()) + x.z() * x.z(); };
  const double bb = std::max(n2(B0), n2(B1)), cc = std::max(n2(C0), n2(C1));
  const double ext = 2 * ((n1(vec(PlaneBatch::Dx)) + ma) + (mb + mc));
  const double r = reach.abs + reach.rel * ext;
  const double t = r * std::sqrt(bb * cc) * (1 + 1e-12) + 32 * 0x1p-53 * (ma * mb * mc) + 1e-290;
  const bool above = q0 > t && q3 > t && q1 > 3 * t && q2 > 3 * t;
  const bool below = q0 < -t && q3 < -t && q1 < -3 * t && q2 < -3 * t;
  return !(above || below);
}

const char* plane_filter_target() {
  return hwy::TargetName(hwy::SupportedAndGeneratedTargets().empty()
                             ? HWY_STATIC_TARGET
                             : hwy::SupportedAndGeneratedTargets().front());
}

}  // namespace ccdlab
#endif  // HWY_ONCE
