#!/usr/bin/python3
"""What a BV test costs as the hierarchy outgrows the caches: the traversal's bound from below.

    /usr/bin/python3 analysis/traversal_bound.py [--cli build/bin/ccdlab] [--config experiments/configs/steady/drape_fold_92k.yaml]
        [--resolutions 16,24,34,48,68,104,150,214] [--rounds 3] [--threads 1]

Runs one steady config (a replayed step, experiments/configs/steady/) at several cloth resolutions, `sequential`,
and prints per resolution the triangles, the BV tests and candidates per step, the wide view's size (352-byte
records at K = 18, one per four nodes) and the traversal's ns per BV test (median over steps 2..N and rounds).
The walk is the same code at every size and the same kind of step (the same fold, finer), so what changes is where
its records live: a hierarchy of a few hundred KiB stays in L2, and its ns per BV test is what the walk's
instructions cost with every record at hand — the bound the larger steps are measured against (docs/wide-bvh.md,
"What a BV test costs"). The rest, per test, is waiting for records.
"""
import argparse
import os
import statistics
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from ccdlab_results import run_records  # noqa: E402

RECORD_BYTES = 352  # WideLayout's record at K = 18 (docs/appendix-wide-bvh.md)


def run(cli, config, resolution, threads):
    records = run_records(cli, config, [f"scene.resolution={resolution}", f"threads={threads}",
                                        "scheduler.name=sequential"], "traversal_bound")
    summary = next(r for r in records if r.get("type") == "summary")
    return [r for r in records if r.get("type") == "step"][2:], summary["triangles"]


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--cli", default="build/bin/ccdlab")
    ap.add_argument("--config", default="experiments/configs/steady/drape_fold_92k.yaml")
    ap.add_argument("--resolutions", default="16,24,34,48,68,104,150,214")
    ap.add_argument("--rounds", type=int, default=3)
    ap.add_argument("--threads", type=int, default=1)
    a = ap.parse_args()
    resolutions = [int(r) for r in a.resolutions.split(",")]
    ns = {r: [] for r in resolutions}
    counts, triangles = {}, {}
    for _ in range(a.rounds):
        for r in resolutions:
            steps, triangles[r] = run(a.cli, a.config, r, a.threads)
            ns[r] += [s["ms"]["traverse"] * 1e6 / s["counters"]["bv_tests"] for s in steps if s["counters"]["bv_tests"]]
            counts[r] = steps[-1]["counters"]
    print(f"`{a.cli}`, {os.path.basename(a.config)} at each resolution, `sequential`, {a.threads} thread(s), "
          f"{a.rounds} rounds, medians of steps 2..N\n")
    print("| cloth resolution | triangles | BV tests per step | candidates | wide view (KiB) | ns per BV test |")
    print("|---|---|---|---|---|---|")
    for r in resolutions:
        c = counts[r]
        kib = triangles[r] * 2 / 4 * RECORD_BYTES / 1024  # ~2·n nodes in a binary hierarchy, four per record
        print(f"| {r} | {triangles[r]:,} | {c['bv_tests']:,} | {c['candidate_pairs']:,} | {kib:,.0f} | "
              f"{statistics.median(ns[r]):.2f} |")


if __name__ == "__main__":
    main()
