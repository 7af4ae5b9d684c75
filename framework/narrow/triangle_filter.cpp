// Highway compiles this file once per SIMD target (foreach_target.h) and picks one at run time.
#include "framework/narrow/triangle_filter.hpp"

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "framework/narrow/triangle_filter.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

#ifndef CCDLAB_TRIANGLE_FILTER_LAYOUT
#define CCDLAB_TRIANGLE_FILTER_LAYOUT
namespace ccdlab::detail {
// A staged candidate: corners 0–2 of f, then 0–2 of g; each at t0 then t1; x, y, z. One column per coordinate.
constexpr int kTriangleCorners = 6;
constexpr int kTriangleColumns = kTriangleCorners * 2 * 3;
constexpr int triangle_column(int corner, int frame, int axis) { return (corner * 2 + frame) * 3 + axis; }
// The gap's terms (triangle_filter.hpp): 16u per unit of L̄, the slack, and the floor.
constexpr float kTriangleErrFactor = 16 * 0x1p-24f, kTriangleSlack = 1 + 0x1p-18f, kTriangleTiny = 1e-30f;
// The 26-DOP's thirteen axes, as DopValue and dop_value compute them: x, y, z; x ± y, x ± z, y ± z; x + y ± z,
// x − y + z, −x + y + z. ‖axis‖₁ scales the gap.
constexpr int kDopAxisCount = 13;
// A staged candidate's boxes: face (f, g), frame, side (lo, hi), axis.
constexpr int kBoxColumns = 24;
constexpr int box_column(int face, int frame, int side, int axis) { return ((face * 2 + frame) * 2 + side) * 3 + axis; }
constexpr int dop_axis_norm1(int a) { return a < 3 ? 1 : a < 9 ? 2 : 3; }
}  // namespace ccdlab::detail
#endif

HWY_BEFORE_NAMESPACE();
namespace ccdlab {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;
using detail::kTriangleColumns;
using detail::triangle_column;

/// Writes rows [i, i + 8) of six columns from eight records of 8 floats each (a b c 0 | d e f 0), at `base` +
/// off[k]: one aligned 256-bit load each, then an 8 × 8 transpose of which six rows are kept; col[h][j] receives
/// half h's value j.
HWY_INLINE void StoreTransposed8(const float* base, const std::int32_t* off, float* const (&col)[2][3]) {
#if HWY_TARGET == HWY_AVX2 || HWY_TARGET == HWY_AVX3 || HWY_TARGET == HWY_AVX3_DL
  const hn::Full256<float> d8;
  const hn::Full256<double> d4;
  hn::Vec<decltype(d8)> r[8];
  for (int k = 0; k < 8; ++k) r[k] = hn::Load(d8, base + off[k]);
  // Per 128-bit half: pairs of rows interleaved, then pairs of pairs, then the halves joined.
  hn::Vec<decltype(d4)> ab[4], c0[4];
  for (int k = 0; k < 4; ++k) {
    ab[k] = hn::BitCast(d4, hn::InterleaveLower(d8, r[2 * k], r[2 * k + 1]));  // a a b b | d d e e
    c0[k] = hn::BitCast(d4, hn::InterleaveUpper(d8, r[2 * k], r[2 * k + 1]));  // c c 0 0 | f f 0 0
  }
  const hn::Vec<decltype(d4)> value[2][3] = {
      {hn::InterleaveLower(d4, ab[0], ab[1]), hn::InterleaveUpper(d4, ab[0], ab[1]), hn::InterleaveLower(d4, c0[0], c0[1])},
      {hn::InterleaveLower(d4, ab[2], ab[3]), hn::InterleaveUpper(d4, ab[2], ab[3]), hn::InterleaveLower(d4, c0[2], c0[3])}};
  for (int j = 0; j < 3; ++j) {  // value[q][j]: rows 4q..4q+3's value j, half 0 | half 1
    hn::Store(hn::BitCast(d8, hn::ConcatLowerLower(d4, value[1][j], value[0][j])), d8, col[0][j]);
    hn::Store(hn::BitCast(d8, hn::ConcatUpperUpper(d4, value[1][j], value[0][j])), d8, col[1][j]);
  }
#else
  for (int k = 0; k < 8; ++k)
    for (int h = 0; h < 2; ++h)
      for (int j = 0; j < 3; ++j) col[h][j][k] = base[off[k] + 4 * h + j];
#endif
}

/// Writes rows [0, n ≤ kBlock) of `block` (column c at block + c·stride) from records of 8 floats at `base` +
/// off[e][i], e < kEntities, whose halves h and values j go to column column(e, h, j). The offsets are found
/// first, in a loop of their own: pair → face → point is a chain of dependent loads, and a short loop lets the
/// core run far ahead on it.
template <std::size_t kBlock, int kEntities, class Column>
HWY_INLINE void StageRecords(const std::int32_t (&off)[kEntities][kBlock], const float* base, std::size_t n,
                             float* block, std::size_t stride, const Column& column) {
  n = std::min(n, kBlock);  // callers pass at most kBlock; said so the compiler sees the bound of `off`
  std::size_t i = 0;
  for (; i + 8 <= n; i += 8)
    for (int e = 0; e < kEntities; ++e) {
      float* const col[2][3] = {
          {block + stride * std::size_t(column(e, 0, 0)) + i, block + stride * std::size_t(column(e, 0, 1)) + i,
           block + stride * std::size_t(column(e, 0, 2)) + i},
          {block + stride * std::size_t(column(e, 1, 0)) + i, block + stride * std::size_t(column(e, 1, 1)) + i,
           block + stride * std::size_t(column(e, 1, 2)) + i}};
      StoreTransposed8(base, off[e] + i, col);
    }
  for (; i < n; ++i)
    for (int e = 0; e < kEntities; ++e)
      for (int h = 0; h < 2; ++h)
        for (int j = 0; j < 3; ++j) block[stride * std::size_t(column(e, h, j)) + i] = base[off[e][i] + 4 * h + j];
}

/// Rows [0, n) of `block` from the candidates' corners (triangle_column; FloatFramePoints at x01).
template <std::size_t kBlock>
void StageTriangles(const std::int32_t* pairs, const std::int32_t* faces, const float* x01, std::size_t n,
                    float* block, std::size_t stride) {
  n = std::min(n, kBlock);
  std::int32_t off[detail::kTriangleCorners][kBlock];
  for (std::size_t i = 0; i < n; ++i)
    for (int corner = 0; corner < detail::kTriangleCorners; ++corner)
      off[corner][i] = 8 * faces[3 * std::ptrdiff_t(pairs[2 * i + corner / 3]) + corner % 3];
  StageRecords<kBlock>(off, x01, n, block, stride, [](int corner, int frame, int axis) { return triangle_column(corner, frame, axis); });
}

/// Rows [0, n) of `block` from the candidates' two faces' boxes (box_column; FloatFaceBoxes at boxes).
template <std::size_t kBlock>
void StageBoxes(const std::int32_t* pairs, const float* boxes, std::size_t n, float* block, std::size_t stride) {
  n = std::min(n, kBlock);
  std::int32_t off[4][kBlock];  // (face, frame)
  for (std::size_t i = 0; i < n; ++i)
    for (int e = 0; e < 4; ++e) off[e][i] = 16 * pairs[2 * i + e / 2] + 8 * (e % 2);
  StageRecords<kBlock>(off, boxes, n, block, stride, [](int e, int side, int axis) { return detail::box_column(e / 2, e % 2, side, axis); });
}

template <class V>
struct Xyz {
  V x, y, z;
};

template <class V>
HWY_INLINE Xyz<V> Sub(const Xyz<V>& u, const Xyz<V>& v) {
  return Xyz<V>{hn::Sub(u.x, v.x), hn::Sub(u.y, v.y), hn::Sub(u.z, v.z)};
}
template <class V>
HWY_INLINE Xyz<V> Cross(const Xyz<V>& y, const Xyz<V>& z) {
  return Xyz<V>{hn::Sub(hn::Mul(y.y, z.z), hn::Mul(y.z, z.y)), hn::Sub(hn::Mul(y.z, z.x), hn::Mul(y.x, z.z)),
                hn::Sub(hn::Mul(y.x, z.y), hn::Mul(y.y, z.x))};
}
template <class V>
HWY_INLINE V Dot(const Xyz<V>& x, const Xyz<V>& c) {
  return hn::Add(hn::Add(hn::Mul(x.x, c.x), hn::Mul(x.y, c.y)), hn::Mul(x.z, c.z));
}
/// The axis of two moving vectors: u0×v0 + u1×v1 (t0 and t1).
template <class V>
HWY_INLINE Xyz<V> MovingCross(const Xyz<V>& u0, const Xyz<V>& v0, const Xyz<V>& u1, const Xyz<V>& v1) {
  const Xyz<V> n0 = Cross(u0, v0), n1 = Cross(u1, v1);
  return Xyz<V>{hn::Add(n0.x, n1.x), hn::Add(n0.y, n1.y), hn::Add(n0.z, n1.z)};
}

/// The twelve points relative to corner 0 at t0 (rel[0][0] = 0): what every axis projects.
template <class V>
struct Corners {
  Xyz<V> pt[6][2];   ///< corners 0–2 of f, 3–5 of g; at t0, t1
  Xyz<V> rel[6][2];  ///< pt − pt[0][0]
};

/// Whether one face stays beyond the other along an axis by more than `gap` at both ends of the step, hence
/// throughout (triangle_filter.hpp). `project(corner, frame)`: the corner's projection on the axis.
template <class D, class Project, class V = hn::Vec<D>>
HWY_INLINE hn::Mask<D> Separated(D, const Project& project, V gap) {
  V lo[2][2], hi[2][2];  // [face][frame]
  for (int face = 0; face < 2; ++face)
    for (int frame = 0; frame < 2; ++frame) {
      lo[face][frame] = hi[face][frame] = project(3 * face, frame);
      for (int k = 1; k < 3; ++k) {
        const V s = project(3 * face + k, frame);
        lo[face][frame] = hn::Min(lo[face][frame], s), hi[face][frame] = hn::Max(hi[face][frame], s);
      }
    }
  const auto g_above = hn::And(hn::Gt(hn::Sub(lo[1][0], hi[0][0]), gap), hn::Gt(hn::Sub(lo[1][1], hi[0][1]), gap));
  const auto g_below = hn::And(hn::Gt(hn::Sub(lo[0][0], hi[1][0]), gap), hn::Gt(hn::Sub(lo[0][1], hi[1][1]), gap));
  return hn::Or(g_above, g_below);
}

/// Axis a of the 26-DOP (detail::kDopAxes) on a relative point: sums and differences of its coordinates, in the
/// order of dop_value.
template <class V>
HWY_INLINE V DopValue(int a, const Xyz<V>& p) {
  switch (a) {
    case 0: return p.x;
    case 1: return p.y;
    case 2: return p.z;
    case 3: return hn::Add(p.x, p.y);
    case 4: return hn::Sub(p.x, p.y);
    case 5: return hn::Add(p.x, p.z);
    case 6: return hn::Sub(p.x, p.z);
    case 7: return hn::Add(p.y, p.z);
    case 8: return hn::Sub(p.y, p.z);
    case 9: return hn::Add(hn::Add(p.x, p.y), p.z);
    case 10: return hn::Sub(hn::Add(p.x, p.y), p.z);
    case 11: return hn::Add(hn::Sub(p.x, p.y), p.z);
    default: return hn::Sub(p.z, hn::Sub(p.x, p.y));
  }
}

/// Axes [first, kAxisCount) on one vector of candidates: culled lanes, or'ed into `culled`, stopping once every
/// lane is culled. Axes 0–2 (x, y, z) project the points as they are (exactly; so does the box pass), the other
/// DOP axes the points relative to corner 0, then the two faces' normals.
template <class D, class V = hn::Vec<D>, class M = hn::Mask<D>>
HWY_INLINE M TriangleCulled(D d, const Corners<V>& c, V gap_factor, int first, M culled) {
  const V tiny = hn::Set(d, detail::kTriangleTiny);
  for (int a = first; a < detail::kDopAxisCount && !hn::AllTrue(d, culled); ++a) {
    const V gap = hn::Add(hn::Mul(hn::Set(d, float(detail::dop_axis_norm1(a))), gap_factor), tiny);
    culled = hn::Or(culled, a < 3 ? Separated(d, [&](int corner, int frame) { return DopValue(a, c.pt[corner][frame]); }, gap)
                                  : Separated(d, [&](int corner, int frame) { return DopValue(a, c.rel[corner][frame]); }, gap));
  }
  for (int o = 0; o < 6 && !hn::AllTrue(d, culled); o += 3) {
    const auto& pt = c.pt;
    const Xyz<V> n = MovingCross(Sub(pt[o + 1][0], pt[o][0]), Sub(pt[o + 2][0], pt[o][0]),
                                 Sub(pt[o + 1][1], pt[o][1]), Sub(pt[o + 2][1], pt[o][1]));
    const V norm1 = hn::Add(hn::Add(hn::Abs(n.x), hn::Abs(n.y)), hn::Abs(n.z));
    const V gap = hn::Add(hn::Mul(norm1, gap_factor), tiny);
    culled = hn::Or(culled, Separated(d, [&](int corner, int frame) { return Dot(c.rel[corner][frame], n); }, gap));
  }
  return culled;
}

/// The gap factor of GapFactor from L̄ (the same operations).
template <class D, class V = hn::Vec<D>>
HWY_INLINE V GapFactorOf(D d, V extent, float abs_reach, float rel_reach, float error) {
  const V eps8 = hn::Mul(hn::Set(d, 8.0f), hn::Set(d, error));
  const V reach = hn::Add(hn::Set(d, abs_reach), hn::Mul(hn::Set(d, rel_reach), hn::Add(extent, eps8)));
  return hn::Add(hn::Add(hn::Mul(reach, hn::Set(d, detail::kTriangleSlack)),
                         hn::Mul(hn::Set(d, detail::kTriangleErrFactor), extent)),
                 eps8);
}

/// Axes x, y, z on one vector of candidates from their faces' boxes at both ends (columns box_column at
/// `block` + c·stride + i): the same answers as TriangleCulled's first three axes, the same gap factor.
template <class D, class V = hn::Vec<D>>
HWY_INLINE hn::Mask<D> BoxesCulled(D d, const float* block, std::size_t stride, std::size_t i, float abs_reach,
                                   float rel_reach, float error, hn::Mask<D> culled) {
  const auto at = [&](int face, int frame, int side, int axis) {
    return hn::Load(d, block + stride * std::size_t(detail::box_column(face, frame, side, axis)) + i);
  };
  V lo[3], hi[3];
  for (int axis = 0; axis < 3; ++axis) {
    lo[axis] = hn::Min(hn::Min(at(0, 0, 0, axis), at(0, 1, 0, axis)), hn::Min(at(1, 0, 0, axis), at(1, 1, 0, axis)));
    hi[axis] = hn::Max(hn::Max(at(0, 0, 1, axis), at(0, 1, 1, axis)), hn::Max(at(1, 0, 1, axis), at(1, 1, 1, axis)));
  }
  const V extent = hn::Add(hn::Add(hn::Sub(hi[0], lo[0]), hn::Sub(hi[1], lo[1])), hn::Sub(hi[2], lo[2]));
  const V gap = hn::Add(hn::Mul(hn::Set(d, 1.0f), GapFactorOf(d, extent, abs_reach, rel_reach, error)),
                        hn::Set(d, detail::kTriangleTiny));
  for (int axis = 0; axis < 3; ++axis) {
    const auto g_above = hn::And(hn::Gt(hn::Sub(at(1, 0, 0, axis), at(0, 0, 1, axis)), gap),
                                 hn::Gt(hn::Sub(at(1, 1, 0, axis), at(0, 1, 1, axis)), gap));
    const auto g_below = hn::And(hn::Gt(hn::Sub(at(0, 0, 0, axis), at(1, 0, 1, axis)), gap),
                                 hn::Gt(hn::Sub(at(0, 1, 0, axis), at(1, 1, 1, axis)), gap));
    culled = hn::Or(culled, hn::Or(g_above, g_below));
  }
  return culled;
}

/// r·slack + 16u·L̄ + 8ε for one vector of candidates, r = abs + rel·(L̄ + 8ε): L ≤ the twelve points'
/// bounding-box extent in the 1-norm, + 6ε for the exact points. `abs_reach`, `rel_reach` and `error` (ε) as
/// floats no smaller than the doubles they stand for.
template <class D, class V = hn::Vec<D>>
HWY_INLINE V GapFactor(D d, const Corners<V>& c, float abs_reach, float rel_reach, float error) {
  const auto& pt = c.pt;
  V lo[3] = {pt[0][0].x, pt[0][0].y, pt[0][0].z}, hi[3] = {lo[0], lo[1], lo[2]};
  for (int corner = 0; corner < 6; ++corner)
    for (int frame = 0; frame < 2; ++frame) {
      const Xyz<V>& p = pt[corner][frame];
      lo[0] = hn::Min(lo[0], p.x), lo[1] = hn::Min(lo[1], p.y), lo[2] = hn::Min(lo[2], p.z);
      hi[0] = hn::Max(hi[0], p.x), hi[1] = hn::Max(hi[1], p.y), hi[2] = hn::Max(hi[2], p.z);
    }
  const V extent = hn::Add(hn::Add(hn::Sub(hi[0], lo[0]), hn::Sub(hi[1], lo[1])), hn::Sub(hi[2], lo[2]));
  return GapFactorOf(d, extent, abs_reach, rel_reach, error);
}

/// Two passes, so that the costly axes see only what the cheap ones leave: x, y and z from the faces' boxes (a line a face, no arithmetic but the comparisons) on every candidate,
/// then the other axes on the survivors, kBlock at a time, from their corners.
std::size_t TriangleFilter(const std::int32_t* pairs, const std::int32_t* faces, const float* x01, const float* boxes,
                           std::size_t n, float abs_reach, float rel_reach, float error, std::uint8_t* keep,
                           bool box_pass) {
  const hn::ScalableTag<float> d;
  using V = hn::Vec<decltype(d)>;
  const std::size_t N = hn::Lanes(d);
  constexpr std::size_t kBlock = 64, kStride = kBlock + 16;  // + 16: a full vector past a short block's end
  HWY_ALIGN float block[kTriangleColumns * kStride];
  std::int32_t survivors[2 * 2 * kBlock];  // < kBlock left over + a block's; their pairs, and rows in `keep`
  std::size_t survivor_row[2 * kBlock], count = 0, fine = 0;
  const auto pad = [&](int columns, std::size_t m) {  // the last vector's lanes past m: zeros, never culled
    if (m % N != 0)
      for (int c = 0; c < columns; ++c) std::fill_n(block + kStride * std::size_t(c) + m, N - m % N, 0.0f);
  };
  const auto corners_pass = [&](std::size_t m) {  // axes 3.. on the first m survivors
    fine += m;
    StageTriangles<kBlock>(survivors, faces, x01, m, block, kStride);
    pad(kTriangleColumns, m);
    for (std::size_t i = 0; i < m; i += N) {
      Corners<V> c;
      for (int corner = 0; corner < 6; ++corner)
        for (int frame = 0; frame < 2; ++frame) {
          const float* col = block + kStride * std::size_t(triangle_column(corner, frame, 0)) + i;
          c.pt[corner][frame] = {hn::Load(d, col), hn::Load(d, col + kStride), hn::Load(d, col + 2 * kStride)};
        }
      for (int corner = 0; corner < 6; ++corner)
        for (int frame = 0; frame < 2; ++frame) c.rel[corner][frame] = Sub(c.pt[corner][frame], c.pt[0][0]);
      const std::size_t lanes = std::min(N, m - i);
      const auto culled = TriangleCulled(d, c, GapFactor(d, c, abs_reach, rel_reach, error), 3,
                                         hn::Not(hn::FirstN(d, lanes)));
      std::uint8_t bits[8] = {};
      hn::StoreMaskBits(d, culled, bits);
      for (std::size_t j = 0; j < lanes; ++j)
        if ((bits[j / 8] >> (j % 8)) & 1) keep[survivor_row[i + j]] = 0;
    }
  };
  for (std::size_t b = 0; b < n; b += kBlock) {
    const std::size_t m = std::min(kBlock, n - b);
    if (box_pass) {
      StageBoxes<kBlock>(pairs + 2 * b, boxes, m, block, kStride);
      pad(detail::kBoxColumns, m);
      for (std::size_t i = 0; i < m; i += N) {
        const std::size_t lanes = std::min(N, m - i);
        const auto culled = BoxesCulled(d, block, kStride, i, abs_reach, rel_reach, error, hn::FirstN(d, 0));
        std::uint8_t bits[8] = {};
        hn::StoreMaskBits(d, culled, bits);
        for (std::size_t j = 0; j < lanes; ++j) keep[b + i + j] = std::uint8_t(((bits[j / 8] >> (j % 8)) & 1) ^ 1);
      }
    } else {
      std::fill_n(keep + b, m, std::uint8_t(1));
    }
    for (std::size_t j = 0; j < m; ++j) {  // branch-free append of the survivors
      const std::size_t row = b + j;
      survivors[2 * count] = pairs[2 * row], survivors[2 * count + 1] = pairs[2 * row + 1];
      survivor_row[count] = row;
      count += keep[row];
    }
    if (count >= kBlock) {
      corners_pass(kBlock);
      count -= kBlock;
      std::copy_n(survivors + 2 * kBlock, 2 * count, survivors);
      std::copy_n(survivor_row + kBlock, count, survivor_row);
    }
  }
  if (count > 0) corners_pass(count);  // count < kBlock here
  return fine;
}

}  // namespace HWY_NAMESPACE
}  // namespace ccdlab
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
#include <algorithm>
#include <cmath>
#include <limits>

namespace ccdlab {

HWY_EXPORT(TriangleFilter);

namespace {
/// A float no smaller than x (non-negative x; +∞ past float's range, NaN stays NaN).
float float_at_least(double x) {
  const float f = float(x);
  return double(f) >= x ? f : std::nextafter(f, std::numeric_limits<float>::infinity());
}
}  // namespace

std::size_t triangle_filter(std::span<const FacePair> candidates, const Face* faces, const FloatFrames& frames,
                            CullReach reach, std::uint8_t* keep, bool box_pass) {
  static_assert(sizeof(FacePair) == 2 * sizeof(std::int32_t) && sizeof(Face) == 3 * sizeof(std::int32_t) &&
                    sizeof(FloatFramePoints) == 8 * sizeof(float) && sizeof(FloatFaceBoxes) == 16 * sizeof(float),
                "TriangleFilter reads ids as packed int32 and coordinate j of point p in frame f at 8p + 4f + j");
  if (candidates.empty()) return 0;
  return HWY_DYNAMIC_DISPATCH(TriangleFilter)(reinterpret_cast<const std::int32_t*>(candidates.data()),
                                       reinterpret_cast<const std::int32_t*>(faces),
                                       reinterpret_cast<const float*>(frames.points.data()),
                                       reinterpret_cast<const float*>(frames.boxes.data()), candidates.size(),
                                       float_at_least(reach.abs), float_at_least(reach.rel),
                                       float_at_least(frames.error), keep, box_pass);
}

namespace {
struct Vec3f {
  float x, y, z;
};
Vec3f operator-(const Vec3f& a, const Vec3f& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
Vec3f cross(const Vec3f& y, const Vec3f& z) {
  return Vec3f{y.y * z.z - y.z * z.y, y.z * z.x - y.x * z.z, y.x * z.y - y.y * z.x};
}
float dot(const Vec3f& x, const Vec3f& c) { return (x.x * c.x + x.y * c.y) + x.z * c.z; }
Vec3f moving_cross(const Vec3f& u0, const Vec3f& v0, const Vec3f& u1, const Vec3f& v1) {
  const Vec3f n0 = cross(u0, v0), n1 = cross(u1, v1);
  return {n0.x + n1.x, n0.y + n1.y, n0.z + n1.z};
}

/// Separated for one candidate, the same operations in the same order (`value[corner][frame]`).
bool separated(const float (&value)[6][2], float gap) {
  float lo[2][2], hi[2][2];
  for (int face = 0; face < 2; ++face)
    for (int frame = 0; frame < 2; ++frame) {
      lo[face][frame] = hi[face][frame] = value[3 * face][frame];
      for (int k = 1; k < 3; ++k) {
        const float s = value[3 * face + k][frame];
        lo[face][frame] = std::min(lo[face][frame], s), hi[face][frame] = std::max(hi[face][frame], s);
      }
    }
  return (lo[1][0] - hi[0][0] > gap && lo[1][1] - hi[0][1] > gap) ||
         (lo[0][0] - hi[1][0] > gap && lo[0][1] - hi[1][1] > gap);
}

/// DopValue for one point.
float dop_value(int a, const Vec3f& p) {
  switch (a) {
    case 0: return p.x;
    case 1: return p.y;
    case 2: return p.z;
    case 3: return p.x + p.y;
    case 4: return p.x - p.y;
    case 5: return p.x + p.z;
    case 6: return p.x - p.z;
    case 7: return p.y + p.z;
    case 8: return p.y - p.z;
    case 9: return (p.x + p.y) + p.z;
    case 10: return (p.x + p.y) - p.z;
    case 11: return (p.x - p.y) + p.z;
    default: return p.z - (p.x - p.y);
  }
}
}  // namespace

bool triangle_pair_keeps(const Face& f, const Face& g, const FloatFrames& frames, CullReach reach) {
  Vec3f pt[6][2], rel[6][2];
  for (int k = 0; k < 6; ++k) {
    const FloatFramePoints& p = frames.points[std::size_t(k < 3 ? f[k] : g[k - 3])];
    pt[k][0] = {p.t0[0], p.t0[1], p.t0[2]}, pt[k][1] = {p.t1[0], p.t1[1], p.t1[2]};
  }
  for (int k = 0; k < 6; ++k) rel[k][0] = pt[k][0] - pt[0][0], rel[k][1] = pt[k][1] - pt[0][0];
  float lo[3] = {pt[0][0].x, pt[0][0].y, pt[0][0].z}, hi[3] = {lo[0], lo[1], lo[2]};
  for (const auto& corner : pt)
    for (const Vec3f& p : corner) {
      lo[0] = std::min(lo[0], p.x), lo[1] = std::min(lo[1], p.y), lo[2] = std::min(lo[2], p.z);
      hi[0] = std::max(hi[0], p.x), hi[1] = std::max(hi[1], p.y), hi[2] = std::max(hi[2], p.z);
    }
  const float extent = ((hi[0] - lo[0]) + (hi[1] - lo[1])) + (hi[2] - lo[2]);
  const float eps8 = 8.0f * float_at_least(frames.error);
  const float r = float_at_least(reach.abs) + float_at_least(reach.rel) * (extent + eps8);
  const float gap_factor = (r * detail::kTriangleSlack + detail::kTriangleErrFactor * extent) + eps8;
  float value[6][2];
  for (int a = 0; a < detail::kDopAxisCount; ++a) {  // the 26-DOP's axes
    const auto& p = a < 3 ? pt : rel;  // x, y, z as they are (exact), the others relative to corner 0
    for (int k = 0; k < 6; ++k) value[k][0] = dop_value(a, p[k][0]), value[k][1] = dop_value(a, p[k][1]);
    if (separated(value, float(detail::dop_axis_norm1(a)) * gap_factor + detail::kTriangleTiny)) return false;
  }
  for (int o = 0; o < 6; o += 3) {  // the two face axes
    const Vec3f n = moving_cross(pt[o + 1][0] - pt[o][0], pt[o + 2][0] - pt[o][0], pt[o + 1][1] - pt[o][1],
                                 pt[o + 2][1] - pt[o][1]);
    const float norm1 = (std::abs(n.x) + std::abs(n.y)) + std::abs(n.z);
    for (int k = 0; k < 6; ++k) value[k][0] = dot(rel[k][0], n), value[k][1] = dot(rel[k][1], n);
    if (separated(value, norm1 * gap_factor + detail::kTriangleTiny)) return false;
  }
  return true;
}

}  // namespace ccdlab
#endif  // HWY_ONCE
