#!/usr/bin/python3
"""Regret table of the adaptive rules (framework/narrow/rules/): each rule forced on, forced off, and adaptive.

    /usr/bin/python3 analysis/rule_regret.py [--cli build/bin/ccdlab] [--configs 'experiments/configs/steady/*.yaml']
        [--threads 1,2] [--rounds 3] [--rules sixteenths,proximity,...] [--out results/regret]

For every steady config and thread count (1: `sequential`; more: `--scheduler`, phc by default) it runs the
adaptive pipeline once untimed (the first run after another config is slower), then, in each round, the adaptive pipeline (every rule `auto`) and, per rule, the pipeline with that rule forced `on` and forced
`off` (the other rules adaptive), in an order that rotates from round to round; the time of a run is the median of
`ms.total` over steps 2..N (the steady state: the build and the first refit left out), and a setting's time the
median over rounds. Regret = adaptive / min(on, off) − 1: how much the rule's own choice lost against the better
fixed one (negative: it won, by choosing per step). Every run of a config must report the same contact hash
(exit 1 otherwise): the rules only cull, never change the answer.

Writes OUT/regret.csv (one row per config × threads × rule) and OUT/regret.md (the table docs/narrow-phase.md
shows), and prints the table with the largest regret last.
"""
import argparse
import csv
import glob
import os
import statistics
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from ccdlab_results import run_records  # noqa: E402

# Each rule and the setting that forces it (the end boxes' is bv.end_boxes, the others narrow.rules.*).
RULES = {
    "triangles": "narrow.rules.triangles",
    "sixteenths": "narrow.rules.sixteenths",
    "proximity": "narrow.rules.proximity",
    "orphan_carry": "narrow.rules.orphan_carry",
    "certificates": "narrow.rules.certificates",
    "end_boxes": "bv.end_boxes",
}


def run(cli, config, threads, scheduler, sets):
    """(steady ms, hash, git revision) of one `ccdlab run`."""
    records = run_records(cli, config, [f"threads={threads}", f"scheduler={scheduler}", *sets], "rule_regret")
    steps = [r for r in records if r.get("type") == "step"]
    config_record = next((r for r in records if r.get("type") == "config"), {})
    ms = [s["ms"]["total"] for s in steps][2:] or [s["ms"]["total"] for s in steps]
    hashes = {s["hash"] for s in steps}
    return statistics.median(ms), tuple(sorted(hashes)), config_record.get("git_revision", "?")


def measure(cli, config, threads, scheduler, rules, rounds):
    """{rule: {setting: median ms}} with 'auto' shared by every rule; the revision measured."""
    variants = [("auto", "auto", [])]
    for rule in rules:
        variants += [(rule, v, [f"{RULES[rule]}={v}"]) for v in ("on", "off")]
    times = {(r, v): [] for r, v, _ in variants}
    hashes, revision = set(), "?"
    run(cli, config, threads, scheduler, [])  # untimed: the first run after another config is slower (caches, pages)
    for k in range(rounds):
        shift = (k * 3) % len(variants)
        for rule, value, sets in variants[shift:] + variants[:shift]:
            ms, h, revision = run(cli, config, threads, scheduler, sets)
            times[(rule, value)].append(ms)
            hashes.add(h)
    if len(hashes) != 1:
        sys.exit(f"rule_regret: {config} x{threads}: the settings found different contact sets: {hashes}")
    med = {key: statistics.median(v) for key, v in times.items()}
    return {rule: {"auto": med[("auto", "auto")], "on": med[(rule, "on")], "off": med[(rule, "off")]} for rule in rules}, revision


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--cli", default="build/bin/ccdlab")
    ap.add_argument("--configs", default="experiments/configs/steady/*.yaml")
    ap.add_argument("--threads", default="1,2")
    ap.add_argument("--scheduler", default="phc", help="the scheduler at more than one thread")
    ap.add_argument("--rounds", type=int, default=3)
    ap.add_argument("--rules", default=",".join(RULES))
    ap.add_argument("--out", default="results/regret")
    a = ap.parse_args()
    rules = [r for r in a.rules.split(",") if r]
    for r in rules:
        if r not in RULES:
            sys.exit(f"rule_regret: --rules: unknown rule '{r}'; valid: {', '.join(RULES)}")
    configs = sorted(glob.glob(a.configs))
    if not configs:
        sys.exit(f"rule_regret: no config matches {a.configs}")
    os.makedirs(a.out, exist_ok=True)
    rows, revision = [], "?"
    for config in configs:
        for threads in [int(t) for t in a.threads.split(",")]:
            scheduler = "sequential" if threads == 1 else a.scheduler
            print(f"rule_regret: {config} x{threads} ({scheduler}) ...", file=sys.stderr)
            result, revision = measure(a.cli, config, threads, scheduler, rules, a.rounds)
            for rule, t in result.items():
                best = min(t["on"], t["off"])
                rows.append({"config": os.path.splitext(os.path.basename(config))[0], "threads": threads,
                             "scheduler": scheduler, "rule": rule, "auto_ms": round(t["auto"], 5),
                             "on_ms": round(t["on"], 5), "off_ms": round(t["off"], 5),
                             "regret_pct": round(100 * (t["auto"] / best - 1), 1), "revision": revision})
    with open(os.path.join(a.out, "regret.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)
    lines = [f"Adaptive against each rule forced, ms per step (median of steps 2..N, median of {a.rounds} alternating "
             f"rounds) at `{revision}`; regret = adaptive ÷ the better forced setting − 1.", "",
             "| config | threads | rule | adaptive | on | off | regret |", "|---|---|---|---|---|---|---|"]
    for r in rows:
        lines.append(f"| {r['config']} | {r['threads']} ({r['scheduler']}) | {r['rule']} | {r['auto_ms']:.2f} | "
                     f"{r['on_ms']:.2f} | {r['off_ms']:.2f} | {r['regret_pct']:+.1f}% |")
    worst = max(rows, key=lambda r: r["regret_pct"])
    lines += ["", f"Largest regret: {worst['regret_pct']:+.1f}% ({worst['config']}, {worst['threads']} thread(s), "
              f"{worst['rule']})."]
    with open(os.path.join(a.out, "regret.md"), "w") as f:
        f.write("\n".join(lines) + "\n")
    print("\n".join(lines))


if __name__ == "__main__":
    main()
