"""CAD export (issue 5, thesis step 11): geometry adapter, parts, STEP round trip, geometric verification.

Cases 1 and 3 run through the flowchart, the model is built and exported once per module
(fixtures), the STEP file is read back and its parts compared with the result values
within 0.01 mm. Every product family is built: standard/reverse layout, with/without
axial damping, round/rectangular wire, single/double eccentric pivot, flat/toothed pulley.
"""

from __future__ import annotations

import dataclasses
import json
import math

import cadquery as cq
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from synth import catalog, flowchart
from synth.cad import export_result, geometry_from
from synth.cad.assembly import build, colour_of, part_names
from synth.cad.dimensions import _example_inputs, _example_values
from synth.cad.solids import spring_pitch_mm, stack
from synth.cad.verify import failed, verify_model
from synth.cli import main
from synth.design.result import FAIL, PASS
from synth.errors import InputError
from synth.io.documents import load_input

from synth.data import CASES_DIR

CASES = str(CASES_DIR)
TOL = 0.01  # mm, the acceptance tolerance
ALL_PARTS = {"support_plate", "pivot", "spring_bushing", "main_spring", "cone_spring", "damper_pad", "pivot_bushing",
             "arm", "ball_bearing", "pulley", "endcap_spacer", "endcap", "fixation_bolt"}


def _by_id(checks, cid):
    return next(c for c in checks if c.id == cid)


def _measured(checks):
    """The checks measured on the solids: without the interference computation its check is not verified."""
    i = _by_id(checks, "cad_interference")
    assert i.verdict == "not verified" and i.value is None and "not computed" in i.note
    return [c for c in checks if c.id != "cad_interference"]


def _example(values=None, inputs=None):
    """The geometry of the case-1-like example result (the thesis's 41 mm spring), its values updated by
    ``values``, as its JSON (``--json``) is read."""
    res = _example_values()
    res["values"].update(values or {})
    return geometry_from(res, inputs=_example_inputs() if inputs is None else inputs)


# --- fixtures: each assembly built and exported once ----------------------------------------------

@pytest.fixture(scope="module")
def inputs():
    return {c: load_input(f"{CASES}/{c}.yaml") for c in ("case1", "case3")}


@pytest.fixture(scope="module")
def results(inputs):
    return {c: flowchart.run(d) for c, d in inputs.items()}


@pytest.fixture(scope="module")
def exported(results, tmp_path_factory):
    out = {}
    for c, r in results.items():
        folder = tmp_path_factory.mktemp(c)
        model, checks, info = export_result(r, folder)
        out[c] = (r, model, checks, info, folder)
    return out


@pytest.fixture(scope="module")
def reimported(exported):
    return {c: cq.Assembly.importStep(str(v[4] / "tensioner.step")) for c, v in exported.items()}


def _imported_shapes(assy) -> dict:
    return {name: sub.obj.moved(sub.loc) for name, sub in assy.objects.items() if sub.obj is not None}


# --- adapter -----------------------------------------------------------------------------------------

def test_geometry_reads_the_result_values(results):
    r = results["case1"]
    g = geometry_from(r)
    v = r.values
    assert (g.pulley_width_mm, g.pivot_diameter_mm, g.bearing_outer_diameter_mm) == (
        v["pulley_width_mm"], v["pivot_diameter_mm"], v["bearing_outer_diameter_mm"])
    assert g.spring_mean_diameter_mm == v["main_spring_mean_body_diameter_mm"]
    # Table 10's 14.8 mm with the printed 3.5 mm pad; the flowchart's pad (class 3 of Table 3 for D_ax = 1.71 N m)
    # is 2.5 mm high, so eq. (52) leaves 15.8 mm
    assert g.spring_housing_height_mm == pytest.approx(15.8)
    # damper pad DP3 (Table 3): D_o 34.5, R_m 13.5 -> bore 4*13.5 - 34.5 = 19.5 mm
    assert g.damper_pad_inner_diameter_mm == pytest.approx(19.5)
    # endcap spacer ES3 (Table 4): R_m 14.5, A 670 -> width 670/(2 pi 14.5) = 7.354 -> 21.646 / 36.354 mm
    assert g.endcap_spacer_inner_diameter_mm == pytest.approx(29.0 - 670 / (2 * math.pi * 14.5), abs=1e-9)
    assert g.endcap_spacer_outer_diameter_mm == pytest.approx(29.0 + 670 / (2 * math.pi * 14.5), abs=1e-9)
    # 6006: 11 balls of 7.144 mm (catalog row named by the result)
    assert (g.bearing_ball_count, g.bearing_ball_diameter_mm) == (11, 7.144)
    assert not g.feasible  # the flowchart's case-1 spring fails (the CAD still exports it)


def test_json_without_inputs_needs_them(results, inputs):
    # every --json carries its inputs now (the flowchart's too); one without them needs --input
    d = json.loads(json.dumps(results["case3"].to_dict()))
    assert geometry_from(d).pulley_diameter_mm == 65.5
    d["inputs"] = None
    with pytest.raises(InputError, match="pass --input"):
        geometry_from(d)
    g = geometry_from(d, inputs=inputs["case3"])
    assert g.pulley_diameter_mm == 65.5 and not g.axial_damping


def test_missing_dimension_is_named():
    res = _example_values()
    del res["values"]["bearing_width_mm"]
    with pytest.raises(InputError, match="result.bearing_width_mm"):
        geometry_from(res, inputs=_example_inputs())


def test_design_result_and_its_json(inputs, tmp_path):
    from synth.optimise import solve
    r = solve(inputs["case3"], "standard", "flowchart")
    g = geometry_from(r)
    assert g.bearing_designation == r.parts["ball_bearing"]
    assert g.spring_mean_diameter_mm == r.parts["main_spring_mean_body_diameter_mm"]
    path = tmp_path / "design.json"
    path.write_text(json.dumps(r.to_dict(), default=str))
    # the saved JSON is self-contained (it carries its inputs); its numbers have 6 significant figures
    saved = dataclasses.asdict(geometry_from(str(path)))
    for k, v in dataclasses.asdict(g).items():
        assert saved[k] == (pytest.approx(v, rel=1e-5) if isinstance(v, float) else v), k
    rc = main(["cad", str(path), "--out", str(tmp_path / "cad"), "--no-stl", "--no-pictures"])
    assert rc in (0, 1)
    assert (tmp_path / "cad" / "tensioner.step").stat().st_size > 10_000
    report = json.loads((tmp_path / "cad" / "cad_report.json").read_text())
    assert report["status"] == r.status and report["feasible"] is False


# --- cases 1 and 3: STEP round trip -----------------------------------------------------------------

@pytest.mark.parametrize("case, n_parts", [("case1", 13), ("case3", 10)])
def test_step_reimports_every_part_valid(reimported, exported, case, n_parts):
    shapes = _imported_shapes(reimported[case])
    model = exported[case][1]
    assert set(shapes) == set(model.parts) and len(shapes) == n_parts
    for name, s in shapes.items():
        assert s.isValid(), name
        assert s.Volume() > 0, name
        assert s.Volume() == pytest.approx(model.parts[name].Volume(), rel=1e-6), name


@pytest.mark.parametrize("case", ["case1", "case3"])
def test_step_keeps_colours(reimported, case):
    kids = {c.name: c for c in reimported[case].children}
    for name in ("pulley", "main_spring", "arm"):
        got = kids[name].color.toTuple()
        assert got[:3] == pytest.approx(colour_of(name)[:3], abs=2e-3), name


@pytest.mark.parametrize("case", ["case1", "case3"])
def test_step_key_dimensions_match_the_result(reimported, exported, case):
    r = exported[case][0]
    v, d = r.values, dataclasses.make_dataclass("Inputs", list(r.inputs))(**r.inputs)
    s = _imported_shapes(reimported[case])
    pul = s["pulley"].BoundingBox()
    assert pul.xlen == pytest.approx(d.pulley_diameter_mm, abs=TOL)      # case 1: 66, case 3: 65.5
    assert pul.ylen == pytest.approx(d.pulley_diameter_mm, abs=TOL)
    assert pul.zlen == pytest.approx(v["pulley_width_mm"], abs=TOL)      # 20 / 30 (belt + 4 mm)
    assert 0.5 * (pul.zmin + pul.zmax) == pytest.approx(d.middle_plane_belt_height_mm, abs=TOL)
    piv = s["pivot"].BoundingBox()
    assert piv.xlen == pytest.approx(v["pivot_diameter_mm"], abs=TOL)    # 16 / 21
    brg = s["ball_bearing"].BoundingBox()
    assert brg.ylen == pytest.approx(v["bearing_outer_diameter_mm"], abs=TOL)  # 55 (6006)
    assert brg.zlen == pytest.approx(v["bearing_width_mm"], abs=TOL)           # 13
    assert 0.5 * (brg.xmin + brg.xmax) == pytest.approx(d.working_arm_mm, abs=TOL)
    # overall height: pivot top = belt plane + B/2 + h_es + h_e + h_calking (eq. 50 as a chain of faces)
    # case 1: 29.5 + 6.5 + 1.5 + 1.2 + 1.0 = 39.7; case 3 (no spacer): 20 + 6.5 + 1.2 + 1.0 = 28.7
    expected_top = {"case1": 39.7, "case3": 28.7}[case]
    assert piv.zmax == pytest.approx(expected_top, abs=TOL)
    whole = cq.Compound.makeCompound(list(s.values())).BoundingBox()
    # the bolt: 1.5 d below the crankcase face, head 0.7 d above the pivot (M8: -12 .. top + 5.6)
    assert whole.zmin == pytest.approx(-12.0, abs=TOL)
    # top: the bolt head or, for case 3, the pulley (20 + 30/2 = 35 > 28.7 + 5.6)
    top = max(expected_top + 5.6, d.middle_plane_belt_height_mm + v["pulley_width_mm"] / 2)
    assert whole.zmax == pytest.approx(top, abs=TOL)
    spr = s["main_spring"].BoundingBox()
    w = v["main_spring_wire_size_mm"]
    assert spr.xlen == pytest.approx(v["main_spring_mean_body_diameter_mm"] + w[-1], abs=TOL)


@pytest.mark.parametrize("case", ["case1", "case3"])
def test_pictures_written_small(exported, case):
    folder = exported[case][4]
    for name in ("exploded.png", "section.png"):
        size = (folder / name).stat().st_size
        assert 10_000 < size < 300_000, (name, size)
    assert len(list((folder / "stl").glob("*.stl"))) == len(exported[case][1].parts)


@pytest.mark.parametrize("case", ["case1", "case3"])
def test_case_checks_agree_with_the_flowchart(exported, case):
    """The flowchart's nearest springs (case 1: VDSiCr 2.5 x 2.5 flat wire at Dm 43.5 in a 45 mm housing; case 3:
    OTEVA 91 SC 2.0 x 2.0 at Dm 45.5 in 47 mm, since the EN 10270-2 strength table and the case's default
    50 deg installation travel) stick out of the housing: the CAD sees it as interference with the support-plate cup, as the physics does
    (spring outer contact, eq. 81-82). Everything else fits."""
    checks = exported[case][2]
    assert {c.id for c in failed(checks)} == {"cad_interference", "cad_spring_diameter"}
    assert "interfering: support_plate/main_spring" in _by_id(checks, "cad_interference").note
    assert "," not in _by_id(checks, "cad_interference").note.split("interfering: ")[1]   # that pair only
    # the drawn spring's outer diameter is the result's Dm + radial wire size: 43.5 + 2.5 and 45.5 + 2.0
    # (case 3 at the dry friction 0.10: the flowchart's spring is sized to more torque, Dm 47.4 + 2.0)
    assert _by_id(checks, "cad_spring_diameter").value == pytest.approx({"case1": 46.0, "case3": 49.4}[case], abs=TOL)
    for cid in ("cad_pivot_height", "cad_axial_space", "cad_belt_plane", "cad_spring_height", "cad_crankcase_face",
                "cad_collar"):
        assert _by_id(checks, cid).verdict == PASS, cid


# --- product families ------------------------------------------------------------------------------

def _thesis_spring_case1(g):
    """Case 1 with the thesis tool's spring (Table 10: 2.3 x 2.3 flat wire, Dm 41 mm, 4.09 coils)."""
    return g.replace(spring_mean_diameter_mm=41.0, spring_wire_axial_mm=2.3, spring_wire_radial_mm=2.3,
                     spring_active_coils=4.09)


@pytest.fixture(scope="module")
def families(results, inputs):
    g1 = _thesis_spring_case1(geometry_from(results["case1"]))
    g3 = geometry_from(results["case3"]).replace(spring_mean_diameter_mm=44.0, spring_wire_axial_mm=2.3,
                                                 spring_wire_radial_mm=2.3, spring_active_coils=2.18)
    rev = flowchart.run(dataclasses.replace(inputs["case1"], middle_plane_belt_height_mm=16.0))
    # reverse: eq. (53) leaves a 10.6 mm housing above the 2.5 mm pad of class 3 (Table 3 at 1.71 N m); 2.5 coils of
    # the 2.3 mm wire fit it (4.09 would need 11.9 mm)
    g_rev = _thesis_spring_case1(geometry_from(rev)).replace(spring_active_coils=2.5)
    assert g_rev.spring_housing_height_mm == pytest.approx(10.6)
    single = flowchart.run(dataclasses.replace(inputs["case3"], belt_loading_type="single_eccentric", loading_arm_mm=None))
    g_single = geometry_from(single).replace(spring_mean_diameter_mm=44.0, spring_wire_axial_mm=2.3,
                                             spring_wire_radial_mm=2.3, spring_active_coils=2.18)
    fam = {"standard+axial+rectangular+double+toothed": g1, "standard+radial+round+double+flat": g3,
           "reverse+axial+rectangular+double+toothed": g_rev, "standard+radial+round+single+flat": g_single,
           "standard+axial+round+double+flat": g1.replace(wire_section="round", pulley_type="flat",
                                                          spring_wire_radial_mm=2.3)}
    return {k: (g, build(g)) for k, g in fam.items()}


def test_every_family_value_is_covered(families):
    gs = [g for g, _ in families.values()]
    assert {g.layout for g in gs} == {"standard", "reverse"}
    assert {g.axial_damping for g in gs} == {True, False}
    assert {g.wire_section for g in gs} == {"round", "rectangular"}
    assert {g.eccentric for g in gs} == {"single_eccentric", "double_eccentric"}
    assert {g.pulley_type for g in gs} == {"flat", "toothed"}


@pytest.mark.parametrize("family", ["standard+axial+rectangular+double+toothed", "standard+radial+round+double+flat",
                                    "reverse+axial+rectangular+double+toothed", "standard+radial+round+single+flat",
                                    "standard+axial+round+double+flat"])
def test_family_builds_valid_parts_and_passes(families, family):
    g, m = families[family]
    expected = ALL_PARTS if g.axial_damping else ALL_PARTS - {"cone_spring", "damper_pad", "endcap_spacer"}
    assert set(m.parts) == expected == set(part_names(g))
    assert all(s.isValid() for s in m.parts.values())
    checks = verify_model(m)
    assert not failed(checks), [(c.id, c.value, c.limit, c.note) for c in failed(checks)]
    assert not any(math.isnan(c.value) for c in checks)


def test_reverse_layout_puts_the_pulley_below_the_housing(families):
    g, m = families["reverse+axial+rectangular+double+toothed"]
    pulley, spring = m.parts["pulley"].BoundingBox(), m.parts["main_spring"].BoundingBox()
    assert spring.zmin > 0.5 * (pulley.zmin + pulley.zmax)
    # eq. (53) with the damper pad: the stack ends exactly at the max pivot height (40 mm)
    assert m.parts["pivot"].BoundingBox().zmax == pytest.approx(g.max_pivot_height_mm, abs=TOL)
    # eq. (51): bearing bottom = pivot base (3.0) + endcap spacer (1.5) when the hub reaches the spacer
    assert m.parts["endcap_spacer"].BoundingBox().zmin == pytest.approx(g.pivot_base_height_mm, abs=TOL)


def test_single_eccentric_bolt_is_concentric(families):
    g, m = families["standard+radial+round+single+flat"]
    assert g.loading_arm_mm == 0.0
    bb = m.parts["fixation_bolt"].BoundingBox()
    assert 0.5 * (bb.xmin + bb.xmax) == pytest.approx(0.0, abs=TOL)
    gd, md = families["standard+radial+round+double+flat"]
    bbd = md.parts["fixation_bolt"].BoundingBox()
    assert 0.5 * (bbd.xmin + bbd.xmax) == pytest.approx(-gd.loading_arm_mm, abs=TOL)   # case 3: -3 mm


def test_toothed_pulley_has_teeth(families):
    _, toothed = families["standard+axial+rectangular+double+toothed"]
    _, flat = families["standard+axial+round+double+flat"]
    assert len(toothed.parts["pulley"].Faces()) > len(flat.parts["pulley"].Faces()) + 50
    assert toothed.parts["pulley"].Volume() < flat.parts["pulley"].Volume()


def test_round_and_rectangular_wire_sections(families):
    _, rect = families["standard+axial+rectangular+double+toothed"]
    _, rnd = families["standard+axial+round+double+flat"]
    # same helix, section 2.3 x 2.3 square vs 2.3 round: volume ratio pi/4
    assert rnd.parts["main_spring"].Volume() / rect.parts["main_spring"].Volume() == pytest.approx(math.pi / 4, rel=0.01)


# --- verification catches bad geometry --------------------------------------------------------------

def test_spring_wider_than_its_housing_is_caught(families):
    g, _ = families["standard+axial+rectangular+double+toothed"]
    bad = build(g.replace(spring_mean_diameter_mm=46.0))   # 46 + 2.3 = 48.3 > 45 mm housing
    checks = verify_model(bad)
    c = _by_id(checks, "cad_spring_diameter")
    assert c.verdict == FAIL and c.value == pytest.approx(48.3, abs=TOL)
    i = _by_id(checks, "cad_interference")
    assert i.verdict == FAIL and "support_plate/main_spring" in i.note


def test_thesis_case3_spring_does_not_fit_the_housing_height(results):
    """NOTES.md: case 3's printed 3.0 mm wire fails the coil gap; drawn, 2.18 coils at the 3.05 mm
    minimum pitch are 2.18*3.05 + 3.0 = 9.65 mm tall in an 8.8 mm housing."""
    g = geometry_from(results["case3"]).replace(spring_mean_diameter_mm=44.0, spring_wire_axial_mm=3.0,
                                                spring_wire_radial_mm=3.0, spring_active_coils=2.18)
    assert spring_pitch_mm(g) == pytest.approx(3.05)
    c = _by_id(verify_model(build(g), interference=False), "cad_spring_height")
    assert c.verdict == FAIL and c.value == pytest.approx(2.18 * 3.05 + 3.0, abs=TOL)


def test_belt_plane_off_the_pulley_is_caught(families):
    g, _ = families["standard+radial+round+double+flat"]
    c = _by_id(verify_model(build(g.replace(belt_plane_height_mm=21.0)), interference=False), "cad_belt_plane")
    assert c.verdict == FAIL and c.value == pytest.approx(1.0, abs=TOL)


def test_too_low_pivot_height_is_caught(families):
    g, _ = families["standard+axial+rectangular+double+toothed"]
    c = _by_id(verify_model(build(g.replace(max_pivot_height_mm=39.0)), interference=False), "cad_pivot_height")
    assert c.verdict == FAIL and c.value == pytest.approx(39.7, abs=TOL)


def test_long_bushing_leaves_no_room_for_the_collar(families):
    g, _ = families["standard+radial+round+double+flat"]
    c = _by_id(verify_model(build(g.replace(pivot_bushing_length_mm=25.0)), interference=False), "cad_collar")
    # hub bottom = bearing top 26.5 - 25 = 1.5 mm, below the flange top 3.2 mm: -1.7 mm
    assert c.verdict == FAIL and c.value == pytest.approx(-1.7, abs=TOL)


# --- properties ----------------------------------------------------------------------------------------

@settings(max_examples=8, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(dm=st.floats(30.0, 50.0), wire=st.floats(1.8, 3.5), coils=st.floats(0.5, 6.0))
def test_spring_checks_match_the_drawn_envelope(dm, wire, coils):
    g = _thesis_spring_case1(_example()).replace(
        spring_mean_diameter_mm=dm, spring_wire_axial_mm=wire, spring_wire_radial_mm=wire, spring_active_coils=coils)
    m = build(g)
    assert m.parts["main_spring"].isValid()
    checks = _measured(verify_model(m, interference=False))
    assert all(c.value is not None and math.isfinite(c.value) for c in checks)
    dia = _by_id(checks, "cad_spring_diameter")
    assert dia.value == pytest.approx(dm + wire, abs=1e-3)
    if abs(dm + wire - 45.0) > 1e-3:
        assert (dia.verdict == PASS) == (dm + wire < 45.0)
    height = _by_id(checks, "cad_spring_height")
    assert height.value == pytest.approx(coils * spring_pitch_mm(g) + wire, abs=1e-3)


@settings(max_examples=5, deadline=None)
@given(h=st.floats(8.0, 20.0))
def test_stack_follows_the_housing_height(h):
    g = _example({"spring_housing_height_mm": h})
    s = stack(g)
    # standard layout, chain of faces from the crankcase (eq. 52 with the pad, then eq. 50):
    # bearing centre = 0.5 + 2.0 + 0.7 + h + 3.5 + 1.5 + 6.5 = h + 14.7; pivot top = centre + 6.5 + 1.5 + 1.2 + 1.0
    assert s.z(s.bearing_centre_u) == pytest.approx(h + 14.7)
    assert s.z(s.pivot_u[1]) == pytest.approx(h + 24.9)


@settings(max_examples=4, deadline=None)
@given(mpbh=st.floats(20.0, 40.0))
def test_belt_plane_check_measures_the_offset(mpbh):
    g = _example(inputs={**_example_inputs(), "middle_plane_belt_height_mm": mpbh})
    c = _by_id(verify_model(build(g), interference=False), "cad_belt_plane")
    # the pulley sits where the result's stack puts it (29.5 mm for the case-1 housing of 14.8 mm)
    assert c.value == pytest.approx(abs(mpbh - 29.5), abs=1e-6)
    assert (c.verdict == PASS) == (abs(mpbh - 29.5) <= 0.01 + 1e-9)


# --- CLI ------------------------------------------------------------------------------------------------

def test_cli_cad_flowchart_json(results, tmp_path, capsys):
    path = tmp_path / "flow.json"
    path.write_text(json.dumps({**results["case3"].to_dict(), "inputs": None}))   # a result without its inputs
    assert main(["cad", str(path), "--out", str(tmp_path / "x")]) == 2
    assert "pass --input" in capsys.readouterr().err
    rc = main(["cad", str(path), "--out", str(tmp_path / "x"), "--input", f"{CASES}/case3.yaml", "--no-stl",
               "--no-pictures"])
    out = capsys.readouterr().out
    assert rc == 1 and "[FAIL] main spring within the housing diameter (3D model)" in out and "INFEASIBLE" in out
    assert (tmp_path / "x" / "tensioner.step").is_file()


def test_cli_demo_cad(tmp_path, capsys):
    # the demo synthesises the embedded default application (thesis case 3 completed: synth/data/default_case.yaml),
    # a feasible design whose every check passes (exit 0 without the capability target: --no-robust), and exports
    # it; every geometric check passes too, and they are checks of the design (its verdict includes them)
    assert main(["demo", "--out", str(tmp_path / "demo"), "--no-report", "--no-robust"]) == 0
    out = capsys.readouterr().out
    assert "Verdict: PASS" in out and "3D model written to" in out and "[FAIL]" not in out
    assert (tmp_path / "demo" / "tensioner.step").is_file() and not (tmp_path / "demo" / "report.html").exists()


def test_constants_have_sources():
    df = catalog.load("constants_cad")
    assert df["source"].str.len().min() > 5 and set(df.columns) == {"name", "value", "unit", "source", "note"}
    cols = catalog.load("cad_colours")
    assert set(cols["part"]) == ALL_PARTS


def test_cli_design_cad(tmp_path, capsys):
    rc = main(["design", f"{CASES}/case3.yaml", "--solver", "flowchart", "--cad", str(tmp_path / "d")])
    out = capsys.readouterr().out
    assert rc == 1  # infeasible nearest design: still exported, and said so
    assert "3D model written to" in out and "INFEASIBLE" in out
    report = json.loads((tmp_path / "d" / "cad_report.json").read_text())
    assert report["status"] == "infeasible" and len(report["parts"]) == 10


@settings(max_examples=6, deadline=None)
@given(h=st.floats(-5.0, 30.0), coils=st.floats(0.0, 10.0), blen=st.floats(5.0, 60.0),
       reverse=st.booleans(), axial=st.booleans())
def test_extreme_geometries_give_verdicts_not_exceptions(h, coils, blen, reverse, axial):
    """A result far outside the packaging (negative housing, huge bushing) still builds valid solids and every
    check has a finite value and a verdict: the failures are reported like any failed constraint."""
    g = _example().replace(
        spring_housing_height_mm=h, spring_active_coils=coils, pivot_bushing_length_mm=blen,
        layout="reverse" if reverse else "standard", axial_damping=axial)
    m = build(g)
    assert all(s.isValid() for s in m.parts.values())
    checks = _measured(verify_model(m, interference=False))  # interference of odd geometries: test_spring_wider_...
    assert all(c.verdict in (PASS, FAIL) and math.isfinite(c.value) for c in checks)


def test_cli_flowchart_json_is_self_contained(tmp_path, capsys):
    assert main(["flowchart", f"{CASES}/case3.yaml", "--json"]) in (0, 1)
    path = tmp_path / "flow.json"
    path.write_text(capsys.readouterr().out)
    assert json.loads(path.read_text())["inputs"]["pulley_diameter_mm"] == 65.5
    assert main(["cad", str(path), "--out", str(tmp_path / "c"), "--no-stl", "--no-pictures"]) == 1
    assert "[FAIL] main spring within the housing diameter (3D model)" in capsys.readouterr().out


# --- the CAD kernel's failures are verdicts (issue 39) --------------------------------------------------------

def test_a_part_the_kernel_cannot_build_fails_a_geometric_check(monkeypatch):
    """OCCT's ``StdFail_NotDone`` on a part (all-zero design rules made a 70-coil spring whose sweep fails: exit 70)
    leaves the part out: ``cad_solids`` fails naming it and why, the checks measured on it are not verified; an
    error in synth's own part code stays an error."""
    from OCP.StdFail import StdFail_NotDone

    import synth.cad.assembly as assembly
    from synth.design.result import NOT_VERIFIED
    g = geometry_from(_example_values(), inputs=_example_inputs())

    def kernel_fails(g):
        raise StdFail_NotDone("BRepOffsetAPI_MakePipeShell::MakeSolid")
    monkeypatch.setitem(assembly.PART_FUNCTIONS, "endcap", kernel_fails)
    m = build(g)
    assert "endcap" not in m.parts and "StdFail_NotDone: BRepOffsetAPI_MakePipeShell" in m.unbuilt["endcap"]
    checks = verify_model(m, interference=False)
    solids = _by_id(checks, "cad_solids")
    assert solids.verdict == FAIL and solids.value == 1 and solids.note.startswith("not built: endcap:")
    assert _by_id(checks, "cad_axial_space").verdict == NOT_VERIFIED
    assert _by_id(checks, "cad_spring_height").verdict == PASS  # measured on the spring, which was built
    monkeypatch.setitem(assembly.PART_FUNCTIONS, "endcap", lambda g: 1 / 0)
    with pytest.raises(ZeroDivisionError):
        build(g)


def test_a_spring_that_is_no_solid_is_not_drawn():
    """A wire wider than its coil (a pinned manual spring, exit 70 before) and a spring of more coils than the model
    draws (70: OCCT's sweep failed, exit 70; the interference booleans of long helices took minutes) are not drawn:
    ``cad_solids`` fails."""
    g = geometry_from(_example_values(), inputs=_example_inputs())
    m = build(g.replace(spring_mean_diameter_mm=2.0))  # 2.3 mm wire on a 2 mm mean diameter
    assert "intersects itself" in m.unbuilt["main_spring"] and "main_spring" not in m.parts
    m = build(g.replace(spring_active_coils=70.0))
    assert "more than the 30 coils the 3D model draws" in m.unbuilt["main_spring"]
    c = _by_id(verify_model(m, interference=True), "cad_solids")
    assert c.verdict == FAIL and "main_spring" in c.note
    assert build(g).unbuilt == {}
