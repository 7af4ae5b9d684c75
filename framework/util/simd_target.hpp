#pragma once
// The program-wide choice of SIMD target: every Highway kernel (the narrow phase's stages, the swept vertex
// k-DOPs, the wide traversal's overlaps, the float tester's roots) dispatches to the best target this CPU and
// build have, at or below the one chosen here.
#include <string_view>

namespace ccdlab {

/// Lets every SIMD kernel dispatch only to `name` or a lesser target: "avx512", "avx2", "sse4", "ssse3" or
/// "scalar" (the environment's CCDLAB_SIMD, read by the command line at start), to measure what each one buys.
/// Same answers on every target. Throws Error naming the valid values, or when this CPU and build have no
/// target at or below it.
void limit_simd_target(std::string_view name);

/// Name of the SIMD target the kernels dispatch to on this machine now (e.g. "AVX2").
[[nodiscard]] const char* simd_target_name();

}  // namespace ccdlab
