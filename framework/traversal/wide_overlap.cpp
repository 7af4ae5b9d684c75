// lane_pair_walk (wide_overlap.hpp): Highway compiles this file once per SIMD target and dispatches
// to the chosen one, which follows CCDLAB_SIMD (limit_simd_target, framework/util/simd_target.hpp) without asking the CPU again.
#include "framework/traversal/wide_overlap.hpp"

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "framework/traversal/wide_overlap.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

HWY_BEFORE_NAMESPACE();
namespace ccdlab {
namespace HWY_NAMESPACE {

/// AVX3 and the better x86 targets (lower bits are better) have what the AVX-512 walk needs; AVX2 the other.
LanePairWalk BestWalk() {
#if defined(CCDLAB_HAS_LANE_PAIR_WALKS) && HWY_ARCH_X86
  return HWY_TARGET <= HWY_AVX3 ? LanePairWalk::avx512 : HWY_TARGET <= HWY_AVX2 ? LanePairWalk::avx2 : LanePairWalk::none;
#else
  return LanePairWalk::none;
#endif
}

}  // namespace HWY_NAMESPACE
}  // namespace ccdlab
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace ccdlab {
HWY_EXPORT(BestWalk);

LanePairWalk lane_pair_walk() { return HWY_DYNAMIC_DISPATCH(BestWalk)(); }

}  // namespace ccdlab
#endif  // HWY_ONCE
