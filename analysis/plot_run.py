#!/usr/bin/python3
"""Plots of one `ccdlab run` result folder: where the time goes per step, and the work done per step.

usage: /usr/bin/python3 analysis/plot_run.py RESULTS_DIR [--out DIR]

Writes RESULTS_DIR/phases.png (stacked milliseconds per phase and step) and RESULTS_DIR/work.png (BV tests,
candidate pairs, elementary tests and contacts per step, log scale), and prints the median of each phase.
"""
from __future__ import annotations

import argparse
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

sys.path.insert(0, str(Path(__file__).resolve().parent))
from ccdlab_results import PHASES, ResultError, load_run  # noqa: E402

PHASE_LABELS = {"build_ms": "BVH build", "swept_bv_ms": "swept BVs", "refit_ms": "refit", "cones_ms": "normal cones",
                "traverse_ms": "BVTT traversal", "narrow_ms": "narrow phase", "orphan_ms": "orphan set"}


def title_of(run) -> str:
    cfg = run.config.get("config", {})
    scene = run.config.get("scene", "")
    parts = [cfg.get("name", run.folder.name)]
    if cfg:
        parts.append(f"k={cfg['bv']['k']} {cfg['scheduler']['name']} x{cfg['threads']} {cfg['tester']['name']}")
    if scene:
        parts.append(scene)
    return " | ".join(parts)


def plot_phases(run, out: Path) -> Path:
    steps = run.steps
    fig, ax = plt.subplots(figsize=(10, 4.5))
    bottom = None
    for phase in PHASES:
        values = steps[phase]
        ax.bar(steps["step"], values, bottom=bottom, label=PHASE_LABELS[phase], width=0.85)
        bottom = values if bottom is None else bottom + values
    ax.set_xlabel("CCD step")
    ax.set_ylabel("milliseconds")
    ax.set_title(title_of(run), fontsize=9)
    ax.legend(fontsize=8, ncol=3)
    ax.grid(axis="y", alpha=0.3)
    fig.tight_layout()
    path = out / "phases.png"
    fig.savefig(path, dpi=120)
    plt.close(fig)
    return path


def plot_work(run, out: Path) -> Path:
    steps = run.steps
    fig, ax = plt.subplots(figsize=(10, 4.5))
    series = {
        "BV overlap tests": steps["bv_tests"],
        "candidate face pairs": steps["candidate_pairs"],
        "elementary tests (VF+EE)": steps["vf_tests"] + steps["ee_tests"],
        "contacts (VF+EE)": steps["contacts_vf"] + steps["contacts_ee"],
    }
    for label, values in series.items():
        ax.plot(steps["step"], values.clip(lower=0.5), marker="o", markersize=3, label=label)
    ax.set_yscale("log")
    ax.set_xlabel("CCD step")
    ax.set_ylabel("count per step")
    ax.set_title(title_of(run), fontsize=9)
    ax.legend(fontsize=8)
    ax.grid(alpha=0.3)
    fig.tight_layout()
    path = out / "work.png"
    fig.savefig(path, dpi=120)
    plt.close(fig)
    return path


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("results", help="result folder of `ccdlab run` (holds steps.csv)")
    parser.add_argument("--out", help="folder for the PNGs (default: the result folder)")
    args = parser.parse_args(argv)
    try:
        run = load_run(args.results)
    except ResultError as e:
        print(f"plot_run: error: {e}", file=sys.stderr)
        return 2
    out = Path(args.out) if args.out else run.folder
    out.mkdir(parents=True, exist_ok=True)
    written = [plot_phases(run, out), plot_work(run, out)]
    medians = run.steps[["total_ms", *PHASES]].median()
    print("median ms per step: " + ", ".join(f"{k.removesuffix('_ms')} {v:.2f}" for k, v in medians.items()))
    for path in written:
        print(f"wrote {path}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
