"""Main-spring margins for many keys x many options: compiled kernels and their numpy twins (bulk screening).

In a design space a main-spring option is (material, wire, mean body
diameter: a row of the space's spring table); it sees the rest of the design
only through a **key**: the spring torque at nominal, the spring-housing
height, outer and inner diameter, and its application's inputs (stiffness,
torque tolerance, theta_pp, the installation and free-arm travels, whether the
durability test is given). Bulk screening needs, for many keys (across many
applications) x thousands of options, the margins of the registry's spring
group (:func:`synth.design.evaluate.spring`: :data:`MARGIN_NAMES`, the
non-advisory constraints of step 9, thesis eq. (64)-(93), figure 71):

(a) :func:`margins` -- every margin, ``(n_keys, n_options, len(checks()))``;
(b) :func:`first_feasible` -- per key, the first feasible option of a list
    in score order (options sorted by the objective), early exit, an optional
    score limit (branch and bound), and how many options were examined;
(c) :func:`max_min_margin` -- per key, the option with the largest smallest
    margin (the nearest design when none is feasible), skipping options an
    upper bound rules out;
(d) :func:`any_feasible` -- per key, whether some option is feasible.

Each takes ``engine="numba"`` (compiled loops over keys x options, no
allocation per pair; :mod:`synth.kernels._main_spring_scans_jit` over the pair physics of
:mod:`synth.kernels._main_spring_jit`) or
``engine="numpy"`` (the registry's group on blocks of keys x options, the
same early exits block by block): the benchmark compares both in one run
and the tests hold them equal to the registry path. Units as in
:mod:`synth.model.torsion_spring` (mm, N m, N m/deg, MPa, deg).

**Registry semantics.** A margin is :func:`synth.design.constraints.margin`
of the value and limit :func:`synth.design.evaluate.spring_values` gives
(the one mapping from the physics to the values; the numpy twin calls it and
:func:`synth.design.evaluate.finish`); ``spring_fatigue`` needs the durability
test (``fatigue_verified``): not verified, its margin is ``+inf`` and it never
makes an option infeasible; the travels and the torque tolerance are per key
(the applications' documented defaults where absent, :mod:`synth.design.applications`);
``spring_material_section`` is an option-only margin (0 for the options of
the space: a material not supplied in a wire section is not in the space).
A NaN margin fails (``-inf``), as in :func:`finish`. Feasible means every
margin ``>= -tol`` (the registry's :data:`~synth.design.constraints.FEAS_TOL`
by default).

**Exactness.** The quantities that depend on the option alone (second
moment, section modulus, index, curvature factor, the index and section
margins, :func:`spring_options`) or on the key alone (working angles,
torques, coil increments, housing limits, :func:`spring_keys`) are computed
once by the reference functions themselves; the kernel repeats only the
per-pair lines of ``main_spring_design`` and of ``margin`` in the same order
of operations, with the same constants
(:func:`synth.model.torsion_spring.main_spring_constants`, read once and
passed in as scalars). Margins then agree with the registry path to the
last bit in practice (tested to 1e-9 relative) and the verdicts are the same.

**Cost.** numba is imported on the first kernel call, not with this module:
the one-application path (``synth design``) never imports it. A process
that calls a kernel pays ``import numba`` once and, the first time ever, the
compilation (then cached on disk, ``cache=True``, beside the module); see
``docs/sections/kernels.md`` for the measured figures. ``parallel=True``
shares the keys among numba's threads (``prange``); it is off by default
because the bulk engine scales out over processes and numba's OpenMP layer
is not fork-safe.

Validity: the ranges of ``main_spring_design`` (positive stiffness and wire
sizes). :func:`spring_keys` and :func:`spring_options` refuse non-finite
inputs; :func:`keys_of_rows` (the evaluator's rows) lets a NaN through, whose
margins are then ``-inf`` as in the registry path.

Thesis case 3 (Tables 13-14: VDSiCr, mean diameter 44 mm, 0.0164 N m/deg,
1.56 N m, 8 % tolerance, theta_pp 16 deg, installation travel 28.6 deg,
housing 8.8 mm high), with the round 2.3 mm wire that reproduces its printed
2.18 coils (it prints 3.0 mm, ``docs/sections/torsion_spring.md``); the housing
diameters 48/30 mm are illustrative (the case does not print them). The
registry checks the installation stress at the upper torque tolerance:
``T_inst = 1.56 * 1.08 + 0.0164 * 28.6 = 2.1538 N m``, ``sigma = k_f T / Z =
1.040646 * 2153.8 / 1.194492 = 1876 MPa`` (the thesis tool prints 1626 MPa at
the lower tolerance), 6 % above the 1763.5 MPa limit; no option is feasible and
the 44 mm one is the nearest:

>>> import numpy as np
>>> opts = spring_options(E_mpa=206000, Rm_mpa=2004, sigma_y_mpa=1763.5, sigma_A0_mpa=701.4, b_mm=2.3, h_mm=2.3,
...                       round_wire=True, b_tol_mm=0.025, h_tol_mm=0.025, mbd_mm=[40.0, 44.0])
>>> keys = spring_keys(spring_torque_nominal_nm=1.56, housing_height_mm=8.8, housing_outer_diameter_mm=48.0,
...                    housing_inner_diameter_mm=30.0, stiffness_nm_per_deg=0.0164, torque_tolerance_pct=8,
...                    theta_pp_deg=16, dtheta_inst_nom_deg=28.6, dtheta_nom_free_arm_deg=30.0)
>>> m = margins(keys, opts)
>>> round(1763.5 * (1 - float(m[0, 1, 0]))), bool((m == margins(keys, opts, engine="numpy")).all())
(1876, True)
>>> first_feasible(keys, opts).index.tolist(), max_min_margin(keys, opts).index.tolist()
([-1], [1])
"""

from __future__ import annotations

import numpy as np

from synth import catalog
from synth.design.constraints import FEAS_TOL
from synth.design.settings import DEFAULT, Settings
from synth.errors import InputError, Problem
from synth.kernels.spring_tables import (ENGINES, MARGIN_NAMES, OPTION_FIELDS, SpringKeys, SpringOptions, check_engine,
                                         checks, compiled_covers, keys_of_rows, kernel_tables, load_kernels, load_rounds, load_scans, margins,
                                         near_above,
                                         numba_loaded, options_of_space, pair_margins, reference_margins,
                                         same_constants, spring_keys, spring_options)

__all__ = ["MARGIN_NAMES", "checks", "compiled_covers", "SpringOptions", "SpringKeys", "spring_options", "options_of_space", "spring_keys",
           "keys_of_rows", "margins", "near_above", "pair_margins", "reference_margins", "yield_thresholds", "first_feasible", "max_min_margin",
           "any_feasible", "FirstFeasible", "MaxMin", "CHUNK_KEYS", "numba_loaded", "load_kernels", "load_scans", "load_rounds", "FEAS_TOL",
           "ENGINES", "OPTION_FIELDS", "stage_round"]


# --------------------------------------------------------------------------------------- candidate lists


def _groups(n_keys: int, n_opt: int, candidates, key_group):
    """``(ptr, idx, key_group)``: each key's candidate options as a ragged list (CSR), int64."""
    if candidates is None:
        candidates = np.arange(n_opt)
    if isinstance(candidates, np.ndarray) or (len(candidates) and np.ndim(candidates[0]) == 0):
        lists = [np.asarray(candidates)]
    else:
        lists = [np.asarray(c) for c in candidates]
    for g, lst in enumerate(lists):
        if lst.size and (lst.dtype.kind not in "iu" or lst.ndim != 1 or lst.min() < 0 or lst.max() >= n_opt):
            raise InputError(Problem(f"candidates[{g}]", lst[:5].tolist(), f"a 1-D list of option indices in [0, {n_opt})"))
    ptr = np.zeros(len(lists) + 1, np.int64)
    ptr[1:] = np.cumsum([lst.size for lst in lists])
    idx = np.concatenate([lst.astype(np.int64) for lst in lists]) if lists else np.zeros(0, np.int64)
    if key_group is None:
        if len(lists) != 1:
            raise InputError(Problem("key_group", None, f"the candidate list (0..{len(lists) - 1}) of each key"))
        kg = np.zeros(n_keys, np.int64)
    else:
        kg = np.asarray(key_group).reshape(-1)
        if kg.size != n_keys or kg.dtype.kind not in "iu" or (n_keys and (kg.min() < 0 or kg.max() >= len(lists))):
            raise InputError(Problem("key_group", kg[:5].tolist(),
                                     f"{n_keys} integers in [0, {len(lists)}) (the candidate list of each key)"))
        kg = kg.astype(np.int64)
    return ptr, idx, kg


def _by_upper_bound(options: SpringOptions, ptr, idx):
    """Each group's candidates sorted by decreasing option upper bound (ties: list order); and their ranks."""
    grp = np.repeat(np.arange(len(ptr) - 1), np.diff(ptr))
    rank = np.arange(len(idx)) - ptr[grp]
    ub = options.upper_bound[idx]
    o = np.lexsort((rank, -ub, grp))
    return idx[o], ub[o], rank[o].astype(np.int64)


def _per_key(x, n, name, default):
    if x is None:
        return np.full(n, default, float)
    a = np.asarray(x, dtype=float).reshape(-1)
    if a.size == 1:
        a = np.full(n, a[0])
    if a.size != n or np.isnan(a).any():
        raise InputError(Problem(name, a[:5].tolist(), f"one number per key ({n})"))
    return a


class FirstFeasible(tuple):
    """``(index, visited)``: per key the chosen option (-1: none) and the options examined."""

    index = property(lambda self: self[0])
    visited = property(lambda self: self[1])


class MaxMin(tuple):
    """``(index, value, visited)``: per key the option with the largest smallest margin, that margin, the
    options examined."""

    index = property(lambda self: self[0])
    value = property(lambda self: self[1])
    visited = property(lambda self: self[2])


# --------------------------------------------------------------------------------------- (b) and (d)


def first_feasible(keys: SpringKeys, options: SpringOptions, order=None, *, key_group=None, score=None,
                   score_limit=None, tol: float = FEAS_TOL, engine: str = "numba",
                   parallel: bool = False, settings: Settings = DEFAULT) -> FirstFeasible:
    """(b) Per key, the first option of ``order`` whose margins are all ``>= -tol`` (early exit).

    ``order``: option indices in score order (e.g. ``np.argsort(cost, kind="stable")``), one list for every
    key, or a list of such lists with ``key_group[i]`` naming key ``i``'s (one list per application).
    Default: every option in index order. With ``score`` and ``score_limit`` (per key) a key's scan stops at
    the first candidate whose score exceeds its limit (the branch and bound of the bulk engine): ``score`` per
    option, or one array per list (aligned with it: an application's own scores). ``tol``: the registry's
    ``FEAS_TOL`` (its verdict) by default. A NaN margin fails.

    Returns :class:`FirstFeasible` ``(index, visited)``: ``index[i] = -1`` when no option qualifies;
    ``visited`` counts the options the kernel examined (numpy: the pairs evaluated, whole blocks).
    """
    engine = check_engine(engine, settings)
    n = len(keys)
    ptr, idx, kg = _groups(n, len(options), order, key_group)
    sc = _candidate_scores(score, ptr, idx, len(options))
    lim = _per_key(score_limit, n, "score_limit", np.inf)
    return _first_feasible(keys, options, ptr, idx, kg, sc, lim, float(tol), engine, parallel, settings)


def _candidate_scores(score, ptr, idx, n_opt) -> np.ndarray:
    """The score of every candidate (aligned with ``idx``): from one score per option or one array per list."""
    if score is None:
        return np.zeros(len(idx))
    if isinstance(score, np.ndarray) or (len(score) and np.ndim(score[0]) == 0):
        return _per_key(score, n_opt, "score", 0.0)[idx]
    parts = [np.asarray(x, dtype=float).reshape(-1) for x in score]
    sizes = np.diff(ptr)
    if len(parts) != len(sizes) or any(len(x) != m for x, m in zip(parts, sizes)):
        raise InputError(Problem("score", f"{len(parts)} arrays", f"one score per option ({n_opt}) or one array per "
                                 f"candidate list, as long as it ({sizes[:5].tolist()}...)"))
    out = np.concatenate(parts) if parts else np.zeros(0)
    if np.isnan(out).any():
        raise InputError(Problem("score", "NaN", "numbers"))
    return out


def _first_feasible(keys, options, ptr, idx, kg, sc, lim, tol, engine, parallel, settings) -> FirstFeasible:
    """:func:`first_feasible` on checked candidate lists (CSR ``ptr``, ``idx``, scores ``sc`` aligned with ``idx``;
    ``kg`` per key)."""
    same_constants(keys, options)
    n = len(keys)
    if engine == "numba":
        _, kt, ot, c = kernel_tables(keys, options)
        kperm, kptr, chunk_list = _chunks(kg, keys.derived["t_inst"])
        pick, visited, work = np.empty(n, np.int64), np.empty(n, np.int64), np.empty(n, np.int64)
        scans = load_scans()
        scan = scans.first_feasible_scan_parallel if parallel else scans.first_feasible_scan
        scan(kt, ot, c, float(tol), yield_thresholds(options, tol), ptr, idx, chunk_list, kptr, kperm,
             np.ascontiguousarray(sc, dtype=float), lim, pick, visited, work)
        return FirstFeasible((pick, visited))
    return FirstFeasible(_first_feasible_numpy(keys, options, ptr, idx, kg, sc, lim, tol, settings))


#: keys per chunk of the score-order scan: the keys of one candidate list walk it together, up to this many
#: (numerics, not physics: any value gives the same answer; chunks are the unit of ``parallel=True``)
CHUNK_KEYS = 128


def _chunks(key_group, t_inst):
    """Keys sorted by candidate list, then installation torque; chunks of at most :data:`CHUNK_KEYS` keys of one
    list: ``(kperm, kptr, chunk_list)``."""
    n = len(key_group)
    kperm = np.lexsort((t_inst, key_group)).astype(np.int64)
    g = key_group[kperm]
    first = np.ones(n, bool)
    first[1:] = g[1:] != g[:-1]
    start = np.maximum.accumulate(np.where(first, np.arange(n), 0))
    head = np.flatnonzero((np.arange(n) - start) % CHUNK_KEYS == 0)
    kptr = np.append(head, n).astype(np.int64)
    return kperm, kptr, g[head].astype(np.int64)


def _ordinal(x):
    """Doubles as integers in the same order (-0.0 and 0.0 both 0)."""
    u = np.asarray(x, dtype=float).view(np.int64)
    return np.where(u >= 0, u, -(u & np.int64(0x7FFFFFFFFFFFFFFF)))


def _from_ordinal(k):
    return np.where(k >= 0, k, (-k) | np.int64(-0x8000000000000000)).view(np.float64)


def yield_thresholds(options: SpringOptions, tol: float = FEAS_TOL) -> np.ndarray:
    """Per option, the largest installation torque ``T_inst`` [N m] whose yield margin (eq. 72-77) is ``>= -tol``.

    The margin ``(sigma_y - k_f T 1000 / Z) / |sigma_y|`` is computed by a chain
    of operations each monotone in ``T`` (IEEE rounding keeps monotonicity),
    so the check passes exactly for ``T_inst <= threshold``; the threshold is
    found by bisection on the ordered doubles (64 steps), evaluating the very
    expression of the kernels and the reference. Memoised per ``tol``.
    """
    memo = options._table.setdefault("t_max", {})
    if tol not in memo:
        d = options.derived
        kf, z, sy, sc = d["kf"], d["z"], d["sy"], d["sy_scale"]
        a = _ordinal(np.full(len(options), -np.inf))  # passes at -inf, fails at +inf (finite option data)
        b = _ordinal(np.full(len(options), np.inf))
        while True:
            mid = (a >> 1) + (b >> 1) + (a & b & 1)  # floor((a + b) / 2) without overflow
            todo = mid > a
            if not todo.any():
                break
            t = _from_ordinal(mid)
            with np.errstate(over="ignore", invalid="ignore"):
                ok = (sy - kf * t * 1000.0 / z) / sc >= -tol
            a = np.where(todo & ok, mid, a)
            b = np.where(todo & ~ok, mid, b)
        memo[tol] = np.ascontiguousarray(_from_ordinal(a))
    return memo[tol]


def _blocks(length):
    """Block boundaries of the numpy scans: ``bulk_spring_first_block`` growing by ``bulk_spring_block_growth``."""
    pos, block = 0, int(catalog.constant("bulk_spring_first_block"))
    growth = max(int(catalog.constant("bulk_spring_block_growth")), 1)
    while pos < length:
        yield pos, min(pos + block, length)
        pos += block
        block *= growth


def _keys_by_group(kg, n_groups):
    """The keys of each group, in key order (one sort, not one scan of every key per group)."""
    order = np.argsort(kg, kind="stable")
    return np.split(order, np.cumsum(np.bincount(kg, minlength=n_groups))[:-1])


def _first_feasible_numpy(keys, options, ptr, idx, kg, score, limit, tol, settings):
    """(b) in numpy: each list in blocks for the keys still looking, the registry path on every pair of a block.

    Options that no key of the list can pass are left out first, exactly: an option-only margin (index range,
    material section) below ``-tol``, or an installation-torque threshold (:func:`yield_thresholds`) below the
    smallest installation torque of the list's keys. Both bound the margins from above under any design rule (a
    rule tightens a limit or asks for more margin); the threshold is the thesis's limit basis's, so another basis
    skips it."""
    pick, visited = np.full(len(keys), -1, np.int64), np.zeros(len(keys), np.int64)
    t_max = (yield_thresholds(options, tol) if settings.spring_limit_basis == "thesis"
             else np.full(len(options), np.inf))
    t_inst = keys.derived["t_inst"]
    for g, kk in enumerate(_keys_by_group(kg, len(ptr) - 1)):
        lst = idx[ptr[g]:ptr[g + 1]]
        if not len(kk) or not len(lst):
            continue
        over = score[ptr[g]:ptr[g + 1]][None, :] > limit[kk][:, None]
        stop = np.where(over.any(axis=1), np.argmax(over, axis=1), len(lst))  # scan length of each key
        with np.errstate(invalid="ignore"):
            t_lo = np.nanmin(t_inst[kk]) if np.isfinite(t_inst[kk]).any() else np.inf
        can = np.flatnonzero((options.upper_bound[lst] >= -tol) & (t_max[lst] >= t_lo))  # positions in lst
        active = stop > 0
        for lo, hi in _blocks(len(can)):
            a = np.flatnonzero(active)
            if not len(a):
                break
            pos = can[lo:hi]
            m = reference_margins(keys, options, kk[a], lst[pos], settings=settings)
            ok = np.all(m >= -tol, axis=2) & (pos[None, :] < stop[a][:, None])
            visited[kk[a]] += ((pos[None, :] < stop[a][:, None])).sum(axis=1)
            has = ok.any(axis=1)
            pick[kk[a[has]]] = lst[pos[np.argmax(ok[has], axis=1)]]
            active[a[has]] = False
            active &= (stop > (pos[-1] + 1)) if len(pos) else False
    return pick, visited


def any_feasible(keys: SpringKeys, options: SpringOptions, candidates=None, *, key_group=None, tol: float = FEAS_TOL,
                 engine: str = "numba", parallel: bool = False, settings: Settings = DEFAULT) -> FirstFeasible:
    """(d) Per key, whether some option of ``candidates`` (lists as in :func:`first_feasible`) is feasible.

    Options whose index margins fail cannot be feasible for any key and are
    not scanned; the others are scanned in the order given (the answer does
    not depend on it) and a key stops at its first feasible option. The cost
    order of the bulk engine is a good order: cheap springs come first and
    the yield threshold settles them for most keys at once (2.5x faster than
    decreasing index margins on the generated portfolio). Returns
    :class:`FirstFeasible` ``(found, visited)`` with ``found`` boolean.
    """
    engine = check_engine(engine, settings)
    ptr, idx, kg = _groups(len(keys), len(options), candidates, key_group)
    keep = options.upper_bound[idx] >= -tol
    grp = np.repeat(np.arange(len(ptr) - 1), np.diff(ptr))[keep]
    ptr_k = np.zeros_like(ptr)
    ptr_k[1:] = np.cumsum(np.bincount(grp, minlength=len(ptr) - 1))
    r = _first_feasible(keys, options, ptr_k, idx[keep], kg, np.zeros(int(keep.sum())), np.full(len(keys), np.inf),
                        float(tol), engine, parallel, settings)
    return FirstFeasible((r.index >= 0, r.visited))


# --------------------------------------------------------------------------------------- (c)


def max_min_margin(keys: SpringKeys, options: SpringOptions, candidates=None, *, key_group=None, cap=None,
                   engine: str = "numba", parallel: bool = False, settings: Settings = DEFAULT) -> MaxMin:
    """(c) Per key, the option of ``candidates`` with the largest smallest margin (NaN read as -inf).

    Ties go to the option listed first (lists as in :func:`first_feasible`;
    default every option, so the lowest index, as ``numpy.argmax``). The
    options are scanned in decreasing order of their index margins, a bound
    of the smallest margin that holds for every key: the scan stops when the
    bound falls below the best value found, and an option's margins stop
    being evaluated once their minimum is below it. ``cap`` (per key): the
    scan also stops once the best value reaches it (the caller needs no more,
    e.g. the core's own margin in a nearest-design search); then only
    ``min(value, cap)`` is defined. The keys of one list walk it together in
    increasing installation torque (numba): once a key's yield margin for an
    option is below the smallest best value of the keys still looking, the
    option is settled for the keys after it too.

    Returns :class:`MaxMin` ``(index, value, visited)``; ``index = -1`` for a
    key with no candidate; ``visited``: the pairs whose margins were
    evaluated (at least the yield margin; numpy: whole blocks).
    """
    engine = check_engine(engine, settings)
    same_constants(keys, options)
    n = len(keys)
    ptr, idx, kg = _groups(n, len(options), candidates, key_group)
    idx_s, ub_s, rank_s = _by_upper_bound(options, ptr, idx)
    cp = _per_key(cap, n, "cap", np.inf)
    if engine == "numba":
        _, kt, ot, c = kernel_tables(keys, options)
        kperm, kptr, chunk_list = _chunks(kg, keys.derived["t_inst"])
        pick, value, visited = np.empty(n, np.int64), np.empty(n), np.empty(n, np.int64)
        best_rank, work = np.empty(n, np.int64), np.empty(n, np.int64)
        scans = load_scans()
        scan = scans.max_min_scan_parallel if parallel else scans.max_min_scan
        scan(kt, ot, c, ptr, idx_s, ub_s, rank_s, chunk_list, kptr, kperm, cp, pick, value, visited, best_rank, work)
        return MaxMin((pick, value, visited))
    return MaxMin(_max_min_numpy(keys, options, ptr, idx_s, ub_s, rank_s, kg, cp, settings))


def _max_min_numpy(keys, options, ptr, idx, ub, rank, kg, cap, settings):
    n = len(keys)
    pick, value, visited = np.full(n, -1, np.int64), np.full(n, -np.inf), np.zeros(n, np.int64)
    best_rank = np.full(n, np.iinfo(np.int64).max)
    for g, kk in enumerate(_keys_by_group(kg, len(ptr) - 1)):
        lo_g, hi_g = ptr[g], ptr[g + 1]
        active = np.ones(len(kk), bool)
        for lo, hi in _blocks(hi_g - lo_g):
            a = np.flatnonzero(active)
            if not len(a):
                break
            ka, pos = kk[a], np.arange(lo_g + lo, lo_g + hi)
            m = reference_margins(keys, options, ka, idx[pos], settings=settings)
            v = np.min(np.where(np.isnan(m), -np.inf, m), axis=2)
            visited[ka] += hi - lo
            vmax = v.max(axis=1)
            rb = np.where(v == vmax[:, None], rank[pos][None, :], np.iinfo(np.int64).max).min(axis=1)
            upd = (vmax > value[ka]) | ((vmax == value[ka]) & (rb < best_rank[ka]))
            ku = ka[upd]
            value[ku], best_rank[ku] = vmax[upd], rb[upd]
            pick[ku] = idx[pos[np.argmax(rank[pos][None, :] == rb[upd][:, None], axis=1)]]  # ranks are unique in a list
            active[a] = ~(value[ka] >= cap[ka])
            if lo_g + hi < hi_g:
                active[a] &= ~(ub[lo_g + hi] < value[ka])
    return pick, value, visited


# --------------------------------------------------------------------------------------- window pairs


def _window_args(groups, lo, hi, mbd, exclude, exclude_row, need, need_row) -> tuple:
    """The arrays of :func:`window_pairs` and :func:`stage_round` as their kernels take them (a condition not given:
    a one-row table its rows ``-1`` never read)."""
    groups = np.ascontiguousarray(groups, dtype=np.int64)
    lo, hi, mbd = (np.ascontiguousarray(x, dtype=float) for x in (lo, hi, mbd))
    none_t, none_r = np.zeros((1, len(mbd)), bool), np.full(len(lo), -1, np.int64)
    ex = none_t if exclude is None else np.ascontiguousarray(exclude, dtype=bool)
    er = none_r if exclude is None else np.ascontiguousarray(exclude_row, dtype=np.int64)
    nd = none_t if need is None else np.ascontiguousarray(need, dtype=bool)
    nr = none_r if need is None else np.ascontiguousarray(need_row, dtype=np.int64)
    return groups, lo, hi, mbd, ex, er, nd, nr


def window_pairs(groups, lo, hi, mbd, *, exclude=None, exclude_row=None, need=None, need_row=None,
                 limit: int = 100_000):
    """Blocks ``(g, o)`` of the candidate pairs of ``groups`` (in that order) x options ``o`` ascending: the option's
    mean body diameter ``mbd[o]`` in the group's window ``[lo[g], hi[g]]`` (:func:`synth.design.space.spring_window`),
    ``exclude[exclude_row[g], o]`` false and ``need[need_row[g], o]`` true (a row ``-1``, or no table: no
    condition). One compiled pass per block of about ``limit`` pairs (whole groups), nothing of size groups x
    options; the pairs are those of ``numpy.nonzero`` of the window mask with the conditions, in its order.

    >>> [(g.tolist(), o.tolist()) for g, o in window_pairs(np.array([1, 0]), np.array([1.0, 2.0]),
    ...                                                     np.array([2.0, 3.0]), np.array([3.0, 1.5, 2.0]))]
    [([1, 1, 0, 0], [0, 2, 1, 2])]
    """
    rounds = load_rounds()
    groups, lo, hi, mbd, ex, er, nd, nr = _window_args(groups, lo, hi, mbd, exclude, exclude_row, need, need_row)
    limit = max(int(limit), 1)
    out_g, out_o = np.empty(limit + len(mbd), np.int64), np.empty(limit + len(mbd), np.int64)
    start = 0
    while start < len(groups):
        n, start = rounds.window_pairs(groups, lo, hi, mbd, ex, er, nd, nr, start, limit, out_g, out_o)
        if n:
            yield out_g[:n].copy(), out_o[:n].copy()


def stage_round(groups, lo, hi, mbd, keys: SpringKeys, key_of, options: SpringOptions, opt_of, cols, bind, *,
                no_binding: int, finite, line, survive, failed, best, best_b, exclude=None, exclude_row=None,
                need=None, need_row=None, tol: float = FEAS_TOL) -> int:
    """One round of the platform producer's main-spring stages (:func:`synth.platform.producer._spring`) in one
    compiled pass, nothing of the size of its pairs: the pairs :func:`window_pairs` gives (``groups`` x options
    ``o``, the same conditions and order), each of key ``key_of[g]`` x option row ``opt_of[o]`` judged by the
    smallest of its margins ``cols`` (column numbers of :func:`checks`, first of ties) with the binding ``bind[c]``
    (``no_binding`` where that margin is ``+inf``), and recorded in ``survive``, ``failed``, ``best`` and
    ``best_b`` (updated in place) as ``record_stage`` records them. The margins are the doubles of
    :func:`pair_margins` (the compiled engine: the caller runs this only where it covers the registry's checks).
    Returns the pairs evaluated."""
    same_constants(keys, options)
    _, kt, ot, c = kernel_tables(keys, options)
    groups, lo, hi, mbd, ex, er, nd, nr = _window_args(groups, lo, hi, mbd, exclude, exclude_row, need, need_row)
    return int(load_rounds().stage_round(groups, lo, hi, mbd, sorted_runs(mbd), ex, er, nd, nr, np.ascontiguousarray(key_of, dtype=np.int64),
                                         np.ascontiguousarray(opt_of, dtype=np.int64), kt, ot, c,
                                         np.ascontiguousarray(cols, dtype=np.int64), np.ascontiguousarray(bind, dtype=np.int64),
                                         int(no_binding), float(tol), finite, line, survive, failed, best, best_b))


def sorted_runs(mbd) -> np.ndarray:
    """The starts of the runs of non-decreasing values of ``mbd`` and ``len(mbd)`` (int64): within a run a window
    ``[lo, hi]`` is a range found by bisection. A NaN anywhere (admitted by no window) makes every option a run of
    its own: the plain test, option by option.

    >>> sorted_runs(np.array([20.0, 21.0, 21.0, 20.0, 22.0])).tolist()
    [0, 3, 5]
    """
    mbd = np.asarray(mbd, dtype=float)
    if np.isnan(mbd).any():
        return np.arange(len(mbd) + 1, dtype=np.int64)
    return np.r_[0, np.flatnonzero(mbd[1:] < mbd[:-1]) + 1, len(mbd)].astype(np.int64)
