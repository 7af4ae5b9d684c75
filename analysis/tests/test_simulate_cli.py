"""pytest for `ccdlab simulate`: frames as PLY that meshio reads, meta.json with per-frame, per-effect records
and zero crossing triangle pairs, the cache (a second run with the same scene simulates nothing, --force does),
located errors, and the pictures of analysis/render_scene.py."""
import json
import subprocess
import sys
from pathlib import Path

import pytest

meshio = pytest.importorskip("meshio")

ROOT = Path(__file__).resolve().parents[2]
CLI = ROOT / "build" / "bin" / "ccdlab"
SCENE = ROOT / "experiments" / "scenes" / "cloth_ball.yaml"


def simulate(*args):
    return subprocess.run([str(CLI), "simulate", str(SCENE), "--no-progress", *args], capture_output=True, text=True)


@pytest.mark.skipif(not CLI.exists(), reason="build/bin/ccdlab not built")
def test_simulate_writes_frames_meta_and_caches(tmp_path):
    out = tmp_path / "ball"
    args = ["--set", "resolution=0.01", "--set", "frames=6", "--set", "threads=2", "--out", str(out)]
    done = simulate(*args)
    assert done.returncode == 0, done.stderr
    meta = json.loads((out / "meta.json").read_text())
    assert meta["complete"] and meta["scene"] == "cloth_ball" and len(meta["frames"]) == 6
    names = [n.split(":")[1] for n in meta["effects_total"]]
    assert names == ["gravity", "damping", "stretch", "bend", "obstacle_contact", "ccd_contact"]
    for record in meta["frames"]:
        mesh = meshio.read(out / record["file"])
        assert len(mesh.cells_dict["triangle"]) == meta["triangles"]
        assert record["intersecting_pairs"] == 0
        assert set(record["effects"]) == set(meta["effects_total"])
    last = meshio.read(out / meta["frames"][-1]["file"]).points
    first = meshio.read(out / meta["frames"][0]["file"]).points
    assert last[0][1] < first[0][1], "the sheet fell"

    again = simulate(*args)
    assert again.returncode == 0 and "cached" in again.stdout
    # The thread count is not part of the cache key: frames do not depend on it.
    assert "cached" in simulate(*args[:-3], "threads=1", "--out", str(out)).stdout
    assert "warning" not in again.stderr, "made by this revision: no warning"
    # Frames of another revision are reused (the key is the scene), with a warning naming both revisions.
    meta["git_revision"] = "0123456789ab"
    (out / "meta.json").write_text(json.dumps(meta))
    stale = simulate(*args)
    assert stale.returncode == 0 and "cached" in stale.stdout
    assert "warning" in stale.stderr and "0123456789ab" in stale.stderr and "--force" in stale.stderr
    forced = simulate(*args, "--force")
    assert forced.returncode == 0 and "cached" not in forced.stdout

    sys.path.insert(0, str(ROOT / "analysis"))
    import sim_table
    table = sim_table.markdown([sim_table.summary(out, 1)], 1)
    assert "| cloth_ball |" in table and "| ccd_contact |" in table and "contacts resolved" in table
    import render_scene
    assert render_scene.main([str(out), "--frames", "0,5", "--out", str(tmp_path / "f.png"), "--dpi", "40"]) == 0
    assert (tmp_path / "f.png").read_bytes()[:4] == b"\x89PNG"


@pytest.mark.skipif(not CLI.exists(), reason="build/bin/ccdlab not built")
def test_simulate_errors_are_located(tmp_path):
    done = simulate("--set", "resolution=-1", "--out", str(tmp_path / "x"))
    assert done.returncode == 2 and "resolution" in done.stderr
    bad = tmp_path / "bad.yaml"
    bad.write_text("frames: 2\nresolution: 1\nthreads: 1\ncloth:\n  - {shape: sheet, size: [1, 1], cells: [2, 2]}\n"
                   "effects:\n  - {name: gravty}\n")
    done = subprocess.run([str(CLI), "simulate", str(bad), "--out", str(tmp_path / "y")], capture_output=True, text=True)
    assert done.returncode == 2 and "bad.yaml:7" in done.stderr and "gravity" in done.stderr


@pytest.mark.skipif(not CLI.exists(), reason="build/bin/ccdlab not built")
def test_an_experiment_names_a_simulated_scene(tmp_path):
    """`scene: {builtin: simulated, file: …}` simulates once (cached) and runs CCD on the frames with the scene's
    bodies; the answer does not depend on the threads of either."""
    config = tmp_path / "exp.yaml"
    config.write_text(f"name: sim\nscene: {{builtin: simulated, file: {SCENE}, num_frames: 4, resolution: 0.01}}\n"
                      f"output: {{dir: {tmp_path / 'out'}}}\n")
    hashes = set()
    for threads in ("1", "2"):
        done = subprocess.run([str(CLI), "run", str(config), "--json", "--no-progress", "--set", f"threads={threads}",
                               "--set", f"scene.threads={threads}"], capture_output=True, text=True, cwd=tmp_path)
        assert done.returncode == 0, done.stderr
        summary = json.loads(done.stdout)
        assert summary["steps"] == 3
        hashes.add(summary["hash"])
    assert len(hashes) == 1
    # first_frame: CCD from a later frame of the same (cached) frames; too late a start is refused.
    done = subprocess.run([str(CLI), "run", str(config), "--json", "--no-progress", "--set", "scene.first_frame=1"],
                          capture_output=True, text=True, cwd=tmp_path)
    assert done.returncode == 0, done.stderr
    assert json.loads(done.stdout)["steps"] == 2
    done = subprocess.run([str(CLI), "run", str(config), "--no-progress", "--set", "scene.first_frame=3"],
                          capture_output=True, text=True, cwd=tmp_path)
    assert done.returncode != 0 and "scene.first_frame: expected 0 … 2" in done.stderr, done.stderr
    bad = tmp_path / "bad.yaml"
    bad.write_text("scene: {builtin: simulated}\n")
    done = subprocess.run([str(CLI), "run", str(bad), "--no-progress"], capture_output=True, text=True)
    assert done.returncode == 2 and "needs file" in done.stderr
