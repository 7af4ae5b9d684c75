#pragma once
// k-DOP bounding volumes (discrete oriented polytopes) for K = 6, 14, 18, 26, with the axis tables of the
// seed paper (../shared/docs/paper-summary.md). A K-DOP stores, for each of its K/2 fixed axes d_i, the interval
// [min_i, max_i] of d_i · x over the bounded points. The axes are NOT normalised: d_i · x is exact up to one
// or two roundings for the integer axes below, and thickness is inflated by |d_i|.
//
//   K = 6  : (1,0,0) (0,1,0) (0,0,1)                                         — the AABB
//   K = 14 : the 3 above + (1,1,1) (1,-1,1) (1,1,-1) (1,-1,-1)                — + 4 corner diagonals
//   K = 18 : the 3 above + (1,1,0) (1,0,1) (0,1,1) (1,-1,0) (1,0,-1) (0,1,-1) — + 6 edge diagonals
//   K = 26 : the 3 + the 4 corner diagonals + the 6 edge diagonals (13 axes)
//
// Storage is float (half the bytes of double: more nodes per cache line in traversal). Every bound is
// rounded OUTWARD from a double computation that is itself padded by its worst-case rounding error, so a
// float k-DOP always contains the exact k-DOP of its points: culling stays conservative.
#include <array>
#include <bit>
#include <cmath>
#include <concepts>
#include <cstdint>
#include <limits>
#include <optional>
#include <utility>
#include <variant>

#include "framework/geometry/vec.hpp"

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace ccdlab {

/// Axis table of a K-DOP: K/2 integer direction vectors (entries in {-1, 0, 1}).
template <int K>
struct KDopAxes;

template <>
struct KDopAxes<6> {
  static constexpr std::array<std::array<int, 3>, 3> axes{{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}};
};
template <>
struct KDopAxes<14> {
  static constexpr std::array<std::array<int, 3>, 7> axes{
      {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 1}, {1, -1, 1}, {1, 1, -1}, {1, -1, -1}}};
};
template <>
struct KDopAxes<18> {
  static constexpr std::array<std::array<int, 3>, 9> axes{{{1, 0, 0},
                                                           {0, 1, 0},
                                                           {0, 0, 1},
                                                           {1, 1, 0},
                                                           {1, 0, 1},
                                                           {0, 1, 1},
                                                           {1, -1, 0},
                                                           {1, 0, -1},
                                                           {0, 1, -1}}};
};
template <>
struct KDopAxes<26> {
  static constexpr std::array<std::array<int, 3>, 13> axes{{{1, 0, 0},
                                                            {0, 1, 0},
                                                            {0, 0, 1},
                                                            {1, 1, 1},
                                                            {1, -1, 1},
                                                            {1, 1, -1},
                                                            {1, -1, -1},
                                                            {1, 1, 0},
                                                            {1, 0, 1},
                                                            {0, 1, 1},
                                                            {1, -1, 0},
                                                            {1, 0, -1},
                                                            {0, 1, -1}}};
};

namespace detail {
/// The next float towards −∞ / +∞ (f finite), by stepping the bit pattern (no libm call in the hot loop).
inline float float_below(float f) {
  if (f == 0) return -std::numeric_limits<float>::denorm_min();
  auto bits = std::bit_cast<std::uint32_t>(f);
  return std::bit_cast<float>(f > 0 ? bits - 1 : bits + 1);
}
inline float float_above(float f) { return -float_below(-f); }
/// Largest float <= x (x finite).
inline float round_down(double x) {
  auto f = static_cast<float>(x);
  return static_cast<double>(f) > x ? float_below(f) : f;
}
/// Smallest float >= x (x finite).
inline float round_up(double x) {
  auto f = static_cast<float>(x);
  return static_cast<double>(f) < x ? float_above(f) : f;
}
}  // namespace detail

template <int K>
class KDop;

/// The K that have axis tables, as one type list. Everything chosen by a run-time K derives from it: is_kdop_k,
/// the text kKdopKs every config, CLI flag and binding quotes, and the variants over the k-DOP types (KdopVariant).
template <int... Ks>
struct KdopKList {
  static constexpr std::array<int, sizeof...(Ks)> values{Ks...};
  /// std::variant<Array<KDop<K>>...> over the list's K, in its order.
  template <template <class> class Array>
  using variant = std::variant<Array<KDop<Ks>>...>;
};
using KdopKs = KdopKList<6, 14, 18, 26>;

inline constexpr bool is_kdop_k(int k) {
  for (int v : KdopKs::values)
    if (v == k) return true;
  return false;
}

namespace detail {
/// KdopKs::values as text, "6, 14, 18, 26", at compile time.
constexpr std::size_t k_list_text_size() {
  std::size_t n = 0;
  for (int v : KdopKs::values) {
    if (n) n += 2;
    for (int x = v; x; x /= 10) ++n;
  }
  return n;
}
constexpr std::array<char, k_list_text_size() + 1> k_list_text() {
  std::array<char, k_list_text_size() + 1> out{};
  std::size_t at = 0;
  for (int v : KdopKs::values) {
    if (at) out[at++] = ',', out[at++] = ' ';
    std::size_t digits = 0;
    for (int x = v; x; x /= 10) ++digits;
    for (std::size_t i = digits; i-- > 0; v /= 10) out[at + i] = char('0' + v % 10);
    at += digits;
  }
  return out;
}
inline constexpr auto kKdopKsText = k_list_text();
}  // namespace detail
inline constexpr const char* kKdopKs = detail::kKdopKsText.data();

/// A variant over Array<KDop<K>> for every K of the list, holding an empty Array of KDop<k> (the one dispatch
/// from a run-time K to the k-DOP types); nullopt unless is_kdop_k(k).
template <template <class> class Array>
using KdopVariant = KdopKs::variant<Array>;
template <template <class> class Array, std::size_t I = 0>
std::optional<KdopVariant<Array>> empty_kdop_variant(int k) {
  if constexpr (I == KdopKs::values.size()) {
    return std::nullopt;
  } else {
    if (k == KdopKs::values[I]) return KdopVariant<Array>{Array<KDop<KdopKs::values[I]>>{}};
    return empty_kdop_variant<Array, I + 1>(k);
  }
}

template <int K>
class KDop {
  static_assert(is_kdop_k(K), "k-DOPs exist for the K of KdopKs");

 public:
  static constexpr int k = K;
  static constexpr int num_axes = K / 2;
  static constexpr const auto& axes = KDopAxes<K>::axes;

  /// An empty k-DOP (overlaps nothing; merging with it is the identity).
  KDop() {
    min_.fill(std::numeric_limits<float>::infinity());
    max_.fill(-std::numeric_limits<float>::infinity());
  }

  /// The k-DOP with these bounds per axis (already rounded outward by whoever computed them).
  static KDop from_bounds(const std::array<float, num_axes>& mins, const std::array<float, num_axes>& maxs) {
    KDop d;
    d.min_ = mins;
    d.max_ = maxs;
    return d;
  }

  /// Grows the k-DOP to contain point p (conservatively, see header).
  void grow(const Vec3& p) {
    for (int i = 0; i < num_axes; ++i) {
      const auto& d = axes[i];
      double s = d[0] * p.x() + d[1] * p.y() + d[2] * p.z();
      // Two additions at most: error <= 2u (|x| + |y| + |z|), u = 2^-53; pad by 4u to be safe.
      double err = 4.440892098500626e-16 * (std::abs(p.x()) + std::abs(p.y()) + std::abs(p.z()));
      min_[i] = std::min(min_[i], detail::round_down(s - err));
      max_[i] = std::max(max_[i], detail::round_up(s + err));
    }
  }
  /// Grows the k-DOP to contain N points, rounding outward once per axis (faster than N grow calls).
  template <std::size_t N>
  void grow(const std::array<const Vec3*, N>& pts) {
    double mag = 0;
    std::array<double, num_axes> lo, hi;
    lo.fill(std::numeric_limits<double>::infinity());
    hi.fill(-std::numeric_limits<double>::infinity());
    for (const Vec3* p : pts) {
      mag = std::max(mag, std::abs(p->x()) + std::abs(p->y()) + std::abs(p->z()));
      std::array<double, num_axes> s;
      project(*p, s, std::make_index_sequence<num_axes>{});
      for (int i = 0; i < num_axes; ++i) {
        lo[i] = std::min(lo[i], s[i]);
        hi[i] = std::max(hi[i], s[i]);
      }
    }
    const double err = 4.440892098500626e-16 * mag;  // see grow(p)
    for (int i = 0; i < num_axes; ++i) {
      min_[i] = std::min(min_[i], detail::round_down(lo[i] - err));
      max_[i] = std::max(max_[i], detail::round_up(hi[i] + err));
    }
  }
  void merge(const KDop& o) {
    for (int i = 0; i < num_axes; ++i) {
      min_[i] = std::min(min_[i], o.min_[i]);
      max_[i] = std::max(max_[i], o.max_[i]);
    }
  }
  /// Inflates every slab by thickness r (a ball of radius r projects to r·|d_i| on axis d_i).
  void inflate(double r) {
    if (r <= 0) return;
    for (int i = 0; i < num_axes; ++i) {
      const auto& d = axes[i];
      double len = std::sqrt(double(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]));
      min_[i] = detail::round_down(double(min_[i]) - r * len * (1 + 1e-15));
      max_[i] = detail::round_up(double(max_[i]) + r * len * (1 + 1e-15));
    }
  }
  /// Closed-interval overlap on every axis (touching counts as overlap).
  [[nodiscard]] bool overlaps(const KDop& o) const {
    bool sep = false;
    int i = 0;
#if defined(__SSE2__)
    // Four axes per compare (SSE2 is in every x86-64 CPU: no dispatch, stays inline in the traversal); the
    // last num_axes % 4 plain. Same answers, NaN included (both compares are false on NaN).
    __m128 apart = _mm_setzero_ps();
    for (; i + 4 <= num_axes; i += 4) {
      apart = _mm_or_ps(apart, _mm_cmpgt_ps(_mm_loadu_ps(&min_[i]), _mm_loadu_ps(&o.max_[i])));
      apart = _mm_or_ps(apart, _mm_cmpgt_ps(_mm_loadu_ps(&o.min_[i]), _mm_loadu_ps(&max_[i])));
    }
    sep = _mm_movemask_ps(apart) != 0;
#endif
    for (; i < num_axes; ++i) sep |= int(min_[i] > o.max_[i]) | int(o.min_[i] > max_[i]);
    return !sep;
  }
  [[nodiscard]] bool contains(const Vec3& p) const {
    KDop q;
    q.grow(p);
    for (int i = 0; i < num_axes; ++i)
      if (q.min_[i] < min_[i] || q.max_[i] > max_[i]) {
        // q is padded outward; accept if the exact projection is inside.
        const auto& d = axes[i];
        double s = d[0] * p.x() + d[1] * p.y() + d[2] * p.z();
        if (s < min_[i] || s > max_[i]) return false;
      }
    return true;
  }
  [[nodiscard]] bool empty() const { return min_[0] > max_[0]; }
  /// Sum of the extents along x, y, z: a cheap size measure used to pick which node to descend.
  [[nodiscard]] float size_measure() const { return (max_[0] - min_[0]) + (max_[1] - min_[1]) + (max_[2] - min_[2]); }
  [[nodiscard]] float min(int i) const { return min_[i]; }
  [[nodiscard]] float max(int i) const { return max_[i]; }
  /// The bounds as arrays of num_axes floats (SIMD copies).
  [[nodiscard]] const float* mins() const { return min_.data(); }
  [[nodiscard]] const float* maxs() const { return max_.data(); }

 private:
  /// d_i · p for every axis, unrolled with the axis entries as constants (0 and ±1 fold away).
  template <std::size_t... I>
  static void project(const Vec3& p, std::array<double, num_axes>& out, std::index_sequence<I...>) {
    ((out[I] = double(axes[I][0]) * p.x() + double(axes[I][1]) * p.y() + double(axes[I][2]) * p.z()), ...);
  }

  std::array<float, num_axes> min_;
  std::array<float, num_axes> max_;
};

/// What a bounding volume must offer the hierarchy and the traversal.
template <class BV>
concept BoundingVolume = std::default_initializable<BV> && requires(BV bv, const BV cbv, Vec3 p) {
  bv.grow(p);
  bv.merge(cbv);
  bv.inflate(1.0);
  { cbv.overlaps(cbv) } -> std::convertible_to<bool>;
  { cbv.size_measure() } -> std::convertible_to<float>;
};

static_assert(BoundingVolume<KDop<6>> && BoundingVolume<KDop<26>>);
static_assert(sizeof(KDop<18>) == 18 * sizeof(float));

}  // namespace ccdlab
