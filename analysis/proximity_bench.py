#!/usr/bin/python3
"""The proximity query's benchmark on the shared real frames: for each frame and d̂ (fractions of its bounding-box
diagonal), `ccdlab proximity` at 1 and 2 threads (ms of the first query, which builds the hierarchy, and the median
of the refit ones; pairs; peak resident memory), the reference sweep over boxes as a one-thread baseline (its ms;
the same pairs or the script fails), and a CCD step between the frame and the next (`ccdlab step`, one step, the
hierarchy built) for scale. Writes results/proximity/bench.csv and prints a Markdown table.

usage: /usr/bin/python3 analysis/proximity_bench.py [--ccdlab build/bin/ccdlab] [--data ../shared/data/meshes]
       [--dhat 1e-3,1e-2] [--repeat 5] [--out results/proximity]
"""
from __future__ import annotations

import argparse
import csv
import json
import re
import subprocess
import sys
from pathlib import Path

FRAMES = [("cloth-funnel", "227.ply", "228.ply"), ("rod-twist", "3036.ply", "3037.ply"),
          ("n-body-simulation", "balls16_18.ply", "balls16_19.ply")]


def timed(cmd: list[str]) -> tuple[dict, float]:
    """The command's JSON output and its peak resident memory in MiB (GNU time)."""
    done = subprocess.run(["/usr/bin/time", "-f", "PEAK_KB %M", *cmd], capture_output=True, text=True)
    if done.returncode != 0:
        sys.exit(f"proximity_bench: {' '.join(cmd)} failed ({done.returncode}): {done.stderr.strip()[-500:]}")
    peak = int(re.search(r"PEAK_KB (\d+)", done.stderr).group(1)) / 1024
    return json.loads(done.stdout), peak


def main(argv=None) -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--ccdlab", default="build/bin/ccdlab")
    p.add_argument("--data", default="../shared/data/meshes")
    p.add_argument("--dhat", default="1e-3,1e-2", help="fractions of the bounding-box diagonal")
    p.add_argument("--repeat", type=int, default=5, help="queries per run (the first builds the hierarchy)")
    p.add_argument("--out", default="results/proximity")
    a = p.parse_args(argv)
    data = Path(a.data)
    if not (data / FRAMES[0][0]).exists():
        sys.exit(f"proximity_bench: {data} holds no shared frames")
    rows = []
    for scene, f0, f1 in FRAMES:
        mesh, nxt = str(data / scene / f0), str(data / scene / f1)
        ccd = {t: timed([a.ccdlab, "step", mesh, nxt, "--json", "--no-progress", "--threads", str(t),
                         "--scheduler", "sequential" if t == 1 else "phc"])[0]["ms"]["total"] for t in (1, 2)}
        for rel in a.dhat.split(","):
            row = {"scene": scene, "frame": f0, "dhat_relative": float(rel)}
            for t in (1, 2):
                cmd = [a.ccdlab, "proximity", mesh, "--dhat", rel, "--relative", "--json", "--no-progress",
                       "--repeat", str(a.repeat), "--threads", str(t), "--scheduler", "sequential" if t == 1 else "phc"]
                if t == 1:
                    cmd.append("--check")
                j, peak = timed(cmd)
                row.update({"triangles": j["triangles"], "dhat": j["dhat"], "vf": j["pairs"]["vf"], "ee": j["pairs"]["ee"],
                            "hash": j["hash"], f"first_ms_{t}": j["query_ms"]["first"],
                            f"refit_ms_{t}": j["query_ms"]["refit_median"], f"peak_mib_{t}": peak,
                            f"ccd_step_ms_{t}": ccd[t]})
                if t == 1:
                    assert j["reference"]["equal"], j["reference"]
                    row["reference_ms"] = j["reference"]["ms"]
                    row["in_rationals"] = j["decided_in_rationals"]
            rows.append(row)
            print(f"{scene} {rel}: {row['vf'] + row['ee']} pairs, refit {row['refit_ms_1']:.1f} / {row['refit_ms_2']:.1f} ms",
                  file=sys.stderr)
    out = Path(a.out)
    out.mkdir(parents=True, exist_ok=True)
    with (out / "bench.csv").open("w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)
    print("| frame | triangles | d̂ / diagonal | pairs VF + EE | pairs per triangle | query ms, 1 thread: first / refit "
          "| 2 threads: first / refit | reference sweep ms (1 thread) | CCD step ms, 1 / 2 threads | peak MiB (2 threads) |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for r in rows:
        n = r["vf"] + r["ee"]
        print(f"| {r['scene']} {r['frame']} | {r['triangles']:,} | {r['dhat_relative']:g} | {r['vf']:,} + {r['ee']:,} "
              f"| {n / r['triangles']:.2f} | {r['first_ms_1']:.0f} / {r['refit_ms_1']:.1f} "
              f"| {r['first_ms_2']:.0f} / {r['refit_ms_2']:.1f} | {r['reference_ms']:.0f} "
              f"| {r['ccd_step_ms_1']:.0f} / {r['ccd_step_ms_2']:.0f} | {r['peak_mib_2']:.0f} |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
