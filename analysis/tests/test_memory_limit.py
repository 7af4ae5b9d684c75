"""pytest for memory_limit, measured: the peak resident memory of the `ccdlab` process itself (its rusage, read by
wait4), not the pipeline's own estimate. A step whose contacts would not fit under the limit stops while they still
fit, exit 2, with the message that says so; one that fits completes under the limit with the contacts of a run
without one. The shared rod-twist step with a thickness of ~1.3 edges (25M contacts, 5 GB unbounded) is refused
under 400 MiB within seconds (skipped where ../shared/data is absent)."""
import json
import os
import subprocess
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
CLI = ROOT / "build" / "bin" / "ccdlab"
TINY = ROOT / "tests" / "cli" / "tiny.yaml"
ROD = ROOT.parent / "shared" / "data" / "meshes" / "rod-twist"
MIB = 1 << 20

pytestmark = pytest.mark.skipif(not CLI.exists(), reason="build/bin/ccdlab not built")


def measured(tmp_path, *args):
    """Runs the CLI; returns (exit code, stdout + stderr, peak resident bytes of that process)."""
    out = tmp_path / "out.txt"
    with open(out, "w") as f:
        child = subprocess.Popen([str(CLI), *args], stdout=f, stderr=subprocess.STDOUT, cwd=tmp_path)
        _, status, usage = os.wait4(child.pid, 0)
    child.returncode = os.waitstatus_to_exitcode(status)
    return child.returncode, out.read_text(), usage.ru_maxrss * 1024  # ru_maxrss is in KiB on Linux


def inflated(thickness, limit):
    """The small built-in scene at 7,248 triangles with a thickness of several edges: a dense step."""
    return ["run", str(TINY), "--no-progress", "--json", "--set", "scene.resolution=60", "--set",
            f"tester.thickness={thickness}", "--set", f"memory_limit={limit}", "--set", "output.dir=out"]


def test_contacts_that_would_not_fit_stop_the_step_under_the_limit(tmp_path):
    rc, text, peak = measured(tmp_path, *inflated(0.2, "150MiB"))
    assert rc == 2, text
    assert "memory_limit 150.0 MiB: the step's contacts would not fit" in text, text
    assert "or lower the tester's thickness (0.2)" in text, text
    assert peak < 150 * MIB, f"peak {peak / MIB:.0f} MiB"
    assert not (tmp_path / "out" / "steps.csv").exists()  # nothing left behind as complete


def test_a_step_that_fits_completes_under_the_limit_with_the_same_contacts(tmp_path):
    rc, text, peak = measured(tmp_path, *inflated(0.02, "300MiB"))
    assert rc == 0, text
    limited = json.loads(text[text.index("{"):])
    rc, text, _ = measured(tmp_path, *inflated(0.02, "none"))
    assert rc == 0, text
    free = json.loads(text[text.index("{"):])
    assert limited["hash"] == free["hash"]
    assert peak < 300 * MIB, f"peak {peak / MIB:.0f} MiB"


@pytest.mark.skipif(not ROD.exists(), reason="../shared/data not found")
def test_the_rod_twist_step_inflated_is_refused_under_400_mib(tmp_path):
    rc, text, peak = measured(tmp_path, "step", str(ROD / "3036.ply"), str(ROD / "3037.ply"), "--tester",
                              "float:thickness=0.01", "--memory-limit", "400MiB")
    assert rc == 2, text
    assert "the step's contacts would not fit" in text, text
    assert peak < 400 * MIB, f"peak {peak / MIB:.0f} MiB"
