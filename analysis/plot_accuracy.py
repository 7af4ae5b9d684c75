#!/usr/bin/python3
"""What accuracy costs in time: the accuracy ladder from `experiments/scripts/accuracy.sh`.

usage: /usr/bin/python3 analysis/plot_accuracy.py RESULTS_DIR

Reads RESULTS_DIR/queries.csv (one row per tester and query, written by `ccdlab validate --out`) and, if present,
RESULTS_DIR/pipeline.csv (ms per step of the cloth pipeline per tester and round) and RESULTS_DIR/earliest.csv
(the earliest time of impact of real steps per tester, against exact's). Writes
RESULTS_DIR/accuracy_overview.png — the picture to take in at a glance: each rung at its defaults, median µs per
query over all sets (whisker to p99) against its false hits, misses marked beside it — and accuracy_time.png, every
tester and parameter per group of query sets; prints markdown tables.
"""
from __future__ import annotations

import argparse
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pandas as pd  # noqa: E402

sys.path.insert(0, str(Path(__file__).resolve().parent))
from ccdlab_results import read_table  # noqa: E402

QUERY_COLUMNS = ["set", "tester", "query", "truth", "hit", "route", "us", "toi", "exact_toi"]
PIPELINE_COLUMNS = ["round", "tester", "ms_per_step", "contacts_vf", "contacts_ee", "hash"]
EARLIEST_COLUMNS = ["step", "tester", "earliest_toi", "exact_toi", "ms"]
ROUTE_FALLBACK = 2


def group_of(set_name: str, collection: str = "", scene: str = "") -> str:
    """Query sets grouped as in docs/results-accuracy.md: by the collection and scene columns of queries.csv, else by the
    older path-like set names ("handcrafted/<scene>/<kind>", "simulation/<scene>/<stem>")."""
    if collection == "handcrafted" or set_name.startswith("handcrafted/"):
        return "handcrafted (Wang et al.)"
    if collection == "hard-cases" or set_name.startswith("hard-cases/"):
        return "hard cases (built-in)"
    if scene:
        return scene
    parts = set_name.split("/")
    return parts[1] if parts[0] == "simulation" and len(parts) > 1 else set_name


def summarize(queries: pd.DataFrame) -> pd.DataFrame:
    q = queries.copy()
    if "collection" in q.columns:
        q["group"] = [group_of(s, str(c) if isinstance(c, str) else "", str(sc) if isinstance(sc, str) else "")
                      for s, c, sc in zip(q["set"], q["collection"], q["scene"])]
    else:
        q["group"] = q["set"].map(group_of)
    q["fn"] = (q.truth == 1) & (q.hit == 0)
    q["fp"] = (q.truth == 0) & (q.hit == 1)
    both = (q.hit == 1) & (q.truth == 1)
    q["toi_err"] = np.where(both, (q.toi - q.exact_toi).abs(), np.nan)
    rows = []
    for (group, tester), g in q.groupby(["group", "tester"], sort=False):
        rows.append({"group": group, "tester": tester, "queries": len(g), "positives": int(g.truth.sum()),
                     "FN": int(g.fn.sum()), "FP": int(g.fp.sum()), "median_us": g.us.median(),
                     "p99_us": g.us.quantile(0.99), "max_us": g.us.max(),
                     "fallback_pct": 100.0 * (g.route == ROUTE_FALLBACK).mean(),
                     "toi_max_err": g.toi_err.max() if g.toi_err.notna().any() else 0.0})
    return pd.DataFrame(rows)


def plot(summary: pd.DataFrame, out: Path) -> Path:
    groups = list(dict.fromkeys(summary.group))
    testers = list(dict.fromkeys(summary.tester))
    cols = min(3, len(groups))
    nrows = (len(groups) + cols - 1) // cols
    fig, axes = plt.subplots(nrows, cols, figsize=(5.2 * cols, 4.2 * nrows), squeeze=False)
    for ax, group in zip(axes.flat, groups):
        rows = summary[summary.group == group]
        for i, tester in enumerate(testers):
            r = rows[rows.tester == tester]
            if r.empty:
                continue
            r = r.iloc[0]
            color = f"C{i % 10}"
            # Counts are shown as count + 1 on a log axis so that zero stays visible at the bottom.
            for value, marker, label in ((r.FN, "v", "misses"), (r.FP, "^", "false hits")):
                ax.plot([r.median_us, r.p99_us], [value + 1, value + 1], color=color, linewidth=0.8, alpha=0.6)
                ax.plot(r.median_us, value + 1, marker=marker, color=color, linestyle="none", markersize=7,
                        markerfacecolor=color if marker == "v" else "none",
                        label=f"{tester} ({label})" if ax is axes.flat[0] else None)
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_ylim(0.7, max(10.0, float(max(rows.FN.max(), rows.FP.max()) + 1) * 1.5))
        ax.set_title(f"{group} ({int(rows.queries.iloc[0])} queries)", fontsize=9)
        ax.set_xlabel("µs per query (median, whisker to p99)")
        ax.set_ylabel("wrong answers + 1")
        ax.grid(alpha=0.3, which="both")
    for ax in list(axes.flat)[len(groups):]:
        ax.axis("off")
    handles, labels = axes.flat[0].get_legend_handles_labels()
    fig.legend(handles, labels, fontsize=7, loc="lower center", ncol=4, frameon=False)
    fig.tight_layout(rect=(0, 0.12 if len(testers) > 4 else 0.08, 1, 1))
    path = out / "accuracy_time.png"
    for ext in ("png", "pdf", "svg"):  # PNG for the docs, vector for print
        fig.savefig(path.with_suffix(f".{ext}"), dpi=110)
    plt.close(fig)
    return path


RUNG_COLORS = ["#1f77b4", "#ff7f0e", "#2ca02c", "#9467bd", "#8c564b", "#17becf", "#7f7f7f", "#bcbd22"]  # no red


def overview(queries: pd.DataFrame, out: Path) -> Path:
    """One panel: each rung at its defaults (a tester name without parameters) over every query of every set —
    median µs (whisker to p99) against false hits; misses, where there are any, written in red beside the point
    (a tester with misses is not conservative). The parameter sweeps are in accuracy_time.png."""
    q = queries[~queries.tester.str.contains(":")]
    if q.empty:
        q = queries
    fig, ax = plt.subplots(figsize=(7.5, 4.8))
    for i, (tester, g) in enumerate(q.groupby("tester", sort=False)):
        fp = int(((g.truth == 0) & (g.hit == 1)).sum())
        fn = int(((g.truth == 1) & (g.hit == 0)).sum())
        med, p99 = g.us.median(), g.us.quantile(0.99)
        color = RUNG_COLORS[i % len(RUNG_COLORS)]
        ax.plot([med, p99], [fp + 1, fp + 1], color=color, linewidth=1.5, alpha=0.6)
        ax.plot(med, fp + 1, "o", color=color, markersize=9)
        ax.annotate(tester, (med, fp + 1), textcoords="offset points", xytext=(7, 6), fontsize=9, color=color)
        if fn:
            ax.annotate(f"{fn} misses", (med, fp + 1), textcoords="offset points", xytext=(7, -12), fontsize=9,
                        color="red", fontweight="bold")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_ylim(0.6, None)
    ax.set_xlabel(f"µs per query: median over all {q.groupby('tester', sort=False).size().iloc[0]} queries, "
                  "whisker to p99")
    ax.set_ylabel("false hits + 1")
    ax.set_title("What accuracy costs: each tester on every shared set and hard case (misses in red)", fontsize=10)
    ax.grid(alpha=0.3, which="both")
    fig.tight_layout()
    path = out / "accuracy_overview.png"
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path


def markdown_earliest(earliest: pd.DataFrame) -> list[str]:
    lines = ["### Earliest time of impact on real steps (`ccdlab step A B --earliest`)", "",
             "| step | tester | earliest time | exact's | error (exact − tester) | ms |", "|---|---|---:|---:|---:|---:|"]
    for r in earliest.itertuples():
        lines.append(f"| {r.step} | {r.tester} | {r.earliest_toi:.12g} | {r.exact_toi:.12g} | "
                     f"{r.exact_toi - r.earliest_toi:.2g} | {r.ms:.1f} |")
    return lines + [""]


def markdown(summary: pd.DataFrame, pipeline: pd.DataFrame | None, earliest: pd.DataFrame | None = None) -> str:
    lines = []
    for group in dict.fromkeys(summary.group):
        rows = summary[summary.group == group]
        lines += [f"### {group}: {int(rows.queries.iloc[0])} queries, {int(rows.positives.iloc[0])} colliding", "",
                  "| tester | misses | false hits | median µs | p99 µs | max µs | fallback % | ToI max error |",
                  "|---|---:|---:|---:|---:|---:|---:|---:|"]
        for r in rows.itertuples():
            lines.append(f"| {r.tester} | {r.FN} | {r.FP} | {r.median_us:.2f} | {r.p99_us:.2f} | {r.max_us:.1f} | "
                         f"{r.fallback_pct:.1f} | {r.toi_max_err:.2g} |")
        lines.append("")
    if pipeline is not None and len(pipeline):
        lines += ["### Pipeline, default cloth scene (ms per step, over rounds)", "",
                  "| tester | median ms/step | min ms/step | contacts (vf + ee) | hash |", "|---|---:|---:|---:|---|"]
        for tester, g in pipeline.groupby("tester", sort=False):
            lines.append(f"| {tester} | {g.ms_per_step.median():.1f} | {g.ms_per_step.min():.1f} | "
                         f"{int(g.contacts_vf.iloc[0] + g.contacts_ee.iloc[0])} | {g.hash.iloc[0]} |")
        lines.append("")
    if earliest is not None and len(earliest):
        lines += markdown_earliest(earliest)
    return "\n".join(lines)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("results", type=Path)
    args = parser.parse_args(argv)
    try:
        queries = read_table(args.results / "queries.csv", QUERY_COLUMNS, "run `ccdlab validate … --out DIR` first")
        pipeline = None
        if (args.results / "pipeline.csv").is_file():
            pipeline = read_table(args.results / "pipeline.csv", PIPELINE_COLUMNS, "written by accuracy.sh")
        earliest = None
        if (args.results / "earliest.csv").is_file():
            earliest = read_table(args.results / "earliest.csv", EARLIEST_COLUMNS, "written by accuracy.sh")
    except (FileNotFoundError, ValueError) as e:
        print(f"plot_accuracy.py: error: {e}", file=sys.stderr)
        return 2
    summary = summarize(queries)
    path = plot(summary, args.results)
    glance = overview(queries, args.results)
    print(markdown(summary, pipeline, earliest))
    print(f"wrote {glance} and {path}", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
