"""Shrink fit of the crankshaft toothed pulley: hand calculations, physics defaults, ISO 286, fit selection.

The paper's own tables (Siczek et al., Combustion Engines 2025, Tables 1-4) are
asserted in ``tests/validation/test_shrink_fit_paper.py``.
"""

import math

import pytest

from conftest import shrink_fit_case as _case
from conftest import shrink_fit_row as _row
from synth.shrink_fit import analysis, fits, friction, pressure, selection


@pytest.fixture(scope="module")
def physics():
    return analysis.analyse(_case(model=None))


def test_eq2_with_softer_hardness_everywhere():
    # eq. (2) as defined (HB of the softer journal, 245): 0.1*1256/245 + 0.072 + 0.9 sqrt(0.01285) sqrt(0.19482)
    hand = 0.1 * 1256 / 245 + 0.072 + 0.9 * math.sqrt(0.01285) * math.sqrt(47.73 / 245)
    assert hand == pytest.approx(0.6297, abs=1e-4)
    assert float(friction.mu_plastic(0.01285, 47.73, 245, 1256, 0.072)) == pytest.approx(hand, rel=1e-12)



def test_physics_default(physics):
    new, worn = physics["table2"]
    # Lame with diametral interference: p = 0.5 * 210000 * 0.027 * 0.00841813 = 23.865 MPa
    assert new["pressure_min_mpa"] == pytest.approx(0.5 * 210000 * 0.027 * 0.00841813, rel=1e-5)
    assert worn["pressure_min_mpa"] == pytest.approx(0.5 * 210000 * (0.027 - 0.011704) * 0.00841813, rel=1e-5)
    # worn, minimum interference: p/HB = 13.52/245 = 0.0552 < 0.0625, elastic contact: eq. (1) friction
    r = _row(physics["table3"], "worn", "min")
    assert not r["saturated"] and r["mu"] == r["mu_eq1"]
    assert physics["load"]["computed_nm"] == 30.0 and physics["load"]["design_load_nm"] == 96.0
    assert physics["verdict"] == "fail"
    assert "0.8 (Rz_s + Rz_h)" in physics["model"]["smoothing"]


def test_smoothing_rule_2017_halves_g():
    res = analysis.analyse(_case().with_model(smoothing_rule="din7190_2017"))
    # 0.4 (4.8 + 2.33) + 0.4 (4.72 + 2.78) = 5.852 um
    assert res["table2"][1]["smoothing_total_mm"] == pytest.approx(0.005852, rel=1e-9)
    assert res["model"]["smoothing_factor"] == 0.4 and "DIN 7190-1:2017" in res["model"]["smoothing"]


def test_plasticity_limits():
    # hub: Q = 30/35, Re (1 - Q^2)/sqrt(3 + Q^4) = 1100 * 0.265306 / 1.881429 = 155.11 MPa
    assert float(pressure.hub_yield_pressure_mpa(30, 35, 1100)) == pytest.approx(155.11, abs=0.01)
    # hollow journal: Re (1 - 0.16)/2 = 0.42 Re
    assert float(pressure.journal_yield_pressure_mpa(30, 12, 520)) == pytest.approx(218.4, rel=1e-12)


# ---------------------------------------------------------------- ISO 286
@pytest.mark.parametrize("designation, umin, umax", [
    ("30H7/u6", 0.027, 0.061),     # the paper
    ("25H7/s6", 0.014, 0.048),     # ISO 286-2: s6 +35/+48, H7 0/+21
    ("40H7/p6", 0.001, 0.042),     # p6 +26/+42, H7 0/+25
    ("45H7/x6", 0.072, 0.113),     # x6 +97/+113
    ("12H8/u7", 0.006, 0.051),     # u7 +33/+51, H8 0/+27
    ("30H7/js6", -0.0275, 0.0065),  # js6 +-6.5
    ("10H7/n6", -0.005, 0.019),    # 6-10 range: n6 +10/+19, H7 0/+15
    ("50H7/k8", -0.025, 0.039),    # k: ei = 0 above IT7, so k8 is 0/+39 against H7 0/+25
])
def test_iso286_fits(designation, umin, umax):
    f = fits.fit_limits(designation)
    assert f["interference_min_mm"] == pytest.approx(umin, abs=1e-9)
    assert f["interference_max_mm"] == pytest.approx(umax, abs=1e-9)


@pytest.mark.parametrize("designation, message", [
    ("30H7/z6", "shaft letter one of"), ("16H7/t6", "shaft letter one of"), ("60H7/u6", "nominal diameter over 6"),
    ("30G7/u6", "hole-basis"), ("30H9/u6", "tolerance grade"), ("thirty", "ISO 286 hole-basis fit"),
])
def test_iso286_unknown_fit(designation, message):
    from synth.errors import InputError
    with pytest.raises(InputError, match=message):
        fits.fit_limits(designation)


# ---------------------------------------------------------------- fit selection
def test_fit_selection_paper_journal():
    sel = selection.select_fit(_case(model=None), reassemblies=1)
    ok = [r for r in sel["rows"] if r["admissible"]]
    assert sel["fit"] == "30H7/x6"
    # x6 after one re-assembly: p = 0.5 * 210000 * (0.043 - 0.011704) * 0.00841813 = 27.66 MPa (p/HB 0.113: plastic);
    # mu(2) = 0.1*1256/245 + 0.072 + 0.9 sqrt(0.02004) sqrt(0.1129) = 0.6275; M = 0.5 pi 900 15 mu p = 368.1 Nm;
    # margin = 368.1 / (1.5 * 96) - 1 = 1.556
    p = 0.5 * 210000 * (0.043 - 0.011704) * 0.00841813
    mu = 0.1 * 1256 / 245 + 0.072 + 0.9 * math.sqrt(0.02004) * math.sqrt(p / 245)
    hand = 0.5 * math.pi * 900 * 15 * mu * p / 1000 / 144 - 1
    assert sel["margin"] == max(r["slip_margin"] for r in ok) == pytest.approx(hand, rel=1e-3)
    assert all(r["pressure_max_mpa"] <= r["yield_pressure_mpa"] for r in ok)
    bad = {r["fit"]: r for r in sel["rows"] if not r["admissible"]}
    loose = {"30H7/k6", "30H7/m6", "30H7/n6"}
    assert loose <= set(bad)
    # every other fit that is not admissible slips: a negative margin is never labelled admissible (issue 15)
    for fit, r in bad.items():
        if fit not in loose:
            assert r["slip_margin"] < 0 and r["reason"].startswith("slips after 1 re-assemblies")
    assert all(r["slip_margin"] >= 0 for r in ok)


def test_fit_selection_respects_plasticity():
    # paper pressures (eq. 17 as applied) and a C45+QT hub (Re 490): limit 490*0.265306/1.881429 = 69.1 MPa
    sel = selection.select_fit(_case(hub_material="C45+QT_d16"), reassemblies=1)
    elastic = {r["fit"] for r in sel["rows"] if "plasticises" not in r["reason"] and r["interference_min_mm"] > 0}
    assert elastic == {"30H7/p6"}
    # the one elastic fit slips after the re-assembly: no fit is admissible (a negative margin is not admissible)
    p6 = next(r for r in sel["rows"] if r["fit"] == "30H7/p6")
    assert p6["slip_margin"] < 0 and not p6["admissible"] and sel["fit"] is None
    assert sel["rows"][0]["yield_pressure_mpa"] == pytest.approx(69.10, abs=0.01)


def test_margin_vs_reassemblies_and_plot(tmp_path):
    case = _case()
    curves = selection.margin_vs_reassemblies(case, 3)
    m = curves["margins"]["30H7/u6"]
    assert curves["reassemblies"] == [0, 1, 2, 3]
    assert m[1] == pytest.approx(251.17 / 180 - 1, rel=1e-3)   # n = 1 is the paper's i = 2
    assert m[3] == -1.0                                           # smoothing exceeds U_min: loose
    assert all(a >= b for a, b in zip(m, m[1:]))
    out = tmp_path / "m.png"
    selection.plot_margins(curves, out)
    assert out.stat().st_size > 1000


# ---------------------------------------------------------------- one check type (issue 21)
def test_checks_are_the_registry_group_judged_by_its_rule(physics):
    """The four checks are the registry's group ``shrink_fit`` (one ``Check`` type, one margin, one verdict rule):
    the hub check by hand (107.8 MPa against the Lame limit 155.11 MPa: (155.11 - p)/155.11), and a margin
    within the shared round-off tolerance (-FEAS_TOL < m < 0) passes as every tensioner check does."""
    from synth.design.constraints import FEAS_TOL, by_group
    from synth.design.result import Check
    assert [c["id"] for c in physics["checks"]] == [c.id for c in by_group("shrink_fit")] == [
        "shrink_fit_slip_new", "shrink_fit_slip_worn", "shrink_fit_hub_elastic", "shrink_fit_journal_elastic"]
    hub = next(c for c in physics["checks"] if c["id"] == "shrink_fit_hub_elastic")
    assert hub["sense"] == "<=" and hub["margin"] == pytest.approx((hub["limit"] - hub["value"]) / hub["limit"], rel=1e-12)
    assert hub["limit"] == pytest.approx(155.11, abs=0.01)
    worn = next(c for c in physics["checks"] if c["id"] == "shrink_fit_slip_worn")
    assert worn["verdict"] == "fail" and worn["correction"]           # a failed check says what to change
    assert physics["margin"] == min(c["margin"] for c in physics["checks"])
    limit = 180.0
    assert Check.judged("shrink_fit_slip_worn", limit * (1 - FEAS_TOL / 2), limit).verdict == "pass"
    assert Check.judged("shrink_fit_slip_worn", limit * (1 - 2 * FEAS_TOL), limit).verdict == "fail"
