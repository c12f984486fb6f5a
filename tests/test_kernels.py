"""Compiled main-spring kernels (synth.kernels.main_spring) against the registry's spring group.

Sources: the reference is the registry path itself, synth.design.evaluate.spring (spring_values of thesis step 9,
eq. (64)-(93), and the registry's margin()); the keys come from generated applications (every optional input
present and absent) through the one evaluator's core group (realistic) and from hypothesis draws across the input
schema's bounds (extremes); (b)-(d) are checked against brute force over the full margin table.
"""

import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from synth.data.generated_applications import generate
from synth.design import evaluate
from synth.design.applications import Applications
from synth.design.constraints import FEAS_TOL, REGISTRY
from synth.design.space import core_rows, space
from synth.errors import InputError
from synth.kernels import main_spring, spring_tables
from synth.model import torsion_spring as s9

ROOT = Path(__file__).resolve().parents[1]
SETTINGS = evaluate.Settings(fidelity="screening")


# ------------------------------------------------------------------ fixtures: realistic keys and every catalog spring


def _evaluator_keys(inputs):
    """Every core of every application as the evaluator builds it: the applications, the spring-key dict, the
    application of each row."""
    sp = space()
    apps = Applications.of(inputs)
    per = [core_rows(sp, d) for d in inputs]
    a = np.concatenate([np.full(len(c), i) for i, c in enumerate(per)]).astype(np.int64)
    c = np.concatenate(per)
    with np.errstate(all="ignore"):
        cg = evaluate.core(apps, a, sp.rows("core", c), SETTINGS)
    return apps, evaluate.spring_keys(cg, np.arange(len(a))), cg


@pytest.fixture(scope="module")
def space_springs():
    """The design space's spring options (every material x wire x mean body diameter the space holds)."""
    return main_spring.options_of_space()


@pytest.fixture(scope="module")
def realistic():
    """600 spring keys drawn (seeded) from the cores of 60 generated applications (optional inputs present and
    absent: travels, torque tolerance, durability test), with the evaluator's inputs."""
    rng = np.random.default_rng(13)
    apps, keys, _ = _evaluator_keys(generate(60, seed=13, vary=True))
    stack = np.stack([keys["app"].astype(float)] + [keys[k] for k in (
        "spring_torque_nominal_nm", "spring_housing_height_mm", "spring_housing_outer_diameter_mm",
        "spring_housing_inner_diameter_mm")], axis=1)
    _, first = np.unique(stack, axis=0, return_index=True)
    pick = np.concatenate([rng.choice(first[keys["app"][first] == i], size=10, replace=False) for i in range(60)])
    assert len(pick) == 600
    return apps, keys, pick, main_spring.keys_of_rows(apps, keys, pick)


def _assert_close(a, ref):
    """Margins equal to 1e-9 relative (absolute below 1), the same infinities and NaNs, the same verdicts."""
    assert a.shape == ref.shape
    same_special = (np.isnan(a) == np.isnan(ref)) & (np.isinf(a) == np.isinf(ref))
    assert same_special.all()
    fin = np.isfinite(ref)
    assert (a[~fin & ~np.isnan(ref)] == ref[~fin & ~np.isnan(ref)]).all()
    err = np.abs(a[fin] - ref[fin]) / np.maximum(1.0, np.abs(ref[fin]))
    assert err.size == 0 or err.max() <= 1e-9
    with np.errstate(invalid="ignore"):
        assert ((a >= -FEAS_TOL) == (ref >= -FEAS_TOL)).all()


# ------------------------------------------------------------------ (a) margins


def test_margin_names_are_the_registrys_spring_group():
    ids = [c.id for c in REGISTRY.values() if c.group == "spring" and not c.advisory]
    assert list(main_spring.MARGIN_NAMES) == ids


def test_reference_margins_are_the_registry_spring_group(realistic, space_springs):
    # the numpy twin is the registry path: evaluate.spring on (key, option) rows gives the same margins, bit for bit
    apps, keys, pick, kk = realistic
    rng = np.random.default_rng(2)
    ki = rng.choice(len(pick), 40, replace=False)
    oi = rng.choice(len(space_springs), 300, replace=False)
    ref = main_spring.reference_margins(kk, space_springs, ki, oi)
    rows_k = np.repeat(pick[ki], len(oi))
    rows_o = np.tile(oi, len(ki))
    with np.errstate(all="ignore"):
        g = evaluate.spring(apps, keys, rows_k, space().rows("spring", rows_o), SETTINGS)
    for m, name in enumerate(main_spring.MARGIN_NAMES):
        assert np.array_equal(ref[:, :, m].ravel(), g.margins[name]), name


def test_margins_equal_the_registry_on_600_generated_keys(realistic, space_springs):
    _, _, _, keys = realistic
    opts = space_springs
    assert len(opts) >= 10000
    rng = np.random.default_rng(5)
    feasible = 0
    for lo in range(0, len(keys), 100):  # 100 keys x every option, then 2,000 drawn options for the others
        sub = keys.take(np.arange(lo, min(lo + 100, len(keys))))
        o = opts if lo == 0 else opts.take(np.sort(rng.choice(len(opts), 2000, replace=False)))
        a = main_spring.margins(sub, o)
        ref = main_spring.reference_margins(sub, o)
        _assert_close(a, ref)
        assert (a == ref).mean() > 0.999  # the same operations in the same order: bit-for-bit in practice
        feasible += int(np.all(ref >= -FEAS_TOL, axis=2).sum())
    assert feasible > 0


def test_fatigue_is_not_verified_without_the_durability_test(realistic, space_springs):
    # registry: spring_fatigue needs the durability test; not verified -> +inf, never infeasible
    _, _, _, keys = realistic
    off = ~keys.raw["fatigue_verified"]
    assert off.any() and (~off).any()  # generate(vary=True) leaves the durability test out of some applications
    m = main_spring.margins(keys.take(np.flatnonzero(off)[:20]), space_springs.take(np.arange(0, 11000, 50)))
    assert np.isposinf(m[:, :, main_spring.MARGIN_NAMES.index("spring_fatigue")]).all()


def test_margins_reproduce_a_hand_calculated_pair():
    # case 3 pair of the module doctest at the registry's upper tolerance:
    # T_inst = 1.56 * 1.08 + 0.0164 * 28.6 = 2.15384 N m, Z = pi 2.3^3 / 32 = 1.194492 mm^3,
    # c = 44 / 2.3 = 19.13043, k_f = (4c^2 - c - 1) / (4c(c - 1)) = 1.040646 -> sigma_inst = 1876.43 MPa
    opts = main_spring.spring_options(E_mpa=206000, Rm_mpa=2004, sigma_y_mpa=1763.5, sigma_A0_mpa=701.4, b_mm=2.3, h_mm=2.3,
                            round_wire=True, mbd_mm=44.0)
    keys = main_spring.spring_keys(spring_torque_nominal_nm=1.56, housing_height_mm=8.8, housing_outer_diameter_mm=48.0,
                         housing_inner_diameter_mm=30.0, stiffness_nm_per_deg=0.0164, torque_tolerance_pct=8,
                         theta_pp_deg=16, dtheta_inst_nom_deg=28.6)
    m = dict(zip(main_spring.MARGIN_NAMES, main_spring.margins(keys, opts)[0, 0]))
    assert 1763.5 * (1 - m["spring_yield"]) == pytest.approx(1876.43, abs=0.01)
    # index margins: (19.1304 - 4) / 4 and (20 - 19.1304) / 20; a supplied material: section margin 0
    assert m["spring_index_min"] == pytest.approx(3.78261, abs=1e-5)
    assert m["spring_index_max"] == pytest.approx(0.043478, abs=1e-6)
    assert m["spring_material_section"] == 0.0


def test_a_material_not_supplied_in_the_section_is_never_feasible():
    kw = dict(E_mpa=206000, Rm_mpa=2004, sigma_y_mpa=1763.5, sigma_A0_mpa=701.4, b_mm=2.3, h_mm=2.3, round_wire=True,
              mbd_mm=30.0)
    opts = main_spring.spring_options(**kw, supplied_in_section=np.array([True, False]))
    keys = main_spring.spring_keys(spring_torque_nominal_nm=0.3, housing_height_mm=20.0, housing_outer_diameter_mm=40.0,
                         housing_inner_diameter_mm=20.0, stiffness_nm_per_deg=0.01, torque_tolerance_pct=5,
                         theta_pp_deg=10)
    m = main_spring.margins(keys, opts)[0]
    assert m[1, main_spring.MARGIN_NAMES.index("spring_material_section")] == -1.0
    assert (m[0] >= 0).all()  # the same spring, supplied: feasible
    assert main_spring.first_feasible(keys, opts, [1, 0]).index.tolist() == [0]
    assert main_spring.max_min_margin(keys, opts, [1]).value.tolist() == [-1.0]


_pos = dict(allow_nan=False, allow_infinity=False)


@st.composite
def _extreme_keys(draw, n=6):
    """Keys across the schema's bounds and beyond the realistic range: zero torque, huge housings, tiny stiffness."""
    def arr(lo, hi, special=()):
        vals = st.one_of(st.floats(lo, hi, **_pos), st.sampled_from(list(special) or [lo, hi]))
        return np.array(draw(st.lists(vals, min_size=n, max_size=n)))
    outer = arr(1.0, 5000.0, (1.0, 60.0, 5000.0))
    return main_spring.spring_keys(
        spring_torque_nominal_nm=arr(0.0, 100.0, (0.0, 1e-6, 100.0)),
        housing_height_mm=arr(0.1, 1000.0, (0.1, 9.0, 1000.0)),
        housing_outer_diameter_mm=outer,
        housing_inner_diameter_mm=outer * arr(0.0, 1.2, (0.0, 0.5, 1.0)),
        stiffness_nm_per_deg=arr(1e-9, 10.0, (1e-9, 1e-6, 0.02, 10.0)),
        torque_tolerance_pct=arr(0.0, 50.0), theta_pp_deg=arr(0.0, 90.0),
        dtheta_inst_nom_deg=arr(0.0, 180.0), dtheta_nom_free_arm_deg=arr(0.0, 180.0),
        fatigue_verified=np.array(draw(st.lists(st.booleans(), min_size=n, max_size=n))))


@settings(max_examples=50, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(keys=_extreme_keys(), seed=st.integers(0, 2**31 - 1), mbd=st.sampled_from([1.0, 5.0, 44.0, 500.0]))
def test_margins_equal_reference_at_the_extremes(space_springs, keys, seed, mbd):
    rng = np.random.default_rng(seed)
    opts = space_springs.take(rng.choice(len(space_springs), size=40, replace=False))
    raw = {k: v[:3] for k, v in opts.raw.items()}
    raw["main_spring_mean_body_diameter_mm"] = np.full(3, mbd)  # an extreme diameter
    odd = spring_tables._options(raw)
    for o in (opts, odd):
        ref = main_spring.reference_margins(keys, o)
        _assert_close(main_spring.margins(keys, o), ref)
        ok, mins = _brute(ref, FEAS_TOL)
        first = np.where(ok.any(axis=1), np.argmax(ok, axis=1), -1)
        assert np.array_equal(main_spring.first_feasible(keys, o).index, first)
        assert np.array_equal(main_spring.max_min_margin(keys, o).index, np.argmax(mins, axis=1))


@pytest.mark.parametrize("tol", [0.0, FEAS_TOL])
def test_yield_threshold_decides_the_yield_check_exactly(realistic, space_springs, tol):
    # the scan of (b) replaces the yield check by T_inst <= threshold: same verdict as the reference on every pair
    keys = realistic[3].take(np.arange(0, 600, 6))
    opts = space_springs.take(np.arange(0, len(space_springs), 3))
    t_max = main_spring.yield_thresholds(opts, tol)
    ref = main_spring.reference_margins(keys, opts)[:, :, 0]
    by_threshold = keys.derived["t_inst"][:, None] <= t_max[None, :]
    assert np.array_equal(by_threshold, ref >= -tol)
    assert 0.05 < by_threshold.mean() < 0.95
    # and it is the largest such torque: one double more fails
    d = opts.derived
    up = np.nextafter(t_max, np.inf)
    assert ((d["sy"] - d["kf"] * t_max * 1000.0 / d["z"]) / d["sy_scale"] >= -tol).all()
    assert not ((d["sy"] - d["kf"] * up * 1000.0 / d["z"]) / d["sy_scale"] >= -tol).any()


# ------------------------------------------------------------------ (b)-(d) against brute force


def _brute(ref, tol):
    ok = np.all(ref >= -tol, axis=2)
    mins = np.min(np.where(np.isnan(ref), -np.inf, ref), axis=2)
    return ok, mins


@pytest.fixture(scope="module")
def scan_case(realistic, space_springs):
    """300 keys in 3 groups (applications), each group its own seeded candidate list of 1,500 options."""
    rng = np.random.default_rng(7)
    keys = realistic[3].take(rng.choice(600, size=300, replace=False))
    opts = space_springs.take(np.sort(rng.choice(len(space_springs), size=3000, replace=False)))
    lists = [rng.permutation(3000)[:1500] for _ in range(3)]
    key_group = rng.integers(0, 3, size=len(keys))
    ref = main_spring.reference_margins(keys, opts)
    return keys, opts, lists, key_group, ref


@pytest.mark.parametrize("engine", ["numba", "numpy"])
@pytest.mark.parametrize("tol", [0.0, FEAS_TOL])
def test_first_feasible_is_the_first_feasible_option_of_each_list(scan_case, engine, tol):
    keys, opts, lists, kg, ref = scan_case
    ok, _ = _brute(ref, tol)
    r = main_spring.first_feasible(keys, opts, lists, key_group=kg, tol=tol, engine=engine)
    found = 0
    for i in range(len(keys)):
        lst = lists[kg[i]]
        hits = np.flatnonzero(ok[i, lst])
        assert r.index[i] == (lst[hits[0]] if len(hits) else -1)
        if engine == "numba":  # the kernel examines exactly the options up to the hit
            assert r.visited[i] == (hits[0] + 1 if len(hits) else len(lst))
        found += bool(len(hits))
    assert 0 < found < len(keys)  # keys with and without a feasible option


@pytest.mark.parametrize("engine", ["numba", "numpy"])
@pytest.mark.parametrize("per_list", [False, True])
def test_first_feasible_stops_at_the_score_limit(scan_case, engine, per_list):
    keys, opts, lists, kg, ref = scan_case
    ok, _ = _brute(ref, FEAS_TOL)
    rng = np.random.default_rng(3)
    if per_list:  # each list its own scores (an application's spring cost follows its stiffness)
        scores = [np.sort(rng.uniform(0, 10, len(lst))) for lst in lists]
        order, score = lists, scores
    else:
        s = rng.uniform(0, 10, len(opts))
        order = [lst[np.argsort(s[lst], kind="stable")] for lst in lists]  # score order, as the bulk engine scans
        score, scores = s, [s[lst] for lst in order]
    limit = np.random.default_rng(4).uniform(0, 10, len(keys))
    r = main_spring.first_feasible(keys, opts, order, key_group=kg, score=score, score_limit=limit, engine=engine)
    for i in range(len(keys)):
        lst = order[kg[i]][scores[kg[i]] <= limit[i]]
        hits = np.flatnonzero(ok[i, lst])
        assert r.index[i] == (lst[hits[0]] if len(hits) else -1)


@pytest.mark.parametrize("engine", ["numba", "numpy"])
def test_max_min_margin_is_the_argmax_of_the_smallest_margin(scan_case, engine):
    keys, opts, lists, kg, ref = scan_case
    _, mins = _brute(ref, 0.0)
    r = main_spring.max_min_margin(keys, opts, lists, key_group=kg, engine=engine)
    for i in range(len(keys)):
        lst = lists[kg[i]]
        best = int(np.argmax(mins[i, lst]))  # first of the ties in list order
        assert r.index[i] == lst[best] and r.value[i] == mins[i, lst[best]]
    assert (r.visited < np.array([len(lists[g]) for g in kg])).any()  # the bound skipped options


@pytest.mark.parametrize("engine", ["numba", "numpy"])
def test_max_min_margin_with_a_cap_is_exact_below_it(scan_case, engine):
    keys, opts, lists, kg, ref = scan_case
    _, mins = _brute(ref, 0.0)
    true = np.array([mins[i, lists[kg[i]]].max() for i in range(len(keys))])
    cap = np.where(np.arange(len(keys)) % 2 == 0, -0.05, 0.0)
    r = main_spring.max_min_margin(keys, opts, lists, key_group=kg, cap=cap, engine=engine)
    assert np.array_equal(np.minimum(r.value, cap), np.minimum(true, cap))
    assert (mins[np.arange(len(keys)), r.index] == r.value).all()


@pytest.mark.parametrize("engine", ["numba", "numpy"])
def test_near_figures_above_a_floor_are_the_tables_where_they_reach_it(scan_case, engine):
    # the bulk's nearest design reads the near figures of the springs that reach its smallest margin: those pairs'
    # figures exactly as near_figures of the whole table's rows, every other pair known to be below the floor; the
    # compiled engine skips most pairs' physics
    from synth.design.combine import near_figures
    keys, opts, _, _, _ = scan_case
    table = main_spring.margins(keys, opts, engine=engine)
    a, b, f = (x.reshape(table.shape[:2]) for x in near_figures(table.reshape(-1, table.shape[2])))
    assert (f > 0).any() and (f == 0).any() and (b > a).any() and (b == a).any()  # every figure is exercised
    floor = float(np.quantile(a[np.isfinite(a)], 0.9))
    low, second, failing = main_spring.near_above(keys, opts, floor, engine=engine)
    reach = a >= floor
    assert 0 < reach.sum() < reach.size
    assert np.array_equal(low >= floor, reach)
    assert np.array_equal(low[reach], a[reach]) and np.array_equal(second[reach], b[reach])
    assert np.array_equal(failing[reach], f[reach])
    low, second, failing = main_spring.near_above(keys, opts, -np.inf, engine=engine)  # no floor: the whole table
    assert np.array_equal(low, a) and np.array_equal(second, b) and np.array_equal(failing, f)


def test_max_min_margin_ties_at_the_section_margin_go_to_the_lowest_index(space_springs, realistic):
    # every supplied option's smallest margin is at most 0 (spring_material_section = 0): the feasible ones tie at
    # 0 and argmax (the reference's nearest design) takes the first; the kernel too
    keys = realistic[3].take(np.arange(0, 600, 20))
    opts = space_springs.take(np.arange(0, len(space_springs), 7))
    mins = _brute(main_spring.reference_margins(keys, opts), 0.0)[1]
    assert (mins <= 0).all() and (mins == 0).any()
    r = main_spring.max_min_margin(keys, opts)
    assert np.array_equal(r.index, np.argmax(mins, axis=1))


@pytest.mark.parametrize("engine", ["numba", "numpy"])
def test_any_feasible_matches_brute_force(scan_case, engine):
    keys, opts, lists, kg, ref = scan_case
    ok, _ = _brute(ref, FEAS_TOL)
    r = main_spring.any_feasible(keys, opts, lists, key_group=kg, tol=FEAS_TOL, engine=engine)
    expect = np.array([ok[i, lists[kg[i]]].any() for i in range(len(keys))])
    assert np.array_equal(r.index, expect)
    assert expect.any() and not expect.all()


def test_parallel_kernels_give_the_serial_answers(scan_case):
    keys, opts, lists, kg, ref = scan_case
    buf = np.full(ref.shape, np.nan)
    assert main_spring.margins(keys, opts, parallel=True, out=buf) is buf
    assert np.array_equal(buf, main_spring.margins(keys, opts))
    for fn in (main_spring.first_feasible, main_spring.max_min_margin, main_spring.any_feasible):
        a, b = fn(keys, opts, lists, key_group=kg, parallel=True), fn(keys, opts, lists, key_group=kg)
        for x, y in zip(a, b):
            assert np.array_equal(x, y)


def test_nan_keys_of_failing_cores_are_infeasible_not_errors(space_springs):
    # the nearest design evaluates every core, also those whose values are NaN: -inf margins, as the registry's
    apps, keys, _ = _evaluator_keys(generate(2, seed=3))
    keys = {k: v.copy() for k, v in keys.items()}
    keys["spring_housing_height_mm"][0] = np.nan
    kk = main_spring.keys_of_rows(apps, keys, np.array([0, 1]))
    opts = space_springs.take(np.arange(0, 11000, 100))
    m = main_spring.margins(kk, opts)
    _assert_close(m, main_spring.reference_margins(kk, opts))
    assert (main_spring.first_feasible(kk, opts).index[:1] == -1).all()
    assert main_spring.max_min_margin(kk, opts).value[0] == -np.inf


# ------------------------------------------------------------------ bad input, lazy import


def test_bad_inputs_name_the_field():
    good = dict(spring_torque_nominal_nm=1.0, housing_height_mm=9.0, housing_outer_diameter_mm=50.0,
                housing_inner_diameter_mm=30.0, stiffness_nm_per_deg=0.02, torque_tolerance_pct=5, theta_pp_deg=16)
    with pytest.raises(InputError, match="stiffness_nm_per_deg"):
        main_spring.spring_keys(**{**good, "stiffness_nm_per_deg": 0.0})
    with pytest.raises(InputError, match="housing_outer_diameter_mm"):
        main_spring.spring_keys(**{**good, "housing_outer_diameter_mm": [50.0, np.nan]})
    with pytest.raises(InputError, match="theta_pp_deg.*1 or 3 values"):
        main_spring.spring_keys(**{**good, "housing_height_mm": [9.0, 9.0, 9.0], "theta_pp_deg": [16.0, 16.0]})
    keys = main_spring.spring_keys(**good)
    opts = main_spring.spring_options(E_mpa=206000, Rm_mpa=2000, sigma_y_mpa=1760, sigma_A0_mpa=700, b_mm=2.3, h_mm=2.3,
                            round_wire=True, mbd_mm=[40.0, 44.0])
    with pytest.raises(InputError, match="candidates"):
        main_spring.first_feasible(keys, opts, np.array([0, 2]))
    with pytest.raises(InputError, match="key_group"):
        main_spring.max_min_margin(keys, opts, [np.array([0]), np.array([1])])
    with pytest.raises(InputError, match="score"):
        main_spring.first_feasible(keys, opts, [np.array([0, 1])], key_group=np.array([0]), score=[np.array([1.0])])
    with pytest.raises(InputError, match="engine"):
        main_spring.margins(keys, opts, engine="cuda")
    with pytest.raises(InputError, match="out"):
        main_spring.margins(keys, opts, out=np.empty((1, 2, 7)))
    with pytest.raises(InputError, match="round_wire"):
        main_spring.spring_options(E_mpa=206000, Rm_mpa=2000, sigma_y_mpa=1760, sigma_A0_mpa=700, b_mm=2.3, h_mm=2.3,
                         round_wire="yes", mbd_mm=44.0)


def test_importing_the_kernels_the_model_and_the_cli_does_not_import_numba():
    # the one-application path (synth design) must not pay for numba: only a kernel call loads it
    code = ("import sys, synth.kernels, synth.model.torsion_spring, synth.cli, synth.kernels.main_spring as k\n"
            "assert 'numba' not in sys.modules and not k.numba_loaded(), 'numba imported'\n")
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    r = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True, timeout=120)
    assert r.returncode == 0, r.stderr


def test_keys_built_before_a_catalog_change_are_refused(monkeypatch):
    keys = main_spring.spring_keys(spring_torque_nominal_nm=1.0, housing_height_mm=9.0, housing_outer_diameter_mm=50.0,
                         housing_inner_diameter_mm=30.0, stiffness_nm_per_deg=0.02, torque_tolerance_pct=5,
                         theta_pp_deg=16)
    opts = main_spring.spring_options(E_mpa=206000, Rm_mpa=2000, sigma_y_mpa=1760, sigma_A0_mpa=700, b_mm=2.3, h_mm=2.3,
                            round_wire=True, mbd_mm=44.0)
    changed = {**s9.main_spring_constants(), "main_spring_index_max": 18.0}  # e.g. a user catalog folder
    monkeypatch.setattr(s9, "main_spring_constants", lambda: changed)
    with pytest.raises(InputError, match="main_spring_index_max"):
        main_spring.margins(keys, opts)


# --------------------------------------------------------------------------- the spring lists' order (issue 19)
@pytest.mark.parametrize("weights", [{"cost": 1.0, "standard": 1e4}, {"standard": 1e4, "cost": 1.0}, {"cost": 1.0},
                                     {"standard": 0.5, "cost": 3.0, "margin": 2.0}])
def test_list_order_is_numpys_weighted_sums_bit_for_bit(weights):
    """The compiled order checks and first scores of the spring lists equal numpy's weighted sums (``np.diff`` of
    each row) for every weight order, at extreme stiffnesses (zero, NaN, tiny, huge, negative) and on the springs
    of the space; the applications' lists and scores (computed when read) are the numpy engine's."""
    from synth.data.generated_applications import generate
    from synth.optimise.batch import Batch, wsum
    from synth.optimise.product import option_scores
    apps = generate(40, seed=5)
    fast, ref = Batch(apps, spring_engine="numba"), Batch(apps, spring_engine="numpy")
    rng = np.random.default_rng(0)
    order = np.argsort(wsum(option_scores(fast.sp, "spring", 1.0), weights), kind="stable")  # the base order
    cand = order[np.isin(order, rng.choice(len(order), size=min(300, len(order)), replace=False))]
    stiff = np.r_[0.0, np.nan, 1e-300, 1e300, -1.0, rng.uniform(0.01, 5.0, 60)]
    first_f, good_f = fast.springs.list_order(weights, stiff, cand)
    first_r, good_r = ref.springs.list_order(weights, stiff, cand)
    np.testing.assert_array_equal(first_f, first_r)  # NaN where NaN, every other double the same
    np.testing.assert_array_equal(good_f, good_r)
    assert not good_f[1] and good_f[5:].any()  # a NaN stiffness keeps no order; real ones do
    lists_f, of_f, smin_f, _, _ = fast.springs.app_lists(weights)
    lists_r, of_r, smin_r, _, _ = ref.springs.app_lists(weights)
    np.testing.assert_array_equal(of_f, of_r)
    np.testing.assert_array_equal(smin_f, smin_r)
    assert len(lists_f) == len(lists_r) and all(np.array_equal(a, b) for a, b in zip(lists_f, lists_r))
    for i in np.flatnonzero(of_f >= 0):  # each application's scores along its list: growing, the first smin
        lst = lists_f[of_f[i]]
        sc_f = fast.springs.scores(weights, np.full(len(lst), i), lst)
        np.testing.assert_array_equal(sc_f, ref.springs.scores(weights, np.full(len(lst), i), lst))
        np.testing.assert_array_equal(sc_f, wsum(option_scores(fast.sp, "spring", apps[i].spring_stiffness_nm_per_deg,
                                                               lst), weights))  # one application's whole list
        assert sc_f[0] == smin_f[i] and (np.diff(sc_f) >= 0).all()
        # the score cut's bisection is numpy's searchsorted on the whole list: below, at, between and above
        lim = np.r_[sc_f[0] - 1.0, sc_f[[0, len(sc_f) // 2, -1]], np.nextafter(sc_f[len(sc_f) // 2], np.inf),
                    sc_f[-1] + 1.0, np.inf]
        got = fast.springs.last_within(weights, np.full(len(lim), i), lim)
        np.testing.assert_array_equal(got[:-1], np.searchsorted(sc_f, lim[:-1], side="right") - 1.0)
        assert got[-1] == np.inf


@settings(max_examples=40, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(seed=st.integers(0, 2**32 - 1), limit=st.integers(1, 40), conditions=st.booleans())
def test_window_pairs_are_numpys_nonzero_of_the_mask_in_its_order(seed, limit, conditions):
    """The compiled candidate enumeration is ``np.nonzero`` of the dense window-and-conditions mask (groups in the
    given order, options ascending), whatever the block size; NaN bounds admit nothing."""
    rng = np.random.default_rng(seed)
    n_g, n_o = int(rng.integers(0, 12)), int(rng.integers(1, 30))
    mbd = rng.choice([20.0, 30.0, 40.0, 50.0, np.nan], n_o)
    lo, hi = rng.choice([15.0, 25.0, 35.0, np.nan], n_g), rng.choice([25.0, 45.0, 60.0, np.nan, -np.inf], n_g)
    groups = rng.permutation(n_g)[: int(rng.integers(0, n_g + 1))]
    mask = (mbd[None, :] >= lo[groups, None]) & (mbd[None, :] <= hi[groups, None])
    kw = {}
    if conditions:
        ex, nd = rng.random((3, n_o)) < 0.3, rng.random((4, n_o)) < 0.7
        er, nr = rng.integers(-1, 3, n_g), rng.integers(-1, 4, n_g)
        mask &= ~np.where(er[groups, None] >= 0, ex[er[groups]], False)
        mask &= np.where(nr[groups, None] >= 0, nd[nr[groups]], True)
        kw = dict(exclude=ex, exclude_row=er, need=nd, need_row=nr)
    gi, want_o = np.nonzero(mask)
    got = list(main_spring.window_pairs(groups, lo, hi, mbd, limit=limit, **kw))
    got_g = np.concatenate([g for g, _ in got]) if got else np.zeros(0, np.int64)
    got_o = np.concatenate([o for _, o in got]) if got else np.zeros(0, np.int64)
    assert got_g.tolist() == groups[gi].tolist() and got_o.tolist() == want_o.tolist()
    assert all(len(g) < limit + n_o and len(g) > 0 for g, _ in got)


@settings(max_examples=40, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(seed=st.integers(0, 2**32 - 1))
def test_record_stage_is_the_numpy_bookkeeping(seed):
    """The compiled stage bookkeeping of the platform producer equals its numpy statement: survivors, failures along
    the line of a finite group value, and per group the largest margin (NaN-propagating, ``np.maximum.reduceat``)
    with the binding of the first pair reaching it, kept when strictly larger."""
    from synth.platform.pairs import segment_best
    rng = np.random.default_rng(seed)
    n_g, n_o, n = int(rng.integers(1, 6)), int(rng.integers(1, 8)), int(rng.integers(0, 30))
    gg = np.sort(rng.integers(0, n_g, n))
    oo = rng.integers(0, n_o, n)
    m = rng.choice([-0.5, -0.1, 0.0, 0.2, 0.2, np.nan, -np.inf], n)
    b = rng.integers(0, 9, n).astype(np.int16)
    ok = m >= 0
    finite, line = rng.random(n_g) < 0.7, rng.integers(0, 3, n_g).astype(np.int64)
    best0, bb0 = rng.choice([-np.inf, -0.2, 0.1], n_g), rng.integers(0, 9, n_g).astype(np.int16)
    want_s, want_f = np.zeros((n_g, n_o), bool), np.zeros((3, n_o), bool)
    want_s[gg[ok], oo[ok]] = True
    bad = ~ok & finite[gg]
    want_f[line[gg[bad]], oo[bad]] = True
    want_b, want_bb = best0.copy(), bb0.copy()
    g, mm, at = segment_best(gg, m)
    upd = mm > want_b[g]
    want_b[g[upd]], want_bb[g[upd]] = mm[upd], b[at[upd]]
    got_s, got_f, got_b, got_bb = np.zeros_like(want_s), np.zeros_like(want_f), best0.copy(), bb0.copy()
    main_spring.load_rounds().record_stage(gg, oo, ok, m, b, finite, line, got_s, got_f, got_b, got_bb)
    assert (got_s == want_s).all() and (got_f == want_f).all()
    assert np.array_equal(got_b, want_b, equal_nan=True) and (got_bb == want_bb).all()
