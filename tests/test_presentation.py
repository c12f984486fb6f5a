"""Presentation rules of issue 35, the same in every medium through :mod:`synth.formatting`: a yes/no check (a part
present or not, a supplier rated or not) reads ``yes``/``no`` with no limit and no margin; a margin against a zero
limit is the distance in the check's unit, not a percentage of nothing; numbers in plain notation; an absent part
``none``, not 0; the workbook's checks in the flowchart's step order.

Before (ab57224) the terminal printed ``bushing supplier rated for the application type: 1 >= 1 -  margin +0.0 %``,
``spring torque at nominal positive: 1.724 >= 0 Nm  margin +172.4 %``, ``Axial force [N] 2.284e+04`` and
``cone_spring_aspect_ratio 0``; the report and the workbook said the same in their own forms."""

from __future__ import annotations

import pytest

import synth
from synth import formatting as fmt
from synth.design.result import FAIL, Check
from synth.scenes.demo import default_input

#: the default case's optimum (synth design synth/data/default_case.yaml): no damper pad, so no cone spring
PARTS = {"ball_bearing": "6006", "pivot_class_diameter_mm": 20.0, "pivot_bushing_supplier": "B",
         "damper_pad_class": "none", "pivot_bushing_length_mm": 15.0, "endcap_spacer_class": "none",
         "cone_spring_aspect_ratio": 0.0, "cone_spring_deflection_ratio": 0.0, "cone_spring_external_diameter_mm": 0.0,
         "cone_spring_internal_diameter_mm": 0.0, "main_spring_material": "OTEVA91SC", "main_spring_wire": "F2.00x2.00",
         "main_spring_mean_body_diameter_mm": 33.0, "bolt_format": "M6x1", "bolt_head_type": "hex",
         "bolt_property_class": "12.9", "bolt_washer": "ISO 7089", "bolt_tightening": "torque_wrench_tested"}
#: the registry's yes/no checks that the default design evaluates
LOGICAL = ("bushing_rated", "spring_material_section", "axial_group_complete", "axial_group_matches_split",
           "axial_group_not_superfluous")


@pytest.fixture(scope="module")
def result():
    return synth.verify(default_input(), PARTS)


def _check(r, cid):
    return next(c for c in r.checks if c.id == cid)


def test_the_yes_no_checks_are_those_of_the_registry(result):
    found = {c.id for c in result.checks if c.value is not None and fmt.is_logical(c.constraint, c.value, c.limit)}
    assert found == set(LOGICAL)


def test_terminal_prints_yes_no_checks_as_yes_and_a_zero_limit_as_a_distance(result):
    from synth.report.text import render
    out = render(result)
    lines = {c.id: next(x for x in out.splitlines() if f" {c.constraint.label}: " in x) for c in result.checks
             if c.id in LOGICAL + ("spring_torque_positive",)}
    for cid in LOGICAL:
        assert lines[cid].split(f"{_check(result, cid).constraint.label}: ")[1].startswith("yes  ("), lines[cid]
        assert "margin" not in lines[cid] and ">=" not in lines[cid]
    torque = _check(result, "spring_torque_positive")
    assert torque.limit == 0.0 and torque.value == pytest.approx(1.7238, abs=1e-4)
    assert "1.724 >= 0 Nm  margin 1.724 Nm above the limit" in lines["spring_torque_positive"]
    assert "%" not in lines["spring_torque_positive"]
    assert "e+0" not in out and "e-0" not in out  # plain numbers (the bolt's axial force was 2.284e+04)
    design = out.split("Design (part keys)")[1].split("\n\n")[0]
    rows = dict(line.split(maxsplit=1) for line in design.splitlines()[2:] if line.strip())
    assert rows["cone_spring_aspect_ratio"] == rows["cone_spring_internal_diameter_mm"] == "none"  # not 0
    assert rows["damper_pad_class"] == "none" and "0" not in rows.values()


def test_a_failing_yes_no_check_says_no():
    c = Check("bushing_rated", 0.0, 1.0, -1.0, FAIL)
    assert fmt.check_relation(c) == "no" and fmt.check_margin(c) == "-"
    assert fmt.check_words(c) == "bushing supplier rated for the application type: no"


def test_report_rows_and_workbook_say_the_same(result):
    from synth.excel.results_workbook import build_results
    from synth.report.html import check_row
    row = check_row(_check(result, "bushing_rated"), result)
    assert (row["value"], row["sense"], row["limit"], row["unit"], row["margin"]) == ("yes", "", "", "", "-")
    row = check_row(_check(result, "spring_torque_positive"), result)
    assert (row["value"], row["limit"], row["margin"]) == ("1.724", "0", "1.724 Nm above the limit")
    ws = build_results(result)["Checks"]
    rows = [[c.value for c in r] for r in ws.iter_rows(min_row=5) if r[0].value is not None]
    steps = [r[0] for r in rows]
    assert steps == sorted(steps) and len(rows) >= 40  # the flowchart's step order
    by_label = {r[2]: r for r in rows}
    rated = by_label[_check(result, "bushing_rated").constraint.label]
    assert rated[3:8] == ["yes", None, None, None, None]  # value yes; no relation, limit, unit or margin
    torque = by_label[_check(result, "spring_torque_positive").constraint.label]
    assert torque[3] == pytest.approx(1.7238, abs=1e-4) and torque[5] == 0 and torque[7] == "1.724 Nm above the limit"
    assert isinstance(by_label[_check(result, "spring_yield").constraint.label][7], float)  # percent elsewhere


def test_shortfall_against_a_zero_limit_is_in_the_unit():
    from synth.design.constraints import REGISTRY
    from synth.report.advice import shortfall_of
    assert shortfall_of({"constraint": "spring_torque_positive", "margin": -0.5}) == "0.5 Nm"
    assert shortfall_of({"id": "under_head", "margin": -0.35216}) == "35.2 %"
    assert fmt.shortfall(REGISTRY["cone_force_band"], -0.2) == "20.0 %"  # a zero limit with a scale: percent


def test_sensitivity_figures_have_every_line_in_the_legend_and_the_design_point(result, monkeypatch):
    """Fig. 17-19: the dotted asymmetry ratio (on the right axis) was missing from the legend and the design's own
    value was not marked."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from synth.report import plots, thesis_graphs
    from synth.report.graph_data import Data, new_figure
    monkeypatch.setattr(thesis_graphs, "SWEEP_POINTS", 7)  # a coarse sweep: the legend, not the curve, is under test
    dt = Data(result, None)
    for gid, value in (("sensitivity_differential_angle", dt.need("differential_angle_deg")),
                       ("sensitivity_mu_pivot_bushing", dt.need("mu_pivot_bushing"))):
        fig, ax = new_figure(gid)
        plots.FUNCS[gid](dt, ax, "pass")
        labels = ax.get_legend_handles_labels()[1]
        assert "asymmetry ratio (right axis)" in labels and f"design point ({fmt.number(value)})" in labels, labels
        assert any(line.get_xdata()[0] == value for line in ax.lines if line.get_label() == labels[-1]
                   or line.get_marker() == "o")
        plt.close(fig)


def test_drive_figure_explains_its_line_styles_and_marks_the_durability_speed():
    """synth drive --plot: the dotted lines (each span's smallest tension) were unexplained and the durability speed
    unmarked. A small sweep of the shape synth.drive.analysis.analyse returns."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np
    from synth.report.plots import drive_figure
    speed = np.linspace(800.0, 6000.0, 5)
    res = {"name": "example", "spans": ["crank-tensioner", "tensioner-cam"], "slack": {"limit_n": 50.0},
           "durability": {"speed_rpm": 4500.0},
           "sweep": {"speed_rpm": speed, "theta_pp_deg": np.linspace(2.0, 6.0, 5),
                     "tension_min_n": np.full((5, 2), 200.0), "tension_max_n": np.full((5, 2), 600.0)}}
    fig = drive_figure(res)
    labels = [t.get_text() for ax in fig.axes for t in ax.get_legend().get_texts()]
    assert {"solid: largest tension", "dotted: smallest tension", "slack limit",
            "durability speed (4500 rpm)"} <= set(labels), labels
    plt.close(fig)


def test_a_graph_drawn_only_on_request_is_not_listed_as_not_drawn():
    """'Graphs not drawn: no Pareto front given' in a review document: the Pareto and solver graphs are drawn from a
    file the user gives; without one nothing is missing."""
    from synth.report.html import listed_skips
    from synth.report.plots import Skipped
    rows = listed_skips([Skipped("pareto", "Pareto front", "no Pareto front given (--pareto FILE ...)"),
                         Skipped("solvers", "Solvers", "no solver comparison given"),
                         Skipped("bushing_wear", "Pivot bushing wear", "a reason")])
    assert rows == [{"id": "bushing_wear", "title": "Pivot bushing wear", "reason": "a reason"}]


def test_the_production_scatter_table_is_in_percent_like_every_other():
    """The capability table printed margins as fractions (+0.134) beside percent everywhere else."""
    from synth.report.robust import text_lines
    robust = {"targets": "Ppk >= 1.33", "settings": {"samples": 256, "seed": 1}, "meets": False, "min_ppk": 0.2,
              "max_p_violation": 0.27, "failing": ["spring_fatigue"],
              "checks": [{"id": "spring_fatigue", "method": "monte carlo", "target": True, "nominal_margin": 0.0569,
                          "worst_case_margin": -0.0312, "rss_margin": 0.0105, "ppk": 0.2, "p_violation": 0.27,
                          "p_lo": 0.22, "p_hi": 0.33, "contributors": []}]}
    out = "\n".join(text_lines(robust))
    row = next(x for x in out.splitlines() if "spring_fatigue" in x and "+" in x)
    assert row.split()[1:4] == ["+5.7", "%", "-3.1"] and "27 % [22 %, 33 %]" in row
    assert "largest P(violation) 27 %" in out and "0.0569" not in out


def test_the_pivot_class_is_explained_beside_the_pivot_diameter_in_every_listing(result):
    """The pivot class (thesis Table 2, the arm's bore for a 1 mm bushing wall) is not the pivot's diameter: the
    default design's class 20 with the 0.5 mm bushing gives a 21 mm pivot (20 + 2 x (1 - 0.5)), and each listing of
    the parts says so (issue 35: "pivot class 17" beside "pivot diameter 18 mm" unexplained)."""
    from synth.report.html import render_html
    from synth.report.text import render
    from synth.ui.views import parts_table
    assert result.parts["pivot_class_diameter_mm"] == 20 and result.values["pivot_diameter_mm"] == 21
    note = "pivot diameter 21 mm = class + 2 x (1 mm - 0.5 mm bushing wall)"
    line = next(x for x in render(result).splitlines() if x.strip().startswith("pivot_class_diameter_mm"))
    assert line.split()[1] == "20" and note in line
    assert note in parts_table(result)
    assert note in render_html(result, [], [])
