"""pytest for analysis/bound_floor.py: faces whose paths cross in a known order, written here as PLY."""
import subprocess
import sys
from pathlib import Path

import meshio
import numpy as np

ROOT = Path(__file__).resolve().parents[2]
SCRIPT = ROOT / "analysis" / "bound_floor.py"

# Face A slides +8 along x; B slides -7.5 along y and crosses A's path after A has left (at t = 1/2 A is at
# x 4..5, B at y 4.25..5.25): their swept boxes overlap, their second halves' too, no quarter's. C sits still on
# A's start: apart from t ~ 1/8 on, but touching A at t0, so no split removes it. D shares A's first vertex
# (which moves with A) and overlaps A's boxes: adjacent, never a candidate.
START = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0],              # A
                  [4, 8, 0], [5, 8, 0], [4, 9, 0],              # B
                  [0.5, 0.5, 0], [1.5, 0.5, 0], [0.5, 1.5, 0],  # C
                  [0.5, -1, 0], [0, -1, 0]], dtype=float)        # D (with A's vertex 0)
MOVE = np.zeros_like(START)
MOVE[0:3, 0] = 8
MOVE[3:6, 1] = -7.5
FACES = np.array([[0, 1, 2], [3, 4, 5], [6, 7, 8], [0, 9, 10]])


def write_step(tmp_path, end=None, faces=FACES):
    a, b = tmp_path / "a.ply", tmp_path / "b.ply"
    meshio.write(str(a), meshio.Mesh(START, [("triangle", FACES)]), binary=False)
    meshio.write(str(b), meshio.Mesh(START + MOVE if end is None else end, [("triangle", faces)]), binary=False)
    return a, b


def run(a, b, *extra):
    return subprocess.run([sys.executable, str(SCRIPT), str(a), str(b), *extra], capture_output=True, text=True)


def counts(stdout):
    return [int(line.split("|")[2].replace(",", "")) for line in stdout.splitlines() if line.startswith("| ")
            and not line.startswith("| bound")]


def test_splits_remove_the_crossing_pair_but_not_the_pair_overlapping_at_t0(tmp_path):
    done = run(*write_step(tmp_path), "--k", "6", "--pieces", "2,4,8")
    assert done.returncode == 0, done.stderr
    # whole step: A-B and A-C; halves: both; quarters and eighths: A-C only; floor: A-C.
    assert counts(done.stdout) == [2, 2, 1, 1, 1]


def test_more_axes_never_keep_more_pairs(tmp_path):
    a, b = write_step(tmp_path)
    by_k = {k: counts(run(a, b, "--k", str(k), "--pieces", "2,4").stdout) for k in (6, 14, 18, 26)}
    for low, high in ((6, 14), (6, 18), (18, 26)):
        assert all(h <= l for l, h in zip(by_k[low], by_k[high])), by_k
    assert all(row[-1] == 1 for row in by_k.values())  # A-C overlap at t0 on every axis


def test_frames_that_do_not_match_fail_naming_the_file(tmp_path):
    a, b = write_step(tmp_path, end=(START + MOVE)[:-1], faces=FACES[:3])
    done = run(a, b)
    assert done.returncode != 0
    assert str(b) in done.stderr and "vertices" in done.stderr


def test_bad_pieces_fail(tmp_path):
    done = run(*write_step(tmp_path), "--pieces", "2,x")
    assert done.returncode != 0 and "--pieces" in done.stderr


def test_pairs_within_one_piece_are_counted_apart(tmp_path):
    # A strip of three faces: f0 and f2 share no vertex but are joined through f1, and f2 lies over f0 (one
    # candidate, within one piece); f3, a separate piece, lies over f0 too (a candidate between pieces).
    points = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0],          # f0
                       [5, 5, 5],                                # f1 = (2, 3, 4)
                       [0.2, 0.2, 0], [0.8, 0.2, 0], [0.2, 0.8, 0],  # f2
                       [0.3, 0.3, 0], [0.9, 0.3, 0], [0.3, 0.9, 0]], dtype=float)  # f3
    faces = np.array([[0, 1, 2], [2, 3, 4], [4, 5, 6], [7, 8, 9]])
    a, b = tmp_path / "a.ply", tmp_path / "b.ply"
    for path in (a, b):
        meshio.write(str(path), meshio.Mesh(points, [("triangle", faces)]), binary=False)
    done = run(a, b, "--k", "6", "--pieces", "2")
    assert done.returncode == 0, done.stderr
    # f0-f2 (one piece), f0-f3, f2-f3 and f1-f3 (f1's box reaches down to f3's): 4 candidates, all overlapping
    # at rest, one of them within a piece.
    assert counts(done.stdout) == [4, 4, 4]
    assert "1 of the 4 swept candidates join two faces of one connected piece (2 pieces)" in done.stdout


def test_feature_pairs_equal_brute_force_on_boxes(tmp_path):
    # A 5 x 5 vertex grid, crumpled and moved at random: every vertex-face and edge-edge pair sharing no vertex,
    # tested box against box (K = 6), must give the script's counts.
    rng = np.random.default_rng(7)
    n = 5
    grid = np.array([[x, y, 0.0] for y in range(n) for x in range(n)]) + rng.normal(0, 0.3, (n * n, 3))
    faces = np.array([f for y in range(n - 1) for x in range(n - 1) for f in
                      ([y * n + x, y * n + x + 1, (y + 1) * n + x],
                       [y * n + x + 1, (y + 1) * n + x + 1, (y + 1) * n + x])])
    end = grid + rng.normal(0, 0.8, grid.shape)
    a, b = tmp_path / "a.ply", tmp_path / "b.ply"
    meshio.write(str(a), meshio.Mesh(grid, [("triangle", faces)]), binary=False)
    meshio.write(str(b), meshio.Mesh(end, [("triangle", faces)]), binary=False)
    # The PLY round trip keeps float64, so the brute force reads the same numbers.
    def box(ids):
        pts = np.concatenate([grid[ids], end[ids]])
        return pts.min(axis=0), pts.max(axis=0)

    def overlap(p, q):
        return bool(np.all(p[0] <= q[1]) and np.all(q[0] <= p[1]))

    edges = sorted({tuple(sorted((f[u], f[(u + 1) % 3]))) for f in faces for u in range(3)})
    vf = sum(overlap(box([v]), box(f)) for v in range(n * n) for f in faces if v not in f)
    ee = sum(overlap(box(list(e)), box(list(g))) for k, e in enumerate(edges) for g in edges[k + 1:]
             if not set(e) & set(g))
    assert vf > 0 and ee > 0
    done = run(a, b, "--k", "6", "--pieces", "2", "--features")
    assert done.returncode == 0, done.stderr
    assert f"{vf:,} vertex-face + {ee:,} edge-edge" in done.stdout, (vf, ee, done.stdout)
