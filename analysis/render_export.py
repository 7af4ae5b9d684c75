#!/usr/bin/python3
"""Pictures of a `ccdlab export` folder, rendered off-screen with matplotlib (no display, no VTK needed).

usage: /usr/bin/python3 analysis/render_export.py EXPORT_DIR [--out DIR] [--levels 1,3,5] [--dpi 90]

Reads the .vtu files with meshio and writes, into --out (default: EXPORT_DIR):
  mesh_contacts.png  the mesh at the detailed step's frame, triangles coloured by contacts touching them
  bvh_levels.png     the BVH at a few depths, each node's k-DOP drawn as its polyhedron
  front.png          the BVTT front after the step: one line per node pair, coloured kept / sprouted / pruned
  contacts.png       the contact points coloured by time of contact, over the colliding features
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
from mpl_toolkits.mplot3d.art3d import Line3DCollection, Poly3DCollection  # noqa: E402

try:
    import meshio  # noqa: E402
except ImportError:  # pragma: no cover
    meshio = None

CHANGE_COLOURS = ["#9e9e9e", "#1f77b4", "#d62728"]  # kept, sprouted, pruned
CHANGE_NAMES = ["kept", "sprouted", "pruned"]


def cells_of(mesh, types):
    """(cell point lists, per-cell values of every array) for the cells of the given types, in file order."""
    polys, values = [], {name: [] for name in mesh.cell_data}
    for b, block in enumerate(mesh.cells):
        if block.type.split("(")[0] not in types:
            continue
        polys.extend([list(c) for c in block.data])
        for name in mesh.cell_data:
            values[name].extend(np.asarray(mesh.cell_data[name][b]).tolist())
    return polys, {k: np.asarray(v) for k, v in values.items()}


def frame_axes(ax, points, title):
    lo, hi = points.min(axis=0), points.max(axis=0)
    centre, half = (lo + hi) / 2, (hi - lo).max() / 2 * 1.05
    ax.set_xlim(centre[0] - half, centre[0] + half)
    ax.set_ylim(centre[1] - half, centre[1] + half)
    ax.set_zlim(centre[2] - half, centre[2] + half)
    ax.set_box_aspect((1, 1, 1), zoom=1.35)
    ax.view_init(elev=28, azim=-60)
    ax.set_axis_off()
    ax.set_title(title, fontsize=9)


def render_mesh(export: Path, index: dict, out: Path, dpi: int) -> Path:
    mesh = meshio.read(export / f"mesh/frame_{index['step']:04d}.vtu")
    tris, values = cells_of(mesh, {"triangle"})
    counts = values["contacts"]
    fig = plt.figure(figsize=(5.5, 4.5))
    ax = fig.add_subplot(projection="3d")
    norm = matplotlib.colors.Normalize(0, max(1, counts.max()))
    colours = plt.cm.magma_r(norm(counts)) * 0.85 + 0.15
    colours[counts == 0] = (0.85, 0.87, 0.9, 1)
    ax.add_collection3d(Poly3DCollection(mesh.points[np.array(tris)], facecolors=colours, edgecolors=(0, 0, 0, 0.15),
                                         linewidths=0.2))
    frame_axes(ax, mesh.points, f"frame {index['step']}: contacts of step {index['step']} per triangle")
    fig.colorbar(plt.cm.ScalarMappable(norm=norm, cmap="magma_r"), ax=ax, shrink=0.6, label="contacts touching")
    return save(fig, out / "mesh_contacts.png", dpi)


def render_bvh(export: Path, index: dict, out: Path, dpi: int, levels: list[int]) -> Path:
    fig = plt.figure(figsize=(3.2 * len(levels), 3.4))
    cloth = meshio.read(export / f"mesh/frame_{index['step']:04d}.vtu")
    k = index["config"]["bv"]["k"]
    for i, depth in enumerate(levels):
        path = export / "bvh" / f"body0_depth{depth:02d}.vtu"
        ax = fig.add_subplot(1, len(levels), i + 1, projection="3d")
        if not path.exists():
            ax.set_axis_off()
            ax.set_title(f"depth {depth}: none", fontsize=9)
            continue
        hull = meshio.read(path)
        polys, values = cells_of(hull, {"polygon", "triangle"})
        nodes = values["node"]
        palette = plt.cm.tab20(np.unique(nodes, return_inverse=True)[1] % 20)
        palette[:, 3] = 0.35
        ax.add_collection3d(Poly3DCollection([hull.points[p] for p in polys], facecolors=palette,
                                             edgecolors=(0, 0, 0, 0.5), linewidths=0.3))
        frame_axes(ax, cloth.points, f"depth {depth}: {len(np.unique(nodes))} {k}-DOPs")
    fig.suptitle(f"BVH of the cloth (body 0), volumes swept over step {index['step']}", fontsize=10)
    return save(fig, out / "bvh_levels.png", dpi)


def render_front(export: Path, index: dict, out: Path, dpi: int) -> Path:
    fig = plt.figure(figsize=(5.5, 4.5))
    ax = fig.add_subplot(projection="3d")
    cloth = meshio.read(export / f"mesh/frame_{index['step']:04d}.vtu")
    tris, _ = cells_of(cloth, {"triangle"})
    ax.add_collection3d(Poly3DCollection(cloth.points[np.array(tris)], facecolors=(0.9, 0.9, 0.92, 0.25),
                                         edgecolors="none"))
    for name in index["files"][2]["file"]:
        front = meshio.read(export / name)
        lines, values = cells_of(front, {"line"})
        for change in (0, 1, 2):  # kept first, so the changes draw on top
            chosen = [front.points[l] for l, c in zip(lines, values["change"]) if int(c) == change]
            if chosen:
                ax.add_collection3d(Line3DCollection(chosen, colors=CHANGE_COLOURS[change],
                                                     linewidths=0.3 if change == 0 else 0.6,
                                                     alpha=0.35 if change == 0 else 0.9))
    f = index["front"]
    for change, name in enumerate(CHANGE_NAMES):
        ax.plot([], [], color=CHANGE_COLOURS[change], label=f"{name} ({f[name]})")
    ax.legend(loc="upper left", fontsize=7, frameon=False)
    frame_axes(ax, cloth.points, f"BVTT front after step {index['step']}: node pairs (centre to centre)")
    return save(fig, out / "front.png", dpi)


def render_contacts(export: Path, index: dict, out: Path, dpi: int) -> Path:
    contacts = meshio.read(export / "contacts.vtu")
    fig = plt.figure(figsize=(5.5, 4.5))
    ax = fig.add_subplot(projection="3d")
    tris, tv = cells_of(contacts, {"triangle"})
    if tris:
        ax.add_collection3d(Poly3DCollection(contacts.points[np.array(tris)], facecolors=(0.6, 0.7, 0.85, 0.25),
                                             edgecolors=(0.3, 0.3, 0.4, 0.3), linewidths=0.2))
    lines, _ = cells_of(contacts, {"line"})
    if lines:
        ax.add_collection3d(Line3DCollection([contacts.points[l] for l in lines], colors=(0.4, 0.4, 0.4, 0.5),
                                             linewidths=0.4))
    points, pv = cells_of(contacts, {"vertex"})
    xyz = contacts.points[[p[0] for p in points]]
    sc = ax.scatter(xyz[:, 0], xyz[:, 1], xyz[:, 2], c=pv["toi"], cmap="viridis", vmin=0, vmax=1, s=6,
                    marker=None, depthshade=False)
    sc.set_paths([matplotlib.markers.MarkerStyle("o").get_path()])
    kinds = pv["kind"].astype(int)
    fig.colorbar(sc, ax=ax, shrink=0.6, label="time of contact")
    frame_axes(ax, contacts.points, f"step {index['step']}: {int((kinds == 0).sum())} VF + {int((kinds == 1).sum())} "
               "EE contacts at their time of contact")
    return save(fig, out / "contacts.png", dpi)


def save(fig, path: Path, dpi: int) -> Path:
    fig.tight_layout()
    fig.savefig(path, dpi=dpi, bbox_inches="tight")
    plt.close(fig)
    return path


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("export", help="folder written by `ccdlab export`")
    parser.add_argument("--out", help="folder for the PNGs (default: the export folder)")
    parser.add_argument("--levels", default="1,3,5", help="BVH depths to draw side by side")
    parser.add_argument("--dpi", type=int, default=90)
    args = parser.parse_args(argv)
    if meshio is None:
        print("render_export: error: python3-meshio is not installed", file=sys.stderr)
        return 2
    export = Path(args.export)
    try:
        index = json.loads((export / "export.json").read_text())
        levels = [int(v) for v in args.levels.split(",")]
    except (OSError, ValueError) as e:
        print(f"render_export: error: {e}", file=sys.stderr)
        return 2
    out = Path(args.out) if args.out else export
    out.mkdir(parents=True, exist_ok=True)
    for path in (render_mesh(export, index, out, args.dpi), render_bvh(export, index, out, args.dpi, levels),
                 render_front(export, index, out, args.dpi), render_contacts(export, index, out, args.dpi)):
        print(f"wrote {path}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
