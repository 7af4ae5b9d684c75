"""pytest for the ccdlab Python package (build/python/ccdlab, or the installed one: conftest.py): answers, options and
errors on meshes made here, and the same contacts (ids, times, coordinates, normals) as the CLI on the real
cloth-funnel step (skipped where ../shared/data is absent)."""
import csv
import subprocess
from pathlib import Path

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[2]
ccdlab = pytest.importorskip("ccdlab", reason="the Python package is neither built (build/python) nor installed")
FUNNEL = ROOT.parent / "shared" / "data" / "meshes" / "cloth-funnel"


def falling_vertex():
    """Two triangles of one mesh: a small one whose lowest vertex drops through a big horizontal one."""
    x0 = np.array([[0, 0, 0], [2, 0, 0], [0, 2, 0],                  # big triangle, z = 0
                   [0.4, 0.3, 0.5], [0.6, 0.3, 0.9], [0.4, 0.5, 0.9]])  # small one above it
    x1 = x0.copy()
    x1[3:, 2] -= 0.625                                                 # vertex 3 crosses z = 0 at t = 0.8
    return x0, x1, np.array([[0, 1, 2], [3, 4, 5]])


def test_a_falling_vertex_hits_the_face_at_half_time():
    x0, x1, faces = falling_vertex()
    r = ccdlab.step(x0, x1, faces)
    assert r["vf"].tolist() == [[3, 0, 1, 2]]
    assert r["ee"].shape == (0, 4)
    assert r["vf_toi"][0] == pytest.approx(0.8, abs=1e-9)
    # Barycentric weights of f1, f2 at the hit point (0.4, 0.3, 0): 0.4 / 2 and 0.3 / 2.
    assert r["vf_coords"][0] == pytest.approx([0.2, 0.15], abs=1e-9)
    assert abs(r["vf_normal"][0] @ [0, 0, 1]) == pytest.approx(1.0)
    for tester in ("filtered", "conservative", "exact", {"name": "conservative", "fallback": "exact"},
                   "conservative:delta=1e-4"):
        assert ccdlab.step(x0, x1, faces, tester=tester)["hash"] == r["hash"], tester


def test_options_are_the_yaml_strategies_and_errors_name_them():
    x0, x1, faces = falling_vertex()
    for k in (6, 14, 18, 26):
        for scheduler in ("sequential", "phc", "static", "front"):
            r = ccdlab.step(x0, x1, faces, k=k, scheduler=scheduler, threads=2, width=4)
            assert r["vf"].shape == (1, 4)
    with pytest.raises(ccdlab.Error, match="k: expected one of 6, 14, 18, 26, got 7"):
        ccdlab.step(x0, x1, faces, k=7)
    with pytest.raises(ccdlab.Error, match=r"tester=conservative:delta=2: tester.delta: expected a number in \[0, 1\]"):
        ccdlab.step(x0, x1, faces, tester="conservative:delta=2")
    with pytest.raises(ccdlab.Error, match="unknown option 'kk'"):
        ccdlab.step(x0, x1, faces, kk=18)
    for end_boxes in (True, False, "auto", "on", "off"):
        assert ccdlab.step(x0, x1, faces, end_boxes=end_boxes)["vf"].shape == (1, 4)
    with pytest.raises(ccdlab.Error, match="end_boxes: expected on, off, auto, true or false, got 'often'"):
        ccdlab.step(x0, x1, faces, end_boxes="often")
    # A thickness far larger than the scene: refused with the estimate, unless the limit allows it.
    with pytest.raises(ccdlab.Error, match="candidate triangle pairs expected .* above candidate_limit = 0.25 per "
                                           "triangle: the tester's thickness 100 is"):
        ccdlab.step(x0, x1, faces, tester="float:thickness=100", candidate_limit=0.25)
    assert ccdlab.step(x0, x1, faces, tester="float:thickness=100", candidate_limit=0)["vf"].shape[0] > 0
    with pytest.raises(ccdlab.Error, match="candidate_limit: expected 0 \\(no limit\\) or a finite number > 0"):
        ccdlab.step(x0, x1, faces, candidate_limit=-1)
    # A step past its time limit stops and says so; with room it runs.
    with pytest.raises(ccdlab.Error, match="time_limit 1e-09 s: the step was stopped after"):
        ccdlab.step(x0, x1, faces, time_limit=1e-9)
    assert ccdlab.step(x0, x1, faces, time_limit=600)["vf"].shape == (1, 4)
    with pytest.raises(ccdlab.Error, match="faces\\[1\\]\\[2\\] = 9 is not a vertex index"):
        ccdlab.step(x0, x1, np.array([[0, 1, 2], [3, 4, 9]]))
    bad = x1.copy()
    bad[4, 0] = np.nan
    with pytest.raises(ccdlab.Error, match="is not finite"):
        ccdlab.step(x0, bad, faces)


def test_faces_must_hold_integers_and_every_message_names_its_call():
    x0, x1, faces = falling_vertex()
    with pytest.raises(ccdlab.Error, match=r"^ccdlab.step: faces\[0\]\[0\] = 0.5 is not an integer vertex index"):
        ccdlab.step(x0, x1, np.array([[0.5, 1, 2], [3, 4, 5]]))
    assert ccdlab.step(x0, x1, faces.astype(float))["vf"].tolist() == [[3, 0, 1, 2]]  # integral floats are fine
    with pytest.raises(ccdlab.Error, match=r"^ccdlab.step: faces must be an F×3 array-like of integer vertex indices, "
                                           r"got an array of dtype <U1 and shape 1×3"):
        ccdlab.step(x0, x1, np.array([["a", "b", "c"]]))
    with pytest.raises(ccdlab.Error, match=r"^ccdlab.step: faces: face 1: degenerate"):
        ccdlab.step(x0, x1, np.array([[0, 1, 2], [3, 4, 4]]))
    with pytest.raises(ccdlab.Error, match=r"^ccdlab.step: x1 has 5 vertices, x0 has 6"):
        ccdlab.step(x0, x1[:5], faces)
    with pytest.raises(ccdlab.Error, match=r"^ccdlab.sequence: frames\[1\] has 5 vertices"):
        ccdlab.sequence([x0, x1[:5]], faces)
    with pytest.raises(ccdlab.Error, match=r"^ccdlab.earliest_toi: unknown option 'kk'"):
        ccdlab.earliest_toi(x0, x1, faces, kk=1)
    with pytest.raises(ccdlab.Error, match=r"^ccdlab.earliest_toi: faces\[0\]\[1\] = 1.5"):
        ccdlab.earliest_toi(x0, x1, np.array([[0, 1.5, 2]]))


def test_array_likes_are_converted_and_the_rest_refused_naming_shape_and_dtype():
    x0, x1, faces = falling_vertex()
    expected = ccdlab.step(x0, x1, faces)["hash"]
    def doubled(a):  # every other row of a twice-as-long array: not contiguous
        return np.repeat(a, 2, axis=0)[::2]
    for name, (a, b, f) in {
            "lists": (x0.tolist(), x1.tolist(), faces.tolist()),
            "tuples": (tuple(map(tuple, x0)), tuple(map(tuple, x1)), tuple(map(tuple, faces))),
            "float32 and int32": (x0.astype(np.float32), x1.astype(np.float32), faces.astype(np.int32)),
            "Fortran order": (np.asfortranarray(x0), np.asfortranarray(x1), np.asfortranarray(faces)),
            "strided": (doubled(x0), doubled(x1), doubled(faces)),
            "uint16 faces": (x0, x1, faces.astype(np.uint16))}.items():
        assert not name.startswith("strided") or not a.flags["C_CONTIGUOUS"]
        assert ccdlab.step(a, b, f)["hash"] == expected, name
        assert ccdlab.earliest_toi(a, b, f) == pytest.approx(0.8, abs=1e-9), name
    assert ccdlab.sequence([x0.tolist(), x1.tolist()], faces.tolist())[0]["hash"] == expected
    assert ccdlab.sequence(np.stack([x0, x1]), faces)[0]["hash"] == expected
    for args, message in [
            (("abc", x1, faces), "x0 must be an N×3 array-like of positions, got str"),
            ((None, x1, faces), "x0 must be an N×3 array-like of positions, got NoneType"),
            (([[0, 0], [1, 2, 3]], x1, faces), "x0 must be an N×3 array-like of positions, got list that NumPy cannot read"),
            ((x0, x1[:, :2], faces), "x1 must be an N×3 array-like of positions, got an array of dtype float64 and shape 6×2"),
            ((x0, x1, "abc"), "faces must be an F×3 array-like of integer vertex indices, got str"),
            ((x0, x1, [0, 1, 2]), "faces must be an F×3 array-like of integer vertex indices, got an array of dtype int64 and shape 3")]:
        with pytest.raises(ccdlab.Error, match="^ccdlab.step: " + message.replace("(", r"\(")):
            ccdlab.step(*args)
    with pytest.raises(ccdlab.Error, match="^ccdlab.sequence: frames must be a list of N×3 array-likes of positions, got str"):
        ccdlab.sequence("abc", faces)


def test_earliest_toi_is_the_steps_earliest_contact():
    x0, x1, faces = falling_vertex()
    exact = ccdlab.earliest_toi(x0, x1, faces, tester="exact")
    for tester in ("float", "exact", "conservative"):
        r = ccdlab.step(x0, x1, faces, tester=tester)
        t = ccdlab.earliest_toi(x0, x1, faces, tester=tester, scheduler="phc", threads=2)
        first = min(r["vf_toi"].tolist() + r["ee_toi"].tolist())
        if tester == "conservative":  # narrowed: from its step's lower bound to within 1e-9 of the truth
            assert first <= t <= exact and exact - t <= 1e-9
        else:
            assert t == first, tester
    assert ccdlab.earliest_toi(x0, x0, faces) == 1.0  # no motion, no contact


def test_sequence_refits_one_hierarchy_over_the_frames():
    x0, x1, faces = falling_vertex()
    mid = x0.copy()
    mid[3:, 2] -= 0.25  # vertex 3 at z = 0.25: the crossing is in the second step, at t = 0.25 / 0.375
    steps = ccdlab.sequence([x0, mid, x1], faces)
    assert len(steps) == 2
    assert steps[0]["vf"].shape == (0, 4) and steps[1]["vf"].tolist() == [[3, 0, 1, 2]]
    assert steps[1]["vf_toi"][0] == pytest.approx(2 / 3, abs=1e-9)
    assert steps[0]["ms"]["build"] > 0 and steps[1]["ms"]["build"] == 0


@pytest.mark.skipif(not (FUNNEL / "227.ply").exists(), reason="../shared/data is absent")
def test_funnel_contacts_equal_the_cli(tmp_path):
    meshio = pytest.importorskip("meshio")
    m0, m1 = meshio.read(FUNNEL / "227.ply"), meshio.read(FUNNEL / "228.ply")
    r = ccdlab.step(m0.points, m1.points, m0.cells_dict["triangle"], scheduler="phc", threads=2)
    cli = ROOT / "build" / "bin" / "ccdlab"
    subprocess.run([str(cli), "step", str(FUNNEL / "227.ply"), str(FUNNEL / "228.ply"), "--contacts",
                    str(tmp_path / "c.csv")], check=True, capture_output=True)
    rows = list(csv.DictReader((tmp_path / "c.csv").open()))
    want = {"vf": [], "ee": []}
    for row in rows:
        want[row["kind"]].append(([int(row[c]) for c in "abcd"], float(row["toi"]), [float(row["u"]), float(row["v"])],
                                  [float(row[c]) for c in ("nx", "ny", "nz")]))
    assert len(rows) == 134  # the step's true contacts (../shared/data ground truth)
    for kind in ("vf", "ee"):
        assert r[kind].tolist() == [w[0] for w in want[kind]]
        assert r[kind + "_toi"].tolist() == pytest.approx([w[1] for w in want[kind]], abs=1e-15)
        assert np.allclose(r[kind + "_coords"], np.array([w[2] for w in want[kind]]).reshape(-1, 2), rtol=0, atol=1e-15)
        assert np.allclose(r[kind + "_normal"], np.array([w[3] for w in want[kind]]).reshape(-1, 3), rtol=0, atol=1e-15)
        assert np.allclose(np.linalg.norm(r[kind + "_normal"], axis=1), 1.0)


def test_validate_scores_like_the_cli():
    """ccdlab.validate gives, per set and tester, the answers `ccdlab validate --json` gives (times aside)."""
    cli = ROOT / "build" / "bin" / "ccdlab"
    if not cli.exists():
        pytest.skip("build/bin/ccdlab not built")
    done = subprocess.run([str(cli), "validate", "hard-cases", "--tester", "float", "--tester", "conservative",
                           "--json", "--no-progress", "--repeat", "1"], capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    import json
    keys = ("set", "scene", "tester", "queries", "positives", "false_negatives", "false_positives", "fallbacks",
            "toi_late")
    expected = [{k: s[k] for k in keys} for s in json.loads(done.stdout)["scores"]]
    rows = ccdlab.validate(["hard-cases"], testers=["float", "conservative"])
    assert [{k: r[k] for k in keys} for r in rows] == expected
    assert all(r["false_negatives"] == 0 for r in rows if r["tester"] == "conservative")
    with pytest.raises(ccdlab.Error, match="tester.name: expected one of"):
        ccdlab.validate(["hard-cases"], testers=["nope"])
    with pytest.raises(ccdlab.Error):
        ccdlab.validate(["/nonexistent/queries"])


def test_the_stubs_list_every_setting_as_the_table_does():
    """__init__.pyi's Options (the keywords' types for a type checker) is the settings table's
    (framework/config/settings.def): a row added, renamed or retyped there fails here until the stub follows."""
    stub = (ROOT / "experiments" / "python" / "ccdlab" / "__init__.pyi").read_text()
    block = stub[stub.index("class Options(TypedDict, total=False):"):]
    block = block[:block.index("\n\n")]
    listed = [line.strip() for line in block.splitlines()[2:]]
    assert listed == [f"{s['keyword']}: {s['type']}  # {s['doc']}" for s in ccdlab.settings()]


def test_every_setting_is_a_keyword_whose_default_changes_nothing():
    x0, x1, faces = falling_vertex()
    reference = ccdlab.step(x0, x1, faces)["hash"]
    for s in ccdlab.settings():
        assert ccdlab.step(x0, x1, faces, **{s["keyword"]: s["default"]})["hash"] == reference, s["keyword"]
    with pytest.raises(ccdlab.Error, match="ccdlab.step: rule_proximity: expected auto, on, off, true or false, got 'sometimes'"):
        ccdlab.step(x0, x1, faces, rule_proximity="sometimes")
