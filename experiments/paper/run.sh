#!/usr/bin/env bash
# The paper's Table 1 (ms per step by K) and Table 2 (ms per step by scheduler) on every scene we have, with
# the paper's numbers beside ours and the figures: installs dependencies, builds, runs the benches, writes
# docs/results.md and docs/img/results/ (raw results in results/paper/). About 30 minutes on 2 cores with the
# simulated scenes cached (simulating skirt, flamenco and cloth_ball once at full size adds about 20 more) and the
# shared data present. Options go to experiments/paper/paper_tables.py (--rounds R, --scenes a,b).
set -euo pipefail
cd "$(dirname "$0")/../.."
experiments/scripts/install-deps.sh
experiments/scripts/build.sh release
/usr/bin/python3 experiments/paper/paper_tables.py --doc docs/results.md "$@"
