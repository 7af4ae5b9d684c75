#pragma once
// One k-DOP against the four lanes of a wide node: one 4-float compare per axis and side. Four floats are
// exactly one SSE2 register, and SSE2 is part of every x86-64 CPU, so this needs no run-time dispatch and stays
// inline in the traversal loop (Highway's static target on a baseline x86-64 build is its scalar one, one
// lane). Other CPUs take the plain loops, which are also the reference the tests compare with.
#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "framework/hierarchy/wide_bvh.hpp"

namespace ccdlab {

/// Bit j set ⇔ lane j's k-DOP overlaps q (closed intervals on every axis, as KDop::overlaps). Empty lanes never do.
/// q: a BV or a WideLane<BV> (anything with min(i), max(i)).
template <class BV, class Query>
inline unsigned overlapping_lanes_plain(const WideBounds<BV>& w, const Query& q) {
  unsigned mask = 0;
  for (int j = 0; j < WideLayout::kWidth; ++j) {
    bool apart = false;
    for (int i = 0; i < BV::num_axes; ++i) apart |= (w.lo[i][j] > q.max(i)) | (q.min(i) > w.hi[i][j]);
    mask |= unsigned(!apart) << j;
  }
  return mask;
}

/// The lanes' size measures (KDop::size_measure: the extents along the first three axes, summed in that order).
template <class BV>
inline void lane_sizes_plain(const WideBounds<BV>& w, float* out) {
  for (int j = 0; j < WideLayout::kWidth; ++j)
    out[j] = (w.hi[0][j] - w.lo[0][j]) + (w.hi[1][j] - w.lo[1][j]) + (w.hi[2][j] - w.lo[2][j]);
}

#if defined(__SSE2__)
static_assert(WideLayout::kWidth == 4, "one SSE2 register per axis and side");

template <class BV, class Query>
inline unsigned overlapping_lanes(const WideBounds<BV>& w, const Query& q) {
  __m128 apart = _mm_setzero_ps();
  for (int i = 0; i < BV::num_axes; ++i) {
    apart = _mm_or_ps(apart, _mm_cmpgt_ps(_mm_load_ps(w.lo[i]), _mm_set1_ps(q.max(i))));
    apart = _mm_or_ps(apart, _mm_cmpgt_ps(_mm_set1_ps(q.min(i)), _mm_load_ps(w.hi[i])));
  }
  return ~unsigned(_mm_movemask_ps(apart)) & 0xFu;
}

template <class BV>
inline void lane_sizes(const WideBounds<BV>& w, float* out) {
  const auto extent = [&](int i) { return _mm_sub_ps(_mm_load_ps(w.hi[i]), _mm_load_ps(w.lo[i])); };
  _mm_storeu_ps(out, _mm_add_ps(_mm_add_ps(extent(0), extent(1)), extent(2)));
}
#else
template <class BV, class Query>
inline unsigned overlapping_lanes(const WideBounds<BV>& w, const Query& q) {
  return overlapping_lanes_plain(w, q);
}
template <class BV>
inline void lane_sizes(const WideBounds<BV>& w, float* out) {
  lane_sizes_plain(w, out);
}
#endif

}  // namespace ccdlab
