#!/usr/bin/env bash
# A Slurm job array that runs a sweep as SHARDS shards, one array task each, then merges the results.
#
#   sbatch --array=0-7 experiments/sweeps/slurm_array.sh experiments/sweeps/k_scheduler_threads.yaml 8
#   # when every task has finished (or from a dependent job: sbatch --dependency=afterok:JOBID …):
#   build/bin/ccdlab sweep experiments/sweeps/k_scheduler_threads.yaml --merge
#
# Task i runs `ccdlab sweep SWEEP.yaml --shard i/SHARDS`: a deterministic share of the runs, each into its own
# folder under the sweep's output.dir (put it on a file system every node sees). A task that is preempted or
# requeued skips the runs it already finished. Threads per run come from the sweep file (threads: …); ask
# Slurm for as many CPUs. Outside Slurm (SLURM_ARRAY_TASK_ID unset) the script runs shard 0.
#SBATCH --job-name=ccdlab-sweep
#SBATCH --cpus-per-task=2
#SBATCH --time=02:00:00
#SBATCH --output=ccdlab-sweep-%A_%a.log
set -euo pipefail
sweep="${1:?usage: slurm_array.sh SWEEP.yaml SHARDS}"
shards="${2:?usage: slurm_array.sh SWEEP.yaml SHARDS}"
ccdlab="${CCDLAB:-${SLURM_SUBMIT_DIR:-$(pwd)}/build/bin/ccdlab}"
task="${SLURM_ARRAY_TASK_ID:-0}"
exec "$ccdlab" sweep "$sweep" --shard "$task/$shards" --no-progress
