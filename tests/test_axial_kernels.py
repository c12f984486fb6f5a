"""Compiled twins of the axial group's physics (synth.kernels.axial) against the numpy reference.

Sources: the reference is synth.model.disc_spring.cone_spring (thesis step 8, eq. (9), (55)-(63), DIN EN 16984 /
16983) and synth.model.friction_wear.plastic_wear (thesis step 5, eq. (43)-(49)), called through the one evaluator's
axial group (synth.design.evaluate.axial) on the rows of generated applications (realistic: every optional input
present and absent) and directly on seeded draws across the models' validity ranges (extremes: aspect ratios up to
2.7 < 2 sqrt 2, wear constants from 0 to 1e-5, zero and 100,000 h tests). The stated tolerance is
synth.kernels.axial.RTOL / ATOL (the twins differ from the reference only in the last bits of log/exp/arctan/pow
and in the wear root's solver, Brent instead of Chandrupatla, both to 4 eps).
"""

import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from synth.data.generated_applications import generate
from synth.design import evaluate as E
from synth.design.constraints import REGISTRY
from synth.design.applications import Applications
from synth.design.space import core_rows, space
from synth.errors import InputError
from synth.kernels import axial as K
from synth.model import disc_spring as s8
from synth.model import friction_wear as s5

ROOT = Path(__file__).resolve().parents[1]


def _assert_equal(twin: dict, ref: dict, keys=None):
    """The values of ``keys`` (default every key of ``ref``) equal bit for bit (NaN where NaN), the same shapes."""
    for k in ref if keys is None else keys:
        assert np.shape(twin[k]) == np.shape(ref[k]), k
        assert np.array_equal(np.asarray(twin[k], float), np.asarray(ref[k], float), equal_nan=True), k


def _assert_twin(twin: dict, ref: dict, scales: dict):
    """Every value of ``twin`` equals ``ref`` within ``RTOL`` of its magnitude or ``ATOL`` of the magnitude of its
    kind in its row (``scales``: unit suffix -> magnitude, e.g. ``"_n"``: the row's forces, so that a difference of
    two nearly equal forces, a room in a band or a spring worn flat, is compared with the forces it comes from);
    the same NaNs and infinities; the same keys and shapes."""
    assert set(twin) == set(ref)
    for k, r in ref.items():
        r, v = np.asarray(r, dtype=float), np.asarray(twin[k], dtype=float)
        assert v.shape == r.shape, k
        assert (np.isnan(v) == np.isnan(r)).all(), k
        assert (v[np.isinf(r)] == r[np.isinf(r)]).all(), k
        fin = np.isfinite(r)
        allowed = K.RTOL * np.abs(r)
        for suffix, magnitude in scales.items():
            if k.endswith(suffix):
                allowed = np.fmax(allowed, K.ATOL * np.broadcast_to(np.abs(magnitude), r.shape))
        err = np.abs(v - r)
        assert (err[fin] <= allowed[fin]).all(), (k, float(np.max(err[fin] / np.maximum(np.abs(r[fin]), 1e-300))))


# ------------------------------------------------------------------ realistic: the evaluator's axial rows


@pytest.fixture(scope="module")
def axial_rows():
    """4,000 (core, real axial option) rows of 60 generated applications, seeded, with the evaluator's inputs."""
    inputs = generate(60, seed=21, vary=True)
    sp = space()
    apps = Applications.of(inputs)
    per = [core_rows(sp, d) for d in inputs]
    a = np.concatenate([np.full(len(c), i) for i, c in enumerate(per)]).astype(np.int64)
    c = np.concatenate(per)
    rng = np.random.default_rng(21)
    real = np.flatnonzero(sp.tables["axial"]["axial_group_present"])
    out = {}
    for fidelity in ("screening", "full"):
        st = E.Settings(fidelity=fidelity)
        with np.errstate(all="ignore"):
            cg = E.core(apps, a, sp.rows("core", c), st)
        pad = np.flatnonzero(np.asarray(cg.values["axial_group_present"], dtype=float) > 0)
        rr, oo = rng.choice(pad, 4000), rng.choice(real, 4000)
        out[fidelity] = (apps, cg, rr, sp.rows("axial", oo), st)
    return out


def test_checks_before_the_physics_are_the_groups_own(axial_rows):
    """The axial checks a search evaluates before the physics (evaluate.axial_before_physics, the bulk engine's
    cut) carry the full group's margins and states bit for bit, read nothing the fidelity changes, and reject
    rows here (else the cut would be untested)."""
    apps, cg, rr, o, st = axial_rows["screening"]
    with np.errstate(all="ignore"):
        full = E.axial(apps, cg, rr, o, st)
        pre = E.axial_before_physics(apps, cg, rr, o)
    assert {"endcap_spacer_capacity", "belt_plane", "cone_outer_on_pad"} <= set(pre.margins)
    assert set(pre.margins) < set(full.margins)
    for k, m in pre.margins.items():
        assert np.array_equal(m, full.margins[k]), k
        assert np.array_equal(pre.state[k], full.state[k]), k
    assert set(pre.margins) <= set(E.fidelity_free()) | {c for c in pre.margins if REGISTRY[c].advisory}
    ok = pre.ok()
    assert not ok.all() and not (full.ok() & ~ok).any()  # a row the cut rejects the group rejects


@pytest.mark.parametrize("fidelity", ["screening", "full"])
def test_checks_before_the_wear_are_the_groups_own(axial_rows, fidelity):
    """The axial checks the platform's feasibility evaluates before the plastic wear (evaluate.axial_before_wear:
    the cone spring sized, no wear) carry the whole group's margins and states bit for bit, hold every check but
    those that read the wear, and reject rows the whole group rejects (here most: the wear is solved for few)."""
    apps, cg, rr, o, st = axial_rows[fidelity]
    with np.errstate(all="ignore"):
        full = E.axial(apps, cg, rr, o, st, engine="numba")
        pre = E.axial_before_wear(apps, cg, rr, o, st, engine="numba")
    wear = {c for c in full.margins if set(REGISTRY[c].reads()) & set(E.PLASTIC_WEAR_VALUES)}
    assert wear >= {"damping_eol", "damper_pad_wear", "endcap_spacer_wear"}
    assert set(pre.margins) == set(full.margins) - wear
    for k, m in pre.margins.items():
        assert np.array_equal(m, full.margins[k]), k
        assert np.array_equal(pre.state[k], full.state[k]), k
    ok = pre.ok()
    assert ok.any() and not ok.all() and not (full.ok() & ~ok).any()
    assert (pre.min_margin(objective_only=False) >= full.min_margin(objective_only=False)).all()


@pytest.mark.parametrize("fidelity", ["screening", "full"])
def test_axial_group_on_the_twins_equals_the_reference(axial_rows, fidelity):
    apps, cg, rr, o, st = axial_rows[fidelity]
    with np.errstate(all="ignore"):
        ref = E.axial(apps, cg, rr, o, st)  # no engine named: the reference
        twin = E.axial(apps, cg, rr, o, st, engine="numba")
    v = ref.values
    # the cone spring bit for bit (and so every value and margin that reads no wear), the wear within the tolerance
    wear = set(E.PLASTIC_WEAR_VALUES)
    _assert_equal(twin.values, v, [k for k in v if k not in wear])
    mu_r = np.asarray(apps.damping_target_or_zero_nm)[np.asarray(cg.values["app"])[rr]] / np.maximum(
        v["cone_spring_fax_nominal_n"], 1e-300)  # N m per N of axial force (eq. (9)): the damping's magnitude
    forces = np.abs(v["cone_spring_fax_max_tolerance_n"]) + np.abs(v["cone_spring_fax_nominal_n"])
    _assert_twin(twin.values, v, {"_n": forces, "_mm": v["cone_spring_nominal_deflection_mm"],
                                  "_nm": v["cone_spring_fax_nominal_n"] * mu_r})
    # the same verdicts, margins within the tolerance of the values they come from
    assert (twin.ok() == ref.ok()).all()
    assert twin.ok().any() and not twin.ok().all()
    for k, m in ref.margins.items():
        m, t = np.asarray(m, dtype=float), np.asarray(twin.margins[k], dtype=float)
        assert (np.isnan(m) == np.isnan(t)).all(), k
        fin = np.isfinite(m)
        assert (t[~fin & ~np.isnan(m)] == m[~fin & ~np.isnan(m)]).all(), k
        assert (np.abs(m[fin] - t[fin]) <= 1e-9 * np.maximum(1.0, np.abs(m[fin]))).all(), k
    # the wear root was solved on these rows (not only the first-order branch)
    if fidelity == "full":
        assert (np.nan_to_num(ref.values["plastic_wear_total_mm"]) > 0.01).sum() > 100


# ------------------------------------------------------------------ extremes: direct calls across the validity ranges


def _draws(n: int, seed: int) -> dict:
    rng = np.random.default_rng(seed)
    de = rng.uniform(15.0, 60.0, n)
    ad = np.exp(rng.uniform(np.log(0.05), np.log(50.0), n))
    ad[:n // 20] = 1e6  # springs thicker than DIN EN 16983's groups (16 mm): no force tolerance (NaN)
    return {
        "ad": ad, "target": rng.uniform(0.0, 12.0, n),
        "tol": rng.uniform(0.0, 1.0, n),
        "rad": rng.uniform(0.0, 1.0, n), "mu": rng.uniform(0.05, 0.3, n), "r_dp": rng.uniform(5.0, 30.0, n),
        "r_es": rng.uniform(5.0, 30.0, n), "de": de, "di": de / rng.uniform(1.2, 3.0, n),
        "gap": rng.uniform(0.0, 0.5, n), "zeta": rng.uniform(0.05, 2.7, n), "phi": rng.uniform(0.02, 1.0, n),
    }


@pytest.mark.parametrize("fidelity", ["screening", "full"])
def test_cone_spring_twin_equals_the_reference_at_the_extremes(fidelity):
    d = _draws(3000, 3)
    args = (d["ad"], d["target"], d["tol"], d["rad"], d["mu"], d["r_dp"], d["r_es"], d["de"], d["di"], d["gap"])
    kw = dict(aspect_ratio=d["zeta"], deflection_ratio=d["phi"], fidelity=fidelity)
    with np.errstate(all="ignore"):
        ref = s8.cone_spring(*args, **kw)
        twin = K.cone_spring(*args, **kw, engine="numba")
    assert set(twin) == set(ref)
    _assert_equal(twin, ref)
    assert np.isnan(ref["cone_spring_force_tolerance_plus"]).any()   # beyond DIN EN 16983's thickness groups
    # a scalar call (the reference's shape: 0-d), scalar diameters with rows of the rest
    first = dict(aspect_ratio=d["zeta"][0], deflection_ratio=d["phi"][0], fidelity=fidelity)
    one = K.cone_spring(*(x[0] for x in args), **first, engine="numba")
    assert all(np.shape(v) == () for v in one.values())
    _assert_equal(one, s8.cone_spring(*(x[0] for x in args), **first))
    mixed = args[:7] + (30.0, 16.2, 0.22)
    with np.errstate(all="ignore"):
        _assert_equal(K.cone_spring(*mixed, **kw, engine="numba"), s8.cone_spring(*mixed, **kw))


@pytest.mark.parametrize("fidelity", ["screening", "full"])
def test_plastic_wear_twin_equals_the_reference_at_the_extremes(fidelity):
    n = 3000
    d = _draws(n, 4)
    rng = np.random.default_rng(5)
    with np.errstate(all="ignore"):
        cs = s8.cone_spring(d["ad"], d["target"], d["tol"], d["rad"], d["mu"], d["r_dp"], d["r_es"], d["de"],
                            d["di"], d["gap"], aspect_ratio=d["zeta"], deflection_ratio=d["phi"])
    t, h0 = cs["cone_spring_thickness_mm"], cs["cone_spring_cone_height_mm"]
    s0 = h0 * rng.uniform(-0.05, 1.0, n)                       # a spring lifted off (s0 <= 0) up to flat
    kw = rng.choice([0.0, 1e-20, 1e-9, 1e-7, 1e-6, 1e-5], n)  # no wear, the first-order branch, up to worn flat
    dur = rng.choice([0.0, 1.0, 50.0, 1200.0, 1e5], n)
    args = (s0, d["de"], d["di"], t, h0, rng.uniform(50.0, 900.0, n), d["r_dp"], rng.uniform(1.0, 5.0, n),
            rng.uniform(50.0, 900.0, n), d["r_es"], rng.uniform(0.5, 3.0, n), rng.uniform(2.0, 40.0, n),
            rng.uniform(10.0, 200.0, n), dur, d["rad"])
    opts = dict(k_wear_mm3_per_n_m=kw, plastic_friction_coefficient=d["mu"], fidelity=fidelity)
    with np.errstate(all="ignore"):
        ref = s5.plastic_wear(*args, **opts)
        twin = K.plastic_wear(*args, **opts, engine="numba")
    _assert_twin(twin, ref, {"_n": ref["cone_spring_force_initial_n"], "_mm": s0,
                             "_nm": ref["axial_damping_initial_nm"]})
    w = ref["plastic_wear_total_mm"]
    assert (w == 0).any() and (w > 0.5 * s0).any() and (s0 <= 0).any()


def test_published_example_on_the_twins():
    # the reference's own doctests (thesis case 1): full 0.287 mm / 1.533 N m, screening 0.294 mm / 1.52 N m
    args = (0.668, 30.0, 16.2, 0.742, 0.890, 460, 12.5, 3.5, 490, 13.5, 1.5, 16, 50, 1200, 0.287)
    mat = s5.plastic_material()
    for fidelity, w, d in (("full", 0.287, 1.533), ("screening", 0.294, 1.52)):
        r = K.plastic_wear(*args, **mat, fidelity=fidelity, engine="numba")
        assert round(float(r["plastic_wear_total_mm"]), 3) == w
        assert round(float(r["damping_eol_nm"]), 3 if fidelity == "full" else 2) == d


# ------------------------------------------------------------------ the reference answers what the twins do not


def test_refused_rows_raise_the_references_error():
    args = (1.7129, 2.0, 0.3, 0.2871, np.array([0.1294, 0.0]), 12.5, 13.5, 30.0, 16.2, 0.22)
    with pytest.raises(InputError, match="plastic_friction_coefficient"):
        K.cone_spring(*args, aspect_ratio=1.2, deflection_ratio=0.75, engine="numba")
    wear = (0.668, 30.0, 16.2, 0.742, 0.890, np.array([460.0, -1.0]), 12.5, 3.5, 490, 13.5, 1.5, 16, 50, 1200, 0.287)
    with pytest.raises(InputError, match="contact_area_mm2"):
        K.plastic_wear(*wear, k_wear_mm3_per_n_m=1e-7, plastic_friction_coefficient=0.129, engine="numba")
    with pytest.raises(InputError, match="engine"):
        K.cone_spring(*args, aspect_ratio=1.2, deflection_ratio=0.75, engine="fortran")


def test_wear_history_and_made_springs_are_the_references():
    wear = (0.668, 30.0, 16.2, 0.742, 0.890, 460, 12.5, 3.5, 490, 13.5, 1.5, 16, 50, 1200, 0.287)
    mat = s5.plastic_material()
    twin = K.plastic_wear(*wear, **mat, time_points=5, engine="numba")
    ref = s5.plastic_wear(*wear, **mat, time_points=5)
    assert np.array_equal(twin["history"]["plastic_wear_total_mm"], ref["history"]["plastic_wear_total_mm"])
    cs = (1.7129, 2.0, 0.3, 0.2871, 0.1294, 12.5, 13.5, 30.0, 16.2, 0.22)
    made = dict(aspect_ratio=1.2, deflection_ratio=0.75, thickness_mm=0.75, deflection_offset_mm=0.05)
    twin, ref = K.cone_spring(*cs, **made, engine="numba"), s8.cone_spring(*cs, **made)
    assert set(twin) == set(ref) and all(np.array_equal(v, ref[k]) for k, v in twin.items())


def test_importing_the_axial_kernels_does_not_import_numba():
    code = ("import sys, synth.kernels.axial as k, synth.design.evaluate\n"
            "assert 'numba' not in sys.modules and not k.numba_loaded(), 'numba imported'\n")
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    r = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True, timeout=120)
    assert r.returncode == 0, r.stderr


def test_each_twin_compiles_one_signature():
    # issue 36: a one-row call (its output table is C- and F-contiguous) and a column that is a read-only view of
    # the caller's array typed the kernels apart, and the first bulk run compiled each twin twice
    gap = np.array([0.22, 0.3])
    cs = (1.7129, 2.0, 0.3, 0.2871, 0.1294, 12.5, 13.5, 30.0, 16.2)
    for g in (gap[0], gap):
        K.cone_spring(*cs, g, aspect_ratio=1.2, deflection_ratio=0.75, engine="numba")
    wear = (0.668, 30.0, 16.2, 0.742, 0.890, 460, 12.5, 3.5, 490, 13.5, 1.5, 16, 50, 1200)
    mat = s5.plastic_material()
    for rad in (0.287, np.array([0.287, 0.3])):
        K.plastic_wear(*wear, rad, **mat, engine="numba")
    jit = K.load_kernels()
    assert len(jit.cone_spring_rows.signatures) == 1, jit.cone_spring_rows.signatures
    assert len(jit.plastic_wear_rows.signatures) == 1, jit.plastic_wear_rows.signatures
