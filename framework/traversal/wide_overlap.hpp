#pragma once
// One k-DOP against the four lanes of a wide node, one 4-float SIMD compare per axis and side. Highway's static
// target (the baseline of the build: SSE2 on any x86-64, NEON on arm64) is enough for 4 floats, so this stays
// inline in the traversal loop without run-time dispatch. Do not include from a foreach_target.h file.
#include <hwy/highway.h>

#include "framework/hierarchy/wide_bvh.hpp"

namespace ccdlab {

/// Bit j set ⇔ lane j's k-DOP overlaps q (closed intervals on every axis, as KDop::overlaps). Empty lanes never do.
template <class BV>
inline unsigned overlapping_lanes(const WideBounds<BV>& w, const BV& q) {
  namespace hn = hwy::HWY_NAMESPACE;
  const hn::FixedTag<float, WideLayout::kWidth> d;
  auto apart = hn::Or(hn::Gt(hn::Load(d, w.lo[0]), hn::Set(d, q.max(0))),
                      hn::Gt(hn::Set(d, q.min(0)), hn::Load(d, w.hi[0])));
  for (int i = 1; i < BV::num_axes; ++i)
    apart = hn::Or(apart, hn::Or(hn::Gt(hn::Load(d, w.lo[i]), hn::Set(d, q.max(i))),
                                 hn::Gt(hn::Set(d, q.min(i)), hn::Load(d, w.hi[i]))));
  std::uint8_t bits[8] = {};
  hn::StoreMaskBits(d, apart, bits);
  return ~unsigned(bits[0]) & ((1u << WideLayout::kWidth) - 1);
}

/// The lanes' size measures (KDop::size_measure: the extents along the first three axes, summed in that order).
template <class BV>
inline void lane_sizes(const WideBounds<BV>& w, float* out) {
  namespace hn = hwy::HWY_NAMESPACE;
  const hn::FixedTag<float, WideLayout::kWidth> d;
  const auto extent = [&](int i) { return hn::Sub(hn::Load(d, w.hi[i]), hn::Load(d, w.lo[i])); };
  hn::Store(hn::Add(hn::Add(extent(0), extent(1)), extent(2)), d, out);
}

}  // namespace ccdlab
