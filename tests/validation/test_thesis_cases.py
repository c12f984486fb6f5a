"""Thesis case studies 1 (as run) and 3: the thesis tool's and the real tensioner's designs through
``synth flowchart --parts``, and ``synth design`` on the same inputs.

Source: the thesis (``synth/data/cases/case1_as_run.yaml``, ``case3.yaml``: Tables 9-10 and 13-14, inputs as
the tool ran them, see ``cases/NOTES.md``). Each application is given the installation travel its printed
stresses imply (eq. 69: 50 deg for case 1, 28.6 deg for case 3; ``docs/sections/torsion_spring.md``).

Every check that fails is asserted here and explained in ``docs/sections/validation.md`` (docs/model.md), by
physics: the printed stresses of case 1 do not follow from eq. (71)-(77) for the printed spring; case 1's printed
damper pad and endcap spacer are Table 3-4's class 2, below the class 3 its 1.71 N m axial damping falls in; case 3's
printed 3.0 mm wire cannot give 2.18 coils at the specified stiffness, so its springs are verified in the consistent
reading, 2.3 mm (the printed coils and hooks angles of both the tool's and the production spring); case 3's radial
damping is the friction circle's, not the printed target. Tolerance on reproduced values: 1 % (our own arithmetic).
"""

from __future__ import annotations

import dataclasses
import json

import numpy as np
import pytest

from synth import catalog, flowchart
from synth.data import case_path
from synth.design.evaluate import Settings
from synth.optimise import solve
from synth.io.documents import load_input

TRAVEL = {"case1_as_run": 50.0, "case3": 28.6}
_BOLT = {"bolt_format": "M8x1.25", "bolt_head_type": "hex", "bolt_property_class": "8.8"}
DESIGNS = {
    # the thesis tool's printed designs (Tables 10 and 14); the cone spring sized as the tool sizes it
    ("case1_as_run", "tool"): {**_BOLT, "ball_bearing": "6006", "pivot_class_diameter_mm": 16.0,
                               "pivot_bushing_supplier": "A", "damper_pad_class": "DP2", "pivot_bushing_length_mm": 16.0,
                               "endcap_spacer_class": "ES2", "cone_spring_aspect_ratio": 1.2,
                               "cone_spring_deflection_ratio": 0.75, "cone_spring_external_diameter_mm": 30.0,
                               "cone_spring_internal_diameter_mm": 16.2, "main_spring_material": "VDSiCr",
                               "main_spring_wire": "F2.30x2.30", "main_spring_mean_body_diameter_mm": 41.0},
    ("case3", "tool"): {**_BOLT, "ball_bearing": "6006", "pivot_class_diameter_mm": 20.0,
                        "pivot_bushing_supplier": "B", "damper_pad_class": "none", "pivot_bushing_length_mm": 21.0,
                        "endcap_spacer_class": "none", "cone_spring_aspect_ratio": 0.0,
                        "cone_spring_deflection_ratio": 0.0, "cone_spring_external_diameter_mm": 0.0,
                        "cone_spring_internal_diameter_mm": 0.0, "main_spring_material": "VDSiCr",
                        # printed 3.0 mm: the consistent reading (test_case3_wire_consistent_reading)
                        "main_spring_wire": "R2.30", "main_spring_mean_body_diameter_mm": 44.0},
}
# the production tensioners (the cases' real_tensioner blocks): catalog lengths, their own pads and springs
DESIGNS[("case1_as_run", "real")] = {**DESIGNS[("case1_as_run", "tool")], "pivot_bushing_length_mm": 18.0,
                                     "damper_pad_class": "REAL1", "endcap_spacer_class": "REAL1",
                                     "cone_spring_external_diameter_mm": 27.1, "cone_spring_internal_diameter_mm": 18.2,
                                     "main_spring_mean_body_diameter_mm": 36.8}
DESIGNS[("case3", "real")] = {**DESIGNS[("case3", "tool")], "pivot_bushing_length_mm": 22.0,
                              "main_spring_mean_body_diameter_mm": 39.1}
# what fails, and (docs/sections/validation.md) why
FAILS = {
    ("case1_as_run", "tool"): {"spring_yield", "spring_fatigue", "damper_pad_capacity", "endcap_spacer_capacity"},
    ("case1_as_run", "real"): {"cone_force_band", "cone_not_flattened", "damping_eol", "spring_yield",
                               "spring_fatigue"},
    # case 3's radial damping meets its band with the default dry friction 0.10 (0.483 N m); with the thesis tool's
    # 0.15 it was 0.72 N m, above 0.65 (tests/test_production_friction.py)
    ("case3", "tool"): {"spring_yield", "spring_fatigue"},
    ("case3", "real"): {"spring_yield", "spring_fatigue", "spring_coil_gap"},
}


@pytest.fixture
def real_parts_catalog(tmp_path):
    """The real case-1 damper pad (350 mm2, R 11 mm, 27.5 mm, 2.5 mm) and endcap spacer (410 mm2, R 12.5 mm,
    1.5 mm) as a user catalog. They are not rows of Tables 3-4 (the thesis: "out-of-standard plastic friction
    elements"), so no table bound applies to them: they carry the tables' top bound (2.00 N m) and the physical
    checks (wear, end-of-life damping, cone spring) judge them."""
    (tmp_path / "damper_pads.csv").write_text(
        "class,max_axial_damping_nm,contact_area_mm2,mean_radius_mm,outer_diameter_mm,axial_height_mm,unit_cost_eur,"
        "standard,source\nREAL1,2.00,350,11.0,27.5,2.5,0.2,false,thesis case 1 real tensioner (Table 10)\n")
    (tmp_path / "endcap_spacers.csv").write_text(
        "class,max_axial_damping_nm,contact_area_mm2,mean_radius_mm,axial_height_mm,unit_cost_eur,standard,source\n"
        "REAL1,2.00,410,12.5,1.5,0.1,false,thesis case 1 real tensioner (Table 10)\n")
    catalog.set_user_dirs(tmp_path)
    yield tmp_path
    catalog.set_user_dirs()


def _input(case):
    return dataclasses.replace(load_input(case_path(case)), arm_travel_nominal_to_installation_deg=TRAVEL[case])


@pytest.mark.parametrize("key", sorted(DESIGNS))
def test_printed_designs_fail_exactly_the_explained_checks(key, real_parts_catalog, tmp_path):
    """``synth flowchart INPUT --parts RESULT.json`` of the printed design: the failing checks are the explained ones."""
    from synth.cli import main
    case, which = key
    data = {k: v for k, v in dataclasses.asdict(_input(case)).items() if v is not None}
    (tmp_path / "input.json").write_text(json.dumps(data))
    (tmp_path / "parts.json").write_text(json.dumps({"kind": "synth.result", "parts": DESIGNS[key], "values": {},
                                                     "checks": []}))
    r = flowchart.run(_input(case), Settings(), parts=DESIGNS[key], time_points=0)
    assert {c.id for c in r.failed()} == FAILS[key]
    code = main(["--catalogs", str(real_parts_catalog), "flowchart", str(tmp_path / "input.json"), "--parts",
                 str(tmp_path / "parts.json")])
    assert code == 1


def test_case1_printed_spring_stress_follows_the_equations_not_the_print():
    """Case 1: the printed spring (flat 2.3 x 2.3, Dm 41) carries 4.09 N m at installation: 2126 MPa with the
    curvature factor (eq. 71-77), above Rm of the wire (1910 MPa, EN 10270-2): the printed 1448 MPa does not
    follow from the printed geometry. Its coil count at the specified stiffness is 3.62 (printed 4.09)."""
    r = flowchart.run(_input("case1_as_run"), Settings(), parts=DESIGNS[("case1_as_run", "tool")], time_points=0)
    assert r.values["main_spring_sigma_inst_mpa"] == pytest.approx(2126, rel=0.01)
    assert r.values["main_spring_active_coils_free"] == pytest.approx(3.62, rel=0.01)
    assert r.values["main_spring_sigma_inst_mpa"] > 1910.0


def test_case3_printed_wire_cannot_give_the_printed_coils():
    """Case 3: 3.0 mm round wire at Dm 44 and 0.0164 N m/deg needs 6.3 coils (eq. 64-65), not the printed 2.18,
    and 6.3 coils of 3 mm do not fit an 8.8 mm housing (coil gap -72 %); the production spring (Dm 39.1) would need
    7.1, not 2.52. Radial damping 0.48 N m (friction circle of the 21 mm pivot, the default dry mu 0.10) is within the
    0.45 +/- 0.20 N m band (with the tool's mu 0.15 it was 0.72 N m: the tool met the band by printing the target)."""
    r = flowchart.run(_input("case3"), Settings(), parts=dict(DESIGNS[("case3", "tool")], main_spring_wire="R3.00"),
                      time_points=0)
    assert r.values["main_spring_active_coils_free"] == pytest.approx(6.31, rel=0.01)
    assert r.check("spring_coil_gap").margin == pytest.approx(-0.722, abs=0.01)
    assert r.values["radial_damping_nm"] == pytest.approx(1.85 * 10.5 * np.sin(np.arctan(0.10)) / 4.0, rel=1e-9)
    real = flowchart.run(_input("case3"), Settings(), parts=dict(DESIGNS[("case3", "real")], main_spring_wire="R3.00"),
                         time_points=0)
    assert real.values["main_spring_active_coils_free"] == pytest.approx(7.10, rel=0.01)


@pytest.fixture
def tool_friction(tmp_path):
    """The thesis tool's dry pivot-bushing friction 0.15 (cases/NOTES.md) as a user catalog: the tool's printed
    case-3 spring torque 1.56 N m and stresses are its; synth's default is 0.10 (friction_coefficients.csv)."""
    fr = catalog.load("friction_coefficients")
    fr = fr[fr["friction"] == "pivot_bushing dry"].assign(mu=0.15)
    fr.to_csv(tmp_path / "friction_coefficients.csv", index=False)
    with catalog.overriding(tmp_path):
        yield


def test_case3_wire_consistent_reading(tool_friction):
    """The consistent reading of case 3's wire is 2.3 mm: eq. (64) n_a = E pi d^4 / (64 * 180 k_t mbd) gives 2.179 at
    Dm 44 (printed 2.18) and 2.452 at the production Dm 39.1, whose free-state hooks angle 360 (3 - 2.452) = 197.3 deg
    is the printed 197; the tool's 295.70 deg is printed 295.56. The verdict on it: the coil gap passes (+9.5 %) for
    the tool's spring; at synth's worst-case torque (+8 %, eq. (66)) the installation stress 1885 MPa exceeds
    0.88 Rm = 1724.8 MPa (-9.3 %) and the Goodman factor is 1.08 < 1.2; with the -8 % the printed stresses imply,
    every step-9 check passes (tests/test_torsion_spring.py::test_case3_reproduced_with_2_3_mm_wire)."""
    tool = flowchart.run(_input("case3"), Settings(), parts=DESIGNS[("case3", "tool")], time_points=0)
    real = flowchart.run(_input("case3"), Settings(), parts=DESIGNS[("case3", "real")], time_points=0)
    e, k, d = 206000.0, 0.0164 * 1000.0, 2.3
    for r, mbd, printed in ((tool, 44.0, 2.18), (real, 39.1, None)):
        n_a = e * np.pi * d ** 4 / (64.0 * 180.0 * k * mbd)
        assert r.values["main_spring_active_coils_free"] == pytest.approx(n_a, rel=1e-9)
        if printed:
            assert n_a == pytest.approx(printed, abs=0.005)
    assert tool.values["hooks_angle_free_state_deg"] == pytest.approx(295.56, rel=0.001)
    assert real.values["hooks_angle_free_state_deg"] == pytest.approx(197.0, rel=0.003)
    assert tool.check("spring_coil_gap").margin == pytest.approx(0.095, abs=0.005)
    assert tool.check("spring_yield").value == pytest.approx(1885.4, rel=0.001)
    assert tool.check("spring_yield").limit == pytest.approx(0.88 * 1960.0, rel=1e-9)
    assert tool.values["main_spring_safety_factor"] == pytest.approx(1.084, abs=0.002)
    assert real.check("spring_coil_gap").margin == pytest.approx(-0.012, abs=0.002)


def test_design_finds_case3_feasible():
    r = solve(_input("case3"), "standard", "enumerate", settings=Settings(), relax=False)
    assert r.status == "optimal" and not r.failed()


def test_design_finds_case1_a_verified_relaxation_within_10_percent():
    """Case 1 has no feasible catalog design (the main spring); the smallest relaxation found changes one input by at
    most 10 % and is verified: with it, the exhaustive optimum is feasible."""
    d = _input("case1_as_run")
    r = solve(d, "standard", "enumerate", settings=Settings(), relax=True)
    assert r.status == "infeasible"
    assert {c.id for c in r.failed()} <= {"spring_yield", "spring_fatigue", "spring_outer_contact", "spring_coil_gap"}
    single = [x for x in r.diagnosis["relaxations"] if len(x["inputs"]) == 1]
    assert single and single[0]["relative_change"] <= 0.10
    (name, change), = single[0]["inputs"].items()
    again = solve(dataclasses.replace(d, **{name: change["to"]}), "standard", "enumerate", settings=Settings(),
                  relax=False)
    assert again.status == "optimal" and not again.failed()
