"""pytest for the paper experiment and its figures: experiments/paper/paper_tables.py --quick on the built-in
scene and a simulated one (small) writes Table 1 (one row per K), Table 2 (every scheduler, identical contacts),
the paper's numbers beside, the simulated scene beside the paper's data of its kind, and the figures in PNG,
PDF and SVG; the Amdahl fit recovers a known serial fraction."""
import subprocess
import sys
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

ROOT = Path(__file__).resolve().parents[2]
CLI = ROOT / "build" / "bin" / "ccdlab"
sys.path.insert(0, str(ROOT / "analysis"))

import plot_scaling  # noqa: E402


def test_amdahl_fit_recovers_the_serial_fraction():
    cores = np.array([1, 2, 4, 8, 16, 32, 64], float)
    for f in (0.0, 0.05, 0.3):
        speedup = 1 / (f + (1 - f) / cores)
        assert plot_scaling.amdahl_fraction(cores, speedup) == pytest.approx(f, abs=1e-12)


@pytest.mark.skipif(not CLI.exists(), reason="build/bin/ccdlab not built")
def test_quick_paper_tables_on_the_builtin_scene(tmp_path):
    out = tmp_path / "paper"
    done = subprocess.run([sys.executable, str(ROOT / "experiments/paper/paper_tables.py"), "--quick", "--scenes",
                           "drape,skirt", "--out", str(out)], capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    t1 = pd.read_csv(out / "table1.csv")
    assert sorted(t1[t1.scene == "drape"].k) == [6, 14, 18, 26]
    assert (t1.iccd_ms > 0).all() and (t1.front_sim8_ms > 0).all()
    assert t1.groupby("scene").hash.nunique().eq(1).all(), "the contact set does not depend on K"
    t2 = pd.read_csv(out / "table2.csv")
    assert list(t2.scene) == ["drape", "skirt"] and t2.identical.all()
    for s in ("sequential", "phc", "front", "static"):
        assert t2[f"{s}_2_ms_min"].iloc[0] <= t2[f"{s}_2_ms"].iloc[0] <= t2[f"{s}_2_ms_max"].iloc[0]
    page = (out / "results.md").read_text()
    assert "## Table 1" in page and "## Table 2" in page
    noisy = sum(int((t2[f"{s}_{n}_ms_max"] > 1.1 * t2[f"{s}_{n}_ms_min"]).sum())
                for s in ("sequential", "phc", "front", "static") for n in (1, 2))
    assert f"Noise: {noisy} of 16 configurations at K = 18" in page, "the rounds' spread is said on the page"
    assert "| Flamenco (49K) | 64.7 | 52.1 | 48.6 | 69.7 |" in page, "the paper's Table 1 beside ours"
    assert "374.4" in page
    assert "| skirt (" in page and "| Princess (40K) |" in page, "a simulated scene beside the paper's data of its kind"
    for stem in ("speedup_drape", "by_k", "by_scheduler"):
        for ext in ("png", "pdf", "svg"):
            assert (out / "figures" / f"{stem}.{ext}").stat().st_size > 1000


@pytest.mark.skipif(not CLI.exists(), reason="build/bin/ccdlab not built")
def test_paper_tables_rejects_unknown_scenes(tmp_path):
    done = subprocess.run([sys.executable, str(ROOT / "experiments/paper/paper_tables.py"), "--scenes", "princess",
                           "--out", str(tmp_path)], capture_output=True, text=True)
    assert done.returncode == 2 and "unknown princess" in done.stderr
