"""Bulk engine (issue 7): the fast engine equals the reference (``solve`` per application), column contract,
scenes without axial damping or durability test, never a NaN outside unevaluated margins.

Since the core rebuild there is one engine module (``synth.bulk.engine``): the fast path evaluates a chunk on the
applications axis of the one evaluator, the reference loops over ``solve``; the margin columns are the registry's
constraint ids (the 3D model's aside)."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pandas as pd

from synth.bulk.capability import NUMBERS as CAPABILITY_NUMBERS
import pytest
from hypothesis import HealthCheck, given, settings, strategies as st

from synth.bulk import screen_applications
from synth.bulk.engine import columns, constraint_ids, screen_applications_reference
from synth.data.generated_applications import generate
from synth.design.constraints import REGISTRY
from synth.design.evaluate import Settings
from synth.design.space import PART_KEYS
from synth.design.verify import verify
from synth.optimise import solve
from synth.data import case_path
from synth.io.documents import load_input

from conftest import case_flowchart, case_input

CONSTRAINTS = constraint_ids()


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


def test_fast_equals_reference_cost():
    # two feasible applications (the fast path) and one infeasible (the fast path hands it to solve: the same code
    # as the reference, so a chunk of infeasible applications only would compare solve with itself)
    apps = generate(3, seed=2)
    fast = screen_applications(apps, objective="cost", diagnose=False)
    assert fast["feasible"].sum() == 2
    _assert_same(fast, screen_applications_reference(apps, objective="cost", diagnose=False))


def test_margin_objective_rows_are_the_max_min_design():
    # the margin objective takes the per-application path (solve); its row keeps the largest smallest margin,
    # never below the most standardised design's
    d = generate(2, seed=5)[1]
    std = screen_applications([d], objective="standard", diagnose=False).iloc[0]
    mar = screen_applications([d], objective="margin", diagnose=False).iloc[0]
    assert std["feasible"] and mar["feasible"]
    assert mar["objective_margin"] >= std["objective_margin"] - 1e-12
    assert mar["objective_margin"] == pytest.approx(solve(d, "margin", relax=False,
                                                          settings=Settings(fidelity="screening")).objectives["margin"])


def test_fast_equals_reference_under_a_pivot_wall_rule():
    """A design rule on the pivot wall (a 2 mm minimum wall and 20 % margin beyond it, :mod:`synth.design.rules`)
    reaches the fast path's per-core bolt checks as every other check (the registry's ``finish``): the nearest
    designs of the two infeasible applications equal the enumeration's (pivot classes 17 and 23 mm, smallest
    margins -0.074 and -0.067; the fast path judged the wall without the rule before issue 21's mend and chose
    15 and 14 mm at -0.5; the second's ties on its smallest margin went to the 16 mm class, failing 4 checks, the
    next -4.0 %, before the one key of near designs: now 23 mm, failing 3, the next -3.7 %) and the feasible one's
    optimum too."""
    from synth.design.settings import Settings
    pool = generate(6, seed=5)
    apps = [pool[0], pool[5], pool[1]]
    ruled = Settings(fidelity="screening", rules={"limits": {"pivot_min_wall_mm": 2.0},
                                                  "min_margins": {"pivot_wall": 0.2}})
    fast = screen_applications(apps, diagnose=False, settings=ruled)
    ref = screen_applications_reference(apps, diagnose=False, settings=ruled)
    _assert_same(fast, ref)
    assert fast["feasible"].tolist() == [False, False, True]
    assert fast["part_pivot_class_diameter_mm"].astype(float).tolist()[:2] == [17.0, 23.0]


def test_fast_equals_reference_full_fidelity():
    apps = generate(3, seed=2)
    fast = screen_applications(apps, fidelity="full", diagnose=False)
    assert fast["feasible"].any()   # rows of the fast path, not only solve's
    _assert_same(fast, screen_applications_reference(apps, fidelity="full", diagnose=False))


def test_one_row_equals_solve(apps, ref_standard):
    """Row 1 against solve itself: parts, status and every margin."""
    r = solve(apps[1], "standard,cost,margin", "enumerate", relax=False)  # synth design's: ties by the margin
    row = screen_applications([apps[1]], diagnose=False).iloc[0]
    assert row["status"] == r.status and row["verdict"] == r.verdict
    parts = {k: row[f"part_{k}"] for k in PART_KEYS}
    assert parts == r.parts  # since the dry friction 0.10 two cone-spring variants of this row tie: the margin decides
    assert r.margins
    for name, m in r.margins.items():
        assert row[f"margin_{name}"] == pytest.approx(m, abs=1e-9)
    for c in r.checks:   # a check without a margin (not verified, not applicable) has NaN; a warning has its own
        if c.id in CONSTRAINTS and c.id not in r.margins:
            if c.verdict == "warning" or REGISTRY[c.id].advisory:  # advisory: its margin, passing or warning
                assert row[f"margin_{c.id}"] == pytest.approx(c.margin, abs=1e-9), c.id
            else:
                assert math.isnan(row[f"margin_{c.id}"]), c.id
    assert row["objective_cost_eur"] == pytest.approx(r.objectives["cost"], abs=1e-9)


def test_column_contract(ref_standard):
    cols = columns()
    assert list(ref_standard.columns) == cols
    assert cols[:6] == ["feasible", "status", "verdict", "objective_standard", "objective_cost_eur",
                        "objective_margin"]
    assert [f"part_{k}" for k in PART_KEYS] == cols[6:6 + len(PART_KEYS)]
    # one margin column per registry constraint but the 3D model's and the shrink fit's, in registry order
    assert [f"margin_{n}" for n in REGISTRY if REGISTRY[n].group not in ("cad", "shrink_fit")] == \
        [c for c in cols if c.startswith("margin_") and c != "margin_min"]
    assert cols[-3:] == ["violated", "relaxation", "notes"]
    assert ref_standard["feasible"].dtype == bool
    assert set(ref_standard["status"]) <= {"optimal", "infeasible"}
    assert set(ref_standard["verdict"]) <= {"pass", "incomplete", "fail"}
    assert (ref_standard["feasible"] == (ref_standard["verdict"] != "fail")).all()


def test_empty_chunk():
    df = screen_applications([])
    assert list(df.columns) == columns() and len(df) == 0


def test_empty_reference_chunk():
    df = screen_applications_reference([])
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
    """Case 3 (dry, radial damping) declared only_radial: no damper pad, the axial-group margins not applicable
    (NaN), infeasible without the pad: the nearest design and the relaxation the diagnosis finds."""
    d = dataclasses.replace(load_input(case_path("case3")), damping_typology="only_radial")
    # (infeasible: the engine hands it to solve with the diagnosis, the reference's own code: no comparison here)
    fast = screen_applications([d])
    row = fast.iloc[0]
    assert row["part_damper_pad_class"] == "none" and row["part_endcap_spacer_class"] == "none"
    for name in ("cone_sigma_om", "damping_eol", "endcap_spacer_capacity"):
        assert math.isnan(row[f"margin_{name}"])
    # (the rows' notes list not-verified and assumed checks only; "not applicable" is not noted any more)
    assert ("not verified: pin_within_pulley, pin_clearance: lockup_pin_position_radius_mm, "
            "lockup_pin_angular_position_deg, lockup_pin_diameter_mm missing (lock-up pin data)") in row["notes"]
    # without the damper pad the spring alone cannot hold the torque band: the nearest design binds on the
    # spring's own yield (what truly binds, not a coil gap chosen to be violated), relaxed by the tolerance
    assert row["status"] == "infeasible" and row["violated"].startswith("spring_yield:")
    assert row["binding_constraint"] == "spring_yield"
    # with the dry friction 0.10 (issue 34) the spring carries more torque and the diagnosis finds no single
    # relaxation (before: damping_tolerance_nm 0.2->0.3391; tests/test_optimise.py, reported to the lead)
    assert row["relaxation"] == ""


def _no_durability():
    return dataclasses.replace(generate(2, seed=0)[1], durability_theta_peak_to_peak_deg=None,
                               durability_frequency_hz=None, durability_duration_h=None)


def test_missing_durability_fast_equals_reference():
    d = _no_durability()
    _assert_same(screen_applications([d], diagnose=False), screen_applications_reference([d], diagnose=False))


def test_missing_durability_application():
    d = _no_durability()
    fast = screen_applications([d], diagnose=False)
    ref = screen_applications_reference([d], diagnose=False)
    _assert_same(fast.drop(columns="notes"), ref.drop(columns="notes"))
    row = fast.iloc[0]
    for name in ("bushing_p", "bushing_pv", "bushing_wear", "spring_fatigue"):
        assert math.isnan(row[f"margin_{name}"])
    assert "durability test not given" in ref.iloc[0]["notes"]
    assert "bushing_p, bushing_pv, bushing_pvt, bushing_wear, bushing_parallelism, spring_fatigue: durability" in \
        row["notes"]
    # the length is still a part: without a durability test nothing but the fit decides, so the cheapest (shortest)
    assert row["part_pivot_bushing_length_mm"] == 10.0
    assert row["status"] == "optimal" and row["verdict"] == "incomplete"


def test_bad_working_arm_is_a_row_not_an_exception():
    # a 40 mm working arm is beyond Table 2 for every bearing: every core fails, the row says which constraint
    d = dataclasses.replace(generate(1, seed=0)[0], working_arm_mm=40.0)
    df = screen_applications([d, generate(2, seed=0)[1]], diagnose=False)
    assert not df.loc[0, "feasible"] and df.loc[0, "status"] == "infeasible"
    assert "working_arm_table2:" in df.loc[0, "violated"]
    assert df.loc[1, "status"] == "optimal"


def _nan_outside_margins(df: pd.DataFrame) -> list:
    bad = []
    for c in df.columns:
        if c.startswith("margin_") and c != "margin_min":
            continue
        if c.startswith("part_"):
            continue  # None/NaN part where the space has no such choice (bushing length without durability)
        if c in CAPABILITY_NUMBERS:
            continue  # empty (NaN) without a capability target: these screenings set none
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
    # a NaN margin is a check without one (not verified, not applicable); an advisory warning keeps its margin;
    # a not-verified one is explained in the notes
    r = verify(d, {k: row[f"part_{k}"] for k in PART_KEYS}, Settings(fidelity="screening"), detail=False) \
        if row["part_ball_bearing"] else None
    if r is not None:
        for c in r.checks:
            if c.id in CONSTRAINTS:
                assert math.isnan(row[f"margin_{c.id}"]) == (c.verdict in ("not verified", "not applicable")), c.id
        if r.not_verified():
            assert "not verified: " in row["notes"]
    assert row["feasible"] == (row["status"] == "optimal")


def test_advisory_margins_are_kept_or_dropped_together():
    # case 1's design with h0/t 1.3: above Table 7's 1.2 (a warning), the other ratios within their ranges
    r = verify(case_input("case1_as_run"), dict(case_flowchart("case1_as_run").parts, cone_spring_aspect_ratio=1.3))
    assert r.check("cone_aspect_ratio_max").verdict == "warning" and r.check("cone_aspect_ratio_min").verdict == "pass"
    assert ("cone_aspect_ratio_max" in r.margins) == ("cone_aspect_ratio_min" in r.margins)


def test_layout_switch_is_explained_in_bulk_as_in_design():
    """Issue 20: loosening the axial space from 40 to 40.001 mm makes eq. (18) select the reverse layout, which has
    no feasible design for the default application. ``synth design`` says so; a portfolio row says it too (fast
    engine and reference alike): the first relaxation is back to twice the belt height, the note names eq. (17)."""
    from synth.scenes.demo import default_input
    base = default_input()
    apps = [dataclasses.replace(base, max_axial_displacement_mm=x) for x in (40.0, 40.001)]
    fast = screen_applications(apps, fidelity="full")
    ref = screen_applications_reference(apps, fidelity="full")
    for rows in (fast, ref):
        assert list(rows["feasible"]) == [True, False]
        assert rows["relaxation"][1] == "max_axial_displacement_mm 40.001->40"
        assert "eq. (17) selects the standard layout" in rows["notes"][1]
        assert "layout" not in rows["notes"][0]


@pytest.mark.parametrize("method", ["thesis", "vdi2230"])
def test_bolt_group_once_per_distinct_bolt_equals_every_row(method):
    """The bulk engine evaluates the bolt group once per (application, bolt as the group reads it) and gathers its
    figures per row (``BoltScan.bolt_keys``): the values and margins of every (application, bolt) row are bit-equal
    to those of its key's bolt; at the thesis method (the tightening method not read) fewer keys than bolts, and the
    batch's per-pair smallest margins are those of every row."""
    from synth.design import evaluate
    from synth.optimise.batch import Batch
    b = Batch(generate(6, seed=3), Settings(fidelity="screening", bolt_method=method))
    sp, nb = b.sp, b.sp.n("bolt")
    a, bolt = np.repeat(np.arange(len(b)), nb), np.tile(np.arange(nb), len(b))
    code, rep = b.bolts.bolt_keys()
    assert (len(rep) < nb) == (method == "thesis")
    with np.errstate(over="ignore", divide="ignore", invalid="ignore"):
        every = evaluate.bolt(b.apps, b.cg, b.ptr[a], sp.rows_read("bolt", bolt), b.settings)
        once = evaluate.bolt(b.apps, b.cg, b.ptr[np.repeat(np.arange(len(b)), len(rep))],
                             sp.rows_read("bolt", np.tile(rep, len(b))), b.settings)
    row = a * len(rep) + code[bolt]
    for k, v in every.values.items():
        np.testing.assert_array_equal(np.asarray(once.values[k])[row], v, err_msg=k)
    for k, v in every.margins.items():
        np.testing.assert_array_equal(once.margins[k][row], v, err_msg=k)
    assert np.isfinite(every.values["bolt_sigma_eqv_mpa"]).any()
    ok, mn = b.bolts.app(np.arange(len(b)), np.arange(nb))
    m = np.min([every.margins[c] for c in b.bolts.ids], axis=0)
    np.testing.assert_array_equal(mn[a, bolt], m)
    assert ok.any() and not ok.all()


def test_the_bolt_group_refuses_a_column_it_does_not_declare():
    """Group ``bolt`` reads the bolt table only through ``bolt_reads`` (searches evaluate bolts equal in those
    columns once): a column it does not declare is a KeyError naming it."""
    from synth.design.bolt_group import BOLT_READS, _Declared
    o = _Declared({"bolt_d_mm": [8.0], "cost_eur": [1.0]}, BOLT_READS)
    assert o["bolt_d_mm"] == [8.0] and "bolt_d_mm" in o and "cost_eur" not in o
    with pytest.raises(KeyError, match="cost_eur"):
        o["cost_eur"]
