"""Step 4, pivot bushing (thesis eq. 28-42, Table 5): hand calculations, case studies 1 and 3, properties."""

import math

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st
from scipy.integrate import quad

from synth import catalog
from synth.checks import FAIL, PASS
from synth.errors import InputError
from synth.model import plain_bushing as s4

from conftest import load_case


def hubload_n(inp):
    """HL = T_calc / (l_arm * sin(alpha)) (corrected eq. 7, NOTES.md)."""
    return inp["calculated_torque_target_nm"] / (
        inp["working_arm_mm"] / 1000 * math.sin(math.radians(inp["differential_angle_deg"])))


def case_kwargs(inp, axial_damping):
    supplier = s4.supplier_for_thickness(inp["pivot_bushing_radial_thickness_mm"])
    return dict(supplier=supplier, environment=inp["application_type"],
                belt_plane_height_mm=inp["middle_plane_belt_height_mm"],
                max_pivot_height_mm=inp["max_pivot_height_mm"], axial_damping=axial_damping,
                pulley_diameter_mm=inp["pulley_diameter_mm"],
                parallelism_max_mm=inp["pulley_max_parallelism_eol_mm"])


def durability(inp):
    return (inp["durability_theta_peak_to_peak_deg"], inp["durability_frequency_hz"], inp["durability_duration_h"])


# Case 1: HL = 3.25 / (0.005 sin 85 deg) = 652.48 N; case 3: HL = 1.85 / (0.004 * 1) = 462.5 N.
CASES = {
    "case1_as_run": dict(hl=652.4829, axial=True),
    "case3": dict(hl=462.5, axial=False),
}


# --- catalog ----------------------------------------------------------------------------------

def test_table5_limits_in_catalog():
    a_bio, a_dry = s4.supplier_limits("A", "belt_in_oil"), s4.supplier_limits("A", "dry")
    b_dry = s4.supplier_limits("B", "dry")
    assert (a_dry["p_max_mpa"], a_dry["pv_max_mpa_m_per_s"], a_dry["pvt_max_mpa_m_per_s_h"]) == (2.5, 0.8, 800)
    assert (a_bio["p_max_mpa"], a_bio["pv_max_mpa_m_per_s"], a_bio["pvt_max_mpa_m_per_s_h"]) == (5.0, 0.95, 850)
    assert (b_dry["p_max_mpa"], b_dry["pv_max_mpa_m_per_s"], b_dry["pvt_max_mpa_m_per_s_h"]) == (3.0, 0.6, 600)
    assert (a_bio["radial_thickness_mm"], b_dry["radial_thickness_mm"]) == (1.0, 0.5)


def test_catalog_has_source_cost_standard():
    df = catalog.load("pivot_bushings")
    for col in ("source", "unit_cost_eur", "standard", "lengths_mm"):
        assert df[col].notna().all()


def test_supplier_b_not_rated_for_bio():
    with pytest.raises(InputError, match="rated for belt_in_oil"):
        s4.supplier_limits("B", "belt_in_oil")


def test_unknown_thickness_and_environment():
    with pytest.raises(InputError, match="pivot_bushing_radial_thickness_mm.*one of"):
        s4.supplier_for_thickness(0.7)
    with pytest.raises(InputError, match="application_type"):
        s4.supplier_limits("A", "wet")


# --- eq. (28)-(32) hand calculations ----------------------------------------------------------

def test_pressure_speed_pv_pvt_case1_by_hand():
    # p = 652.48 / (16 * 16) = 2.5488 MPa
    p = s4.bushing_pressure_mpa(652.4829, 16.0, 16.0)
    assert float(p) == pytest.approx(2.54876, rel=1e-5)
    # v = 2 * 16 deg (0.279253 rad) * 0.008 m * 50 Hz = 0.223402 m/s
    v = s4.sliding_speed_m_per_s(16.0, 50.0, 16.0)
    assert float(v) == pytest.approx(0.223402, rel=1e-5)
    # pv = 2.54876 * 0.223402 = 0.569399 MPa m/s ; pvt = 683.28 MPa m/s h (below supplier A BIO 0.95 / 850)
    assert float(s4.pv_mpa_m_per_s(p, v)) == pytest.approx(0.569399, rel=1e-5)
    assert float(s4.pvt_mpa_m_per_s_h(p, v, 1200.0)) == pytest.approx(683.28, rel=1e-4)


def test_wear_screening_by_hand():
    # w = k p v t = 1e-8 * 2.54876 * 0.223402 * 1200 * 3600 = 0.024598 mm
    w = s4.wear_mm(1e-8, 2.54876, 0.223402, 1200.0)
    assert float(w) == pytest.approx(0.024598, rel=1e-4)


def test_max_length_eq33_34():
    # eq. (34): 40 - 8 - 6 = 26 ; eq. (33): 34 - 5 - 4 = 25 (gaps in constants_bushing.csv)
    assert s4.max_bushing_length_mm([40.0, 34.0], [True, False]).tolist() == [26.0, 25.0]


def test_reactions_eq35_37_by_hand():
    # L = 20, belt plane 3 mm above the centre: a = 13, b = 7 -> R_A = 600*7/20 = 210, R_B = 390
    ra, rb = s4.end_reactions_n(600.0, 3.0, 20.0)
    assert (float(ra), float(rb)) == pytest.approx((210.0, 390.0))
    # belt plane beyond the upper end (e = 15 > L/2): R_A reverses (opposite side), sum still HL
    ra, rb = s4.end_reactions_n(600.0, 15.0, 20.0)
    assert float(ra) == pytest.approx(-150.0) and float(ra + rb) == pytest.approx(600.0)


def test_end_pressures_models():
    # p_mean 2, e = 3, L = 20: two-point 2*(1 -/+ 2*3/20) = 1.4 / 2.6 ; linear 2*(1 -/+ 6*3/20) = 0.2 / 3.8
    assert [float(x) for x in s4.end_pressures_mpa(2.0, 3.0, 20.0, model="two_point")] == pytest.approx([1.4, 2.6])
    assert [float(x) for x in s4.end_pressures_mpa(2.0, 3.0, 20.0, model="linear")] == pytest.approx([0.2, 3.8])
    # two-point end pressures are eq. (38)-(39): R / (D * L/2) with D = 16: 210 / 160 = 1.3125
    ra, _ = s4.end_reactions_n(600.0, 3.0, 20.0)
    p_mean = float(s4.bushing_pressure_mpa(600.0, 16.0, 20.0))
    pa, _ = s4.end_pressures_mpa(p_mean, 3.0, 20.0, model="two_point")
    assert float(pa) == pytest.approx(float(ra) / (16.0 * 10.0))
    with pytest.raises(InputError, match="pressure_model"):
        s4.end_pressures_mpa(2.0, 3.0, 20.0, model="parabolic")


def test_parallelism_eq42_by_hand_and_centred_bushing():
    # 66 * (0.03 - 0.01) / 16 = 0.0825 mm
    assert float(s4.pulley_parallelism_mm(66.0, 0.01, 0.03, 16.0)) == pytest.approx(0.0825)
    # belt plane at the centre of the span: e = 0, no tilt
    r = s4.evaluate_bushing(462.5, 21.0, 15.0, 16.0, 50.0, 1200.0, **case_kwargs(load_case("case3")["inputs"], False))
    assert float(r["eccentricity_mm"]) == 0.0 and float(r["parallelism_mm"]) == 0.0


def test_eccentricity_clipped_to_span():
    # case 1 span [8, 34]: L = 16 centre clipped to 26 -> e = 29.5 - 26 = 3.5 ; L = 24 -> centre 22, e = 7.5
    assert s4.bushing_eccentricity_mm([16.0, 24.0], 29.5, 40.0, True).tolist() == [3.5, 7.5]


# --- fidelity: screening vs full (solve_ivp) ----------------------------------------------------

def test_full_equals_screening_without_clearance():
    kw = dict(fidelity="full", radial_clearance_mm=0.0)
    assert float(s4.wear_mm(1e-8, 2.0, 0.2, 1000.0, **kw)) == pytest.approx(float(s4.wear_mm(1e-8, 2.0, 0.2, 1000.0)))


def test_full_running_in_against_independent_quadrature():
    # t(u) = integral_0^u g(phi0(u')) / (pi/2) du' (the ODE inverted); check u(tau) from solve_ivp
    def g(u):
        phi = math.acos(1.0 / (1.0 + u))
        return (phi + math.sin(phi) * math.cos(phi)) / (math.pi / 2)
    for u_target in (0.05, 0.7, 3.0, 20.0):
        tau, _ = quad(g, 0.0, u_target, limit=200)
        c, k, p, v = 0.03, 1e-8, 2.0, 0.2
        t_h = tau * c / (k * p * v) / 3600.0
        w = s4.wear_mm(k, p, v, t_h, fidelity="full", radial_clearance_mm=c)
        assert float(w) == pytest.approx(u_target * c, rel=2e-4)


def test_full_minus_screening_is_a_bounded_running_in_offset():
    # screening wear k p v t: 0.0173 mm at 1200 h (u = w/c = 0.58, still running in), 0.26 / 0.52 mm at
    # 18000 / 36000 h (u = 8.6 / 17: run in)
    k, p, v, c = 1e-8, 2.0, 0.2, 0.03
    t = np.array([1200.0, 18000.0, 36000.0])
    diff = s4.wear_mm(k, p, v, t, fidelity="full", radial_clearance_mm=c) - s4.wear_mm(k, p, v, t)
    assert np.all(diff > 0)
    # run in: the offset tends to a constant below the clearance
    assert diff[2] == pytest.approx(diff[1], rel=0.01) and diff[2] < c and diff[0] < diff[1]


def test_fidelity_name_checked():
    with pytest.raises(InputError, match="fidelity"):
        s4.wear_mm(1e-8, 2.0, 0.2, 10.0, fidelity="exact")


# --- case studies: the "lengthen the bushing" iteration -----------------------------------------

@pytest.mark.parametrize("name, thesis_len, real_len", [("case1_as_run", 16.0, 18.0), ("case3", 21.0, 22.0)])
def test_thesis_scheme_reproduces_case_lengths(name, thesis_len, real_len):
    case = load_case(name)
    inp = case["inputs"]
    assert case["thesis_tool"]["pivot_bushing_length_mm"] == thesis_len
    assert case["real_tensioner"]["pivot_bushing_length_mm"] == real_len
    hl = hubload_n(inp)
    assert hl == pytest.approx(CASES[name]["hl"], rel=1e-5)
    d = case["thesis_tool"]["pivot_diameter_mm"]
    r = s4.select_bushing_length(hl, d, *durability(inp), scheme="thesis",
                                 **case_kwargs(inp, CASES[name]["axial"]))
    assert bool(r["found"])
    assert float(r["length_mm"]) == pytest.approx(thesis_len, rel=1e-9)          # tool: L = D
    assert float(r["length_catalog_mm"]) == pytest.approx(real_len, rel=1e-9)    # real: next available


@pytest.mark.parametrize("name", ["case1_as_run", "case3"])
def test_first_trial_half_diameter_fails_table5(name):
    # the tool needed one re-iteration: at L = D/2, Table 5 fails
    # case 1 (A, BIO): p = 652.48/(16*8) = 5.10 > 5 ; case 3 (B, dry): pv = 0.615 > 0.6, pvt = 738 > 600
    case = load_case(name)
    inp = case["inputs"]
    d = case["thesis_tool"]["pivot_diameter_mm"]
    r = s4.evaluate_bushing(hubload_n(inp), d, d / 2, *durability(inp), **case_kwargs(inp, CASES[name]["axial"]))
    assert not bool(r["passes"])
    assert float(r["margin_pv"]) < 0 and float(r["margin_pvt"]) < 0
    if name == "case1_as_run":
        assert float(r["p_mpa"]) == pytest.approx(5.0977, rel=1e-4) and float(r["margin_p"]) < 0
    else:
        assert float(r["pv_mpa_m_per_s"]) == pytest.approx(0.61502, rel=1e-4) and float(r["margin_p"]) > 0


@pytest.mark.parametrize("name", ["case1_as_run", "case3"])
def test_catalog_scheme_picks_shortest_available_passing(name):
    # lean choice: 15 mm passes in both cases (14 mm pvt bound: case 1 needs L >= 12.9 mm)
    case = load_case(name)
    inp = case["inputs"]
    d = case["thesis_tool"]["pivot_diameter_mm"]
    kw = case_kwargs(inp, CASES[name]["axial"])
    r = s4.select_bushing_length(hubload_n(inp), d, *durability(inp), **kw)
    assert float(r["length_mm"]) == 15.0 and bool(r["passes"])
    shorter = s4.evaluate_bushing(hubload_n(inp), d, 12.0, *durability(inp), **kw)
    assert not bool(shorter["passes"])


def test_no_length_fits_reports_not_found_and_checks():
    # 3 kN on a 16 mm pivot in a 40 mm pivot: no length passes p*v*t -> longest fitting candidate, found False
    kw = case_kwargs(load_case("case1_as_run")["inputs"], True)
    r = s4.select_bushing_length(3000.0, 16.0, 16.0, 50.0, 1200.0, **kw)
    assert not bool(r["found"]) and float(r["length_mm"]) == 25.0 and float(r["margin_pvt"]) < 0
    checks = s4.bushing_checks(r, supplier="A", environment="belt_in_oil", parallelism_max_mm=0.3)
    verdicts = {c.name: c.verdict for c in checks}
    assert verdicts["pivot bushing p*v*t"] == FAIL
    assert verdicts["pivot bushing length vs space on the pivot"] == PASS
    assert "pivot diameter" in checks[2].correction


def test_vectorised_over_designs():
    n = 500
    hl = np.linspace(200.0, 900.0, n)
    kw = case_kwargs(load_case("case1_as_run")["inputs"], True)
    r = s4.select_bushing_length(hl, 16.0, 16.0, 50.0, 1200.0, **kw)
    assert r["length_mm"].shape == (n,)
    # more load never needs a shorter bushing
    assert np.all(np.diff(r["length_mm"]) >= 0)
    one = s4.select_bushing_length(hl[123], 16.0, 16.0, 50.0, 1200.0, **kw)
    assert float(one["length_mm"]) == r["length_mm"][123]


def test_invalid_geometry_raises():
    kw = case_kwargs(load_case("case1_as_run")["inputs"], True)
    with pytest.raises(InputError, match="pivot_bushing_length_mm"):
        s4.evaluate_bushing(600.0, 16.0, 0.0, 16.0, 50.0, 1200.0, **kw)


# --- properties ---------------------------------------------------------------------------------

KW1 = case_kwargs({"pivot_bushing_radial_thickness_mm": 1.0, "application_type": "belt_in_oil",
                   "middle_plane_belt_height_mm": 29.5, "max_pivot_height_mm": 40.0,
                   "pulley_diameter_mm": 66.0, "pulley_max_parallelism_eol_mm": 0.3}, True)


@settings(max_examples=40, deadline=None)
@given(hl=st.floats(1.0, 5e4), length=st.floats(1.0, 60.0), t1=st.floats(0.0, 5e4), dt=st.floats(0.0, 5e4),
       fidelity=st.sampled_from(s4.FIDELITIES), model=st.sampled_from(list(s4.PRESSURE_MODELS)))
def test_wear_monotonic_in_time_never_nan(hl, length, t1, dt, fidelity, model):
    r1 = s4.evaluate_bushing(hl, 16.0, length, 16.0, 50.0, t1, fidelity=fidelity, pressure_model=model, **KW1)
    r2 = s4.evaluate_bushing(hl, 16.0, length, 16.0, 50.0, t1 + dt, fidelity=fidelity, pressure_model=model, **KW1)
    for r in (r1, r2):
        assert all(np.all(np.isfinite(np.asarray(v, dtype=float))) for v in r.values())
    assert float(r2["wear_mean_mm"]) >= float(r1["wear_mean_mm"]) - 1e-15
    assert float(r2["wear_max_mm"]) >= float(r1["wear_max_mm"]) - 1e-15


@settings(max_examples=40, deadline=None)
@given(hl=st.floats(1.0, 5e4), factor=st.floats(1.0, 10.0), fidelity=st.sampled_from(s4.FIDELITIES))
def test_wear_monotonic_in_load(hl, factor, fidelity):
    w1 = s4.evaluate_bushing(hl, 16.0, 16.0, 16.0, 50.0, 1200.0, fidelity=fidelity, **KW1)["wear_max_mm"]
    w2 = s4.evaluate_bushing(hl * factor, 16.0, 16.0, 16.0, 50.0, 1200.0, fidelity=fidelity, **KW1)["wear_max_mm"]
    assert float(w2) >= float(w1) * (1 - 1e-9)


@settings(max_examples=25, deadline=None)
@given(hl=st.floats(1.0, 5e4), length=st.floats(1.0, 60.0), fidelity=st.sampled_from(s4.FIDELITIES))
def test_zero_duration_zero_wear(hl, length, fidelity):
    r = s4.evaluate_bushing(hl, 16.0, length, 16.0, 50.0, 0.0, fidelity=fidelity, **KW1)
    assert float(r["wear_max_mm"]) == 0.0 and float(r["parallelism_mm"]) == 0.0
    assert float(r["pvt_mpa_m_per_s_h"]) == 0.0 and float(r["margin_wear"]) == 1.0


@settings(max_examples=25, deadline=None)
@given(hl=st.floats(2e4, 1e6), fidelity=st.sampled_from(s4.FIDELITIES))
def test_wear_through_sliding_layer_fails_clearly(hl, fidelity):
    r = s4.evaluate_bushing(hl, 16.0, 20.0, 16.0, 50.0, 1200.0, fidelity=fidelity, **KW1)
    assert float(r["wear_max_mm"]) > 0.25 and float(r["margin_wear"]) < 0 and not bool(r["passes"])
    assert np.isfinite(float(r["margin_wear"]))
    checks = s4.bushing_checks(r, supplier="A", environment="belt_in_oil", parallelism_max_mm=0.3)
    assert checks[3].verdict == FAIL
