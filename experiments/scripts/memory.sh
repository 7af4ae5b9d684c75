#!/usr/bin/env bash
# Peak resident memory of one real step with and without memory_limit (docs/reliability.md#memory):
# experiments/scripts/memory.sh [T0.ply T1.ply] — default: the largest shared step, n-body balls16 18→19.
# For each scheduler: no limit, then limits that force the step to stream its candidates in BVTT slices;
# prints one Markdown row per run (peak RSS of the step, slices, ms, contact-set hash: the hashes must agree).
set -euo pipefail
cd "$(dirname "$0")/../.."
data=../shared/data/meshes/n-body-simulation
t0="${1:-$data/balls16_18.ply}"
t1="${2:-$data/balls16_19.ply}"
[ -f "$t0" ] || { echo "memory.sh: $t0 not found (../shared/data absent?)" >&2; exit 2; }
[ -x build/bin/ccdlab ] || experiments/scripts/build.sh release >&2
row='import json, sys
j = json.load(sys.stdin); m, c, cfg = j["memory"], j["contacts"], j["config"]
print("| {} | {} | {:.0f} | {} | {:.0f} | {} + {} | {} |".format(cfg["scheduler"]["name"], cfg["memory_limit"], m["peak_rss_mb"],
      m["streamed_slices"], j["ms"]["total"], c["vf"], c["ee"], j["hash"]))'
echo "| scheduler | memory_limit | peak RSS of the step (MiB) | streamed slices | ms | contacts (vf + ee) | hash |"
echo "|---|---|---|---|---|---|---|"
for scheduler in sequential front; do
  for limit in none 160MiB 140MiB 125MiB; do
    build/bin/ccdlab step "$t0" "$t1" --scheduler "$scheduler" --memory-limit "$limit" --json |
      /usr/bin/python3 -c "$row"
  done
done
