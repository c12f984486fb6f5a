"""The fast paths (issue 13) against the reference per-application path: the same rows, designs and relaxations.

Sources: the reference is ``screen_applications_reference`` (``solve(d, objective, "enumerate", exhaustive=True)``
per application: every core and option of the catalog product evaluated, the nearest design by the exhaustive
``nearest_design``, each relaxation probe one exhaustive feasibility check) and ``row_from_result``; the
applications are generated across the input schema's choices with every optional input present and absent
(``generate(n, seed, vary=True)``). No timing is asserted here: speed is measured by ``benchmarks/``.

* 100 generated applications at screening fidelity (ten slices of 10, each with feasible and failing rows;
  `benchmarks/bench_bulk.py` compares more): every column equal (same verdicts,
  statuses, chosen or nearest designs, objectives, notes; margins to 1e-9);
* the relaxations of the infeasible ones (diagnosis on) and full fidelity on smaller samples;
* ``solve(d, ..., "enumerate")`` (branch and bound) against ``exhaustive=True``: the same Result;
* :func:`synth.optimise.diagnose.relaxations_batch` against :func:`~synth.optimise.diagnose.relaxations`;
* an application whose data a physics function refuses does not change the others' rows.
"""

from __future__ import annotations

import dataclasses
import json

import numpy as np
import pandas as pd
import pytest

from synth.bulk.engine import columns, screen_applications, screen_applications_reference
from synth.data.generated_applications import generate
from synth.design.evaluate import Settings
from synth.optimise import solve
from synth.optimise.batch import Batch, any_feasible
from synth.optimise.diagnose import is_feasible, relaxations, relaxations_batch

PORTFOLIO = generate(100, seed=31, vary=True)  # the slices below; the first 40 for the relaxations


def assert_same_rows(fast: pd.DataFrame, ref: pd.DataFrame):
    """Every column equal: floats to 1e-9 (NaN where NaN, the same infinities), the others as text."""
    assert list(fast.columns) == list(ref.columns) == columns()
    assert len(fast) == len(ref)
    for c in fast.columns:
        a, b = fast[c].to_numpy(), ref[c].to_numpy()
        if fast[c].dtype == float:
            with np.errstate(invalid="ignore"):
                same = (np.isnan(a) & np.isnan(b)) | (a == b) | (np.abs(a - b) <= 1e-9)
            assert same.all(), (c, np.flatnonzero(~same)[:5], a[~same][:3], b[~same][:3])
        else:
            bad = [i for i, (x, y) in enumerate(zip(a, b)) if str(x) != str(y)]
            assert not bad, (c, bad[:5], [a[i] for i in bad[:2]], [b[i] for i in bad[:2]])


def _infeasible(apps, settings, n: int) -> list:
    """The first ``n`` applications of ``apps`` that no design satisfies (checked one by one, stopping at the
    ``n``-th: a feasibility check costs 0.1-0.6 s of CPU, and checking all 40 took 14 s of the suite)."""
    found = []
    for d in apps:
        if len(found) == n:
            break
        if not is_feasible(d, settings):
            found.append(d)
    return found


@pytest.mark.parametrize("part", range(10))
def test_fast_path_equals_the_reference_on_100_generated_applications(part):
    # 10 slices of 10 (each reference row is a whole per-application search, about 0.6 s: 500 took 320 s of the
    # suite, 200 took 120 s)
    apps = PORTFOLIO[10 * part:10 * (part + 1)]
    fast = screen_applications(apps, objective="standard", fidelity="screening", diagnose=False)
    ref = screen_applications_reference(apps, objective="standard", fidelity="screening", diagnose=False)
    assert_same_rows(fast, ref)
    # both verdicts and both kinds of rows occur in every slice (otherwise the comparison proves little)
    assert 0 < fast["feasible"].sum() < len(apps)
    assert {"pass", "incomplete", "fail"} >= set(fast["verdict"]) and "fail" in set(fast["verdict"])


def test_relaxations_equal_the_reference():
    # infeasible applications (generated with every input given, and varied), diagnosis on: the same probes, the
    # same bisection, the same relaxation strings
    st = Settings(fidelity="screening")
    # 6 applications (4 + 2 varied: optional inputs absent): each reference row is a whole sequential diagnosis
    # (1-7 s of CPU each; the 9 of before took 44 s of the suite, these 12 s of CPU of 25); 3 get a relaxation (two
    # of the spring's stiffness, one of the bolt's threads), 3 none
    given = _infeasible(generate(40, seed=38), st, 5)
    varied = _infeasible(PORTFOLIO[:40], st, 3)
    apps = [given[i] for i in (0, 1, 2, 4)] + [varied[i] for i in (0, 2)]
    assert len(apps) == 6
    fast = screen_applications(apps, objective="standard", diagnose=True)
    ref = screen_applications_reference(apps, objective="standard", diagnose=True)
    assert_same_rows(fast, ref)
    relaxed = [r for r in fast["relaxation"] if r]
    assert len(relaxed) >= 3 and len(apps) - len(relaxed) >= 3
    assert {r.split()[0] for r in relaxed} >= {"spring_stiffness_nm_per_deg", "number_of_active_threads"}


def test_full_fidelity_and_cost_objective_equal_the_reference():
    # 20 generated applications, 10 for each setting (20 for each took 25 s of CPU): each slice has chosen designs
    # and nearest ones
    portfolio = generate(20, seed=32, vary=True)
    for part, (fid, obj) in enumerate((("full", "standard"), ("screening", "cost"))):
        apps = portfolio[10 * part:10 * (part + 1)]
        assert len(apps) == 10
        fast = screen_applications(apps, objective=obj, fidelity=fid, diagnose=False)
        assert_same_rows(fast, screen_applications_reference(apps, objective=obj, fidelity=fid, diagnose=False))
        assert 0 < fast["feasible"].sum() < len(apps)  # chosen designs and nearest ones compared


def _without_stats(r) -> str:
    d = r.to_dict()
    d.pop("stats")
    return json.dumps(d, sort_keys=True, default=str)


@pytest.mark.parametrize("part, fidelity", [(0, "screening"), (1, "full")])
def test_branch_and_bound_solve_is_the_exhaustive_result(part, fidelity):
    # 24 generated applications, 12 at each fidelity (24 at each took 16 s of CPU per fidelity, mostly the exhaustive
    # diagnosis of the infeasible ones); each half has optimal and infeasible ones
    st = Settings(fidelity=fidelity)
    apps = generate(24, seed=33, vary=True)[12 * part:12 * (part + 1)]
    statuses = set()
    for d in apps:
        fast = solve(d, "standard", "enumerate", settings=st)
        ref = solve(d, "standard", "enumerate", settings=st, exhaustive=True)
        assert _without_stats(fast) == _without_stats(ref)
        statuses.add(fast.status)
    assert statuses == {"optimal", "infeasible"}


def test_batched_relaxations_equal_the_sequential_ones():
    st = Settings(fidelity="screening")
    apps = _infeasible(generate(40, seed=34, vary=True), st, 6)
    violated = []
    for d in apps:
        r = solve(d, "standard", "enumerate", settings=st, relax=False, exhaustive=True)
        violated.append([c.id for c in r.failed()])
    batch = relaxations_batch(apps, violated, settings=st)
    for d, v, got in zip(apps, violated, batch):
        assert got == relaxations(d, v, settings=st)
    assert any(batch)


def test_feasibility_probe_equals_is_feasible():
    st = Settings(fidelity="screening")
    apps = generate(40, seed=35, vary=True)
    got = any_feasible(apps, st)
    assert got == [is_feasible(d, st) for d in apps]
    assert any(got) and not all(got)


def test_an_application_the_physics_refuses_gets_its_own_row():
    # the fixation refuses a support whose external diameter is not above the internal one (InputError inside the
    # chunk's vectorised call): that application takes the reference path, the others are unaffected
    apps = generate(6, seed=36)
    bad = dataclasses.replace(apps[2], engine_support_external_diameter_mm=apps[2].engine_support_internal_diameter_mm)
    chunk = apps[:2] + [bad] + apps[3:]
    fast = screen_applications(chunk, diagnose=False)
    assert_same_rows(fast, screen_applications_reference(chunk, diagnose=False))
    assert fast.loc[2, "notes"].startswith("not evaluated")
    assert_same_rows(fast.drop(index=2).reset_index(drop=True),
                     screen_applications_reference(apps[:2] + apps[3:], diagnose=False))


def test_batch_nearest_design_is_the_exhaustive_one():
    from synth.optimise.diagnose import nearest_design
    from synth.optimise.product import evaluate
    st = Settings(fidelity="screening")
    # 12 generated applications in one batch (25 took 14 s of CPU: each exhaustive reference evaluates the whole
    # unpruned product, 0.5 s)
    apps = generate(12, seed=37, vary=True)
    b = Batch(apps, st, spring_engine="numpy")
    near = b.nearest()
    for i, d in enumerate(apps):
        ev = evaluate(d, st, prune=False)
        pos, opts, value = nearest_design(ev)
        assert (int(b.C[near[i][0]]), near[i][1], near[i][2]) == (int(ev.cores[pos]), opts, value)
