"""pytest for analysis/compare.py: run folders and bench folders side by side as one Markdown table, times
relative to the first run, a warning when the runs did not find the same contacts, a clear error otherwise."""
import json
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
import compare  # noqa: E402
from test_plot_run import make_run  # noqa: E402


def with_hash(folder: Path, h: str) -> Path:
    lines = (folder / "steps.jsonl").read_text().splitlines()
    summary = json.loads(lines[-1])
    summary["hash"] = h
    (folder / "steps.jsonl").write_text("\n".join(lines[:-1] + [json.dumps(summary)]) + "\n")
    return folder


def test_runs_side_by_side(tmp_path, capsys):
    a = with_hash(make_run(tmp_path / "k18", steps=3), "aaaa")
    b = with_hash(make_run(tmp_path / "k6", steps=5), "aaaa")
    bench = tmp_path / "bench"
    bench.mkdir()
    (bench / "bench.csv").write_text(
        "scheduler,threads,ms_per_step,ms_per_step_min,ms_per_step_max,speedup,bv_tests_per_step,lambda,"
        "elementary_tests_per_step,hash,git_revision\nfront,2,4.3,4.0,5.0,2,100,0.5,10,aaaa,abc\n")
    assert compare.main([str(a), str(b), str(bench), "--phases", "--out", str(tmp_path / "t.md")]) == 0
    out = capsys.readouterr().out
    lines = [l for l in out.splitlines() if l.startswith("| ")]
    assert len(lines) == 4  # header + 3 runs
    assert "| k18 |" in lines[1] and "| 1.00× |" in lines[1]
    assert "| k6 |" in lines[2] and "| 5 |" in lines[2]
    assert "bench: front ×2" in lines[3] and "| 0.50× |" in lines[3]  # 4.3 / 8.6 (median of 7.6, 8.6, 9.6)
    assert "traverse ms" in lines[0]
    assert "Warning" not in out
    assert (tmp_path / "t.md").read_text() == out


def test_different_answers_are_flagged_and_bad_paths_refused(tmp_path, capsys):
    a = with_hash(make_run(tmp_path / "a"), "aaaa")
    b = with_hash(make_run(tmp_path / "b"), "bbbb")
    assert compare.main([str(a), str(b)]) == 0
    assert "2 different contact hashes" in capsys.readouterr().out
    assert compare.main([str(tmp_path / "nothing")]) == 2
    assert "not a run folder" in capsys.readouterr().err
