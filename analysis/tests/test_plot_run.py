"""pytest for analysis/: result loading and plotting, on result folders made here."""
import json
import sys
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
import plot_run  # noqa: E402
from ccdlab_results import ResultError, load_run  # noqa: E402

HEADER = ("step,frame_t0,frame_t1,bv_tests,candidate_pairs,vf_pairs,ee_pairs,orphan_vf,orphan_ee,vf_tests,ee_tests,"
          "orphan_tests,contacts_vf,contacts_ee,build_ms,swept_bv_ms,refit_ms,traverse_ms,narrow_ms,orphan_ms,total_ms,hash,"
          "experiment,scheduler,threads,k,tester,git_revision")


def make_run(folder: Path, steps: int = 3) -> Path:
    folder.mkdir(parents=True, exist_ok=True)
    rows = [HEADER]
    for s in range(steps):
        rows.append(f"{s},{s},{s + 1},1000,{100 + s},50,60,5,6,40,50,3,{s},{2 * s},{1.5 if s == 0 else 0},"
                    f"0.5,0.1,2.0,3.0,1.0,{7.6 + s},00000000deadbeef,t,sequential,1,18,float,abc")
    (folder / "steps.csv").write_text("\n".join(rows) + "\n")
    config = {"type": "config", "config": {"name": "t", "bv": {"k": 18}, "scheduler": {"name": "sequential"},
                                           "threads": 1, "tester": {"name": "float"}}, "scene": "test scene"}
    records = [json.dumps(config)]
    for s in range(steps):
        records.append(json.dumps({"type": "step", "step": s, "traversal": {
            "front_nodes": 100 + 10 * s, "sprouted": 12 * s, "pruned": s, "rebuilds": int(s == 0)}}))
    records.append(json.dumps({"type": "summary", "steps": steps}))
    (folder / "steps.jsonl").write_text("\n".join(records) + "\n")
    return folder


def test_load_run_reads_steps_config_and_summary(tmp_path):
    run = load_run(make_run(tmp_path / "r", steps=4))
    assert len(run.steps) == 4
    assert run.config["config"]["bv"]["k"] == 18
    assert run.summary["steps"] == 4


def test_plots_are_written(tmp_path, capsys):
    folder = make_run(tmp_path / "r")
    assert plot_run.main([str(folder)]) == 0
    for name in ("phases.png", "work.png"):
        png = folder / name
        assert png.is_file() and png.stat().st_size > 5000
        assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert "median ms per step: total 8.60" in capsys.readouterr().out
    for ext in ("png", "pdf", "svg"):
        assert (folder / f"timeline.{ext}").stat().st_size > 5000


def test_front_size_per_step_is_read_from_the_step_records(tmp_path):
    run = load_run(make_run(tmp_path / "r", steps=3))
    assert run.traversal.front_nodes.tolist() == [100, 110, 120]
    assert run.traversal.rebuilds.tolist() == [1, 0, 0]


def test_missing_folder_is_a_clear_error(tmp_path, capsys):
    assert plot_run.main([str(tmp_path / "absent")]) == 2
    assert "steps.csv: not found" in capsys.readouterr().err


def test_missing_columns_and_bad_jsonl_are_named(tmp_path):
    folder = tmp_path / "bad"
    folder.mkdir()
    (folder / "steps.csv").write_text("step,total_ms\n0,1.0\n")
    with pytest.raises(ResultError, match="missing columns bv_tests"):
        load_run(folder)
    folder = make_run(tmp_path / "badjson")
    (folder / "steps.jsonl").write_text('{"type": "config"}\n{not json\n')
    with pytest.raises(ResultError, match=r"steps.jsonl:2: invalid JSON"):
        load_run(folder)


def test_scaling_plot_from_bench_results(tmp_path, capsys):
    import plot_scaling
    folder = tmp_path / "bench"
    folder.mkdir()
    (folder / "bench.csv").write_text(
        "scheduler,threads,ms_per_step,ms_per_step_min,ms_per_step_max,speedup,bv_tests_per_step,lambda\n"
        "sequential,1,100,95,110,1,1000,1\nsequential,2,60,58,66,1.67,1000,1\nfront,1,90,88,91,1.11,600,0.6\n"
        "front,2,46,45,50,2.17,600,0.6\n")
    rows = ["scheduler,cores,predicted_ms_per_step,predicted_speedup,measured_ms_per_step"]
    for s, base in (("sequential", 100.0), ("front", 90.0)):
        for n in (1, 2, 4, 8):
            measured = {1: base, 2: base * 0.55}.get(n, "")
            rows.append(f"{s},{n},{base / n},{100 / (base / n)},{measured}")
    (folder / "scaling.csv").write_text("\n".join(rows) + "\n")
    assert plot_scaling.main([str(folder)]) == 0
    png = folder / "speedup.png"
    assert png.is_file() and png.read_bytes()[:4] == b"\x89PNG"
    assert (folder / "speedup.pdf").read_bytes()[:4] == b"%PDF"
    assert b"<svg" in (folder / "speedup.svg").read_bytes()[:2000]
    assert plot_scaling.main([str(tmp_path / "nothing")]) == 2
    assert "scaling.csv: not found" in capsys.readouterr().err


def test_incomplete_run_is_refused(tmp_path):
    folder = make_run(tmp_path / "cut")
    lines = (folder / "steps.jsonl").read_text().splitlines()
    (folder / "steps.jsonl").write_text(lines[0] + "\n")  # the summary record is missing
    with pytest.raises(ResultError, match=r"no summary record: the run did not complete"):
        load_run(folder)
