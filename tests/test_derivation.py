"""Each check's derivation (synth.design.derivation, ``synth design --explain``, ``synth.derive``): the numbers it
shows equal a hand calculation from the thesis's equations and the catalog rows, read here from the CSV files and the
default application's file, not from synth's own output."""

from __future__ import annotations

import csv
import json
import math
from pathlib import Path

import pytest
import yaml

import synth
from synth.cli import main
from synth.design.derivation import derive
from synth.errors import InputError

ROOT = Path(__file__).resolve().parents[1]
DEFAULT = ROOT / "synth" / "data" / "default_case.yaml"
INPUTS = yaml.safe_load(DEFAULT.read_text(encoding="utf-8"))["inputs"]
#: a feasible design of the default application (thesis case 3 completed): the demo's nominal optimum
PARTS = {"ball_bearing": "6006", "pivot_class_diameter_mm": 17.0, "pivot_bushing_supplier": "B",
         "damper_pad_class": "none", "pivot_bushing_length_mm": 15.0, "endcap_spacer_class": "none",
         "cone_spring_aspect_ratio": 0.0, "cone_spring_deflection_ratio": 0.0, "cone_spring_external_diameter_mm": 0.0,
         "cone_spring_internal_diameter_mm": 0.0,
         "main_spring_material": "VDSiCrV", "main_spring_wire": "F2.00x2.00", "main_spring_mean_body_diameter_mm": 43.0,
         "bolt_format": "M8x1.25", "bolt_head_type": "hex", "bolt_property_class": "8.8"}


def _row(name: str, key_col: str, key: str, **match) -> dict:
    with open(ROOT / "catalogs" / f"{name}.csv", newline="", encoding="utf-8") as fh:
        for row in csv.DictReader(fh):
            if row[key_col] == key and all(row[k] == v for k, v in match.items()):
                return row
    raise KeyError(key)


def _mu(interface: str) -> float:
    return float(_row("friction_coefficients", "interface", interface, environment="dry")["mu"])


def _walk(q):
    yield q
    for x in (q.step.inputs if q.step else []) + list(q.parts):
        yield from _walk(x)


def _find(q, key):
    return next(x for x in _walk(q) if x.key.rstrip("_") == key)


@pytest.fixture(scope="module")
def d():
    return synth.load(DEFAULT)


def test_self_locking_lever_ratio_is_the_thesis_eq_12_by_hand(d):
    # eq. (12)-(13): rho = r_p sin(atan(mu)) / (e_w sin(alpha)); the pivot diameter is the class plus twice the
    # bushing's radial thickness (step 2); mu the dry pivot-bushing coefficient of catalogs/friction_coefficients.csv
    r_p = (PARTS["pivot_class_diameter_mm"] + 2 * INPUTS["pivot_bushing_radial_thickness_mm"]) / 2  # 9 mm
    mu = _mu("pivot_bushing")  # 0.10 (dry; GGB's band, the case-3 production tensioner: issue 34)
    rho = r_p * math.sin(math.atan(mu)) / (INPUTS["working_arm_mm"] * math.sin(math.radians(
        INPUTS["differential_angle_deg"])))
    assert rho == pytest.approx(9 * 0.0995037 / 4, abs=1e-5)  # sin(atan 0.10) = 0.0995037: 0.22388
    dv = derive(d, PARTS, "self_locking")
    assert dv.value.key == "lever_ratio" and dv.value.value == pytest.approx(rho, rel=1e-9)
    assert dv.limit.value == 1.0 and dv.margin == pytest.approx(1.0 - rho, rel=1e-9)
    assert dv.value.step.function == "synth.model.damping.lever_ratio" and "eq. (12)" in dv.value.step.equation
    assert _find(dv.value, "pivot_diameter_mm").value == pytest.approx(2 * r_p)
    m = _find(dv.value, "mu_pivot_bushing")
    assert m.value == mu and m.origin == "catalog" and "friction_coefficients.csv pivot_bushing, dry" in m.source
    assert _find(dv.value, "working_arm_mm").origin == "input"
    text = dv.text()
    assert f"(1 - {rho:.4f}) / 1 = +{100 * (1 - rho):.1f} %" in text
    assert "lever_ratio(pivot_diameter_mm = 18 mm, mu_pivot_bushing = 0.1, working_arm_mm = 4 mm" in text


def test_bolt_yield_is_the_thesis_eq_98_to_107_by_hand(d):
    bolt = _row("bolts", "designation", "M8x1.25")
    As, P, d2, d3 = (float(bolt[k]) for k in ("stress_area_mm2", "pitch_mm", "d2_mm", "d3_mm"))
    rp02 = float(_row("bolt_property_classes", "property_class", "8.8")["rp02_min_mpa"])  # ISO 898-1: 640 MPa
    # eq. (7): hubload from the calculated torque; eq. (98)-(99): the bolt force against sliding
    hubload = INPUTS["calculated_torque_target_nm"] * 1000 / (INPUTS["working_arm_mm"] * math.sin(math.radians(
        INPUTS["differential_angle_deg"])))
    force = hubload * INPUTS["sliding_safety_factor"] / _mu("pivot_base_crankcase")
    assert force == pytest.approx(13875.0)
    sigma = force / As  # eq. (103), on the stress area
    # eq. (106) in the VDI 2230 form: T_G = F d2/2 (P / (pi d2) + 1.155 mu_G); eq. (105): tau = 16 T_G / (pi d3^3)
    torque = force * d2 / 2 * (P / (math.pi * d2) + 1.155 * _mu("thread"))
    tau = 16 * torque / (math.pi * d3 ** 3)
    eqv = math.sqrt(sigma ** 2 + 3 * tau ** 2)  # eq. (107)
    assert (round(sigma, 1), round(tau, 1), round(eqv, 1)) == (379.1, 203.9, 518.1)
    dv = derive(d, PARTS, "bolt_yield")
    assert dv.value.value == pytest.approx(eqv, rel=2e-4)  # 1.155 is VDI 2230's rounding of 2/sqrt(3)
    assert _find(dv.value, "sigma_mpa").value == pytest.approx(sigma, rel=1e-9)
    assert _find(dv.value, "tau_mpa").value == pytest.approx(tau, rel=2e-4)
    assert _find(dv.value, "thread_torque_nmm").value == pytest.approx(torque, rel=2e-4)
    assert _find(dv.value, "bolt_force_n").value == pytest.approx(force, rel=1e-9)
    area = _find(dv.value, "area_mm2")
    assert area.value == As and area.origin == "catalog" and "bolts.csv M8x1.25" in area.source
    assert dv.limit.value == pytest.approx(rp02) and dv.margin == pytest.approx((rp02 - dv.value.value) / rp02)
    assert _find(dv.limit, "rp02_mpa").source.startswith("catalogs/bolt_property_classes.csv 8.8")
    text = dv.text()
    assert f"(640 - {eqv:.1f}) / 640 = +{100 * (640 - eqv) / 640:.1f} %" in text
    assert "von_mises_stress_mpa(sigma_mpa = 379.1 MPa, tau_mpa = 203.9 MPa) = 518.1 MPa" in text
    assert any("ISO 898-1" in src for _, _, src in dv.sources)  # the catalog rows' own sources are cited


def test_a_bad_check_id_names_the_accepted_ones(d):
    with pytest.raises(InputError, match="bolt_yeld.*accepted: one of the design checks: .*self_locking"):
        derive(d, PARTS, "bolt_yeld")


def test_the_api_derives_a_result_and_an_input(d):
    r = synth.verify(d, PARTS)
    one = synth.derive(r, "damping_upper")
    assert one.limit.value == pytest.approx(INPUTS["damping_target_nm"] + INPUTS["damping_tolerance_nm"])
    assert [x.key for x in one.limit.parts] == ["damping_target_nm", "damping_tolerance_nm"]
    both = synth.derive(DEFAULT, ["self_locking", "under_head"], parts=PARTS)
    assert [x.check for x in both] == ["self_locking", "under_head"]
    json.dumps([x.as_dict() for x in both])  # plain data
    with pytest.raises(InputError, match="parts"):
        synth.derive(DEFAULT, "self_locking")


def test_cli_explain_prints_the_derivation_and_refuses_a_bad_id(capsys):
    code = main(["design", str(DEFAULT), "--explain", "self_locking"])
    out = capsys.readouterr().out
    assert code == 0 and "\nDerivations\n" in out and "lever_ratio(pivot_diameter_mm = 21 mm" in out  # class 20 kept
    assert out.rstrip().splitlines()[-1] == "Verdict: PASS"
    code = main(["design", str(DEFAULT), "--explain", "bolt_yeld"])
    err = capsys.readouterr().err
    assert code == 2 and "--explain: got 'bolt_yeld'" in err and "self_locking" in err and "Traceback" not in err


def test_the_report_appendix_derives_the_smallest_margins(d):
    from synth.report.html import derivation_rows, render_html
    r = synth.verify(d, PARTS)
    rows = derivation_rows(r)
    want = list(dict.fromkeys([c.id for c in r.failed()] + [c.id for c in r.binding(5)]))  # failing, then smallest
    assert [x["check"] for x in rows] == want and len(rows) >= 5
    html = render_html(r, [], [])
    assert '<section id="derivations" class="page">' in html and 'href="#derivations"' in html
    assert all(f'<h3 id="derivation-{x["check"]}">' in html for x in rows)
    assert "goodman_safety_factor(sigma_max_mpa = " in html  # spring_fatigue, among them, traced


def test_the_trace_records_only_its_own_thread_and_restores_the_functions():
    """The recording wrappers stand in for the physics functions only while the traced call runs, and a call made by
    another thread meanwhile is not recorded (a profiler hook was per thread; the wrappers must be too)."""
    import threading

    from synth.design import trace
    from synth.model import bolted_joint

    original = bolted_joint.fixation
    seen = {}

    def other():
        seen["constant"] = trace.sys.modules["synth.catalog"].constant("bolt_yield_utilisation_max")

    def run():
        t = threading.Thread(target=other)
        t.start()
        t.join()
        return trace.sys.modules["synth.catalog"].constant("bolt_yield_utilisation_max")

    out, tracer = trace.traced(run)
    assert out == seen["constant"]
    assert [c.qualname for c in tracer.calls] == ["synth.catalog.constant"]
    assert tracer.calls[0].args["name"] == "bolt_yield_utilisation_max" and tracer.calls[0].result == out
    assert bolted_joint.fixation is original
