"""pytest for `ccdlab export`: every file it writes opens with meshio, the series list their files, and the
arrays say what export.json says (frames, contacts of the detailed step, front changes, BVH depths)."""
import json
import subprocess
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np
import pytest

meshio = pytest.importorskip("meshio")

ROOT = Path(__file__).resolve().parents[2]
CLI = ROOT / "build" / "bin" / "ccdlab"


def cell_array(mesh, name):
    return np.concatenate([np.asarray(block) for block in mesh.cell_data[name]])


@pytest.mark.skipif(not CLI.exists(), reason="build/bin/ccdlab not built")
@pytest.mark.parametrize("k", [6, 18])
def test_export_opens_in_meshio(tmp_path, k):
    out = tmp_path / "vtk"
    done = subprocess.run(
        [str(CLI), "export", str(ROOT / "experiments/configs/default.yaml"), "--set", "scene.resolution=12",
         "--set", "scene.num_frames=6", "--set", "scene.sphere_segments=8", "--set", f"bv.k={k}",
         "--levels", "5", "--out", str(out), "--no-progress"],
        capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    index = json.loads((out / "export.json").read_text())
    assert index["config"]["bv"]["k"] == k
    step = index["step"]

    frames = [d.get("file") for d in ET.parse(out / "mesh.pvd").getroot().iter("DataSet")]
    assert len(frames) == index["frames"] == 6
    for name in frames:
        mesh = meshio.read(out / name)
        assert mesh.cells[0].type == "triangle"
        assert sum(len(c.data) for c in mesh.cells) == index["triangles"]
        assert "displacement" in mesh.point_data
    busiest = meshio.read(out / frames[step])
    assert cell_array(busiest, "contacts").sum() > 0, "the detailed step has contacts on its triangles"

    levels = list(ET.parse(out / "bvh.pvd").getroot().iter("DataSet"))
    assert {float(d.get("timestep")) for d in levels} == {0, 1, 2, 3, 4}
    root = meshio.read(out / "bvh" / "body0_depth00.vtu")
    faces = sum(len(c.data) for c in root.cells)
    assert 6 <= faces <= k and set(cell_array(root, "node")) == {0}
    deeper = meshio.read(out / "bvh" / "body0_depth04.vtu")
    assert set(cell_array(deeper, "depth")) == {4} and len(set(cell_array(deeper, "node"))) > 1

    changes = np.zeros(3, dtype=int)
    for name in index["files"][2]["file"]:
        front = meshio.read(out / name)
        change = cell_array(front, "change").astype(int)
        changes += np.bincount(change, minlength=3)
        assert {c.type for c in front.cells} <= {"line", "vertex"}
    assert changes.tolist() == [index["front"]["kept"], index["front"]["sprouted"], index["front"]["pruned"]]

    contacts = meshio.read(out / "contacts.vtu")
    role, toi = cell_array(contacts, "role"), cell_array(contacts, "toi")
    assert (role == 0).sum() == index["contacts"] > 0
    assert ((toi >= 0) & (toi <= 1)).all()


@pytest.mark.skipif(not CLI.exists(), reason="build/bin/ccdlab not built")
def test_export_rejects_a_step_out_of_range(tmp_path):
    done = subprocess.run(
        [str(CLI), "export", str(ROOT / "experiments/configs/default.yaml"), "--set", "scene.resolution=8",
         "--set", "scene.num_frames=3", "--step", "7", "--out", str(tmp_path / "x"), "--no-progress"],
        capture_output=True, text=True)
    assert done.returncode == 2
    assert "--step: expected a step from 0 to 1" in done.stderr


@pytest.mark.skipif(not CLI.exists(), reason="build/bin/ccdlab not built")
def test_render_export_writes_the_four_pictures(tmp_path):
    import sys
    sys.path.insert(0, str(ROOT / "analysis"))
    import render_export

    out = tmp_path / "vtk"
    done = subprocess.run(
        [str(CLI), "export", str(ROOT / "experiments/configs/teaching.yaml"), "--set", "scene.resolution=8",
         "--set", "scene.num_frames=4", "--out", str(out), "--no-progress"], capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    assert render_export.main([str(out), "--out", str(tmp_path / "png"), "--levels", "0,2", "--dpi", "40"]) == 0
    for name in ("mesh_contacts", "bvh_levels", "front", "contacts"):
        png = tmp_path / "png" / f"{name}.png"
        assert png.stat().st_size > 1000 and png.read_bytes()[:4] == b"\x89PNG"
    assert render_export.main([str(tmp_path / "missing")]) == 2
