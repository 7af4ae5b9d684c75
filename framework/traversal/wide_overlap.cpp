// lane_pairs_walk_available (wide_overlap.hpp): Highway compiles this file once per SIMD target and dispatches
// to the chosen one, which follows CCDLAB_SIMD (limit_simd_target) without asking the CPU again.
#include "framework/traversal/wide_overlap.hpp"

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "framework/traversal/wide_overlap.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

HWY_BEFORE_NAMESPACE();
namespace ccdlab {
namespace HWY_NAMESPACE {

/// AVX3 and the better x86 targets (AVX3_DL: lower bits are better) have what the walk needs.
bool HasAvx512Walk() {
#if defined(CCDLAB_HAS_AVX512_WALK) && HWY_ARCH_X86
  return HWY_TARGET <= HWY_AVX3;
#else
  return false;
#endif
}

}  // namespace HWY_NAMESPACE
}  // namespace ccdlab
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace ccdlab {
HWY_EXPORT(HasAvx512Walk);

bool lane_pairs_walk_available() { return HWY_DYNAMIC_DISPATCH(HasAvx512Walk)(); }

}  // namespace ccdlab
#endif  // HWY_ONCE
