"""issue 34's done-when: ``synth design --capability 1.33`` on the default case, and an independent Monte Carlo of
the design it names.

On the default case (thesis case 3 completed) no catalog design passes every check with a made joint: the
application's 11 mm seat caps the head's bearing, and a tightening method's window (F_M,max = 1.6 F_req for the
torque found on the joint) crushes it. synth names that input and the value that allows a design at Ppk >= 1.33
(percentile method), and the design. The independent Monte Carlo below reproduces that design's capability with
its own numbers: plain pseudo-random sampling (numpy's PCG64, not Sobol), its own reading of
``catalogs/tolerances.csv`` (the csv module: kinds and bands resolved here), and the physics through
:mod:`synth.model` (not the evaluator): every targeted check whose Ppk synth reports below 3 agrees within 0.05
(the ISO 22514-2 percentile index of both), every bounded check (its scatter from uniform bands only: synth reports
0 ppm from its worst case) shows no violation in 400,000 samples.
"""

from __future__ import annotations

import csv
import dataclasses

import numpy as np
import pytest

from synth import catalog
from synth.model import bolted_joint, damping, packaging, plain_bushing, pivot, torsion_spring
from synth.robust.settings import RobustSettings
from synth.robust.synthesis import robust_solve
from synth.scenes.demo import default_input

N = 400_000
SAMPLES = 8192  # synth design's default


@pytest.fixture(scope="module")
def answer():
    d = default_input()
    rs = RobustSettings(capability=1.33, samples=SAMPLES)
    r = robust_solve(d, "standard,cost", rs=rs)
    why = r.robust["prevented_by"]
    relaxed = dataclasses.replace(d, **{why["name"]: why["allows"]})
    r2 = robust_solve(relaxed, "standard,cost", rs=rs)
    return d, r, why, relaxed, r2


def test_the_default_case_names_the_seat_and_the_value_that_allows_a_capable_design(answer):
    d, r, why, relaxed, r2 = answer
    # the answer as asked (the thesis's nominal joint) with its production capability, which misses the target
    assert r.feasible and r.robust["meets"] is False and "under_head" in r.robust["failing"]
    assert why["kind"] == "input"
    assert why["name"] == "bolt_head_contact_external_diameter_mm" and why["value"] == 11.0
    # F_M,max = 1.6 x 13875 N on a 400 MPa support needs a bearing of sqrt(4 x 22200/(pi 400) + 8.2^2) = 11.74 mm
    assert 11.74 <= why["allows"] <= 12.5
    assert "bolt_head_contact_external_diameter_mm = 11 mm" in r.notes[-1]
    assert r2.robust["meets"] and r2.parts == why["design"]
    # buildable: its head bears on its own flange within the seat, tightened by a method of the catalog
    assert r2.parts["bolt_head_type"] in ("flange", "hex", "socket") and r2.get("bolt_head_contact_diameter_mm") <= \
        why["allows"] + 1e-9
    targeted = [c for c in r2.robust["checks"] if c["target"]]
    assert all(c["ppk"] is None or c["ppk"] >= 1.33 for c in targeted)  # None: +inf (a constant, a 0 ppm bound)
    assert r2.robust["settings"]["method"] == "percentile"


# --------------------------------------------------------------------------------------------- its own catalog reading
def _rows(name):
    with open(catalog.builtin_dir() / f"{name}.csv", newline="") as fh:
        return list(csv.DictReader(row for row in fh if not row.startswith("#")))


def _constant(name):
    for path in sorted(catalog.builtin_dir().glob("constants*.csv")):
        with open(path, newline="") as fh:
            for row in csv.DictReader(fh):
                if row["name"] == name:
                    return float(row["value"])
    raise KeyError(name)


def _bands(d, parts):
    """``{quantity: (kind, lo, hi)}`` of the quantities in play for a radial-only design, read from the CSV here."""
    tol = {r["quantity"]: r for r in _rows("tolerances")}
    wire = {r["designation"]: r for r in _rows("spring_wires")}[parts["main_spring_wire"]]
    out = {}
    for q, r in tol.items():
        src = r["band_from"].strip()
        if src.startswith("spring_wires."):
            h = float(wire[src.split(".")[1]])
            out[q] = (r["kind"], -h, h)
        elif src.startswith("constants."):
            h = _constant(src.split(".")[1])
            out[q] = (r["kind"], -h, h)
        elif src.startswith("input."):
            h = float(getattr(d, src.split(".")[1]))
            out[q] = (r["kind"], -h, h)
        elif src.startswith("iso286_it_grades."):
            pd = pivot.pivot_diameter_mm(parts["pivot_class_diameter_mm"], 0.5)
            it = next(x for x in _rows("iso286_it_grades") if float(x["over_mm"]) < pd <= float(x["up_to_mm"]))
            h = float(it[src.split(".")[1]]) / 2000.0
            out[q] = (r["kind"], -h, h)
        elif src == "bolt_tightening.alpha_a_max":
            a = float({x["tightening_method"]: x for x in _rows("tightening_factors")}[parts["bolt_tightening"]]
                      ["alpha_a_max"])
            h = 100.0 * (a - 1.0) / (a + 1.0)
            out[q] = (r["kind"], -h, h)
        elif src == "spring_material_strength":
            out[q] = (r["kind"], 0.0, 1.0)  # resolved below, in the material's own range
        elif not src and float(r["band"]) > 0:
            out[q] = (r["kind"], -float(r["band"]), float(r["band"]))
    return out


def _draw(rng, kind, lo, hi, n):
    if kind == "normal":
        return (lo + hi) / 2.0 + (hi - lo) / 6.0 * rng.standard_normal(n)
    return rng.uniform(lo, hi, n)


def _percentile_ppk(m):
    med, low = np.quantile(m, [0.5, 0.00135])
    return med / (med - low)


def _independent(d, parts, n=N, seed=20250101):
    """The targeted margins of the radial-only design ``parts`` of input ``d`` for ``n`` made tensioners."""
    rng = np.random.default_rng(seed)
    bands = _bands(d, parts)
    dev = {q: _draw(rng, k, lo, hi, n) for q, (k, lo, hi) in bands.items()}
    zero = np.zeros(n)
    g = dev.get
    # --- the core: the design's split at nominal, then the made tensioner (eq. (12)-(13) forward)
    mu0 = float({r["friction"]: r for r in _rows("friction_coefficients")}["pivot_bushing dry"]["mu"])
    wall = float({r["supplier"]: r for r in _rows("pivot_bushings")}[parts["pivot_bushing_supplier"]]["radial_thickness_mm"])
    pd0 = float(pivot.pivot_diameter_mm(parts["pivot_class_diameter_mm"], wall))
    arm, alpha, t_c = d.working_arm_mm, d.differential_angle_deg, d.calculated_torque_target_nm
    rho0 = damping.lever_ratio(pd0, mu0, arm, alpha)
    m_s0 = float(damping.damping_split(t_c, d.damping_target_nm, rho0)["spring_torque_nominal_nm"])
    mu = mu0 * (1.0 + g("pivot_bushing_friction", zero) / 100.0)
    pd = pd0 + g("pivot_diameter", zero)
    rho = damping.lever_ratio(pd, mu, arm, alpha)
    m_s = m_s0 * (1.0 + g("spring_torque", zero) / 100.0)
    made = damping.made_tensioner(m_s, 0.0, rho)
    dmp = made["damping_nm"]
    hub = damping.hubload_nominal_n(made["calculated_torque_nm"], arm, alpha)
    up, lo_ = d.damping_target_nm + d.damping_tolerance_nm, d.damping_target_nm - d.damping_tolerance_nm
    out = {"damping_upper": (up - dmp) / up, "damping_lower": (dmp - lo_) / lo_, "self_locking": 1.0 - rho}
    # --- the bushing (step 4)
    bush = {r["supplier"]: r for r in _rows("pivot_bushings")}[parts["pivot_bushing_supplier"]]
    b = plain_bushing.evaluate_bushing(hub, pd, parts["pivot_bushing_length_mm"], d.durability_theta_peak_to_peak_deg,
                                       d.durability_frequency_hz, d.durability_duration_h,
                                       k_w_mm3_per_n_m=float(bush["k_w_dry_mm3_per_n_m"]),
                                       radial_clearance_mm=float(bush["radial_clearance_mm"]),
                                       belt_plane_height_mm=d.middle_plane_belt_height_mm,
                                       max_pivot_height_mm=d.max_pivot_height_mm, axial_damping=False,
                                       pulley_diameter_mm=d.pulley_diameter_mm)
    pvt = float(bush["pvt_max_dry_mpa_m_per_s_h"])
    out["bushing_pvt"] = (pvt - b["pvt_mpa_m_per_s_h"]) / pvt
    # --- the main spring (step 9): the made wire, coil diameter, strength and torque; its coils as drawn
    wire = {r["designation"]: r for r in _rows("spring_wires")}[parts["main_spring_wire"]]
    mat = {r[next(iter(r))]: r for r in _rows("spring_materials")}[parts["main_spring_material"]]
    rnd = wire["section"] == "round"
    b0, h0, dm0 = float(wire["b_mm"]), float(wire["h_mm"]), parts["main_spring_mean_body_diameter_mm"]
    hh = h0 + g("spring_wire_height", zero)
    bb = hh if rnd else b0 + g("spring_wire_width", zero)
    dm = dm0 + g("spring_coil_diameter", zero)
    e = float(mat["E_mpa"])
    dia = torsion_spring.rm_lookup_diameter_mm(b0, h0, rnd)
    rm_min = float(torsion_spring.material_strength_mpa(parts["main_spring_material"], dia, "min"))
    rm_max = float(torsion_spring.material_strength_mpa(parts["main_spring_material"], dia, "max"))
    rm = rm_min + (rm_max - rm_min) * rng.uniform(0.0, 1.0, n) if "spring_tensile_strength" in bands else rm_min
    k0 = d.spring_stiffness_nm_per_deg
    n_nom = torsion_spring.active_coils(e, torsion_spring.second_moment_mm4(b0, h0, rnd), dm0, k0)
    n_made = torsion_spring.active_coils(e, torsion_spring.second_moment_mm4(bb, hh, rnd), dm, k0)
    bearing = {r["designation"]: r for r in _rows("ball_bearings")}[parts["ball_bearing"]]
    sp = torsion_spring.main_spring_design(
        E_mpa=e, Rm_mpa=rm, sigma_y_mpa=float(mat["sigma_y_bend_fraction"]) * rm,
        sigma_A0_mpa=float(mat["sigma_A0_fraction"]) * rm, b_mm=bb, h_mm=hh, round_wire=rnd, mbd_mm=dm,
        stiffness_nm_per_deg=k0 * n_made / n_nom, spring_torque_nominal_nm=m_s, torque_tolerance_pct=0.0,
        theta_pp_deg=d.durability_theta_peak_to_peak_deg,
        housing_height_mm=packaging.spring_housing_height_mm(d.middle_plane_belt_height_mm, float(bearing["B_mm"])),
        housing_outer_diameter_mm=packaging.spring_housing_outer_diameter_mm(float(bearing["D_mm"]), arm),
        housing_inner_diameter_mm=packaging.spring_housing_inner_diameter_mm(parts["pivot_class_diameter_mm"]),
        dtheta_inst_nom_deg=d.arm_travel_nominal_to_installation_deg,
        dtheta_nom_free_arm_deg=d.arm_travel_nominal_to_free_deg, mbd_tol_mm=0.0,
        housing_outer_tol_mm=-g("spring_housing_outer_diameter", zero),
        housing_inner_tol_mm=g("spring_housing_inner_diameter", zero))
    lim = sp["sigma_y_limit_mpa"]  # the thesis basis (the default spring_limit_basis)
    out["spring_yield"] = (lim - sp["main_spring_sigma_inst_mpa"]) / lim
    sf = _constant("main_spring_min_safety_factor")
    out["spring_fatigue"] = (sp["main_spring_safety_factor"] - sf) / sf
    c_max, c_min = _constant("main_spring_index_max"), _constant("main_spring_index_min")
    out["spring_index_max"] = (c_max - sp["spring_index"]) / c_max
    out["spring_index_min"] = (sp["spring_index"] - c_min) / c_min
    out["spring_outer_contact"] = (sp["housing_outer_diameter_min_mm"] - sp["outer_diameter_max_mm"]) / \
        sp["housing_outer_diameter_min_mm"]
    out["spring_inner_contact"] = (sp["inner_diameter_min_mm"] - sp["housing_inner_diameter_max_mm"]) / \
        sp["housing_inner_diameter_max_mm"]
    out["spring_coil_gap"] = (sp["coil_gap_worst_mm"] - _constant("main_spring_min_coil_gap_mm")) / bb
    # --- the joint (step 10): the made preload in its tightening window, the safety factors on the specified hubload
    hl_spec = float(bolted_joint.nominal_hubload_n(t_c, arm, alpha))

    def joint(belt_offset_mm, **made):
        return bolted_joint.fixation(
            hl_spec, d.middle_plane_belt_height_mm, belt_offset_mm, d.tilting_safety_factor,
            d.sliding_safety_factor, d.engine_support_internal_diameter_mm, d.engine_support_external_diameter_mm,
            d.contact_angle_deg, d.support_yield_strength_compression_mpa, d.support_yield_strength_traction_mpa,
            method="vdi2230", number_of_active_threads=d.number_of_active_threads,
            bolt_head_contact_external_diameter_mm=d.bolt_head_contact_external_diameter_mm,
            head_type=parts["bolt_head_type"], washer=parts["bolt_washer"], bolt_format=parts["bolt_format"],
            bolt_property_class=parts["bolt_property_class"], tightening_method=parts["bolt_tightening"], **made)
    window = joint(d.middle_plane_belt_height_increment_worst_mm)
    f_made = float(window["bolt_axial_force_n"]) * (1.0 + g("bolt_preload", zero) / 100.0)
    j = joint(g("belt_offset", zero), clamp_force_n=f_made)
    out["tilting"] = (j["tilting_safety_factor"] - d.tilting_safety_factor) / d.tilting_safety_factor
    out["sliding"] = (j["sliding_safety_factor"] - d.sliding_safety_factor) / d.sliding_safety_factor
    s_c, s_t = d.support_yield_strength_compression_mpa, d.support_yield_strength_traction_mpa
    out["under_head"] = (s_c - j["bolt_under_head_stress_mpa"]) / s_c
    out["thread"] = (s_t - j["bolt_thread_stress_mpa"]) / s_t
    out["pivot_base_pressure"] = (s_c - j["pivot_base_max_pressure_mpa"]) / s_c
    zul = float(window["bolt_permissible_preload_n"])
    out["bolt_preload_vdi"] = (zul - f_made) / zul
    return out


def test_an_independent_monte_carlo_agrees_within_0_05_in_ppk(answer):
    _, _, _, relaxed, r2 = answer
    parts = r2.parts
    assert parts["damper_pad_class"] == "none"  # a radial-only design: the independent model covers it
    mine = _independent(relaxed, parts)
    checks = {c["id"]: c for c in r2.robust["checks"] if c["target"]}
    compared = 0
    for cid, c in checks.items():
        if c["sd_margin"] == 0 or (not c["bounded"] and (c["ppk"] is None or c["ppk"] >= 3.0)):
            continue  # deterministic, or far above the target (an index of 10 is not compared to 0.05)
        assert cid in mine, f"{cid}: a targeted check near the target that the independent model does not compute"
        m = np.asarray(mine[cid], dtype=float)
        if c["bounded"]:
            assert c["ppm"] == 0.0 and int((m < -1e-9).sum()) == 0, cid
        else:
            assert _percentile_ppk(m) == pytest.approx(c["ppk_percentile"], abs=0.05), cid
        compared += 1
    assert compared >= 6, compared
    assert {"spring_fatigue", "damping_upper", "sliding", "under_head"} <= set(mine)
