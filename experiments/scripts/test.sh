#!/usr/bin/env bash
# Runs every test: install dependencies, build (release preset), GoogleTest + CLI tests via ctest, the installed
# package used by a consumer project (tests/install/consumer.sh), the Python package installed with pip and the
# pytest suite of analysis/ against it; then the suite
# under ASan + UBSan and the parallel tests under TSan (experiments/scripts/sanitize.sh), and 60 s of libFuzzer on each reader (experiments/scripts/fuzz.sh).
# CCDLAB_QUICK=1 stops after pytest (for a quick local check; CI runs everything).
set -euo pipefail
cd "$(dirname "$0")/../.."
export CCDLAB_WERROR=1  # warnings are errors in every build below (experiments/scripts/build.sh)
experiments/scripts/install-deps.sh
experiments/scripts/build.sh release
ctest --preset release
tests/install/consumer.sh build
# The Python package as solver authors install it (pyproject.toml, offline): into a fresh virtual environment that
# sees Debian's packages, from the build above; the pytest suite then runs against the installed package.
rm -rf build/venv
/usr/bin/python3 -m venv --system-site-packages build/venv
build/venv/bin/pip install --no-build-isolation --no-index --quiet .
CCDLAB_INSTALLED=1 build/venv/bin/python -m pytest -q analysis/tests
[ "${CCDLAB_QUICK:-0}" = 1 ] && exit 0
experiments/scripts/sanitize.sh asan tsan
for target in obj ply query_csv config; do
  experiments/scripts/fuzz.sh "$target" "${CCDLAB_FUZZ_SECONDS:-60}"
done
