#!/usr/bin/python3
"""Markdown tables of simulated scenes (`ccdlab simulate` folders): time per frame and per effect, quality.

usage: /usr/bin/python3 analysis/sim_table.py SCENE_DIR [SCENE_DIR …] [--skip N]

Per scene: triangles, frames, median simulation ms per frame (frames after the first N, default 1), the median
ms per frame of every effect, what each effect did per frame, the largest number of crossing triangle pairs and
of pairs closer than the thickness in any frame, and the revision that simulated it.
"""
from __future__ import annotations

import argparse
import json
import statistics
import sys
from pathlib import Path


def summary(folder: Path, skip: int) -> dict:
    meta = json.loads((folder / "meta.json").read_text())
    frames = meta["frames"][skip:] or meta["frames"]
    per_effect = {}
    for key in meta["effects_total"]:
        label = key.split(":", 1)[1]
        ms = statistics.median(f["effects"][key]["ms"] for f in frames)
        work = statistics.median(f["effects"][key]["work"] for f in frames)
        what = frames[0]["effects"][key]["work_is"]
        per_effect.setdefault(label, []).append((ms, work, what))
    return {"scene": meta["scene"], "triangles": meta["triangles"], "frames": len(meta["frames"]),
            "sim_ms": statistics.median(f["sim_ms"] for f in frames), "effects": per_effect,
            "crossing_max": max(f["intersecting_pairs"] for f in meta["frames"]),
            # with an obstacle's triangle (meta.json of older revisions does not split them: "?")
            "obstacle_crossing_max": max((f.get("intersecting_obstacle_pairs", "?") for f in meta["frames"]),
                                         key=lambda v: -1 if v == "?" else v),
            "crossing_frames": sum(1 for f in meta["frames"] if f["intersecting_pairs"] > 0),
            "close_max": max(f["close_pairs"] for f in meta["frames"]), "revision": meta["git_revision"],
            "stats": {k.split(":", 1)[1]: v["stats"] for k, v in meta["effects_total"].items() if v.get("stats")}}


def markdown(rows: list[dict], skip: int) -> str:
    lines = [f"| scene | triangles | frames | sim ms / frame (median, frames {skip}+) | crossing pairs (max) | "
             "of them with obstacles (max) | frames with crossings | close pairs (max) | revision |",
             "|---|---:|---:|---:|---:|---:|---:|---:|---|"]
    for r in rows:
        lines.append(f"| {r['scene']} | {r['triangles']:,} | {r['frames']} | {r['sim_ms']:,.0f} | {r['crossing_max']} | "
                     f"{r['obstacle_crossing_max']} | {r['crossing_frames']} | {r['close_max']:,} | {r['revision']} |")
    lines += ["", "Per effect, median ms per frame (and what it did per frame):", "",
              "| scene | " + " | ".join(["effect", "ms / frame", "work / frame"]) + " |", "|---|---|---:|---|"]
    for r in rows:
        for label, entries in r["effects"].items():
            for ms, work, what in entries:
                lines.append(f"| {r['scene']} | {label} | {ms:,.1f} | {work:,.0f} {what} |")
    stats = [(r["scene"], label, st) for r in rows for label, st in r["stats"].items()]
    if stats:
        lines += ["", "Effect totals over the run:", "", "| scene | effect | totals |", "|---|---|---|"]
        lines += [f"| {scene} | {label} | " + ", ".join(f"{k} {v:,}" for k, v in st.items()) + " |"
                  for scene, label, st in stats]
    return "\n".join(lines) + "\n"


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("scenes", nargs="+")
    parser.add_argument("--skip", type=int, default=1, help="frames left out of the medians (the first is frame 0)")
    args = parser.parse_args(argv)
    try:
        rows = [summary(Path(f), args.skip) for f in args.scenes]
    except (OSError, KeyError, ValueError) as e:
        print(f"sim_table: error: {e}", file=sys.stderr)
        return 2
    print(markdown(rows, args.skip), end="")
    return 0


if __name__ == "__main__":
    sys.exit(main())
