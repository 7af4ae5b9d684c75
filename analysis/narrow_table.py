#!/usr/bin/python3
"""Per-phase table of real steps: two ccdlab builds (or two narrow modes of one) in alternating rounds.

    /usr/bin/python3 analysis/narrow_table.py --a BASE_CLI --b build/bin/ccdlab [--rounds 3] [--threads 1]
        [--a-args "..."] [--b-args "..."] [--data ../shared/data] > table.md

Runs `CLI step T0 T1 --json ARGS` for every real step of ../shared/data/meshes (those present), A and B
alternating (A B, B A, ...), and prints one Markdown row per step and side with the medians: BV tests,
elementary tests, tests per true contact, ms per phase, and ns per feature pair in the narrow phase
(candidates' pairs and orphans together). Both sides must report the same contact hash (exit 1 otherwise).

`--c CLI --c-args "..."` adds a third side, alternating with the other two in every round (A B C, C B A, ...),
e.g. the revision before a change beside the change and the baseline. The A/B and A/C rows give the total's
ratio as the median of the per-round ratios (each round's runs are close in time: this VM's speed drifts
between rounds), the narrow phase's as the ratio of the medians.

`--steady N` times the steady state instead, as in a simulation's later steps: each run is one process,
`CLI run` of frames T0 T1 T0 T1 ... (N steps, every other one backwards: the same pairs and contacts), and
its value is the median over steps 2..N (the first builds the hierarchy and touches the memory). The side
arguments are then options of `run`, e.g. "--set scheduler=phc --set tester=filtered".
"""
import argparse
import csv
import json
import os
import re
import shlex
import statistics
import subprocess
import sys
import tempfile

STEPS = [("cloth-funnel", "227.ply", "228.ply"),
         ("rod-twist", "3036.ply", "3037.ply"),
         ("n-body-simulation", "balls16_18.ply", "balls16_19.ply")]


def run(cli, t0, t1, args):
    out = subprocess.run([cli, "step", t0, t1, "--json"] + args, capture_output=True, text=True)
    if out.returncode != 0:
        sys.exit(f"narrow_table: {cli} step {t0} failed: {out.stderr.strip()[-300:]}")
    return json.loads(out.stdout)


def run_steady(cli, t0, t1, args, steps, threads):
    """One `CLI run` of `steps` steps between t0 and t1 and back; the step record as `step --json` has it."""
    with tempfile.TemporaryDirectory() as tmp:
        frames = "\n".join(f"    - {os.path.abspath(t1 if i % 2 else t0)}" for i in range(steps + 1))
        config = os.path.join(tmp, "steady.yaml")
        with open(config, "w") as f:
            f.write(f"name: steady\nscene:\n  frames:\n{frames}\nthreads: {threads}\noutput:\n  dir: {tmp}/out\n")
        out = subprocess.run([cli, "run", config, "--no-progress"] + args, capture_output=True, text=True)
        if out.returncode != 0:
            sys.exit(f"narrow_table: {cli} run failed: {out.stderr.strip()[-300:]}")
        with open(os.path.join(tmp, "out", "steps.csv")) as f:
            rows = list(csv.DictReader(f))
    later = rows[1:] or rows
    triangles = re.search(r"\((\d+) triangles", out.stdout)
    med = lambda key: statistics.median(float(r[key]) for r in later)
    first = rows[0]
    count = lambda key: int(first[key])
    return {"triangles": int(triangles.group(1)) if triangles else 0,
            "counters": {k: count(k) for k in ("bv_tests", "vf_pairs", "ee_pairs", "vf_tests", "ee_tests")},
            "contacts": {"vf": count("contacts_vf"), "ee": count("contacts_ee")}, "hash": first["hash"],
            "ms": {"narrow": med("narrow_ms"), "orphans": med("orphan_ms"), "total": med("total_ms"),
                   "traverse": med("traverse_ms")}}


def summary(runs):
    med = lambda f: statistics.median(f(r) for r in runs)
    r0 = runs[0]
    c = r0["counters"]
    contacts = r0["contacts"]["vf"] + r0["contacts"]["ee"]
    tests = c["vf_tests"] + c["ee_tests"]
    pairs = c["vf_pairs"] + c["ee_pairs"]
    narrow = med(lambda r: r["ms"]["narrow"] + r["ms"]["orphans"])
    return {
        "bv_tests": c["bv_tests"], "pairs": pairs, "tests": tests, "contacts": contacts,
        "total": med(lambda r: r["ms"]["total"]), "traverse": med(lambda r: r["ms"]["traverse"]),
        "narrow": narrow, "ns_per_pair": 1e6 * narrow / max(pairs, 1),
        "ns_per_test": 1e6 * narrow / max(tests, 1), "hash": r0["hash"],
    }


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--a", required=True, help="CLI of side A")
    ap.add_argument("--b", default="build/bin/ccdlab", help="CLI of side B")
    ap.add_argument("--c", default=None, help="CLI of an optional side C")
    ap.add_argument("--a-args", default="", help="extra step arguments of side A")
    ap.add_argument("--b-args", default="", help="extra step arguments of side B")
    ap.add_argument("--c-args", default="", help="extra step arguments of side C")
    ap.add_argument("--threads", type=int, default=1)
    ap.add_argument("--rounds", type=int, default=3)
    ap.add_argument("--steady", type=int, default=0, metavar="N",
                    help="time N steps in one process each run (medians of steps 2..N) instead of one-step runs")
    ap.add_argument("--data", default=os.path.join(os.path.dirname(__file__), "..", "..", "shared", "data"))
    o = ap.parse_args()
    sides = {"A": (o.a, shlex.split(o.a_args)), "B": (o.b, shlex.split(o.b_args))}
    if o.c:
        sides["C"] = (o.c, shlex.split(o.c_args))
    names = list(sides)
    mode = f"steady state: {o.steady} steps a run, medians of steps 2..{o.steady}; " if o.steady else ""
    described = ", ".join(f"{n} = `{cli} {' '.join(args)}`" for n, (cli, args) in sides.items())
    print(f"threads {o.threads}, {mode}{o.rounds} alternating rounds, medians. {described}\n")
    print("| step | side | triangles | BV tests | feature pairs | elementary tests | tests / true contact | "
          "ms total | ms traverse | ms narrow + orphans | ns / feature pair | ns / test |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|")
    status = 0
    for scene, f0, f1 in STEPS:
        t0 = os.path.join(o.data, "meshes", scene, f0)
        t1 = os.path.join(o.data, "meshes", scene, f1)
        if not os.path.exists(t0):
            print(f"narrow_table: {t0} absent, skipped", file=sys.stderr)
            continue
        runs = {n: [] for n in names}
        for i in range(o.rounds):
            for side in (names if i % 2 == 0 else names[::-1]):
                cli, args = sides[side]
                if o.steady:
                    runs[side].append(run_steady(cli, t0, t1, args, o.steady, o.threads))
                else:
                    runs[side].append(run(cli, t0, t1, args + ["--threads", str(o.threads)]))
        rows = {side: summary(r) for side, r in runs.items()}
        hashes = {side: row["hash"] for side, row in rows.items()}
        if len(set(hashes.values())) > 1:
            print(f"narrow_table: {scene}: contact hashes differ: {hashes}", file=sys.stderr)
            status = 1
        tri = runs["A"][0].get("triangles", "")
        for side in names:
            s = rows[side]
            print(f"| {scene} | {side} | {tri:,} | {s['bv_tests'] / 1e6:.2f}M | {s['pairs'] / 1e6:.2f}M | "
                  f"{s['tests'] / 1e6:.3f}M | {s['tests'] / max(s['contacts'], 1):.1f} | {s['total']:.0f} | "
                  f"{s['traverse']:.0f} | {s['narrow']:.0f} | {s['ns_per_pair']:.0f} | {s['ns_per_test']:.0f} |")
        for other in names[1:]:
            per_round = statistics.median(a["ms"]["total"] / x["ms"]["total"] for a, x in zip(runs["A"], runs[other]))
            print(f"| {scene} | A/{other} | | | | | | {per_round:.2f}× | | "
                  f"{rows['A']['narrow'] / rows[other]['narrow']:.2f}× | "
                  f"{rows['A']['ns_per_pair'] / rows[other]['ns_per_pair']:.2f}× | |")
    sys.exit(status)


if __name__ == "__main__":
    main()
