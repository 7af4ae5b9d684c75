#!/usr/bin/env bash
# The main job: install dependencies, build, run the default experiment on the built-in scene,
# print its per-step table and write CSV/JSONL results and PNG plots to results/default/.
set -euo pipefail
cd "$(dirname "$0")/../.."
experiments/scripts/install-deps.sh
experiments/scripts/build.sh release
build/bin/ccdlab run experiments/configs/default.yaml "$@"
/usr/bin/python3 analysis/plot_run.py results/default
