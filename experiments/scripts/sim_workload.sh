#!/usr/bin/env bash
# The CCD workload of simulated scenes (docs/simulation.md): `ccdlab run` on every step of each scene's cached
# full-size frames, K = 18, sequential, one thread, `float` with the scene's own thickness, so "contacts" are the
# feature pairs that come within the thickness — what the scene's contact response works on. Prints one
# Markdown row per scene (per step: BV tests, candidate face pairs, contacts).
#   experiments/scripts/sim_workload.sh [SCENE …]     (default: cloth_ball skirt flamenco funnel)
# Simulates a scene first if its frames are not cached (results/scenes/NAME-HASH/).
set -euo pipefail
cd "$(dirname "$0")/../.."
out=results/sim_workload
mkdir -p "$out"
echo "| scene | steps | BV tests / step | candidate face pairs / step | contacts / step (VF + EE, within the thickness) |"
echo "|---|---:|---:|---:|---:|"
for scene in "${@:-cloth_ball skirt flamenco funnel}"; do
  for s in $scene; do
    thickness=$(awk '$1 == "thickness:" {print $2}' "experiments/scenes/$s.yaml")
    cat > "$out/$s.yaml" <<EOC
name: workload_$s
scene: {builtin: simulated, file: experiments/scenes/$s.yaml, resolution: 1}
bv: {k: 18}
scheduler: sequential
threads: 1
tester: {name: float, thickness: $thickness}
output: {dir: $out/$s}
EOC
    build/bin/ccdlab run "$out/$s.yaml" --json --no-progress > "$out/$s.json"
    /usr/bin/python3 - "$out/$s.json" "$s" <<'EOP'
import json, sys
d = json.load(open(sys.argv[1]))
c, n = d["counters"], d["steps"]
contacts = d["contacts"]["vf"] + d["contacts"]["ee"]
print(f"| {sys.argv[2]} | {n} | {c['bv_tests'] / n:,.0f} | {c['candidate_pairs'] / n:,.0f} | {contacts / n:,.0f} |")
EOP
  done
done
