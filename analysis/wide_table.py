#!/usr/bin/python3
"""Binary BVH against its 4-wide view (bv.width 2 vs 4) on the real steps, in alternating rounds.

    /usr/bin/python3 analysis/wide_table.py [--cli build/bin/ccdlab] [--rounds 3] [--data ../shared/data]
        [--runs "sequential:1,phc:2"] [--out docs/data/wide-bvh.csv] > table.md

Each real step of ../shared/data/meshes (those present) is run as a sequence A B A B A B (`ccdlab run`, frames
from files), so steps 1–4 refit a tree built at step 0: the steady state of a simulation, where the wide view
costs one more refit per step and no build. Widths alternate (2 4, 4 2, ...). Per step, scheduler and
threads: medians over rounds of the medians of steps 1–4 — BV tests, ms of traversal and refit, ns per BV
test, ms per step. Both widths must report the same candidates and contact hashes (exit 1 otherwise).
"""
import argparse
import csv
import os
import statistics
import subprocess
import sys
import tempfile

STEPS = [("cloth-funnel", "227.ply", "228.ply"),
         ("rod-twist", "3036.ply", "3037.ply"),
         ("n-body-simulation", "balls16_18.ply", "balls16_19.ply")]


def run(cli, yaml_path, out_dir, width, scheduler, threads):
    args = [cli, "run", yaml_path, "--no-progress", "--set", f"output.dir={out_dir}", "--set", f"bv.width={width}",
            "--set", f"scheduler={scheduler}", "--set", f"threads={threads}"]
    done = subprocess.run(args, capture_output=True, text=True)
    if done.returncode != 0:
        sys.exit(f"wide_table: {' '.join(args)} failed: {done.stderr.strip()[-300:]}")
    with open(os.path.join(out_dir, "steps.csv")) as f:
        rows = list(csv.DictReader(f))
    steady = rows[1:]
    med = lambda key: statistics.median(float(r[key]) for r in steady)
    return {"bv_tests": int(steady[0]["bv_tests"]), "candidates": [r["candidate_pairs"] for r in rows],
            "hashes": [r["hash"] for r in rows], "traverse_ms": med("traverse_ms"), "refit_ms": med("refit_ms"),
            "total_ms": med("total_ms"), "revision": rows[0]["git_revision"]}


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--cli", default="build/bin/ccdlab")
    ap.add_argument("--rounds", type=int, default=3)
    ap.add_argument("--data", default=os.path.join(os.path.dirname(__file__), "..", "..", "shared", "data"))
    ap.add_argument("--runs", default="sequential:1,phc:2", help="scheduler:threads pairs")
    ap.add_argument("--out", help="also write the rows as CSV here")
    a = ap.parse_args()
    runs = [tuple(x.split(":")) for x in a.runs.split(",")]
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for scene, f0, f1 in STEPS:
            d = os.path.abspath(os.path.join(a.data, "meshes", scene))
            if not os.path.exists(os.path.join(d, f0)):
                print(f"wide_table: {scene} absent, skipped", file=sys.stderr)
                continue
            yaml_path = os.path.join(tmp, scene + ".yaml")
            frames = ", ".join(os.path.join(d, f) for f in [f0, f1] * 3)
            with open(yaml_path, "w") as f:
                f.write(f"name: {scene}\nscene:\n  frames: [{frames}]\n")
            for scheduler, threads in runs:
                got = {2: [], 4: []}
                for r in range(a.rounds):
                    for w in ((2, 4) if r % 2 == 0 else (4, 2)):
                        got[w].append(run(a.cli, yaml_path, os.path.join(tmp, "out"), w, scheduler, threads))
                ref = got[2][0]
                for w in (2, 4):
                    for g in got[w]:
                        if g["hashes"] != ref["hashes"] or g["candidates"] != ref["candidates"]:
                            sys.exit(f"wide_table: {scene} {scheduler} x{threads}: width {w} differs from width 2")
                for w in (2, 4):
                    med = lambda k: statistics.median(g[k] for g in got[w])
                    rows.append({"step": scene, "scheduler": scheduler, "threads": threads, "width": w,
                                 "bv_tests": got[w][0]["bv_tests"], "traverse_ms": round(med("traverse_ms"), 1),
                                 "ns_per_bv_test": round(med("traverse_ms") * 1e6 / got[w][0]["bv_tests"], 1),
                                 "refit_ms": round(med("refit_ms"), 1), "total_ms": round(med("total_ms"), 1),
                                 "revision": ref["revision"], "rounds": a.rounds})
    if a.out and rows:
        with open(a.out, "w", newline="") as f:
            w = csv.DictWriter(f, fieldnames=list(rows[0]))
            w.writeheader()
            w.writerows(rows)
    print("| step | scheduler × threads | width | BV tests | traverse ms | ns / BV test | refit ms | ms / step |")
    print("|---|---|---|---|---|---|---|---|")
    for r in rows:
        print(f"| {r['step']} | {r['scheduler']} × {r['threads']} | {r['width']} | {r['bv_tests']:,} | "
              f"{r['traverse_ms']} | {r['ns_per_bv_test']} | {r['refit_ms']} | {r['total_ms']} |")
    if rows:
        print(f"\nrevision {rows[0]['revision']}, medians of {a.rounds} alternating rounds × steps 1–4 (steady state)")


if __name__ == "__main__":
    main()
