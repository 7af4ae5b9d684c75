#!/usr/bin/python3
"""Speed-up against cores from a `ccdlab bench` result folder.

usage: /usr/bin/python3 analysis/plot_scaling.py RESULTS_DIR [--out DIR] [--stem NAME]

Reads RESULTS_DIR/bench.csv (measured ms/step per scheduler and thread count: median, fastest and slowest
round), scaling.csv (the schedule simulator's prediction per core count) and bench.jsonl (scene, triangles, K,
tester, rounds, revision). Writes NAME.png, NAME.pdf and NAME.svg (default NAME: speedup) with two panels:
  left   speed-up over sequential at 1 thread: measured points (median; bars: slowest to fastest round), the
         simulated curve to the largest core count, an Amdahl fit of that curve with its serial fraction f,
         and the ideal line
  right  parallel efficiency (speed-up ÷ cores) of the same
Prints the measured and simulated tables.
"""
from __future__ import annotations

import argparse
import json
import re
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import matplotlib.ticker  # noqa: E402
import numpy as np  # noqa: E402
import pandas as pd  # noqa: E402

sys.path.insert(0, str(Path(__file__).resolve().parent))
from ccdlab_results import read_table  # noqa: E402

SCALING_COLUMNS = ["scheduler", "cores", "predicted_ms_per_step", "predicted_speedup", "measured_ms_per_step"]
BENCH_COLUMNS = ["scheduler", "threads", "ms_per_step", "ms_per_step_min", "speedup", "bv_tests_per_step", "lambda"]
STYLES = {  # marker, line style: told apart in black and white too
    "sequential": ("o", "-"), "phc": ("s", "--"), "front": ("^", "-."), "static": ("D", ":"), "embree": ("v", (0, (5, 1))),
}
FORMATS = ("png", "pdf", "svg")


def load(folder: Path):
    hint = "run `ccdlab bench CONFIG.yaml` first"
    scaling = read_table(folder / "scaling.csv", SCALING_COLUMNS, hint)
    bench = read_table(folder / "bench.csv", BENCH_COLUMNS, hint)
    header = {}
    jsonl = folder / "bench.jsonl"
    if jsonl.is_file():
        header = json.loads(jsonl.read_text().splitlines()[0])
    return scaling, bench, header


def amdahl_fraction(cores: np.ndarray, speedup: np.ndarray) -> float:
    """Least-squares serial fraction f of S(n) = 1 / (f + (1 − f) / n): linear in f as 1/S − 1/n = f (1 − 1/n)."""
    x = 1 - 1 / cores
    y = 1 / speedup - 1 / cores
    keep = x > 0
    if not keep.any():
        return 0.0
    return float(np.clip((x[keep] @ y[keep]) / (x[keep] @ x[keep]), 0, 1))


def title_of(header: dict) -> str:
    config = header.get("config", {})
    k = config.get("bv", {}).get("k", "?")
    tester = config.get("tester", {})
    tester = tester.get("name", tester) if isinstance(tester, dict) else tester
    scene = re.sub(r"\S*/", "", str(header.get("scene", "?")))  # file names without their folders
    return (f"{scene}\n{header.get('triangles', '?'):,} triangles, K={k}, tester {tester}, "
            f"{header.get('rounds', '?')} rounds, rev {header.get('git_revision', '?')}"
            if isinstance(header.get("triangles"), int) else "ccdlab bench")


def plot(scaling: pd.DataFrame, bench: pd.DataFrame, header: dict, out: Path, stem: str = "speedup") -> list[Path]:
    reference = bench[(bench.scheduler == "sequential") & (bench.threads == 1)]
    ref_ms = float(reference.ms_per_step.iloc[0]) if len(reference) else float(bench.ms_per_step.max())
    fig, (ax, eff) = plt.subplots(1, 2, figsize=(11, 4.8), gridspec_kw={"width_ratios": [3, 2]})
    top = int(scaling.cores.max())
    fits = []
    for i, (scheduler, rows) in enumerate(scaling.groupby("scheduler", sort=False)):
        color = f"C{i}"
        marker, style = STYLES.get(scheduler.split("/")[0], ("x", "-"))
        rows = rows.sort_values("cores")
        cores = rows.cores.to_numpy(float)
        sim = rows.predicted_speedup.to_numpy(float)
        ax.plot(cores, sim, linestyle=style, color=color, linewidth=1.4, label=f"{scheduler}: simulated")
        eff.plot(cores, sim / cores, linestyle=style, color=color, linewidth=1.4)
        own = sim / sim[0] if sim[0] > 0 else sim  # the scheduler against its own 1-core time
        f = amdahl_fraction(cores, own)
        fits.append((scheduler, f))
        grid = np.geomspace(1, top, 64)
        ax.plot(grid, sim[0] / (f + (1 - f) / grid), linestyle=(0, (1, 2)), color=color, linewidth=0.9, alpha=0.8,
                label=f"{scheduler}: Amdahl fit, f = {f:.3f}")
        measured = bench[bench.scheduler == scheduler].sort_values("threads")
        if len(measured):
            s = ref_ms / measured.ms_per_step.to_numpy(float)
            fast = ref_ms / measured.ms_per_step_min.to_numpy(float)
            slow = ref_ms / (measured.ms_per_step_max.to_numpy(float) if "ms_per_step_max" in measured
                             else measured.ms_per_step.to_numpy(float))
            t = measured.threads.to_numpy(float)
            ax.errorbar(t, s, yerr=[s - slow, fast - s], linestyle="none", marker=marker, markersize=7,
                        markerfacecolor="white", color=color, capsize=3, label=f"{scheduler}: measured")
            eff.errorbar(t, s / t, yerr=[(s - slow) / t, (fast - s) / t], linestyle="none", marker=marker,
                         markersize=6, markerfacecolor="white", color=color, capsize=3)
    ax.plot([1, top], [1, top], color="black", linewidth=0.8, linestyle="-", alpha=0.4, label="ideal")
    eff.axhline(1, color="black", linewidth=0.8, alpha=0.4)
    for a in (ax, eff):
        a.set_xscale("log", base=2)
        a.xaxis.set_major_formatter(matplotlib.ticker.FuncFormatter(lambda v, _: f"{v:g}"))
        a.set_xlabel("cores")
        a.grid(alpha=0.3, which="both")
    ax.set_yscale("log", base=2)
    ax.yaxis.set_major_formatter(matplotlib.ticker.FuncFormatter(lambda v, _: f"{v:g}"))
    ax.set_ylabel("speed-up over sequential ×1 (whole step)")
    eff.set_ylabel("parallel efficiency (speed-up ÷ cores)")
    eff.set_ylim(0, 1.15)
    fig.legend(*ax.get_legend_handles_labels(), fontsize=7, ncol=4, loc="lower center", frameon=False)
    fig.suptitle(title_of(header), fontsize=9)
    fig.tight_layout(rect=(0, 0.16, 1, 1))
    paths = []
    for ext in FORMATS:
        path = out / f"{stem}.{ext}"
        fig.savefig(path, dpi=120)
        paths.append(path)
    plt.close(fig)
    return paths


def plot_folder(folder: Path, out: Path, stem: str = "speedup") -> list[Path]:
    scaling, bench, header = load(Path(folder))
    return plot(scaling, bench, header, Path(out), stem)


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("results", help="result folder of `ccdlab bench`")
    parser.add_argument("--out", help="folder for the figures (default: the result folder)")
    parser.add_argument("--stem", default="speedup", help="file name of the figures, without extension")
    args = parser.parse_args(argv)
    folder = Path(args.results)
    try:
        scaling, bench, header = load(folder)
    except (FileNotFoundError, ValueError, pd.errors.ParserError) as e:
        print(f"plot_scaling: error: {e}", file=sys.stderr)
        return 2
    out = Path(args.out) if args.out else folder
    out.mkdir(parents=True, exist_ok=True)
    paths = plot(scaling, bench, header, out, args.stem)
    print(bench.to_string(index=False))
    print()
    print(scaling.to_string(index=False))
    print("wrote " + ", ".join(str(p) for p in paths))
    return 0


if __name__ == "__main__":
    sys.exit(main())
