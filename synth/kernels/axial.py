"""The axial group's physics (cone spring, plastic wear) on many rows: compiled twins and the numpy reference.

The axial damping group (thesis steps 5 and 8) is where the bulk engine and the platform's feasibility data
spend most of their time: :func:`synth.design.evaluate.axial` sizes a cone spring for every (core, axial
option) row it is given (:func:`synth.model.disc_spring.cone_spring`) and, where the durability test is given,
follows the plastic wear along its characteristic to the end of the test
(:func:`synth.model.friction_wear.plastic_wear`: at full fidelity a root per row). The numpy reference costs about
2-4 ms a call before its first row (validation, catalog reads, scipy's ``find_root``) and 3 us a row at full
fidelity; the twins 0.2-0.4 ms and 1 us (``benchmarks/bench_axial.py``).

:func:`cone_spring` and :func:`plastic_wear` take the reference's arguments (as the evaluator passes them) and an
``engine``: ``"numpy"`` calls the reference itself; ``"numba"`` runs the compiled twin
(:mod:`synth.kernels._axial_jit`: the reference's lines row by row, the wear root by scipy's compiled ``brentq``).
The evaluator's axial group (:func:`synth.design.evaluate.axial`) passes the engine its caller names, an argument:
the reference unless a caller that evaluates many rows chose the twin (:func:`synth.kernels.engines.axial`: the
bulk engine's :class:`~synth.optimise.batch.Batch`, the production samples of :mod:`synth.robust`,
:data:`synth.robust.sampling.AXIAL_ENGINE`, and the platform producer of ``synth rationalise``,
:data:`synth.platform.producer.AXIAL_ENGINE`: its option margins stand within
:data:`synth.platform.producer.MARGIN_TOL` of the optimiser's, with the same feasible options,
``tests/test_platform_real.py``); the one-application path keeps the reference (it never imports numba). The twin hands the call back to the reference
where the reference is the only definition: a made cone spring (a production-scatter sample of
:mod:`synth.robust`), given force tolerances, the wear history (``time_points``), or a row the reference refuses
(it then raises its own :class:`~synth.errors.InputError`).

**Equality.** The cone spring's twin equals the reference bit for bit: its steps 1-3 (the nominal force, the
thickness) are the reference's own functions, ``t ** 3``, ``t ** 4`` and ``ln(De/Di)`` are computed by numpy as the
reference computes them, and the compiled rest is IEEE arithmetic in the reference's order (no fast-math, no fused
operations). The wear's twin cannot be: numpy evaluates ``log``, ``exp``, ``arctan``, ``expm1`` and powers with its
own SIMD routines (SVML on AVX-512 machines) and numba with the C library's (the two differ in the last bit of a few
per cent of their results), and the wear root comes from Brent's method instead of Chandrupatla's, both to
``4 eps`` relative. Every wear value agrees with the reference within :data:`RTOL` relative to its magnitude, or
within :data:`ATOL` relative to the magnitude of its kind in its row where it is a difference of nearly equal
values (a spring worn flat against the force at new, the wear against the deflection at new).
``tests/test_axial_kernels.py`` holds both on the generated applications' rows (wear measured within 1e-13) and
at the validity edges, and the verdicts equal.

>>> import numpy as np
>>> from synth.model.disc_spring import cone_spring as reference
>>> args = (1.7129, 2.0, 0.3, 0.2871, 0.1294, 12.5, 13.5, 30.0, 16.2, 0.22)
>>> ref = reference(*args, aspect_ratio=1.2, deflection_ratio=0.75)
>>> twin = cone_spring(*args, aspect_ratio=1.2, deflection_ratio=0.75, engine="numba")
>>> round(float(twin["cone_spring_thickness_mm"]), 3), all(np.array_equal(twin[k], ref[k]) for k in ref)
(0.742, True)
"""

from __future__ import annotations

import numpy as np

from synth import catalog
from synth.errors import InputError, Problem
from synth.kernels.numba_setup import Compiled
from synth.model import disc_spring as s8
from synth.model import friction_wear as s5

__all__ = ["ENGINES", "RTOL", "ATOL", "cone_spring", "plastic_wear", "load_kernels", "numba_loaded", "distinct_rows",
           "DISTINCT_SHARE"]

ENGINES = ("numba", "numpy")
#: the twin's stated agreement with the reference: relative to a value's magnitude
RTOL = 1e-12
#: and, for a difference of two nearly equal forces or wears, relative to the magnitude of the forces
ATOL = 1e-12

_ADDRESSES: tuple | None = None


def _import_kernels():
    from synth.kernels import _axial_jit
    return _axial_jit


#: the compiled twins' module (imports numba on the first call; later calls are an attribute lookup)
load_kernels = Compiled(_import_kernels)
#: whether this process has loaded the compiled twins' module (and so imported numba) yet
numba_loaded = load_kernels.loaded


def _addresses() -> tuple:
    """``(brentq, residual)``: the C addresses of scipy's compiled ``brentq`` and of the wear residual callback."""
    global _ADDRESSES
    if _ADDRESSES is None:
        from numba.extending import get_cython_function_address
        solver = get_cython_function_address("scipy.optimize.cython_optimize._zeros", "brentq")
        _ADDRESSES = (int(solver), int(load_kernels().wear_residual.address))
    return _ADDRESSES


def _check_engine(engine: str) -> None:
    if engine not in ENGINES:
        raise InputError(Problem("engine", engine, " or ".join(ENGINES)))


def _columns(*xs) -> tuple:
    """``(shape, columns)``: the arguments' broadcast shape and each argument broadcast to it as one contiguous,
    writeable float row per design (numba types a read-only array apart: a column that is a view of the caller's
    array would compile the kernel a second time)."""
    shape = np.broadcast_shapes(*(np.shape(x) for x in xs))
    cols = [np.ascontiguousarray(np.broadcast_to(np.asarray(x, dtype=float), shape).ravel()) for x in xs]
    return shape, [c if c.flags.writeable else c.copy() for c in cols]


def _table(n: int, k: int) -> np.ndarray:
    """An uninitialised ``(n, k)`` float table in Fortran order (each value a contiguous column) that numba types
    as Fortran-ordered for every ``n``: a one-row table is C-contiguous too, which numba would type as a C array and
    compile the kernel for a second time, so it gets a spare row (the kernels write rows ``0..n-1`` only)."""
    return np.empty((max(n, 2), k), order="F")


def _elastic_scale() -> float:
    """``4 E / (1 - nu^2)`` [MPa] with the catalog's elastic constants, computed as the reference computes it."""
    e, nu = s8.elastic_constants()
    return float(4.0 * e / (1.0 - nu ** 2))


def cone_spring(axial_damping_nm_, damping_target_nm, damping_tolerance_nm, radial_damping_nm,
                plastic_friction_coefficient, damper_pad_mean_radius_mm, endcap_spacer_mean_radius_mm,
                outer_diameter_mm, inner_diameter_mm, gap_tolerance_mm, *, aspect_ratio, deflection_ratio,
                fidelity: str = "full", engine: str = "numpy", **kw) -> dict:
    """:func:`synth.model.disc_spring.cone_spring` (the same arguments and values) on the ``engine``.

    ``engine="numba"`` runs the compiled twin on rows (every argument broadcast to one length); the reference
    answers a made spring or given force tolerances (``kw``) and any call with a row it refuses."""
    _check_engine(engine)
    args = (axial_damping_nm_, damping_target_nm, damping_tolerance_nm, radial_damping_nm,
            plastic_friction_coefficient, damper_pad_mean_radius_mm, endcap_spacer_mean_radius_mm,
            outer_diameter_mm, inner_diameter_mm, gap_tolerance_mm)
    opts = dict(aspect_ratio=aspect_ratio, deflection_ratio=deflection_ratio, fidelity=fidelity, **kw)
    if engine == "numpy" or kw or fidelity not in s8.FIDELITIES:
        return s8.cone_spring(*args, **opts)
    shape, cols = _columns(*args, aspect_ratio, deflection_ratio)
    ad, _, _, _, mu, r_dp, r_es, de, di, _, zeta, phi = cols
    # steps 1-3 by the reference's own functions (they validate the rows), the powers and the log by numpy as the
    # reference computes them: the compiled rest is arithmetic alone, equal to the reference bit for bit
    f_nom = s8.required_axial_force_n(ad, mu, r_dp, r_es)
    t = s8.disc_spring_thickness_for_force_mm(f_nom, de, di, zeta, phi, fidelity=fidelity)
    jit = load_kernels()
    tab, lo, hi, inc_lo, inc_hi = s8.tolerance_rows()
    out = _table(len(ad), len(jit.CONE_SPRING_OUT))
    bad = np.zeros(len(ad), dtype=bool)
    jit.cone_spring_rows(f_nom, t, t ** 3, t ** 4, np.log(de / di), *cols[1:], fidelity == "screening",
                         _elastic_scale(), np.ascontiguousarray(lo, float), np.ascontiguousarray(hi, float),
                         np.ascontiguousarray(inc_lo, bool), np.ascontiguousarray(inc_hi, bool),
                         tab["force_tol_plus_pct"].to_numpy(float), tab["force_tol_minus_pct"].to_numpy(float), out,
                         bad)
    if bad.any():
        return s8.cone_spring(*args, **opts)
    return {k: out[:len(ad), c].reshape(shape) for c, k in enumerate(jit.CONE_SPRING_OUT)}


def plastic_wear(initial_deflection_mm, outer_diameter_mm, inner_diameter_mm, thickness_mm, cone_height_mm,
                 damper_pad_contact_area_mm2, damper_pad_mean_radius_mm, damper_pad_axial_height_mm,
                 endcap_spacer_contact_area_mm2, endcap_spacer_mean_radius_mm, endcap_spacer_axial_height_mm,
                 durability_theta_peak_to_peak_deg, durability_frequency_hz, durability_duration_h,
                 radial_damping_nm, *, k_wear_mm3_per_n_m, plastic_friction_coefficient, fidelity: str = "full",
                 time_points: int = 0, engine: str = "numpy", **kw) -> dict:
    """:func:`synth.model.friction_wear.plastic_wear` (the same arguments and values) on the ``engine``, with the
    wear constant and friction coefficient given (as the evaluator gives them).

    ``engine="numba"`` runs the compiled twin; the reference answers the wear history (``time_points > 0``), other
    materials or relaxations (``kw``) and any call with a row it refuses."""
    _check_engine(engine)
    args = (initial_deflection_mm, outer_diameter_mm, inner_diameter_mm, thickness_mm, cone_height_mm,
            damper_pad_contact_area_mm2, damper_pad_mean_radius_mm, damper_pad_axial_height_mm,
            endcap_spacer_contact_area_mm2, endcap_spacer_mean_radius_mm, endcap_spacer_axial_height_mm,
            durability_theta_peak_to_peak_deg, durability_frequency_hz, durability_duration_h, radial_damping_nm)
    opts = dict(k_wear_mm3_per_n_m=k_wear_mm3_per_n_m, plastic_friction_coefficient=plastic_friction_coefficient,
                fidelity=fidelity, time_points=time_points, **kw)
    if engine == "numpy" or kw or int(time_points) > 0 or fidelity not in s5.FIDELITIES:
        return s5.plastic_wear(*args, **opts)
    shape, cols = _columns(*args, k_wear_mm3_per_n_m, plastic_friction_coefficient)
    n = len(cols[0])
    jit = load_kernels()
    solver, callback = _addresses()
    t, de, di = cols[3], cols[1], cols[2]
    inputs = [t ** 3, t ** 4, np.log(de / di), *cols]
    keep, back = distinct_rows(inputs)   # the wear once per distinct row of the kernel's inputs
    if keep is not None:
        inputs = [x[keep] for x in inputs]
    m = len(inputs[0])
    out = _table(m, len(jit.PLASTIC_WEAR_OUT))
    bad = np.zeros(m, dtype=bool)
    jit.plastic_wear_rows(*inputs, fidelity == "screening", _elastic_scale(),
                          float(catalog.constant("cone_spring_relaxation_pct")),
                          float(catalog.constant("cone_spring_relaxation_time_h")),
                          float(catalog.constant("plastic_max_wear_fraction")),
                          int(catalog.constant("plastic_wear_secant_passes")), solver, callback, out, bad)
    if bad.any():
        return s5.plastic_wear(*args, **opts)
    if keep is not None:
        return {k: out[:m, c][back].reshape(shape) for c, k in enumerate(jit.PLASTIC_WEAR_OUT)}
    return {k: out[:n, c].reshape(shape) for c, k in enumerate(jit.PLASTIC_WEAR_OUT)}


#: the share of distinct rows above which :func:`distinct_rows` keeps every row (the gathers would cost more)
DISTINCT_SHARE = 0.9
def distinct_rows(columns: list) -> tuple:
    """``(keep, back)``: rows ``keep`` hold each distinct row of the float ``columns`` once (bit for bit: ``-0.0``
    and ``0.0`` differ, a NaN equals the same NaN) and ``row i == row keep[back[i]]``; ``(None, None)`` where
    more than :data:`DISTINCT_SHARE` of the rows are distinct. A row-by-row kernel (each output row a function of
    its input row alone) run on ``keep`` and gathered by ``back`` gives the values of running it on every row.
    One compiled pass (:func:`synth.kernels._axial_jit.distinct_rows`: a hash table of the rows' bits, every match
    compared in full).

    >>> keep, back = distinct_rows([np.array([1.0, 2.0, 1.0, 1.0]), np.array([0.0, 0.0, 0.0, -0.0])])
    >>> keep.tolist(), back.tolist()
    ([0, 1, 3], [0, 1, 0, 2])
    """
    n = len(columns[0]) if columns else 0
    if n < 2:
        return None, None
    jit = load_kernels()
    bits = tuple(np.ascontiguousarray(c, dtype=np.float64).view(np.uint64) for c in columns)
    keep, back = np.empty(n, np.int64), np.empty(n, np.int64)
    k = jit.distinct_rows(bits, keep, back)
    if k > DISTINCT_SHARE * n:
        return None, None
    return keep[:k], back
