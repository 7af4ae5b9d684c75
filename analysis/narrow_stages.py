#!/usr/bin/python3
"""Per-stage table of the narrow phase in the steady state: two ccdlab builds (or two settings) alternating.

    /usr/bin/python3 analysis/narrow_stages.py --a BASE_CLI --b build/bin/ccdlab CONFIG.yaml [CONFIG.yaml ...]
        [--rounds 3] [--threads 1] [--a-env CCDLAB_SIMD=avx2] [--b-env ...] [--set scheduler=sequential ...]
        [--b-set bv.end_boxes=true ...]

Runs `CLI run CONFIG --set threads=T --set output.dir=TMP --no-progress` (a steady config: experiments/configs/
steady/), A and B alternating (A B, B A, ...), and prints one Markdown row per narrow stage and side: the
median thread-ms over steps 2..N of every run, the pairs it received and removed (counts of the last step; the
"in" of stages 2–4 is what they and the later stages removed plus the elementary tests, i.e. it leaves out
the few that stage 1's final float test removes after stage 4), and ns per pair in. Both sides must report
the same contact hash (exit 1 otherwise).
"""
import argparse
import os
import statistics
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from ccdlab_results import run_records  # noqa: E402


def run(cli, config, threads, sets, env):
    records = run_records(cli, config, [f"threads={threads}", *sets], "narrow_stages", env)
    return [s for s in records if "ms" in s and s.get("type") != "config"]


def stages(step):
    """(name, pairs in, pairs removed, ms key) per stage, from one step's record."""
    n, c = step["narrow_stages"], step["counters"]
    pairs = c["vf_pairs"] + c["ee_pairs"]
    tests = c["vf_tests"] + c["ee_tests"]
    tri_in = n.get("triangle_tested", 0)
    gathered_from = c["candidate_pairs"] - n.get("triangle_culled", 0)  # candidates whose pairs are gathered
    plane_in = n["plane_culled"] + n["split_culled"] + n["proximity_culled"] + tests
    split_in = plane_in - n["plane_culled"]
    proximity_in = n.get("proximity_tested", split_in - n["split_culled"])  # 0 in steps where stage 4 does not run
    return [("stage 0 (whole triangles)", tri_in, n.get("triangle_culled", 0), "triangle_ms"),
            ("gather (candidates → feature pairs; + orphans)", gathered_from, None, "gather_ms"),
            ("stage 1 (feature 26-DOPs)", pairs, n["kdop_culled"], "kdop_ms"),
            ("stage 2 (plane)", plane_in, n["plane_culled"], "plane_ms"),
            ("stage 3 (split)", split_in, n["split_culled"], "split_ms"),
            ("stage 4 (proximity)", proximity_in, n["proximity_culled"], "proximity_ms"),
            ("elementary tests", tests, None, "test_ms")]


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("configs", nargs="+")
    ap.add_argument("--a", required=True)
    ap.add_argument("--b", default="build/bin/ccdlab")
    ap.add_argument("--a-env", action="append", default=[], help="KEY=VALUE in side A's environment")
    ap.add_argument("--b-env", action="append", default=[])
    ap.add_argument("--set", action="append", default=[], help="a `run --set` for both sides")
    ap.add_argument("--a-set", action="append", default=[], help="a `run --set` for side A only")
    ap.add_argument("--b-set", action="append", default=[])
    ap.add_argument("--threads", type=int, default=1)
    ap.add_argument("--rounds", type=int, default=3)
    o = ap.parse_args()
    env = lambda kvs: dict(kv.split("=", 1) for kv in kvs)
    sides = {"A": (o.a, env(o.a_env), o.set + o.a_set), "B": (o.b, env(o.b_env), o.set + o.b_set)}
    print(f"threads {o.threads}, {o.rounds} alternating rounds, medians of steps 2..N. "
          + ", ".join(f"{k} = `{cli}` {' '.join(f'{x}' for x in e.items())} {' '.join(sets)}".rstrip()
                      for k, (cli, e, sets) in sides.items()) + "\n")
    print("| config | stage | A ms | B ms | A pairs in → removed | B pairs in → removed | A ns / pair in | B ns / pair in |")
    print("|---|---|---|---|---|---|---|---|")
    status = 0
    for config in o.configs:
        runs = {"A": [], "B": []}
        for i in range(o.rounds):
            for side in ("A", "B") if i % 2 == 0 else ("B", "A"):
                cli, e, sets = sides[side]
                runs[side].append(run(cli, config, o.threads, sets, e))
        hashes = {side: r[0][0]["hash"] for side, r in runs.items()}
        if len(set(hashes.values())) > 1:
            print(f"narrow_stages: {config}: contact hashes differ: {hashes}", file=sys.stderr)
            status = 1
        later = {side: [s for r in rs for s in r[1:]] for side, rs in runs.items()}
        name = os.path.splitext(os.path.basename(config))[0]
        # Counts of the last step: past the measuring steps of the per-step rules (end boxes, stage 0), which
        # run with a stage the other steps may leave out.
        rows = {side: stages(later[side][-1]) for side in later}
        for k, (stage, _, _, key) in enumerate(rows["A"]):
            ms = {side: statistics.median(s["narrow_stages"].get(key, 0.0) for s in later[side]) for side in later}
            cell, ns = {}, {}
            for side in later:
                _, pin, removed, _ = rows[side][k]
                cell[side] = f"{pin:,}" + (f" → {removed:,}" if removed is not None else "")
                ns[side] = f"{1e6 * ms[side] / pin:.1f}" if pin else "—"
            print(f"| {name} | {stage} | {ms['A']:.1f} | {ms['B']:.1f} | {cell['A']} | {cell['B']} | {ns['A']} | {ns['B']} |")
        for key, label in (("refit", "refit"), ("traverse", "traversal"), ("narrow", "narrow (candidates)"),
                           ("orphans", "orphans"), ("total", "whole step")):
            a = statistics.median(s["ms"][key] for s in later["A"])
            b = statistics.median(s["ms"][key] for s in later["B"])
            print(f"| {name} | **{label}** | {a:.1f} | {b:.1f} | | | A/B {a / b:.2f}× | |")
    sys.exit(status)


if __name__ == "__main__":
    main()
