"""The configuration is an argument (issue 33; issue 39's Python API): one :class:`~synth.design.settings.Settings`
resolved where a run starts and passed to every search, worker and kernel choice. Each test reproduces a defect of
the commit before (d4b9b72), where rules, the spring limit basis and the user catalogs reached the evaluator through
process-wide state that some paths forgot:

* two threads synthesising under different rules saw each other's (16 of 16 runs);
* ``synth.synthesise(d, rules={"spring_limit_basis": "en13906"})`` judged with the thesis's basis (the demo's
  spring passed at +4.97 % instead of failing at -1.79 %);
* ``synth bulk --rules`` with ``spring_limit_basis: en13906`` wrote a RESULT byte-identical to the default's;
* the platform producer kept the compiled spring kernels under ``min_margins: {spring_coil_gap: 0.6}`` and under the
  EN 13906 basis (the no-rules counts), and its Dask path dropped the rules;
* a check whose physics reads a core value its group's function does not (``pivot_diameter_mm`` in the axial group,
  ``bearing_width_mm`` in the bushing and bolt groups) raised ``KeyError``, and a spring check reading an application
  field crashed ``synth.synthesise`` (``'_Requirements' object has no attribute 'f'``).
"""

from __future__ import annotations

import inspect
import threading

import numpy as np
import pandas as pd
import pytest

import synth
from synth.bulk.portfolio import write_table
from synth.data.generated_applications import generate
from synth.design.constraints import Constraint, registered
from synth.design.evaluate import Settings
from synth.design.space import PART_KEYS, SUBSYSTEMS
from synth.platform.portfolio_feasibility import feasibility

COIL_GAP = {"name": "coil gap rule", "min_margins": {"spring_coil_gap": 0.6}}
EN13906 = {"name": "static rule", "spring_limit_basis": "en13906"}


@pytest.fixture(scope="module")
def demo():
    from synth.scenes.demo import default_input
    return default_input()


# ------------------------------------------------------------------------------------------------ the Python API
def test_two_threads_synthesising_under_different_rules_each_get_their_own():
    """Issue 39: a thread calling ``synth.synthesise(d)`` picked up another thread's ``rules=`` (a web server, a
    notebook): 16 runs, each thread's result judged by its own rules only."""
    d = generate(14, seed=11)[13]  # a quick synthesis (about 0.1 s)
    ruled = {"name": "thread A", "min_margins": {"spring_yield": 0.01}}
    gate = threading.Barrier(2)
    got: dict = {"a": [], "b": []}

    def work(name, rules):
        for _ in range(8):
            gate.wait()
            got[name].append(synth.synthesise(d, rules=rules))
    threads = [threading.Thread(target=work, args=("a", ruled)), threading.Thread(target=work, args=("b", None))]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert len(got["a"]) + len(got["b"]) == 16
    assert all(r.rules.get("name") == "thread A" and r.check("spring_yield").required == 0.01 for r in got["a"])
    assert all(r.rules == {} and r.check("spring_yield").required == 0.0 for r in got["b"])


def test_synthesise_judges_by_the_spring_limit_basis_of_its_rules():
    """The basis lives in the rules only (``Settings.spring_limit_basis`` reads them): the design's spring yield
    margin is the static rule's, as the one evaluator gives it (the thesis's before: the demo's spring passed at
    +4.97 % where the static rule fails it at -1.79 %)."""
    d = generate(14, seed=11)[13]
    r = synth.synthesise(d, rules=EN13906)
    assert r.rules["spring_limit_basis"] == r.settings["spring_limit_basis"] == "en13906"
    v = synth.verify(d, r.parts, spring_limit_basis="en13906")
    thesis = synth.verify(d, r.parts)
    assert r.check("spring_yield").margin == v.check("spring_yield").margin != thesis.check("spring_yield").margin
    # the keyword sets the same basis, over the rules' own
    k = synth.verify(d, r.parts, rules={"spring_limit_basis": "thesis"}, spring_limit_basis="en13906")
    assert k.check("spring_yield").margin == v.check("spring_yield").margin


# ------------------------------------------------------------------------------------------------ bulk
def test_bulk_rules_with_the_en13906_basis_judge_every_row_by_it(tmp_path):
    """``synth bulk --rules`` (``spring_limit_basis: en13906``) wrote the default's RESULT byte for byte while its
    manifest said en13906: every row's spring yield margin is now the static rule's (the one evaluator's, for the
    row's design)."""
    from synth.cli import main
    apps = generate(14, seed=11)[12:14]
    table = pd.DataFrame([{k: v for k, v in a.__dict__.items() if v is not None} for a in apps])
    path = write_table(table, tmp_path / "p.csv")
    rules = tmp_path / "rules.yaml"
    rules.write_text("name: static rule\nspring_limit_basis: en13906\n", encoding="utf-8")
    assert main(["bulk", str(path), "--out", str(tmp_path / "a.csv"), "--no-diagnose"]) == 0
    assert main(["bulk", str(path), "--out", str(tmp_path / "b.csv"), "--no-diagnose", "--rules", str(rules)]) == 0
    a, b = (pd.read_csv(tmp_path / f"{x}.csv") for x in "ab")
    assert (tmp_path / "a.csv").read_bytes() != (tmp_path / "b.csv").read_bytes()
    for i, d in enumerate(apps):
        row = b.iloc[i]
        parts = {k: row[f"part_{k}"] for k in PART_KEYS}
        parts = {k: (v.item() if hasattr(v, "item") else v) for k, v in parts.items()}
        want = synth.verify(d, parts, spring_limit_basis="en13906").check("spring_yield").margin
        assert row["margin_spring_yield"] == pytest.approx(want, abs=1e-6)  # 6 significant figures in the CSV
        assert row["margin_spring_yield"] != a.iloc[i]["margin_spring_yield"]


# ------------------------------------------------------------------------------------------------ the platform
def _assert_producer_is_the_product(pf, inputs, settings):
    """Per application, feasible core and subsystem: the producer's feasible options and margins are the optimiser's
    catalog product's under the same configuration (:func:`synth.optimise.product.evaluate`)."""
    from synth.optimise.product import evaluate
    from synth.platform.options import catalogue
    from synth.platform.producer import MARGIN_TOL
    cat = catalogue()
    for a, d in zip(pf.apps, inputs):
        ev = evaluate(d, settings)
        cores = ev.cores[ev.rows]
        assert sorted(a.core_rows.tolist()) == sorted(cores.tolist())
        for r_idx, row in enumerate(cores):
            c = int(np.flatnonzero(a.core_rows == row)[0])
            for s in SUBSYSTEMS:
                g = int(a.group[s][c])
                mine = dict(zip([int(cat.option_row[s][int(o)]) for o in a.feasible[s][g]], a.option_margin[s][g]))
                theirs = np.flatnonzero(ev.subs[s].feasible[r_idx])
                assert set(mine) == set(theirs.tolist()), (a.app_id, s, int(row))
                for k in theirs:
                    assert abs(mine[int(k)] - ev.subs[s].margin[r_idx, k]) <= (MARGIN_TOL if s == "axial" else 0.0)


def _spring_counts(pf) -> list:
    return [sum(len(x) for x in a.feasible["spring"]) for a in pf.apps]


@pytest.fixture(scope="module")
def platform_apps():
    return generate(12, seed=1)[5:8]  # three applications with thousands of feasible springs


@pytest.mark.parametrize("rules", [COIL_GAP, EN13906], ids=["spring_coil_gap", "en13906"])
def test_the_producer_judges_springs_by_the_rules(platform_apps, rules):
    """Under a coil-gap margin of 60 % or the EN 13906 basis the compiled spring kernels (which hold the catalog's
    limits, the thesis's basis and no required margin) give way to their numpy twin: the producer's feasible springs
    are the catalog product's under the rules (they were the no-rules counts, 5750 and 4183 of the issue's)."""
    plain = feasibility(platform_apps)
    s = Settings(rules=rules)
    pf = feasibility(platform_apps, settings=s)
    assert _spring_counts(pf) != _spring_counts(plain)
    assert sum(_spring_counts(pf)) < sum(_spring_counts(plain))
    _assert_producer_is_the_product(pf, platform_apps, s)


def test_the_producer_on_dask_judges_by_the_rules(platform_apps):
    """The Dask path gave the workers no rules (the no-rules counts): the settings travel with every chunk."""
    s = Settings(rules=COIL_GAP)
    here = feasibility(platform_apps[:2], settings=s)
    there = feasibility(platform_apps[:2], settings=s, engine="dask", workers=2)
    assert there.stats["chunks"] == 2
    assert _spring_counts(there) == _spring_counts(here) != _spring_counts(feasibility(platform_apps[:2]))


# ------------------------------------------------------------------------------------------------ what a check reads
def _check(cid: str, group: str, key: str, limit: float) -> Constraint:
    """A check of ``group``: ``key <= limit`` (margin ``(limit - key) / limit``), its physics reading ``key``."""
    def physics(**kw):
        v = np.asarray(kw[key], dtype=float)
        return {f"{cid}_value": v, f"{cid}_limit": np.full(np.shape(v), limit)}
    physics.__signature__ = inspect.Signature([inspect.Parameter(key, inspect.Parameter.KEYWORD_ONLY)])
    return Constraint(id=cid, label=f"{group} check reading {key}", step=0, equation="test", unit="mm", group=group,
                      value=f"{cid}_value", limit=f"{cid}_limit", sense="<=", physics=physics)


def test_checks_reading_core_values_their_groups_do_not_read_are_judged_per_core():
    """A check of the axial, bushing or bolt group whose physics reads a core value the group's function does not
    (the pivot diameter, the bearing width) raised KeyError until a hand-kept tuple was edited; the core values a
    group reads are now derived from the registry (:func:`synth.design.evaluate.core_values`), and the searches
    that evaluate a group once per distinct value of what it reads of the core key on them: the bulk engine's
    fast path gives the exhaustive enumeration's answers, the platform producer the catalog product's."""
    from synth.bulk.engine import screen_applications, screen_applications_reference
    checks = (_check("probe_axial_pivot", "axial", "pivot_diameter_mm", 19.5),
              _check("probe_bushing_bearing", "bushing", "bearing_width_mm", 15.5),
              _check("probe_bolt_bearing", "bolt", "bearing_width_mm", 16.5))
    apps = generate(4, seed=3)
    with registered(*checks):
        fast = screen_applications(apps, diagnose=False)
        ref = screen_applications_reference(apps, diagnose=False)
        pd.testing.assert_frame_equal(fast, ref, check_exact=False, rtol=1e-9, atol=1e-12)
        for c in checks:  # every check was evaluated, and one of them binds a chosen design
            assert fast[f"margin_{c.id}"].notna().all()
        assert (fast[[f"margin_{c.id}" for c in checks]].to_numpy() < 0.05).any()
        r = synth.synthesise(apps[0])
        assert all(c.id in r.margins for c in checks)
        pf = feasibility(apps[:2])
        _assert_producer_is_the_product(pf, apps[:2], Settings())
        from synth.design.evaluate import core_values
        names = {"pivot_diameter_mm": 0, "bearing_width_mm": 0}
        assert "pivot_diameter_mm" in core_values("axial", names)
        assert "bearing_width_mm" in core_values("bushing", names) and "bearing_width_mm" in core_values("bolt", names)
    assert "pivot_diameter_mm" not in core_values("axial", names)  # the registry as it is now


def test_a_spring_check_reading_an_application_field_is_judged_on_every_path(demo):
    """A spring check whose physics reads an application field crashed ``synth.synthesise`` (the kernels' numpy
    twin passed a stub instead of the applications): the keys carry their applications now."""
    check = _check("probe_spring_height", "spring", "max_pivot_height_mm", 1000.0)
    with registered(check):
        r = synth.synthesise(demo)
        want = (1000.0 - demo.max_pivot_height_mm) / 1000.0
        assert r.margins["probe_spring_height"] == pytest.approx(want, rel=1e-12)
        df = synth.screen([demo], diagnose=False, progress=False)
        assert df["margin_probe_spring_height"].iloc[0] == pytest.approx(want, rel=1e-12)
        pf = feasibility([demo])
        assert any(len(x) for x in pf.apps[0].feasible["spring"])


# ------------------------------------------------------------------------------------------------ user catalogs
def test_user_catalogs_are_per_call_and_reach_every_worker(tmp_path, demo):
    """``catalogs=`` is the call's, not the process's: a thread verifying with a user catalog (a 0.2 mm minimum
    coil gap) and one without, at once, each read their own; the bulk run hands the folders to its chunks."""
    folder = tmp_path / "cat"
    folder.mkdir()
    (folder / "constants_main_spring.csv").write_text(
        "name,value,unit,source,note\nmain_spring_min_coil_gap_mm,0.2,mm,test,stricter\n", encoding="utf-8")
    parts = synth.synthesise(demo).parts
    gate = threading.Barrier(2)
    got: dict = {"user": [], "plain": []}

    def work(name, kw):
        for _ in range(4):
            gate.wait()
            got[name].append(synth.verify(demo, parts, **kw).check("spring_coil_gap").limit)
    threads = [threading.Thread(target=work, args=("user", {"catalogs": [folder]})),
               threading.Thread(target=work, args=("plain", {}))]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert got == {"user": [0.2] * 4, "plain": [0.0] * 4}
    from synth import catalog
    assert catalog.user_dirs() == []
    df = synth.screen([demo], diagnose=False, progress=False, catalogs=[folder])
    plain = synth.screen([demo], diagnose=False, progress=False)
    assert df["margin_spring_coil_gap"].iloc[0] != plain["margin_spring_coil_gap"].iloc[0]
