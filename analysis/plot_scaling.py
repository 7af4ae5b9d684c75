#!/usr/bin/python3
"""Speed-up against cores from a `ccdlab bench` result folder.

usage: /usr/bin/python3 analysis/plot_scaling.py RESULTS_DIR [--out DIR]

Reads RESULTS_DIR/scaling.csv (simulated ms/step per scheduler and core count, measured where run) and
RESULTS_DIR/bench.csv; writes RESULTS_DIR/speedup.png (lines: simulated speed-up over sequential at 1 thread;
markers: measured) and prints a markdown table of both CSVs.
"""
from __future__ import annotations

import argparse
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import pandas as pd  # noqa: E402

sys.path.insert(0, str(Path(__file__).resolve().parent))
from ccdlab_results import read_table  # noqa: E402

SCALING_COLUMNS = ["scheduler", "cores", "predicted_ms_per_step", "predicted_speedup", "measured_ms_per_step"]
BENCH_COLUMNS = ["scheduler", "threads", "ms_per_step", "speedup", "bv_tests_per_step", "lambda"]


def load(folder: Path):
    hint = "run `ccdlab bench CONFIG.yaml` first"
    return [read_table(folder / "scaling.csv", SCALING_COLUMNS, hint), read_table(folder / "bench.csv", BENCH_COLUMNS, hint)]


def plot(scaling: pd.DataFrame, bench: pd.DataFrame, out: Path) -> Path:
    reference = bench[(bench.scheduler == "sequential") & (bench.threads == 1)]
    ref_ms = float(reference.ms_per_step.iloc[0]) if len(reference) else float(bench.ms_per_step.max())
    fig, ax = plt.subplots(figsize=(7.5, 5))
    for i, (scheduler, rows) in enumerate(scaling.groupby("scheduler", sort=False)):
        color = f"C{i}"
        ax.plot(rows.cores, rows.predicted_speedup, marker="o", markersize=3, color=color, label=f"{scheduler} (simulated)")
        measured = bench[bench.scheduler == scheduler]
        ax.plot(measured.threads, ref_ms / measured.ms_per_step, linestyle="none", marker="s", markersize=8,
                markerfacecolor="none", color=color, label=f"{scheduler} (measured)")
    top = max(scaling.cores)
    ax.plot([1, top], [1, top], color="grey", linewidth=0.8, linestyle=":", label="linear")
    ax.set_xscale("log", base=2)
    ax.set_yscale("log", base=2)
    ax.set_xlabel("cores")
    ax.set_ylabel("speed-up over sequential, 1 thread (whole step)")
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=7, ncol=2)
    fig.tight_layout()
    path = out / "speedup.png"
    fig.savefig(path, dpi=120)
    plt.close(fig)
    return path


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("results", help="result folder of `ccdlab bench`")
    parser.add_argument("--out", help="folder for the PNG (default: the result folder)")
    args = parser.parse_args(argv)
    folder = Path(args.results)
    try:
        scaling, bench = load(folder)
    except (FileNotFoundError, ValueError, pd.errors.ParserError) as e:
        print(f"plot_scaling: error: {e}", file=sys.stderr)
        return 2
    out = Path(args.out) if args.out else folder
    out.mkdir(parents=True, exist_ok=True)
    path = plot(scaling, bench, out)
    print(bench.to_string(index=False))
    print()
    print(scaling.to_string(index=False))
    print(f"wrote {path}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
