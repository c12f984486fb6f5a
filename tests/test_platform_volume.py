"""Platform parts priced at the summed volume of the applications they serve (``synth.platform.volume``).

A hand-made portfolio of two applications of 600 pieces a year: application 1 may use bearing A or B, application
2 only A. Bearing A costs 1.00 EUR a piece below 1,000 pieces a year and 0.80 from 1,000; B costs 0.95 at any
volume. Each application alone buys A at 1.00, so the cheapest platform priced at each application's own volume
(the volume-blind one) gives application 1 bearing B (0.95); priced at the pooled volume, both on A reach the
1,000-piece break: 1,200 x 0.80 = 960 EUR a year against 600 x 1.00 + 600 x 0.95 = 1,170, and A's volume saving is
600 x 1.00 + 600 x 1.00 - 960 = 240 EUR a year (20 % of 1,200).
"""

import numpy as np
import pytest

from formulations.platform import solve as solve_milp
from synth.platform.compile import compile_portfolio
from synth.platform.data import FAMILIES, AppFeasibility, PortfolioFeasibility, validate
from synth.platform.rationalise import rationalise
from synth.platform.volume import PriceCurves, pool_prices, volume_saving
from tests.test_platform import _designs

SUBS = {"bushing": ("pivot_bushing",), "axial": ("endcap_spacer_class", "cone_spring"), "spring": ("main_spring",),
        "bolt": ("bolt",)}


def _portfolio(fixed_b: float = 0.0) -> PortfolioFeasibility:
    parts = {f: [f"{f}0"] for f in FAMILIES}
    parts["ball_bearing"] = ["A", "B"]
    options = {"bushing": {"pivot_bushing": np.array([0])},
               "axial": {"endcap_spacer_class": np.array([-1]), "cone_spring": np.array([-1])},
               "spring": {"main_spring": np.array([0])}, "bolt": {"bolt": np.array([0])}}

    def app(name, bearings):
        bearings = np.array(bearings)
        n = len(bearings)
        zero = np.zeros(n, np.int64)
        return AppFeasibility(
            app_id=name, core_parts={"ball_bearing": bearings, "pivot_class_diameter_mm": zero,
                                     "damper_pad_class": zero - 1},
            core_cost_eur=np.where(bearings == 0, 1.00, 0.95), core_margin=np.full(n, 0.1),
            group={s: zero for s in SUBS}, feasible={s: [np.array([0])] for s in SUBS},
            option_margin={s: [np.array([0.1])] for s in SUBS}, volume=600.0)
    fixed = {f: np.zeros(len(parts[f])) for f in FAMILIES}
    fixed["ball_bearing"][1] = fixed_b
    return validate(PortfolioFeasibility(apps=[app("one", [0, 1]), app("two", [0])], parts=parts,
                                         part_cost_eur=fixed, options=options,
                                         option_cost_eur={s: np.zeros(1) for s in SUBS}, volumes_given=True))


CURVES = PriceCurves(np.array([1.0, 1000.0]), {"ball_bearing": np.array([[1.00, 0.80], [0.95, 0.95]])},
                     included={"ball_bearing": np.array([1.00, 0.95])})


@pytest.mark.parametrize("build", ["arrays", "pyomo"])
def test_a_common_part_crossing_a_break_saves_the_hand_calculation(build):
    r = rationalise(_portfolio(), "cost", curves=CURVES, build=build, time_limit=30)
    assert r.status == "optimal" and r.platform["ball_bearing"] == {0}
    assert r.objective_value == pytest.approx(960.0)
    vs = r.price["volume"]
    assert vs["saving_eur"] == pytest.approx(240.0) and vs["saving_pct"] == pytest.approx(0.20)
    assert vs["own_eur"] == pytest.approx(1200.0) and vs["pooled_eur"] == pytest.approx(960.0)
    a = next(p for p in vs["per_part"] if p["part"] == "A")
    assert (a["applications"], a["pooled_volume"]) == (2, 1200.0)


def test_a_platform_with_volumes_saves_more_than_one_without():
    """Priced at each application's own volume the MILP keeps B for application 1 (1,170 EUR a year, no part
    pooled across a break); priced at the pooled volume it drops B (960): more saving, lower total cost."""
    pf = _portfolio()
    blind = rationalise(pf, "cost", curves=None, time_limit=30)
    pooled = rationalise(pf, "cost", curves=CURVES, time_limit=30)
    assert blind.platform["ball_bearing"] == {0, 1} and blind.objective_value == pytest.approx(1195.0 - 25.0)
    s_blind = volume_saving(pf, blind.records, CURVES)
    s_pooled = volume_saving(pf, pooled.records, CURVES)
    assert s_blind["saving_eur"] == pytest.approx(0.0) and s_pooled["saving_eur"] == pytest.approx(240.0)
    assert s_pooled["pooled_eur"] < s_blind["pooled_eur"]


def test_a_break_no_volume_reaches_is_left_out_and_the_pooled_price_holds():
    """At 400 pieces each (800 together) the 1,000 break is out of reach: no break variable, each at 1.00 or 0.95;
    a fixed cost on B above the 0.05 x 400 it saves makes A the platform."""
    pf = _portfolio(fixed_b=50.0)
    for a in pf.apps:
        a.volume = 400.0
    w = compile_portfolio(pf, "cost")
    assert pool_prices(w, CURVES) == 0
    sol = solve_milp(w.instance(), "cost", time_limit=30)
    assert sol.status == "optimal" and sol.objective == pytest.approx(800.0)


def _random_curves(pf, seed: int) -> PriceCurves:
    """Bearings and bolts whose unit price falls at 500 and 1,000 pieces a year (random steps), the price the
    feasibility data hold being the one-piece price plus a random offset (what pool_prices replaces)."""
    rng = np.random.default_rng(seed)
    prices, inc = {}, {}
    for f in ("ball_bearing", "bolt"):
        n = len(pf.parts[f])
        p0 = rng.uniform(0.5, 2.0, n)
        prices[f] = np.stack([p0, p0 - rng.uniform(0.0, 0.4, n), p0 - rng.uniform(0.4, 0.5, n)], axis=1)
        inc[f] = p0 + rng.uniform(-0.2, 0.2, n)
    return PriceCurves(np.array([1.0, 500.0, 1000.0]), prices, inc)


def _pooled_brute_force(pf, curves) -> float:
    """The cheapest (fixed costs of the parts used + every application's design at the pooled prices) over every
    combination of the applications' designs: plain enumeration, independent of the compiler and the MILP."""
    import itertools
    per = [(a, _designs(pf, a)) for a in pf.apps]
    per = [(a, d) for a, d in per if d]
    best = np.inf
    for combo in itertools.product(*[d for _, d in per]):
        used = frozenset().union(*[parts for parts, _ in combo])
        vol = {p: sum(a.volume for (a, _), (parts, _) in zip(per, combo) if p in parts) for p in used}
        total = sum(float(pf.part_cost_eur[f][c]) for f, c in used)
        for (a, _), (parts, cost) in zip(per, combo):
            adj = sum(float(curves.price(f, [c], [vol[(f, c)]])[0] - curves.included[f][c])
                      for f, c in parts if f in curves.prices)
            total += a.volume * (cost + adj)
        best = min(best, total)
    return best


@pytest.mark.parametrize("seed", [3, 4, 7, 8])
def test_pooled_milp_equals_brute_force(seed):
    """Two random applications (volumes 1-999, so 500 and 1,000 are reachable only together or alone): the MILP
    with the volume breaks finds the cheapest combination of designs, both builds."""
    from tests.test_platform import random_portfolio
    pf = random_portfolio(2, seed)
    rng = np.random.default_rng(seed)
    for a in pf.apps:
        a.volume = float(rng.integers(300, 900))
    assert all(_designs(pf, a) for a in pf.apps)
    w = compile_portfolio(pf, "cost")
    curves = _random_curves(pf, seed)
    assert pool_prices(w, curves) > 0                  # breaks left to the MILP
    curves = _random_curves(pf, seed)
    want = _pooled_brute_force(pf, curves)
    for build in ("arrays", "pyomo"):
        r = rationalise(pf, "cost", curves=curves, build=build, time_limit=30, verify=False)
        assert r.status == "optimal" and r.objective_value == pytest.approx(want, rel=1e-9, abs=1e-6), build
        assert r.greedy_value >= want - 1e-6            # the greedy designs with the breaks they reach: no better
        ok = [x for x in r.records if x["feasible"]]   # the records are the MILP's designs: they cost its objective
        vol = {a.app_id: a.volume for a in pf.apps}
        pooled = {}
        for x in ok:
            for f, c in x["codes"].items():
                if c >= 0:
                    pooled[(f, c)] = pooled.get((f, c), 0.0) + vol[x["app_id"]]
        total = sum(float(pf.part_cost_eur[f][c]) for f, c in pooled)
        for x in ok:
            total += vol[x["app_id"]] * (x["unit_cost_eur"] + sum(
                float(curves.price(f, [c], [pooled[(f, c)]])[0] - curves.included[f][c])
                for f, c in x["codes"].items() if c >= 0 and f in curves.prices))
        assert total == pytest.approx(want, rel=1e-9, abs=1e-6)


def test_array_build_hands_highs_the_pyomo_model_with_breaks():
    """With volume breaks the two builds still give HiGHS the same model, column for column."""
    from pyomo.contrib.appsi.solvers import Highs
    from formulations.platform import build_arrays, build_model, highs_model
    from synth.platform.prune import prune
    from tests.test_platform import _highs_lp, random_portfolio
    pf = random_portfolio(6, 3)
    w = compile_portfolio(pf, "cost")
    assert pool_prices(w, _random_curves(pf, 3)) > 0
    prune(w)
    inst = w.instance()
    m = build_model(inst, "cost")
    ref = Highs()
    ref.set_instance(m)
    arr = build_arrays(inst, "cost")
    want, got = _highs_lp(ref._solver_model), _highs_lp(highs_model(arr))
    for k in want:
        assert np.array_equal(got[k], want[k]) if isinstance(want[k], np.ndarray) else got[k] == want[k], k
    assert arr.size == m.size


def test_the_outputs_show_the_volume_saving_beside_the_parts():
    from synth.platform.outputs import platform_table, summary_markdown
    pf = _portfolio()
    r = rationalise(pf, "cost", curves=CURVES, time_limit=30)
    t = platform_table(pf, r)
    a = t[(t.family == "ball_bearing") & (t.part == "A")].iloc[0]
    assert (a.applications, a.annual_volume, a.volume_saving_eur) == (2, 1200.0, pytest.approx(240.0))
    text = summary_markdown(pf, r)
    assert "volume saving 240 EUR/year (20.00%)" in text and "| ball_bearing | A | 2 | 1,200 | 1,200 | 960 | 240 |" \
        in text
    pf.volumes_given = False                           # no volume column: no pooled volume, and it says so
    blind = rationalise(pf, "cost", time_limit=30)
    assert blind.price["volume"] is None and list(platform_table(pf, blind).columns) == ["family", "part",
                                                                                         "applications"]
    assert "No annual volumes" in summary_markdown(pf, blind)
