"""Four drive-design reports of a belt maker's software (Gates) on real accessory drives: the tensioner's position
table, the duty table and the first system mode.

Source: the public repository ``kaydgn/MFSim``, file ``tests/fixtures/fead-validation.js`` (read at commit
3b9b07d3), indexed by ``docs/gates-reports/README.md`` (the repository's archive test checks the fixture's static
values against the reports' PDFs: 284 values, no mismatch; its Mode 1 values are the PDFs' where the README says the
fixture's differ). Reports AG00686 (8PK1475HD), AG00810 (10PK1215HD), AG00879 (8PK1392HD) and AG00976 (8PK1715HD,
"Corrected-IDR1"). One fixture per report: ``tests/validation/data/gates_*.yaml`` holds the report's printed results,
``synth/data/drives/gates_*.yaml`` its drive as the report states it (pulley centres, pitch and effective diameters,
wrap sides, the tensioner's pivot, arm, free-arm angle, preload, rate, spring mean load and load stop, the belt's
ribs, length, tolerance and wear, the duty cycle's power per engine speed).

Tolerances (issue 37): every value within 1 %, angles within 0.2 deg. The reports print 0.1 deg, 0.1 mm, 0.1 N in
the position table and whole newtons in the duty table. The measured largest differences are in
docs/sections/drive.md; AG0868 8PK is kept out of these tests (the drive the tests do not use).

The first mode: one EA per rib for every drive (synth.drive.belt.EA_PER_RIB_N), fitted on AG00686 alone; AG00810 is
its prediction. AG00879's and AG00976's vibration inputs (crank and arm inertias, pulley mass) are not transcribed:
no mode is predicted for them.
"""

from pathlib import Path

import pytest
import yaml
from scipy.optimize import brentq

from synth.drive.belt import EA_PER_RIB_N
from synth.drive.compare import compare_with_report
from synth.drive.inputs import load_drive
from synth.drive.modes import system_modes

DATA = Path(__file__).resolve().parent / "data"
DRIVES = Path(__file__).resolve().parents[2] / "synth" / "data" / "drives"
REPORTS = ("gates_ag00686", "gates_ag00810", "gates_ag00879", "gates_ag00976_1715")


def _report(name):
    rep = yaml.safe_load((DATA / f"{name}.yaml").read_text(encoding="utf-8"))
    return rep, load_drive(DRIVES / rep["drive"])


@pytest.fixture(scope="module", params=REPORTS)
def compared(request):
    rep, drive = _report(request.param)
    return rep, compare_with_report(drive, rep)


def test_every_position_and_duty_value_within_1_percent_and_0_2_deg(compared):
    rep, rows = compared
    n_positions = sum(len([k for k in p if k != "name"]) for p in rep["positions"])
    n_duty = sum(len(p["T"]) + len(p["H"]) for p in rep["duty"])
    assert sum(r["table"] == "positions" for r in rows) == n_positions   # every printed value compared
    assert sum(r["table"] == "duty" for r in rows) == n_duty
    for r in rows:
        if r["table"] == "modes":
            continue
        if r["unit"] == "deg":
            assert abs(r["difference"]) <= 0.2, r
        else:
            assert abs(r["difference"]) <= 0.01, r


def test_the_mean_position_is_the_spring_mean_load(compared):
    """The hand calculation: the spring's torque at the report's mean angle, preload + rate x rel, is its mean load
    (AG00686: 8.59 + 0.482 x 33.1 = 24.54 Nm, within the 0.05 deg the report rounds to)."""
    rep, rows = compared
    mean = next(r for r in rows if r["row"] == "Mean" and r["quantity"] == "rel")
    if rep["report"] == "AG00686":
        assert 8.59 + 0.482 * mean["report"] == pytest.approx(24.54, abs=0.03)
        assert mean["ours"] == pytest.approx((24.54 - 8.59) / 0.482, abs=1e-9)
    assert abs(mean["difference"]) <= 0.06


def test_the_first_mode_with_one_ea_per_rib():
    """EA per rib fitted on AG00686's Mode 1 (12.61 Hz, its PDF) is the named default; AG00810 is predicted with it
    (its PDF: 15.05 Hz): 17.50 Hz, 16 % high, the largest of the reports' predictions (docs/sections/drive.md)."""
    rep, drive = _report("gates_ag00686")
    fitted = brentq(lambda ea: system_modes(drive, ea)["frequency_hz"][0] - rep["mode1_hz"], 3000.0, 30000.0)
    assert fitted == pytest.approx(EA_PER_RIB_N, rel=0.005)
    assert system_modes(drive)["frequency_hz"][0] == pytest.approx(rep["mode1_hz"], rel=0.005)
    rep, drive = _report("gates_ag00810")
    predicted = system_modes(drive)["frequency_hz"][0]
    assert predicted == pytest.approx(17.50, abs=0.01)
    assert predicted / rep["mode1_hz"] - 1.0 == pytest.approx(0.163, abs=0.002)


@pytest.mark.parametrize("name", ["gates_ag00879", "gates_ag00976_1715"])
def test_no_mode_without_the_vibration_inputs(name):
    from synth.drive.analysis import analyse
    rep, drive = _report(name)
    assert "system" not in analyse(drive, check=False).get("modes", {})
