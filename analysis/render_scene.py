#!/usr/bin/python3
"""Pictures of simulated frames (`ccdlab simulate` output), rendered off-screen with matplotlib.

usage: /usr/bin/python3 analysis/render_scene.py SCENE_DIR [--frames 0,20,40] [--out FILE.png] [--dpi 90]

Reads SCENE_DIR/meta.json (bodies, per-frame quality) and the frames' PLY files with meshio; draws the chosen
frames side by side, cloth in blue, obstacles in grey, each titled with its time, intersecting pairs and the
simulation time of the frame. Default: four frames spread over the sequence, into SCENE_DIR/frames.png.
"""
from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from mpl_toolkits.mplot3d.art3d import Poly3DCollection  # noqa: E402

try:
    import meshio  # noqa: E402
except ImportError:  # pragma: no cover
    meshio = None


def render(folder: Path, frames: list[int], out: Path, dpi: int) -> Path:
    meta = json.loads((folder / "meta.json").read_text())
    fig = plt.figure(figsize=(3.6 * len(frames), 3.8))
    records = {f["frame"]: f for f in meta["frames"]}
    first = meshio.read(folder / meta["frames"][0]["file"])
    lo, hi = first.points.min(axis=0), first.points.max(axis=0)
    for k, frame in enumerate(frames):
        rec = records[frame]
        mesh = meshio.read(folder / rec["file"])
        tris = mesh.cells_dict["triangle"]
        ax = fig.add_subplot(1, len(frames), k + 1, projection="3d")
        for body in meta["bodies"]:
            f0, f1 = body["faces"]
            colour = (0.25, 0.45, 0.8, 0.95) if body["kind"] == "cloth" else (0.6, 0.6, 0.6, 0.6)
            # y is up in scenes; matplotlib's z is up
            polys = mesh.points[tris[f0:f1]][:, :, [0, 2, 1]]
            shade = np.abs(np.cross(polys[:, 1] - polys[:, 0], polys[:, 2] - polys[:, 0])[:, 2])
            shade = shade / (np.linalg.norm(np.cross(polys[:, 1] - polys[:, 0], polys[:, 2] - polys[:, 0]), axis=1) + 1e-30)
            colours = np.tile(colour, (len(polys), 1))
            colours[:, :3] *= (0.55 + 0.45 * shade)[:, None]
            ax.add_collection3d(Poly3DCollection(polys, facecolors=colours, edgecolors="none"))
        centre, half = (lo + hi) / 2, (hi - lo).max() / 2
        ax.set_xlim(centre[0] - half, centre[0] + half)
        ax.set_ylim(centre[2] - half, centre[2] + half)
        ax.set_zlim(centre[1] - 1.3 * half, centre[1] + 0.7 * half)
        ax.set_box_aspect((1, 1, 1), zoom=1.25)
        ax.view_init(elev=22, azim=-55)
        ax.set_axis_off()
        ax.set_title(f"frame {frame}, t = {rec['time_s']:.2f} s\n{rec['intersecting_pairs']} crossing pairs, "
                     f"{rec['sim_ms']:.0f} ms", fontsize=8)
    # Above the frames' two-line titles (bbox_inches="tight" keeps it in the picture).
    fig.suptitle(f"{meta['scene']}: {meta['triangles']:,} triangles, rev {meta['git_revision']}", fontsize=10, y=1.06)
    fig.tight_layout()
    fig.savefig(out, dpi=dpi, bbox_inches="tight")
    plt.close(fig)
    return out


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("scene", help="folder written by `ccdlab simulate`")
    parser.add_argument("--frames", help="comma-separated frame numbers")
    parser.add_argument("--out", help="PNG file (default: SCENE/frames.png)")
    parser.add_argument("--dpi", type=int, default=90)
    args = parser.parse_args(argv)
    if meshio is None:
        print("render_scene: error: python3-meshio is not installed", file=sys.stderr)
        return 2
    folder = Path(args.scene)
    try:
        meta = json.loads((folder / "meta.json").read_text())
        n = len(meta["frames"])
        frames = [int(v) for v in args.frames.split(",")] if args.frames else sorted({0, n // 3, 2 * n // 3, n - 1})
        if any(f < 0 or f >= n for f in frames):
            raise ValueError(f"--frames: expected frames from 0 to {n - 1}, got {args.frames}")
    except (OSError, ValueError, KeyError) as e:
        print(f"render_scene: error: {e}", file=sys.stderr)
        return 2
    print(f"wrote {render(folder, frames, Path(args.out) if args.out else folder / 'frames.png', args.dpi)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
