"""The bulk engine's row is ``synth design``'s design for the same application, ties included (issue 34).

``synth design`` synthesises a single objective name with the margin as its last tie-break
(:func:`synth.optimise.objectives.with_margin_tiebreak`: ``standard`` is ``standard,cost,margin``) on the exact
solver's tables (:func:`synth.optimise.solvers.enumerate.solve_space`); the fast engine searches the decomposed space
by branch and bound (:meth:`synth.optimise.batch.Batch.optimum_margin_ties`). On generated applications about
two feasible rows in three have tied designs (the cone spring's variants, main springs of one price): before the
fix the fast engine named another design in 50 of 70 feasible rows of ``generate(120, seed=7)``, and the exact
solver's 1e-7 tie tolerance on the lexicographic score (1e4 x standard + cost) let it take a design 0.86 mEUR
dearer for its margin (rows 84 and 113).
"""

from __future__ import annotations

import math

import pytest

from synth.bulk import screen_applications
from synth.data.generated_applications import generate
from synth.design.evaluate import Settings
from synth.design.space import PART_KEYS
from synth.optimise import solve
from synth.scenes._options import default_args, synthesise


def _parts(row) -> dict:
    return {k: row[f"part_{k}"] for k in PART_KEYS}


def _same(row, r) -> list:
    """What differs between a bulk row and a synthesis result (empty: the same design, objectives and verdict)."""
    out = []
    feasible = r.status == "optimal" and not r.failed()
    if bool(row["feasible"]) != feasible:
        return [("feasible", row["feasible"], r.status)]
    if not feasible:
        return out
    parts = {k: r.parts.get(k) for k in PART_KEYS}
    out += [(k, a, parts[k]) for k, a in _parts(row).items() if a != parts[k]]
    for col, key in (("objective_standard", "standard"), ("objective_cost_eur", "cost"), ("objective_margin", "margin")):
        if not math.isclose(float(row[col]), float(r.objectives[key]), rel_tol=1e-9, abs_tol=1e-9):
            out.append((col, row[col], r.objectives[key]))
    return out


def test_bulk_rows_are_the_exact_solvers_with_the_margin_tiebreak():
    # rows 80-119 of seed 7: rows 84 and 113 (the 0.86 mEUR tie) and 19 more whose designs tie in score
    apps = generate(120, seed=7)[80:]
    settings = Settings(fidelity="screening")
    df = screen_applications(apps, objective="standard", settings=settings, diagnose=False)
    assert 15 < int(df["feasible"].sum()) < len(apps)
    bad = {}
    for i, d in enumerate(apps):
        r = solve(d, "standard,cost,margin", "enumerate", settings=settings, relax=False)
        diff = _same(df.iloc[i], r)
        if diff:
            bad[80 + i] = diff
    assert not bad, bad


@pytest.mark.parametrize("fidelity", ["full"])
def test_bulk_rows_are_synth_design(fidelity):
    # synth design itself (its default synthesis: the objective standard, every named part honoured) against
    # synth bulk --fidelity full on the same applications
    apps = generate(12, seed=3)
    args = default_args()
    args.fidelity = fidelity
    df = screen_applications(apps, objective="standard", fidelity=fidelity, diagnose=False)
    assert int(df["feasible"].sum()) >= 6
    bad = {i: diff for i, d in enumerate(apps) if (diff := _same(df.iloc[i], synthesise(d, args)))}
    assert not bad, bad
