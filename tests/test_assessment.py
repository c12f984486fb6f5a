"""The one assessment (:mod:`synth.design.assessment`, issue 21): what the registry's margins mean, judged once.

Cross-checks: the assessment of many designs evaluated together (one row each, :func:`evaluate_design`) against
each design's own flowchart result (its checks, made by the flowchart's sequential evaluation), on generated
applications whose designs fail, warn (advisory ranges), are not verified (missing optional data) and use
documented defaults; a saved result read back; and a property test of the rules on random margins against a
plain per-check statement of them (the module docstring's).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st

from synth import flowchart
from synth.data.generated_applications import generate
from synth.design import evaluate
from synth.design.applications import Applications
from synth.design.assessment import (EVALUATED, NOT_APPLICABLE, NOT_VERIFIED_STATE, Assessment, assess,
                                     columns_of)
from synth.design.constraints import FEAS_TOL, REGISTRY
from synth.design.result import FAIL, NOT_VERIFIED, PASS, WARNING, Result
from synth.design.result import NOT_APPLICABLE as NOT_APPLICABLE_VERDICT
from synth.design.space import space
from synth.design.verify import evaluate_design
from synth.optimise.answer import design_margin

SETTINGS = evaluate.Settings(fidelity="screening-only")  # one model on both paths (the flowchart's and the rows')
TOL = 1e-9


@pytest.fixture(scope="module")
def judged():
    """``(flowchart results, the assessment of their designs evaluated together)``."""
    apps_in = generate(30, seed=11, vary=True)
    results = [flowchart.run(d, SETTINGS, time_points=0) for d in apps_in]
    keep = [i for i, r in enumerate(results) if r.parts]
    sp = space()
    per = [sp.design_attributes(results[i].parts) for i in keep]
    attrs = {t: {c: np.concatenate([np.asarray(a[t][c]) for a in per]) for c in per[0][t]} for t in per[0]}
    apps = Applications.of([apps_in[i] for i in keep])
    with np.errstate(all="ignore"):
        groups = evaluate_design(apps, attrs, SETTINGS, detail=False)
    return [results[i] for i in keep], assess(groups, apps)


def _close(a: float, b: float) -> bool:
    return a == b if (math.isinf(a) or math.isinf(b)) else abs(a - b) <= TOL * max(1.0, abs(b))


def test_the_assessment_of_many_designs_equals_each_design_s_checks(judged):
    results, a = judged
    ids = list(a.columns.ids)
    verdicts = {FAIL: 0, WARNING: 0, NOT_VERIFIED: 0}
    for j, r in enumerate(results):
        for c in r.checks:
            if c.id not in ids:
                continue
            k = ids.index(c.id)
            state = int(a.state[j, k])
            got = {NOT_APPLICABLE: NOT_APPLICABLE_VERDICT, NOT_VERIFIED_STATE: NOT_VERIFIED}.get(state) or (
                FAIL if a.failed[j, k] else WARNING if a.warning[j, k] else PASS)
            assert got == c.verdict, (j, c.id, got, c.verdict)
            verdicts[c.verdict] = verdicts.get(c.verdict, 0) + 1
            if state == EVALUATED:
                assert _close(float(a.margins[j, k]), c.margin), (j, c.id)
                assert bool(a.assumed[j, k]) == bool(c.assumed), (j, c.id)
        # the design's judgement: verdict, smallest margin, margin objective, binding constraint
        assert a.verdict[j] == r.verdict, j
        assert _close(float(a.margin_min[j]), min(r.margins.values(), default=math.inf)), j
        assert _close(float(a.objective_margin[j]), design_margin(r)), j
        failed = sorted(r.failed(), key=lambda c: c.margin)
        bind = (failed[:1] or r.binding(1) or [None])[0]
        assert a.binding_ids()[j] == (bind.id if bind else ""), j
    # the designs cover every verdict of a check and of a design
    assert min(verdicts[FAIL], verdicts[WARNING], verdicts[NOT_VERIFIED]) > 0, verdicts
    assert {"fail", "incomplete"} <= set(a.verdict.tolist())
    assert a.assumed.any() and (a.verdict == "incomplete").any()


def test_a_saved_result_is_judged_as_the_one_it_was_saved_from(judged):
    results, _ = judged
    for r in results[:6]:
        back = Result.from_dict(r.to_dict(digits=None))
        x, y = r.assessment(), back.assessment()
        assert back.verdict == r.verdict
        assert y.binding_ids().tolist() == x.binding_ids().tolist()
        assert y.objective_margin.tolist() == x.objective_margin.tolist()
        finite = {k: v for k, v in r.margins.items() if math.isfinite(v)}  # JSON keeps no infinite margin
        assert back.margins == finite


def _column_ids() -> list:
    """A mix of registry checks: non-advisory ones in and out of the margin objective, advisory ones, one with an
    ``objective_unless`` value."""
    mix = [cid for cid, c in REGISTRY.items() if c.advisory][:2]
    mix += [cid for cid, c in REGISTRY.items() if not c.advisory and not c.objective][:2]
    mix += [cid for cid, c in REGISTRY.items() if c.objective and not c.advisory and not c.objective_unless][:2]
    mix += [cid for cid, c in REGISTRY.items() if c.objective_unless][:1]
    return [cid for cid in REGISTRY if cid in mix]  # registry order


MARGINS = st.sampled_from([-math.inf, -1.0, -2 * FEAS_TOL, -FEAS_TOL, 0.0, 0.25, 0.25, 3.0, math.inf])


@settings(max_examples=150, deadline=None)
@given(st.data())
def test_the_rules_on_random_margins(data):
    ids = _column_ids()
    k = len(ids)
    n = data.draw(st.integers(1, 4))
    marg = np.array(data.draw(st.lists(MARGINS, min_size=n * k, max_size=n * k)), dtype=float).reshape(n, k)
    state = np.array(data.draw(st.lists(st.sampled_from([EVALUATED, EVALUATED, NOT_APPLICABLE, NOT_VERIFIED_STATE]),
                                        min_size=n * k, max_size=n * k)), dtype=np.int8).reshape(n, k)
    unless = np.array(data.draw(st.lists(st.sampled_from([0.0, 1.0, math.nan]), min_size=n, max_size=n)))
    marg = np.where(state == EVALUATED, marg, np.inf)  # the evaluator's contract
    cols = columns_of(tuple(ids))
    u = {j: unless for j, cid in enumerate(ids) if REGISTRY[cid].objective_unless}
    a = Assessment(cols, [marg[:, c] for c in range(k)], [state[:, c] for c in range(k)], u)
    for i in range(n):
        cons = [REGISTRY[cid] for cid in ids]
        ev = [state[i, c] == EVALUATED for c in range(k)]
        fails = [c for c in range(k) if ev[c] and not cons[c].advisory and marg[i, c] < -FEAS_TOL]
        counted = [marg[i, c] for c in range(k) if ev[c] and not cons[c].advisory]
        in_obj = [marg[i, c] for c in range(k) if ev[c] and cons[c].objective and not cons[c].advisory
                  and not (cons[c].objective_unless and unless[i] > 0)]
        cands = [c for c in range(k) if ev[c] and cons[c].objective and not cons[c].advisory]
        incomplete = any(state[i, c] == NOT_VERIFIED_STATE for c in range(k))
        assert a.verdict[i] == ("fail" if fails else "incomplete" if incomplete else "pass")
        assert bool(a.ok[i]) == (not fails)
        assert a.margin_min[i] == min(counted, default=math.inf)
        assert a.objective_margin[i] == min(in_obj, default=math.inf)
        if fails:  # the most violated, the first of ties
            assert a.binding[i] == min(fails, key=lambda c: (marg[i, c], c))
        elif cands:
            assert a.binding[i] == min(cands, key=lambda c: (marg[i, c], c))
            assert a.binding_margin[i] == marg[i, a.binding[i]]
        else:
            assert a.binding_ids()[i] == "" and a.binding_margin[i] == math.inf
        warn = [c for c in range(k) if ev[c] and cons[c].advisory and marg[i, c] < -FEAS_TOL]
        assert np.flatnonzero(a.warning[i]).tolist() == warn
