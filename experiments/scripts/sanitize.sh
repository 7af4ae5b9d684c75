#!/usr/bin/env bash
# The test suite under sanitizers (clang-14):
#   asan: every test (GoogleTest + CLI) under AddressSanitizer + UBSan (undefined behaviour is fatal);
#   tsan: the parallel parts — every scheduler × thread count, the executor, restructuring, normal cones, the
#         combinations and differential tests, the proximity query — under ThreadSanitizer, with libomp's Archer tool so that
#         OpenMP's own synchronisation is understood (no false reports from the runtime).
# Usage: experiments/scripts/sanitize.sh [asan] [tsan]   (default: both)
set -euo pipefail
cd "$(dirname "$0")/../.."
which=("$@")
[ ${#which[@]} -eq 0 ] && which=(asan tsan)
for s in "${which[@]}"; do
  case "$s" in
    asan)
      experiments/scripts/build.sh asan
      ctest --preset asan  # the preset sets ASAN_OPTIONS, UBSAN_OPTIONS and the LeakSanitizer suppressions
      ;;
    tsan)
      cmake --preset tsan -DCMAKE_COMPILE_WARNING_AS_ERROR="$([ "${CCDLAB_WERROR:-0}" = 1 ] && echo ON || echo OFF)" >/dev/null
      cmake --build --preset tsan -j "$(nproc)" --target ccdlab_tests
      # Archer needs TSan's runtime flag for OpenMP; the preset sets OMP_TOOL_LIBRARIES and TSAN_OPTIONS.
      ctest --preset tsan
      ;;
    *) echo "sanitize.sh: unknown sanitizer '$s' (asan, tsan)" >&2; exit 2 ;;
  esac
done
