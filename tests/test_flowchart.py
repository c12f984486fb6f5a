"""The thesis flowchart end to end: case reproduction, JSON keys, verdicts, extremes."""

import math
import json

import numpy as np
import pytest

from synth import flowchart, schema
from synth.io import documents
from synth.design.result import FAIL, NOT_VERIFIED
from synth.cli import main
from synth.compare import compare_case
from conftest import CASES, case_flowchart, load_case

# Outputs the equations determine and that synth reproduces within 3 % (default settings).
# Anything not listed is explained in docs/model.md (case 3's 483 N bolt hubload, the spring
# catalog search, the cone-spring band constants, case 1's spring stresses).
# Case 1's plastic elements follow Table 3-4's index by the axial damping (class 3 for 1.71 N m) where the tool printed
# class 2: test_case1_plastic_elements_follow_tables_3_4_not_the_print (docs/sections/flowchart_rules.md).
# pivot_bushing_length_mm is the part since the core rebuild: the next catalog length (18 / 22 mm, the real
# tensioners'); the thesis tool printed the required length (16 / 21 mm), now pivot_bushing_length_required_mm
# (test_bushing_part_is_the_next_catalog_length_of_the_tools_length).
REPRODUCED = {
    # (the tightening torque and the under-head stress: the tool's 13 mm contact needs a head bearing on 13 mm, the
    # flowchart's escalation is hex-headed (11.63 mm; tests/test_bolted_joint.py reproduces them with a flange head))
    "case1_as_run": ["pulley_width_mm", "pivot_diameter_mm", "axial_damping_nm",
                     "radial_damping_nm", "spring_torque_nominal_nm", "endcap_spacer_axial_height_mm",
                     "cone_spring_min_internal_diameter_mm", "bolt_axial_force_n",
                     "bolt_sigma_mpa",
                     "bolt_tau_mpa", "bolt_sigma_eqv_mpa", "bolt_thread_stress_mpa",
                     "pivot_base_contact_surface_mm2", "average_contact_pressure_mpa", "tilting_safety_factor",
                     "sliding_safety_factor"],
    # (case 3's spring torque 1.56 N m is the tool's dry friction 0.15's; the default is 0.10 (friction_coefficients.csv,
    # tests/test_production_friction.py reproduces 1.56 at 0.15))
    "case3": ["pulley_width_mm", "pivot_diameter_mm",
              "spring_housing_height_mm", "pivot_base_contact_surface_mm2", "tilting_safety_factor",
              "sliding_safety_factor"],
}
SAME = ["architecture", "ball_bearing", "axial_damping_present", "bolt_format", "bolt_property_class",
        "main_spring_working_condition", "main_spring_wire_section"]


@pytest.mark.parametrize("name", sorted(REPRODUCED))
def test_reproduces_thesis_tool_within_3_percent(name):
    rows = {r["key"]: r for r in compare_case(CASES / f"{name}.yaml")["rows"]}
    for key in REPRODUCED[name]:
        assert rows[key]["err_thesis"] is not None, key
        assert abs(rows[key]["err_thesis"]) <= 0.03, (key, rows[key])
    for key in SAME:
        if name == "case3" and key == "main_spring_wire_section":
            # no catalog spring passes case 3 (coil gap, outer contact); the reported spring is the one with the
            # largest smallest margin, whose section is an artefact of that rule (since the EN 10270-2 strength
            # table: TDSiCr 2.2 x 2.2 flat instead of 2.4 round)
            continue
        assert rows[key]["match"] is True, (key, rows[key])


@pytest.mark.parametrize("name, required, part", [("case1_as_run", 16.0, 18.0), ("case3", 21.0, 22.0)])
def test_bushing_part_is_the_next_catalog_length_of_the_tools_length(name, required, part):
    # a deliberate change of the core rebuild: pivot_bushing_length_mm is the part (the next catalog length,
    # which is the real tensioner's), the thesis tool's printed length is the required one
    rows = {r["key"]: r for r in compare_case(CASES / f"{name}.yaml")["rows"]}
    row = rows["pivot_bushing_length_mm"]
    assert (row["thesis_tool"], row["real"], row["ours"]) == (required, part, part) and row["err_real"] == 0.0
    r = case_flowchart(name)
    assert r.get("pivot_bushing_length_required_mm") == required


@pytest.mark.parametrize("name", ["case1_as_run", "case3"])
def test_json_prints_every_thesis_tool_key(name, capsys):
    rc = main(["flowchart", str(CASES / f"{name}.yaml"), "--json"])
    out = json.loads(capsys.readouterr().out)
    assert set(load_case(name)["thesis_tool"]) <= set(out["parts"]) | set(out["values"])
    assert out["verdict"] == "fail" and rc == 1   # both cases fail step 9 (docs/model.md); exit code as without --json
    assert [c["id"] for c in out["checks"]] == [c.id for c in case_flowchart(name).checks]


def test_case1_values_pinned():
    r = case_flowchart("case1_as_run")
    v = r.values
    # hand: rho = 8 sin(atan .055)/(5 sin 85) = 0.08822; D_rad = 3.25 rho; M_s = 3.25 - 2 rho
    rho = 8 * np.sin(np.arctan(0.055)) / (5 * np.sin(np.radians(85)))
    assert v["radial_damping_nm"] == pytest.approx(3.25 * rho, rel=1e-9)
    assert v["spring_torque_nominal_nm"] == pytest.approx(3.25 - 2 * rho, rel=1e-9)
    # Tables 3-4 at D_ax = 2 - 3.25 rho = 1.713 N m: the row 1.10 < DAX < 2.00 (class 3)
    assert v["axial_damping_nm"] == pytest.approx(2.0 - 3.25 * rho, rel=1e-9)
    assert (r.get("damper_pad_class"), r.get("endcap_spacer_class")) == ("DP3", "ES3")
    assert {0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10} <= set(r.steps_run)


def test_case1_plastic_elements_follow_tables_3_4_not_the_print():
    """Case 1 moves where the text wins: Tables 3-4 give class 3 for D_ax = 1.71 N m (1.10 < DAX < 2.00); the tool
    printed class 2 (0.7 < DAX < 1.10). Every value that follows from the pad moves with it, by the table and eq. (52)."""
    rows = {r["key"]: r for r in compare_case(CASES / "case1_as_run.yaml")["rows"]}
    ours = {k: rows[k]["ours"] for k in rows}
    tool = {k: rows[k]["thesis_tool"] for k in rows}
    # Table 3 rows 3 (ours) and 2 (printed): contact surface, mean radius, outer diameter, axial height
    assert [ours[f"damper_pad_{k}"] for k in ("contact_area_mm2", "mean_radius_mm", "outer_diameter_mm",
                                              "axial_height_mm")] == [490, 13.5, 34.5, 2.5]
    assert [tool[f"damper_pad_{k}"] for k in ("contact_area_mm2", "mean_radius_mm", "outer_diameter_mm",
                                              "axial_height_mm")] == [460, 12.5, 31.5, 3.5]
    # Table 4 rows 3 and 2
    assert [ours["endcap_spacer_contact_area_mm2"], ours["endcap_spacer_mean_radius_mm"]] == [670, 14.5]
    assert [tool["endcap_spacer_contact_area_mm2"], tool["endcap_spacer_mean_radius_mm"]] == [490, 13.5]
    # eq. (52) with the damper pad: the 1 mm lower pad leaves a 1 mm higher spring housing (14.8 -> 15.8 mm)
    assert ours["spring_housing_height_mm"] == pytest.approx(tool["spring_housing_height_mm"] + 1.0, abs=1e-9)
    # the cone spring's largest outer diameter: 1 mm below the pad's (step 8), rounded down: 33 (printed 30)
    assert (ours["cone_spring_max_external_diameter_mm"], tool["cone_spring_max_external_diameter_mm"]) == (33, 30)


def test_case3_runs_radial_only_and_meets_its_damping():
    r = case_flowchart("case3")
    assert 5 not in r.steps_run and 8 not in r.steps_run  # no axial group: no wear, no cone spring
    assert r.get("damper_pad_class") == "none" and r.check("cone_force_band").verdict == "not applicable"
    c = r.check("damping_upper")
    # the default dry friction 0.10: 0.483 N m within 0.45 +/- 0.20 (the tool's 0.15 gave 0.720, above: it printed
    # the 0.45 target; tests/test_production_friction.py)
    assert c.verdict != FAIL and c.value == pytest.approx(1.85 * 10.5 * math.sin(math.atan(0.10)) / 4.0, rel=1e-9)
    pin = [ch for ch in r.not_verified() if ch.id in ("pin_within_pulley", "pin_clearance")]
    assert len(pin) == 2 and all("lock-up pin" in ch.note for ch in pin)


def test_linear_friction_option_reproduces_the_tool_convention():
    d = documents.load_input(CASES / "case3.yaml")
    r = flowchart.run(d, flowchart.Settings(friction_circle=False))
    assert r.values["radial_damping_nm"] == pytest.approx(1.85 * 10.5 * 0.10 / 4.0, rel=1e-9)  # 0.486


def _case(name="case1_as_run", **changes):
    raw = dict(load_case(name)["inputs"], **changes)
    return schema.validate(raw)


def _nan_values(r):
    return [k for k, val in r.values.items() if isinstance(val, float) and np.isnan(val)]


def test_zero_length_durability_test_gives_finite_results():
    r = flowchart.run(_case(durability_duration_h=0.0))
    assert r.values["plastic_wear_total_mm"] == 0.0
    assert r.values["damping_eol_nm"] == pytest.approx(r.values["damping_nm"], rel=0.06)  # relaxation only
    for k, val in r.values.items():
        if isinstance(val, float):
            assert np.isfinite(val), k


def test_missing_optional_data_is_reported_not_verified():
    raw = dict(load_case("case1_as_run")["inputs"])
    for k in ("durability_duration_h", "tilting_safety_factor", "pulley_max_parallelism_eol_mm"):
        raw.pop(k)
    r = flowchart.run(schema.validate(raw))
    nv = {c.id: c.note for c in r.checks if c.verdict == NOT_VERIFIED}
    # the durability test (its duration is missing): step 4, 5 and the spring's fatigue; the fixation (a safety
    # target is missing): every step-10 check; the parallelism limit: its check
    assert {"bushing_p", "bushing_wear", "damping_eol", "spring_fatigue", "bushing_parallelism"} <= set(nv)
    assert {"tilting", "sliding", "bolt_yield", "under_head", "thread", "pivot_bore", "pivot_base_pressure"} <= set(nv)
    assert "durability test" in nv["bushing_p"] and "fixation data" in nv["tilting"]
    assert all(n.startswith("not verified:") and " missing (" in n for n in nv.values())
    assert "durability_duration_h missing" in nv["bushing_p"] and "tilting_safety_factor missing" in nv["tilting"]
    assert r.verdict == FAIL   # the spring still fails (as in the full case)
    # everything else of the full case is verified as before
    full = case_flowchart("case1_as_run")
    assert {c.id for c in full.checks if c.verdict in ("pass", "fail")} - set(nv) == \
        {c.id for c in r.checks if c.verdict in ("pass", "fail")}


def test_not_verified_note_names_the_missing_field():
    raw = dict(load_case("case1_as_run")["inputs"])
    for k in ("durability_duration_h", "tilting_safety_factor"):
        raw.pop(k)
    r = flowchart.run(schema.validate(raw))
    assert "tilting_safety_factor" in r.check("tilting").note
    assert "durability_duration_h" in r.check("bushing_p").note


def test_self_locking_arm_stops_with_a_clear_failed_check():
    # a huge pivot bushing friction cannot be set from the input: use a tiny working arm instead
    # lever 0.3 sin(85) = 0.299 mm < friction circle 8 sin(atan .055) = 0.439 mm
    r = flowchart.run(_case(working_arm_mm=0.3, loading_arm_mm=0.5, pivot_class_diameter_mm=16))
    c = r.check("self_locking")
    assert c.verdict == FAIL and c.value > 1
    assert max(r.steps_run) == 3
    # the steps not run are listed as not verified, with the reason
    assert r.check("spring_yield").verdict == NOT_VERIFIED and "stopped at step 3" in r.check("spring_yield").note


@pytest.mark.parametrize("alpha", [0.5, 179.5])
def test_differential_angle_near_0_and_180(alpha):
    # the lever vanishes: huge hubload (6007 bearing), no Table 2 class for the 5 mm arm: the flowchart stops at
    # step 2 with failing checks; nothing may crash
    r = flowchart.run(_case(differential_angle_deg=alpha))
    assert r.verdict == FAIL and max(r.steps_run) == 2
    assert {"working_arm_table2", "self_locking"} <= {c.id for c in r.failed()}
    for c in r.checks:
        assert c.margin is None or not np.isnan(c.margin), c.id
    # values: see test_stopped_result_values_are_never_nan (a core defect of the stopped result)
    assert set(_nan_values(r)) <= {"cone_spring_max_external_diameter_mm"}


def test_stopped_result_values_are_never_nan():
    r = flowchart.run(_case(differential_angle_deg=0.5))
    assert max(r.steps_run) == 2
    assert _nan_values(r) == []


def test_manual_spring_verifies_the_given_part():
    r = flowchart.run(_case("case3", main_spring_mode="manual", main_spring_material="VDSiCr",
                            main_spring_wire_section="round", main_spring_wire_size_mm=[3.0],
                            main_spring_mean_body_diameter_mm=44.0))
    assert r.values["main_spring_wire_size_mm"] == [3.0]
    assert r.get("main_spring_wire") == "R3.00" and r.get("main_spring_mean_body_diameter_mm") == 44.0
    # NOTES.md: the printed 3.0 mm wire fails the coil-gap check in the 8.8 mm housing
    assert r.check("spring_coil_gap").verdict == FAIL


def test_manual_bolt_is_verified_not_escalated():
    # automatic: M8x1.25 8.8 passes (case 1); a manual M10x1.5 10.9 is kept and checked: its 10.2 mm bore does
    # not fit the 8.2 mm support
    auto = case_flowchart("case1_as_run")
    assert (auto.get("bolt_format"), auto.get("bolt_property_class")) == ("M8x1.25", "8.8")
    r = flowchart.run(_case(bolt_mode="manual", bolt_format="M10x1.5", bolt_property_class="10.9"))
    assert (r.get("bolt_format"), r.get("bolt_property_class")) == ("M10x1.5", "10.9")
    assert r.check("pivot_bore").verdict == FAIL and r.check("bolt_yield").verdict == "pass"


def test_screening_eol_damping_is_optimistic_by_a_bounded_amount():
    # screening = linear cone spring (flatter force drop) + closed-form wear: it overstates the
    # end-of-life damping; on case 1 by ~13 % (benchmarks/bench_flowchart.py reports the number)
    d = documents.load_input(CASES / "case1_as_run.yaml")
    full = flowchart.run(d, flowchart.Settings(fidelity="full"))
    fast = flowchart.run(d, flowchart.Settings(fidelity="screening-only"))
    assert full.values["damping_eol_nm"] < fast.values["damping_eol_nm"] < 1.15 * full.values["damping_eol_nm"]
    assert any("not verified at full fidelity" in n for n in fast.notes)
    # fidelity "screening" reports nothing the full model did not check: the same design, values and checks
    judged = flowchart.run(d, flowchart.Settings(fidelity="screening"))
    assert judged.parts == full.parts and judged.values["damping_eol_nm"] == full.values["damping_eol_nm"]
    assert [(c.id, c.verdict, c.margin) for c in judged.checks] == [(c.id, c.verdict, c.margin) for c in full.checks]


from hypothesis import HealthCheck, given, settings, strategies as st  # noqa: E402


@settings(max_examples=25, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(alpha=st.floats(1.0, 179.0), arm=st.floats(2.5, 5.0), torque=st.floats(0.5, 6.0),
       damping=st.floats(0.1, 3.0), env=st.sampled_from(["dry", "belt_in_oil"]),
       hours=st.floats(0.0, 3000.0, allow_subnormal=False), stiffness=st.floats(0.005, 0.05))
def test_any_valid_input_gives_a_verdict_never_nan(alpha, arm, torque, damping, env, hours, stiffness):
    raw = dict(load_case("case1_as_run")["inputs"], differential_angle_deg=alpha, working_arm_mm=arm,
               calculated_torque_target_nm=torque, damping_target_nm=damping, damping_tolerance_nm=damping / 4,
               damping_eol_limit_nm=damping * 0.75, application_type=env, durability_duration_h=hours,
               spring_stiffness_nm_per_deg=stiffness, pivot_class_diameter_mm=None, loading_arm_mm=None,
               pivot_bushing_radial_thickness_mm=1.0)
    r = flowchart.run(schema.validate(raw), flowchart.Settings(fidelity="screening"))
    assert r.verdict in ("pass", "fail", "incomplete")
    # a run stopped by the procedure keeps no NaN values: test_stopped_result_values_are_never_nan
    stopped = max(r.steps_run) < 10
    for k in _nan_values(r):
        assert stopped, k
    for c in r.checks:
        assert c.margin is None or not np.isnan(c.margin), c.id
