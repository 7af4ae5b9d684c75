#!/usr/bin/env bash
# Baseline of the sequential pipeline, per K, on the built-in default scene and the funnel step (if
# ../shared/data is present). Configurations alternate within each round (k = 6, 14, 18, 26, 6, …) so drift
# of the machine hits them alike; the table takes the median over rounds. Writes results/baseline/*.json and
# docs-ready markdown to results/baseline/table.md.
#   usage: experiments/scripts/baseline.sh [ROUNDS]    (after experiments/scripts/build.sh)
set -euo pipefail
cd "$(dirname "$0")/../.."
rounds="${1:-5}"
out=results/baseline
mkdir -p "$out"
rm -f "$out"/*.json
scenes=(default)
[ -f ../shared/data/meshes/cloth-funnel/227.ply ] && scenes+=(funnel)
for r in $(seq 1 "$rounds"); do
  for scene in "${scenes[@]}"; do
    for k in 6 14 18 26; do
      build/bin/ccdlab run "experiments/configs/$scene.yaml" --json --no-progress \
        --set bv.k=$k --set "output.dir=$out/runs/${scene}_k$k" > "$out/${scene}_k${k}_r$r.json"
      echo "round $r $scene k=$k: $(grep -m1 ms_per_step "$out/${scene}_k${k}_r$r.json")" >&2
    done
  done
done
/usr/bin/python3 analysis/baseline_table.py "$out" | tee "$out/table.md"
