"""The Python API at the top level of synth (issue 15): load, synthesise, run_flowchart, verify, screen,
write_report; Result.to_frame and _repr_html_; progress bars; the docs page's example as a doctest."""

from __future__ import annotations

import doctest
import io
import json
import subprocess
import sys
import types
from pathlib import Path

import pytest

import synth
from conftest import CASES
from synth.design.constraints import REGISTRY
from synth.design.result import FAIL, NOT_VERIFIED
from synth import progress

ROOT = Path(__file__).resolve().parents[1]


@pytest.fixture(scope="module")
def case3():
    return synth.load(CASES / "case3.yaml")


@pytest.fixture(scope="module")
def synthesis(case3):
    return synth.synthesise(case3)


def test_import_synth_is_light():
    code = ("import sys, synth; heavy = ('numpy', 'pandas', 'matplotlib', 'jinja2', 'scipy', 'synth.design',"
            " 'synth.schema'); print([m for m in heavy if m in sys.modules])")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True,
                         env={"PYTHONPATH": str(ROOT), "PATH": ""})
    assert out.stdout.strip() == "[]"
    assert synth.Result.__name__ == "Result" and synth.DesignInput.__name__ == "DesignInput"
    with pytest.raises(AttributeError, match="no attribute 'nothing'"):
        synth.nothing  # noqa: B018


def test_py_typed_ships_with_the_package():
    assert (Path(synth.__file__).parent / "py.typed").is_file()


def test_load_reads_a_case_file_a_saved_result_and_the_template(case3, tmp_path, synthesis):
    saved = tmp_path / "r.json"
    saved.write_text(json.dumps(synthesis.to_dict()))
    assert synth.load(saved) == case3                       # a saved result carries its inputs
    xlsx = tmp_path / "in.xlsx"
    from synth import cli
    assert cli.main(["template", str(xlsx)]) == 0
    assert synth.load(xlsx).differential_angle_deg == 85     # thesis case 1, Table 9 (the template's example)
    bad = tmp_path / "bad.yaml"
    bad.write_text("inputs: {working_arm_mm: -1}\n")
    with pytest.raises(synth.InputError, match="working_arm_mm"):
        synth.load(bad)


def test_synthesise_is_what_synth_design_prints(case3, synthesis, tmp_path, capsys):
    from synth import cli
    cli.main(["design", str(CASES / "case3.yaml"), "--json"])
    printed = json.loads(capsys.readouterr().out)
    assert printed["parts"] == synthesis.parts and printed["verdict"] == synthesis.verdict
    assert synthesis.solver == "enumerate" and synthesis.objective.startswith("standard")


def test_settings_reach_the_result_and_unknown_ones_are_named(case3):
    case1 = synth.load(CASES / "case1.yaml")
    full = synth.run_flowchart(case1)
    linear = synth.run_flowchart(case1, friction_circle=False)
    assert full.settings["friction_circle"] is True and linear.settings["friction_circle"] is False
    # the friction circle r sin(atan mu) is shorter than r mu: less radial damping on the same pivot
    assert linear.values["radial_damping_nm"] != pytest.approx(full.values["radial_damping_nm"], rel=1e-3)
    with pytest.raises(synth.InputError) as err:
        synth.synthesise(case3, fidelty="screening")
    assert "fidelty" in str(err.value) and "fidelity" in str(err.value)
    with pytest.raises(synth.InputError, match="fidelity"):
        synth.verify(case3, {}, fidelity="coarse")


def test_run_flowchart_reproduces_table_14(case3):
    f = synth.run_flowchart(case3)
    assert f.status == "baseline" and f.parts["ball_bearing"] == "6006"
    assert f.values["pulley_width_mm"] == 30.0                # thesis Table 14: pulley width 30 mm
    assert len(f.curves.get("plastic_wear", {}).get("time_h", [])) in (0, 60)


def test_verify_reproduces_the_synthesis_and_keeps_the_wear_history(synthesis, case3):
    v = synth.verify(case3, synthesis.parts)
    assert [c.id for c in v.checks] == [c.id for c in synthesis.checks]
    for a, b in zip(v.checks, synthesis.checks):
        assert a.verdict == b.verdict and (a.margin == b.margin or (a.margin is None and b.margin is None))
    case1 = synth.load(CASES / "case1.yaml")
    f = synth.run_flowchart(case1)
    w = synth.verify(case1, f.parts)
    hist = w.curves["plastic_wear"]
    assert len(hist["time_h"]) == 60 and hist["time_h"][-1] == pytest.approx(1200.0)   # Table 9: 1200 h
    assert hist["plastic_wear_total_mm"][-1] == pytest.approx(w.values["plastic_wear_total_mm"], rel=1e-9)
    with pytest.raises(synth.InputError, match="bolt_format"):
        synth.verify(case1, {k: v for k, v in f.parts.items() if k != "bolt_format"})


def test_to_frame_is_one_row_per_check(synthesis):
    df = synthesis.to_frame()
    assert list(df.index) == [c.id for c in synthesis.checks] and set(df.index) <= set(REGISTRY)
    assert (df["verdict"] == FAIL).sum() == len(synthesis.failed())
    for c in synthesis.checks:
        if c.margin is not None:
            assert df.loc[c.id, "margin"] == c.margin and df.loc[c.id, "label"] == REGISTRY[c.id].label
    assert df.loc[df["verdict"] == FAIL, "correction"].str.len().gt(0).all()


def test_repr_html_is_the_digest(synthesis):
    text = synthesis._repr_html_()
    assert text.startswith("<style>") and f"Verdict: {synthesis.verdict.upper()}" in text
    import html
    failed = sorted(synthesis.failed(), key=lambda c: c.margin)
    pos = [text.index(f'data-check="{c.id}"') for c in failed]
    assert pos == sorted(pos)                                 # worst first
    for c in failed:
        assert html.escape(c.label) in text
    for c in synthesis.not_verified():
        assert c.verdict == NOT_VERIFIED and html.escape(c.note) in text
    assert "<table" in text and "output" not in text.split("digest", 1)[0]


def test_screen_agrees_with_the_synthesis_and_reports_bad_rows():
    from synth.bulk.sample import sample_portfolio
    table = sample_portfolio(3, seed=0)
    broken = table.copy()
    broken.loc[1, "working_arm_mm"] = -5.0
    out = synth.screen(broken, objective="cost", progress=False)
    assert len(out) == 3 and list(out.columns[: len(table.columns)]) == list(table.columns)
    assert out.loc[1, "status"] == "error" and "working_arm_mm" in out.loc[1, "error"]
    # the bulk fast path and the optimiser give the same design (two code paths, one answer)
    from synth.bulk.portfolio import records
    recs = records(table)
    for i in (0, 2):
        r = synth.synthesise(recs[i], objective="cost", fidelity="screening")
        assert out.loc[i, "part_ball_bearing"] == r.parts["ball_bearing"]
        assert out.loc[i, "part_main_spring_wire"] == r.parts["main_spring_wire"]
        assert bool(out.loc[i, "feasible"]) == (r.verdict != FAIL)
    with pytest.raises(synth.InputError, match="chunk_size"):
        synth.screen(table, chunk_size=0)


def test_screen_takes_inputs_and_files(case3, tmp_path):
    from synth.bulk.sample import sample_portfolio
    path = tmp_path / "p.csv"
    sample_portfolio(2, seed=1).to_csv(path, index=False)
    from_file = synth.screen(path, progress=False)
    from_list = synth.screen([case3, CASES / "case1.yaml"], progress=False, chunk_size=1)
    assert len(from_file) == 2 and len(from_list) == 2 and (from_list["error"] == "").all()
    assert from_list.loc[0, "differential_angle_deg"] == case3.differential_angle_deg


class _Tty(io.StringIO):
    def isatty(self):
        return True


def test_progress_uses_tqdm_in_a_notebook(monkeypatch):
    monkeypatch.delenv("SYNTH_PROGRESS", raising=False)
    assert not progress.in_notebook()
    shell = type("ZMQInteractiveShell", (), {})()
    monkeypatch.setitem(sys.modules, "IPython", types.SimpleNamespace(get_ipython=lambda: shell))
    assert progress.in_notebook()
    sink = io.StringIO()                                     # a notebook's stderr is no terminal
    assert list(progress.progress(range(5), "screen", stream=sink)) == list(range(5))
    assert "screen: 100%" in sink.getvalue() and "5/5" in sink.getvalue()
    monkeypatch.setenv("SYNTH_PROGRESS", "0")                # off is off, in a notebook too
    quiet = io.StringIO()
    list(progress.progress(range(3), "x", stream=quiet))
    assert quiet.getvalue() == ""


def test_progress_terminal_bar_without_tqdm_and_tqdm_on_demand(monkeypatch):
    monkeypatch.delenv("SYNTH_PROGRESS", raising=False)
    tty = _Tty()
    list(progress.progress(range(4), "wear", stream=tty))
    assert "wear: [" in tty.getvalue() and "4/4" in tty.getvalue()     # synth's own bar on a terminal
    monkeypatch.setenv("SYNTH_PROGRESS", "tqdm")
    sink = io.StringIO()
    list(progress.progress(range(4), "wear", stream=sink))
    assert "100%" in sink.getvalue()
    monkeypatch.setitem(sys.modules, "tqdm.auto", None)                 # tqdm absent: no bar, no error
    none = io.StringIO()
    assert list(progress.progress(range(2), "x", stream=none)) == [0, 1] and none.getvalue() == ""


def test_write_report_of_a_result(synthesis, tmp_path):
    out = synth.write_report(synthesis, tmp_path / "rep", author="A. Engineer", pdf=False, cad_pictures=False)
    text = out["html"].read_text(encoding="utf-8")
    assert out["pdf"] is None and out["xlsx"].is_file() and "A. Engineer" in text
    assert out["result"].parts == synthesis.parts


def test_api_page_example_runs():
    page = ROOT / "docs" / "sections" / "api.md"
    failures, tried = doctest.testfile(str(page), module_relative=False, verbose=False,
                                       optionflags=doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE)
    assert tried >= 15 and failures == 0
