// Highway compiles this file once per SIMD target (foreach_target.h) and picks one at run time.
#include "framework/narrow/triangle_filter.hpp"

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "framework/narrow/triangle_filter.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

#include "framework/narrow/point_loads-inl.h"

#ifndef CCDLAB_TRIANGLE_FILTER_LAYOUT
#define CCDLAB_TRIANGLE_FILTER_LAYOUT
namespace ccdlab::detail {
// A staged candidate: corners 0–2 of f, then 0–2 of g; each at t0 then t1; x, y, z. One column per coordinate.
constexpr int kTriangleCorners = 6;
constexpr int kTriangleColumns = kTriangleCorners * 2 * 3;
constexpr int triangle_column(int corner, int frame, int axis) { return (corner * 2 + frame) * 3 + axis; }
// The gap's rounding terms (triangle_filter.hpp): 16u per unit of L̄, the reach's slack, and a floor.
constexpr double kTriangleErrFactor = 16 * 0x1p-53, kTriangleSlack = 1 + 1e-12, kTriangleTiny = 1e-290;
}  // namespace ccdlab::detail
#endif

HWY_BEFORE_NAMESPACE();
namespace ccdlab {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;
using detail::kTriangleColumns;
using detail::triangle_column;

/// Writes rows [0, n ≤ kBlock) of the block (column c at block + c·stride) from the candidates' corners. The
/// corner ids first, in a loop of their own: pair → face → point is a chain of dependent loads, and a short loop
/// lets the core run far ahead on it.
template <std::size_t kBlock>
void StageTriangles(const std::int32_t* pairs, const std::int32_t* faces, const double* x01,
                    std::size_t n, double* block, std::size_t stride) {
  std::int32_t ids[detail::kTriangleCorners][kBlock];
  for (std::size_t i = 0; i < n; ++i)
    for (int corner = 0; corner < detail::kTriangleCorners; ++corner)
      ids[corner][i] = faces[3 * std::ptrdiff_t(pairs[2 * i + corner / 3]) + corner % 3];
  std::size_t i = 0;
#if CCDLAB_POINT_LOADS_4
  const Points4Tag d4;
  for (; i + 4 <= n; i += 4) {
    for (int corner = 0; corner < detail::kTriangleCorners; ++corner) {
      const std::int32_t id[4] = {ids[corner][i], ids[corner][i + 1], ids[corner][i + 2], ids[corner][i + 3]};
      for (int frame = 0; frame < 2; ++frame) {
        const Points4 p = LoadFramePoints4(x01, frame, id);
        double* col = block + stride * std::size_t(triangle_column(corner, frame, 0)) + i;
        hn::Store(p.x, d4, col);
        hn::Store(p.y, d4, col + stride);
        hn::Store(p.z, d4, col + 2 * stride);
      }
    }
  }
#endif
  for (; i < n; ++i)
    for (int corner = 0; corner < detail::kTriangleCorners; ++corner)
      for (int frame = 0; frame < 2; ++frame)
        for (int axis = 0; axis < 3; ++axis)
          block[stride * std::size_t(triangle_column(corner, frame, axis)) + i] =
              x01[8 * std::ptrdiff_t(ids[corner][i]) + 4 * frame + axis];
}

template <class V>
struct Xyz {
  V x, y, z;
};

/// Whether the twelve points, projected on the axis n = B0×C0 + B1×C1 of the face with corners o, b, c (B, C its
/// edges from o at t0 and t1), leave the two faces' intervals farther apart than the reach (triangle_filter.hpp).
/// `gap_factor` = reach·slack + 16u·L̄ (L̄ bounds every |p − o| coordinate); operations in the order of
/// triangle_pair_keeps.
template <class D, class V = hn::Vec<D>>
HWY_INLINE hn::Mask<D> SideCulled(D d, const Xyz<V> (&pt)[6][2], int o, int b, int c, int other, V gap_factor) {
  const auto sub = [](const Xyz<V>& u, const Xyz<V>& v) {
    return Xyz<V>{hn::Sub(u.x, v.x), hn::Sub(u.y, v.y), hn::Sub(u.z, v.z)};
  };
  const auto cross = [](const Xyz<V>& y, const Xyz<V>& z) {
    return Xyz<V>{hn::Sub(hn::Mul(y.y, z.z), hn::Mul(y.z, z.y)), hn::Sub(hn::Mul(y.z, z.x), hn::Mul(y.x, z.z)),
                  hn::Sub(hn::Mul(y.x, z.y), hn::Mul(y.y, z.x))};
  };
  const auto dot = [](const Xyz<V>& x, const Xyz<V>& c) {
    return hn::Add(hn::Add(hn::Mul(x.x, c.x), hn::Mul(x.y, c.y)), hn::Mul(x.z, c.z));
  };
  const Xyz<V> n0 = cross(sub(pt[b][0], pt[o][0]), sub(pt[c][0], pt[o][0]));
  const Xyz<V> n1 = cross(sub(pt[b][1], pt[o][1]), sub(pt[c][1], pt[o][1]));
  const Xyz<V> n{hn::Add(n0.x, n1.x), hn::Add(n0.y, n1.y), hn::Add(n0.z, n1.z)};
  // Every point relative to o at its own time: the face's (0, B, C at t0 and t1), then the other face's.
  V own_lo = hn::Zero(d), own_hi = own_lo;
  for (const int corner : {b, c})
    for (int frame = 0; frame < 2; ++frame) {
      const V s = dot(sub(pt[corner][frame], pt[o][frame]), n);
      own_lo = hn::Min(own_lo, s), own_hi = hn::Max(own_hi, s);
    }
  V lo = dot(sub(pt[other][0], pt[o][0]), n), hi = lo;
  for (int corner = other; corner < other + 3; ++corner)
    for (int frame = 0; frame < 2; ++frame) {
      if (corner == other && frame == 0) continue;
      const V s = dot(sub(pt[corner][frame], pt[o][frame]), n);
      lo = hn::Min(lo, s), hi = hn::Max(hi, s);
    }
  const V norm1 = hn::Add(hn::Add(hn::Abs(n.x), hn::Abs(n.y)), hn::Abs(n.z));
  const V gap = hn::Add(hn::Mul(norm1, gap_factor), hn::Set(d, detail::kTriangleTiny));
  return hn::Or(hn::Gt(hn::Sub(lo, own_hi), gap), hn::Gt(hn::Sub(own_lo, hi), gap));
}

/// Stage 0 on one vector of candidates, `pt` their corners: keep[j] for the first `lanes`.
template <class D, class V = hn::Vec<D>>
HWY_INLINE void TriangleTest(D d, const Xyz<V> (&pt)[6][2], double abs_reach, double rel_reach, std::size_t lanes,
                             std::uint8_t* keep) {
  // The reach: L ≤ the twelve points' bounding-box extent in the 1-norm.
  V lo[3] = {pt[0][0].x, pt[0][0].y, pt[0][0].z}, hi[3] = {lo[0], lo[1], lo[2]};
  for (int corner = 0; corner < 6; ++corner)
    for (int frame = 0; frame < 2; ++frame) {
      const Xyz<V>& p = pt[corner][frame];
      lo[0] = hn::Min(lo[0], p.x), lo[1] = hn::Min(lo[1], p.y), lo[2] = hn::Min(lo[2], p.z);
      hi[0] = hn::Max(hi[0], p.x), hi[1] = hn::Max(hi[1], p.y), hi[2] = hn::Max(hi[2], p.z);
    }
  const V extent = hn::Add(hn::Add(hn::Sub(hi[0], lo[0]), hn::Sub(hi[1], lo[1])), hn::Sub(hi[2], lo[2]));
  const V reach = hn::Add(hn::Set(d, abs_reach), hn::Mul(hn::Set(d, rel_reach), extent));
  const V gap_factor = hn::Add(hn::Mul(reach, hn::Set(d, detail::kTriangleSlack)),
                               hn::Mul(hn::Set(d, detail::kTriangleErrFactor), extent));
  auto culled = SideCulled(d, pt, 0, 1, 2, 3, gap_factor);
  if (!hn::AllTrue(d, culled)) culled = hn::Or(culled, SideCulled(d, pt, 3, 4, 5, 0, gap_factor));
  std::uint8_t bits[8] = {};
  hn::StoreMaskBits(d, culled, bits);
  for (std::size_t j = 0; j < lanes; ++j) keep[j] = std::uint8_t(((bits[j / 8] >> (j % 8)) & 1) ^ 1);
}

void TriangleFilter(const std::int32_t* pairs, const std::int32_t* faces, const double* x01, std::size_t n, double abs_reach, double rel_reach, std::uint8_t* keep) {
  const hn::ScalableTag<double> d;
  using V = hn::Vec<decltype(d)>;
  const std::size_t N = hn::Lanes(d);
  constexpr std::size_t kBlock = 64, kStride = kBlock + 8;  // + 8: a full vector past a short block's end
  HWY_ALIGN double block[kTriangleColumns * kStride];
  for (std::size_t b = 0; b < n; b += kBlock) {
    const std::size_t m = std::min(kBlock, n - b);
    StageTriangles<kBlock>(pairs + 2 * b, faces, x01, m, block, kStride);
    if (m % N != 0)  // the last vector's lanes past the end: zeros, never reported
      for (int c = 0; c < kTriangleColumns; ++c) std::fill_n(block + kStride * std::size_t(c) + m, N - m % N, 0.0);
    for (std::size_t i = 0; i < m; i += N) {
      Xyz<V> pt[6][2];
      for (int corner = 0; corner < 6; ++corner)
        for (int frame = 0; frame < 2; ++frame) {
          const double* col = block + kStride * std::size_t(triangle_column(corner, frame, 0)) + i;
          pt[corner][frame] = {hn::Load(d, col), hn::Load(d, col + kStride), hn::Load(d, col + 2 * kStride)};
        }
      TriangleTest(d, pt, abs_reach, rel_reach, std::min(N, m - i), keep + b + i);
    }
  }
}

}  // namespace HWY_NAMESPACE
}  // namespace ccdlab
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
#include <algorithm>
#include <cmath>

namespace ccdlab {

HWY_EXPORT(TriangleFilter);

void triangle_filter(std::span<const FacePair> candidates, const Face* faces, const FramePoints* points,
                     CullReach reach, std::uint8_t* keep) {
  static_assert(sizeof(FacePair) == 2 * sizeof(std::int32_t) && sizeof(Face) == 3 * sizeof(std::int32_t) &&
                    sizeof(FramePoints) == 8 * sizeof(double),
                "TriangleFilter reads ids as packed int32 and coordinate j of point p in frame f at 8p + 4f + j");
  if (candidates.empty()) return;
  HWY_DYNAMIC_DISPATCH(TriangleFilter)(reinterpret_cast<const std::int32_t*>(candidates.data()),
                                       reinterpret_cast<const std::int32_t*>(faces),
                                       reinterpret_cast<const double*>(points), candidates.size(), reach.abs,
                                       reach.rel, keep);
}

namespace {
/// SideCulled for one candidate, the same operations in the same order.
bool side_culled(const Vec3 (&pt)[6][2], int o, int b, int c, int other, double gap_factor) {
  const auto cross = [](const Vec3& y, const Vec3& z) {
    return Vec3(y.y() * z.z() - y.z() * z.y(), y.z() * z.x() - y.x() * z.z(), y.x() * z.y() - y.y() * z.x());
  };
  const auto dot = [](const Vec3& x, const Vec3& c) { return (x.x() * c.x() + x.y() * c.y()) + x.z() * c.z(); };
  const Vec3 n0 = cross(pt[b][0] - pt[o][0], pt[c][0] - pt[o][0]);
  const Vec3 n1 = cross(pt[b][1] - pt[o][1], pt[c][1] - pt[o][1]);
  const Vec3 n(n0.x() + n1.x(), n0.y() + n1.y(), n0.z() + n1.z());
  double own_lo = 0, own_hi = 0;
  for (const int corner : {b, c})
    for (int frame = 0; frame < 2; ++frame) {
      const double s = dot(pt[corner][frame] - pt[o][frame], n);
      own_lo = std::min(own_lo, s), own_hi = std::max(own_hi, s);
    }
  double lo = dot(pt[other][0] - pt[o][0], n), hi = lo;
  for (int corner = other; corner < other + 3; ++corner)
    for (int frame = 0; frame < 2; ++frame) {
      if (corner == other && frame == 0) continue;
      const double s = dot(pt[corner][frame] - pt[o][frame], n);
      lo = std::min(lo, s), hi = std::max(hi, s);
    }
  const double norm1 = (std::abs(n.x()) + std::abs(n.y())) + std::abs(n.z());
  const double gap = norm1 * gap_factor + detail::kTriangleTiny;
  return lo - own_hi > gap || own_lo - hi > gap;
}
}  // namespace

bool triangle_pair_keeps(const Face& f, const Face& g, const Vec3* x_t0, const Vec3* x_t1, CullReach reach) {
  Vec3 pt[6][2];
  for (int k = 0; k < 3; ++k) {
    pt[k][0] = x_t0[f[k]], pt[k][1] = x_t1[f[k]];
    pt[3 + k][0] = x_t0[g[k]], pt[3 + k][1] = x_t1[g[k]];
  }
  Vec3 lo = pt[0][0], hi = pt[0][0];
  for (const auto& corner : pt)
    for (const Vec3& p : corner) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  const double extent = ((hi.x() - lo.x()) + (hi.y() - lo.y())) + (hi.z() - lo.z());
  const double r = reach.abs + reach.rel * extent;
  const double gap_factor = r * detail::kTriangleSlack + detail::kTriangleErrFactor * extent;
  return !(side_culled(pt, 0, 1, 2, 3, gap_factor) || side_culled(pt, 3, 4, 5, 0, gap_factor));
}

}  // namespace ccdlab
#endif  // HWY_ONCE
