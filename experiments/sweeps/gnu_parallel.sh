#!/usr/bin/env bash
# Runs a sweep as N shards side by side on one machine (or, with GNU parallel's --sshlogin, on several), then
# merges the finished runs into OUTPUT_DIR/runs.csv.
#
#   experiments/sweeps/gnu_parallel.sh SWEEP.yaml [SHARDS] [-- extra ccdlab sweep options, e.g. --set threads=1]
#
# Each shard is `ccdlab sweep SWEEP.yaml --shard i/SHARDS`: a deterministic share of the runs, so shards never
# run the same run, and a shard started again skips what is complete. Uses GNU parallel when installed
# (apt-get install parallel), otherwise xargs -P with the same effect. Shards on one machine compete for its
# cores: for timings, give each shard threads ≤ cores / SHARDS, or run them one after another.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
ccdlab="${CCDLAB:-$here/../../build/bin/ccdlab}"
sweep="${1:?usage: gnu_parallel.sh SWEEP.yaml [SHARDS] [-- ccdlab sweep options]}"
shards="${2:-2}"
shift $(( $# >= 2 ? 2 : 1 ))
[ "${1:-}" = "--" ] && shift
extra=("$@")
if command -v parallel >/dev/null 2>&1; then
  parallel --halt now,fail=1 --line-buffer "$ccdlab" sweep "$sweep" --shard {}/"$shards" --no-progress "${extra[@]}" \
    ::: $(seq 0 $((shards - 1)))
else
  seq 0 $((shards - 1)) | xargs -P "$shards" -I{} "$ccdlab" sweep "$sweep" --shard {}/"$shards" --no-progress "${extra[@]}"
fi
"$ccdlab" sweep "$sweep" --merge "${extra[@]}"
