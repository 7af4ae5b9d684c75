#!/usr/bin/python3
"""Density of steady steps: what kind of step each config replays, from the counts of its first step with every
culling pass forced on (so that each stage's removal shows; counts are the same for every scheduler).

    /usr/bin/python3 analysis/density_table.py [--cli build/bin/ccdlab] CONFIG.yaml [CONFIG.yaml ...]

Prints one Markdown row per config: triangles, contacts per triangle, candidate pairs per triangle, the share of
elementary tests that are hits, and what stages 0, 3 (halves and sixteenths) and 4 removed of what they received.
"""
import argparse
import os
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from ccdlab_results import run_records  # noqa: E402

FORCED = ["narrow.rules.triangles=on", "narrow.rules.sixteenths=on", "narrow.rules.proximity=on"]


def first_step(cli, config):
    records = run_records(cli, config, FORCED, "density_table")
    config = next(r for r in records if r.get("type") == "config")
    step = next(r for r in records if r.get("type") == "step")
    return config, step


def share(removed, received):
    return f"{100 * removed / received:.0f}% of {received:,}" if received else "—"


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--cli", default="build/bin/ccdlab")
    ap.add_argument("configs", nargs="+")
    a = ap.parse_args()
    print("| step | triangles | contacts per triangle | candidates per triangle | tests that hit | stage 0 removes | "
          "stage 3 removes | of which sixteenths | stage 4 removes |")
    print("|---|---|---|---|---|---|---|---|---|")
    for path in a.configs:
        config, step = first_step(a.cli, path)
        c, n = step["counters"], step["narrow_stages"]
        triangles = config.get("scene_info", {}).get("triangles") or config.get("triangles") or 0
        contacts = step["contacts"]["vf"] + step["contacts"]["ee"]
        tests = c["vf_tests"] + c["ee_tests"]
        pairs = c["vf_pairs"] + c["ee_pairs"]
        split_in = pairs - n["kdop_culled"] - n["plane_culled"] if pairs else 0
        name = os.path.splitext(os.path.basename(path))[0]
        per = (lambda x: f"{x / triangles:.2f}") if triangles else (lambda x: "?")
        print(f"| `steady/{name}` | {triangles:,} | {per(contacts)} | {per(c['candidate_pairs'])} | "
              f"{share(contacts, tests)} | {share(n['triangle_culled'], n['triangle_tested'])} | "
              f"{share(n['split_culled'], split_in)} | {share(n['sixteenths_culled'], n['sixteenths_tested'])} | "
              f"{share(n['proximity_culled'], n['proximity_tested'])} |")


if __name__ == "__main__":
    main()
