"""pytest for analysis/plot_accuracy.py on a small results folder made here."""
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
import plot_accuracy  # noqa: E402


def make_results(folder: Path) -> Path:
    folder.mkdir(parents=True, exist_ok=True)
    rows = ["set,tester,query,truth,hit,route,us,toi,exact_toi"]
    for tester, wrong in (("float", 1), ("exact", 0)):
        for i in range(20):
            truth = i % 2
            hit = truth if i >= wrong else 1 - truth  # `wrong` answers at the start
            for name in ("handcrafted/a/edge-edge", "simulation/funnel/1ee"):
                rows.append(f"{name},{tester},{i},{truth},{hit},0,{0.5 + i * 0.1},0.25,0.25")
    (folder / "queries.csv").write_text("\n".join(rows) + "\n")
    (folder / "pipeline.csv").write_text("round,tester,ms_per_step,contacts_vf,contacts_ee,hash\n"
                                         "1,float,50.0,10,20,abc\n2,float,52.0,10,20,abc\n1,exact,190.0,10,20,abc\n")
    (folder / "earliest.csv").write_text("step,tester,earliest_toi,exact_toi,ms\n"
                                         "funnel,conservative,0.25,0.2500000001,12.5\nfunnel,exact,0.2500000001,0.2500000001,40\n")
    return folder


def test_groups_from_the_scene_and_collection_columns(tmp_path):
    import pandas as pd
    rows = ["set,scene,collection,tester,query,origin,truth,hit,route,us,toi,exact_toi"]
    for i in range(4):
        rows.append(f"wedges/edge-edge,wedges,handcrafted,float,{i},\"q.csv:{i + 1}\",1,1,0,0.5,0.5,0.5")
        rows.append(f"cloth-funnel/227ee,cloth-funnel,simulation,float,{i},q.csv:{i + 1},0,0,0,0.5,1,1")
        rows.append(f"hard-cases/two-roots,hard-cases,hard-cases,float,{i},hard-cases/two-roots: x,0,0,0,0.5,1,1")
    (tmp_path / "queries.csv").write_text("\n".join(rows) + "\n")
    summary = plot_accuracy.summarize(pd.read_csv(tmp_path / "queries.csv"))
    assert set(summary.group) == {"handcrafted (Wang et al.)", "cloth-funnel", "hard cases (built-in)"}


def test_summary_counts_misses_and_false_hits(tmp_path):
    import pandas as pd
    summary = plot_accuracy.summarize(pd.read_csv(make_results(tmp_path / "r") / "queries.csv"))
    row = summary[(summary.tester == "float") & (summary.group == "funnel")].iloc[0]
    assert row.queries == 20 and row.FN + row.FP == 1
    assert summary[summary.tester == "exact"].FN.sum() == 0


def test_plot_and_tables_are_written(tmp_path, capsys):
    folder = make_results(tmp_path / "r")
    assert plot_accuracy.main([str(folder)]) == 0
    assert (folder / "accuracy_time.png").stat().st_size > 1000
    assert (folder / "accuracy_overview.png").stat().st_size > 1000
    out = capsys.readouterr().out
    assert "### handcrafted (Wang et al.)" in out and "| float | 51.0 | 50.0 | 30 | abc |" in out
    assert "| funnel | conservative | 0.25 | 0.2500000001 | 1e-10 | 12.5 |" in out


def test_missing_file_is_a_clear_error(tmp_path, capsys):
    assert plot_accuracy.main([str(tmp_path)]) == 2
    assert "queries.csv: not found" in capsys.readouterr().err
