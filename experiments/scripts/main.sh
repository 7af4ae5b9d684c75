#!/usr/bin/env bash
# The main job: install dependencies, build, run the default experiment on the built-in scene,
# print its per-step table and write CSV/JSONL results and PNG plots to results/default/; then a small
# simulated scene (cloth_ball at 5% size: simulated once with only its declared effects, cached in
# results/cloth_ball_small/scene/, then CCD on its frames) with its plots and a picture of its frames.
set -euo pipefail
cd "$(dirname "$0")/../.."
experiments/scripts/install-deps.sh
experiments/scripts/build.sh release
build/bin/ccdlab run experiments/configs/default.yaml "$@"
/usr/bin/python3 analysis/plot_run.py results/default
build/bin/ccdlab run experiments/configs/cloth_ball_small.yaml "$@"
/usr/bin/python3 analysis/plot_run.py results/cloth_ball_small
/usr/bin/python3 analysis/render_scene.py results/cloth_ball_small/scene --out results/cloth_ball_small/frames.png
