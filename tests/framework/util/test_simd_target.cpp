// The program-wide SIMD target choice (framework/util/simd_target.hpp).
#include <gtest/gtest.h>

#include <hwy/targets.h>

#include <string>

#include "framework/util/simd_target.hpp"
#include "framework/util/error.hpp"

namespace ccdlab {
namespace CCDLAB_UNITY_ID {  // a namespace of this file's own (tests/CMakeLists.txt)

TEST(SimdTargets, CcdlabSimdLimitsTheDispatchToTheNamedTargetOrALesserOne) {
  const std::string best = simd_target_name();
  limit_simd_target("scalar");
  const std::string scalar = simd_target_name();
  EXPECT_TRUE(scalar == "EMU128" || scalar == "SCALAR") << scalar;
  if (hwy::SupportedTargets() & HWY_AVX2) {
    limit_simd_target("avx2");
    EXPECT_STREQ(simd_target_name(), "AVX2");
  }
  limit_simd_target("avx512");  // the best this CPU has, AVX-512 or not
  EXPECT_EQ(simd_target_name(), best);
  EXPECT_THROW(limit_simd_target("avx1024"), Error);
  EXPECT_EQ(simd_target_name(), best);  // a refused name changes nothing
  hwy::SetSupportedTargetsForTest(0);
}

}  // namespace CCDLAB_UNITY_ID
}  // namespace ccdlab
