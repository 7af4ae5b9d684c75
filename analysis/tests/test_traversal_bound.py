"""pytest for analysis/traversal_bound.py: one row per resolution, with the run's own triangle count (drape_fold:
the 2·r² sheet and its sphere), BV tests that grow with the sheet, and a positive cost per BV test."""
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
CLI = ROOT / "build" / "bin" / "ccdlab"


@pytest.mark.skipif(not CLI.exists(), reason="build/bin/ccdlab not built")
def test_one_row_per_resolution_with_the_runs_counts():
    done = subprocess.run([sys.executable, str(ROOT / "analysis/traversal_bound.py"), "--cli", str(CLI),
                           "--resolutions", "12,20", "--rounds", "1"], capture_output=True, text=True, cwd=ROOT)
    assert done.returncode == 0, done.stderr
    rows = [line.split("|")[1:-1] for line in done.stdout.splitlines() if line.startswith("| ") and line[2].isdigit()]
    assert [int(r[0]) for r in rows] == [12, 20]
    triangles = [int(r[1].replace(",", "")) for r in rows]
    assert triangles[1] - triangles[0] == 2 * 20 * 20 - 2 * 12 * 12  # the sheet grows; the sphere stays
    bv_tests = [int(r[2].replace(",", "")) for r in rows]
    assert 0 < bv_tests[0] < bv_tests[1]
    assert all(float(r[5]) > 0 for r in rows)
