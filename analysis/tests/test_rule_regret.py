"""pytest for analysis/rule_regret.py and analysis/density_table.py on a small crumpled step written here as PLY."""
import csv
import subprocess
import sys
from pathlib import Path

import pytest

from test_wide_table import CLI, ROOT, crumpled_step


def replay_config(tmp_path, thickness=0.0):
    crumpled_step(tmp_path / "step")
    frames = [str(tmp_path / "step" / name) for name in sorted(p.name for p in (tmp_path / "step").glob("*.ply"))]
    assert len(frames) == 2
    config = tmp_path / "crumpled.yaml"
    listed = "".join(f"    - {frames[i % 2]}\n" for i in range(7))
    config.write_text(f"name: crumpled\nscene:\n  frames:\n{listed}bv: {{k: 18}}\n"
                      f"tester: {{name: float, thickness: {thickness}}}\noutput: {{dir: {tmp_path / 'out'}}}\n")
    return config


@pytest.mark.skipif(not CLI.exists(), reason="build/bin/ccdlab not built")
def test_regret_rows_per_rule_and_thread_count(tmp_path):
    config = replay_config(tmp_path)
    out = tmp_path / "regret"
    done = subprocess.run([sys.executable, str(ROOT / "analysis" / "rule_regret.py"), "--cli", str(CLI), "--configs",
                           str(config), "--threads", "1,2", "--rounds", "1", "--rules", "sixteenths,end_boxes",
                           "--out", str(out)], capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    with open(out / "regret.csv") as f:
        rows = list(csv.DictReader(f))
    assert [(r["threads"], r["rule"]) for r in rows] == [("1", "sixteenths"), ("1", "end_boxes"), ("2", "sixteenths"),
                                                         ("2", "end_boxes")]
    for r in rows:
        best = min(float(r["on_ms"]), float(r["off_ms"]))
        assert float(r["regret_pct"]) == pytest.approx(100 * (float(r["auto_ms"]) / best - 1), abs=0.2)
    assert "Largest regret" in (out / "regret.md").read_text()


@pytest.mark.skipif(not CLI.exists(), reason="build/bin/ccdlab not built")
def test_unknown_rule_is_refused(tmp_path):
    done = subprocess.run([sys.executable, str(ROOT / "analysis" / "rule_regret.py"), "--cli", str(CLI), "--configs",
                           str(replay_config(tmp_path)), "--rules", "sixteenth"], capture_output=True, text=True)
    assert done.returncode != 0
    assert "unknown rule 'sixteenth'" in done.stderr


@pytest.mark.skipif(not CLI.exists(), reason="build/bin/ccdlab not built")
def test_density_row_counts_the_first_step(tmp_path):
    config = replay_config(tmp_path, thickness=0.05)
    done = subprocess.run([sys.executable, str(ROOT / "analysis" / "density_table.py"), "--cli", str(CLI), str(config)],
                          capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    row = [c.strip() for c in done.stdout.splitlines()[2].split("|")[1:-1]]
    assert row[0] == "`steady/crumpled`"
    assert row[1] == "512"  # 2·16² triangles
    assert float(row[2]) > 0  # contacts per triangle: the sheet folds over itself, within the thickness
    assert "% of" in row[4]  # the share of tests that hit
