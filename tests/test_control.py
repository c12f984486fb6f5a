"""The engineer in control (issue 23), end to end through the command line: the parts an input names kept or each
change named with why, --fix/--free/--pin-inputs for every part and solver, relaxations by who controls them,
--top K, design rules, units and words, progress, the report and the workbooks, the core install."""

from __future__ import annotations

import json
import math
import os
import re
import subprocess
import sys
from pathlib import Path

import pytest
import yaml

from synth.cli import main
from synth.data import CASES_DIR

ROOT = Path(__file__).resolve().parents[1]
DEFAULT = ROOT / "synth" / "data" / "default_case.yaml"
MANUAL = {"main_spring_mode": "manual", "main_spring_material": "VDSiCr", "main_spring_wire_section": "round",
          "main_spring_wire_size_mm": [3.0], "main_spring_mean_body_diameter_mm": 44.0,
          "bolt_mode": "manual", "bolt_format": "M8x1.25", "bolt_property_class": "8.8"}


def _inputs(path=DEFAULT) -> dict:
    return dict(yaml.safe_load(Path(path).read_text())["inputs"])


def _write(tmp_path, name, inputs, rules=None) -> str:
    doc = {"name": name, "inputs": inputs}
    if rules is not None:
        doc["rules"] = rules
    p = tmp_path / f"{name}.yaml"
    p.write_text(yaml.safe_dump(doc, sort_keys=False))
    return str(p)


def _run(capsys, *argv):
    code = main([str(a) for a in argv])
    out = capsys.readouterr()
    return code, out.out, out.err


def _json(capsys, *argv):
    code, out, err = _run(capsys, *argv, "--json")
    return code, json.loads(out)


# ----------------------------------------------------------------------------------------------- inputs honoured
@pytest.fixture(scope="module")
def default_json():
    """``synth design default_case.yaml --top 3 --json`` (one synthesis shared by the tests that read it)."""
    import io
    from contextlib import redirect_stdout
    buf = io.StringIO()
    with redirect_stdout(buf):
        code = main(["design", str(DEFAULT), "--top", "3", "--json"])
    return code, json.loads(buf.getvalue())


def test_default_case_names_each_part_it_does_not_keep_and_why(default_json, capsys, tmp_path):
    code, r = default_json
    assert code == 0 and r["verdict"] == "pass"
    # the default case's pivot class 20 and bushing thickness are kept (its damping meets the band with the dry
    # friction 0.10, issue 34); asked for class 26, the arm wall fails: freed, with the reason and the way back
    assert r["changes"] == []
    assert r["control"]["kept_when_possible"] == ["pivot_class_diameter_mm", "pivot_bushing_radial_thickness_mm"]
    code, r = _json(capsys, "design", _write(tmp_path, "pc26", {**_inputs(), "pivot_class_diameter_mm": 26}))
    assert [(c["field"], c["input"], c["design"], c["how"]) for c in r["changes"]] == \
        [("pivot_class_diameter_mm", 26.0, 19.0, "freed: no design keeps it")]
    assert "arm wall on the eccentric side by 50.0 %" in r["changes"][0]["why"]
    assert "--fix pivot_class_diameter_mm" in r["changes"][0]["why"]
    code, out, _ = _run(capsys, "design", DEFAULT)
    assert "kept as the input names: pivot_class_diameter_mm, pivot_bushing_radial_thickness_mm" in out


def test_case3_at_its_own_travel_honours_or_names_every_input_part(tmp_path, capsys):
    ins = {**_inputs(CASES_DIR / "case3.yaml"), "arm_travel_nominal_to_installation_deg": 28.6}
    code, r = _json(capsys, "design", _write(tmp_path, "case3_own_travel", ins))
    from synth.design.space import design_inputs, same_input
    have = design_inputs(r["parts"])
    named = [n for n in ("pivot_class_diameter_mm", "pivot_bushing_radial_thickness_mm") if ins.get(n) is not None]
    changed = {c["field"] for c in r["changes"]}
    for n in named:  # kept, or a digest line says so
        assert same_input(ins[n], have[n]) or n in changed, n
    assert all(c["why"] for c in r["changes"])


def test_fix_keeps_the_part_whatever_the_verdict_and_free_frees_it(capsys, tmp_path):
    pc26 = _write(tmp_path, "pc26", {**_inputs(), "pivot_class_diameter_mm": 26})  # the arm wall fails at 26
    code, r = _json(capsys, "design", pc26, "--fix", "pivot_class_diameter_mm")
    assert code == 1 and r["status"] == "infeasible" and r["parts"]["pivot_class_diameter_mm"] == 26.0
    assert r["control"]["fixed"] == ["pivot_class_diameter_mm"]
    # the bushing thickness it names is only kept when possible: no design passes either way, so it is freed, said so
    assert [(c["field"], c["how"]) for c in r["changes"]] in (
        [], [("pivot_bushing_radial_thickness_mm", "freed: no design passes either way")])
    # the diagnosis keeps it too; its relaxations never propose another pivot class
    assert all("pivot_class_diameter_mm" not in x["inputs"] for x in r["diagnosis"]["relaxations"])
    code, r = _json(capsys, "design", pc26, "--free", "pivot_class_diameter_mm")
    assert code == 0 and [c["how"] for c in r["changes"]] == ["free"]
    code, out, err = _run(capsys, "design", DEFAULT, "--fix", "pivot_clas_diameter_mm")
    assert code == 2 and "did you mean pivot_class_diameter_mm" in err
    code, out, err = _run(capsys, "design", DEFAULT, "--fix", "bolt_format")
    assert code == 2 and "bolt_format" in err and "gives a value" in err
    code, out, err = _run(capsys, "design", DEFAULT, "--fix", "pivot_class_diameter_mm", "--free",
                          "pivot_class_diameter_mm")
    assert code == 2 and "--free" in err


@pytest.mark.parametrize("solver", ["enumerate", "minlp"])
def test_pin_inputs_keeps_a_manual_spring_and_bolt_for_every_solver(tmp_path, capsys, solver):
    path = _write(tmp_path, "manual", {**_inputs(), **MANUAL})
    code, r = _json(capsys, "design", path, "--pin-inputs", "--solver", solver)
    p = r["parts"]
    assert (p["pivot_class_diameter_mm"], p["main_spring_material"], p["main_spring_wire"],
            p["main_spring_mean_body_diameter_mm"], p["bolt_format"], p["bolt_property_class"]) == \
        (20.0, "VDSiCr", "R3.00", 44.0, "M8x1.25", "8.8")
    assert code == 1 and r["changes"] == []  # kept, and the 3.0 mm wire at 44 mm fails: said so, not replaced


def test_a_manual_spring_is_kept_unless_no_design_with_it_passes(tmp_path, capsys):
    path = _write(tmp_path, "manual", {**_inputs(), **MANUAL})
    code, r = _json(capsys, "design", path)
    assert code == 0
    fields = {c["field"] for c in r["changes"]}
    assert {"main_spring_material", "main_spring_mean_body_diameter_mm"} <= fields
    assert not fields & {"bolt_format", "bolt_property_class"}  # the bolt it names passes: kept
    assert (r["parts"]["bolt_format"], r["parts"]["bolt_property_class"]) == ("M8x1.25", "8.8")
    spring = next(c for c in r["changes"] if c["field"] == "main_spring_mean_body_diameter_mm")
    assert "main spring coil gap" in spring["why"]


# ----------------------------------------------------------------------------------------------- relaxations
def test_belt_in_oil_says_no_designer_change_and_what_to_ask_for_with_units(tmp_path, capsys, monkeypatch):
    _synthesise_once(monkeypatch, _SHARED)  # the JSON and the text render one synthesis
    from synth.report.advice import NO_DESIGNER
    path = _write(tmp_path, "belt_in_oil", {**_inputs(), "application_type": "belt_in_oil"})
    code, r = _json(capsys, "design", path)
    assert code == 1
    first = r["diagnosis"]["relaxations"][0]
    assert first["owner"] == "specification"  # no relaxation of the designer's inputs exists (all were tried)
    assert first["inputs"]["spring_stiffness_nm_per_deg"]["unit"] == "Nm/deg"
    code, out, _ = _run(capsys, "design", path)
    assert NO_DESIGNER in out
    assert re.search(r"ask for spring_stiffness_nm_per_deg 0\.03\d+ Nm/deg instead of 0\.0164 \(\+\d+\.\d %\)", out)
    # every failing spring check's correction agrees with the catalog search: no other spring is offered (the
    # search's summary is the diagnosis's)
    assert "a smaller mean diameter" not in out and "every catalog main spring material" in out


def test_case1_gets_a_combined_relaxation_of_two_inputs_designer_first(capsys, monkeypatch):
    _synthesise_once(monkeypatch, _SHARED)  # the JSON and the text render one synthesis
    from synth.report.advice import NO_DESIGNER
    code, r = _json(capsys, "design", CASES_DIR / "case1.yaml")
    rel = r["diagnosis"]["relaxations"]
    assert code == 1 and rel and all(len(x["inputs"]) == 2 for x in rel)  # no single input suffices
    owners = [x["owner"] for x in rel]
    assert owners == sorted(owners, key=lambda o: o != "designer")  # the designer's first
    code, out, _ = _run(capsys, "design", CASES_DIR / "case1.yaml")
    if rel[0]["owner"] != "designer":
        assert NO_DESIGNER in out
    assert "change bolt_head_contact_external_diameter_mm 11 -> " in out and " mm (+" in out


def test_case1_advice_never_contradicts_itself(capsys, monkeypatch):
    _synthesise_once(monkeypatch, _SHARED)  # case 1's synthesis, shared with the test above
    # issue 35: case 1 printed "no change the tensioner designer controls ... makes a design feasible; ask ... for
    # one of:" followed by "change bolt_head_contact_external_diameter_mm ... and ask for spring_stiffness ...", and
    # a "suggested correction" that reported the search ("every catalog bolt format ... was tried ...")
    from synth.report.advice import ASK_SPECIFICATION, NO_DESIGNER, TOGETHER
    code, out, _ = _run(capsys, "design", CASES_DIR / "case1.yaml")
    diagnosis = out.split("\nDiagnosis\n", 1)[1].split("\n\n", 1)[0].splitlines()
    feasible = [x.strip() for x in diagnosis if x.strip().startswith("feasible if you")]
    assert code == 1 and feasible
    for line in feasible:  # the designer's change and the specification's never in one sentence
        for sentence in line.split(". "):
            assert not ("change " in sentence and "ask for" in sentence.lower()), sentence
            assert not ("change " in sentence and "Ask the specification" in sentence), sentence
    text = [x.strip() for x in diagnosis]
    if NO_DESIGNER in text:  # no designer-alone change exists: every relaxation listed after it says what to ask for
        after = text[text.index(NO_DESIGNER) + 1:]
        assert after[0] in (ASK_SPECIFICATION, TOGETHER)
        assert all("Ask the specification for " in x or x.startswith("feasible if you ask for ") for x in after
                   if x.startswith("feasible if you"))
    assert re.search(r"every catalog bolt format, bolt head type, bolt property class(, [a-z ]+)* was tried",
                     out.split("\nDiagnosis\n")[1])  # the washer and the tightening method are bolt options too
    corrections = [x.split("suggested correction: ", 1)[1] for x in out.splitlines() if "suggested correction: " in x]
    assert corrections and not any(c.startswith("every catalog") or "was tried" in c for c in corrections)
    # the under-head pressure's correction is the relaxation that relaxes it, in two sentences
    assert re.search(r"under-head pressure.*\n +suggested correction: change bolt_head_contact_external_diameter_mm "
                     r"11 -> 12\.0\d mm \(\+\d+\.\d %\)\. Ask the specification for spring_stiffness_nm_per_deg", out)


def test_relaxation_candidates_and_owners_are_declared_once_on_the_fields():
    from synth import schema
    from synth.design.constraints import REGISTRY
    from synth.optimise.diagnose import relaxable
    rel = relaxable()
    assert list(rel) == [f.name for f in schema.FIELDS if f.relax]   # direction and owner: the fields'
    assert rel["max_pivot_height_mm"][:2] == (1, ("spring_cavity", "bushing_p", "bushing_pv", "bushing_pvt",
                                                  "bushing_wear", "bushing_parallelism", "bushing_length",
                                                  "belt_plane", "spring_coil_gap"))
    assert rel["tilting_safety_factor"] == (-1, ("bolt_yield", "under_head", "thread", "pivot_base_pressure"), True)
    for name, (_, ids, spec) in rel.items():   # what a field relaxes: the registry's relaxed_by
        assert ids and all(name in REGISTRY[i].relaxed_by for i in ids)
        assert spec == (schema.field_by_name(name).owner == "specification")
    assert schema.field_by_name("spring_stiffness_nm_per_deg").owner == "specification"
    assert schema.field_by_name("max_pivot_height_mm").owner == "designer"
    assert schema.PART_FIELDS[:2] == ("pivot_class_diameter_mm", "pivot_bushing_radial_thickness_mm")


# ----------------------------------------------------------------------------------------------- --top K
def test_top_k_lists_the_best_designs_in_objective_order(default_json, capsys, tmp_path):
    code, r = default_json
    alts = r["alternatives"]
    assert [a["rank"] for a in alts] == [1, 2, 3]
    assert alts[0]["parts"] == r["parts"] and alts[0]["differs"] == {}
    keys = [(a["objectives"]["standard"], a["objectives"]["cost"]) for a in alts]
    assert keys == sorted(keys)  # objective order (standard, then cost)
    assert all(a["differs"] and a["verdict"] == "pass" and 0 <= a["margin"] < 1 for a in alts[1:])
    for a in alts[1:]:
        for k, (first, this) in a["differs"].items():
            assert alts[0]["parts"][k] == first and a["parts"][k] == this
    code, out, _ = _run(capsys, "design", DEFAULT, "--top", "2")
    assert "Alternatives: the 2 best distinct designs in objective order" in out and "#2" in out
    code, out, err = _run(capsys, "design", DEFAULT, "--top", "0")
    assert code == 2 and "--top" in err


def test_top_k_in_the_python_api_and_the_report(tmp_path):
    import synth
    from synth.scenes.report import make_report
    r = synth.synthesise(str(DEFAULT), top=2)
    assert len(r.alternatives) == 2 and r.alternatives[0]["parts"] == r.parts
    rep = make_report(r, tmp_path, show_progress=False, cad_pictures=False, pdf=False,
                      source_name=str(DEFAULT), application="default (thesis case 3, completed)")
    html = rep["html"].read_text()
    assert 'id="alternatives"' in html and 'data-rank="2"' in html
    assert "<title>synth design report: default (thesis case 3, completed) - default_case.yaml</title>" in html
    assert "Application</th><td>default (thesis case 3, completed)" in html
    assert "Parts the input names" in html  # the digest's change lines survive the report's re-verification


# ----------------------------------------------------------------------------------------------- design rules
RULES = {"name": "ACME tensioner rules rev. C", "limits": {"main_spring_min_safety_factor": 1.25},
         "min_margins": {"spring_yield": "3 %"}, "capability": {"ppk_min": 1.33}}


#: the syntheses the diagnosis tests share (case 1 and the belt in oil: each 3-5 s of CPU, rendered as JSON and text)
_SHARED: dict = {}


def _synthesise_once(monkeypatch, memo: dict | None = None) -> list:
    """Make the scenes' synthesis (``solve_honouring``) compute each distinct call once in this test (or once in
    the tests given the same ``memo``) and hand a copy of the result to the later ones (the robust synthesis of a
    rules file costs seconds; the JSON, the text and the report render the same one). Returns the list of calls
    computed."""
    import copy

    from synth.scenes import _options
    real, memo, computed = _options.solve_honouring, ({} if memo is None else memo), []

    def once(d, objective, solver, **kw):
        key = repr((d, objective, solver, sorted((k, v) for k, v in kw.items() if k != "robust"), "robust" in kw))
        if key not in memo:
            computed.append(key)
            memo[key] = real(d, objective, solver, **kw)
        return copy.deepcopy(memo[key])
    monkeypatch.setattr(_options, "solve_honouring", once)
    return computed


def test_rules_section_is_applied_and_echoed_everywhere(tmp_path, capsys, monkeypatch):
    computed = _synthesise_once(monkeypatch)
    path = _write(tmp_path, "ruled", _inputs(), RULES)
    # 1,024 production samples, not 8,192: the verdict (no design reaches Ppk 1.33) is far from the target
    code, r = _json(capsys, "design", path, "--samples", "1024")
    assert r["rules"]["name"] == "ACME tensioner rules rev. C"
    # the rules' capability target (Ppk >= 1.33) makes the synthesis the robust one; no catalog design meets it
    assert "1.33" in r["robust"]["targets"] and r["robust"]["meets"] is False and code == 1
    fat, yld = (next(c for c in r["checks"] if c["id"] == k) for k in ("spring_fatigue", "spring_yield"))
    assert fat["limit"] == 1.25 and fat["value"] >= 1.25  # the company's safety factor, not the catalog's 1.2
    physical = (yld["limit"] - yld["value"]) / yld["limit"]
    assert yld["required_margin"] == 0.03 and yld["margin"] == pytest.approx(physical - 0.03, abs=2e-6)
    assert yld["margin"] >= 0
    code, out, _ = _run(capsys, "design", path, "--samples", "1024")
    assert "design rules: ACME tensioner rules rev. C" in out and "minimum margin spring_yield: 3 %" in out
    assert "beyond the required 3 %" in out
    code, out, _ = _run(capsys, "report", path, "--out", tmp_path / "rep", "--no-pdf", "--no-cad", "--samples", "1024")
    html = (tmp_path / "rep" / "report.html").read_text()
    assert "Design rules</th><td>design rules: ACME tensioner rules rev. C" in html
    assert len(computed) == 1  # the design's JSON, its text and the report: one robust synthesis
    # a rules file given on the command line; a bad key is named
    bad = tmp_path / "bad_rules.yaml"
    bad.write_text("min_margins:\n  spring_yld: 0.05\n")
    code, out, err = _run(capsys, "design", DEFAULT, "--rules", bad)
    assert code == 2 and "rules.min_margins.spring_yld" in err.replace("bad_rules.yaml", "rules")
    bad.write_text("limits:\n  main_spring_min_safety_factor: 1.1\n")  # looser than the catalog's 1.2: refused
    code, out, err = _run(capsys, "design", DEFAULT, "--rules", bad)
    assert code == 2 and "at least the catalog's 1.2" in err


def test_rules_change_the_design_in_every_solver_and_the_flowchart(tmp_path, capsys):
    strict = tmp_path / "strict.yaml"
    strict.write_text(yaml.safe_dump({"rules": {"name": "strict", "min_margins": {"spring_coil_gap": 0.2}}}))
    code, r = _json(capsys, "design", DEFAULT, "--rules", strict)
    gap = next(c for c in r["checks"] if c["id"] == "spring_coil_gap")
    assert gap["required_margin"] == 0.2 and (gap["margin"] >= 0 or r["verdict"] == "fail")
    code, f = _json(capsys, "flowchart", DEFAULT, "--rules", strict)
    assert f["rules"]["name"] == "strict"


# ----------------------------------------------------------------------------------------------- units and words
def test_objective_line_has_units_and_exports_have_six_significant_figures(default_json, capsys):
    code, r = default_json

    nums = [v for c in r["checks"] for v in (c["value"], c["limit"], c["margin"]) if isinstance(v, float)]
    nums += [v for v in r["values"].values() if isinstance(v, float)]
    assert len(nums) > 100 and all(float(f"{x:.6g}") == x for x in nums)  # 6 significant figures at most
    code, out, _ = _run(capsys, "design", DEFAULT)
    # the supplier's friction (0.10) and the M6 head on its ISO 7089 washer (issue 34), priced by synth.cost: bearing
    # 1.1 + bushing B 15 0.2922 + spring OTEVA91SC F2x2 Dm 33 0.3030 + bolt M6 hex 12.9 0.0461 + washer 0.0030
    # a margin on its limit (round-off of zero) reads 0.0 % (synth.formatting.percent: one form for every medium)
    assert "objectives: non-standard parts 2 (weighted count), cost 1.744 EUR, smallest margin 0.0 %" in out
    from synth.bulk.portfolio import CSV_FLOAT, write_table
    import pandas as pd
    df = pd.DataFrame({"margin": [1 / 3]})
    tmp = Path(os.environ.get("TMPDIR", "/tmp"))
    assert write_table(df, tmp / "synth_sig.csv", float_format=CSV_FLOAT).read_text().splitlines()[1] == "0.333333"
    # a portfolio of inputs keeps every digit (read back exactly)
    assert write_table(df, tmp / "synth_all.csv").read_text().splitlines()[1] == repr(1 / 3)


def test_a_stiffness_typed_in_nm_per_rad_is_named(tmp_path, capsys):
    path = _write(tmp_path, "rad", {**_inputs(), "spring_stiffness_nm_per_deg": 0.94})
    code, out, _ = _run(capsys, "flowchart", path)
    assert ("spring_stiffness_nm_per_deg = 0.94 Nm/deg is outside the usual 0.005-0.1 Nm/deg; as Nm/rad it would "
            "be 0.01641 Nm/deg: check the unit") in out


def test_plots_label_constraints_in_words_and_margins_in_percent(tmp_path, capsys, monkeypatch):
    from synth.bulk import summary as S
    from synth.optimise import pareto
    labels = []
    monkeypatch.setattr(S, "_bar", lambda ax, lab, values, title, xlabel: labels.extend(lab))
    table = __import__("pandas").DataFrame({
        "status": ["optimal", "infeasible"], "feasible": [True, False], "application_type": ["dry", "dry"],
        "binding_constraint": ["spring_yield", ""], "binding_margin": [0.1, float("nan")],
        "violated": ["", "spring_coil_gap:-0.200"], "relaxation": ["", ""], "part_bearing": ["6006", None]})
    S.write_summary(S.summarise(table), tmp_path / "summary")
    from synth.design.constraints import words
    assert words("spring_yield", 48) in labels and "\n" in words("spring_yield", 48)
    assert not any(re.fullmatch(r"[a-z_]+", x) for x in labels if "_" in x)
    code, out, _ = _run(capsys, "pareto", DEFAULT, "--out", tmp_path / "front", "--points", "3")
    assert "| cost [EUR] | 90 % band [EUR] | smallest margin |" in out and "spring_coil_gap |" not in out
    front = json.loads((tmp_path / "front" / "front.json").read_text())
    assert all(abs(p["margin"]) < 1 for p in front)  # fractions in data
    assert callable(pareto.plot_front)


# ----------------------------------------------------------------------------------------------- progress
def test_rationalise_shows_every_long_phase_on_a_terminal_and_nothing_in_scripts(tmp_path, capsys, monkeypatch):
    argv = ["rationalise", "synthetic:6:2", "--out", tmp_path / "p", "--points", "2", "--time-limit", "20"]
    monkeypatch.setenv("SYNTH_PROGRESS", "1")
    code, out, err = _run(capsys, *argv)
    assert code == 0
    for phase in ("feasibility", "platform, compile", "platform, highs MILP", "trade-off curve (margin)"):  # per stage
        assert f"synth rationalise: {phase}" in err, phase
    monkeypatch.setenv("SYNTH_PROGRESS", "0")
    code, out, err = _run(capsys, *argv[:3], tmp_path / "q", *argv[4:])
    assert code == 0 and "synth rationalise:" not in err


# ----------------------------------------------------------------------------------------------- report and CAD
def test_cad_pictures_print_their_text_at_6_pt_or_more_on_a4():
    from synth.cad import pictures as P
    from synth.report.html import CAD_PRINT_MAX_HEIGHT_MM, _CSS
    assert f"max-height:{CAD_PRINT_MAX_HEIGHT_MM:g}mm" in _CSS and "figure.cad{display:block;width:auto" in _CSS
    size = 6.5  # the pictures' height [in] (section_picture, exploded_picture)
    pictures = {"section": (size * 1.45, size, P.DIMENSION_PT), "exploded": (size * 1.2, size, P.LABEL_PT)}
    frame_in = 0.25  # the figure's border, padding and margins [in]
    for page_w_mm in (297 - 22, 210 - 22):  # A4 landscape and portrait between the report's @page margins
        box_w, box_h = page_w_mm / 25.4 - frame_in, CAD_PRINT_MAX_HEIGHT_MM / 25.4
        for name, (w, h, pt) in pictures.items():
            printed = pt * min(box_w / w, box_h / h, 1e9)
            assert printed >= 6.0, (name, page_w_mm, printed)


def test_exploded_view_shows_every_part(tmp_path):
    pytest.importorskip("cadquery")
    import numpy as np
    from synth.cad import geometry_from, pictures as P
    from synth.cad.assembly import build
    from synth.optimise import solve
    from synth.io.documents import load_input
    model = build(geometry_from(solve(load_input(CASES_DIR / "case1_as_run.yaml"))))
    plt, fig, ax = P._figure("", 6.5, 110, legend=False)
    shapes = P.exploded_parts(model)
    pts = np.concatenate(list(P._draw(ax, shapes, "iso", hatch_cut=False).values()))
    P._frame(ax, pts)
    assert set(P._visible_anchors(shapes, fig, ax, "iso")) == set(model.parts)
    plt.close(fig)
    # levels clear of each other along the axis: the bearing is no longer inside the pulley
    z = {n: s.BoundingBox() for n, s in shapes.items()}
    assert z["ball_bearing"].zmax <= z["pulley"].zmin + 1e-6 and z["pivot_bushing"].zmax <= z["arm"].zmin + 1e-6


def test_template_names_synth_design_explains_every_cell_and_lists_every_fixed_set(tmp_path):
    from openpyxl import load_workbook
    from synth import schema
    from synth.excel.template import fixed_sets, write_template
    ws = load_workbook(write_template(tmp_path / "t.xlsx")).worksheets[0]
    assert "synth design THIS.xlsx" in ws["A2"].value
    cells = {ws.cell(r, 2).value: r for r in range(1, ws.max_row + 1)}
    listed = {}
    for dv in ws.data_validations.dataValidation:
        if dv.type == "list":
            for rng in dv.sqref.ranges:
                listed[rng.min_row] = True
    for f in schema.FIELDS:
        r = cells[f.name]
        note = (ws[f"D{r}"].comment or ws[f"E{r}"].comment)
        assert note is not None and (f.label or f.name) in note.text, f.name
        if f.unit not in ("-", ""):
            assert f"[{f.unit}]" in note.text, f.name
        if f.name in fixed_sets():
            assert listed.get(r), f"{f.name}: no drop-down"
    assert ws.page_margins.top - ws.page_margins.header >= 0.4  # the header line clear of the table


# ----------------------------------------------------------------------------------------------- core install
def test_core_install_runs_without_cadquery_and_a_cad_scene_says_what_to_install(tmp_path):
    code = ("import sys; sys.modules['cadquery'] = None\n"
            "from synth.cli import main\nsys.exit(main(sys.argv[1:]))")
    env = {**os.environ, "PYTHONPATH": str(ROOT) + os.pathsep + os.environ.get("PYTHONPATH", "")}

    def run(*argv):
        return subprocess.run([sys.executable, "-c", code, *map(str, argv)], capture_output=True, text=True,
                              env=env, timeout=300)
    r = run("design", DEFAULT, "--cad", tmp_path / "cad")
    assert r.returncode == 2 and 'pip install "synth[cad]"' in r.stderr and "Traceback" not in r.stderr
    r = run("demo", "--out", tmp_path / "demo")
    assert r.returncode == 2 and "synth demo --no-cad" in r.stderr
    r = run("demo", "--out", tmp_path / "demo", "--no-cad", "--no-report", "--no-robust")
    assert r.returncode == 0, r.stderr
    text = (ROOT / "pyproject.toml").read_text()
    assert 'cad = ["cadquery' in text and '"cadquery>=2.4",\n' not in text.split("[project.optional")[0]
    readme = (ROOT / "README.md").read_text()
    assert 'pip install -q -e ".[cad]" && .venv/bin/synth demo' in readme


@pytest.mark.skipif(not os.environ.get("SYNTH_SLOW"), reason="slow (CAD and report): set SYNTH_SLOW=1 to run")
def test_demo_writes_one_step_file_and_names_the_application(tmp_path, capsys):
    code, out, _ = _run(capsys, "demo", "--out", tmp_path)  # no catalog design reaches its Ppk 1.33: FAIL (issue 35)
    assert code == 1 and "synth demo: the most standardised tensioner for default (thesis case 3, completed)" in out
    assert out.rstrip().splitlines()[-1].startswith("Verdict: FAIL (production capability Ppk >= 1.33 missed")
    assert [p.name for p in tmp_path.rglob("*.step")] == ["tensioner.step"]
    assert math.isfinite(len((tmp_path / "report.html").read_text()))
