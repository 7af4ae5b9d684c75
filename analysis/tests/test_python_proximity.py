"""pytest for the proximity query from Python (ccdlab.proximity, ccdlab.active_set_and_step) and for the package
itself: what it installs, which one is under test, its version."""
import csv
import os
import re
import subprocess
import tomllib
from pathlib import Path

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[2]
ccdlab = pytest.importorskip("ccdlab", reason="the Python package is neither built (build/python) nor installed")
FUNNEL = ROOT.parent / "shared" / "data" / "meshes" / "cloth-funnel"


def hovering_vertex():
    """A big triangle at z = 0 and a small one whose lowest vertex (3) is 0.5 above it, falling 0.625."""
    x0 = np.array([[0, 0, 0], [2, 0, 0], [0, 2, 0], [0.4, 0.3, 0.5], [0.6, 0.3, 0.9], [0.4, 0.5, 0.9]], float)
    x1 = x0.copy()
    x1[3:, 2] -= 0.625
    return x0, x1, np.array([[0, 1, 2], [3, 4, 5]])


def test_the_package_under_test_is_the_one_asked_for():
    installed = os.environ.get("CCDLAB_INSTALLED") == "1"
    in_build = Path(ccdlab.__file__).resolve().is_relative_to(ROOT / "build" / "python")
    assert in_build != installed, ccdlab.__file__
    here = Path(ccdlab.__file__).parent
    assert (here / "__init__.pyi").exists() and (here / "py.typed").exists(), "type stubs shipped beside the module"
    assert ccdlab.Error.__module__ == "ccdlab" and issubclass(ccdlab.Error, ValueError)


def test_the_package_version_is_the_cmake_projects():
    version = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]["version"]
    cmake = re.search(r"project\(ccdlab VERSION (\S+)", (ROOT / "CMakeLists.txt").read_text()).group(1)
    assert version == cmake


def test_a_vertex_above_a_face_is_near_it_with_its_distance_and_type():
    x0, _, faces = hovering_vertex()
    p = ccdlab.proximity(x0, faces, 0.55)  # edge (0, 1) is 0.58 from vertex 3: no EE pair
    assert p["vf"].tolist() == [[3, 0, 1, 2]]
    assert p["vf_distance"].tolist() == [0.5]
    assert p["vf_type"].tolist() == ["p_t"]
    assert p["vf_coords"][0] == pytest.approx([0.2, 0.15], abs=1e-15)
    assert p["ee"].shape == (0, 4) and p["ee_type"].shape == (0,)
    assert ccdlab.proximity(x0, faces, 0.5)["vf"].shape == (0, 4)  # at exactly d̂: not closer
    assert ccdlab.proximity(x0, faces, np.nextafter(0.5, 1))["vf"].shape == (1, 4)
    for scheduler in ("sequential", "phc", "front", "static"):
        for threads in (1, 2):
            assert ccdlab.proximity(x0.tolist(), faces, 0.55, scheduler=scheduler, threads=threads)["hash"] == p["hash"]
    assert ccdlab.proximity(x0, faces, 0.6)["ee"].tolist() == [[0, 1, 3, 4], [0, 1, 3, 5]]


def test_proximity_errors_name_the_call_and_the_argument():
    x0, _, faces = hovering_vertex()
    with pytest.raises(ccdlab.Error, match=r"^ccdlab.proximity: dhat = 0: expected a finite distance > 0"):
        ccdlab.proximity(x0, faces, 0)
    with pytest.raises(ccdlab.Error, match=r"^ccdlab.proximity: dhat = nan"):
        ccdlab.proximity(x0, faces, float("nan"))
    with pytest.raises(ccdlab.Error, match=r"^ccdlab.proximity: tester: not an option here"):
        ccdlab.proximity(x0, faces, 0.1, tester="exact")
    with pytest.raises(ccdlab.Error, match=r"^ccdlab.proximity: x must be an N×3 array-like of positions"):
        ccdlab.proximity(x0[:, :2], faces, 0.1)
    with pytest.raises(ccdlab.Error, match=r"^ccdlab.proximity: proximity query: about .* the proximity query's dhat 100"):
        ccdlab.proximity(x0, faces, 100.0, candidate_limit=0.1)
    with pytest.raises(ccdlab.Error, match=r"^ccdlab.active_set_and_step: separation = -1"):
        ccdlab.active_set_and_step(x0, x0, faces, 0.1, -1)


def test_active_set_and_step_gives_the_step_that_keeps_the_separation():
    x0, x1, faces = hovering_vertex()
    a = ccdlab.active_set_and_step(x0, x1, faces, 0.55, 0.1, scheduler="phc", threads=2)
    assert a["vf"].tolist() == [[3, 0, 1, 2]] and a["hash"] == ccdlab.proximity(x0, faces, 0.55)["hash"]
    # Vertex 3 comes within 0.1 of the face after 0.4 of its 0.625 fall: t = 0.64, never later.
    assert 0.63 < a["step_size"] <= 0.64
    x = x0 + a["step_size"] * (x1 - x0)
    assert ccdlab.proximity(x, faces, 0.1)["vf"].shape == (0, 4)
    assert ccdlab.active_set_and_step(x0, x0, faces, 0.6, 0.1)["step_size"] == 1.0


@pytest.mark.skipif(not (FUNNEL / "227.ply").exists(), reason="../shared/data is absent")
def test_funnel_pairs_equal_the_cli(tmp_path):
    meshio = pytest.importorskip("meshio")
    m = meshio.read(FUNNEL / "227.ply")
    lo, hi = m.points.min(axis=0), m.points.max(axis=0)
    dhat = 1e-3 * float(np.linalg.norm(hi - lo))
    p = ccdlab.proximity(m.points, m.cells_dict["triangle"], dhat, scheduler="phc", threads=2)
    cli = ROOT / "build" / "bin" / "ccdlab"
    out = subprocess.run([str(cli), "proximity", str(FUNNEL / "227.ply"), "--dhat", "1e-3", "--relative", "--pairs",
                          str(tmp_path / "p.csv"), "--json", "--no-progress"], check=True, capture_output=True, text=True)
    assert f'"hash": "{p["hash"]}"' in out.stdout
    rows = list(csv.DictReader((tmp_path / "p.csv").open()))
    for kind in ("vf", "ee"):
        want = [r for r in rows if r["kind"] == kind]
        assert len(want) > 1000
        assert p[kind].tolist() == [[int(r[c]) for c in "abcd"] for r in want]
        assert p[kind + "_distance"].tolist() == [float(r["distance"]) for r in want]
        assert p[kind + "_type"].tolist() == [r["type"] for r in want]
        assert (p[kind + "_distance"] < dhat).all()


def test_a_detector_keeps_its_hierarchies_across_calls_and_answers_as_the_functions():
    x0, x1, faces = hovering_vertex()
    d = ccdlab.Detector(faces, scheduler="phc", threads=2, tester={"name": "conservative", "delta": 1e-6})
    assert "name: conservative" in d.options and "threads: 2" in d.options
    for _ in range(2):  # built, then refit
        r, f = d.step(x0, x1), ccdlab.step(x0, x1, faces, tester="conservative:delta=1e-6")
        assert r["vf"].tolist() == f["vf"].tolist() and r["vf_toi"].tolist() == f["vf_toi"].tolist()
        assert d.earliest_toi(x0, x1) == ccdlab.earliest_toi(x0, x1, faces, tester="conservative:delta=1e-6")
        p, q = d.proximity(x0, 0.6), ccdlab.proximity(x0, faces, 0.6)
        for key in ("vf", "vf_distance", "vf_type", "vf_coords", "ee", "ee_distance", "ee_type", "ee_coords"):
            assert p[key].tolist() == q[key].tolist(), key
        a = d.active_set_and_step(x0.tolist(), x1, 0.55, 0.1)
        assert a["step_size"] == ccdlab.active_set_and_step(x0, x1, faces, 0.55, 0.1)["step_size"]
    # Several bodies: the floor triangle is an obstacle, the small one cloth.
    b = ccdlab.Detector(bodies=[{"faces": [[0, 1, 2]], "vertices": 3, "obstacle": True, "name": "floor"},
                                {"faces": [[0, 1, 2]], "vertices": 3, "name": "cloth"}])
    assert b.proximity(x0, 0.55)["vf"].tolist() == [[3, 0, 1, 2]]


def test_detector_errors_are_spelled_for_python():
    x0, x1, faces = hovering_vertex()
    d = ccdlab.Detector(faces)
    with pytest.raises(ccdlab.Error, match=r"^ccdlab.Detector: k: expected one of 6, 14, 18, 26, got 7"):
        ccdlab.Detector(faces, k=7)
    with pytest.raises(ccdlab.Error, match=r"^ccdlab.Detector: unknown option 'kk'"):
        ccdlab.Detector(faces, kk=1)
    with pytest.raises(ccdlab.Error, match=r"^ccdlab.Detector: give faces .* or bodies"):
        ccdlab.Detector()
    with pytest.raises(ccdlab.Error, match=r"^ccdlab.Detector: bodies\[0\]: unknown key 'vertex'"):
        ccdlab.Detector(bodies=[{"faces": [[0, 1, 2]], "vertex": 3}])
    with pytest.raises(ccdlab.Error, match=r"^ccdlab.Detector.proximity: dhat = -1"):
        d.proximity(x0, -1)
    d.step(x0, x1)
    with pytest.raises(ccdlab.Error, match=r"^ccdlab.Detector.step: x0 has 5 positions, but this detector's mesh has 6"):
        d.step(x0[:5], x1[:5])
