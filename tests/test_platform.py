"""Platform rationalisation: the MILP against brute force, the reductions, the greedy baseline.

The brute force below is independent of the compiler, the reductions and the MILP: it
enumerates every subset of the parts that occur in the data and, for each, every design
of every application (core x one option per subsystem) with plain Python loops.
"""

import itertools

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings, strategies as st

from formulations.platform import solve as solve_milp
from synth.errors import InputError
from synth.platform.assign import assign, serve
from synth.platform.compile import app_option_cost, compile_portfolio
from synth.platform.data import CORE_FAMILIES, FAMILIES, SUBSYSTEM_FAMILIES, SUBSYSTEMS, validate
from synth.platform.greedy import greedy
from synth.platform.prune import prune
from synth.platform.rationalise import rationalise
from synth.platform.synthetic import synthetic_portfolio

from synth.platform.data import AppFeasibility, PortfolioFeasibility

#: a portfolio small enough for brute force: 15 parts, 2^15 platforms
SIZES = {"ball_bearing": 2, "pivot_class_diameter_mm": 2, "damper_pad_class": 1, "pivot_bushing": 2,
         "endcap_spacer_class": 1, "cone_spring": 1, "main_spring": 4, "bolt": 2}


#: the same number of parts with two spacers and two cone springs (four two-part axial options): the part
#: substitution of R2 on options of several parts
SIZES_AXIAL = {**SIZES, "endcap_spacer_class": 2, "cone_spring": 2, "main_spring": 2}


def random_portfolio(n_apps: int, seed: int, sizes: dict = SIZES, nested_axial: bool = False) -> PortfolioFeasibility:
    """Random feasibility data of the interface's shape (random cores, groups and feasible sets)."""
    rng = np.random.default_rng(seed)
    parts = {f: [f"{f[:3]}{i}" for i in range(n)] for f, n in sizes.items()}
    ax = [(-1, -1)] + [(e, c) for e in range(sizes["endcap_spacer_class"]) for c in range(sizes["cone_spring"])]
    options = {"bushing": {"pivot_bushing": np.arange(sizes["pivot_bushing"])},
               "axial": {"endcap_spacer_class": np.array([e for e, _ in ax]), "cone_spring": np.array([c for _, c in ax])},
               "spring": {"main_spring": np.arange(sizes["main_spring"])}, "bolt": {"bolt": np.arange(sizes["bolt"])}}
    ocost = {s: np.round(rng.uniform(0.1, 2.0, len(next(iter(o.values())))), 3) for s, o in options.items()}
    grid = np.array(list(itertools.product(range(2), range(2), (-1, 0))))
    apps = []
    for a in range(n_apps):
        cores = grid[np.sort(rng.choice(len(grid), rng.integers(1, 5), replace=False))]
        nc = len(cores)
        group, feas, marg = {}, {}, {}
        for s in SUBSYSTEMS:
            n_opt = len(ocost[s])
            ng = int(rng.integers(1, 3))
            group[s] = rng.integers(0, ng, nc)
            feas[s] = [np.flatnonzero(rng.random(n_opt) < 0.6) for _ in range(ng)]
            if s == "axial" and nested_axial:   # a larger spacer or cone spring serves more (as on real data)
                ec = np.array(ax)
                feas[s] = [np.flatnonzero((ec[:, 0] >= rng.integers(0, 2)) & (ec[:, 1] >= rng.integers(0, 2)))
                           for _ in range(ng)]
            marg[s] = [np.round(rng.uniform(0.0, 1.0, len(f)), 3) for f in feas[s]]
        apps.append(AppFeasibility(
            app_id=f"R{a}", core_parts={"ball_bearing": cores[:, 0], "pivot_class_diameter_mm": cores[:, 1],
                                        "damper_pad_class": cores[:, 2]},
            core_cost_eur=np.round(rng.uniform(0.5, 3.0, nc), 3), core_margin=np.round(rng.uniform(0, 1, nc), 3),
            group=group, feasible=feas, option_margin=marg, volume=float(rng.integers(1, 1000)),
            option_cost_eur={"spring": np.round(rng.uniform(0.1, 2.0, sizes["main_spring"]), 3)}
            if rng.random() < 0.5 else None))
    fixed = {f: np.round(rng.uniform(100.0, 3000.0, n), 1) for f, n in sizes.items()}
    return validate(PortfolioFeasibility(apps=apps, parts=parts, part_cost_eur=fixed, options=options,
                                         option_cost_eur=ocost))


def _designs(pf, a):
    """Every feasible design of application ``a``: (set of (family, code), unit cost)."""
    out = []
    for c in range(a.n_cores):
        per_sub = []
        for s in SUBSYSTEMS:
            cost = app_option_cost(pf, a, s)
            per_sub.append([(k, cost[k]) for k in a.feasible[s][int(a.group[s][c])]])
        core = {(f, int(a.core_parts[f][c])) for f in CORE_FAMILIES if a.core_parts[f][c] >= 0}
        for combo in itertools.product(*per_sub):
            parts = set(core)
            for s, (k, _) in zip(SUBSYSTEMS, combo):
                parts |= {(f, int(pf.options[s][f][k])) for f in SUBSYSTEM_FAMILIES[s] if pf.options[s][f][k] >= 0}
            out.append((frozenset(parts), float(a.core_cost_eur[c]) + sum(x for _, x in combo)))
    return out


def brute_force(pf, objective, weights=None):
    """Optimal objective over all 2^15 platforms, every application with a design served (numpy over platforms)."""
    w = {f: 1.0 for f in FAMILIES} | (weights or {})
    bit, price = {}, []
    for f in FAMILIES:
        for c in range(len(pf.parts[f])):
            bit[(f, c)] = len(price)
            price.append(w[f] if objective == "variants" else float(pf.part_cost_eur[f][c]))
    P = np.arange(2 ** len(price), dtype=np.int64)                   # every platform as a bit mask
    total = ((P[:, None] >> np.arange(len(price))) & 1) @ np.array(price)
    for a in pf.apps:
        d = _designs(pf, a)
        if not d:
            continue                                                 # no platform serves it
        masks = np.array([sum(1 << bit[p] for p in parts) for parts, _ in d], np.int64)
        cost = np.array([c for _, c in d])
        ok = (masks[None, :] & ~P[:, None]) == 0
        best = np.where(ok, cost[None, :], np.inf).min(axis=1)
        total = total + (best * a.volume if objective == "cost" else np.where(np.isfinite(best), 0.0, np.inf))
    return float(total.min())


def _milp(pf, objective, pruned, **kw):
    w = compile_portfolio(pf, objective)
    if pruned:
        prune(w)
    inst = w.instance()
    return w, inst, solve_milp(inst, objective, time_limit=60, **kw)


@pytest.mark.parametrize("seed", [0, 1, 2, 3, 4, 5])
@pytest.mark.parametrize("objective", ["variants", "cost"])
def test_milp_equals_brute_force(seed, objective):
    pf = random_portfolio(4, seed)
    expected = brute_force(pf, objective)
    for pruned in (False, True):
        _, _, sol = _milp(pf, objective, pruned)
        assert sol.status == "optimal"
        assert sol.objective == pytest.approx(expected, rel=1e-7)


@pytest.mark.parametrize("seed", [0, 1, 2, 3, 4, 5, 6, 7])
@pytest.mark.parametrize("objective", ["variants", "cost"])
def test_milp_equals_brute_force_with_two_part_axial_options(seed, objective):
    """R2's part substitution on the (spacer, cone spring) options keeps the optimum."""
    pf = random_portfolio(5, seed, SIZES_AXIAL, nested_axial=True)
    expected = brute_force(pf, objective)
    w, _, sol = _milp(pf, objective, True)
    assert sol.status == "optimal" and sol.objective == pytest.approx(expected, rel=1e-7)
    assert _milp(pf, objective, False)[2].objective == pytest.approx(expected, rel=1e-7)


def test_part_substitution_removes_axial_parts():
    """The test above is not vacuous: R2 removes cone springs or spacers (with the other part held) there."""
    from synth.platform.prune import _substitute
    n = []
    for seed in range(8):
        w = compile_portfolio(random_portfolio(5, seed, SIZES_AXIAL, nested_axial=True), "variants")
        n.append(sum(_substitute(w, SUBSYSTEMS.index("axial"), FAMILIES.index(f), False)
                     for f in ("cone_spring", "endcap_spacer_class")))
    assert sum(x > 0 for x in n) >= 4


@settings(max_examples=12, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(seed=st.integers(0, 10_000), n=st.integers(1, 6), objective=st.sampled_from(["variants", "cost"]))
def test_milp_equals_brute_force_property(seed, n, objective):
    pf = random_portfolio(n, seed)
    _, _, sol = _milp(pf, objective, True)
    assert sol.objective == pytest.approx(brute_force(pf, objective), rel=1e-7)


@pytest.mark.parametrize("seed", [5, 6, 7])
@pytest.mark.parametrize("objective", ["variants", "cost"])
def test_pruning_keeps_the_optimum(seed, objective):
    pf = synthetic_portfolio(15, seed=seed)
    w_raw, _, raw = _milp(pf, objective, False)
    w, _, red = _milp(pf, objective, True)
    assert raw.status == red.status == "optimal"
    assert red.objective == pytest.approx(raw.objective, rel=1e-7)
    assert w.sizes()["row_options"] < w_raw.sizes()["row_options"]  # it does reduce


@pytest.mark.parametrize("seed", [0, 1, 2])
@pytest.mark.parametrize("objective", ["variants", "cost"])
def test_greedy_is_never_better_and_serves_all(seed, objective):
    pf = synthetic_portfolio(12, seed=seed)
    for pruned in (False, True):
        w = compile_portfolio(pf, objective)
        if pruned:
            prune(w)
        inst = w.instance()
        y = greedy(inst, objective)
        assert serve(inst, y)[0].all()
        sol = solve_milp(inst, objective, time_limit=60)
        from synth.platform.assign import objective_value
        assert objective_value(inst, y, objective) >= sol.objective - 1e-6 * max(1.0, abs(sol.objective))


@pytest.mark.parametrize("objective", ["variants", "cost"])
def test_assignment_uses_only_platform_parts_and_is_feasible(objective):
    pf = synthetic_portfolio(25, seed=11)
    r = rationalise(pf, objective, time_limit=60)
    assert r.status == "optimal"
    servable = [x["feasible"] for x in r.per_app_optima]
    assert [x["feasible"] for x in r.records] == servable
    assert r.n_parts <= r.n_parts_union_optima
    for a, rec in zip(pf.apps, r.records):
        if not rec["feasible"]:
            assert rec["reason"]
            continue
        c = rec["core"]
        for f in CORE_FAMILIES:
            code = int(a.core_parts[f][c])
            assert code < 0 or code in r.platform[f]
        for s in SUBSYSTEMS:
            k = rec["options"][s]
            assert k in a.feasible[s][int(a.group[s][c])]  # feasible in the data for the core's group
            for f in SUBSYSTEM_FAMILIES[s]:
                code = int(pf.options[s][f][k])
                assert code < 0 or code in r.platform[f]
        assert rec["margin"] >= 0
    if objective == "variants":
        assert r.objective_value == pytest.approx(r.n_parts)  # unit weights: the objective is the part count
    # the price of standardisation is not negative: no application is cheaper than its own optimum
    for rec, opt in zip(r.records, r.per_app_optima):
        if rec["feasible"]:
            assert rec["unit_cost_eur"] >= opt["unit_cost_eur"] - 1e-9


def test_serve_and_assign_agree():
    pf = synthetic_portfolio(10, seed=3)
    w = compile_portfolio(pf, "cost")
    inst = w.instance()
    y = greedy(inst, "cost")
    served, cost, _ = serve(inst, y)
    from synth.platform.assign import platform_from_y
    recs = assign(pf, platform_from_y(w, y))
    got = np.array([recs[i]["unit_cost_eur"] * pf.apps[i].volume for i in w.app_index])
    np.testing.assert_allclose(got, cost, rtol=1e-9)
    assert served.all()


def test_max_variants_caps_a_family_and_reports_the_unserved():
    pf = synthetic_portfolio(20, seed=2)
    free = rationalise(pf, "variants", time_limit=60)
    n_b = len(free.platform["ball_bearing"])
    assert n_b >= 2
    capped = rationalise(pf, "variants", time_limit=60, max_variants={"ball_bearing": 1})
    assert len(capped.platform["ball_bearing"]) == 1
    lost = [x for x, y in zip(capped.records, free.records) if y["feasible"] and not x["feasible"]]
    for x in lost:
        assert "max-variants" in x["reason"]
    served = sum(x["feasible"] for x in capped.records)
    assert served + len(lost) == sum(x["feasible"] for x in free.records)


def test_weights_steer_the_platform():
    pf = synthetic_portfolio(15, seed=4)
    plain = rationalise(pf, "variants", time_limit=60)
    heavy = rationalise(pf, "variants", time_limit=60, weights={"main_spring": 10.0})
    assert len(heavy.platform["main_spring"]) <= len(plain.platform["main_spring"])
    assert heavy.n_parts >= plain.n_parts


def test_bad_options_are_named():
    pf = synthetic_portfolio(2, seed=0)
    with pytest.raises(InputError, match="objective"):
        rationalise(pf, "cheapest")
    with pytest.raises(InputError, match="--max-variants family"):
        rationalise(pf, max_variants={"bearing": 2})
    with pytest.raises(InputError, match="--time-limit"):
        rationalise(pf, time_limit=0)


def test_validate_names_the_broken_field():
    pf = synthetic_portfolio(2, seed=0)
    pf.apps[0].group["spring"] = pf.apps[0].group["spring"][:-1]
    with pytest.raises(InputError, match=r"APP-0000: group\[spring\]"):
        validate(pf)


def test_unservable_application_says_why():
    pf = synthetic_portfolio(30, seed=0)
    r = rationalise(pf, "variants", time_limit=60)
    bad = [x for x in r.records if not x["feasible"]]
    assert bad and all(x["reason"] for x in bad)
    assert any("no feasible core" in x["reason"] or "no core passes" in x["reason"] for x in bad)
    assert any("missing: " in x["reason"] for x in bad)


def test_precompiled_compile_equals_a_fresh_one():
    """One precompile serves every floor and objective: compiling from it equals compiling afresh (a floor
    must not edit the shared arrays; the reductions edit the Work in place, so prune each before the next)."""
    from synth.platform.compile import precompile
    pf = synthetic_portfolio(40, seed=5)
    pre = precompile(pf)
    margins = np.concatenate([a.core_margin for a in pf.apps])
    floors = [None, 0.0, *np.quantile(margins[margins > 0], [0.25, 0.5, 0.9])]
    sizes = []
    for floor in floors:
        for objective in ("variants", "cost"):
            a = compile_portfolio(pf, objective, min_margin=floor)
            b = compile_portfolio(pf, objective, min_margin=floor, pre=pre)
            prune(compile_portfolio(pf, objective, min_margin=floor, pre=pre))
            assert a.unservable == b.unservable
            ia, ib = a.instance(), b.instance()
            for k, v in vars(ia).items():
                assert np.array_equal(v, vars(ib)[k]) if isinstance(v, np.ndarray) else v == vars(ib)[k], (floor, k)
        sizes.append(a.sizes()["row_options"])
    assert sizes[2] > 0 and sizes[-1] < sizes[0]     # the floors keep some options and remove others


@pytest.mark.parametrize("kind", ["margin", "cost"])
def test_tradeoff_rounds_equal_fresh_rationalise(kind):
    from synth.platform.rationalise import tradeoff
    pf = synthetic_portfolio(40 if kind == "margin" else 15, seed=3)
    shared = tradeoff(pf, kind, points=3, time_limit=30)
    fresh = tradeoff(pf, kind, points=3, time_limit=30, share=False)   # each round compiled afresh, in full
    assert len(shared) >= 2 and shared == fresh


def _highs_lp(h) -> dict:
    """The model a ``highspy.Highs`` holds, as arrays (matrix, bounds, costs, integrality, sense)."""
    lp = h.getLp()
    a = lp.a_matrix_
    return {"start": np.array(a.start_), "index": np.array(a.index_), "value": np.array(a.value_),
            "format": str(a.format_), "cost": np.array(lp.col_cost_), "col_lower": np.array(lp.col_lower_),
            "col_upper": np.array(lp.col_upper_), "row_lower": np.array(lp.row_lower_),
            "row_upper": np.array(lp.row_upper_), "integrality": [int(x) for x in lp.integrality_],
            "sense": str(lp.sense_), "offset": lp.offset_}


@pytest.mark.parametrize("objective", ["variants", "cost"])
@pytest.mark.parametrize("kw", [{}, {"allow_unserved": True, "budget": 7.5,
                                     "max_variants": {"main_spring": 2, "bolt": 1}}])
def test_array_build_hands_highs_the_pyomo_model(objective, kw):
    """``synthetic:40``: HiGHS receives from :func:`build_arrays` exactly the model appsi translates from
    :func:`build_model` (every column, row, coefficient, bound, cost and integrality in the same place), and the two
    builds' solves return the same platform, objective, bound and unserved applications (the variants objective:
    the others take HiGHS 10-60 s a solve, and the same model is the same solve)."""
    from pyomo.contrib.appsi.solvers import Highs
    from formulations.platform import build_arrays, build_model, highs_model
    w = compile_portfolio(synthetic_portfolio(40, seed=0), objective)
    prune(w, allow_unserved=bool(kw))
    inst = w.instance()
    m = build_model(inst, objective, **kw)
    ref = Highs()
    ref.set_instance(m)
    arr = build_arrays(inst, objective, **kw)
    want, got = _highs_lp(ref._solver_model), _highs_lp(highs_model(arr))
    assert len(got["cost"]) > 1000 and len(got["index"]) > 3000
    for k in want:
        assert np.array_equal(got[k], want[k]) if isinstance(want[k], np.ndarray) else got[k] == want[k], k
    assert arr.size == m.size
    if kw or objective != "variants":
        return
    a, b = solve_milp(inst, objective, time_limit=60, **kw), solve_milp(inst, objective, time_limit=60, model=m, **kw)
    assert a.status == b.status == "optimal" and (a.objective, a.bound, a.size) == (b.objective, b.bound, b.size)
    assert np.array_equal(a.y, b.y) and a.y.any()
    assert a.unserved is None and b.unserved is None


def test_compiled_option_indices_are_int32_and_the_instance_the_same():
    """Issue 36's memory: the per-option arrays the compilation keeps (option indices, group numbers, pattern ids)
    are int32; the packed instance, before and after pruning, holds the same numbers as int64."""
    from synth.platform.compile import flat_groups, precompile
    pf = synthetic_portfolio(8, seed=3)
    pre = precompile(pf)
    for s in SUBSYSTEMS:
        idx, mar, cost, grp, gptr = flat_groups(pf, s)
        assert idx.dtype == grp.dtype == np.int32 and gptr.dtype == np.int64
        assert idx.tolist() == [int(k) for a in pf.apps for x in a.feasible[s] for k in x]
        assert pre.options[s][0].dtype == np.int32
    w = prune(compile_portfolio(pf, "cost"))
    inst = w.instance()
    assert inst.row_opt_pattern.dtype == inst.row_core.dtype == np.int64
