"""numba kernels of the main-spring margins (thesis step 9): the pair physics and the margin tables; imported only
through :mod:`synth.kernels.spring_tables`' loaders.

This module imports numba at import time, so nothing imports it except the
lazy loaders of :mod:`synth.kernels.spring_tables` (the one-application path
never pays for numba). Every arithmetic line repeats one line of
:func:`synth.model.torsion_spring.main_spring_design` and of the registry's
:func:`synth.design.constraints.margin`, in the same order of operations, so
the margins are the registry's spring-group margins
(:func:`synth.design.evaluate.spring`) to the last bit in practice; the
quantities that depend on the option alone (second moment, section modulus,
curvature factor, the index and material-section margins) or on the key alone
(working angles, torques, coil increments, housing limits, whether the
fatigue check is verified) are computed beforehand by the reference functions
themselves and arrive here as the columns of two tables (``opts[j, O_*]``,
``keys[i, K_*]``).

The per-pair physics (:func:`yield_margin`, :func:`fatigue_margin`, :func:`coils`, :func:`gap_margin`,
:func:`contact_margins`, :func:`geometry_margins`, :func:`pair_margins` and the early-exit forms
:func:`pair_feasible_past_yield`, :func:`min_margin_past_yield`) is written here once; the scans
(:mod:`synth.kernels._main_spring_scans_jit`) and the platform's stage rounds
(:mod:`synth.kernels._main_spring_rounds_jit`) call it. Tables (loops over keys x options, no allocation per pair):

* :func:`margins_table` -- every margin, ``out[i, j, m]`` (:func:`margins_table_parallel`: over numba's threads);
* :func:`near_table_above` -- the near figures of the pairs whose cheap margins reach a floor;
* :func:`margins_pairs` -- the margins of listed pairs.
"""

from __future__ import annotations

import numpy as np
from numba import njit, prange

from synth.kernels._ieee import maximum as _maximum, minimum as _minimum
from synth.kernels.numba_setup import announce_compiles

announce_compiles()  # a line on stderr when this process compiles a kernel (synth.kernels.numba_setup)

#: columns of the option table (``spring_options`` computes them by name; the kernels read them by number)
OPTION_COLUMNS = ("ei", "mbd", "kf", "z", "rm", "sa0", "sy", "sy_scale", "h", "h_tol", "bb", "b_scale", "idx_min",
                  "idx_max", "sec", "ub")
#: columns of the key table (``spring_keys``)
KEY_COLUMNS = ("k180", "t_plus", "t_minus", "t_inst", "inc_inst", "inc_free_arm", "inc_nom", "height", "outer_min",
               "outer_scale", "inner_max", "inner_scale", "winding", "fatigue")
#: the scalar constants
CONST_NAMES = ("mbd_tol", "sf_min", "sf_scale", "min_gap")
(O_EI, O_MBD, O_KF, O_Z, O_RM, O_SA0, O_SY, O_SY_SCALE, O_H, O_H_TOL, O_BB, O_B_SCALE, O_IDX_MIN,
 O_IDX_MAX, O_SEC, O_UB) = range(len(OPTION_COLUMNS))
(K_K180, K_T_PLUS, K_T_MINUS, K_T_INST, K_INC_INST, K_INC_FREE_ARM, K_INC_NOM, K_HEIGHT, K_OUTER_MIN, K_OUTER_SCALE,
 K_INNER_MAX, K_INNER_SCALE, K_WINDING, K_FATIGUE) = range(len(KEY_COLUMNS))
C_MBD_TOL, C_SF_MIN, C_SF_SCALE, C_MIN_GAP = range(len(CONST_NAMES))
#: margins of ``margins_table``, in the registry's order of the spring group (``torsion_spring.MARGIN_NAMES``)
M_YIELD, M_SECTION, M_FATIGUE, M_OUTER, M_INNER, M_GAP, M_IDX_MIN, M_IDX_MAX = range(8)
N_MARGINS = 8


@njit(cache=True, error_model="numpy")
def yield_margin(keys, i, opts, j):
    """eq. (72)-(77): ``(sigma_y - k_f T_inst 1000 / Z) / |sigma_y|``."""
    s_inst = opts[j, O_KF] * keys[i, K_T_INST] * 1000.0 / opts[j, O_Z]
    return (opts[j, O_SY] - s_inst) / opts[j, O_SY_SCALE]


@njit(cache=True, error_model="numpy")
def fatigue_margin(keys, i, opts, j, cst):
    """Figure 71: Smith-Goodman safety factor of the +-theta_pp/2 swing against its minimum; +inf where the
    check is not verified (no durability test: the registry's ``needs``)."""
    if keys[i, K_FATIGUE] == 0.0:
        return np.inf
    kf, z = opts[j, O_KF], opts[j, O_Z]
    smax = kf * keys[i, K_T_PLUS] * 1000.0 / z
    smin = kf * keys[i, K_T_MINUS] * 1000.0 / z
    sa = abs(smax - smin) / 2.0
    sm = (smax + smin) / 2.0
    denom = sa / opts[j, O_SA0] + _maximum(sm, 0.0) / opts[j, O_RM]
    sf_g = 1.0 / denom if denom > 0 else np.inf
    peak = _maximum(abs(smax), abs(smin))
    sf_y = opts[j, O_SY] / peak if peak > 0 else np.inf
    sf = _minimum(sf_g, sf_y)
    return (sf - cst[C_SF_MIN]) / cst[C_SF_SCALE]


@njit(cache=True, error_model="numpy")
def coils(keys, i, opts, j):
    """eq. (64)-(65), (78)-(79): active coils in the free state and with the hooks at installation, free arm and
    nominal (winding adds theta/360, unwinding removes it; at least 1e-6)."""
    n_a = opts[j, O_EI] / (keys[i, K_K180] * opts[j, O_MBD])
    c_inst = _maximum(n_a + keys[i, K_INC_INST], 1e-6)
    c_free_arm = _maximum(n_a + keys[i, K_INC_FREE_ARM], 1e-6)
    c_nom = _maximum(n_a + keys[i, K_INC_NOM], 1e-6)
    return n_a, c_inst, c_free_arm, c_nom


@njit(cache=True, error_model="numpy")
def gap_margin(keys, i, opts, j, cst, c_inst, c_free_arm, c_nom):
    """eq. (89)-(93): coil gap in the worst condition (most coils), per axial wire size."""
    n_worst = _maximum(_maximum(c_inst, c_free_arm), c_nom)
    bb = opts[j, O_BB]
    gap = (keys[i, K_HEIGHT] - bb) / _maximum(n_worst, 1e-9) - bb
    return (gap - cst[C_MIN_GAP]) / opts[j, O_B_SCALE]


@njit(cache=True, error_model="numpy")
def contact_margins(keys, i, opts, j, cst, n_a, c_inst):
    """eq. (80)-(88): outer contact (largest diameter) and inner contact (smallest diameter) with the housing."""
    mbd = opts[j, O_MBD]
    d_free = mbd * n_a / _maximum(_maximum(n_a, 1e-6), 1e-9)                        # eq. 80, free state
    d_inst = mbd * n_a / _maximum(c_inst, 1e-9)
    if keys[i, K_WINDING] != 0.0:
        big, small = d_free, d_inst
    else:
        big, small = d_inst, d_free
    mbd_tol = cst[C_MBD_TOL]
    d_out = big + mbd_tol + opts[j, O_H] + opts[j, O_H_TOL]                          # eq. 83-84
    d_in = small - mbd_tol - opts[j, O_H] - opts[j, O_H_TOL]                         # eq. 87-88
    m_out = (keys[i, K_OUTER_MIN] - d_out) / keys[i, K_OUTER_SCALE]                   # eq. 81
    m_in = (d_in - keys[i, K_INNER_MAX]) / keys[i, K_INNER_SCALE]                     # eq. 85 (corrected)
    return m_out, m_in


@njit(cache=True, error_model="numpy")
def geometry_margins(keys, i, opts, j, cst):
    """Outer contact, inner contact and coil-gap margins of key ``i`` x option ``j``."""
    n_a, c_inst, c_free_arm, c_nom = coils(keys, i, opts, j)
    m_out, m_in = contact_margins(keys, i, opts, j, cst, n_a, c_inst)
    return m_out, m_in, gap_margin(keys, i, opts, j, cst, c_inst, c_free_arm, c_nom)


@njit(cache=True, error_model="numpy")
def pair_feasible_past_yield(keys, i, opts, j, cst, tol):
    """Whether the coil-gap, fatigue and contact margins of a pair that passes the index and yield checks are
    all ``>= -tol`` (most selective first, early exit; NaN fails). In the generated portfolios the yield check
    rejects about 60 % of the options within the index range, and the coil gap about 90 % of the rest."""
    n_a, c_inst, c_free_arm, c_nom = coils(keys, i, opts, j)
    if not (gap_margin(keys, i, opts, j, cst, c_inst, c_free_arm, c_nom) >= -tol):
        return False
    if not (fatigue_margin(keys, i, opts, j, cst) >= -tol):
        return False
    m_out, m_in = contact_margins(keys, i, opts, j, cst, n_a, c_inst)
    return m_out >= -tol and m_in >= -tol


@njit(cache=True, error_model="numpy")
def clean_min(a, b):
    """``min(a, b)`` with NaN read as -inf (as the optimiser's ``_clean``)."""
    if b != b:
        return -np.inf
    return b if b < a else a


@njit(cache=True, error_model="numpy")
def min_margin_past_yield(keys, i, opts, j, cst, best, m):
    """Smallest margin of key ``i`` x option ``j`` (NaN as -inf) given ``m``, the minimum of its index and
    yield margins; returns early once it is below ``best`` (the caller then only needs to know it cannot win)."""
    n_a, c_inst, c_free_arm, c_nom = coils(keys, i, opts, j)
    m = clean_min(m, gap_margin(keys, i, opts, j, cst, c_inst, c_free_arm, c_nom))
    if m < best:
        return m
    m = clean_min(m, fatigue_margin(keys, i, opts, j, cst))
    if m < best:
        return m
    m_out, m_in = contact_margins(keys, i, opts, j, cst, n_a, c_inst)
    return clean_min(clean_min(m, m_out), m_in)


@njit(cache=True, error_model="numpy")
def as_registry(m):
    """A margin as the registry keeps it: NaN is -inf (infeasible, never silently kept)."""
    return -np.inf if m != m else m


@njit(cache=True, error_model="numpy")
def option_margin(opts, j, c):
    """The option-only margin ``c`` (``M_SECTION``, ``M_IDX_MIN`` or ``M_IDX_MAX``: the material section and the
    spring index range, computed beforehand per option) of option ``j``, as the registry keeps it."""
    return as_registry(opts[j, O_SEC if c == M_SECTION else (O_IDX_MIN if c == M_IDX_MIN else O_IDX_MAX)])


@njit(cache=True, error_model="numpy")
def pair_margins(keys, i, opts, j, cst, row):
    """The eight margins of key ``i`` x option ``j`` into ``row`` (order of ``MARGIN_NAMES``)."""
    row[M_YIELD] = as_registry(yield_margin(keys, i, opts, j))
    row[M_SECTION] = option_margin(opts, j, M_SECTION)
    row[M_FATIGUE] = as_registry(fatigue_margin(keys, i, opts, j, cst))
    m_out, m_in, m_gap = geometry_margins(keys, i, opts, j, cst)
    row[M_OUTER] = as_registry(m_out)
    row[M_INNER] = as_registry(m_in)
    row[M_GAP] = as_registry(m_gap)
    row[M_IDX_MIN] = option_margin(opts, j, M_IDX_MIN)
    row[M_IDX_MAX] = option_margin(opts, j, M_IDX_MAX)


@njit(cache=True, error_model="numpy")
def _margins_row(keys, i, opts, cst, out):
    for j in range(opts.shape[0]):
        pair_margins(keys, i, opts, j, cst, out[i, j])


@njit(cache=True, error_model="numpy")
def margins_pairs(keys, opts, cst, ki, oj, out):
    """(a) for listed pairs: ``out[p, :]`` = the eight margins of key ``ki[p]`` x option ``oj[p]``."""
    for p in range(ki.shape[0]):
        pair_margins(keys, ki[p], opts, oj[p], cst, out[p])


@njit(cache=True, error_model="numpy")
def margins_table(keys, opts, cst, out):
    """(a) ``out[i, j, :]`` = the eight margins of key ``i`` x option ``j`` (order of ``MARGIN_NAMES``)."""
    for i in range(keys.shape[0]):
        _margins_row(keys, i, opts, cst, out)


@njit(cache=True, error_model="numpy")
def near_table_above(keys, opts, cst, floor, tol, low, second, failing):
    """(a) the near figures (:func:`synth.design.combine.near_figures`) of the pairs that may reach ``floor``:
    ``low[i, j]`` the smallest of key ``i`` x option ``j``'s eight margins, ``second[i, j]`` the second smallest
    (the second of the sorted eight) and ``failing[i, j]`` how many are below ``-tol``; unless its yield margin or
    its option-only bound (index, section) is below ``floor``: then ``low[i, j]`` is that one (an upper bound of
    the smallest margin, below ``floor``) and ``second``, ``failing`` are not written. The margins are no NaN
    (:func:`as_registry`), so the figures are those of the sorted row."""
    row = np.empty(N_MARGINS)
    for i in range(keys.shape[0]):
        for j in range(opts.shape[0]):
            m = min(as_registry(yield_margin(keys, i, opts, j)), opts[j, O_UB])
            if m < floor:
                low[i, j] = m
                continue
            pair_margins(keys, i, opts, j, cst, row)
            a, b, f = np.inf, np.inf, 0
            for c in range(N_MARGINS):
                v = row[c]
                if v < a:
                    b = a
                    a = v
                elif v < b:
                    b = v
                if v < -tol:
                    f += 1
            low[i, j] = a
            second[i, j] = b
            failing[i, j] = f


@njit(cache=True, error_model="numpy", parallel=True)
def margins_table_parallel(keys, opts, cst, out):
    """:func:`margins_table` with the keys shared among numba's threads."""
    for i in prange(keys.shape[0]):
        _margins_row(keys, i, opts, cst, out)
