// Per-target SIMD helpers shared by the narrow phase's staging kernels (plane_filter.cpp, triangle_filter.cpp):
// included once per Highway target inside HWY_NAMESPACE, hence the toggled guard (Highway's -inl.h convention).
#if defined(CCDLAB_NARROW_POINT_LOADS_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef CCDLAB_NARROW_POINT_LOADS_INL_H_
#undef CCDLAB_NARROW_POINT_LOADS_INL_H_
#else
#define CCDLAB_NARROW_POINT_LOADS_INL_H_
#endif

#include <hwy/highway.h>

#include <cstddef>
#include <cstdint>

HWY_BEFORE_NAMESPACE();
namespace ccdlab {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

#undef CCDLAB_POINT_LOADS_4  // set per target
#if HWY_TARGET == HWY_AVX2 || HWY_TARGET == HWY_AVX3 || HWY_TARGET == HWY_AVX3_DL
/// Where 256-bit vectors exist, the staging kernels load four points at a time.
#define CCDLAB_POINT_LOADS_4 1
using Points4Tag = hn::Full256<double>;
/// Four points' coordinates, one vector per axis.
struct Points4 {
  hn::Vec<Points4Tag> x, y, z;
};
/// Points id[0..3] of x (coordinate j of point p at x[3p + j]): (x, y) and (y, z) of each point in two 128-bit
/// loads inside its three doubles, then interleaved and joined.
HWY_INLINE Points4 LoadPoints4(const double* x, const std::int32_t (&id)[4]) {
  const hn::Full256<double> d4;
  const hn::Full128<double> d2;
  hn::Vec<decltype(d2)> xy[4], yz[4];
  for (int k = 0; k < 4; ++k) {
    const double* p = x + 3 * std::ptrdiff_t(id[k]);
    xy[k] = hn::LoadU(d2, p), yz[k] = hn::LoadU(d2, p + 1);
  }
  return Points4{hn::Combine(d4, hn::InterleaveLower(d2, xy[2], xy[3]), hn::InterleaveLower(d2, xy[0], xy[1])),
                 hn::Combine(d4, hn::InterleaveUpper(d2, xy[2], xy[3]), hn::InterleaveUpper(d2, xy[0], xy[1])),
                 hn::Combine(d4, hn::InterleaveUpper(d2, yz[2], yz[3]), hn::InterleaveUpper(d2, yz[0], yz[1]))};
}
#endif

}  // namespace HWY_NAMESPACE
}  // namespace ccdlab
HWY_AFTER_NAMESPACE();

#endif  // CCDLAB_NARROW_POINT_LOADS_INL_H_
