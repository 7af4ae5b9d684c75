#!/usr/bin/python3
"""Bar charts of the paper tables (experiments/paper/paper_tables.py writes table1.csv and table2.csv).

usage: /usr/bin/python3 analysis/plot_tables.py RESULTS_DIR [--out DIR]

  by_k.png/.pdf/.svg          ms per step by K, one panel per scene: ICCD (sequential ×1) and the proposed
                              method (front ×2), bars at the median, whiskers from the fastest to the slowest round,
                              the simulated 8-core time of the proposed method as a marker
  by_scheduler.png/.pdf/.svg  ms per step by scheduler at K = 18, one panel per scene: 1 and 2 threads measured
                              (median, fastest–slowest round) and the simulated 8-core time as a marker
"""
from __future__ import annotations

import argparse
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import matplotlib.lines  # noqa: E402
import matplotlib.patches  # noqa: E402
import pandas as pd  # noqa: E402

FORMATS = ("png", "pdf", "svg")
SCHEDULERS = ("sequential", "phc", "front", "static")
HATCH = {1: "", 2: "//"}


def panels(n: int):
    cols = min(n, 3)
    rows = (n + cols - 1) // cols
    fig, axes = plt.subplots(rows, cols, figsize=(4.2 * cols, 3.3 * rows + 0.8), squeeze=False)
    for a in axes.flat[n:]:
        a.set_visible(False)
    return fig, list(axes.flat[:n])


def save(fig, out: Path, stem: str) -> Path:
    paths = []
    for ext in FORMATS:
        path = out / f"{stem}.{ext}"
        fig.savefig(path, dpi=110, bbox_inches="tight")
        paths.append(path)
    plt.close(fig)
    return paths[0]


def bar(ax, x, median, lo, hi, **kw):
    median, lo, hi = (np.asarray(v, float) for v in (median, lo, hi))
    ax.bar(x, median, yerr=[median - lo, hi - median], capsize=2.5, error_kw={"linewidth": 0.8}, **kw)


def plot_by_k(t1: pd.DataFrame, out: Path, revision: str) -> Path:
    scenes = list(dict.fromkeys(t1.scene))
    fig, axes = panels(len(scenes))
    width = 0.38
    for ax, scene in zip(axes, scenes):
        rows = t1[t1.scene == scene].sort_values("k")
        x = np.arange(len(rows))
        bar(ax, x - width / 2, rows.iccd_ms, rows.iccd_ms_min, rows.iccd_ms_max, width=width, color="C0",
            label="ICCD (sequential ×1)")
        bar(ax, x + width / 2, rows.front_2_ms, rows.front_2_ms_min, rows.front_2_ms_max, width=width, color="C2",
            hatch="//", edgecolor="white", label="proposed (front ×2)")
        ax.plot(x + width / 2, rows.front_sim8_ms, linestyle="none", marker="v", color="black", markersize=6,
                label="proposed, 8 cores simulated")
        ax.set_xticks(x, [f"{k}-DOP" for k in rows.k])
        ax.set_title(f"{scene} ({int(rows.triangles.iloc[0]):,} triangles)", fontsize=9)
        ax.set_ylabel("ms per step")
        ax.grid(axis="y", alpha=0.3)
    fig.legend(*axes[0].get_legend_handles_labels(), loc="lower center", ncol=3, fontsize=8, frameon=False,
               bbox_to_anchor=(0.5, -0.02))
    fig.suptitle(f"ms per step by K (paper Table 1) — median, whiskers fastest–slowest round; rev {revision}", fontsize=10)
    fig.tight_layout(rect=(0, 0.06, 1, 1))
    return save(fig, out, "by_k")


def plot_by_scheduler(t2: pd.DataFrame, out: Path, revision: str) -> Path:
    fig, axes = panels(len(t2))
    width = 0.38
    for ax, (_, r) in zip(axes, t2.iterrows()):
        x = np.arange(len(SCHEDULERS))
        for j, threads in enumerate((1, 2)):
            med = [r[f"{s}_{threads}_ms"] for s in SCHEDULERS]
            lo = [r[f"{s}_{threads}_ms_min"] for s in SCHEDULERS]
            hi = [r[f"{s}_{threads}_ms_max"] for s in SCHEDULERS]
            bar(ax, x + (j - 0.5) * width, med, lo, hi, width=width, color=[f"C{i}" for i in range(4)],
                hatch=HATCH[threads], edgecolor="white", label=f"{threads} thread{'s' if threads > 1 else ''}")
        ax.plot(x + width / 2, [r[f"{s}_sim8_ms"] for s in SCHEDULERS], linestyle="none", marker="v", color="black",
                markersize=6, label="8 cores simulated")
        ax.set_xticks(x, ["ICCD\n(sequential)", "PHC", "proposed\n(front)", "static"], fontsize=8)
        ax.set_title(f"{r.scene} ({int(r.triangles):,} triangles)", fontsize=9)
        ax.set_ylabel("ms per step")
        ax.grid(axis="y", alpha=0.3)
    handles = [matplotlib.patches.Patch(facecolor="0.6", label="1 thread"),
               matplotlib.patches.Patch(facecolor="0.6", hatch="//", edgecolor="white", label="2 threads"),
               matplotlib.lines.Line2D([], [], linestyle="none", marker="v", color="black", label="8 cores simulated")]
    fig.legend(handles=handles, loc="lower center", ncol=3, fontsize=8, frameon=False, bbox_to_anchor=(0.5, -0.02))
    fig.suptitle(f"ms per step by scheduler, K = 18 (paper Table 2) — median, whiskers fastest–slowest round; rev {revision}",
                 fontsize=10)
    fig.tight_layout(rect=(0, 0.06, 1, 1))
    return save(fig, out, "by_scheduler")


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("results", help="folder holding table1.csv and table2.csv")
    parser.add_argument("--out", help="folder for the figures (default: the results folder)")
    args = parser.parse_args(argv)
    folder = Path(args.results)
    try:
        t1 = pd.read_csv(folder / "table1.csv")
        t2 = pd.read_csv(folder / "table2.csv")
    except (OSError, pd.errors.ParserError) as e:
        print(f"plot_tables: error: {e} (run experiments/paper/paper_tables.py first)", file=sys.stderr)
        return 2
    out = Path(args.out) if args.out else folder
    out.mkdir(parents=True, exist_ok=True)
    revision = str(t1.git_revision.iloc[0]) if "git_revision" in t1 else "?"
    print(f"wrote {plot_by_k(t1, out, revision)}, {plot_by_scheduler(t2, out, revision)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
