"""pytest for analysis/narrow_table.py: two and three sides on a small crumpled step written here as PLY."""
import subprocess
import sys
from pathlib import Path

import pytest

from test_wide_table import CLI, ROOT, crumpled_step


def table(tmp_path, *extra):
    return subprocess.run([sys.executable, str(ROOT / "analysis" / "narrow_table.py"), "--a", str(CLI), "--b", str(CLI),
                           "--rounds", "2", "--threads", "2", "--data", str(tmp_path / "data"), *extra],
                          capture_output=True, text=True)


@pytest.mark.skipif(not CLI.exists(), reason="build/bin/ccdlab not built")
def test_third_side_gets_its_rows_and_ratio(tmp_path):
    crumpled_step(tmp_path / "data" / "meshes" / "rod-twist")
    done = table(tmp_path, "--c", str(CLI), "--c-args", "--set scheduler=phc", "--steady", "3")
    assert done.returncode == 0, done.stderr
    rows = [line.split("|")[1:-1] for line in done.stdout.splitlines() if line.startswith("| rod-twist")]
    assert [r[1].strip() for r in rows] == ["A", "B", "C", "A/B", "A/C"]
    for r in rows[3:]:  # the total's ratio: a positive number with its × sign
        assert float(r[7].strip().rstrip("×")) > 0
    assert "C = `" in done.stdout.splitlines()[0]


@pytest.mark.skipif(not CLI.exists(), reason="build/bin/ccdlab not built")
def test_different_answers_fail(tmp_path):
    crumpled_step(tmp_path / "data" / "meshes" / "rod-twist")
    # A thicker contact distance on side C changes the contact set, hence its hash.
    done = table(tmp_path, "--c", str(CLI), "--c-args", "--tester float:thickness=0.05")
    assert done.returncode == 1
    assert "contact hashes differ" in done.stderr
