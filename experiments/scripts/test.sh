#!/usr/bin/env bash
# Runs every test: install dependencies, build (release preset), GoogleTest + CLI tests via ctest, the installed
# package used by a consumer project (tests/install/consumer.sh), the Python package installed with pip and the
# pytest suite of analysis/ against it; then the suite under ASan + UBSan and the parallel tests under TSan
# (experiments/scripts/sanitize.sh), and 60 s of libFuzzer on each reader (experiments/scripts/fuzz.sh), two
# readers at a time (each fuzzer is one process on one core). Prints each part's time at the end.
# CCDLAB_QUICK=1 stops after pytest (for a quick local check; CI runs everything).
set -euo pipefail
cd "$(dirname "$0")/../.."
export CCDLAB_WERROR=1  # warnings are errors in every build below (experiments/scripts/build.sh)

parts=()
start_all=$SECONDS
report() {
  local status=$?
  echo "test.sh: time per part (s):" >&2
  for p in "${parts[@]}"; do echo "  $p" >&2; done
  echo "  total $((SECONDS - start_all))$([ "$status" -ne 0 ] && echo " (failed, exit $status)")" >&2
}
trap report EXIT
part() {  # part NAME COMMAND…: runs the command, records its time
  local name="$1" t0=$SECONDS
  shift
  "$@"
  parts+=("$(printf '%-22s %5d' "$name" $((SECONDS - t0)))")
}

python_package() {
  # The Python package as solver authors install it (pyproject.toml, offline): into a fresh virtual environment
  # that sees Debian's packages, from the build above; the pytest suite then runs against the installed package.
  rm -rf build/venv
  /usr/bin/python3 -m venv --system-site-packages build/venv
  build/venv/bin/pip install --no-build-isolation --no-index --quiet .
  CCDLAB_INSTALLED=1 build/venv/bin/python -m pytest -q analysis/tests
}

fuzz_all() {
  local seconds="${CCDLAB_FUZZ_SECONDS:-60}"
  experiments/scripts/build.sh asan >/dev/null  # the fuzz targets (built already by sanitize.sh)
  local failed=0 pair a b
  for pair in "obj ply" "query_csv config"; do
    set -- $pair
    experiments/scripts/fuzz.sh "$1" "$seconds" & a=$!
    experiments/scripts/fuzz.sh "$2" "$seconds" & b=$!
    wait "$a" || failed=1
    wait "$b" || failed=1
  done
  return "$failed"
}

part "install-deps" experiments/scripts/install-deps.sh
part "build release" experiments/scripts/build.sh release
part "ctest release" ctest --preset release
part "consumer" tests/install/consumer.sh build
part "python package" python_package
[ "${CCDLAB_QUICK:-0}" = 1 ] && exit 0
part "asan: build + ctest" experiments/scripts/sanitize.sh asan
part "tsan: build + ctest" experiments/scripts/sanitize.sh tsan
part "fuzz (4 readers)" fuzz_all
