#!/usr/bin/python3
"""Markdown table of `ccdlab run --json` summaries: median over rounds of ms/step and per phase, per scene and K.

usage: /usr/bin/python3 analysis/baseline_table.py FOLDER   (FOLDER holds SCENE_kK_rR.json files)
"""
from __future__ import annotations

import json
import re
import statistics
import sys
from collections import defaultdict
from pathlib import Path

PHASES = ["build_once", "swept_bv", "refit", "traverse", "narrow", "orphans"]


def main(argv=None) -> int:
    argv = sys.argv[1:] if argv is None else argv
    if len(argv) != 1:
        print(__doc__, file=sys.stderr)
        return 2
    folder = Path(argv[0])
    runs = defaultdict(list)
    for path in sorted(folder.glob("*_k*_r*.json")):
        m = re.match(r"(.+)_k(\d+)_r(\d+)\.json$", path.name)
        try:
            runs[(m.group(1), int(m.group(2)))].append(json.loads(path.read_text()))
        except json.JSONDecodeError as e:
            print(f"baseline_table: error: {path}: invalid JSON: {e.msg}", file=sys.stderr)
            return 2
    if not runs:
        print(f"baseline_table: error: {folder}: no SCENE_kK_rR.json files", file=sys.stderr)
        return 2
    print("| scene | triangles | k | ms/step | " + " | ".join(PHASES) + " | BV tests/step | candidates/step "
          "| VF+EE tests/step | contacts VF / EE (all steps) | hash |")
    print("|---|---|---|---|" + "---|" * len(PHASES) + "---|---|---|---|---|")
    for (scene, k), summaries in sorted(runs.items()):
        s0 = summaries[0]
        steps = s0["steps"]
        med = statistics.median(s["ms_per_step"] for s in summaries)
        phases = [statistics.median(s["ms_per_phase"][p] for s in summaries) for p in PHASES]
        c = s0["counters"]
        hashes = {s["hash"] for s in summaries}
        print(f"| {scene} | {s0['triangles']} | {k} | {med:.2f} | " + " | ".join(f"{p:.2f}" for p in phases)
              + f" | {c['bv_tests'] / steps:,.0f} | {c['candidate_pairs'] / steps:,.0f} | "
              f"{(c['vf_tests'] + c['ee_tests']) / steps:,.0f} | {s0['contacts']['vf']} / {s0['contacts']['ee']} | "
              f"{'/'.join(sorted(hashes))} |")
    print("\nms/step is the median step (with one step, it includes the one-time BVH build, `build_once`).")
    print(f"median over {len(next(iter(runs.values())))} alternating rounds; phases are medians over steps.")
    return 0


if __name__ == "__main__":
    sys.exit(main())
