"""Reading ccdlab result folders (written by `ccdlab run`).

A result folder holds:
  steps.csv     one row per CCD step: counters, per-phase milliseconds, contact-set hash, config columns
  steps.jsonl   {"type": "config", ...}, then one {"type": "step", ...} per step, then {"type": "summary", ...}
  config.yaml   the resolved experiment config
"""
from __future__ import annotations

import json
import os
import subprocess
import sys
import tempfile
from dataclasses import dataclass
from pathlib import Path

import pandas as pd

PHASES = ["build_ms", "swept_bv_ms", "refit_ms", "cones_ms", "traverse_ms", "narrow_ms", "orphan_ms"]
OPTIONAL_PHASES = {"cones_ms"}  # absent from results written before normal-cone culling existed
REQUIRED_COLUMNS = ["step", "bv_tests", "candidate_pairs", "vf_tests", "ee_tests", "contacts_vf", "contacts_ee",
                    "total_ms", *[p for p in PHASES if p not in OPTIONAL_PHASES]]


def run_records(cli: str, config: str, sets: list[str], who: str, env: dict | None = None) -> list[dict]:
    """Every record of steps.jsonl from `CLI run CONFIG --set S ... --no-progress` into a temporary folder; exits
    naming `who`, the command and the end of its stderr when the run fails."""
    with tempfile.TemporaryDirectory() as tmp:
        args = [cli, "run", config, "--no-progress", "--set", f"output.dir={tmp}"]
        for s in sets:
            args += ["--set", s]
        out = subprocess.run(args, capture_output=True, text=True, env={**os.environ, **(env or {})})
        if out.returncode != 0:
            sys.exit(f"{who}: {' '.join(args)} failed: {out.stderr.strip()[-300:]}")
        with open(os.path.join(tmp, "steps.jsonl")) as f:
            return [json.loads(line) for line in f]


def read_table(path: Path, columns: list[str], hint: str) -> pd.DataFrame:
    """A CSV result file that must exist (else FileNotFoundError naming `hint`) and hold `columns` (else ValueError)."""
    if not path.is_file():
        raise FileNotFoundError(f"{path}: not found ({hint})")
    df = pd.read_csv(path)
    missing = [c for c in columns if c not in df.columns]
    if missing:
        raise ValueError(f"{path}: missing columns {', '.join(missing)}")
    return df


class ResultError(Exception):
    """A result folder that is missing, incomplete or malformed; the message names the file."""


@dataclass
class Run:
    folder: Path
    steps: pd.DataFrame
    config: dict
    summary: dict | None
    traversal: pd.DataFrame | None = None  # per step, from steps.jsonl: front_nodes, sprouted, pruned, rebuilds, …


def load_run(folder: str | Path) -> Run:
    folder = Path(folder)
    csv = folder / "steps.csv"
    if not csv.is_file():
        raise ResultError(f"{csv}: not found (run `ccdlab run CONFIG.yaml` first)")
    try:
        steps = pd.read_csv(csv)
    except (pd.errors.ParserError, pd.errors.EmptyDataError) as e:
        raise ResultError(f"{csv}: not a valid CSV: {e}") from e
    missing = [c for c in REQUIRED_COLUMNS if c not in steps.columns]
    if missing:
        raise ResultError(f"{csv}: missing columns {', '.join(missing)}")
    if steps.empty:
        raise ResultError(f"{csv}: no steps")
    for phase in OPTIONAL_PHASES:
        if phase not in steps.columns:
            steps[phase] = 0.0
    config, summary, traversal = {}, None, []
    jsonl = folder / "steps.jsonl"
    if jsonl.is_file():
        for number, line in enumerate(jsonl.read_text().splitlines(), start=1):
            if not line.strip():
                continue
            try:
                record = json.loads(line)
            except json.JSONDecodeError as e:
                raise ResultError(f"{jsonl}:{number}: invalid JSON: {e.msg}") from e
            if record.get("type") == "config":
                config = record
            elif record.get("type") == "summary":
                summary = record
            elif record.get("type") == "step" and "traversal" in record:
                traversal.append({"step": record.get("step"), **record["traversal"]})
        if summary is None:
            # ccdlab writes results under .partial names and renames them when a run is complete; a file
            # without its summary is from an interrupted older version or was cut: never plot it as complete.
            raise ResultError(f"{jsonl}: no summary record: the run did not complete")
    return Run(folder, steps, config, summary, pd.DataFrame(traversal) if traversal else None)
