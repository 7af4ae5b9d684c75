#!/usr/bin/python3
"""One step of an exported scene as mesh files, replayed: a steady config any ccdlab revision can read.

usage: /usr/bin/python3 analysis/replay_files.py EXPORT_DIR STEP OUT_DIR [--frames 11] [--k 18]

EXPORT_DIR is what `ccdlab export CONFIG --out EXPORT_DIR` writes (mesh/frame_NNNN.vtu, one cell array `body`).
Writes each body of frames STEP and STEP + 1 as binary PLY (float64 positions, so that the steps read the exact
positions of the export) and OUT_DIR/replay.yaml: a `scene: {bodies: …}` config whose frames run STEP, STEP + 1,
STEP, … (--frames of them), body 0 a self-colliding cloth and the others kinematic obstacles — the same step as
`replay: {step: STEP}` on the scene itself, for revisions older than the `replay` key (docs/narrow-phase.md,
"Contact-dense steps").
"""
from __future__ import annotations

import argparse
from pathlib import Path

import meshio
import numpy as np


def body_meshes(vtu: Path) -> list[tuple[np.ndarray, np.ndarray]]:
    """(points, triangles) of each body of an exported frame; each body's vertices are one contiguous range."""
    m = meshio.read(vtu)
    body = np.asarray(m.cell_data["body"][0])
    triangles = m.cells[0].data
    out = []
    for b in sorted(set(body.tolist())):
        t = triangles[body == b]
        lo, hi = int(t.min()), int(t.max())
        if len(np.unique(t)) != hi - lo + 1:
            raise SystemExit(f"replay_files: body {b} of {vtu}: its vertices are not one contiguous range")
        out.append((m.points[lo:hi + 1], (t - lo).astype(np.int32)))
    return out


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("export_dir", type=Path)
    ap.add_argument("step", type=int)
    ap.add_argument("out_dir", type=Path)
    ap.add_argument("--frames", type=int, default=11)
    ap.add_argument("--k", type=int, default=18)
    o = ap.parse_args()
    if o.frames < 2:
        ap.error("--frames: at least 2")
    o.out_dir.mkdir(parents=True, exist_ok=True)
    names: list[list[str]] = []
    for frame in (o.step, o.step + 1):
        vtu = o.export_dir / "mesh" / f"frame_{frame:04d}.vtu"
        if not vtu.exists():
            raise SystemExit(f"replay_files: {vtu}: no such frame (the export's steps are its frames - 1)")
        for b, (points, triangles) in enumerate(body_meshes(vtu)):
            path = o.out_dir / f"body{b}_{frame}.ply"
            meshio.write(path, meshio.Mesh(points.astype(np.float64), [("triangle", triangles)]), binary=True)
            if len(names) <= b:
                names.append([])
            names[b].append(str(path.resolve()))
    lines = [f"name: replay_{o.step}", "scene:", "  bodies:"]
    for b, (a, c) in enumerate(names):
        frames = ", ".join(a if i % 2 == 0 else c for i in range(o.frames))
        kinematic = ", kinematic: true" if b else ""
        lines.append(f"    - {{name: body{b}, frames: [{frames}]{kinematic}}}")
    lines += [f"bv: {{k: {o.k}}}", "tester: float", ""]
    (o.out_dir / "replay.yaml").write_text("\n".join(lines))
    print(o.out_dir / "replay.yaml")


if __name__ == "__main__":
    main()
