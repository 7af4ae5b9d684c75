#pragma once
// Running a test body once per Highway SIMD target.
#include <gtest/gtest.h>

#include <hwy/targets.h>

#include <cstdint>
#include <vector>

namespace ccdlab::test {

/// Runs f(target name) once per SIMD target compiled in and supported here (the scalar EMU128 target
/// included), with that target forced; then restores run-time dispatch.
template <class F>
void for_each_simd_target(F&& f) {
  const std::vector<std::int64_t> targets = hwy::SupportedAndGeneratedTargets();
  ASSERT_FALSE(targets.empty());
  for (std::int64_t t : targets) {
    hwy::SetSupportedTargetsForTest(t);
    f(hwy::TargetName(t));
  }
  hwy::SetSupportedTargetsForTest(0);
}

}  // namespace ccdlab::test
