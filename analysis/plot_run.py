#!/usr/bin/python3
"""Plots of one `ccdlab run` result folder: where the time goes per step, and the work done per step.

usage: /usr/bin/python3 analysis/plot_run.py RESULTS_DIR [--out DIR]

Writes RESULTS_DIR/phases.png (stacked milliseconds per phase and step), RESULTS_DIR/work.png (BV tests,
candidate pairs, elementary tests and contacts per step, log scale) and RESULTS_DIR/timeline.png/.pdf/.svg (one
figure, steps on a shared axis: time per phase; the BVTT front — nodes kept, sprouted and pruned — for the
`front` scheduler, candidate pairs otherwise; contacts VF and EE), and prints the median of each phase.
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


def plot_timeline(run, out: Path) -> list[Path]:
    steps = run.steps
    fig, (time_ax, work_ax, contact_ax) = plt.subplots(3, 1, figsize=(10, 7.5), sharex=True,
                                                       gridspec_kw={"height_ratios": [3, 2, 2]})
    time_ax.stackplot(steps["step"], *[steps[p] for p in PHASES], labels=[PHASE_LABELS[p] for p in PHASES], alpha=0.85)
    time_ax.set_ylabel("ms per phase")
    time_ax.legend(fontsize=7, ncol=4, loc="upper left", frameon=False)
    time_ax.grid(alpha=0.3)
    t = run.traversal
    if t is not None and "front_nodes" in t and t.front_nodes.max() > 0:
        work_ax.plot(t.step, t.front_nodes, color="C0", marker="o", markersize=3, label="front nodes")
        work_ax.bar(t.step - 0.2, t.sprouted, width=0.4, color="C2", alpha=0.7, label="sprouted")
        work_ax.bar(t.step + 0.2, t.pruned, width=0.4, color="C3", alpha=0.7, label="pruned")
        for step in t.step[t.rebuilds > 0]:
            work_ax.axvline(step, color="grey", linestyle=":", linewidth=0.8)
        work_ax.set_ylabel("BVTT front (dotted: rebuilt)")
    else:
        work_ax.plot(steps["step"], steps["candidate_pairs"], color="C0", marker="o", markersize=3,
                     label="candidate face pairs")
        work_ax.set_ylabel("candidate pairs")
    work_ax.legend(fontsize=7, loc="upper left", frameon=False)
    work_ax.grid(alpha=0.3)
    contact_ax.plot(steps["step"], steps["contacts_vf"], marker="v", markersize=4, linestyle="--", label="vertex-face")
    contact_ax.plot(steps["step"], steps["contacts_ee"], marker="^", markersize=4, linestyle="-", label="edge-edge")
    contact_ax.set_ylabel("contacts")
    contact_ax.set_xlabel("CCD step")
    contact_ax.legend(fontsize=7, loc="upper left", frameon=False)
    contact_ax.grid(alpha=0.3)
    revision = run.config.get("git_revision", "")
    fig.suptitle(title_of(run) + (f" | rev {revision}" if revision else ""), fontsize=9)
    fig.tight_layout()
    paths = [out / f"timeline.{ext}" for ext in ("png", "pdf", "svg")]
    for path in paths:
        fig.savefig(path, dpi=110)
    plt.close(fig)
    return paths


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
    written = [plot_phases(run, out), plot_work(run, out), *plot_timeline(run, out)]
    medians = run.steps[["total_ms", *PHASES]].median()
    print("median ms per step: " + ", ".join(f"{k.removesuffix('_ms')} {v:.2f}" for k, v in medians.items()))
    for path in written:
        print(f"wrote {path}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
