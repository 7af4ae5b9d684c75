#!/usr/bin/env bash
# The accuracy ladder (issue 4): what accuracy costs in time.
#  1. `ccdlab validate` on the shared query sets (if ../shared/data is present) and the built-in hard cases:
#     the six rungs (float, filtered, additive, conservative, inclusion, exact), conservative with a δ sweep
#     (fallback "hit") and with the exact fallback, inclusion at δ = 1e-2 and 1e-4 too.
#  2. The pipeline's ms per step on the default cloth scene with each rung, in alternating rounds.
#  3. The earliest time of impact of each shared real step (`ccdlab step --earliest`) with each rung, against exact's.
#  4. analysis/plot_accuracy.py: results/accuracy/accuracy_overview.png, accuracy_time.png and the markdown
#     tables (table.md).
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
testers=(float filtered additive)
for delta in 1e-2 1e-4 1e-6 1e-8 0; do testers+=("conservative:delta=$delta"); done
testers+=("conservative:fallback=exact" inclusion:delta=1e-2 inclusion:delta=1e-4 inclusion exact)
args=()
for t in "${testers[@]}"; do args+=(--tester "$t"); done
build/bin/ccdlab validate "${sets[@]}" "${args[@]}" --repeat 5 --no-progress --out "$out" > "$out/validate.txt"
echo "validate: $out/validate.txt, $out/validate.csv, $out/queries.csv" >&2

# Pipeline time per tester: the configurations alternate within each round (forward, then backward).
pipeline_testers=(float filtered additive conservative inclusion exact)
echo "round,tester,ms_per_step,contacts_vf,contacts_ee,hash" > "$out/pipeline.csv"
for r in $(seq 1 "$rounds"); do
  order=("${pipeline_testers[@]}")
  if [ $((r % 2)) -eq 0 ]; then order=(exact inclusion conservative additive filtered float); fi
  for t in "${order[@]}"; do
    json=$(build/bin/ccdlab run experiments/configs/default.yaml --json --no-progress --set tester=$t \
             --set "output.dir=$out/runs/$t")
    /usr/bin/python3 -c 'import json, sys; d = json.loads(sys.argv[1]); c = d["contacts"]
print(",".join(map(str, [sys.argv[2], sys.argv[3], d["ms_per_step"], c["vf"], c["ee"], d["hash"]])))' \
      "$json" "$r" "$t" >> "$out/pipeline.csv"
    echo "round $r $t: $(tail -1 "$out/pipeline.csv")" >&2
  done
done
# The earliest time of impact of each shared real step, per rung (ms: the query's own, one thread).
echo "step,tester,earliest_toi,exact_toi,ms" > "$out/earliest.csv"
meshes=../shared/data/meshes
if [ -d "$meshes" ]; then
  for step in "cloth-funnel/227 cloth-funnel/228" "rod-twist/3036 rod-twist/3037" \
              "n-body-simulation/balls16_18 n-body-simulation/balls16_19"; do
    set -- $step
    earliest() {
      build/bin/ccdlab step "$meshes/$1.ply" "$meshes/$2.ply" --tester "$3" --threads 1 --earliest --json --no-progress |
        /usr/bin/python3 -c 'import json, sys; d = json.load(sys.stdin); print(repr(d["earliest_toi"]), d["ms"]["total"])'
    }
    read -r exact_toi _ <<< "$(earliest "$1" "$2" exact)"
    for t in "${pipeline_testers[@]}"; do
      read -r toi ms <<< "$(earliest "$1" "$2" "$t")"
      echo "${1%%/*},$t,$toi,$exact_toi,$ms" >> "$out/earliest.csv"
    done
    echo "earliest: ${1%%/*} done" >&2
  done
fi
/usr/bin/python3 analysis/plot_accuracy.py "$out" | tee "$out/table.md"
