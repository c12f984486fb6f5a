"""Step 10 (tilting, sliding, fixation bolt): thesis cases, hand calculations, properties.

Sources: thesis Tables 9-10 (case 1, as run: cases/case1_as_run.yaml) and
Tables 13-14 (case 3), cases/NOTES.md; ISO 724, ISO 898-1, VDI 2230-1.
"""

from __future__ import annotations


import numpy as np
import pytest
import yaml
from hypothesis import given, settings
from hypothesis import strategies as st

from synth import catalog
from synth.design.constraints import REGISTRY, margin
from synth.design.evaluate import Settings
from synth.design.verify import verify
from synth.errors import CatalogError, InputError
from synth.model import bolted_joint, vdi2230

from synth.data import CASES_DIR as CASES

from conftest import case_flowchart, case_input
CASE_KEYS = [
    "bolt_tightening_torque_nm", "bolt_axial_force_n", "bolt_sigma_mpa", "bolt_tau_mpa", "bolt_sigma_eqv_mpa",
    "bolt_under_head_stress_mpa", "bolt_thread_stress_mpa", "pivot_base_contact_surface_mm2",
    "average_contact_pressure_mpa", "tilting_safety_factor", "sliding_safety_factor",
]
# the tool's hubload implied by case 3's own outputs: sliding SF 3.00 = 0.10 * 14500 / HL
CASE3_TOOL_HUBLOAD_N = 0.10 * 14500.0 / 3.0


def _case(name):
    return yaml.safe_load((CASES / f"{name}.yaml").read_text())


def _run(inputs, hubload_n=None, **kw):
    """:func:`fixation` of a case file's inputs, for the thesis's bolt (M8x1.25 8.8 hex) unless ``kw`` names one."""
    if "candidates" not in kw:
        kw.setdefault("bolt_format", "M8x1.25")
        kw.setdefault("bolt_property_class", "8.8")
    i = inputs
    hl = bolted_joint.nominal_hubload_n(i["calculated_torque_target_nm"], i["working_arm_mm"], i["differential_angle_deg"]) \
        if hubload_n is None else hubload_n
    return bolted_joint.fixation(
        hl, i["middle_plane_belt_height_mm"], i["middle_plane_belt_height_increment_worst_mm"],
        i["tilting_safety_factor"], i["sliding_safety_factor"], i["engine_support_internal_diameter_mm"],
        i["engine_support_external_diameter_mm"], i["contact_angle_deg"], i["support_yield_strength_compression_mpa"],
        i["support_yield_strength_traction_mpa"], number_of_active_threads=i["number_of_active_threads"],
        application_type=i["application_type"],
        bolt_head_contact_external_diameter_mm=i["bolt_head_contact_external_diameter_mm"], **kw)


def _base(**over):
    """Case 3 geometry as keyword inputs for the property tests."""
    kw = dict(hubload_n=462.5, h=20.0, dh=2.0, sft=3.0, sfs=3.0, dint=8.2, dext=28.0, theta=360.0,
              scomp=400.0, strac=400.0)
    kw.update(over)
    return kw


def _fix(kw, **opts):
    """:func:`fixation` of the keyword inputs ``kw`` for M8x1.25 8.8 unless ``opts`` names a bolt or candidates."""
    if "candidates" not in opts:
        opts.setdefault("bolt_format", "M8x1.25")
        opts.setdefault("bolt_property_class", "8.8")
    opts.setdefault("number_of_active_threads", 2.6)
    opts.setdefault("bolt_head_contact_external_diameter_mm", 11.0)
    return bolted_joint.fixation(kw["hubload_n"], kw["h"], kw["dh"], kw["sft"], kw["sfs"], kw["dint"], kw["dext"],
                        kw["theta"], kw["scomp"], kw["strac"], **opts)


def _margins(r, kw):
    """The registry's step-10 margins of a :func:`fixation` result for the targets and support of ``kw`` (the
    pairing of values and limits is the evaluator's: :func:`test_step10_margins_are_the_evaluators`)."""
    pairs = {"tilting": ("tilting_safety_factor", kw["sft"]), "sliding": ("sliding_safety_factor", kw["sfs"]),
             "bolt_yield": ("bolt_sigma_eqv_mpa", catalog.constant("bolt_yield_utilisation_max") * r["bolt_rp02_mpa"]),
             "under_head": ("bolt_under_head_stress_mpa", kw["scomp"]),
             "thread": ("bolt_thread_stress_mpa", kw["strac"]),
             "pivot_base_pressure": ("pivot_base_max_pressure_mpa", kw["scomp"])}
    out = {cid: margin(REGISTRY[cid], r[v], lim) for cid, (v, lim) in pairs.items()}
    out["pivot_bore"] = margin(REGISTRY["pivot_bore"], kw["dint"], r["pivot_bore_min_mm"])
    if "bolt_permissible_preload_n" in r:
        out["bolt_preload_vdi"] = margin(REGISTRY["bolt_preload_vdi"], r["bolt_required_preload_max_n"],
                                         r["bolt_permissible_preload_n"])
    return out


ESCALATION = [(c["bolt_format"], c["bolt_property_class"]) for c in bolted_joint.bolt_candidates()]


def _escalate(kw, **opts):
    """The thesis's escalation as the flowchart runs it (step 10, :mod:`synth.flowchart`): every bolt of the
    escalation order evaluated as the chosen one, the first whose registry bolt check passes (the last if none):
    the values of that bolt per design."""
    r = _fix(kw, candidates=ESCALATION, **opts)
    ok = margin(REGISTRY["bolt_yield"], r["bolt_sigma_eqv_mpa"],
                catalog.constant("bolt_yield_utilisation_max") * r["bolt_rp02_mpa"]) >= 0
    idx = np.where(ok.any(axis=-1), ok.argmax(axis=-1), len(ESCALATION) - 1)
    return {k: np.take_along_axis(np.asarray(v), idx[..., None], axis=-1)[..., 0] for k, v in r.items()}


def _case_kw(inputs):
    i = inputs
    return dict(sft=i["tilting_safety_factor"], sfs=i["sliding_safety_factor"],
                dint=i["engine_support_internal_diameter_mm"], scomp=i["support_yield_strength_compression_mpa"],
                strac=i["support_yield_strength_traction_mpa"])


@pytest.mark.parametrize("name", ["case1_as_run", "case3"])
def test_step10_margins_are_the_evaluators(name):
    # fixation() of the case's inputs, paired with the limits as above, gives the margins of verify()'s bolt checks
    c = _case(name)
    r = _run(c["inputs"], bolt_format="M8x1.25", bolt_property_class="8.8")
    res = case_flowchart(name)
    assert (res.get("bolt_format"), res.get("bolt_property_class"), res.get("bolt_head_type")) == ("M8x1.25", "8.8", "hex")
    mine = _margins(r, _case_kw(c["inputs"]))
    for cid, m in mine.items():
        if cid != "bolt_preload_vdi":
            assert float(m) == pytest.approx(res.check(cid).margin, rel=1e-9, abs=1e-12), cid


# ----------------------------------------------------------------------------------------------
# catalogs
# ----------------------------------------------------------------------------------------------

def test_bolt_catalog_follows_iso_724_and_898_1():
    df = catalog.load("bolts")
    d, p = df["d_mm"].astype(float), df["pitch_mm"].astype(float)
    # ISO 724 basic dimensions
    np.testing.assert_allclose(df["d2_mm"], d - 0.649519 * p, atol=1.5e-3)
    np.testing.assert_allclose(df["d3_mm"], d - 1.226869 * p, atol=1.5e-3)
    np.testing.assert_allclose(df["D1_mm"], d - 1.082532 * p, atol=1.5e-3)
    # ISO 898-1 stress area pi/4 ((d2+d3)/2)^2, tabulated to 3 significant figures
    a_s = np.pi / 4 * ((df["d2_mm"] + df["d3_mm"]) / 2) ** 2
    np.testing.assert_allclose(df["stress_area_mm2"], a_s, rtol=3e-3)
    assert float(catalog.row("bolts", "M8x1.25")["stress_area_mm2"]) == 36.6
    assert set(df["designation"]) == {"M6x1", "M8x1.25", "M8x1", "M10x1.5", "M10x1.25", "M10x1", "M12x1.75",
                                      "M12x1.5", "M12x1.25"}
    assert df["source"].str.len().min() > 10


def test_head_catalog_covers_every_format_in_three_forms():
    heads = catalog.load("bolt_heads")
    bolts = catalog.load("bolts").set_index("designation")
    assert len(heads) == 3 * len(bolts) and heads["bolt_head"].is_unique
    for fmt, grp in heads.groupby("bolt_format"):
        assert set(grp["head_type"]) == set(vdi2230.HEAD_TYPES)
        dw = grp.set_index("head_type")["dw_min_mm"]
        d = float(bolts.loc[fmt, "d_mm"])
        # the bearing face clears the thread; flange > socket > hex (ISO 4162 / 4762 / 4017 heads of one d)
        assert d < dw["hex"] < dw["socket"] < dw["flange"]
        assert (grp["head_outer_mm"] >= grp["dw_min_mm"]).all()
    coarse = heads[heads["bolt_format"].isin(["M6x1", "M8x1.25", "M10x1.5", "M12x1.75"])]
    assert set(coarse["product_standard"]) == {"ISO 4017", "ISO 4162", "ISO 4762"}
    fine = heads[~heads.index.isin(coarse.index)]
    assert set(fine["product_standard"]) == {"ISO 8676", "ISO 15071", "ISO 12474"}
    # the ISO 4162 flange-head bearing diameters (were flagged 'verify'): M8 14.9, M10 18.7, M12 22.5 mm
    assert [float(bolted_joint.bolt_head(f, "flange")["dw_min_mm"]) for f in ("M8x1.25", "M10x1.5", "M12x1.75")] == \
        [14.9, 18.7, 22.5]
    assert heads["source"].str.len().min() > 40


def test_property_classes_iso_898_1():
    c = catalog.row("bolt_property_classes", "8.8")
    assert (float(c["rm_min_mpa"]), float(c["rp02_min_mpa"])) == (800.0, 640.0)
    assert (float(c["rm_min_d_gt16_mpa"]), float(c["rp02_min_d_gt16_mpa"])) == (830.0, 660.0)
    assert float(catalog.row("bolt_property_classes", "10.9")["rp02_min_mpa"]) == 940.0
    assert float(catalog.row("bolt_property_classes", "12.9")["rp02_min_mpa"]) == 1100.0


def test_friction_lookup_and_errors():
    assert bolted_joint.friction_coefficient("pivot_bushing", "belt_in_oil") == 0.055
    assert bolted_joint.friction_coefficient("pivot_bushing", "dry") == 0.10
    assert bolted_joint.friction_coefficient("thread", "dry") == 0.14
    with pytest.raises(CatalogError, match="application_type.*dry, belt_in_oil"):
        bolted_joint.friction_coefficient("thread", "wet")
    with pytest.raises(CatalogError, match="friction interface.*pivot_base_crankcase"):
        bolted_joint.friction_coefficient("washer", "dry")


# ----------------------------------------------------------------------------------------------
# thesis case studies
# ----------------------------------------------------------------------------------------------

def test_case1_as_run_reproduces_table_10():
    """Case 1 with the as-run inputs: every bolt output within 1 % of Table 10.

    Our preload 16312 N = 652.48 * 2.5 / 0.10 (sliding governs); Table 10 needs
    16254 N (its hubload ~650.2 N, -0.35 %), so the force-proportional outputs
    are +0.36 %; the tightening torque 19.64 N*m matches with mu_K = 0.08 in oil.
    """
    c = _case("case1_as_run")
    # its 13 mm contact is larger than an ISO 4017 M8 hex head's 11.63 mm bearing face: the as-run bolt bore on
    # at least 13 mm (a flange head, 14.9 mm, on the 13 mm seat); with a hex head the contact is the head's own
    r = _run(c["inputs"], head_type="flange")
    tool = c["thesis_tool"]
    for key in CASE_KEYS:
        assert float(r[key]) == pytest.approx(tool[key], rel=0.01), key
    assert str(r["bolt_format"]) == "M8x1.25" and str(r["bolt_property_class"]) == "8.8"
    assert float(r["bolt_tightening_torque_nm"]) == pytest.approx(19.64, rel=1e-3)
    hexa = _run(c["inputs"])
    assert float(hexa["bolt_head_contact_diameter_mm"]) == 11.63
    assert float(hexa["bolt_under_head_stress_mpa"]) == pytest.approx(16312.07 / (np.pi / 4 * (11.63**2 - 8.2**2)),
                                                                        rel=1e-4)


def test_case1_as_printed_fails_sliding_within_targets():
    """Table 9 as printed (targets 3.5/3.5, support 25 mm, head 11 mm) needs more preload than the as-run."""
    c = _case("case1")
    r = _run(c["inputs"])
    # sliding governs: 652.48 * 3.5 / 0.1 = 22837 N
    assert float(r["bolt_axial_force_n"]) == pytest.approx(652.48 * 3.5 / 0.1, rel=1e-4)
    assert float(r["sliding_safety_factor"]) == pytest.approx(3.5, rel=1e-9)


def test_case3_with_tool_hubload_reproduces_table_14():
    """Case 3 with the hubload implied by Table 14 (483.3 N): all outputs within 1 %."""
    c = _case("case3")
    r = _run(c["inputs"], hubload_n=CASE3_TOOL_HUBLOAD_N)
    tool = c["thesis_tool"]
    for key in CASE_KEYS:
        assert float(r[key]) == pytest.approx(tool[key], rel=0.01), key
    assert str(r["bolt_format"]) == "M8x1.25" and str(r["bolt_property_class"]) == "8.8"


def test_case3_with_model_hubload_is_4_percent_low():
    """With HL = 1.85/(0.004 sin 90) = 462.5 N the preload is 13875 N, 4.3 % under the tool's 14500 N.

    The safety factors do not depend on the hubload scale (sliding governs) and
    still match; every force-proportional output is 462.5/483.33 = 0.957 of
    the table (documented in docs/sections/bolted_joint.md).
    """
    c = _case("case3")
    r = _run(c["inputs"])
    tool = c["thesis_tool"]
    assert float(r["bolt_axial_force_n"]) == pytest.approx(462.5 * 3.0 / 0.10, rel=1e-12)
    ratio = 462.5 / CASE3_TOOL_HUBLOAD_N
    for key in ("bolt_axial_force_n", "bolt_under_head_stress_mpa", "bolt_thread_stress_mpa",
                "average_contact_pressure_mpa"):
        assert float(r[key]) / tool[key] == pytest.approx(ratio, rel=1e-3), key
    for key in ("tilting_safety_factor", "sliding_safety_factor", "pivot_base_contact_surface_mm2"):
        assert float(r[key]) == pytest.approx(tool[key], rel=0.01), key


# ----------------------------------------------------------------------------------------------
# hand calculations
# ----------------------------------------------------------------------------------------------

def test_hand_calculation_case3_bolt():
    # F = 14500 N on M8x1.25 (P 1.25, d2 7.188, d3 6.466, As 36.6), mu_G 0.14, mu_K 0.16, dw 11, hole 8.2
    # thread torque = 7250 * (1.25/pi + 0.14*7.188/cos30) = 7250 * (0.39789 + 1.16201) = 11309.3 N*mm
    # head torque   = 14500 * 0.16 * (11+8.2)/2 / 2 = 11136.0 N*mm  -> 22.445 N*m
    t = bolted_joint.tightening_torque_nm(14500.0, 1.25, 7.188, 0.14, 11.0, 8.2, 0.16)
    assert float(t) == pytest.approx(22.4453, abs=2e-3)
    # tau = 16 * 11309.3 / (pi * 6.466^3) = 213.05 MPa ; sigma = 14500/36.6 = 396.17 MPa
    tau = bolted_joint.bolt_torsion_stress_mpa(bolted_joint.thread_torque_nmm(14500.0, 1.25, 7.188, 0.14), 6.466)
    assert float(tau) == pytest.approx(213.05, abs=0.05)
    assert float(bolted_joint.bolt_normal_stress_mpa(14500.0, 36.6)) == pytest.approx(396.175, abs=1e-2)
    # von Mises sqrt(396.17^2 + 3*213.05^2) = 541.40
    assert float(bolted_joint.von_mises_stress_mpa(396.17, 213.05)) == pytest.approx(541.40, abs=0.02)
    # thread area pi*7.188*1.25*cos30 = 24.445 mm^2; stress 14500/(24.445*2.6) = 228.14 MPa
    a = bolted_joint.thread_area_mm2(8.0, 1.25, 7.188, 6.466, 6.647)
    assert float(a) == pytest.approx(24.4454, abs=1e-3)
    assert float(bolted_joint.thread_bearing_stress_mpa(14500.0, a, 2.6)) == pytest.approx(228.14, abs=0.02)
    # alternatives: engagement H1 = (8-6.647)/2 = 0.6765 -> pi*7.188*0.6765 = 15.277; printed pi/4 (64-41.809) = 17.429
    assert float(bolted_joint.thread_area_mm2(8.0, 1.25, 7.188, 6.466, 6.647, model="engagement")) == pytest.approx(15.277, abs=1e-3)
    assert float(bolted_joint.thread_area_mm2(8.0, 1.25, 7.188, 6.466, 6.647, model="printed")) == pytest.approx(17.429, abs=1e-3)


def test_helix_torque_exceeds_linearised_by_about_one_percent():
    # exact: 14500*7.188/2*tan(atan(1.25/(pi*7.188)) + atan(0.14/cos30))
    #      = 52113 * tan(0.055299 + 0.160272) = 52113 * 0.218966 = 11411 N*mm (linearised: 11309)
    t = bolted_joint.thread_torque_nmm(14500.0, 1.25, 7.188, 0.14, model="helix")
    assert float(t) == pytest.approx(11411.0, rel=2e-4)
    assert 1.0 < float(t) / float(bolted_joint.thread_torque_nmm(14500.0, 1.25, 7.188, 0.14)) < 1.02


def test_hand_calculation_tilting_case1():
    # I = pi (22.9^4 - 8.2^4)/64 = pi*270484.9/64 = 13277.3 mm^4; k = 11.45/I = 8.6237e-4 /mm^3
    k = bolted_joint.pivot_base_bending_factor_per_mm3(22.9, 8.2)
    assert float(k) == pytest.approx(11.45 / (np.pi * (22.9**4 - 8.2**4) / 64), rel=1e-12)
    # F_tilt = 652.48 * 2.5 * 31.5 * k * 359.06 = 15909 N  (< sliding 16312 N)
    f = bolted_joint.bolt_force_tilting_n(652.48, 2.5, 31.5, 22.9, 8.2)
    assert float(f) == pytest.approx(652.48 * 2.5 * 31.5 * 8.62369e-4 * 359.060, rel=1e-4)


def test_sector_geometry_against_numerical_integration():
    """Sector model (contact 120 and 250 deg): area, worst-fibre factor vs a polar-grid integration."""
    ro, ri = 14.0, 4.1
    for theta in (120.0, 250.0):
        a = np.radians(theta) / 2
        r = np.linspace(ri, ro, 801)
        ph = np.linspace(-a, a, 1601)
        R, PH = np.meshgrid((r[1:] + r[:-1]) / 2, (ph[1:] + ph[:-1]) / 2, indexing="ij")
        dA = R * np.diff(r)[:, None] * np.diff(ph)[None, :]
        x, y = R * np.cos(PH), R * np.sin(PH)
        area = dA.sum()
        xc = (x * dA).sum() / area
        ixx = (y**2 * dA).sum()
        iyy = ((x - xc) ** 2 * dA).sum()
        assert float(bolted_joint.pivot_base_contact_area_mm2(28.0, 8.2, theta)) == pytest.approx(area, rel=1e-5)
        # worst fibre over all hubload directions, on the outer arc and inner corners
        bx = np.concatenate([ro * np.cos(ph), ri * np.cos([-a, a])]) - xc
        by = np.concatenate([ro * np.sin(ph), ri * np.sin([-a, a])])
        k_num = np.sqrt((by / ixx) ** 2 + (bx / iyy) ** 2).max()
        assert float(bolted_joint.pivot_base_bending_factor_per_mm3(28.0, 8.2, theta)) == pytest.approx(k_num, rel=1e-3)


def test_pressure_field_balances_force_and_moment():
    """The Fig. 74 pressure field integrates to the bolt force and to the tilting moment."""
    ro, ri, theta, f, m, psi = 14.0, 4.1, 200.0, 12000.0, 9000.0, 30.0
    a = np.radians(theta) / 2
    r = np.linspace(ri, ro, 401)
    ph = np.linspace(-a, a, 2001)
    rm, pm = (r[1:] + r[:-1]) / 2, (ph[1:] + ph[:-1]) / 2
    dA = rm[:, None] * np.diff(r)[:, None] * np.diff(ph)[None, :]
    p_ro = bolted_joint.pivot_base_pressure_mpa(np.degrees(pm), f, m, 28.0, 8.2, theta, psi)
    p_avg = f / float(bolted_joint.pivot_base_contact_area_mm2(28.0, 8.2, theta))
    X, Y = rm[:, None] * np.cos(pm)[None, :], rm[:, None] * np.sin(pm)[None, :]
    area = dA.sum()
    xc = (X * dA).sum() / area
    ixx, iyy = (Y**2 * dA).sum(), ((X - xc) ** 2 * dA).sum()
    field = p_avg + m * ((X - xc) * np.cos(np.radians(psi)) / iyy + Y * np.sin(np.radians(psi)) / ixx)
    assert (field * dA).sum() == pytest.approx(f, rel=1e-4)
    u = np.array([np.cos(np.radians(psi)), np.sin(np.radians(psi))])
    moment = (field * ((X - xc) * u[0] + Y * u[1]) * dA).sum()
    assert moment == pytest.approx(m, rel=1e-3)
    # the function returns the same (closed-form) field on the outer edge
    edge = p_avg + m * ((ro * np.cos(pm) - xc) * np.cos(np.radians(psi)) / iyy
                        + ro * np.sin(pm) * np.sin(np.radians(psi)) / ixx)
    np.testing.assert_allclose(p_ro, edge, rtol=1e-3)


def test_full_annulus_pressure_is_the_thesis_sinusoid():
    # case 3: p_avg 25.757, amplitude M k = 462.5*22*4.6745e-4 = 4.7563 MPa
    ang = np.linspace(0.0, 360.0, 13)
    p = bolted_joint.pivot_base_pressure_mpa(ang, 14500.0, 462.5 * 22.0, 28.0, 8.2)
    amp = 462.5 * 22.0 * 32 * 28.0 / (np.pi * (28.0**4 - 8.2**4))
    np.testing.assert_allclose(p, 14500.0 / 562.9418 + amp * np.cos(np.radians(ang)), rtol=1e-6)
    # outside a partial contact there is no pressure
    assert float(bolted_joint.pivot_base_pressure_mpa(170.0, 14500.0, 1000.0, 28.0, 8.2, 180.0)) == 0.0


def test_thesis_partial_contact_option_keeps_force_independent_of_angle():
    # eq. (96) with 360/theta and eq. (97) with theta/360: F_tilt is the full-annulus value
    f360 = bolted_joint.bolt_force_tilting_n(462.5, 3.0, 22.0, 28.0, 8.2, 360.0)
    f120 = bolted_joint.bolt_force_tilting_n(462.5, 3.0, 22.0, 28.0, 8.2, 120.0, model="thesis")
    assert float(f120) == pytest.approx(float(f360), rel=1e-12)
    # the physical sector model needs far more preload on a 120 deg sector
    assert float(bolted_joint.bolt_force_tilting_n(462.5, 3.0, 22.0, 28.0, 8.2, 120.0)) > 2 * float(f360)


def test_column_g_corrections_are_exact_inverses():
    f, dint = 20000.0, 8.2
    dw = bolted_joint.min_head_contact_diameter_mm(f, dint, 400.0)
    assert float(bolted_joint.under_head_stress_mpa(f, dw, dint)) == pytest.approx(400.0, rel=1e-12)
    n = bolted_joint.min_active_threads(f, 24.445, 400.0)
    assert float(bolted_joint.thread_bearing_stress_mpa(f, 24.445, n)) == pytest.approx(400.0, rel=1e-12)


# ----------------------------------------------------------------------------------------------
# escalation, manual mode, checks
# ----------------------------------------------------------------------------------------------

def test_escalation_order_class_then_format():
    # M8x1.25 8.8 yields when sqrt((F/36.6)^2 + 3 (16 F/2 (0.39789+1.16201)/(pi 6.466^3))^2) > 640:
    # sigma = F*0.027322, tau = F*0.014694 -> eqv = F*0.037338 -> F_max = 17140 N
    # limits on M8x1.25: 9.8 19282 N, 10.9 25174 N, 12.9 29459 N.
    # M10x1.5: eqv = F*sqrt((1/58)^2 + 3 (16*0.96831/(pi 8.16^3))^2) = 0.023333 F -> 9.8 30857 N, 10.9 40286 N
    # M12x1.75: eqv = 0.015952 F -> 10.9 58926 N, 12.9 68957 N (the largest candidate)
    hl = np.array([500.0, 580.0, 650.0, 950.0, 1200.0, 2000.0, 1e5])  # sliding SF 3 -> F = 30 HL
    r = _escalate(_base(hubload_n=hl), bolt_head_contact_external_diameter_mm=None)
    assert r["bolt_format"].tolist() == ["M8x1.25", "M8x1.25", "M8x1.25", "M8x1.25", "M10x1.5", "M12x1.75",
                                         "M12x1.75"]
    assert r["bolt_property_class"].tolist() == ["8.8", "9.8", "10.9", "12.9", "10.9", "12.9", "12.9"]
    m = _margins(r, _base())
    assert (m["bolt_yield"][:-1] >= 0).all() and m["bolt_yield"][-1] < 0
    # the M10 needs a 10.2 mm bore: the 8.2 mm support fails the registry's bore check
    assert r["pivot_bore_min_mm"][4] == 10.2 and m["pivot_bore"][4] < 0
    # default head contact diameter is the ISO 4017 dw min of the chosen format
    assert r["bolt_under_head_stress_mpa"][0] == pytest.approx(15000.0 / (np.pi / 4 * (11.63**2 - 8.2**2)))


def test_escalation_threshold_by_hand():
    # F = 17100 N stays on 8.8, F = 17200 N needs 9.8 (threshold 17140 N from the hand calculation above)
    r = _escalate(_base(hubload_n=np.array([17100.0, 17200.0]) / 30.0))
    assert r["bolt_property_class"].tolist() == ["8.8", "9.8"]


def test_manual_bolt_is_verified_not_escalated():
    r = _fix(_base(hubload_n=1200.0), bolt_format="M8x1.25", bolt_property_class="8.8")
    m = _margins(r, _base(hubload_n=1200.0))
    assert str(r["bolt_format"]) == "M8x1.25" and float(m["bolt_yield"]) < 0
    # under head: 36000 N on pi/4 (11^2 - 8.2^2) = 42.22 mm^2 -> 853 MPa > 400;
    # dw >= sqrt(4*36000/(pi*400) + 8.2^2) = sqrt(114.59 + 67.24) = 13.48 mm (column G)
    assert float(r["bolt_under_head_stress_mpa"]) == pytest.approx(36000.0 / (np.pi / 4 * (11.0**2 - 8.2**2)))
    assert float(m["under_head"]) < 0
    assert float(r["min_head_contact_diameter_mm"]) == pytest.approx(13.48, abs=0.005)
    # threads: 36000/(24.445*2.6) = 566 MPa > 400; n >= 36000/(24.445*400) = 3.68
    assert float(m["thread"]) < 0 and float(r["min_active_threads"]) == pytest.approx(3.68, abs=0.005)
    # the registry's corrections name the same remedies
    assert "contact diameter" in REGISTRY["under_head"].correction
    assert "active threads" in REGISTRY["thread"].correction
    with pytest.raises(CatalogError, match="bolt_format.*M10x1.5"):
        _fix(_base(), bolt_format="M9")
    with pytest.raises(CatalogError, match="bolt_property_class.*10.9"):
        _fix(_base(), bolt_property_class="11.9")


def test_vectorised_equals_scalar():
    rng = np.random.default_rng(1)
    n = 2000
    kw = _base(hubload_n=rng.uniform(200, 900, n), h=rng.uniform(10, 40, n), dext=rng.uniform(20, 35, n),
               theta=rng.uniform(90, 360, n), sft=rng.uniform(1.5, 4, n))
    r = _fix(kw, application_type="belt_in_oil")
    for j in (0, 7, 1999):
        one = _fix({k: (v[j] if np.ndim(v) else v) for k, v in kw.items()}, application_type="belt_in_oil")
        for key in CASE_KEYS + ["bolt_rp02_mpa", "pivot_base_max_pressure_mpa"]:
            assert float(one[key]) == pytest.approx(float(r[key][j]), rel=1e-9), key
        assert str(one["bolt_format"]) == r["bolt_format"][j]


@pytest.mark.parametrize("over, match", [
    (dict(theta=0.0), "contact_angle_deg"),
    (dict(theta=361.0), "contact_angle_deg.*360"),
    (dict(hubload_n=-1.0), "hubload_n"),
    (dict(dext=8.0), "engine_support_external_diameter_mm.*internal diameter"),
    (dict(scomp=0.0), "support_yield_strength_compression_mpa"),
])
def test_invalid_inputs_raise_clear_errors(over, match):
    with pytest.raises(InputError, match=match):
        _fix(_base(**over))


def test_invalid_options_and_angles():
    with pytest.raises(InputError, match="application_type"):
        _fix(_base(), application_type="wet")
    with pytest.raises(InputError, match="model.*sector"):
        bolted_joint.pivot_base_bending_factor_per_mm3(28.0, 8.2, model="exact")
    with pytest.raises(InputError, match="differential_angle_deg"):
        bolted_joint.nominal_hubload_n(3.25, 5.0, 180.0)
    with pytest.raises(InputError, match="bolt_head_contact_external_diameter_mm.*seat diameter"):
        _fix(_base(), bolt_head_contact_external_diameter_mm=8.0)
    with pytest.raises(InputError, match="bolt_format.*a bolt format and a property class"):
        _fix(_base(), bolt_format=None)
    with pytest.raises(InputError, match="number_of_active_threads"):
        _fix(_base(), number_of_active_threads=0.0)


# ----------------------------------------------------------------------------------------------
# properties
# ----------------------------------------------------------------------------------------------

finite_pos = st.floats(min_value=1e-3, max_value=1e4, allow_nan=False)


@settings(max_examples=60, deadline=None)
@given(hl=st.floats(1.0, 5000.0), factor=st.floats(1.001, 3.0))
def test_monotonic_in_preload(hl, factor):
    """More hubload -> more preload -> more torque and stress, same bolt (manual)."""
    a = _fix(_base(hubload_n=hl), bolt_format="M10x1.5", bolt_property_class="10.9")
    b = _fix(_base(hubload_n=hl * factor), bolt_format="M10x1.5", bolt_property_class="10.9")
    for key in ("bolt_axial_force_n", "bolt_tightening_torque_nm", "bolt_sigma_eqv_mpa", "bolt_under_head_stress_mpa",
                "bolt_thread_stress_mpa", "average_contact_pressure_mpa"):
        assert float(b[key]) > float(a[key]), key
    # safety factors reached equal the governing target and do not depend on the hubload scale
    assert float(b["sliding_safety_factor"]) == pytest.approx(float(a["sliding_safety_factor"]), rel=1e-9)


@settings(max_examples=60, deadline=None)
@given(mu=st.floats(1e-3, 1e3), mu_t=st.floats(0.0, 1e3))
def test_extreme_friction_is_finite(mu, mu_t):
    r = _fix(_base(), mu_crankcase=mu, mu_thread=mu_t, mu_head=mu_t)
    for key, v in r.items():
        if np.asarray(v).dtype.kind == "f":
            assert np.all(np.isfinite(v)), key
    assert float(r["sliding_safety_factor"]) >= 3.0 * (1 - 1e-12)
    assert float(r["tilting_safety_factor"]) >= 3.0 * (1 - 1e-12)


@settings(max_examples=80, deadline=None)
@given(theta=st.floats(min_value=1e-300, max_value=360.0, exclude_min=False))
def test_contact_angle_extremes_are_finite(theta):
    r = _fix(_base(theta=theta))
    for key in CASE_KEYS:
        assert np.isfinite(float(r[key])), key
    m = _margins(r, _base(theta=theta))
    assert float(m["tilting"]) >= -1e-9 and float(m["sliding"]) >= -1e-9
    assert float(r["pivot_base_contact_surface_mm2"]) > 0


@settings(max_examples=60, deadline=None)
@given(t1=st.floats(90.0, 360.0), t2=st.floats(90.0, 360.0), t0=st.floats(1e-3, 360.0))
def test_more_contact_needs_less_tilting_preload(t1, t2, t0):
    """Above 90 deg more contact needs less preload; the full annulus is the best of all angles.

    Below ~85 deg the requirement is not monotonic: when the inner corners of a
    narrow sector become the worst fibre, widening the sector raises the
    preload by up to ~1 % (57-84 deg for a 8.2/28 mm base; checked against a
    200001-point brute-force search while developing).
    """
    lo, hi = sorted((t1, t2))
    f_lo = bolted_joint.bolt_force_tilting_n(462.5, 3.0, 22.0, 28.0, 8.2, lo)
    f_hi = bolted_joint.bolt_force_tilting_n(462.5, 3.0, 22.0, 28.0, 8.2, hi)
    assert float(f_hi) <= float(f_lo) * (1 + 1e-9)
    f_full = bolted_joint.bolt_force_tilting_n(462.5, 3.0, 22.0, 28.0, 8.2, 360.0)
    assert float(bolted_joint.bolt_force_tilting_n(462.5, 3.0, 22.0, 28.0, 8.2, t0)) >= float(f_full) * (1 - 1e-9)


def test_zero_hubload_gives_infinite_safety_not_nan():
    r = _fix(_base(hubload_n=0.0))
    assert float(r["bolt_axial_force_n"]) == 0.0
    assert np.isinf(float(r["tilting_safety_factor"])) and np.isinf(float(r["sliding_safety_factor"]))
    assert float(r["bolt_tightening_torque_nm"]) == 0.0


# ----------------------------------------------------------------------------------------------
# VDI 2230 path (published tables: tests/validation/test_vdi2230.py)
# ----------------------------------------------------------------------------------------------

def test_thesis_form_is_5_to_18_percent_stricter_than_vdi_2230():
    """At equal utilisation (nu = 0.9) the elastic eq. (103)-(107) (tau on d3) allows 5.5-17.7 % less preload
    than VDI 2230 R7/2 (plastic torsion on d0) for every catalog thread and mu_G 0.08-0.16 (issue 12: 5-16 %);
    the gap grows with friction (more torsion) and with the pitch (d3 smaller)."""
    bolts = catalog.load("bolts")
    gaps = {}
    for mu in (0.08, 0.12, 0.16):
        fv = vdi2230.permissible_assembly_preload_n(bolts["pitch_mm"], bolts["d2_mm"], bolts["d3_mm"], 640.0, mu)
        ft = vdi2230.elastic_permissible_preload_n(bolts["pitch_mm"], bolts["d2_mm"], bolts["d3_mm"],
                                               bolts["stress_area_mm2"], 640.0, mu)
        gaps[mu] = 1.0 - ft / fv
    assert 0.054 < gaps[0.08].min() and gaps[0.16].max() < 0.178
    assert (gaps[0.08] < gaps[0.12]).all() and (gaps[0.12] < gaps[0.16]).all()
    # hand check M8x1.25, mu 0.14: VDI 36.61*0.9*640/sqrt(1 + 3 (1.5*7.188/6.827*(0.05535 + 0.1617))^2) = 18.13 kN;
    # thesis 576/sqrt((1/36.6)^2 + 3 (8*(0.3979 + 1.1620)/(pi 6.466^3))^2) = 15.43 kN: 14.9 % less
    fv = float(vdi2230.permissible_assembly_preload_n(1.25, 7.188, 6.466, 640.0, 0.14))
    ft = float(vdi2230.elastic_permissible_preload_n(1.25, 7.188, 6.466, 36.6, 640.0, 0.14))
    assert (round(fv), round(ft), round(100 * (1 - ft / fv), 1)) == (18131, 15426, 14.9)


def test_thesis_escalation_at_its_force_matches_the_elastic_permissible_preload():
    """Cross-check: the thesis path raises the class exactly where the required force passes the elastic
    permissible preload at the thesis's utilisation (bolt_yield_utilisation_max = 1.0)."""
    f88 = float(vdi2230.elastic_permissible_preload_n(1.25, 7.188, 6.466, 36.6, 640.0, 0.14, utilisation=1.0))
    below = _escalate(_base(hubload_n=0.999 * f88 * 0.10 / 3.0))
    above = _escalate(_base(hubload_n=1.001 * f88 * 0.10 / 3.0))
    assert str(below["bolt_property_class"]) == "8.8" and str(above["bolt_property_class"]) == "9.8"


def test_tightening_factor_from_table_a8():
    # VDI 2230-1 Table A8: torque found on the original part 1.4-1.6, yield/angle-controlled 1.2-1.4
    assert vdi2230.tightening_factor("torque_wrench_tested") == 1.6
    assert vdi2230.tightening_factor("torque_wrench_tested", "min") == 1.4
    assert vdi2230.tightening_factor("yield_controlled", "min") == 1.2
    assert vdi2230.tightening_factor("power_screwdriver") == 2.5
    assert float(vdi2230.tightening_factor_from_scatter(0.0)) == 1.0
    # each row's scatter columns are its factors' (alpha = (1 + s)/(1 - s)) to the table's rounding (2 points)
    tf = catalog.load("tightening_factors")
    for col, s_col in (("alpha_a_min", "scatter_min_pct"), ("alpha_a_max", "scatter_max_pct")):
        s_ = 100 * vdi2230.preload_scatter(tf[col].astype(float))
        np.testing.assert_allclose(s_, tf[s_col].astype(float), atol=2.0)
    offered = tf[tf["design_option"].astype(str).str.lower() == "true"]["tightening_method"].tolist()
    assert offered == ["torque_wrench_tested", "angle_controlled", "yield_controlled"]
    with pytest.raises(InputError, match="tightening_method.*torque_wrench_tested"):
        vdi2230.tightening_factor("impact")
    with pytest.raises(InputError, match="preload scatter"):
        vdi2230.tightening_factor_from_scatter(1.0)


def test_embedding_sums_table_5_4_1_per_surface():
    # Rz 10-40, transverse: thread 3 + head 4.5 + 1 interface 2.5 = 10 um; a through bolt adds the nut face
    assert vdi2230.embedding_um("rz_10_40", "transverse", interfaces=1) == 10.0
    assert vdi2230.embedding_um("rz_10_40", "transverse", interfaces=1, joint_type="through") == 14.5
    assert vdi2230.embedding_um("rz_lt_10", "axial", interfaces=2) == 3.0 + 2.5 + 2 * 1.5
    assert vdi2230.embedding_um("rz_40_160", "transverse", interfaces=0) == 9.5
    with pytest.raises(InputError, match="roughness class.*rz_10_40"):
        vdi2230.embedding_um("rz_5", "axial")
    with pytest.raises(InputError, match="loading.*transverse"):
        vdi2230.embedding_um("rz_lt_10", "bending")


def test_resiliences_by_hand_and_limits():
    # bolt: see the docstring; a socket head (l_SK 0.4 d) and a free thread (A_d3 < A_N) change it as expected
    hexa = float(vdi2230.bolt_resilience_mm_per_n(8.0, 6.466, 40.0, modulus_mpa=210e3, internal_thread_modulus_mpa=70e3))
    sock = float(vdi2230.bolt_resilience_mm_per_n(8.0, 6.466, 40.0, head_type="socket", modulus_mpa=210e3,
                                              internal_thread_modulus_mpa=70e3))
    free = float(vdi2230.bolt_resilience_mm_per_n(8.0, 6.466, 40.0, free_thread_length_mm=10.0, modulus_mpa=210e3,
                                              internal_thread_modulus_mpa=70e3))
    a_n, a_3 = np.pi / 4 * 64, np.pi / 4 * 6.466**2
    assert hexa - sock == pytest.approx(0.8 / (210e3 * a_n))
    assert free - hexa == pytest.approx(10.0 / 210e3 * (1 / a_3 - 1 / a_n))
    # clamped parts: a very wide part is the pure cone (5.1/24), a part no wider than d_W a sleeve
    dw, dh, lk, e = 13.0, 8.2, 40.0, 70e3
    wide = float(vdi2230.clamped_parts_resilience_mm_per_n(dw, dh, 400.0, lk, modulus_mpa=e))
    tan_phi = 0.348 + 0.013 * np.log(lk / dw) + 0.193 * np.log(400.0 / dw)
    dagr = dw + 2 * lk * tan_phi
    cone = 2 * np.log((dw + dh) * (dagr - dh) / ((dw - dh) * (dagr + dh))) / (2 * e * np.pi * dh * tan_phi)
    assert wide == pytest.approx(cone)
    sleeve = float(vdi2230.clamped_parts_resilience_mm_per_n(dw, dh, 12.0, lk, modulus_mpa=e))
    assert sleeve == pytest.approx(lk / (e * np.pi / 4 * (12.0**2 - dh**2)))
    # the cone-plus-sleeve form joins both ends continuously
    just_above = float(vdi2230.clamped_parts_resilience_mm_per_n(dw, dh, dw * (1 + 1e-9), lk, modulus_mpa=e))
    assert just_above == pytest.approx(lk / (e * np.pi / 4 * (dw**2 - dh**2)), rel=1e-6)
    tp = 0.348 + 0.013 * np.log(lk / dw) + 0.193 * np.log(60.0 / dw)
    at_gr = dw + 2 * lk * tp
    below, above = (float(vdi2230.clamped_parts_resilience_mm_per_n(dw, dh, x, lk, modulus_mpa=e))
                    for x in (at_gr * (1 - 1e-7), at_gr * (1 + 1e-7)))
    assert below == pytest.approx(above, rel=1e-4)
    with pytest.raises(InputError, match="free_thread_length_mm"):
        vdi2230.bolt_resilience_mm_per_n(8.0, 6.466, 40.0, free_thread_length_mm=41.0)
    with pytest.raises(InputError, match="joint_type"):
        vdi2230.clamped_parts_resilience_mm_per_n(dw, dh, 22.9, lk, joint_type="glued")


def test_vdi_path_case1_hand_calculation():
    """Case 1 as run, VDI path with embedding (l_K = the 40 mm pivot height): F_Kerf 16312 N (sliding), f_Z 10 um,
    delta_S 5.498e-6 + delta_P 2.039e-6 mm/N -> F_Z 1327 N; torque-controlled (alpha_A 1.6): F_M,min = F_Kerf + F_Z
    = 17639 N, F_M,max = 28222 N. The thesis's M8x1.25 8.8 allows F_M,zul = 18131 N at mu_G 0.14: it fails; 12.9
    (31.2 kN) passes. The window's bottom less the embedding is F_Kerf: the targets hold at the smallest preload."""
    c = _case("case1_as_run")
    lk = c["inputs"]["max_pivot_height_mm"]
    r = _run(c["inputs"], method="vdi2230", embedding=True, clamp_length_mm=lk, head_type="flange")
    assert float(r["bolt_clamp_force_required_n"]) == pytest.approx(16312.07, abs=0.1)
    assert float(r["bolt_embedding_um"]) == 10.0
    d_s = float(vdi2230.bolt_resilience_mm_per_n(8.0, 6.466, lk))
    d_p = float(vdi2230.clamped_parts_resilience_mm_per_n(13.0, 8.2, 22.9, lk))
    assert (d_s, d_p) == (pytest.approx(5.498e-6, rel=1e-3), pytest.approx(2.039e-6, rel=1e-3))
    fz = 10e-3 / (d_s + d_p)
    assert float(r["bolt_embedding_loss_n"]) == pytest.approx(fz) and round(fz) == 1327
    assert float(r["bolt_required_preload_min_n"]) == pytest.approx(16312.07 + fz, rel=1e-6)
    assert float(r["bolt_required_preload_max_n"]) == pytest.approx(1.6 * (16312.07 + fz), rel=1e-6)
    assert float(r["bolt_residual_clamp_force_n"]) == pytest.approx(16312.07, rel=1e-6)
    assert float(r["sliding_safety_factor"]) == pytest.approx(2.5, rel=1e-9)
    assert float(r["bolt_permissible_preload_n"]) == pytest.approx(
        float(vdi2230.permissible_assembly_preload_n(1.25, 7.188, 6.466, 640.0, 0.14)))
    assert float(_margins(r, _case_kw(c["inputs"]))["bolt_preload_vdi"]) < 0
    strong = _run(c["inputs"], method="vdi2230", embedding=True, clamp_length_mm=lk, head_type="flange",
                  bolt_property_class="12.9")
    assert float(_margins(strong, _case_kw(c["inputs"]))["bolt_preload_vdi"]) > 0


def test_vdi_path_case1_through_the_registry():
    # the flowchart's design verified with the VDI setting: the window's top (1.6 F_Kerf = 26.1 kN) exceeds the
    # 8.8 bolt's F_M,zul (18.1 kN), the thesis check does not apply; 12.9 (31.2 kN) passes; the safety factors
    # are those of the window's bottom, F_Kerf itself (sliding 2.5, the target)
    parts = case_flowchart("case1_as_run").parts
    vdi = verify(case_input("case1_as_run"), parts, Settings(bolt_method="vdi2230"))
    assert vdi.check("bolt_preload_vdi").verdict == "fail" and vdi.check("bolt_yield").verdict == "not applicable"
    assert vdi.check("bolt_preload_vdi").limit == pytest.approx(18130.9, rel=1e-4)
    assert vdi.check("bolt_preload_vdi").value == pytest.approx(1.6 * 16312.07, rel=1e-6)
    assert vdi.get("sliding_safety_factor") == pytest.approx(2.5, rel=1e-9)
    thesis = verify(case_input("case1_as_run"), parts)
    assert thesis.check("bolt_yield").verdict == "pass" and thesis.check("bolt_preload_vdi").verdict == "not applicable"
    strong = verify(case_input("case1_as_run"), dict(parts, bolt_property_class="12.9"), Settings(bolt_method="vdi2230"))
    assert strong.check("bolt_preload_vdi").verdict == "pass"


def test_vdi_window_meets_the_targets_at_its_bottom_and_is_judged_at_its_top():
    rng = np.random.default_rng(7)
    n = 400
    kw = _base(hubload_n=rng.uniform(150, 1200, n), h=rng.uniform(10, 40, n), dext=rng.uniform(20, 35, n),
               theta=rng.uniform(120, 360, n), sft=rng.uniform(1.5, 4, n), sfs=rng.uniform(1.5, 4, n))
    for method, alpha in (("torque_wrench_tested", 1.6), ("yield_controlled", 1.4)):
        r = _fix(kw, method="vdi2230", tightening_method=method, bolt_format="M10x1.5", bolt_property_class="10.9",
                 bolt_head_contact_external_diameter_mm=None)
        m = _margins(r, kw)
        f_min, f_max = r["bolt_required_preload_min_n"], r["bolt_required_preload_max_n"]
        np.testing.assert_allclose(f_max, alpha * f_min)
        np.testing.assert_allclose(r["bolt_axial_force_n"], (f_min + f_max) / 2)
        # the head and thread pressures are the window's top's; the safety factors its bottom's
        np.testing.assert_allclose(r["bolt_thread_stress_mpa"] * 2.6 * float(bolted_joint.thread_area_mm2(
            10.0, 1.5, 9.026, 8.160, 8.376)), f_max, rtol=1e-3)
        if method == "torque_wrench_tested":  # sized to the requirement: the targets hold at the bottom exactly
            np.testing.assert_allclose(f_min, r["bolt_clamp_force_required_n"])
            assert (m["sliding"] >= -1e-9).all() and (m["tilting"] >= -1e-9).all()
            assert np.minimum(m["sliding"], m["tilting"]).max() < 1e-9  # one of them binds, at margin 0
        else:  # the bolt's own yield preload: the targets hold where it covers the requirement, and only there
            fy = float(vdi2230.permissible_assembly_preload_n(1.5, 9.026, 8.160, 940.0, 0.14, utilisation=1.0))
            np.testing.assert_allclose(f_min, fy)
            covers = fy >= r["bolt_clamp_force_required_n"]
            assert covers.any() and (~covers).any()
            assert (np.minimum(m["sliding"], m["tilting"])[covers] >= -1e-9).all()
            assert (np.minimum(m["sliding"], m["tilting"])[~covers] < 0).all()
            assert np.isinf(r["bolt_permissible_preload_n"]).all()  # no F_M,zul check: yield is the target


def test_vdi_made_preload_replaces_the_window():
    """A made joint (a production sample): every value at its own preload, the requirement unchanged."""
    kw = _base()
    win = _fix(kw, method="vdi2230", bolt_head_contact_external_diameter_mm=None, head_type="flange")
    made = _fix(kw, method="vdi2230", bolt_head_contact_external_diameter_mm=None, head_type="flange",
                clamp_force_n=np.array([13875.0, 22200.0, np.nan]))
    assert made["sliding_safety_factor"].tolist()[:2] == pytest.approx([3.0, 4.8])
    assert made["bolt_under_head_stress_mpa"][1] == pytest.approx(float(win["bolt_under_head_stress_mpa"]))
    assert made["bolt_under_head_stress_mpa"][2] == pytest.approx(float(win["bolt_under_head_stress_mpa"]))
    assert made["bolt_clamp_force_required_n"].tolist() == pytest.approx([13875.0] * 3)


def test_vdi_path_options_and_errors():
    kw = _base()
    with pytest.raises(InputError, match="clamp_length_mm"):
        _fix(kw, method="vdi2230", embedding=True)
    with pytest.raises(InputError, match="method.*thesis, vdi2230"):
        _fix(kw, method="vdi")
    with pytest.raises(InputError, match="alpha_a"):
        _fix(kw, method="vdi2230", alpha_a=0.9)
    with pytest.raises(InputError, match="tightening_method.*torque_wrench_tested"):
        _fix(kw, method="vdi2230", tightening_method="impact")
    # alpha_A 1 and embedding: the window is the required force plus the embedding loss
    r = _fix(kw, method="vdi2230", embedding=True, clamp_length_mm=30.0, alpha_a=1.0, clamped_interfaces=0,
             embedding_roughness="rz_lt_10", embedding_loading="axial")
    assert float(r["bolt_required_preload_max_n"]) == pytest.approx(13875.0 + float(r["bolt_embedding_loss_n"]))
    assert float(r["bolt_embedding_um"]) == 5.5


def test_every_catalog_screw_is_checked_on_its_own_head():
    """Every bolt option of the design space bears on its own head (or washer) within the default case's 11 mm
    seat; the application's value never replaces it. An ISO 4017 M6 head (dw 8.88 mm) on the default seat:
    13875 N on pi/4 (8.88^2 - 8.2^2) = 9.12 mm^2 is 1521 MPa, far over the support's 400 MPa."""
    from synth.design.applications import Applications
    from synth.design.space import space
    from synth.design import evaluate
    from synth.scenes.demo import default_input
    d = default_input()
    t = space().tables["bolt"]
    apps = Applications.of([d])
    n = len(t["bolt_format"])
    fix = evaluate.fixation_values(apps, np.zeros(n, dtype=np.int64), t)
    own = bolted_joint.head_bearing_diameter_mm(t["bolt_head_dw_min_mm"], t["washer_d2_mm"], t["washer_h_mm"])
    np.testing.assert_allclose(fix["bolt_head_contact_diameter_mm"], np.minimum(own, 11.0))
    assert (own[t["bolt_format"] == "M6x1"] < 11.0).any() and (own > 11.0).any()
    hexa = np.flatnonzero((t["bolt_format"] == "M6x1") & (t["bolt_head_type"] == "hex") & (t["bolt_washer"] == "none"))
    assert fix["bolt_head_contact_diameter_mm"][hexa] == pytest.approx(8.88)
    assert fix["bolt_under_head_stress_mpa"][hexa] == pytest.approx(13875.0 / (np.pi / 4 * (8.88**2 - 8.2**2)), rel=1e-9)
    assert round(float(fix["bolt_under_head_stress_mpa"][hexa[0]])) == 1521
    r = verify(d, {**case_flowchart("case3").parts, "bolt_format": "M6x1", "bolt_head_type": "hex",
                   "bolt_property_class": "12.9", "bolt_washer": "none"})
    assert r.check("under_head").verdict == "fail" and r.check("under_head").value == pytest.approx(1521, abs=1)


def test_a_washer_bears_on_what_its_thickness_spreads_within_the_seat():
    kw = _base()
    base = dict(bolt_head_contact_external_diameter_mm=None, bolt_format="M8x1.25", bolt_property_class="8.8")
    bare = _fix(kw, **base)
    w89 = _fix(kw, washer="ISO 7089", **base)
    w93 = _fix(kw, washer="ISO 7093-1", **base)
    # ISO 7089 M8: 16 x 1.6 mm -> min(16, 11.63 + 3.2) = 14.83; ISO 7093-1: 24 x 2 -> 15.63; bore 8.4 mm
    assert float(w89["bolt_head_contact_diameter_mm"]) == pytest.approx(14.83)
    assert float(w93["bolt_head_contact_diameter_mm"]) == pytest.approx(15.63)
    assert float(w89["bolt_under_head_stress_mpa"]) == pytest.approx(13875.0 / (np.pi / 4 * (14.83**2 - 8.4**2)))
    assert float(w93["bolt_under_head_stress_mpa"]) < float(w89["bolt_under_head_stress_mpa"]) < \
        float(bare["bolt_under_head_stress_mpa"])
    # on an 11 mm seat the washer bears on the seat, and the head turns on the washer (its friction face)
    seat = _fix(kw, washer="ISO 7089", **dict(base, bolt_head_contact_external_diameter_mm=11.0))
    assert float(seat["bolt_head_contact_diameter_mm"]) == 11.0
    assert float(bolted_joint.head_friction_diameter_mm(11.63, 16.0, 11.0)) == 11.63
    with pytest.raises(InputError, match="bolt_washer.*ISO 7089"):
        _fix(kw, washer="DIN 125", **base)
    assert bolted_joint.washer_series() == ("none", "ISO 7089", "ISO 7093-1")


def test_head_type_sets_the_default_bearing_diameter():
    kw = _base()
    out = {h: _fix(kw, head_type=h, bolt_head_contact_external_diameter_mm=None) for h in vdi2230.HEAD_TYPES}
    assert [float(out[h]["bolt_head_contact_diameter_mm"]) for h in ("hex", "socket", "flange")] == [11.63, 12.33, 14.9]
    # larger bearing face: lower head pressure, more under-head friction torque
    assert out["flange"]["bolt_under_head_stress_mpa"] < out["socket"]["bolt_under_head_stress_mpa"] < \
        out["hex"]["bolt_under_head_stress_mpa"]
    assert out["flange"]["bolt_tightening_torque_nm"] > out["hex"]["bolt_tightening_torque_nm"]
    with pytest.raises(InputError, match="head_type.*hex, flange, socket"):
        _fix(kw, head_type="button")
    with pytest.raises(InputError, match="head_type"):
        bolted_joint.bolt_head("M8x1.25", "pan")


@settings(max_examples=60, deadline=None)
@given(st.floats(0.0, 1.0), st.floats(0.0, 1.0), st.sampled_from(["M6x1", "M8x1", "M10x1.5", "M12x1.25"]))
def test_permissible_preload_bounded_and_falling_with_friction(mu1, mu2, fmt):
    b = catalog.row("bolts", fmt)
    f = [float(vdi2230.permissible_assembly_preload_n(b["pitch_mm"], b["d2_mm"], b["d3_mm"], 940.0, m)) for m in (mu1, mu2)]
    a0 = float(vdi2230.stress_area_mm2(b["d2_mm"], b["d3_mm"]))
    assert all(0.0 < x < 0.9 * 940.0 * a0 for x in f)  # torsion always costs some tension
    if mu1 < mu2:
        assert f[0] >= f[1]  # strictly falling; equal only within round-off (mu2 - mu1 ~ 1e-38)
    if mu2 - mu1 > 1e-6:
        assert f[0] > f[1]
    # the thesis form is always the stricter one, at any friction
    el = float(vdi2230.elastic_permissible_preload_n(b["pitch_mm"], b["d2_mm"], b["d3_mm"], b["stress_area_mm2"], 940.0, mu1))
    assert el < f[0]


@pytest.mark.parametrize("method", ["thesis", "vdi2230"])
def test_fixation_once_per_distinct_bolt_equals_each_row_alone(method, monkeypatch):
    """``fixation_values`` computes the fixation once per distinct (application, bolt as the fixation reads it):
    the catalog's bolts of a few applications as one table (one fixation call per kind of seat, each bolt with its
    own head form, washer and tightening method), production samples as their (application, bolt) pairs (each
    sample its own application, with a made preload, a belt offset and a crankcase friction of its own; three
    designs' bolts). Bit-equal to each row evaluated alone (one call naming its bolt)."""
    from synth.data.generated_applications import generate
    from synth.design import evaluate
    from synth.design.applications import Applications
    from synth.design.space import space
    from synth.scenes.demo import default_input
    st_ = Settings(bolt_method=method)
    sp = space()
    nb = sp.n("bolt")
    apps = Applications.of([default_input(), *generate(2, seed=3)])
    real, calls = bolted_joint.fixation, []

    def counted(*args, **kw):
        calls.append("pairs" if kw.get("candidate_of") is not None else "table")
        return real(*args, **kw)
    monkeypatch.setattr(bolted_joint, "fixation", counted)
    a, b = np.repeat(np.arange(len(apps)), nb), np.tile(np.arange(nb), len(apps))
    rng = np.random.default_rng(1)
    n = 60
    samples = apps.with_fields(rng.integers(0, len(apps), n),
                               middle_plane_belt_height_increment_worst_mm=rng.uniform(0.0, 3.0, n))
    samples.derived["bolt_clamp_force_n"] = rng.uniform(8e3, 2.5e4, n)
    samples.derived["mu_crankcase"] = rng.uniform(0.1, 0.2, n)
    sb = np.array([5, 300, 601])[np.arange(n) % 3]
    with np.errstate(all="ignore"):
        table = evaluate.fixation_values(apps, a, sp.rows("bolt", b), st_)
        seats = len(set(apps.given["bolt_head_contact_external_diameter_mm"].tolist()))
        assert calls == ["table"] * seats
        calls.clear()
        pairs = evaluate.fixation_values(samples, np.arange(n), sp.rows("bolt", sb), st_)
        assert "pairs" in calls and len(calls) <= seats
    assert np.isfinite(table["bolt_axial_force_n"]).all() and np.isfinite(pairs["bolt_axial_force_n"]).all()
    with np.errstate(all="ignore"):
        for i in rng.choice(len(a), 24, replace=False):
            alone = evaluate.fixation_values(apps, a[[i]], sp.rows("bolt", b[[i]]), st_)
            for k, v in alone.items():
                assert v[0].tobytes() == table[k][i].tobytes(), (k, i)
        for i in range(0, n, 5):
            alone = evaluate.fixation_values(samples, np.array([i]), sp.rows("bolt", sb[[i]]), st_)
            for k, v in alone.items():
                assert v[0].tobytes() == pairs[k][i].tobytes(), (k, i)
    # the made preload is each sample's own: the pairs are not one design's values repeated
    assert len(np.unique(pairs["bolt_axial_force_n"])) == n
