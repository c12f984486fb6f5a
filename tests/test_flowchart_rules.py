"""The flowchart's decision rules, each pinned to the thesis sentence or table it comes from, with an application on
each side of every boundary (docs/sections/flowchart_rules.md lists every rule and the test that pins it).

Source: the thesis (``shared/seeds/tensioner_design_thesis.txt``): step 3 and Tables 3-4, step 5, step 9, step 10
with eq. (103)-(107); the applications are thesis case 1 (as run) and case 3 with one input moved across a boundary.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from synth import flowchart
from synth.parts import arrays
from synth.model import bolted_joint

from conftest import case_input

CASE1_RHO = 8.0 * math.sin(math.atan(0.055)) / (5.0 * math.sin(math.radians(85.0)))  # r_p sin(atan mu)/(e_w sin a)
CASE1_D_RAD = 3.25 * CASE1_RHO   # radial damping of case 1, eq. (10): 0.2867 N m


def _run(name="case1_as_run", **changes):
    return flowchart.run(case_input(name, **changes), time_points=0)


def _with_axial_damping(d_ax_nm, **changes):
    """Case 1 with the damping target that leaves ``d_ax_nm`` of axial damping (D_ax = D - T_c rho, step 3); no
    end-of-life limit, so step 5 keeps the classes Tables 3-4 give (the iteration is tested below)."""
    return _run(damping_target_nm=CASE1_D_RAD + d_ax_nm, damping_eol_limit_nm=None, **changes)


# --- step 3: "if the tensioner damping required is higher than the radial one, the axial damping group has to be
# introduced"

@pytest.mark.parametrize("excess, present", [(0.01, True), (-0.01, False)])
def test_axial_group_only_where_the_target_exceeds_the_radial_damping(excess, present):
    r = _run(damping_target_nm=CASE1_D_RAD + excess, damping_tolerance_nm=0.05, damping_eol_limit_nm=None)
    assert r.values["radial_damping_nm"] == pytest.approx(CASE1_D_RAD, rel=1e-12)
    assert bool(r.values["axial_damping_present"]) is present
    assert (r.get("damper_pad_class") != "none") is present
    assert ({5, 6, 8} <= set(r.steps_run)) is present


# --- Tables 3-4: "Damper pad dimensions as a function of the axial damping", rows DAX < 0.7, 0.7 < DAX < 1.10,
# 1.10 < DAX < 2.00 Nm, entered with D_ax of eq. (9) (both friction faces), not with half of it

@pytest.mark.parametrize("d_ax, pad, spacer", [
    (0.69, "DP1", "ES1"), (0.71, "DP2", "ES2"),     # the 0.7 N m bound
    (1.09, "DP2", "ES2"), (1.11, "DP3", "ES3"),     # the 1.10 N m bound
    (0.45, "DP1", "ES1"),                           # half of it (0.225) and itself agree: both row 1
    (0.90, "DP2", "ES2"),                           # half of it (0.45) would give row 1
    (1.71, "DP3", "ES3"),                           # case 1: half of it (0.86) would give row 2, as the tool printed
])
def test_tables_3_4_are_entered_with_the_axial_damping(d_ax, pad, spacer):
    r = _with_axial_damping(d_ax)
    assert r.values["axial_damping_nm"] == pytest.approx(d_ax, rel=1e-9)
    assert (r.get("damper_pad_class"), r.get("endcap_spacer_class")) == (pad, spacer)
    for cid in ("damper_pad_capacity", "endcap_spacer_capacity"):
        c = r.check(cid)
        assert c.verdict == "pass" and c.value == pytest.approx(d_ax, rel=1e-9)


@pytest.mark.parametrize("d_ax, verdict", [(1.99, "pass"), (2.01, "fail")])
def test_above_table_3_the_largest_class_is_checked_and_fails(d_ax, verdict):
    r = _with_axial_damping(d_ax)
    assert (r.get("damper_pad_class"), r.get("endcap_spacer_class")) == ("DP3", "ES3")
    assert r.check("damper_pad_capacity").verdict == r.check("endcap_spacer_capacity").verdict == verdict
    assert any("above every damper-pad class of Table 3" in n for n in r.notes) is (verdict == "fail")


def test_the_optimiser_reads_the_same_capacity_rule():
    # the registry's capacity checks (one rule for flowchart, optimiser and bulk): case 1's D_ax = 1.71 N m is above
    # the 1.10 N m bound of class 2, so the tool's printed DP2/ES2 fail them and DP3/ES3 pass
    from synth.design.verify import verify
    base = _run().parts
    printed = verify(case_input("case1_as_run"), {**base, "damper_pad_class": "DP2", "endcap_spacer_class": "ES2",
                                                  "cone_spring_external_diameter_mm": 30.0})
    c = printed.check("damper_pad_capacity")
    assert (c.verdict, c.limit) == ("fail", 1.10) and c.value == pytest.approx(2.0 - CASE1_D_RAD, rel=1e-9)
    assert printed.check("endcap_spacer_capacity").verdict == "fail"
    assert verify(case_input("case1_as_run"), base).check("damper_pad_capacity").verdict == "pass"


# --- step 5: "If this is not the case and if the contact surfaces are not at maximum, these are incremented and
# simulation is run again. This step is repeated until the EOL damping value is respected, or until is possible to
# increase the contact surfaces."

D_AX_CLASS1 = 0.60   # Table 3 row 1: the iteration can take both further rows


def _eol_damping_of_class_1():
    r = _with_axial_damping(D_AX_CLASS1)
    assert r.get("damper_pad_class") == "DP1" and r.check("damping_eol").verdict == "not verified"
    return r.values["damping_eol_nm"]


@pytest.mark.parametrize("offset, pad, attempts", [(-1e-3, "DP1", 0), (+1e-3, "DP2", 1)])
def test_eol_damping_below_its_limit_triggers_the_second_iteration(offset, pad, attempts):
    eol1 = _eol_damping_of_class_1()
    r = _run(damping_target_nm=CASE1_D_RAD + D_AX_CLASS1, damping_eol_limit_nm=eol1 + offset)
    assert (r.get("damper_pad_class"), r.get("endcap_spacer_class")) == (pad, pad.replace("DP", "ES"))
    iterations = [n for n in r.notes if n.startswith("step 5, attempt")]
    assert len(iterations) == attempts
    if attempts:
        assert f"end-of-life damping {eol1:.3f} Nm below the limit" in iterations[0]
        assert "increased to DP2/ES2" in iterations[0]
        # the larger contact surfaces wear less: the re-run passes
        assert r.check("damping_eol").verdict == "pass" and r.values["damping_eol_nm"] > eol1 + offset
    # the axial damping is the same at every attempt: the cone spring is resized for the new radii (eq. (9))
    assert r.values["axial_damping_nm"] == pytest.approx(D_AX_CLASS1, rel=1e-9)


def test_iteration_stops_at_the_largest_contact_surfaces():
    eol1 = _eol_damping_of_class_1()
    r = _run(damping_target_nm=CASE1_D_RAD + D_AX_CLASS1, damping_eol_limit_nm=eol1 + 0.1)
    assert (r.get("damper_pad_class"), r.get("endcap_spacer_class")) == ("DP3", "ES3")
    notes = [n for n in r.notes if n.startswith("step 5, attempt")]
    assert len(notes) == 3 and "no larger class" in notes[-1]
    assert r.check("damping_eol").verdict == "fail"


def test_next_class_follows_the_table_bounds():
    p = arrays()
    assert [flowchart._next_class(p.damper_pad, i) for i in range(3)] == [1, 2, 2]
    assert [flowchart._next_class(p.endcap_spacer, i) for i in range(3)] == [1, 2, 2]


# --- step 9: "Round wire is preferred due to the lower cost ... if it is not sufficient, the rectangular wire is
# implemented" (the cheapest round wire is chosen over a cheaper flat one where round suffices:
# tests/test_torsion_spring.py::test_automatic_spring_is_the_cheapest_feasible_round_wire)

@pytest.mark.parametrize("travel, section", [(28.6, "round"), (35.0, "rectangular")])
def test_rectangular_wire_only_where_no_round_wire_suffices(travel, section, tmp_path):
    # at the thesis tool's dry friction 0.15 (the spring torque the tool printed, 1.56 N m): with the default 0.10
    # (issue 34) case 3's spring carries 1.72 N m and no round wire suffices at any travel
    from synth import catalog
    fr = catalog.load("friction_coefficients")
    fr[fr["friction"] == "pivot_bushing dry"].assign(mu=0.15).to_csv(tmp_path / "friction_coefficients.csv",
                                                                      index=False)
    with catalog.overriding(tmp_path):
        r = _run("case3", arm_travel_nominal_to_installation_deg=travel)
    assert r.values["main_spring_wire_section"] == section
    note = next(n for n in r.notes if n.startswith("main spring (automatic)"))
    n_round = int(note.split(": ")[1].split(" round-wire")[0])
    assert (n_round > 0) is (section == "round")
    assert r.check("spring_yield").verdict == "pass"


# --- step 10: "This output is needed in order to detect the correct bolt material class, in such a way to avoid
# overcoming the yield limit. If the equivalent stress level overcomes the yield limit of the maximum bolt material
# class, the bolt format is increased." As a first attempt, the M8x1,25 is considered.

@pytest.mark.parametrize("sliding_sf, fmt, cls", [
    (2.62, "M8x1.25", "8.8"), (2.63, "M8x1.25", "9.8"),        # sigma_eqv across Rp0.2 = 640 MPa of 8.8
    (4.50, "M8x1.25", "12.9"), (4.60, "M10x1.5", "9.8"),       # across Rp0.2 = 1100 MPa of 12.9: the next format
])
def test_bolt_class_then_format_at_the_yield_limit(sliding_sf, fmt, cls):
    r = _run(sliding_safety_factor=sliding_sf)
    assert (r.get("bolt_format"), r.get("bolt_property_class")) == (fmt, cls)
    c = r.check("bolt_yield")
    assert c.verdict == "pass" and c.value <= c.limit
    # sliding governs (eq. (100)): sigma_eqv is proportional to the safety factor, 609.08 MPa at case 1's 2.5
    assert c.value * 2.5 / sliding_sf == pytest.approx(609.08, rel=1e-4) or fmt != "M8x1.25"


def test_case1_bolt_class_by_eq_103_104_as_printed_and_by_the_stress_area():
    """Case 1 as run: at F = 16312 N (eq. (97)-(100)) the printed eq. (103)-(104) (core diameter d - 1.2268 P) give
    sigma_eqv 647.3 MPa > Rp0.2 640 MPa (class 8.8 fails, 9.8 needed); the ISO 898-1 stress area gives 609.1 MPa,
    the tool printed 607.23 MPa and chose 8.8, and so does the production tensioner: the printed values follow the
    stress area, not the printed equation."""
    r = _run()
    f = r.values["bolt_axial_force_n"]
    assert f == pytest.approx(16312, rel=1e-3)
    d, pitch, mu = 8.0, 1.25, 0.14
    d2, d3 = d - 0.649519 * pitch, d - 1.226869 * pitch                 # ISO 724; eq. (102), (104)
    tau = 16.0 * f / 2.0 * (pitch / math.pi + mu * d2 / math.cos(math.radians(30.0))) / (math.pi * d3 ** 3)
    assert r.values["bolt_tau_mpa"] == pytest.approx(tau, rel=1e-3)   # eq. (105)-(106): 239.7 MPa (printed 239.94)
    core = f / (math.pi / 4.0 * (d - 1.2268 * pitch) ** 2)              # eq. (103)-(104) as printed: 496.7 MPa
    stress_area = f / (math.pi / 4.0 * ((d2 + d3) / 2.0) ** 2)          # ISO 898-1 A_s = 36.6 mm2: 445.7 MPa
    eqv_core, eqv_as = math.hypot(core, math.sqrt(3.0) * tau), math.hypot(stress_area, math.sqrt(3.0) * tau)
    assert (eqv_core, eqv_as) == pytest.approx((647.3, 609.0), abs=0.1)   # synth: 609.08 with A_s = 36.6 (3 figures)
    assert r.values["bolt_sigma_eqv_mpa"] == pytest.approx(eqv_as, rel=2e-3)   # catalog A_s 36.6 (3 figures)
    rp02 = {k: v for k, v in zip(arrays().bolt_class.key, arrays().bolt_class.rp02_min_mpa)}
    assert eqv_core > rp02["8.8"] > eqv_as and eqv_core < rp02["9.8"]
    assert r.get("bolt_property_class") == "8.8"
    # the same two readings through the model's option (normal_stress_area="core" is eq. (103)-(104) as printed)
    args = (r.values["hubload_nominal_n"], 29.5, 2.0, 2.5, 2.5, 8.2, 22.9, 360, 400, 400)   # case1_as_run inputs
    kw = dict(number_of_active_threads=2.3, mu_crankcase=0.10, mu_thread=0.14, mu_head=0.08,
              bolt_head_contact_external_diameter_mm=13.0, candidates=[("M8x1.25", "8.8")])
    printed = bolted_joint.fixation(*args, **kw, normal_stress_area="core")
    assert float(np.ravel(printed["bolt_sigma_eqv_mpa"])[0]) == pytest.approx(eqv_core, rel=2e-3)
