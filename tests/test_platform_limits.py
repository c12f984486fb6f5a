"""The MILP's limits: a node limit gives the same platform on every run and says it bound; the wall-clock safety net
says the platform it stopped at is not reproducible (issue 36: at 10,000 applications the platform followed the
machine's load)."""

import argparse

import highspy
import numpy as np
import pytest

from formulations.platform import HIGHS_THREADS, NODE_LIMIT, TIME_LIMIT_S
from synth.errors import InputError
from synth.platform.data import SUBSYSTEMS, AppFeasibility, PortfolioFeasibility, validate
from synth.platform.outputs import report_section, summary_markdown
from synth.platform.rationalise import rationalise
from synth.scenes import rationalise as scene


def hitting_set_portfolio(n_apps: int = 50, n_springs: int = 20, k: int = 3, seed: int = 1) -> PortfolioFeasibility:
    """One core and one option of every subsystem but the main spring, which each application takes from ``k`` of
    ``n_springs`` drawn at random: the fewest springs that serve every application is a minimum hitting set, whose LP
    relaxation is fractional, so HiGHS branches (the defaults: 14 nodes to the optimum, 9 springs and one part of
    four other families, the root's bound 12; the portfolios :func:`synth.platform.synthetic.synthetic_portfolio` draws solve at the root)."""
    rng = np.random.default_rng(seed)
    parts = {"ball_bearing": ["B0"], "pivot_class_diameter_mm": ["10"], "damper_pad_class": ["P0"],
             "pivot_bushing": ["A/10"], "endcap_spacer_class": ["E0"], "cone_spring": ["C0"],
             "main_spring": [f"S{i}" for i in range(n_springs)], "bolt": ["M8"]}
    options = {"bushing": {"pivot_bushing": np.array([0])},
               "axial": {"endcap_spacer_class": np.array([-1]), "cone_spring": np.array([-1])},
               "spring": {"main_spring": np.arange(n_springs)}, "bolt": {"bolt": np.array([0])}}
    apps = []
    for a in range(n_apps):
        feas = {s: [np.array([0])] for s in SUBSYSTEMS}
        feas["spring"] = [np.sort(rng.choice(n_springs, k, replace=False))]
        apps.append(AppFeasibility(
            app_id=f"H{a:03d}", core_parts={"ball_bearing": np.array([0]), "pivot_class_diameter_mm": np.array([0]),
                                            "damper_pad_class": np.array([-1])},
            core_cost_eur=np.ones(1), core_margin=np.full(1, 0.5), group={s: np.zeros(1, int) for s in SUBSYSTEMS},
            feasible=feas, option_margin={s: [np.full(len(f[0]), 0.5)] for s, f in feas.items()}))
    return validate(PortfolioFeasibility(
        apps=apps, parts=parts, part_cost_eur={f: np.full(len(p), 1000.0) for f, p in parts.items()},
        options=options, option_cost_eur={s: np.ones(len(next(iter(o.values())))) for s, o in options.items()}))


@pytest.fixture(scope="module")
def pf():
    return hitting_set_portfolio()


def _key(r):
    return r.status, {f: sorted(c) for f, c in r.platform.items()}, r.objective_value, r.bound, r.limits


def test_the_node_limit_binds_and_gives_the_same_platform(pf):
    """Three nodes of the 14 the optimum takes: status ``node_limit``, the root's bound (12 against 13: a gap of
    1/13), the same platform, objective, bound and node count on every run; the optimum is no larger, and the
    outputs say which limit bound and that the platform is reproducible."""
    first, again = (rationalise(pf, node_limit=3, verify=False, details=i == 0) for i in range(2))
    assert first.status == "node_limit" and first.limits["nodes"] == 3 and first.reproducible
    assert (first.objective_value, first.bound) == pytest.approx((13.0, 12.0)) and first.gap == pytest.approx(1 / 13)
    assert _key(again) == _key(first)
    best = rationalise(pf, verify=False, details=False)
    assert best.status == "optimal" and best.limits["nodes"] > 3 and best.limits["node_limit"] == NODE_LIMIT
    springs = set(best.platform["main_spring"])           # 9 springs that hit every application's three
    assert len(springs) == 9 and best.n_parts == round(best.objective_value) == 13
    assert all(springs & set(a.feasible["spring"][0].tolist()) for a in pf.apps)
    said = "stopped at the node limit (3 nodes): reproducible, gap 7.69%"
    assert said in report_section(first)
    md = summary_markdown(pf, first)
    assert "- MILP: stopped at the node limit (3 nodes): reproducible, gap 7.692%" in md
    assert "- limits: node limit 3 (deterministic), time limit 600 s (wall-clock safety net); 3 nodes taken" in md


def test_the_node_limit_reaches_the_pyomo_reference(pf):
    """The Pyomo model (``build="pyomo"``, appsi's HiGHS) gets the same limit and thread count: the same stop."""
    a = rationalise(pf, node_limit=3, verify=False, details=False)
    assert _key(rationalise(pf, node_limit=3, verify=False, details=False, build="pyomo")) == _key(a)


def test_the_time_limit_is_a_safety_net_that_says_not_reproducible(pf):
    """A time limit no solve can meet (a microsecond): the platform found so far, and every output says the time
    limit stopped it and that it is not reproducible; the trade-off rows say so too."""
    r = rationalise(pf, time_limit=1e-6, verify=False)
    assert r.limits["milp_status"] == "time_limit" and not r.reproducible
    assert r.status in ("time_limit", "greedy") and r.n_parts >= 13
    assert "stopped at the time limit (1e-06 s)" in report_section(r)
    assert ": not reproducible" in summary_markdown(pf, r)
    assert TIME_LIMIT_S >= 300 and rationalise.__kwdefaults__["time_limit"] == TIME_LIMIT_S


def test_highs_runs_on_one_thread_after_another_pool(pf):
    """HiGHS's thread pool is one per process; one made by another solve with two threads (HiGHS's default on this
    machine) is rebuilt with one, and the platform is the one a fresh process gets."""
    want = _key(rationalise(pf, node_limit=3, verify=False, details=False))
    highspy.Highs.resetGlobalScheduler(True)
    h = highspy.Highs()
    h.setOptionValue("output_flag", False)
    h.setOptionValue("threads", 2)
    h.addVars(1, np.zeros(1), np.ones(1))
    assert h.run() == highspy.HighsStatus.kOk
    assert HIGHS_THREADS == 1 and _key(rationalise(pf, node_limit=3, verify=False, details=False)) == want


def test_a_bad_node_limit_is_named(pf, tmp_path):
    for bad in (0, -3, 2.5, True):
        with pytest.raises(InputError, match="--node-limit"):
            rationalise(pf, node_limit=bad)
    p = argparse.ArgumentParser()
    scene.register(p.add_subparsers())
    args = p.parse_args(["rationalise", "synthetic:3", "--out", str(tmp_path), "--node-limit", "0"])
    with pytest.raises(InputError, match=r"--node-limit: got 0"):
        args.func(args)
    assert p.parse_args(["rationalise", "synthetic:3", "--out", "x"]).node_limit == NODE_LIMIT
