#!/usr/bin/env bash
# Runs every test: install dependencies, build (release preset), GoogleTest + CLI tests via ctest, the installed
# package used by a consumer project (tests/install/consumer.sh), the pytest suite of analysis/; then the suite
# under ASan + UBSan and the parallel tests under TSan (experiments/scripts/sanitize.sh), and 60 s of libFuzzer on each reader (experiments/scripts/fuzz.sh).
# CCDLAB_QUICK=1 stops after pytest (for a quick local check; CI runs everything).
set -euo pipefail
cd "$(dirname "$0")/../.."
export CCDLAB_WERROR=1  # warnings are errors in every build below (experiments/scripts/build.sh)
experiments/scripts/install-deps.sh
experiments/scripts/build.sh release
ctest --preset release
tests/install/consumer.sh build
/usr/bin/python3 -m pytest -q analysis/tests
[ "${CCDLAB_QUICK:-0}" = 1 ] && exit 0
experiments/scripts/sanitize.sh asan tsan
for target in obj ply query_csv config; do
  experiments/scripts/fuzz.sh "$target" "${CCDLAB_FUZZ_SECONDS:-60}"
done
