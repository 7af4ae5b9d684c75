"""pytest for `ccdlab sweep`: a sweep killed after its first run resumes, shards split the runs, and --merge
gathers every finished run into runs.csv (one row per run, every resolved config column, one contact hash)."""
import csv
import signal
import subprocess
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
CLI = ROOT / "build" / "bin" / "ccdlab"

SWEEP = """name: tiny-sweep
scene: {builtin: drape_fold, resolution: 10, num_frames: 3, sphere_segments: 8}
tester: {name: float, thickness: 0}
output: {dir: OUT}
sweep:
  bv.k: [6, 18]
  scheduler: [sequential, phc]
  threads: [1, 2]
"""


def sweep(path, *args):
    done = subprocess.run([str(CLI), "sweep", str(path), "--no-progress", *args], capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    return done.stdout


@pytest.mark.skipif(not CLI.exists(), reason="build/bin/ccdlab not built")
def test_interrupted_sweep_resumes_and_merges(tmp_path):
    out = tmp_path / "out"
    path = tmp_path / "sweep.yaml"
    path.write_text(SWEEP.replace("OUT", str(out)))
    assert "8 runs" in sweep(path, "--dry-run")

    # Kill the sweep as soon as its first run has finished.
    proc = subprocess.Popen([str(CLI), "sweep", str(path), "--no-progress"], stdout=subprocess.PIPE, text=True)
    for line in proc.stdout:
        if line.startswith("[1/8]"):
            proc.send_signal(signal.SIGKILL)
            break
    proc.wait()
    done_before = sorted(p.parent for p in out.glob("*/rep0/run.json"))
    assert 1 <= len(done_before) < 8

    # Shard 1 of 2 runs only odd-indexed runs; then the whole sweep finishes the rest, skipping what is done.
    shard = sweep(path, "--shard", "1/2")
    assert "shard 1/2 holds 4" in shard
    rest = sweep(path)
    skipped = rest.count("complete, skipped")
    assert skipped >= 4 + len(done_before) - 1  # shard 1's four, and what the killed run finished (maybe one of them)
    assert rest.count("ms/step") == 8 - skipped
    assert len(list(out.glob("*/rep0/run.json"))) == 8

    merged = sweep(path, "--merge")
    assert "merged 8 of 8 runs" in merged
    rows = list(csv.DictReader((out / "runs.csv").open()))
    assert len(rows) == 8
    assert {r["label"] for r in rows} == {f"bv.k={k},scheduler={s},threads={t}" for k in (6, 18)
                                          for s in ("sequential", "phc") for t in (1, 2)}
    for col in ("bv.k", "scheduler.name", "threads", "tester.name", "scene.resolution", "ms_per_step", "hash",
                "git_revision", "compiler", "cpu", "config_hash"):
        assert col in rows[0], col
    assert len({r["hash"] for r in rows}) == 1, "every K, scheduler and thread count finds the same contacts"
    assert all(float(r["ms_per_step"]) > 0 for r in rows)


@pytest.mark.skipif(not CLI.exists(), reason="build/bin/ccdlab not built")
def test_bad_shard_is_refused(tmp_path):
    path = tmp_path / "sweep.yaml"
    path.write_text(SWEEP.replace("OUT", str(tmp_path / "out")))
    done = subprocess.run([str(CLI), "sweep", str(path), "--shard", "2/2"], capture_output=True, text=True)
    assert done.returncode == 2
    assert "--shard: expected i/n with 0 <= i < n (e.g. 0/4), got '2/2'" in done.stderr


@pytest.mark.skipif(not CLI.exists(), reason="build/bin/ccdlab not built")
def test_example_scripts_run_every_shard_and_merge(tmp_path):
    """The GNU parallel script (xargs -P where parallel is absent) and the Slurm array script outside Slurm."""
    out = tmp_path / "out"
    path = tmp_path / "sweep.yaml"
    path.write_text(SWEEP.replace("OUT", str(out)))
    env = {"CCDLAB": str(CLI), "PATH": "/usr/bin:/bin"}
    slurm = subprocess.run(["bash", str(ROOT / "experiments/sweeps/slurm_array.sh"), str(path), "4"],
                           capture_output=True, text=True, env={**env, "SLURM_ARRAY_TASK_ID": "3"})
    assert slurm.returncode == 0, slurm.stderr
    assert "shard 3/4 holds 2" in slurm.stdout
    par = subprocess.run(["bash", str(ROOT / "experiments/sweeps/gnu_parallel.sh"), str(path), "3"],
                         capture_output=True, text=True, env=env)
    assert par.returncode == 0, par.stderr
    assert "merged 8 of 8 runs" in par.stdout
    assert par.stdout.count("complete, skipped") == 2  # the Slurm task's two runs
