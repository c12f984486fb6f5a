"""Step 9, main torsion spring: hand calculations, thesis cases 1 and 3, properties.

Sources: thesis eq. (64)-(93), Tables 9-10 (case 1) and 13-14 (case 3), synth/data/cases/NOTES.md.
"""

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from synth import catalog, flowchart
from synth.parts import arrays
from synth.design import evaluate as Ev
from synth.design.applications import Applications
from synth.design.constraints import REGISTRY, margin
from synth.design.space import space, spring_attributes
from synth.design.verify import evaluate_design, verify
from synth.errors import InputError
from synth.model import torsion_spring as ms

from conftest import case_flowchart, case_input, load_case

E = 206000.0  # MPa, EN 13906-1 / thesis tool (NOTES.md)


# ------------------------------------------------------------------ hand calculations


def test_active_coils_round_hand_calc():
    # eq. (64): n = E pi d^4 / (180*64 k mbd), k in N mm/deg
    # 206000 * pi * 2.3^4 / (11520 * 16.4 * 44) = 206000*3.14159*27.9841/8312832 = 2.17861
    n = ms.active_coils(E, ms.second_moment_mm4(2.3, 2.3, True), 44.0, 0.0164)
    assert float(n) == pytest.approx(2.17861, rel=1e-4)


def test_active_coils_rectangular_hand_calc():
    # eq. (65): n = E b h^3 / (180*12 k mbd) = 206000*2.3*12.167/(2160*18*41) = 5764707/1594080 = 3.61633
    n = ms.active_coils(E, ms.second_moment_mm4(2.3, 2.3, False), 41.0, 0.018)
    assert float(n) == pytest.approx(3.61633, rel=1e-4)
    # and stiffness inverts it
    k = ms.stiffness_nm_per_deg(E, ms.second_moment_mm4(2.3, 2.3, False), 41.0, n)
    assert float(k) == pytest.approx(0.018, rel=1e-12)


def test_rectangular_inertia_uses_radial_side_cubed():
    # b = 3 (axial), h = 2 (radial): I = 3*8/12 = 2.0; Z = 3*4/6 = 2.0
    assert float(ms.second_moment_mm4(3.0, 2.0, False)) == pytest.approx(2.0)
    assert float(ms.section_modulus_mm3(3.0, 2.0, False)) == pytest.approx(2.0)


def test_equivalent_diameter_has_pi():
    # eq. (77) corrected: (16*2.3*2.3^2/(3 pi))^(1/3) = (194.672/9.42478)^(1/3) = 20.6554^(1/3) = 2.74375
    d = ms.equivalent_diameter_mm(2.3, 2.3, False)
    assert float(d) == pytest.approx(2.74375, rel=1e-5)
    # same section modulus as the square: pi d^3/32 = b h^2/6 = 2.02783
    assert math.pi * float(d) ** 3 / 32 == pytest.approx(2.3**3 / 6, rel=1e-9)


def test_curvature_factor_hand_calc():
    # c = 10: (400 - 10 - 1)/(4*10*9) = 389/360 = 1.080556 ; outer (400+10-1)/(40*11) = 409/440 = 0.929545
    assert float(ms.curvature_factor(10.0)) == pytest.approx(389 / 360, rel=1e-12)
    assert float(ms.curvature_factor(10.0, "outer")) == pytest.approx(409 / 440, rel=1e-12)
    with pytest.raises(InputError, match="fibre"):
        ms.curvature_factor(10.0, "middle")


def test_bending_stress_round_hand_calc():
    # 3 N m on d = 3 mm, mbd 30: Z = pi*27/32 = 2.650719; c = 10, kf = 1.080556
    # sigma = 1.080556 * 3000 / 2.650719 = 1222.95 MPa
    s = ms.bending_stress_mpa(3.0, 30.0, 3.0, 3.0, True)
    assert float(s) == pytest.approx(1222.95, rel=1e-4)


def test_working_angles_and_torques():
    # eq. (66): 3.07*1.04/0.018 = 177.378 ; (67)-(68): +-8 ; (69): +50 ; (70): -30
    a = ms.working_angles_deg(3.07, 4, 0.018, 16, 50, 30)
    assert float(a["theta_nom"]) == pytest.approx(177.3778, rel=1e-5)
    assert float(a["theta_plus"] - a["theta_minus"]) == pytest.approx(16.0)
    assert float(a["theta_inst"]) == pytest.approx(227.3778, rel=1e-5)
    assert float(a["theta_free_arm"]) == pytest.approx(147.3778, rel=1e-5)
    assert float(ms.torque_nm(a["theta_nom"], 0.018)) == pytest.approx(3.07 * 1.04, rel=1e-12)
    lower = ms.working_angles_deg(3.07, 4, 0.018, 16, 50, 30, torque_tolerance_side=-1)
    assert float(lower["theta_nom"]) == pytest.approx(3.07 * 0.96 / 0.018, rel=1e-12)


def test_coils_diameter_gap_hooks():
    # winding 90 deg adds 0.25 coil; mbd*n conserved: 44*2/2.25 = 39.111
    n = ms.coils_at_angle(2.0, 90.0, True)
    assert float(n) == pytest.approx(2.25)
    assert float(ms.coils_at_angle(2.0, 90.0, False)) == pytest.approx(1.75)
    assert float(ms.mean_diameter_at_coils_mm(44.0, 2.0, n)) == pytest.approx(39.1111, rel=1e-5)
    # eq. (92)/(90): (8.8 - 2.3)/2.5 - 2.3 = 0.3
    assert float(ms.coil_gap_mm(8.8, 2.3, 2.5)) == pytest.approx(0.3)
    # hooks: 360*(ceil(2.18)-2.18) = 295.2 ; winding by 87.2 deg -> 208.0
    assert float(ms.hooks_angle_deg(2.18)) == pytest.approx(295.2)
    assert float(ms.hooks_angle_deg(2.18 + 87.2 / 360)) == pytest.approx(208.0)
    # eq. (83)/(87)
    assert float(ms.outer_diameter_max_mm(41, 0.4, 2.3, 0.03)) == pytest.approx(43.73)
    assert float(ms.inner_diameter_min_mm(41, 0.4, 2.3, 0.03)) == pytest.approx(38.27)


def test_goodman_safety_factor_branches():
    # Goodman branch: sa = 100, sm = 500, A0 = 500, Rm = 2000 -> 1/(0.2 + 0.25) = 2.2222 ; yield cap 1800/600 = 3
    assert float(ms.goodman_safety_factor(600, 400, 2000, 500, 1800)) == pytest.approx(1 / 0.45, rel=1e-9)
    # yield branch: sa = 10, sm = 1500: Goodman 1/(0.02+0.75) = 1.2987 ; yield 1800/1510 = 1.19205
    assert float(ms.goodman_safety_factor(1510, 1490, 2000, 500, 1800)) == pytest.approx(1800 / 1510, rel=1e-9)
    # no load: infinite, not NaN
    assert np.isinf(ms.goodman_safety_factor(0.0, 0.0, 2000, 500, 1800))


def test_material_strength_steps_through_the_standard_table():
    # EN 10270-2 Table 3, VDSiCr: 1.6 < d <= 2.0 -> 2010-2160; 2.0 < d <= 2.5 -> 1960-2060 (a step, not a line)
    assert float(ms.material_strength_mpa("VDSiCr", 2.0)) == pytest.approx(2010.0)
    assert float(ms.material_strength_mpa("VDSiCr", 2.3)) == pytest.approx(1960.0)
    assert float(ms.material_strength_mpa("VDSiCr", 2.5, "max")) == pytest.approx(2060.0)
    # below the first row: the first row (0.5 < d <= 0.8: 2080); above the last row: the last row (5.6-6.0: 1760)
    assert float(ms.material_strength_mpa("VDSiCr", 0.1)) == pytest.approx(2080.0)
    assert float(ms.material_strength_mpa("VDSiCr", 9.0)) == pytest.approx(1760.0)
    # Rm falls (weakly) with diameter for every material of the catalog
    df = catalog.load("spring_material_strength")
    for mat, sub in df.groupby("material"):
        rm = sub.sort_values("d_mm")["Rm_min_mpa"].to_numpy(float)
        assert np.all(np.diff(rm) <= 0), mat
        assert np.all(sub["Rm_max_mpa"].to_numpy(float) > sub["Rm_min_mpa"].to_numpy(float)), mat
    with pytest.raises(InputError, match="main_spring_material"):
        ms.material_strength_mpa("unobtainium", 2.0)
    with pytest.raises(InputError, match="main_spring_wire"):
        ms.wire_properties("R9.99")


def test_static_permissible_stress_is_reported_not_gating():
    # case-3 spring: sigma_inst 1659 MPa with q = 1.0407 (c = 19.13) -> 1594 MPa without q; 0.75 * 1960 = 1470 MPa
    r, _, _ = _case3()
    assert float(r["main_spring_sigma_inst_uncorrected_mpa"]) == pytest.approx(
        float(r["main_spring_sigma_inst_mpa"]) / float(r["curvature_factor"]), rel=1e-12)
    assert float(r["sigma_perm_static_limit_mpa"]) == pytest.approx(1470.0)
    c = REGISTRY["spring_static_permissible"]
    m = margin(c, r["main_spring_sigma_inst_uncorrected_mpa"], r["sigma_perm_static_limit_mpa"])
    assert float(m) == pytest.approx((1470.0 - 1594.2) / 1470.0, abs=2e-4)
    assert c.advisory and not c.objective    # reported (a warning), never gating
    # unwinding: 20 % lower
    assert float(ms.permissible_static_bending_stress_mpa(1960.0, 0.75, winding=False)) == pytest.approx(1176.0)


def test_catalogs_have_required_columns_and_sizes():
    wires = catalog.load("spring_wires")
    assert {"standard", "source", "b_tol_mm", "h_tol_mm"} <= set(wires.columns)
    rnd = wires[wires["section"] == "round"]["b_mm"].to_numpy(float)
    assert rnd.min() <= 2.0 and rnd.max() >= 4.5
    assert "F2.30x2.30" in set(wires["designation"])
    mats = catalog.load("spring_materials")
    assert {"VDSiCr", "VDCrV", "TDSiCr", "DH", "1.4310"} <= set(mats["material"])
    assert float(mats.set_index("material").loc["VDSiCr", "E_mpa"]) == 206000.0


# ------------------------------------------------------------------ catalog parts and the registry's step 9

STEP9 = ("spring_yield", "spring_fatigue", "spring_outer_contact", "spring_inner_contact", "spring_coil_gap",
         "spring_index_min", "spring_index_max")


def catalog_spring(material, wire, mbd_mm, **kw):
    """:func:`main_spring_design` of a catalog material and wire: the attributes the evaluator reads of the part."""
    p = arrays()
    a = spring_attributes(p, [p.spring_material.code(material)], [p.spring_wire.code(wire)], [mbd_mm])
    args = {k: a[k][0] for k in ("E_mpa", "Rm_mpa", "sigma_y_mpa", "sigma_A0_mpa", "b_mm", "h_mm", "round_wire",
                                 "b_tol_mm", "h_tol_mm", "sigma_perm_static_mpa")}
    return ms.main_spring_design(mbd_mm=mbd_mm, **args, **kw), args


def step9_margins(r, b_mm):
    """The registry's step-9 margins of a :func:`main_spring_design` result (values and limits as the evaluator
    pairs them; :func:`test_step9_margins_are_the_evaluators` checks the pairing)."""
    c = catalog.constant
    pairs = {"spring_yield": ("main_spring_sigma_inst_mpa", r["sigma_y_limit_mpa"]),
             "spring_fatigue": ("main_spring_safety_factor", c("main_spring_min_safety_factor")),
             "spring_outer_contact": ("outer_diameter_max_mm", r["housing_outer_diameter_min_mm"]),
             "spring_inner_contact": ("inner_diameter_min_mm", r["housing_inner_diameter_max_mm"]),
             "spring_coil_gap": ("coil_gap_worst_mm", c("main_spring_min_coil_gap_mm")),
             "spring_index_min": ("spring_index", c("main_spring_index_min")),
             "spring_index_max": ("spring_index", c("main_spring_index_max"))}
    return {cid: margin(REGISTRY[cid], r[v], lim, b_mm if cid == "spring_coil_gap" else None)
            for cid, (v, lim) in pairs.items()}


def feasible(r, b_mm):
    return all(bool(np.all(m >= 0)) for m in step9_margins(r, b_mm).values())


def test_step9_margins_are_the_evaluators():
    # case 1's flowchart design: main_spring_design on its core values gives the registry's margins of verify()
    res = case_flowchart("case1_as_run")
    v = res.values
    i = load_case("case1_as_run")["inputs"]
    r, args = catalog_spring(res.get("main_spring_material"), res.get("main_spring_wire"),
                             res.get("main_spring_mean_body_diameter_mm"),
                             stiffness_nm_per_deg=i["spring_stiffness_nm_per_deg"],
                             spring_torque_nominal_nm=v["spring_torque_nominal_nm"],
                             torque_tolerance_pct=i["spring_torque_tolerance_pct"],
                             theta_pp_deg=i["durability_theta_peak_to_peak_deg"],
                             housing_height_mm=v["spring_housing_height_mm"],
                             housing_outer_diameter_mm=v["spring_housing_outer_diameter_mm"],
                             housing_inner_diameter_mm=v["spring_housing_inner_diameter_mm"])
    mine = step9_margins(r, args["b_mm"])
    for cid in STEP9:
        assert float(mine[cid]) == pytest.approx(res.check(cid).margin, rel=1e-12, abs=1e-12), cid


# ------------------------------------------------------------------ thesis case 3 (round wire)


def _case3(wire="R2.30"):
    c = load_case("case3")
    i, t = c["inputs"], c["thesis_tool"]
    r, args = catalog_spring(
        t["main_spring_material"], wire, t["main_spring_mean_body_diameter_mm"],
        stiffness_nm_per_deg=i["spring_stiffness_nm_per_deg"], spring_torque_nominal_nm=t["spring_torque_nominal_nm"],
        torque_tolerance_pct=i["spring_torque_tolerance_pct"], theta_pp_deg=i["durability_theta_peak_to_peak_deg"],
        housing_height_mm=t["spring_housing_height_mm"], housing_outer_diameter_mm=55.0 - 2 * i["working_arm_mm"],
        # eq. (54) and the spring bushing on the 20 mm pivot class (3 mm wall)
        housing_inner_diameter_mm=float(case_flowchart("case3").get("spring_housing_inner_diameter_mm")),
        # as run by the thesis tool (docs): lower torque tolerance, 28.6 deg installation-nominal
        torque_tolerance_side=-1, dtheta_inst_nom_deg=28.6)
    return r, t, args


@pytest.mark.parametrize("key, rel", [
    ("main_spring_active_coils_free", 0.003),   # 2.1786 vs 2.18 (printed, 2 decimals)
    ("hooks_angle_free_state_deg", 0.003),      # 295.70 vs 295.56
    ("main_spring_sigma_a_max_mpa", 0.03),      # 1364.7 vs 1338 (+2.0 %)
    ("main_spring_sigma_a_min_mpa", 0.03),      # 1136.1 vs 1114 (+2.0 %)
    ("main_spring_sigma_inst_mpa", 0.03),       # 1659.0 vs 1626 (+2.0 %)
    ("hooks_angle_nominal_deg", 0.03),          # 208.19 vs 211.86 (-1.7 %)
    # 1.243 vs 1.3 (printed to 1 decimal, so >= 1.25): -4.4 %; Rm_min now follows EN 10270-2 Table 3
    # (1960 MPa at 2.3 mm; the former interpolated 2004 gave 1.271) while sigma_A0 stays an illustrative
    # fraction of Rm, so the thesis tool's fatigue data are not known well enough to pin this closer
    ("main_spring_safety_factor", 0.05),
    ("main_spring_mean_body_diameter_mm", 1e-12),
    ("spring_housing_height_mm", 1e-12),
])
def test_case3_reproduced_with_2_3_mm_wire(key, rel):
    r, t, args = _case3()
    assert float(r[key]) == pytest.approx(t[key], rel=rel)
    assert feasible(r, args["b_mm"])


def test_case3_printed_3_mm_wire_is_inconsistent():
    # 3.0 mm needs 2.1786*(3/2.3)^4 = 6.31 coils for 0.0164 N m/deg, and then the coils touch in the 8.8 mm housing
    r, t, args = _case3("R3.00")
    assert float(r["main_spring_active_coils_free"]) == pytest.approx(2.17861 * (3.0 / 2.3) ** 4, rel=1e-4)
    assert float(r["coil_gap_worst_mm"]) < 0 and float(step9_margins(r, args["b_mm"])["spring_coil_gap"]) < 0
    assert not feasible(r, args["b_mm"])


def test_case3_printed_torque_tolerance_sign_misses_by_far():
    # eq. (66) as printed (+8 %) puts the stresses ~17 % above the tool's: evidence the tool used -8 % here
    c = load_case("case3")
    r, _ = catalog_spring("VDSiCr", "R2.30", 44.0, stiffness_nm_per_deg=0.0164, spring_torque_nominal_nm=1.56,
                          torque_tolerance_pct=8, theta_pp_deg=16, housing_height_mm=8.8, housing_outer_diameter_mm=47.0,
                          housing_inner_diameter_mm=26.0, dtheta_inst_nom_deg=28.6)
    assert float(r["main_spring_sigma_a_max_mpa"]) / c["thesis_tool"]["main_spring_sigma_a_max_mpa"] > 1.15


# ------------------------------------------------------------------ thesis case 1 (flat wire)


def _case1(**kw):
    c = load_case("case1_as_run")
    i, t = c["inputs"], c["thesis_tool"]
    args = dict(stiffness_nm_per_deg=i["spring_stiffness_nm_per_deg"], spring_torque_nominal_nm=t["spring_torque_nominal_nm"],
                torque_tolerance_pct=i["spring_torque_tolerance_pct"], theta_pp_deg=i["durability_theta_peak_to_peak_deg"],
                housing_height_mm=t["spring_housing_height_mm"], housing_outer_diameter_mm=55.0 - 2 * i["working_arm_mm"],
                housing_inner_diameter_mm=22.0,   # spring bushing on the 16 mm pivot class (3 mm wall)
                dtheta_inst_nom_deg=50.0)
    args.update(kw)
    r, a = catalog_spring("VDSiCr", "F2.30x2.30", t["main_spring_mean_body_diameter_mm"], **args)
    return r, c, a


def test_case1_printed_active_coils_is_the_count_at_nominal_torque():
    # ours (free state, eq. 65): 3.6163; the printed 4.09 = 3.6163 + (3.07/0.018)/360 = 4.0901 (coils at T_nom, eq. 78)
    r, c, _ = _case1()
    n = float(r["main_spring_active_coils_free"])
    assert n == pytest.approx(3.61633, rel=1e-4)
    assert n + 3.07 / 0.018 / 360 == pytest.approx(c["thesis_tool"]["main_spring_active_coils_free"], rel=0.001)
    # and the printed free-state hooks angle is 360*(ceil(4.09)-4.09) of that count (328.3 vs 327.6)
    assert float(ms.hooks_angle_deg(n + 3.07 / 0.018 / 360)) == pytest.approx(
        c["thesis_tool"]["hooks_angle_free_state_deg"], rel=0.003)


def test_case1_stress_swing_matches_the_real_tensioner_not_the_tool():
    # sigma+ - sigma- = kf * k * theta_pp * 6/(b h^2) = 1.05259*18*16*0.493140 = 149.5 MPa
    r, c, _ = _case1()
    swing = float(r["main_spring_sigma_a_max_mpa"] - r["main_spring_sigma_a_min_mpa"])
    assert swing == pytest.approx(1.05259 * 18 * 16 * 6 / 2.3**3, rel=1e-4)
    real = c["real_tensioner"]
    assert swing == pytest.approx(real["main_spring_sigma_a_max_mpa"] - real["main_spring_sigma_a_min_mpa"], rel=0.01)
    tool = c["thesis_tool"]
    assert (tool["main_spring_sigma_a_max_mpa"] - tool["main_spring_sigma_a_min_mpa"]) / swing < 0.70
    # the tool's stress ratio still fixes theta_nom = T_nom*1.04/k = 177.4 deg (eq. 66 as printed)
    ratio = tool["main_spring_sigma_a_max_mpa"] / tool["main_spring_sigma_a_min_mpa"]
    assert float(r["sigma_plus_mpa"] / r["sigma_minus_mpa"]) == pytest.approx(ratio, rel=0.001)
    # and the installation angle (sigma_inst - sigma_mid)/(sigma+ - sigma_mid)*8 = 49.9 deg
    mid = (tool["main_spring_sigma_a_max_mpa"] + tool["main_spring_sigma_a_min_mpa"]) / 2
    assert (tool["main_spring_sigma_inst_mpa"] - mid) / (tool["main_spring_sigma_a_max_mpa"] - mid) * 8 == pytest.approx(
        catalog.constant("main_spring_dtheta_inst_nom_deg"), rel=0.02)


def test_case1_physics_flags_the_thesis_spring():
    # 3.07 N m * 1.04 on a 2.3 mm square: sigma_inst = 1.05259*3.07/0.018*... = 2124 MPa > 0.88*1994 = 1755 MPa
    r, _, args = _case1()
    assert float(r["main_spring_sigma_inst_mpa"]) == pytest.approx(2124.5, rel=1e-3)
    m = step9_margins(r, args["b_mm"])
    assert float(m["spring_yield"]) < 0 and not feasible(r, args["b_mm"])
    # the inner contact (now always verified: both housing diameters are inputs of the step) passes
    assert float(m["spring_inner_contact"]) > 0
    # the same verdict through the registry: case 1's design with the thesis's spring fails spring_yield
    res = verify(case_input("case1_as_run"), dict(case_flowchart("case1_as_run").parts, main_spring_material="VDSiCr",
                                                  main_spring_wire="F2.30x2.30", main_spring_mean_body_diameter_mm=41.0))
    assert res.check("spring_yield").verdict == "fail"
    assert res.check("spring_yield").value == pytest.approx(2124.5, rel=0.002)   # T_nom 3.074 (ours) vs 3.07 (printed)
    assert res.check("spring_inner_contact").verdict == "pass"


def test_a_46_mm_spring_in_a_45_mm_housing_fails_outer_contact():
    # case 1's housing is 55 - 2*5 = 45 mm: a 46 mm mean diameter cannot fit (was: a margin of the spring model)
    res = verify(case_input("case1_as_run"), dict(case_flowchart("case1_as_run").parts,
                                                  main_spring_mean_body_diameter_mm=46.0))
    c = res.check("spring_outer_contact")
    assert c.verdict == "fail" and c.value > 46.0 and c.limit == pytest.approx(44.9)


# ------------------------------------------------------------------ automatic mode


def _catalog_product(name, **changes):
    """The registry's spring group over every material x wire x mean diameter of the flowchart's grid, for the core of
    case ``name``'s flowchart design (one call of the evaluator)."""
    d = case_input(name, **changes)
    r = flowchart.run(d)
    apps = Applications.of([d])
    groups = evaluate_design(apps, space().design_attributes(r.parts))
    p, step = arrays(), catalog.constant("main_spring_mbd_step_mm")
    d_in, d_out = r.get("spring_housing_inner_diameter_mm"), r.get("spring_housing_outer_diameter_mm")
    mbd = np.arange(np.ceil(d_in / step) * step, np.floor(d_out / step) * step + step / 2, step)
    m, w, dd = (x.ravel() for x in np.meshgrid(np.arange(len(p.spring_material)), np.arange(len(p.spring_wire)), mbd,
                                               indexing="ij"))
    opts = spring_attributes(p, m, w, dd)
    g = Ev.spring(apps, Ev.spring_keys(groups["core"], np.zeros(1, int)), np.zeros(len(m), int), opts)
    return r, opts, g, mbd


def test_automatic_spring_is_the_cheapest_feasible_round_wire(tmp_path):
    # case 3 at the tool's 28.6 deg installation travel; the registry's margins decide feasibility, step 9's sentence
    # the section ("Round wire is preferred due to the lower cost ... if it is not sufficient, the rectangular wire
    # is implemented"), the catalog cost the spring within it. At the thesis tool's dry friction 0.15 (its printed
    # spring torque 1.56 N m): with the default 0.10 (issue 34) no round wire suffices for case 3
    from synth import catalog
    fr = catalog.load("friction_coefficients")
    fr[fr["friction"] == "pivot_bushing dry"].assign(mu=0.15).to_csv(tmp_path / "friction_coefficients.csv",
                                                                      index=False)
    with catalog.overriding(tmp_path):
        r, opts, g, _ = _catalog_product("case3", arm_travel_nominal_to_installation_deg=28.6)
    ok = np.all([g.margins[c] >= 0 for c in STEP9], axis=0)
    rnd = opts["round_wire"]
    assert (ok & rnd).any() and (ok & ~rnd).any()
    assert f"{(ok & rnd).sum()} round-wire and {(ok & ~rnd).sum()} rectangular-wire springs pass" in " ".join(r.notes)
    cost = opts["cost_eur_times_stiffness"]
    chosen = np.flatnonzero((opts["main_spring_material"] == r.get("main_spring_material"))
                            & (opts["main_spring_wire"] == r.get("main_spring_wire"))
                            & (opts["main_spring_mean_body_diameter_mm"] == r.get("main_spring_mean_body_diameter_mm")))
    assert len(chosen) == 1 and ok[chosen[0]] and rnd[chosen[0]]
    assert cost[chosen[0]] == cost[ok & rnd].min()
    assert cost[ok & ~rnd].min() < cost[chosen[0]]   # a cheaper flat wire passes too: the sentence decides, not cost
    assert [r.check(c).verdict for c in STEP9] == ["pass"] * len(STEP9)


def test_whole_catalog_in_one_call_never_nan():
    r, opts, g, mbd = _catalog_product("case1_as_run")
    assert len(g) == len(arrays().spring_material) * len(arrays().spring_wire) * len(mbd)
    for k, v in g.values.items():
        assert not np.isnan(np.asarray(v, dtype=float)).any(), k
    assert not any(np.isnan(m).any() for m in g.margins.values())


def test_housing_inner_above_outer_gives_a_verdict_not_a_traceback():
    try:
        r = flowchart.run(case_input("case1_as_run", pivot_class_diameter_mm=40.0))
    except InputError as e:
        assert "pivot_class_diameter_mm" in str(e)
    else:
        assert r.verdict == "fail" and r.check("arm_wall").verdict == "fail"


# ------------------------------------------------------------------ properties


@settings(max_examples=60, deadline=None)
@given(n1=st.floats(0.5, 20), n2=st.floats(0.5, 20), d=st.floats(1.5, 5), mbd=st.floats(10, 60))
def test_stiffness_decreases_with_coils(n1, n2, d, mbd):
    lo, hi = sorted((n1, n2))
    k = ms.stiffness_nm_per_deg(E, ms.second_moment_mm4(d, d, True), mbd, np.array([lo, hi]))
    assert k[0] >= k[1] > 0


@settings(max_examples=60, deadline=None)
@given(c=st.floats(-5, 1e4, allow_nan=False))
def test_curvature_factor_finite_for_any_index(c):
    kf = float(ms.curvature_factor(c))
    assert np.isfinite(kf) and kf >= 1.0


@settings(max_examples=60, deadline=None)
@given(t=st.floats(0.1, 10), d=st.floats(1.5, 5), mbd=st.floats(30.0, 80), rnd=st.booleans())
def test_stress_positive_finite_and_falls_with_wire_size(t, d, mbd, rnd):
    # within the valid index range (c >= 4.6 here); near c = 1 the clipped k_f dominates (index check fails there)
    s1 = float(ms.bending_stress_mpa(t, mbd, d, d, rnd))
    s2 = float(ms.bending_stress_mpa(t, mbd, d * 1.1, d * 1.1, rnd))
    assert np.isfinite(s1) and s1 > 0 and s2 < s1


@settings(max_examples=40, deadline=None)
@given(torque=st.floats(0.0, 20), k=st.floats(1e-4, 0.2), mbd=st.floats(2.0, 80), d=st.floats(0.5, 6),
       rnd=st.booleans(), winding=st.booleans(), h=st.floats(0.0, 60), dth=st.floats(0, 400))
def test_design_never_nan_never_raises(torque, k, mbd, d, rnd, winding, h, dth):
    r = ms.main_spring_design(E_mpa=E, Rm_mpa=2000, sigma_y_mpa=1760, sigma_A0_mpa=700, b_mm=d, h_mm=d,
                              round_wire=rnd, mbd_mm=mbd, stiffness_nm_per_deg=k, spring_torque_nominal_nm=torque,
                              torque_tolerance_pct=4, theta_pp_deg=16, housing_height_mm=h,
                              housing_outer_diameter_mm=45, housing_inner_diameter_mm=20, winding=winding,
                              dtheta_inst_nom_deg=dth, dtheta_nom_free_arm_deg=dth)
    for key, val in r.items():
        if key != "not_verified":
            assert not np.isnan(np.asarray(val, dtype=float)).any(), key


@settings(max_examples=40, deadline=None)
@given(t1=st.floats(0.5, 5), t2=st.floats(0.5, 5))
def test_safety_factor_falls_with_torque(t1, t2):
    lo, hi = sorted((t1, t2))
    r, _ = catalog_spring("VDSiCr", "R2.50", 40.0, stiffness_nm_per_deg=0.015,
                          spring_torque_nominal_nm=np.array([lo, hi]), torque_tolerance_pct=4,
                          theta_pp_deg=16, housing_height_mm=12.0, housing_outer_diameter_mm=45.0,
                          housing_inner_diameter_mm=22.0)
    sf = r["main_spring_safety_factor"]
    assert sf[0] >= sf[1] - 1e-12
