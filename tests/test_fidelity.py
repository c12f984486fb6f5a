"""Screen then verify (issue 19): at fidelity ``screening`` nothing is reported feasible that the full model rejects.

The screening model (linear cone spring, closed-form plastic wear) ranks and prunes; the full model (Almen-Laszlo,
the exact wear along it) judges every design a search keeps (:attr:`synth.design.evaluate.Settings.judge`). Checked
against the full model itself, design by design:

* 500 generated applications through the bulk engine at the default fidelity: every design reported feasible
  passes the full model's checks, and every verdict is the full-fidelity engine's; the same check finds designs
  the full model rejects at ``screening-only`` (it has teeth), and those rows say they are unverified;
* the single-application paths (branch and bound, the exhaustive tables the model solvers read, the platform's
  feasibility data) keep only designs the full model passes;
* where the screening model rejects every design the full model accepts (forced here by a screening model that
  fails everything), the searches still find the full model's designs: "no design" is the full model's verdict.
"""

from __future__ import annotations

import numpy as np
import pytest

from synth.bulk.engine import screen_applications
from synth.data.generated_applications import generate
from synth.design import axial_group, evaluate
from synth.design.applications import Applications
from synth.design.space import PART_KEYS, space
from synth.design.verify import evaluate_design
from synth.errors import InputError
from synth.optimise import solve

APPS = generate(500, seed=19, vary=True)
FULL = evaluate.Settings(fidelity="full")


def failing_at_full(apps: list, parts: list) -> list:
    """Indices of the designs ``parts[i]`` (part keys) of ``apps[i]`` that the full model rejects (one vectorised
    verification of all of them: :func:`synth.design.verify.evaluate_design`)."""
    if not parts:
        return []
    sp = space()
    one = [sp.design_attributes(p) for p in parts]
    attrs = {t: {k: np.concatenate([np.asarray(x[t][k]) for x in one]) for k in one[0][t]} for t in one[0]}
    with np.errstate(all="ignore"):
        groups = evaluate_design(Applications.of(apps), attrs, FULL, detail=False)
    ok = np.ones(len(parts), dtype=bool)
    for g in groups.values():
        ok &= g.ok()
    return [int(i) for i in np.flatnonzero(~ok)]


def reported_feasible(df, apps):
    idx = np.flatnonzero(df["feasible"].to_numpy())
    return [apps[i] for i in idx], [{k: df.loc[i, f"part_{k}"] for k in PART_KEYS} for i in idx]


@pytest.fixture(scope="module")
def engine():
    return {fid: screen_applications(APPS, objective="standard", fidelity=fid, diagnose=False)
            for fid in evaluate.FIDELITIES}


def test_no_design_reported_feasible_fails_at_full_fidelity(engine):
    df = engine["screening"]
    apps, parts = reported_feasible(df, APPS)
    assert len(parts) > 150
    assert failing_at_full(apps, parts) == []
    # the verdict of every application is the full model's
    assert (df["feasible"].to_numpy() == engine["full"]["feasible"].to_numpy()).all()
    assert not df["notes"].str.contains("screening-only").any()


def test_screening_only_reports_designs_the_full_model_rejects_and_says_so(engine):
    df = engine["screening-only"]
    apps, parts = reported_feasible(df, APPS)
    assert len(failing_at_full(apps, parts)) >= 10  # the check above can fail: unverified designs do (19 of 500 here)
    assert df["notes"].str.contains(evaluate.UNVERIFIED_NOTE, regex=False).all()


def test_the_judge_is_the_full_model():
    assert evaluate.Settings(fidelity="screening").judge == FULL
    assert evaluate.Settings(fidelity="screening-only").judge.model == "screening"
    assert FULL.judge is FULL
    with pytest.raises(InputError, match="screening-only"):
        evaluate.Settings(fidelity="quick")


@pytest.fixture(scope="module")
def unverified_failures(engine):
    """Applications whose screening-only optimum the full model rejects (the ones screen-then-verify must mend)."""
    apps, parts = reported_feasible(engine["screening-only"], APPS)
    return [apps[i] for i in failing_at_full(apps, parts)]


@pytest.mark.parametrize("solver,kw,n", [("enumerate", {}, 3), ("enumerate", {"exhaustive": True}, 2),
                                          ("milp-highs", {}, 1)])
def test_single_application_paths_report_designs_valid_at_full_fidelity(unverified_failures, solver, kw, n):
    for d in unverified_failures[:n]:
        r = solve(d, "standard", solver, settings=evaluate.Settings(fidelity="screening"), relax=False, **kw)
        assert r.status == "optimal" and not r.failed(), [c.id for c in r.failed()]
        assert failing_at_full([d], [r.parts]) == []
        assert r.settings["fidelity"] == "screening"  # the search's setting is kept; the checks are the judge's
        again = solve(d, "standard", solver, settings=FULL, relax=False, **kw)
        assert r.objectives["standard"] >= again.objectives["standard"] - 1e-12  # never better than the full optimum


def test_platform_feasibility_at_screening_is_judged():
    from synth.platform.portfolio_feasibility import feasibility
    apps = APPS[:16]
    pf = feasibility(apps, None, None, evaluate.Settings(fidelity="screening"))
    full = feasibility(apps, None, None, FULL)
    for a, b in zip(pf.apps, full.apps):
        for k in range(len(a.core_rows)):
            j = list(b.core_rows).index(a.core_rows[k])
            ga, gb = a.group["axial"][k], b.group["axial"][j]
            assert set(a.feasible["axial"][ga].tolist()) <= set(b.feasible["axial"][gb].tolist())


def test_no_design_at_screening_is_the_full_model_s_verdict(monkeypatch):
    """A screening model that rejects every axial option: the searches fall back to the full model alone where the
    axial group decides, and find the full model's optimum (bulk engine, branch and bound, exhaustive tables)."""
    real = evaluate.axial

    def strict(apps, cg, r, o, settings=evaluate.DEFAULT, time_points=0, engine=None):
        g = real(apps, cg, r, o, settings, time_points, engine)
        if settings.model == "screening":
            g.margins["damping_eol"] = np.full(len(g), -1.0)
            g.state["damping_eol"] = np.zeros(len(g), dtype=np.int8)
        return g
    monkeypatch.setattr(evaluate, "axial", strict)
    monkeypatch.setattr(axial_group, "axial", strict)  # screen-then-judge calls its own module's
    apps = [d for d in APPS[:40] if d.damping_typology != "only_radial"][:12]
    full = screen_applications(apps, objective="standard", fidelity="full", diagnose=False)
    assert full["feasible"].sum() >= 3
    scr = screen_applications(apps, objective="standard", fidelity="screening", diagnose=False)
    only = screen_applications(apps, objective="standard", fidelity="screening-only", diagnose=False)
    assert (scr["feasible"].to_numpy() == full["feasible"].to_numpy()).all()
    assert not only["feasible"][only["part_damper_pad_class"] != "none"].any()
    i = int(np.flatnonzero(full["feasible"].to_numpy() & (full["part_damper_pad_class"] != "none").to_numpy())[0])
    for kw in ({}, {"exhaustive": True}):
        r = solve(apps[i], "standard", "enumerate", settings=evaluate.Settings(fidelity="screening"), relax=False, **kw)
        assert r.status == "optimal" and r.objectives["standard"] == full.loc[i, "objective_standard"]


def test_fidelity_free_constraints_have_the_same_margin_in_both_models():
    """What :func:`synth.design.evaluate.axial_full` relies on: the axial constraints reading no value the fidelity
    changes have the same margins at both fidelities (every axial option of every core of 8 applications)."""
    from synth.design.space import core_rows
    apps = [d for d in APPS[:40] if d.damping_typology != "only_radial"][:8]
    a = Applications.of(apps)
    sp = space()
    per = [core_rows(sp, d) for d in apps]
    app = np.repeat(np.arange(len(apps)), [len(c) for c in per])
    cg = evaluate.core(a, app, sp.rows("core", np.concatenate(per)), FULL)
    t = sp.tables["axial"]
    r, k = np.nonzero((cg.values["axial_group_present"] > 0)[:, None] == t["axial_group_present"][None, :])
    with np.errstate(all="ignore"):
        g = {m: evaluate.axial(a, cg, r, sp.rows("axial", k), evaluate.Settings(fidelity=m)) for m in ("full", "screening-only")}
    assert len(r) > 1000 and set(evaluate.FIDELITY_FREE) >= {"belt_plane", "endcap_spacer_capacity"}
    for cid in evaluate.FIDELITY_FREE:
        assert np.array_equal(g["full"].margins[cid], g["screening-only"].margins[cid]), cid
    assert not np.array_equal(g["full"].margins["damping_eol"], g["screening-only"].margins["damping_eol"])
