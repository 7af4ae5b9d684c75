#!/usr/bin/python3
"""Any set of ccdlab runs side by side, as one Markdown table.

usage: /usr/bin/python3 analysis/compare.py RUN [RUN …] [--phases] [--out FILE.md]

Each RUN is a result folder of `ccdlab run` (steps.csv, steps.jsonl), a `ccdlab bench` folder (bench.csv: one row
per scheduler × threads), or a sweep's runs.csv (one row per run). Per run: what was run (scene, K, scheduler ×
threads, tester), median / min / max ms per step, work per step, contacts, contact hash and revision, and the
time relative to the first run (× vs first). With --phases, the median ms of each pipeline phase. Runs whose
contact hashes differ are flagged below the table: comparing their times compares different answers.
"""
from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

import pandas as pd

sys.path.insert(0, str(Path(__file__).resolve().parent))
from ccdlab_results import PHASES, ResultError, load_run  # noqa: E402


def from_run_folder(folder: Path) -> list[dict]:
    run = load_run(folder)
    cfg = run.config.get("config", {})
    steps = run.steps
    row = {
        "run": folder.name, "scene": run.config.get("scene", ""), "k": cfg.get("bv", {}).get("k", steps.k.iloc[0] if "k" in steps else ""),
        "scheduler": f"{steps.scheduler.iloc[0]} ×{steps.threads.iloc[0]}" if "scheduler" in steps else "",
        "tester": steps.tester.iloc[0] if "tester" in steps else "", "steps": len(steps),
        "ms_median": steps.total_ms.median(), "ms_min": steps.total_ms.min(), "ms_max": steps.total_ms.max(),
        "bv_tests": steps.bv_tests.mean(), "elementary_tests": (steps.vf_tests + steps.ee_tests).mean(),
        "contacts": int((steps.contacts_vf + steps.contacts_ee).sum()),
        "hash": run.summary.get("hash", "") if run.summary else "",
        "revision": steps.git_revision.iloc[0] if "git_revision" in steps else "",
    }
    for phase in PHASES:
        row[phase] = steps[phase].median()
    return [row]


def from_bench_folder(folder: Path) -> list[dict]:
    bench = pd.read_csv(folder / "bench.csv")
    header = {}
    if (folder / "bench.jsonl").is_file():
        header = json.loads((folder / "bench.jsonl").read_text().splitlines()[0])
    cfg = header.get("config", {})
    rows = []
    for r in bench.itertuples():
        rows.append({
            "run": f"{folder.name}: {r.scheduler} ×{r.threads}", "scene": header.get("scene", ""),
            "k": cfg.get("bv", {}).get("k", ""), "scheduler": f"{r.scheduler} ×{r.threads}",
            "tester": (cfg.get("tester") or {}).get("name", ""), "steps": header.get("steps", ""),
            "ms_median": r.ms_per_step, "ms_min": getattr(r, "ms_per_step_min", float("nan")),
            "ms_max": getattr(r, "ms_per_step_max", float("nan")), "bv_tests": r.bv_tests_per_step,
            "elementary_tests": getattr(r, "elementary_tests_per_step", float("nan")), "contacts": "",
            "hash": r.hash, "revision": r.git_revision})
    return rows


def from_runs_csv(path: Path) -> list[dict]:
    """A sweep's runs.csv (`ccdlab sweep … --merge`): flattened config and result columns, one row per run."""
    runs = pd.read_csv(path)
    rows = []
    for _, r in runs.iterrows():
        counters = [r.get(f"counters.{c}", float("nan")) for c in ("bv_tests", "vf_tests", "ee_tests")]
        steps = r.get("steps", float("nan"))
        rows.append({
            "run": f"{r.get('label', '')} rep {r.get('repeat', 0)}", "scene": r.get("scene", ""), "k": r.get("bv.k", ""),
            "scheduler": f"{r.get('scheduler.name', '')} ×{r.get('threads', '')}", "tester": r.get("tester.name", ""),
            "steps": steps, "ms_median": r.get("ms_per_step", float("nan")), "ms_min": float("nan"),
            "ms_max": float("nan"), "bv_tests": counters[0] / steps, "elementary_tests": (counters[1] + counters[2]) / steps,
            "contacts": int(r.get("contacts.vf", 0) + r.get("contacts.ee", 0)), "hash": str(r.get("hash", "")),
            "revision": r.get("git_revision", "")})
    return rows


def collect(paths: list[str]) -> pd.DataFrame:
    rows = []
    for p in map(Path, paths):
        if p.is_file() and p.suffix == ".csv":
            rows += from_runs_csv(p)
        elif (p / "steps.csv").is_file():
            rows += from_run_folder(p)
        elif (p / "bench.csv").is_file():
            rows += from_bench_folder(p)
        elif (p / "runs.csv").is_file():
            rows += from_runs_csv(p / "runs.csv")
        else:
            raise ResultError(f"{p}: not a run folder (steps.csv), a bench folder (bench.csv) or a runs.csv")
    return pd.DataFrame(rows)


def number(v, digits=2) -> str:
    if isinstance(v, str):
        return v
    if pd.isna(v):
        return "–"
    return f"{v:,.0f}" if abs(v) >= 1000 else f"{v:.{digits}f}"


def markdown(df: pd.DataFrame, phases: bool) -> str:
    first = df.ms_median.iloc[0]
    columns = ["run", "scene", "k", "scheduler", "tester", "steps", "ms/step median", "min", "max", "× vs first",
               "BV tests/step", "elementary/step", "contacts", "hash", "revision"]
    if phases:
        columns += [p.removesuffix("_ms") + " ms" for p in PHASES]
    lines = ["| " + " | ".join(columns) + " |", "|" + "---|" * len(columns)]
    for _, r in df.iterrows():
        cells = [str(r.run), str(r.scene), str(r.k), str(r.scheduler), str(r.tester), str(r.steps),
                 number(r.ms_median), number(r.ms_min), number(r.ms_max),
                 f"{r.ms_median / first:.2f}×" if first and not pd.isna(r.ms_median) else "–",
                 number(r.bv_tests, 0), number(r.elementary_tests, 0), str(r.contacts), str(r.hash), str(r.revision)]
        if phases:
            cells += [number(r.get(p, float("nan"))) for p in PHASES]
        lines.append("| " + " | ".join(cells) + " |")
    hashes = {h for h in df.hash if isinstance(h, str) and h}
    if len(hashes) > 1:
        lines += ["", f"**Warning:** {len(hashes)} different contact hashes: these runs did not find the same "
                  "contacts (different scenes or a tester that differs), so their times compare different work."]
    return "\n".join(lines) + "\n"


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("runs", nargs="+", help="result folders (run or bench) or runs.csv files")
    parser.add_argument("--phases", action="store_true", help="add the median ms of every phase")
    parser.add_argument("--out", help="also write the table to this Markdown file")
    args = parser.parse_args(argv)
    try:
        table = markdown(collect(args.runs), args.phases)
    except (ResultError, OSError, pd.errors.ParserError, KeyError) as e:
        print(f"compare: error: {e}", file=sys.stderr)
        return 2
    print(table, end="")
    if args.out:
        Path(args.out).write_text(table)
    return 0


if __name__ == "__main__":
    sys.exit(main())
