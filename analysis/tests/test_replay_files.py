"""pytest for analysis/replay_files.py: the files it writes replay the same step as `replay: {step: S}` on the
scene itself — the same positions bit for bit, so the same contact hash every step."""
import json
import subprocess
import sys
from pathlib import Path

import pytest

pytest.importorskip("meshio")

ROOT = Path(__file__).resolve().parents[2]
CLI = ROOT / "build" / "bin" / "ccdlab"
SCENE = ["--set", "scene.resolution=14", "--set", "scene.num_frames=8", "--set", "scene.sphere_segments=8"]


def hashes(config, out, *sets):
    done = subprocess.run([str(CLI), "run", str(config), "--no-progress", "--set", f"output.dir={out}", *sets],
                          capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    rows = [json.loads(line) for line in (out / "steps.jsonl").read_text().splitlines()]
    return [(r["hash"], r["contacts"]["vf"], r["contacts"]["ee"]) for r in rows if r.get("type") == "step"]


@pytest.mark.skipif(not CLI.exists(), reason="build/bin/ccdlab not built")
def test_replayed_files_match_the_replay_key(tmp_path):
    default = ROOT / "experiments/configs/default.yaml"
    done = subprocess.run([str(CLI), "export", str(default), *SCENE, "--levels", "1", "--out", str(tmp_path / "vtk"),
                           "--no-progress"], capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    done = subprocess.run([sys.executable, str(ROOT / "analysis/replay_files.py"), str(tmp_path / "vtk"), "5",
                           str(tmp_path / "files"), "--frames", "4"], capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    from_files = hashes(tmp_path / "files" / "replay.yaml", tmp_path / "a")
    replayed = hashes(default, tmp_path / "b", *SCENE, "--set", "replay.step=5", "--set", "replay.frames=4")
    assert len(from_files) == 3 and from_files[0][1] + from_files[0][2] > 0  # step 5 of this scene has contacts
    assert from_files == replayed
