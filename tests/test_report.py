"""The design report (HTML with the thesis graphs) and the results workbook (issue 6)."""

from __future__ import annotations

import base64
import html
import io
import math
import re

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st
from openpyxl import load_workbook

from types import SimpleNamespace

from conftest import CASES
from synth import cli
from synth.design.result import FAIL, NOT_APPLICABLE, NOT_VERIFIED, PASS, WARNING, Check, Result, row_verdict
from synth.output_table import ROWS
from synth import progress
from synth.report import plots
from synth.scenes.report import make_report

#: ``synth report INPUT --flowchart``: the thesis procedure's design (the default is the synthesis of synth design)
FLOWCHART = SimpleNamespace(flowchart=True, fidelity="full", linear_friction=False)

#: Graphs of the issue that apply to case 1 (axial damping, durability test, main spring, bolt all present).
CASE1_GRAPHS = ("hysteresis_load", "hysteresis_torque", "sensitivity_differential_angle",
                "sensitivity_mu_pivot_bushing", "sensitivity_mu_plastic", "bushing_wear", "pulley_parallelism",
                "damping_decay", "cone_spring_characteristic", "plastic_wear", "cone_spring_force_time",
                "cone_spring_tolerance_band", "goodman", "pivot_base_pressure")
AXIAL_GRAPHS = ("sensitivity_mu_plastic", "damping_decay", "cone_spring_characteristic", "plastic_wear",
                "cone_spring_force_time", "cone_spring_tolerance_band")


@pytest.fixture(scope="module")
def case1(tmp_path_factory):
    path = CASES / "case1.yaml"
    out = tmp_path_factory.mktemp("report1")
    pareto = [{"cost_eur": 3.1, "mass_g": 250.0}, {"cost_eur": 2.8, "mass_g": 270.0}, {"cost_eur": 2.5, "mass_g": 300.0}]
    solvers = [{"solver": "SLSQP", "cost_eur": 2.9, "time_s": 0.4}, {"solver": "NSGA-II", "cost_eur": 2.8, "time_s": 9.0}]
    r = make_report(path, out, FLOWCHART, scenes={"Pareto": pareto, "Solvers": solvers,
                                                  "Optimum": {"cost_eur": 2.8}}, show_progress=False)
    r["text"] = r["html"].read_text(encoding="utf-8")
    r["by_id"] = {g.id: g for g in r["graphs"]}
    return r


@pytest.fixture(scope="module")
def case3(tmp_path_factory):
    path = CASES / "case3.yaml"
    r = make_report(path, tmp_path_factory.mktemp("report3"), FLOWCHART, show_progress=False, cad_pictures=False)
    r["text"] = r["html"].read_text(encoding="utf-8")
    return r


def _figure_png(text: str, gid: str) -> bytes:
    m = re.search(rf'<figure id="fig-{gid}"[^>]*data-points="(\d+)">\s*<img[^>]*src="data:image/png;base64,([^"]+)"', text)
    assert m, f"graph {gid} missing from the HTML"
    assert int(m.group(1)) >= 2
    return base64.b64decode(m.group(2))


@pytest.mark.parametrize("gid", CASE1_GRAPHS + ("pareto", "solvers"))
def test_case1_graph_in_html_with_data(case1, gid):
    png = _figure_png(case1["text"], gid)
    assert png[:8] == b"\x89PNG\r\n\x1a\n" and len(png) > 5000       # a drawn picture, not a stub
    g = case1["by_id"][gid]
    assert g.series and all(np.all(np.isfinite(v)) and v.size >= 1 for v in g.series.values())
    assert max(v.size for v in g.series.values()) >= 2
    assert any(np.ptp(v) > 0 for v in g.series.values() if v.size > 1)   # curves that carry data


def test_html_is_self_contained(case1):
    text = case1["text"]
    assert text.startswith("<!DOCTYPE html>") and "</html>" in text
    assert not re.search(r'src="(?!data:)', text) and "<link" not in text
    for h in ("digest", "metadata", "output", "checks", "graphs", "inputs"):
        assert f'id="{h}"' in text
    # every check that applies, with its label and verdict
    for c in case1["result"].checks:
        if c.verdict != NOT_APPLICABLE:
            assert f'data-check="{c.id}" data-verdict="{html_escape(c.verdict)}">' in text
            assert c.label in html.unescape(text)  # (Jinja2 escapes an apostrophe as &#39;)
    assert "Verdict: FAIL" in text
    # the 3D model's pictures (exploded and section) are embedded
    assert {"cad_1", "cad_2"} <= set(case1["by_id"])
    for gid in ("cad_1", "cad_2"):
        m = re.search(rf'<figure id="fig-{gid}"[^>]*>\s*<img[^>]*src="data:image/png;base64,([^"]+)"', text)
        assert m and base64.b64decode(m.group(1))[:8] == b"\x89PNG\r\n\x1a\n"


def html_escape(s):
    import html
    return html.escape(s, quote=True)


def test_hysteresis_reproduces_the_design_split(case1):
    # At nominal (theta = 0) the cycle's mean is the calculated torque target and its half-width the
    # damping target: by construction of the step-3 split (eq. (12)-(13)), T_c = 3.25 Nm, D = 2.00 Nm (Table 9).
    g = case1["by_id"]["hysteresis_torque"].series
    i = int(np.argmin(np.abs(g["theta_deg"])))
    assert g["theta_deg"][i] == 0.0
    assert (g["torque_loading_nm"][i] + g["torque_unloading_nm"][i]) / 2 == pytest.approx(3.25, rel=1e-9)
    assert (g["torque_loading_nm"][i] - g["torque_unloading_nm"][i]) / 2 == pytest.approx(2.00, rel=1e-9)
    # torque = hubload * lever, lever = e_w sin(alpha) = 5 mm * sin(85 deg) = 4.98097 mm (eq. (7))
    load = case1["by_id"]["hysteresis_load"].series
    lever_m = 5.0 * math.sin(math.radians(85.0)) / 1000.0
    assert load["hubload_loading_n"][i] * lever_m == pytest.approx(g["torque_loading_nm"][i], rel=1e-9)
    # loading above unloading everywhere (a hysteresis cycle)
    assert np.all(load["hubload_loading_n"] > load["hubload_unloading_n"])


def test_sensitivity_without_bushing_friction_leaves_the_axial_damping(case1):
    # mu_pb = 0: no radial damping, the damping is the axial one alone (1.713 Nm for case 1, D - T_c rho)
    s = case1["by_id"]["sensitivity_mu_pivot_bushing"].series
    assert s["values"][0] == 0.0
    assert s["damping_nm"][0] == pytest.approx(case1["result"].values["axial_damping_nm"], rel=1e-9)
    assert np.all(np.diff(s["damping_nm"]) > 0)          # more friction, more damping
    p = case1["by_id"]["sensitivity_mu_plastic"].series  # eq. (9): D_ax proportional to mu_plastic
    assert np.all(np.diff(p["damping_nm"]) > 0)


def test_time_graphs_end_at_the_flowchart_values(case1):
    v = case1["result"].values
    w = case1["by_id"]["bushing_wear"].series
    assert w["time_h"][0] == 0.0 and w["time_h"][-1] == pytest.approx(1200.0)
    assert w["wear_max_mm"][0] == 0.0
    assert w["wear_max_mm"][-1] == pytest.approx(v["pivot_bushing_wear_max_mm"], rel=1e-6)
    par = case1["by_id"]["pulley_parallelism"].series
    assert par["parallelism_mm"][-1] == pytest.approx(v["pivot_bushing_parallelism_mm"], rel=1e-6)
    assert par["limit_mm"][0] == 0.3                      # Table 9: max parallelism at EOL
    d = case1["by_id"]["damping_decay"].series
    assert d["damping_nm"][0] == pytest.approx(2.0, rel=1e-3)   # damping at new = target (step 3 split)
    assert np.all(np.diff(d["damping_nm"]) <= 1e-12)             # decays with wear
    assert d["limit_nm"][0] == 1.5                               # Table 9: EOL limit
    f = case1["by_id"]["cone_spring_force_time"].series["cone_spring_force_n"]
    assert np.all(np.diff(f) <= 1e-9) and f[-1] < f[0]


def test_cone_spring_graphs(case1):
    v = case1["result"].values
    band = case1["by_id"]["cone_spring_tolerance_band"].series
    assert band["fax_min_tolerance_n"][0] == pytest.approx(v["cone_spring_fax_min_tolerance_n"])
    assert band["fax_max_tolerance_n"][0] == pytest.approx(v["cone_spring_fax_max_tolerance_n"])
    ch = case1["by_id"]["cone_spring_characteristic"].series
    assert ch["force_n"][0] == 0.0 and ch["deflection_mm"][-1] == pytest.approx(v["cone_spring_cone_height_mm"])
    # the nominal working point lies on the characteristic and inside the tolerance band
    f_n = ch["nominal_force_n"][0]
    assert band["fax_min_tolerance_n"][0] <= f_n <= band["fax_max_tolerance_n"][0]


def test_goodman_and_pivot_base_pressure(case1):
    v = case1["result"].values
    g = case1["by_id"]["goodman"].series
    assert g["safety_factor"][0] == pytest.approx(v["main_spring_safety_factor"], rel=1e-3)
    assert list(g["working_range_mpa"]) == pytest.approx([v["main_spring_sigma_a_min_mpa"],
                                                          v["main_spring_sigma_a_max_mpa"]])
    p = case1["by_id"]["pivot_base_pressure"].series
    # full annulus: p = F/A + M r / I cos(angle): the mean over the circle is the average pressure F/A
    assert np.mean(p["pressure_nominal_mpa"][:-1]) == pytest.approx(v["average_contact_pressure_mpa"], rel=1e-6)
    assert np.max(p["pressure_worst_mpa"]) == pytest.approx(v["pivot_base_max_pressure_mpa"], rel=1e-6)
    assert np.min(p["pressure_worst_mpa"]) > 0            # no lift-off: tilting verified (green)
    assert case1["by_id"]["pivot_base_pressure"].verdict == PASS


def test_results_workbook_output_table_with_verdict_colours(case1):
    wb = load_workbook(case1["xlsx"])
    assert wb.sheetnames[:4] == ["Output", "Checks", "Input", "Notes"]
    assert {"Optimum", "Pareto", "Solvers"} <= set(wb.sheetnames)
    ws = wb["Output"]
    assert [c.value for c in ws[4]] == ["Section", "Parameter", "Unit", "Value", "Verdict", "Suggested correction"]
    result = case1["result"]
    seen = set()
    for i, (section, label, key, unit) in enumerate(ROWS, start=5):
        assert ws[f"B{i}"].value == label and ws[f"C{i}"].value == unit
        verdict = ws[f"E{i}"].value
        assert verdict == row_verdict(result, key)
        seen.add(verdict)  # its colour: a conditional format (tests/test_workbooks.py, evaluated by LibreOffice)
    assert {PASS, FAIL} <= seen
    assert ws["D6"].value == pytest.approx(20.0)          # pulley width, case 1 Table 10
    # the echo of the data read
    inp = wb["Input"]
    echo = {inp[f"B{r}"].value: inp[f"E{r}"].value for r in range(5, inp.max_row + 1)}
    assert echo["differential_angle_deg"] == 85 and echo["application_type"] == "belt_in_oil"


def test_failed_check_gets_red_and_its_correction(case1):
    failed = case1["result"].failed()
    assert failed   # case 1 (printed): the flowchart's spring and the under-head pressure fail
    wb = load_workbook(case1["xlsx"])
    ws = wb["Checks"]
    rows = {ws[f"C{r}"].value: r for r in range(5, ws.max_row + 1)}
    for c in failed:
        r = rows[c.label]
        assert ws[f"I{r}"].value == FAIL  # red by conditional format: tests/test_workbooks.py
        assert ws[f"K{r}"].value == c.constraint.correction


def test_case3_skips_the_axial_graphs_with_the_reason(case3):
    ids = {g.id for g in case3["graphs"]}
    skipped = {s.id: s.reason for s in case3["skipped"]}
    for gid in AXIAL_GRAPHS:
        assert gid not in ids and "no axial damping" in skipped[gid]
        assert f'id="skip-{gid}"' in case3["text"]
    assert {"hysteresis_load", "hysteresis_torque", "bushing_wear", "pivot_base_pressure"} <= ids
    # no axial group: the cone spring's checks do not apply (the Output rows: test_case3_cone_rows_...)
    assert all(case3["result"].check(c).verdict == NOT_APPLICABLE for c in ("cone_force_band", "cone_sigma_om"))


def test_case3_cone_rows_are_not_applicable(case3):
    ws = load_workbook(case3["xlsx"])["Output"]
    cone = [(ws[f"D{i}"].value, ws[f"E{i}"].value) for i, row in enumerate(ROWS, start=5) if row[0] == "Cone spring"]
    assert cone and all(v is None and verdict in (None, NOT_APPLICABLE) for v, verdict in cone)


def test_report_from_the_excel_template(tmp_path):
    xlsx = tmp_path / "in.xlsx"
    assert cli.main(["template", str(xlsx)]) == 0
    out = tmp_path / "rep"
    rc = cli.main(["report", str(xlsx), "--out", str(out), "--flowchart", "--no-cad"])
    # the template's example is case 1 as run: the flowchart's design fails step 9 (exit code 1)
    assert rc == 1 and (out / "report.html").is_file()
    inp = load_workbook(out / "results.xlsx")["Input"]
    cells = {inp[f"B{r}"].value: inp[f"F{r}"].value for r in range(5, inp.max_row + 1)}
    assert re.fullmatch(r"E\d+", cells["differential_angle_deg"])


def test_report_shows_the_design_of_synth_design(tmp_path, capsys):
    # one synthesis for every scene (issue 11): synth report INPUT reports the design synth design INPUT finds,
    # and a saved --json reports that same design
    import json
    import yaml
    from synth.data.generated_applications import generate
    app = generate(2, seed=0)[1]
    path = tmp_path / "app.yaml"
    path.write_text(yaml.safe_dump({"inputs": {k: v for k, v in app.as_dict().items() if v is not None}}))
    code = cli.main(["design", str(path), "--json"])
    saved = tmp_path / "design.json"
    saved.write_text(capsys.readouterr().out)
    design = json.loads(saved.read_text())
    for source in (path, saved):
        rep = make_report(source, tmp_path / source.stem, show_progress=False, cad_pictures=False)
        assert rep["result"].parts == design["parts"] and rep["result"].exit_code == code


def test_graphs_tolerate_missing_values(case1):
    r = case1["result"]
    stripped = Result(r.status, parts=dict(r.parts), values={k: v for k, v in r.values.items()
                                                             if not k.startswith("bolt_")},
                      inputs=r.inputs, settings=r.settings)
    with pytest.raises(LookupError, match="bolt_axial_force_n missing"):
        plots.graph_png("pivot_base_pressure", stripped)
    g = plots.graph_png("hysteresis_load", stripped)
    assert g.series["theta_deg"].size > 2


def test_cli_report_bad_input_exits_2(tmp_path, capsys):
    bad = tmp_path / "bad.yaml"
    bad.write_text("inputs: {working_arm_mm: -1}\n")
    assert cli.main(["report", str(bad), "--out", str(tmp_path / "o")]) == 2
    assert "working_arm_mm" in capsys.readouterr().err


class _Tty(io.StringIO):
    def isatty(self):
        return True


def test_progress_bar_on_tty_quiet_when_piped(monkeypatch):
    monkeypatch.delenv("SYNTH_PROGRESS", raising=False)
    tty, pipe = _Tty(), io.StringIO()
    assert list(progress.progress(range(4), "wear", stream=tty)) == [0, 1, 2, 3]
    assert "wear: [" in tty.getvalue() and "4/4" in tty.getvalue()
    assert list(progress.progress(range(4), "wear", stream=pipe)) == [0, 1, 2, 3]
    assert pipe.getvalue() == ""
    monkeypatch.setenv("SYNTH_PROGRESS", "0")
    quiet = _Tty()
    list(progress.progress(range(3), "x", stream=quiet))
    assert quiet.getvalue() == ""


@settings(max_examples=40, deadline=None)
@given(n=st.integers(0, 500), total=st.one_of(st.none(), st.integers(1, 100)))
def test_progress_never_raises(n, total):
    tty = _Tty()
    with progress.Progress(total, "x", stream=tty, min_interval_s=0.0) as bar:
        for _ in range(n):
            bar.update(1)
    assert bar.n == n


_ROW_CHECKS = {PASS: ("spring_yield", 1500.0, 1743.0, 0.14), FAIL: ("spring_yield", 1800.0, 1743.0, -0.03),
               NOT_VERIFIED: ("spring_fatigue", None, None, None), NOT_APPLICABLE: ("spring_yield", None, None, None),
               WARNING: ("cone_thinness_max", 43.0, 42.0, -0.02)}


@given(value=st.one_of(st.none(), st.floats(allow_nan=True), st.text(max_size=5)),
       verdicts=st.lists(st.sampled_from(sorted(_ROW_CHECKS)), max_size=4))
def test_row_verdict_is_the_worst_of_the_checks_that_read_the_row(value, verdicts):
    # the main spring's installation stress row: read by spring_yield (its value), not by spring_fatigue
    key = "main_spring_sigma_inst_mpa"
    checks = [Check(*_ROW_CHECKS[v][:4], v) for v in verdicts]
    out = row_verdict(Result("verified", values={key: value}, checks=checks), key)
    assert out in (PASS, FAIL, NOT_VERIFIED, WARNING, NOT_APPLICABLE, None)
    readers = [v for v in verdicts if _ROW_CHECKS[v][0] == "spring_yield"]
    mine = [v for v in readers if v != NOT_APPLICABLE]
    if value is None or (isinstance(value, float) and not math.isfinite(value)):   # NaN/inf count as missing
        # missing where every check reading it does not apply: the design has no such value
        assert out == (NOT_APPLICABLE if readers and not mine else NOT_VERIFIED)
    elif FAIL in mine:
        assert out == FAIL
    elif not mine:
        assert out is None          # no check reads the row: no colour
    else:
        assert out == PASS
