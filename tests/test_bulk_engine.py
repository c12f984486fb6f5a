"""Bulk engine (issue 7): the fast engine equals the reference (``solve`` per application), column contract,
scenes without axial damping or durability test, never a NaN outside unevaluated margins."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pandas as pd
import pytest
from hypothesis import HealthCheck, given, settings, strategies as st

from synth.bulk import screen_applications
from synth.bulk.engine import columns, screen_applications_reference
from synth.data.generated_applications import generate
from synth.optimise import solve
from synth.optimise.evaluate import CONSTRAINTS
from synth.optimise.result import PART_KEYS
from synth.data import case_path
from synth.schema import load_input


def _assert_same(fast: pd.DataFrame, ref: pd.DataFrame):
    """Same parts, status, strings; margins and objectives within 1e-9 (NaN where NaN, inf where inf)."""
    assert list(fast.columns) == list(ref.columns)
    assert len(fast) == len(ref)
    for c in fast.columns:
        a, b = fast[c].to_numpy(), ref[c].to_numpy()
        if fast[c].dtype == float:
            with np.errstate(invalid="ignore"):  # inf - inf where both are inf
                same = (np.isnan(a) & np.isnan(b)) | (a == b) | (np.abs(a - b) <= 1e-9)
            assert same.all(), (c, a[~same], b[~same])
        else:
            assert [str(x) for x in a] == [str(x) for x in b], c


@pytest.fixture(scope="module")
def apps():
    return generate(10, seed=11)


@pytest.fixture(scope="module")
def ref_standard(apps):
    return screen_applications_reference(apps, objective="standard", diagnose=False)


def test_fast_equals_reference_screening(apps, ref_standard):
    fast = screen_applications(apps, objective="standard", diagnose=False)
    _assert_same(fast, ref_standard)
    # the sample has both verdicts (otherwise the comparison proves little)
    assert 0 < fast["feasible"].sum() < len(apps)


def test_fast_equals_reference_cost_with_diagnosis():
    apps = generate(2, seed=4)
    _assert_same(screen_applications(apps, objective="cost"), screen_applications_reference(apps, objective="cost"))


def test_fast_equals_reference_margin_objective():
    apps = generate(2, seed=5)
    _assert_same(screen_applications(apps, objective="margin", diagnose=False),
                 screen_applications_reference(apps, objective="margin", diagnose=False))


def test_fast_equals_reference_full_fidelity():
    apps = generate(3, seed=2)
    _assert_same(screen_applications(apps, fidelity="full", diagnose=False),
                 screen_applications_reference(apps, fidelity="full", diagnose=False))


def test_one_row_equals_solve(apps, ref_standard):
    """Row 1 against solve itself: parts, status and every margin."""
    r = solve(apps[1], "standard", "enumerate", relax=False)
    row = screen_applications([apps[1]], diagnose=False).iloc[0]
    assert row["status"] == r.status
    assert {k: row[f"part_{k}"] for k in PART_KEYS} == r.parts
    for name, m in r.margins.items():
        assert row[f"margin_{name}"] == pytest.approx(m, abs=1e-9)
    assert row["objective_cost_eur"] == pytest.approx(r.objectives["cost"], abs=1e-9)


def test_column_contract(ref_standard):
    cols = columns()
    assert list(ref_standard.columns) == cols
    assert cols[:5] == ["feasible", "status", "objective_standard", "objective_cost_eur", "objective_margin"]
    assert [f"part_{k}" for k in PART_KEYS] == cols[5:5 + len(PART_KEYS)]
    assert [f"margin_{n}" for n in CONSTRAINTS] == [c for c in cols if c.startswith("margin_") and c != "margin_min"]
    assert cols[-3:] == ["violated", "relaxation", "notes"]
    assert ref_standard["feasible"].dtype == bool
    assert set(ref_standard["status"]) <= {"optimal", "infeasible"}


def test_empty_chunk():
    df = screen_applications([])
    assert list(df.columns) == columns() and len(df) == 0


def test_feasible_rows_have_no_violation(ref_standard):
    ok = ref_standard[ref_standard["feasible"]]
    assert (ok["violated"] == "").all() and (ok["relaxation"] == "").all()
    assert (ok["margin_min"] >= -1e-9).all()
    bad = ref_standard[~ref_standard["feasible"]]
    # an infeasible row names its violated constraints, worst first, and the binding one is the worst
    for _, r in bad.iterrows():
        first = r["violated"].split(";")[0]
        name, m = first.split(":")
        assert name == r["binding_constraint"] and float(m) == pytest.approx(r["binding_margin"], abs=5e-4)
        assert r["margin_min"] < 0


def test_only_radial_application():
    """Case 3 (dry, radial damping) declared only_radial: no damper pad, the axial-group margins not evaluated
    and said so; the verdict and relaxation of the optimisation section (case 3: stiffness 0.0164 -> 0.0192)."""
    d = dataclasses.replace(load_input(case_path("case3")), damping_typology="only_radial")
    fast = screen_applications([d])
    _assert_same(fast, screen_applications_reference([d]))
    row = fast.iloc[0]
    assert row["part_damper_pad"] == "none" and row["part_endcap_spacer"] == "none"
    for name in ("cone_sigma_om", "damping_eol", "endcap_spacer_capacity"):
        assert math.isnan(row[f"margin_{name}"])
    assert "only radial damping" in row["notes"]
    # case 3 is infeasible; with the EN 10270-2 strength table the nearest design binds on the spring yield
    # (before: the coil gap, relaxed by the stiffness 0.0164 -> 0.0192) and the diagnosis relaxes the damping
    # tolerance (see test_optimise.test_relaxation_of_case3_is_the_smallest_and_works)
    assert row["status"] == "infeasible" and row["binding_constraint"] == "spring_yield"
    assert row["relaxation"] == "damping_tolerance_nm 0.2->0.3391"


def test_missing_durability_application():
    d = dataclasses.replace(generate(2, seed=0)[1], durability_theta_peak_to_peak_deg=None,
                            durability_frequency_hz=None, durability_duration_h=None)
    fast = screen_applications([d], diagnose=False)
    _assert_same(fast, screen_applications_reference([d], diagnose=False))
    row = fast.iloc[0]
    for name in ("bushing_p", "bushing_pv", "bushing_wear"):
        assert math.isnan(row[f"margin_{name}"])
    assert "durability test not given" in row["notes"]
    assert row["part_bushing_length_mm"] is None or math.isnan(row["part_bushing_length_mm"])


def test_bad_working_arm_is_a_row_not_an_exception():
    d = dataclasses.replace(generate(1, seed=0)[0], working_arm_mm=40.0)
    df = screen_applications([d, generate(2, seed=0)[1]], diagnose=False)
    assert not df.loc[0, "feasible"] and df.loc[0, "notes"].startswith("no design space")
    assert df.loc[1, "status"] == "optimal"


def _nan_outside_margins(df: pd.DataFrame) -> list:
    bad = []
    for c in df.columns:
        if c.startswith("margin_") and c != "margin_min":
            continue
        if c.startswith("part_"):
            continue  # None/NaN part where the space has no such choice (bushing length without durability)
        if df[c].dtype == float and df[c].isna().any():
            bad.append(c)
    return bad


@settings(max_examples=6, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(seed=st.integers(0, 10_000), stiff=st.floats(0.005, 0.2), tol=st.floats(0.5, 20.0))
def test_property_never_nan_never_raises(seed, stiff, tol):
    d = dataclasses.replace(generate(1, seed=seed)[0], spring_stiffness_nm_per_deg=stiff,
                            spring_torque_tolerance_pct=tol)
    df = screen_applications([d], diagnose=False)
    assert _nan_outside_margins(df) == []
    row = df.iloc[0]
    # an unevaluated margin is always explained
    if any(math.isnan(row[f"margin_{n}"]) for n in CONSTRAINTS):
        assert "not evaluated" in row["notes"]
    assert row["feasible"] == (row["status"] == "optimal")
