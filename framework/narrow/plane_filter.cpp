// Highway compiles this file once per SIMD target (foreach_target.h) and picks one at run time.
#include "framework/narrow/plane_filter.hpp"

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "framework/narrow/plane_filter.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

#include "framework/narrow/point_loads-inl.h"

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

// stage_vf_rows / stage_ee_rows (plane_filter.hpp). A row watches four points o, a, b, c (VF: f0, v, f1, f2;
// EE: a0, b0, a1, b1): A = a − o, B = b − o, C = c − o (VF) or c − a (EE), D = o(t1) − o(t0).
template <bool kVf>
HWY_INLINE void RowPoints(const std::int32_t* pair, const std::int32_t* features, std::int32_t* p) {
  if constexpr (kVf) {
    const std::int32_t* f = features + 3 * std::ptrdiff_t(pair[1]);
    p[0] = f[0], p[1] = pair[0], p[2] = f[1], p[3] = f[2];
  } else {
    const std::int32_t *ea = features + 2 * std::ptrdiff_t(pair[0]), *eb = features + 2 * std::ptrdiff_t(pair[1]);
    p[0] = ea[0], p[1] = eb[0], p[2] = ea[1], p[3] = eb[1];
  }
}

/// One row, plain: the expressions PlaneBatch::set is given (one subtraction per double).
template <bool kVf>
HWY_INLINE void StageRowPlain(const std::int32_t* p, const double* x01, double* const* col, std::size_t i) {
  for (int j = 0; j < 3; ++j) {
    auto at = [&](int frame, int role) { return x01[8 * std::ptrdiff_t(p[role]) + 4 * frame + j]; };
    col[PlaneBatch::A0x + j][i] = at(0, 1) - at(0, 0);
    col[PlaneBatch::A1x + j][i] = at(1, 1) - at(1, 0);
    col[PlaneBatch::B0x + j][i] = at(0, 2) - at(0, 0);
    col[PlaneBatch::B1x + j][i] = at(1, 2) - at(1, 0);
    col[PlaneBatch::C0x + j][i] = at(0, 3) - at(0, kVf ? 0 : 1);
    col[PlaneBatch::C1x + j][i] = at(1, 3) - at(1, kVf ? 0 : 1);
    col[PlaneBatch::Dx + j][i] = at(1, 0) - at(0, 0);
  }
}

template <bool kVf>
void StageRowsT(const std::int32_t* pairs, const std::int32_t* features, const double* x01, std::size_t n,
                double* const* col) {
  std::size_t i = 0;
#if CCDLAB_POINT_LOADS_4
  const Points4Tag d4;
  using Xyz = Points4;
  const auto load = [&](int frame, const std::int32_t (&id)[4][4], int role) {
    const std::int32_t ids[4] = {id[0][role], id[1][role], id[2][role], id[3][role]};
    return LoadFramePoints4(x01, frame, ids);
  };
  const auto store = [&](int c, const Xyz& p, const Xyz& q) {  // columns c, c + 1, c + 2 = p − q
    hn::StoreU(hn::Sub(p.x, q.x), d4, col[c] + i);
    hn::StoreU(hn::Sub(p.y, q.y), d4, col[c + 1] + i);
    hn::StoreU(hn::Sub(p.z, q.z), d4, col[c + 2] + i);
  };
  for (; i + 4 <= n; i += 4) {
    std::int32_t id[4][4];
    for (int k = 0; k < 4; ++k) RowPoints<kVf>(pairs + 2 * (i + std::size_t(k)), features, id[k]);
    const Xyz o0 = load(0, id, 0), o1 = load(1, id, 0), a0 = load(0, id, 1), a1 = load(1, id, 1);
    store(PlaneBatch::A0x, a0, o0);
    store(PlaneBatch::A1x, a1, o1);
    store(PlaneBatch::Dx, o1, o0);
    const Xyz b0 = load(0, id, 2), b1 = load(1, id, 2);
    store(PlaneBatch::B0x, b0, o0);
    store(PlaneBatch::B1x, b1, o1);
    const Xyz c0 = load(0, id, 3), c1 = load(1, id, 3);
    store(PlaneBatch::C0x, c0, kVf ? o0 : a0);
    store(PlaneBatch::C1x, c1, kVf ? o1 : a1);
  }
#endif
  for (; i < n; ++i) {
    std::int32_t id[4];
    RowPoints<kVf>(pairs + 2 * i, features, id);
    StageRowPlain<kVf>(id, x01, col, i);
  }
}
void StageRows(const std::int32_t* pairs, const std::int32_t* features, const double* x01, std::size_t n,
               double* const* col, bool vf) {
  if (vf) StageRowsT<true>(pairs, features, x01, n, col);
  else StageRowsT<false>(pairs, features, x01, n, col);
}

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

#include "framework/util/error.hpp"

namespace ccdlab {

HWY_EXPORT(PlaneFilter);
HWY_EXPORT(StageRows);

namespace {
void stage_rows(PlaneBatch& batch, std::size_t first, const std::int32_t* pairs, std::size_t n,
                const std::int32_t* features, const FramePoints* points, bool vf) {
  static_assert(sizeof(FramePoints) == 8 * sizeof(double) && sizeof(Face) == 3 * sizeof(std::int32_t) &&
                    sizeof(Edge) == 2 * sizeof(std::int32_t) && sizeof(VertexFacePair) == 2 * sizeof(std::int32_t) &&
                    sizeof(EdgeEdgePair) == 2 * sizeof(std::int32_t),
                "StageRows reads coordinate j of point p in frame f at 8p + 4f + j, and ids as packed int32");
  if (n == 0) return;
  double* cols[PlaneBatch::kColumns];
  for (int c = 0; c < PlaneBatch::kColumns; ++c) cols[c] = batch.column(c) + first;
  HWY_DYNAMIC_DISPATCH(StageRows)(pairs, features, reinterpret_cast<const double*>(points), n, cols, vf);
}
}  // namespace

void stage_vf_rows(PlaneBatch& batch, std::size_t first, std::span<const VertexFacePair> pairs, const Face* faces,
                   const FramePoints* points) {
  // Casts, not member access: an empty span's data() may be null.
  stage_rows(batch, first, reinterpret_cast<const std::int32_t*>(pairs.data()), pairs.size(),
             reinterpret_cast<const std::int32_t*>(faces), points, true);
}
void stage_ee_rows(PlaneBatch& batch, std::size_t first, std::span<const EdgeEdgePair> pairs, const Edge* edges,
                   const FramePoints* points) {
  stage_rows(batch, first, reinterpret_cast<const std::int32_t*>(pairs.data()), pairs.size(),
             reinterpret_cast<const std::int32_t*>(edges), points, false);
}

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

}  // namespace ccdlab
#endif  // HWY_ONCE
