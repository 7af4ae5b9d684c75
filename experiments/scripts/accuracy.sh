#!/usr/bin/env bash
# The accuracy ladder (issue 4): what accuracy costs in time.
#  1. `ccdlab validate` on the shared query sets (if ../shared/data is present) and the built-in hard cases:
#     float, filtered, conservative with a δ sweep (fallback "hit") and with the exact fallback, exact.
#  2. The pipeline's ms per step on the default cloth scene with each tester, in alternating rounds.
#  3. analysis/plot_accuracy.py: results/accuracy/accuracy_time.png and the markdown tables (table.md).
#   usage: experiments/scripts/accuracy.sh [ROUNDS]    (after experiments/scripts/build.sh)
set -euo pipefail
cd "$(dirname "$0")/../.."
rounds="${1:-3}"
out=results/accuracy
mkdir -p "$out"
sets=(hard-cases)
if [ -d ../shared/data/ccd-queries ]; then
  sets=(../shared/data/ccd-queries hard-cases)
else
  echo "accuracy.sh: ../shared/data/ccd-queries not found: built-in hard cases only" >&2
fi
testers=(float filtered)
for delta in 1e-2 1e-4 1e-6 1e-8 0; do testers+=("conservative:delta=$delta"); done
testers+=("conservative:fallback=exact" exact)
args=()
for t in "${testers[@]}"; do args+=(--tester "$t"); done
build/bin/ccdlab validate "${sets[@]}" "${args[@]}" --repeat 5 --no-progress --out "$out" > "$out/validate.txt"
echo "validate: $out/validate.txt, $out/validate.csv, $out/queries.csv" >&2

# Pipeline time per tester: the configurations alternate within each round (forward, then backward).
pipeline_testers=(float filtered conservative exact)
echo "round,tester,ms_per_step,contacts_vf,contacts_ee,hash" > "$out/pipeline.csv"
for r in $(seq 1 "$rounds"); do
  order=("${pipeline_testers[@]}")
  if [ $((r % 2)) -eq 0 ]; then order=(exact conservative filtered float); fi
  for t in "${order[@]}"; do
    json=$(build/bin/ccdlab run experiments/configs/default.yaml --json --no-progress --set tester=$t \
             --set "output.dir=$out/runs/$t")
    /usr/bin/python3 -c 'import json, sys; d = json.loads(sys.argv[1]); c = d["contacts"]
print(",".join(map(str, [sys.argv[2], sys.argv[3], d["ms_per_step"], c["vf"], c["ee"], d["hash"]])))' \
      "$json" "$r" "$t" >> "$out/pipeline.csv"
    echo "round $r $t: $(tail -1 "$out/pipeline.csv")" >&2
  done
done
/usr/bin/python3 analysis/plot_accuracy.py "$out" | tee "$out/table.md"
