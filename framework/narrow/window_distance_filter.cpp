// Highway compiles this file once per SIMD target (foreach_target.h) and picks one at run time. The SIMD kernel
// and the plain reference below evaluate the same expressions in the same order (-ffp-contract=off); every
// minimum, maximum and clamp is a compare-and-select, so both treat a NaN alike.
#include "framework/narrow/window_distance_filter.hpp"

#include <bit>
#include <cmath>

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "framework/narrow/window_distance_filter.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

#ifndef CCDLAB_PROXIMITY_FILTER_CONSTANTS
#define CCDLAB_PROXIMITY_FILTER_CONSTANTS
namespace ccdlab::proximity_detail {
constexpr double kU = 0x1p-53;
constexpr double kSlack = 128 * kU;    // relative to M: positions at the window's middle, projections, columns
constexpr double kFactor = 1 + 1e-12;  // on the speed and the reach
}  // namespace ccdlab::proximity_detail
#endif

HWY_BEFORE_NAMESPACE();
namespace ccdlab {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;
using namespace proximity_detail;

template <class V>
struct P3 {
  V x, y, z;
};
template <class V>
HWY_INLINE P3<V> Sub3(const P3<V>& p, const P3<V>& q) { return {hn::Sub(p.x, q.x), hn::Sub(p.y, q.y), hn::Sub(p.z, q.z)}; }
template <class V>
HWY_INLINE P3<V> Add3(const P3<V>& p, const P3<V>& q) { return {hn::Add(p.x, q.x), hn::Add(p.y, q.y), hn::Add(p.z, q.z)}; }
template <class V>  // p + s·q
HWY_INLINE P3<V> Along(const P3<V>& p, V s, const P3<V>& q) {
  return {hn::Add(p.x, hn::Mul(s, q.x)), hn::Add(p.y, hn::Mul(s, q.y)), hn::Add(p.z, hn::Mul(s, q.z))};
}
template <class V>
HWY_INLINE V Dot3(const P3<V>& p, const P3<V>& q) {
  return hn::Add(hn::Add(hn::Mul(p.x, q.x), hn::Mul(p.y, q.y)), hn::Mul(p.z, q.z));
}
template <class V>
HWY_INLINE P3<V> Cross3(const P3<V>& y, const P3<V>& z) {
  return {hn::Sub(hn::Mul(y.y, z.z), hn::Mul(y.z, z.y)), hn::Sub(hn::Mul(y.z, z.x), hn::Mul(y.x, z.z)),
          hn::Sub(hn::Mul(y.x, z.y), hn::Mul(y.y, z.x))};
}
template <class V>
HWY_INLINE V Larger(V a, V b) { return hn::IfThenElse(hn::Gt(b, a), b, a); }
template <class V>
HWY_INLINE V Smaller(V a, V b) { return hn::IfThenElse(hn::Lt(b, a), b, a); }

/// The point of the segment s + [0, 1]·dir closest to p (a zero-length segment: s).
template <class V>
HWY_INLINE P3<V> ClosestOnSegment(const P3<V>& p, const P3<V>& s, const P3<V>& dir, V zero, V one) {
  const V dd = Dot3(dir, dir);
  V q = hn::IfThenElseZero(hn::Gt(dd, zero), hn::Div(Dot3(Sub3(p, s), dir), dd));
  q = hn::IfThenElse(hn::Gt(q, zero), q, zero);
  q = hn::IfThenElse(hn::Lt(q, one), q, one);
  return Along(s, q, dir);
}

/// Items [0, n) (row, window middle), all VF or all EE; proven[i] = 1 when item i's window cannot hold a contact.
/// Reads whole vectors: the item arrays hold a vector's worth past n.
template <bool kVf>
void ProximityItemsT(const double* const* col, const double* reach, const std::int64_t* rows, const double* times,
                     std::size_t n, double half_width, std::uint8_t* proven) {
  const hn::ScalableTag<double> d;
  const hn::RebindToSigned<decltype(d)> di;
  using V = hn::Vec<decltype(d)>;
  const std::size_t N = hn::Lanes(d);
  const V zero = hn::Zero(d), one = hn::Set(d, 1.0);
  const V factor = hn::Set(d, kFactor), slack = hn::Set(d, kSlack), hw = hn::Set(d, half_width);
  for (std::size_t i = 0; i < n; i += N) {
    const auto idx = hn::LoadU(di, rows + i);
    auto point = [&](int c) {
      return P3<V>{hn::GatherIndex(d, col[c], idx), hn::GatherIndex(d, col[c + 1], idx), hn::GatherIndex(d, col[c + 2], idx)};
    };
    const P3<V> a0 = point(PlaneBatch::A0x), a1 = point(PlaneBatch::A1x), b0 = point(PlaneBatch::B0x),
                b1 = point(PlaneBatch::B1x), c0 = point(PlaneBatch::C0x), c1 = point(PlaneBatch::C1x);
    V M = zero;
    for (const P3<V>* p : {&a0, &a1, &b0, &b1, &c0, &c1})
      M = Larger(Larger(Larger(M, hn::Abs(p->x)), hn::Abs(p->y)), hn::Abs(p->z));
    const P3<V> ma = Sub3(a1, a0), mb = Sub3(b1, b0), mc = Sub3(c1, c0);
    auto norm = [](const P3<V>& v) { return hn::Sqrt(Dot3(v, v)); };
    V speed = Larger(norm(ma), norm(Sub3(ma, mb)));
    if constexpr (kVf) {
      speed = Larger(speed, norm(Sub3(ma, mc)));
    } else {
      const P3<V> mac = Add3(ma, mc);
      speed = Larger(Larger(speed, norm(mac)), norm(Sub3(mac, mb)));
    }
    const V need = hn::Add(hn::Add(hn::Mul(hn::GatherIndex(d, reach, idx), factor), hn::Mul(hn::Mul(speed, hw), factor)),
                           hn::Mul(slack, M));
    const V t = hn::LoadU(d, times + i);
    const P3<V> a = Along(a0, t, ma), b = Along(b0, t, mb), c = Along(c0, t, mc);
    const P3<V> origin{zero, zero, zero};
    const V need2 = hn::Mul(need, need);
    auto proven_by = hn::Lt(one, zero);  // no lane yet
    auto offer = [&](V numerator, V length2) {  // the gap numerator / |v| exceeds need, |v|² = length2 > 0
      const auto beyond = hn::And(hn::Gt(numerator, zero), hn::Gt(hn::Mul(numerator, numerator), hn::Mul(need2, length2)));
      proven_by = hn::Or(proven_by, hn::And(hn::Gt(length2, zero), beyond));
    };
    const P3<V> normal = Cross3(b, c);
    const V n_len = Dot3(normal, normal);
    if constexpr (kVf) {  // vertex a, face {0, b, c}; a direction points from the face to the vertex
      auto face_gap = [&](const P3<V>& v, V len) {
        offer(hn::Sub(Dot3(v, a), Larger(Larger(zero, Dot3(v, b)), Dot3(v, c))), len);
      };
      const V na = Dot3(normal, a), nb = Dot3(normal, b), nc = Dot3(normal, c);
      offer(hn::Sub(na, Larger(Larger(zero, nb), nc)), n_len);
      offer(hn::Sub(Smaller(Smaller(zero, nb), nc), na), n_len);  // −normal
      for (const P3<V> v : {Sub3(a, ClosestOnSegment(a, origin, b, zero, one)),
                            Sub3(a, ClosestOnSegment(a, b, Sub3(c, b), zero, one)),
                            Sub3(a, ClosestOnSegment(a, origin, c, zero, one))})
        face_gap(v, Dot3(v, v));
    } else {  // edge {0, b}, edge {a, e = a + c}; a direction points from the first edge to the second
      const P3<V> e = Add3(a, c);
      auto edge_gap = [&](const P3<V>& v, V len) {
        offer(hn::Sub(Smaller(Dot3(v, a), Dot3(v, e)), Larger(zero, Dot3(v, b))), len);
      };
      const V na = Dot3(normal, a), ne = Dot3(normal, e), nb = Dot3(normal, b);
      offer(hn::Sub(Smaller(na, ne), Larger(zero, nb)), n_len);
      offer(hn::Sub(Smaller(zero, nb), Larger(na, ne)), n_len);  // −normal
      for (const P3<V> v : {ClosestOnSegment(origin, a, c, zero, one), Sub3(ClosestOnSegment(b, a, c, zero, one), b),
                            Sub3(a, ClosestOnSegment(a, origin, b, zero, one)),
                            Sub3(e, ClosestOnSegment(e, origin, b, zero, one))})
        edge_gap(v, Dot3(v, v));
    }
    std::uint8_t bits[8] = {};
    hn::StoreMaskBits(d, proven_by, bits);
    for (std::size_t j = 0; j < N; ++j) proven[i + j] = (bits[j / 8] >> (j % 8)) & 1;
  }
}

void WindowDistanceItems(const double* const* col, const double* reach, const std::int64_t* rows, const double* times,
                    std::size_t n, double half_width, bool vf, std::uint8_t* proven) {
  if (vf) ProximityItemsT<true>(col, reach, rows, times, n, half_width, proven);
  else ProximityItemsT<false>(col, reach, rows, times, n, half_width, proven);
}

}  // namespace HWY_NAMESPACE
}  // namespace ccdlab
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace ccdlab {

HWY_EXPORT(WindowDistanceItems);

namespace {
/// At least the widest vector's lanes (AVX-512: 8 doubles), a multiple of every target's: each kind's items are
/// padded to a multiple of it. (Not HWY_MAX_BYTES: here, outside the targets, it is the baseline target's.)
constexpr std::size_t kMaxLanes = 16;
}  // namespace

void window_distance_filter(const PlaneBatch& plane, std::size_t vf_rows, std::size_t rows, const std::uint16_t* open,
                      int levels, std::uint8_t* keep, WindowDistanceItems& items) {
  // In rounds: each undecided row offers its earliest untested open window. A row is kept at its first window
  // that is not proven (most rows that reach stage 4 are contacts: they stop after a window or two), dropped once
  // every window is proven.
  const int windows = 1 << levels;
  const double* cols[PlaneBatch::kColumns];
  for (int c = 0; c < PlaneBatch::kColumns; ++c) cols[c] = plane.column(c);
  for (const bool vf : {true, false}) {
    const std::size_t begin = vf ? 0 : vf_rows, end = vf ? vf_rows : rows;
    std::size_t pending = 0;
    items.row.resize(end - begin + 2 * kMaxLanes);
    items.left.resize(end - begin + 2 * kMaxLanes);
    for (std::size_t i = begin; i < end; ++i)
      if (keep[i] && open[i] != 0) items.row[pending] = std::int64_t(i), items.left[pending++] = open[i];
      else keep[i] = 0;
    items.time.resize(pending + 2 * kMaxLanes);
    items.proven.resize(pending + 2 * kMaxLanes);
    while (pending > 0) {
      for (std::size_t j = 0; j < pending; ++j) {
        const unsigned bits = items.left[j];
        items.time[j] = (std::countr_zero(bits) + 0.5) / windows;
        items.left[j] = std::uint16_t(bits & (bits - 1));
      }
      for (std::size_t j = pending; j < (pending + kMaxLanes - 1) / kMaxLanes * kMaxLanes; ++j)  // padding: a real item
        items.row[j] = items.row[0], items.time[j] = items.time[0];
      HWY_DYNAMIC_DISPATCH(WindowDistanceItems)(cols, plane.result_column(PlaneBatch::Reach), items.row.data(),
                                           items.time.data(), pending, 0.5 / windows, vf, items.proven.data());
      std::size_t still = 0;
      for (std::size_t j = 0; j < pending; ++j) {
        const std::int64_t i = items.row[j];
        if (!items.proven[j]) {
          keep[i] = 1;
        } else if (items.left[j] == 0) {
          keep[i] = 0;
        } else {
          items.row[still] = i, items.left[still++] = items.left[j];
        }
      }
      pending = still;
    }
  }
}

namespace {
struct P3 {
  double x, y, z;
};
P3 operator-(const P3& p, const P3& q) { return {p.x - q.x, p.y - q.y, p.z - q.z}; }
P3 operator+(const P3& p, const P3& q) { return {p.x + q.x, p.y + q.y, p.z + q.z}; }
P3 along(const P3& p, double s, const P3& q) { return {p.x + s * q.x, p.y + s * q.y, p.z + s * q.z}; }
double dot(const P3& p, const P3& q) { return (p.x * q.x + p.y * q.y) + p.z * q.z; }
P3 cross(const P3& y, const P3& z) { return {y.y * z.z - y.z * z.y, y.z * z.x - y.x * z.z, y.x * z.y - y.y * z.x}; }
double norm(const P3& v) { return std::sqrt(dot(v, v)); }
double larger(double a, double b) { return b > a ? b : a; }
double smaller(double a, double b) { return b < a ? b : a; }
P3 closest_on_segment(const P3& p, const P3& s, const P3& dir) {
  const double dd = dot(dir, dir);
  double q = dd > 0 ? dot(p - s, dir) / dd : 0.0;
  q = q > 0 ? q : 0.0;
  q = q < 1 ? q : 1.0;
  return along(s, q, dir);
}
}  // namespace

bool window_distance_filter_keeps(const PlaneBatch& plane, std::size_t i, bool vf, std::uint16_t open, int levels) {
  using namespace proximity_detail;
  auto point = [&](int c) { return P3{plane.column(c)[i], plane.column(c + 1)[i], plane.column(c + 2)[i]}; };
  const P3 a0 = point(PlaneBatch::A0x), a1 = point(PlaneBatch::A1x), b0 = point(PlaneBatch::B0x),
           b1 = point(PlaneBatch::B1x), c0 = point(PlaneBatch::C0x), c1 = point(PlaneBatch::C1x);
  double M = 0;
  for (const P3* p : {&a0, &a1, &b0, &b1, &c0, &c1})
    M = larger(larger(larger(M, std::abs(p->x)), std::abs(p->y)), std::abs(p->z));
  const P3 ma = a1 - a0, mb = b1 - b0, mc = c1 - c0;
  double speed = larger(norm(ma), norm(ma - mb));
  speed = vf ? larger(speed, norm(ma - mc)) : larger(larger(speed, norm(ma + mc)), norm((ma + mc) - mb));
  const int windows = 1 << levels;
  const double half_width = 0.5 / windows;
  const double need = (plane.result(PlaneBatch::Reach, i) * kFactor + speed * half_width * kFactor) + kSlack * M;
  const P3 origin{0, 0, 0};
  for (unsigned bits = open; bits != 0; bits &= bits - 1) {
    const double t = (std::countr_zero(bits) + 0.5) / windows;
    const P3 a = along(a0, t, ma), b = along(b0, t, mb), c = along(c0, t, mc);
    const double need2 = need * need;
    bool proven = false;
    auto offer = [&](double numerator, double length2) {
      proven |= length2 > 0 && numerator > 0 && numerator * numerator > need2 * length2;
    };
    const P3 normal = cross(b, c);
    const double n_len = dot(normal, normal);
    if (vf) {
      const double na = dot(normal, a), nb = dot(normal, b), nc = dot(normal, c);
      offer(na - larger(larger(0.0, nb), nc), n_len);
      offer(smaller(smaller(0.0, nb), nc) - na, n_len);
      for (const P3& v : {a - closest_on_segment(a, origin, b), a - closest_on_segment(a, b, c - b),
                          a - closest_on_segment(a, origin, c)})
        offer(dot(v, a) - larger(larger(0.0, dot(v, b)), dot(v, c)), dot(v, v));
    } else {
      const P3 e = a + c;
      const double na = dot(normal, a), ne = dot(normal, e), nb = dot(normal, b);
      offer(smaller(na, ne) - larger(0.0, nb), n_len);
      offer(smaller(0.0, nb) - larger(na, ne), n_len);
      for (const P3& v : {closest_on_segment(origin, a, c), closest_on_segment(b, a, c) - b,
                          a - closest_on_segment(a, origin, b), e - closest_on_segment(e, origin, b)})
        offer(smaller(dot(v, a), dot(v, e)) - larger(0.0, dot(v, b)), dot(v, v));
    }
    if (!proven) return true;
  }
  return false;
}

}  // namespace ccdlab
#endif  // HWY_ONCE
