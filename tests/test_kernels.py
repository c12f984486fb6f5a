"""Compiled main-spring kernels (synth.kernels.torsion_spring) against the reference main_spring_design.

Sources: the reference is synth.model.torsion_spring.main_spring_design (thesis step 9, eq. (64)-(93)); the keys
come from generated applications through the optimiser's design space (realistic) and from hypothesis draws
across the input schema's bounds (extremes); (b)-(d) are checked against brute force over the full margin table.
"""

import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from synth import catalog
from synth.data.generated_applications import generate
from synth.errors import InputError
from synth.kernels import torsion_spring as K
from synth.model import torsion_spring as s9
from synth.optimise import evaluate as E
from synth.optimise.space import build_space

ROOT = Path(__file__).resolve().parents[1]
FEAS_TOL = 1e-9


# ------------------------------------------------------------------ fixtures: realistic keys and every catalog spring


def _space_keys(d, sp):
    """The spring keys of every core of the application's space, as the optimiser builds them (torque >= 1e-6 N m)."""
    _, arr, _, cv = E._core(sp)
    u = np.unique(E.spring_keys(cv, np.arange(len(arr))), axis=0)
    dur = sp.fixed["durability"]
    return u, dict(stiffness_nm_per_deg=d.spring_stiffness_nm_per_deg,
                   torque_tolerance_pct=d.spring_torque_tolerance_pct or 0.0,
                   theta_pp_deg=dur[0] if dur else 0.0)


def _keys_of(u, app):
    return K.spring_keys(spring_torque_nominal_nm=np.maximum(u[:, 0], 1e-6), housing_height_mm=u[:, 1],
                         housing_outer_diameter_mm=u[:, 2], housing_inner_diameter_mm=u[:, 3], **app)


@pytest.fixture(scope="module")
def catalog_springs():
    """Every catalog material x wire x mean body diameter (1 mm grid over 20-70 mm, the optimiser's step)."""
    mats = catalog.load("spring_materials")["material"].astype(str).tolist()
    wires = catalog.load("spring_wires")
    step = catalog.constant("optimise_mbd_step_mm")
    mbd = np.arange(20.0, 70.0 + step / 2, step)
    rows = [(m, w, x) for m in mats for w in range(len(wires)) for x in mbd]
    import pandas as pd
    t = pd.DataFrame({"spring_material": [r[0] for r in rows], "spring_mbd_mm": [r[2] for r in rows]})
    wi = np.array([r[1] for r in rows])
    for col in ("b_mm", "h_mm", "b_tol_mm", "h_tol_mm"):
        t[col] = wires[col].to_numpy(float)[wi]
    t["round_wire"] = (wires["section"].str.strip() == "round").to_numpy()[wi]
    return K.options_from_table(t)


@pytest.fixture(scope="module")
def realistic_keys():
    """600 spring keys drawn (seeded) from the spaces of 60 generated applications, each with its inputs."""
    rng = np.random.default_rng(13)
    parts = []
    for d in generate(60, seed=13):
        sp = build_space(d)
        u, app = _space_keys(d, sp)
        pick = rng.choice(len(u), size=min(10, len(u)), replace=False)
        parts.append((u[pick], app))
    u = np.concatenate([u for u, _ in parts])
    app = {k: np.concatenate([np.full(len(u), a[k]) for u, a in parts]) for k in parts[0][1]}
    keys = _keys_of(u, app)
    assert len(keys) == 600
    return keys


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
        assert ((a >= 0) == (ref >= 0)).all()


# ------------------------------------------------------------------ (a) margins


def test_margins_equal_reference_on_600_generated_keys_x_every_catalog_spring(realistic_keys, catalog_springs):
    keys, opts = realistic_keys, catalog_springs
    assert len(opts) >= 5000
    feasible = 0
    for lo in range(0, len(keys), 100):
        sub = keys.take(np.arange(lo, min(lo + 100, len(keys))))
        a = K.margins(sub, opts)
        ref = K.reference_margins(sub, opts)
        _assert_close(a, ref)
        assert (a == ref).mean() > 0.999  # the same operations in the same order: bit-for-bit in practice
        feasible += int(np.all(ref >= 0, axis=2).sum())
    assert 0 < feasible < len(keys) * len(opts)  # both verdicts occur


def test_margins_equal_optimiser_spring_margins():
    # the keys built as the optimiser builds them give its own margins (synth.optimise.evaluate.spring_margins)
    d = generate(3, seed=5)[1]
    sp = build_space(d)
    u, app = _space_keys(d, sp)
    _, ref, _ = E.spring_margins(sp, u)
    a = K.margins(_keys_of(u, app), K.options_from_table(sp.subsystems["spring"]))
    _assert_close(a, ref)


def test_margins_reproduce_a_hand_calculated_pair():
    # case 3 pair of the module doctest: sigma_inst = k_f T_inst 1000 / Z with T_inst = k theta_inst,
    # theta_inst = 1.56 * 0.92 / 0.0164 + 28.6 = 116.1122 deg, T_inst = 1.90424 N m, Z = pi 2.3^3 / 32 = 1.194492 mm^3,
    # c = 44 / 2.3 = 19.13043, k_f = (4c^2 - c - 1) / (4c(c - 1)) = 1.040646 -> sigma_inst = 1658.98 MPa
    opts = K.spring_options(E_mpa=206000, Rm_mpa=2004, sigma_y_mpa=1763.5, sigma_A0_mpa=701.4, b_mm=2.3, h_mm=2.3,
                            round_wire=True, mbd_mm=44.0)
    keys = K.spring_keys(spring_torque_nominal_nm=1.56, housing_height_mm=8.8, housing_outer_diameter_mm=48.0,
                         housing_inner_diameter_mm=30.0, stiffness_nm_per_deg=0.0164, torque_tolerance_pct=8,
                         theta_pp_deg=16, dtheta_inst_nom_deg=28.6, torque_tolerance_side=-1)
    m = K.margins(keys, opts)[0, 0]
    assert 1763.5 * (1 - m[0]) == pytest.approx(1658.98, abs=0.01)
    # index margins: (19.1304 - 4) / 4 and (20 - 19.1304) / 20
    assert m[5] == pytest.approx(3.78261, abs=1e-5) and m[6] == pytest.approx(0.043478, abs=1e-6)


_pos = dict(allow_nan=False, allow_infinity=False)


@st.composite
def _extreme_keys(draw, n=6):
    """Keys across the schema's bounds and beyond the realistic range: zero torque, huge housings, tiny stiffness."""
    def arr(lo, hi, special=()):
        vals = st.one_of(st.floats(lo, hi, **_pos), st.sampled_from(list(special) or [lo, hi]))
        return np.array(draw(st.lists(vals, min_size=n, max_size=n)))
    outer = arr(1.0, 5000.0, (1.0, 60.0, 5000.0))
    return K.spring_keys(
        spring_torque_nominal_nm=arr(0.0, 100.0, (0.0, 1e-6, 100.0)),
        housing_height_mm=arr(0.1, 1000.0, (0.1, 9.0, 1000.0)),
        housing_outer_diameter_mm=outer,
        housing_inner_diameter_mm=outer * arr(0.0, 1.2, (0.0, 0.5, 1.0)),
        stiffness_nm_per_deg=arr(1e-9, 10.0, (1e-9, 1e-6, 0.02, 10.0)),
        torque_tolerance_pct=arr(0.0, 50.0), theta_pp_deg=arr(0.0, 90.0),
        dtheta_inst_nom_deg=arr(0.0, 180.0), dtheta_nom_free_arm_deg=arr(0.0, 180.0),
        torque_tolerance_side=np.array(draw(st.lists(st.sampled_from([-1.0, 1.0]), min_size=n, max_size=n))),
        winding=np.array(draw(st.lists(st.booleans(), min_size=n, max_size=n))))


@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(keys=_extreme_keys(), seed=st.integers(0, 2**31 - 1), mbd=st.sampled_from([1.0, 5.0, 44.0, 500.0]))
def test_margins_equal_reference_at_the_extremes(catalog_springs, keys, seed, mbd):
    rng = np.random.default_rng(seed)
    opts = catalog_springs.take(rng.choice(len(catalog_springs), size=40, replace=False))
    odd = K.spring_options(**{k: v[:3] for k, v in opts.raw.items() if k != "mbd_mm"}, mbd_mm=mbd)  # extreme diameter
    for o in (opts, odd):
        ref = K.reference_margins(keys, o)
        _assert_close(K.margins(keys, o), ref)
        ok, mins = _brute(ref, 0.0)
        first = np.where(ok.any(axis=1), np.argmax(ok, axis=1), -1)
        assert np.array_equal(K.first_feasible(keys, o).index, first)
        assert np.array_equal(K.max_min_margin(keys, o).index, np.argmax(mins, axis=1))


@pytest.mark.parametrize("tol", [0.0, FEAS_TOL])
def test_yield_threshold_decides_the_yield_check_exactly(realistic_keys, catalog_springs, tol):
    # the scan of (b) replaces the yield check by T_inst <= threshold: same verdict as the reference on every pair
    keys = realistic_keys.take(np.arange(0, 600, 6))
    t_max = K.yield_thresholds(catalog_springs, tol)
    ref = K.reference_margins(keys, catalog_springs)[:, :, 0]
    by_threshold = keys.derived["t_inst"][:, None] <= t_max[None, :]
    assert np.array_equal(by_threshold, ref >= -tol)
    assert 0.05 < by_threshold.mean() < 0.95
    # and it is the largest such torque: one double more fails
    d = catalog_springs.derived
    up = np.nextafter(t_max, np.inf)
    assert ((d["sy"] - d["kf"] * t_max * 1000.0 / d["z"]) / d["sy_scale"] >= -tol).all()
    assert not ((d["sy"] - d["kf"] * up * 1000.0 / d["z"]) / d["sy_scale"] >= -tol).any()


# ------------------------------------------------------------------ (b)-(d) against brute force


def _brute(ref, tol):
    ok = np.all(ref >= -tol, axis=2)
    mins = np.min(np.where(np.isnan(ref), -np.inf, ref), axis=2)
    return ok, mins


@pytest.fixture(scope="module")
def scan_case(realistic_keys, catalog_springs):
    """300 keys in 3 groups (applications), each group its own seeded candidate list of 1,500 options."""
    rng = np.random.default_rng(7)
    keys = realistic_keys.take(rng.choice(len(realistic_keys), size=300, replace=False))
    opts = catalog_springs.take(rng.choice(len(catalog_springs), size=3000, replace=False))
    lists = [rng.permutation(3000)[:1500] for _ in range(3)]
    key_group = rng.integers(0, 3, size=len(keys))
    ref = K.reference_margins(keys, opts)
    return keys, opts, lists, key_group, ref


@pytest.mark.parametrize("engine", ["numba", "numpy"])
@pytest.mark.parametrize("tol", [0.0, FEAS_TOL])
def test_first_feasible_is_the_first_feasible_option_of_each_list(scan_case, engine, tol):
    keys, opts, lists, kg, ref = scan_case
    ok, _ = _brute(ref, tol)
    r = K.first_feasible(keys, opts, lists, key_group=kg, tol=tol, engine=engine)
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
def test_first_feasible_stops_at_the_score_limit(scan_case, engine):
    keys, opts, lists, kg, ref = scan_case
    ok, _ = _brute(ref, 0.0)
    score = np.random.default_rng(3).uniform(0, 10, len(opts))
    order = [lst[np.argsort(score[lst], kind="stable")] for lst in lists]  # score order, as the bulk engine scans
    limit = np.random.default_rng(4).uniform(0, 10, len(keys))
    r = K.first_feasible(keys, opts, order, key_group=kg, score=score, score_limit=limit, engine=engine)
    for i in range(len(keys)):
        lst = order[kg[i]]
        lst = lst[score[lst] <= limit[i]]
        hits = np.flatnonzero(ok[i, lst])
        assert r.index[i] == (lst[hits[0]] if len(hits) else -1)


@pytest.mark.parametrize("engine", ["numba", "numpy"])
def test_max_min_margin_is_the_argmax_of_the_smallest_margin(scan_case, engine):
    keys, opts, lists, kg, ref = scan_case
    _, mins = _brute(ref, 0.0)
    r = K.max_min_margin(keys, opts, lists, key_group=kg, engine=engine)
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
    r = K.max_min_margin(keys, opts, lists, key_group=kg, cap=cap, engine=engine)
    assert np.array_equal(np.minimum(r.value, cap), np.minimum(true, cap))
    assert (mins[np.arange(len(keys)), r.index] == r.value).all()


def test_max_min_margin_default_list_ties_go_to_the_lowest_index(catalog_springs):
    # a key every option fails with the same -inf-free margin pattern: identical options tie, argmax picks the first
    opts = catalog_springs.take(np.array([5, 5, 5, 7, 7]))
    keys = K.spring_keys(spring_torque_nominal_nm=2.0, housing_height_mm=12.0, housing_outer_diameter_mm=50.0,
                         housing_inner_diameter_mm=25.0, stiffness_nm_per_deg=0.03, torque_tolerance_pct=5,
                         theta_pp_deg=16)
    mins = np.min(K.reference_margins(keys, opts), axis=2)[0]
    r = K.max_min_margin(keys, opts)
    assert r.index[0] == int(np.argmax(mins)) and r.index[0] in (0, 3)


@pytest.mark.parametrize("engine", ["numba", "numpy"])
def test_any_feasible_matches_brute_force(scan_case, engine):
    keys, opts, lists, kg, ref = scan_case
    ok, _ = _brute(ref, FEAS_TOL)
    r = K.any_feasible(keys, opts, lists, key_group=kg, tol=FEAS_TOL, engine=engine)
    expect = np.array([ok[i, lists[kg[i]]].any() for i in range(len(keys))])
    assert np.array_equal(r.index, expect)
    assert expect.any() and not expect.all()


def test_parallel_kernels_give_the_serial_answers(scan_case):
    keys, opts, lists, kg, ref = scan_case
    buf = np.full(ref.shape, np.nan)
    assert K.margins(keys, opts, parallel=True, out=buf) is buf
    assert np.array_equal(buf, K.margins(keys, opts))
    for fn in (K.first_feasible, K.max_min_margin, K.any_feasible):
        a, b = fn(keys, opts, lists, key_group=kg, parallel=True), fn(keys, opts, lists, key_group=kg)
        for x, y in zip(a, b):
            assert np.array_equal(x, y)


# ------------------------------------------------------------------ bad input, lazy import


def test_bad_inputs_name_the_field():
    good = dict(spring_torque_nominal_nm=1.0, housing_height_mm=9.0, housing_outer_diameter_mm=50.0,
                housing_inner_diameter_mm=30.0, stiffness_nm_per_deg=0.02, torque_tolerance_pct=5, theta_pp_deg=16)
    with pytest.raises(InputError, match="stiffness_nm_per_deg"):
        K.spring_keys(**{**good, "stiffness_nm_per_deg": 0.0})
    with pytest.raises(InputError, match="housing_outer_diameter_mm"):
        K.spring_keys(**{**good, "housing_outer_diameter_mm": [50.0, np.nan]})
    with pytest.raises(InputError, match="theta_pp_deg.*1 or 3 values"):
        K.spring_keys(**{**good, "housing_height_mm": [9.0, 9.0, 9.0], "theta_pp_deg": [16.0, 16.0]})
    keys = K.spring_keys(**good)
    opts = K.spring_options(E_mpa=206000, Rm_mpa=2000, sigma_y_mpa=1760, sigma_A0_mpa=700, b_mm=2.3, h_mm=2.3,
                            round_wire=True, mbd_mm=[40.0, 44.0])
    with pytest.raises(InputError, match="candidates"):
        K.first_feasible(keys, opts, np.array([0, 2]))
    with pytest.raises(InputError, match="key_group"):
        K.max_min_margin(keys, opts, [np.array([0]), np.array([1])])
    with pytest.raises(InputError, match="engine"):
        K.margins(keys, opts, engine="cuda")
    with pytest.raises(InputError, match="out"):
        K.margins(keys, opts, out=np.empty((1, 2, 6)))
    with pytest.raises(InputError, match="round_wire"):
        K.spring_options(E_mpa=206000, Rm_mpa=2000, sigma_y_mpa=1760, sigma_A0_mpa=700, b_mm=2.3, h_mm=2.3,
                         round_wire="yes", mbd_mm=44.0)


def test_importing_the_kernels_the_model_and_the_cli_does_not_import_numba():
    # the one-application path (synth design) must not pay for numba: only a kernel call loads it
    code = ("import sys, synth.kernels, synth.model.torsion_spring, synth.cli, synth.kernels.torsion_spring as k\n"
            "assert 'numba' not in sys.modules and not k.numba_loaded(), 'numba imported'\n")
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    r = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True, timeout=120)
    assert r.returncode == 0, r.stderr


def test_keys_built_before_a_catalog_change_are_refused(monkeypatch):
    keys = K.spring_keys(spring_torque_nominal_nm=1.0, housing_height_mm=9.0, housing_outer_diameter_mm=50.0,
                         housing_inner_diameter_mm=30.0, stiffness_nm_per_deg=0.02, torque_tolerance_pct=5,
                         theta_pp_deg=16)
    opts = K.spring_options(E_mpa=206000, Rm_mpa=2000, sigma_y_mpa=1760, sigma_A0_mpa=700, b_mm=2.3, h_mm=2.3,
                            round_wire=True, mbd_mm=44.0)
    changed = {**s9.main_spring_constants(), "main_spring_index_max": 18.0}  # e.g. a user catalog folder
    monkeypatch.setattr(s9, "main_spring_constants", lambda: changed)
    with pytest.raises(InputError, match="main_spring_index_max"):
        K.margins(keys, opts)
