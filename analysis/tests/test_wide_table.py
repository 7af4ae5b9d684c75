"""pytest for analysis/wide_table.py: binary vs 4-wide BVH on a small crumpled step written here as PLY."""
import csv
import math
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
CLI = ROOT / "build" / "bin" / "ccdlab"


def write_ply(path: Path, points, faces):
    lines = ["ply", "format ascii 1.0", f"element vertex {len(points)}", "property double x", "property double y",
             "property double z", f"element face {len(faces)}", "property list uchar int vertex_indices", "end_header"]
    lines += [f"{x!r} {y!r} {z!r}" for x, y, z in points]
    lines += [f"3 {a} {b} {c}" for a, b, c in faces]
    path.write_text("\n".join(lines) + "\n")


def crumpled_step(folder: Path):
    """A 16×16 sheet folded over itself, moving a little: many overlapping leaves, some contacts."""
    n = 16
    faces = []
    for i in range(n):
        for j in range(n):
            v = i * (n + 1) + j
            faces += [(v, v + 1, v + n + 2), (v, v + n + 2, v + n + 1)]
    frames = []
    for t in (0.0, 1.0):
        pts = []
        for i in range(n + 1):
            for j in range(n + 1):
                u, w = i / n, j / n
                a = math.pi * 1.9 * u
                pts.append((0.2 * math.cos(a) + 0.01 * t * w, 0.2 * math.sin(a) * (0.3 + u) - 0.02 * t, w))
        frames.append(pts)
    folder.mkdir(parents=True)
    write_ply(folder / "3036.ply", frames[0], faces)
    write_ply(folder / "3037.ply", frames[1], faces)


@pytest.mark.skipif(not CLI.exists(), reason="build/bin/ccdlab not built")
def test_both_widths_reported_with_equal_answers(tmp_path):
    crumpled_step(tmp_path / "data" / "meshes" / "rod-twist")
    out = tmp_path / "wide.csv"
    done = subprocess.run([sys.executable, str(ROOT / "analysis" / "wide_table.py"), "--cli", str(CLI), "--rounds", "2",
                           "--data", str(tmp_path / "data"), "--runs", "sequential:1,phc:2", "--out", str(out)],
                          capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    rows = list(csv.DictReader(out.open()))
    assert [(r["scheduler"], r["width"]) for r in rows] == [("sequential", "2"), ("sequential", "4"), ("phc", "2"),
                                                            ("phc", "4")]
    by = {(r["scheduler"], r["width"]): r for r in rows}
    assert int(by[("sequential", "2")]["bv_tests"]) > 0
    # The wide view's BV tests are lane tests: not the binary walk's count (other nodes are tested), but of its order
    # (the AVX-512 walk opens both sides, the SSE2 one the larger: ~0.8-1.1x the binary count on real steps).
    binary, wide = int(by[("sequential", "2")]["bv_tests"]), int(by[("sequential", "4")]["bv_tests"])
    assert wide != binary and binary / 2 < wide < 2 * binary
    assert "| rod-twist | sequential × 1 | 4 |" in done.stdout
    assert "skipped" in done.stderr  # the other real steps are absent from this data folder
