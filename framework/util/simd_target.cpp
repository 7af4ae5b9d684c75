#include "framework/util/simd_target.hpp"

#include <cstdint>

#include <hwy/highway.h>
#include <hwy/targets.h>

#include "framework/util/error.hpp"

namespace ccdlab {

void limit_simd_target(std::string_view name) {
  // Highway numbers its x86 targets from the best (lowest bit) down: allow `best` and every bit above it.
  std::int64_t best = 0;
  if (name == "avx512") best = HWY_AVX3_DL;
  else if (name == "avx2") best = HWY_AVX2;
  else if (name == "sse4") best = HWY_SSE4;
  else if (name == "ssse3") best = HWY_SSSE3;
  else if (name == "scalar") best = HWY_EMU128;
  else fail("CCDLAB_SIMD: expected avx512, avx2, sse4, ssse3 or scalar, got '{}'", name);
  hwy::SetSupportedTargetsForTest(0);  // the CPU's own set first
  const std::int64_t allowed = hwy::SupportedTargets() & ~(best - 1);
  hwy::SetSupportedTargetsForTest(allowed);
  if (allowed == 0 || hwy::SupportedAndGeneratedTargets().empty()) {
    hwy::SetSupportedTargetsForTest(0);
    fail("CCDLAB_SIMD={}: this CPU and build have no SIMD target at or below it", name);
  }
}

const char* simd_target_name() {
  return hwy::TargetName(hwy::SupportedAndGeneratedTargets().empty() ? HWY_STATIC_TARGET
                                                                     : hwy::SupportedAndGeneratedTargets().front());
}

}  // namespace ccdlab
