#!/usr/bin/env bash
# Fuzzes one reader with libFuzzer (clang, ASan + UBSan): experiments/scripts/fuzz.sh TARGET SECONDS
#   TARGET: obj | ply | query_csv | config (tests/fuzz/fuzz_TARGET.cpp); SECONDS: wall-clock budget.
# Builds the asan preset if needed. The working corpus grows in build-asan/fuzz/TARGET/corpus (seeded from
# tests/fuzz/corpus/TARGET); a crash, a sanitizer report, a leak, a slow input (> 10 s) or an allocation over
# 1 GiB is a finding, written to build-asan/fuzz/TARGET/ — the script then exits non-zero. Every finding
# becomes a regression test (a file in tests/cli/bad_inputs/ and a line in tests/cli/bad_inputs.cmake).
set -euo pipefail
cd "$(dirname "$0")/../.."
target="${1:?usage: fuzz.sh TARGET SECONDS (TARGET: obj, ply, query_csv, config)}"
seconds="${2:?usage: fuzz.sh TARGET SECONDS}"
case "$target" in obj|ply|query_csv|config) ;; *) echo "fuzz.sh: unknown target '$target' (obj, ply, query_csv, config)" >&2; exit 2 ;; esac
[ -x "build-asan/bin/fuzz_$target" ] || experiments/scripts/build.sh asan >&2
work="build-asan/fuzz/$target"
mkdir -p "$work/corpus"
echo "fuzz.sh: fuzz_$target for ${seconds}s (corpus $work/corpus + tests/fuzz/corpus/$target)" >&2
set +e
ASAN_OPTIONS="${ASAN_OPTIONS:-detect_leaks=1}" UBSAN_OPTIONS="${UBSAN_OPTIONS:-print_stacktrace=1}" \
  LSAN_OPTIONS="suppressions=$PWD/tests/sanitizers/lsan.supp" \
  "build-asan/bin/fuzz_$target" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -malloc_limit_mb=1024 \
  -max_len=65536 -print_final_stats=1 -artifact_prefix="$work/" "$work/corpus" "tests/fuzz/corpus/$target" 2>"$work/log"
status=$?
set -e
grep -E "^(stat::number_of_executed_units|stat::peak_rss_mb)|^#[0-9]+ +DONE" "$work/log" >&2 || true
if [ "$status" -ne 0 ]; then
  echo "fuzz.sh: fuzz_$target found a problem (exit $status); the input is in $work/ — last lines of $work/log:" >&2
  tail -n 40 "$work/log" >&2
  exit 1
fi
echo "fuzz.sh: fuzz_$target: no findings in ${seconds}s" >&2
