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
/// Points id[0..3] of one frame of `x01` (FramePoints: coordinate j of point p in frame f at 8p + 4f + j): one
/// aligned 256-bit load per point, then a 4×4 transpose.
HWY_INLINE Points4 LoadFramePoints4(const double* x01, int frame, const std::int32_t (&id)[4]) {
  const hn::Full256<double> d4;
  hn::Vec<decltype(d4)> r[4];
  for (int k = 0; k < 4; ++k) r[k] = hn::Load(d4, x01 + 8 * std::ptrdiff_t(id[k]) + 4 * frame);
  const auto xz01 = hn::InterleaveLower(d4, r[0], r[1]), yw01 = hn::InterleaveUpper(d4, r[0], r[1]);
  const auto xz23 = hn::InterleaveLower(d4, r[2], r[3]), yw23 = hn::InterleaveUpper(d4, r[2], r[3]);
  return Points4{hn::ConcatLowerLower(d4, xz23, xz01), hn::ConcatLowerLower(d4, yw23, yw01),
                 hn::ConcatUpperUpper(d4, xz23, xz01)};
}
#endif

}  // namespace HWY_NAMESPACE
}  // namespace ccdlab
HWY_AFTER_NAMESPACE();

#endif  // CCDLAB_NARROW_POINT_LOADS_INL_H_
