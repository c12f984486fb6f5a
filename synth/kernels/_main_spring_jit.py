"""numba kernels of the main-spring margins (thesis step 9); imported only by :mod:`synth.kernels.main_spring`.

This module imports numba at import time, so nothing imports it except the
lazy loader of :mod:`synth.kernels.main_spring` (the one-application path
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

Kernels (loops over keys x options, no allocation per pair):

* :func:`margins_table` -- every margin, ``out[i, j, m]``;
* :func:`first_feasible_scan` -- per key, the first feasible option of its
  group's list (score order), with early exit and a score limit; the keys of
  a list walk it together, and an exact threshold of the installation torque
  per option (``t_max``, computed by the caller) settles the yield check
  for all of them at once;
* :func:`max_min_scan` -- per key, the option of its group's list with the
  largest smallest margin, scanning in decreasing order of the option-only
  upper bound (index margins) and stopping when that bound, or the key's cap,
  says no later option can win; the keys of a list walk it together in
  increasing installation torque, so one yield margin below the smallest
  best value settles an option for the rest of them;
* :func:`list_order` -- per application, whether a spring list keeps its score order at its stiffness, and its
  first score (the bulk engine's score-ordered lists, :meth:`synth.optimise.batch.Batch._spring_app_lists`);
* :func:`window_pairs` -- the (group, option) pairs of many groups whose option lies in the group's housing window
  and passes a per-group row of two boolean tables, flat (``numpy.nonzero``'s order), a block at a time (the
  platform producer's main-spring rounds, :func:`synth.platform.producer._spring`);
* :func:`record_stage` -- a block of those rounds' verdicts written into the survivor and failed tables and the
  groups' best margins, one pass;
* :func:`stage_round` -- a whole round of those stages in one pass (the window pairs, their margins, the stage's
  smallest margin and the record), nothing of the size of the pairs: the producer's path where the compiled
  kernels cover the registry's spring checks (``window_pairs`` and ``record_stage`` remain the numpy twin's).
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
def _yield_margin(keys, i, opts, j):
    """eq. (72)-(77): ``(sigma_y - k_f T_inst 1000 / Z) / |sigma_y|``."""
    s_inst = opts[j, O_KF] * keys[i, K_T_INST] * 1000.0 / opts[j, O_Z]
    return (opts[j, O_SY] - s_inst) / opts[j, O_SY_SCALE]


@njit(cache=True, error_model="numpy")
def _fatigue_margin(keys, i, opts, j, cst):
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
def _coils(keys, i, opts, j):
    """eq. (64)-(65), (78)-(79): active coils in the free state and with the hooks at installation, free arm and
    nominal (winding adds theta/360, unwinding removes it; at least 1e-6)."""
    n_a = opts[j, O_EI] / (keys[i, K_K180] * opts[j, O_MBD])
    c_inst = _maximum(n_a + keys[i, K_INC_INST], 1e-6)
    c_free_arm = _maximum(n_a + keys[i, K_INC_FREE_ARM], 1e-6)
    c_nom = _maximum(n_a + keys[i, K_INC_NOM], 1e-6)
    return n_a, c_inst, c_free_arm, c_nom


@njit(cache=True, error_model="numpy")
def _gap_margin(keys, i, opts, j, cst, c_inst, c_free_arm, c_nom):
    """eq. (89)-(93): coil gap in the worst condition (most coils), per axial wire size."""
    n_worst = _maximum(_maximum(c_inst, c_free_arm), c_nom)
    bb = opts[j, O_BB]
    gap = (keys[i, K_HEIGHT] - bb) / _maximum(n_worst, 1e-9) - bb
    return (gap - cst[C_MIN_GAP]) / opts[j, O_B_SCALE]


@njit(cache=True, error_model="numpy")
def _contact_margins(keys, i, opts, j, cst, n_a, c_inst):
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
def _geometry_margins(keys, i, opts, j, cst):
    """Outer contact, inner contact and coil-gap margins of key ``i`` x option ``j``."""
    n_a, c_inst, c_free_arm, c_nom = _coils(keys, i, opts, j)
    m_out, m_in = _contact_margins(keys, i, opts, j, cst, n_a, c_inst)
    return m_out, m_in, _gap_margin(keys, i, opts, j, cst, c_inst, c_free_arm, c_nom)


@njit(cache=True, error_model="numpy")
def _pair_feasible_past_yield(keys, i, opts, j, cst, tol):
    """Whether the coil-gap, fatigue and contact margins of a pair that passes the index and yield checks are
    all ``>= -tol`` (most selective first, early exit; NaN fails). In the generated portfolios the yield check
    rejects about 60 % of the options within the index range, and the coil gap about 90 % of the rest."""
    n_a, c_inst, c_free_arm, c_nom = _coils(keys, i, opts, j)
    if not (_gap_margin(keys, i, opts, j, cst, c_inst, c_free_arm, c_nom) >= -tol):
        return False
    if not (_fatigue_margin(keys, i, opts, j, cst) >= -tol):
        return False
    m_out, m_in = _contact_margins(keys, i, opts, j, cst, n_a, c_inst)
    return m_out >= -tol and m_in >= -tol


@njit(cache=True, error_model="numpy")
def _clean_min(a, b):
    """``min(a, b)`` with NaN read as -inf (as the optimiser's ``_clean``)."""
    if b != b:
        return -np.inf
    return b if b < a else a


@njit(cache=True, error_model="numpy")
def _min_margin_past_yield(keys, i, opts, j, cst, best, m):
    """Smallest margin of key ``i`` x option ``j`` (NaN as -inf) given ``m``, the minimum of its index and
    yield margins; returns early once it is below ``best`` (the caller then only needs to know it cannot win)."""
    n_a, c_inst, c_free_arm, c_nom = _coils(keys, i, opts, j)
    m = _clean_min(m, _gap_margin(keys, i, opts, j, cst, c_inst, c_free_arm, c_nom))
    if m < best:
        return m
    m = _clean_min(m, _fatigue_margin(keys, i, opts, j, cst))
    if m < best:
        return m
    m_out, m_in = _contact_margins(keys, i, opts, j, cst, n_a, c_inst)
    return _clean_min(_clean_min(m, m_out), m_in)


@njit(cache=True, error_model="numpy")
def _reg(m):
    """A margin as the registry keeps it: NaN is -inf (infeasible, never silently kept)."""
    return -np.inf if m != m else m


@njit(cache=True, error_model="numpy")
def _pair_margins(keys, i, opts, j, cst, row):
    """The eight margins of key ``i`` x option ``j`` into ``row`` (order of ``MARGIN_NAMES``)."""
    row[M_YIELD] = _reg(_yield_margin(keys, i, opts, j))
    row[M_SECTION] = _reg(opts[j, O_SEC])
    row[M_FATIGUE] = _reg(_fatigue_margin(keys, i, opts, j, cst))
    m_out, m_in, m_gap = _geometry_margins(keys, i, opts, j, cst)
    row[M_OUTER] = _reg(m_out)
    row[M_INNER] = _reg(m_in)
    row[M_GAP] = _reg(m_gap)
    row[M_IDX_MIN] = _reg(opts[j, O_IDX_MIN])
    row[M_IDX_MAX] = _reg(opts[j, O_IDX_MAX])


@njit(cache=True, error_model="numpy")
def _margins_row(keys, i, opts, cst, out):
    for j in range(opts.shape[0]):
        _pair_margins(keys, i, opts, j, cst, out[i, j])


@njit(cache=True, error_model="numpy")
def margins_pairs(keys, opts, cst, ki, oj, out):
    """(a) for listed pairs: ``out[p, :]`` = the eight margins of key ``ki[p]`` x option ``oj[p]``."""
    for p in range(ki.shape[0]):
        _pair_margins(keys, ki[p], opts, oj[p], cst, out[p])


@njit(cache=True, error_model="numpy")
def _remove_at(work, lo, a, n_act):
    """Remove entry ``a`` of the active keys ``work[lo:lo + n_act]``, keeping their order; the new count."""
    for b in range(a, n_act - 1):
        work[lo + b] = work[lo + b + 1]
    return n_act - 1


@njit(cache=True, error_model="numpy")
def _first_feasible_chunk(c, keys, opts, cst, tol, t_max, ptr, idx, chunk_list, kptr, kperm, score, score_limit,
                          pick, visited, work):
    # score[p]: the score of candidate p of the lists (aligned with idx)
    """(b) for the keys ``kperm[kptr[c]:kptr[c+1]]`` (sorted by installation torque), which share the candidate
    list ``chunk_list[c]``: the list is walked once, option by option, for all keys still looking.

    For an option ``j`` only the keys with ``T_inst <= t_max[j]`` pass the yield check (the margin is monotone
    in ``T_inst``, ``t_max`` is its exact threshold), and they are a prefix of the sorted keys; the other checks
    run for them alone. A key leaves when it finds its option or passes its score limit. Same answer as
    scanning each key's list on its own.
    """
    g = chunk_list[c]
    lo, hi = kptr[c], kptr[c + 1]
    p0, p1 = ptr[g], ptr[g + 1]
    n_act = 0
    for a in range(lo, hi):
        i = kperm[a]
        pick[i] = -1
        stop = p1
        lim = score_limit[i]
        if lim < np.inf:
            for p in range(p0, p1):
                if score[p] > lim:
                    stop = p
                    break
        visited[i] = stop - p0  # the options the key examines if it finds none
        if stop > p0:
            work[lo + n_act] = i
            n_act += 1
    for p in range(p0, p1):
        if n_act == 0:
            break
        j = idx[p]
        if not (opts[j, O_UB] >= -tol):
            continue  # index range or material section: no key passes
        t_j = t_max[j]
        a = 0
        while a < n_act:
            i = work[lo + a]
            if not (keys[i, K_T_INST] <= t_j):
                break  # this key and every later one (larger T_inst) fail the yield check
            done = False
            if p - p0 >= visited[i]:
                done = True  # past the key's score limit
            elif _pair_feasible_past_yield(keys, i, opts, j, cst, tol):
                pick[i] = j
                visited[i] = p - p0 + 1
                done = True
            if done:
                n_act = _remove_at(work, lo, a, n_act)
            else:
                a += 1


@njit(cache=True, error_model="numpy")
def _max_min_chunk(c, keys, opts, cst, ptr, idx, ub, rank, chunk_list, kptr, kperm, cap, pick, value, visited,
                   best_rank, work):
    """(c) for the keys ``kperm[kptr[c]:kptr[c+1]]`` (sorted by installation torque), which share the candidate
    list ``chunk_list[c]`` (sorted by decreasing ``ub``, the option-only bound of the smallest margin).

    The list is walked once for all keys. A key stops when ``ub`` falls below its best value or its best
    reaches its cap. For an option, the keys are visited in increasing ``T_inst``: their yield margins
    decrease, so once one is below the smallest best of the keys still looking, no later key can win or tie
    with this option. Same answer (value and tie-break) as scanning each key's list on its own.
    """
    g = chunk_list[c]
    lo, hi = kptr[c], kptr[c + 1]
    p0, p1 = ptr[g], ptr[g + 1]
    n_act = 0
    for a in range(lo, hi):
        i = kperm[a]
        pick[i] = -1
        value[i] = -np.inf
        best_rank[i] = np.iinfo(np.int64).max
        visited[i] = 0
        if not (-np.inf >= cap[i]):
            work[lo + n_act] = i
            n_act += 1
    floor = -np.inf  # smallest best value of the keys still looking
    for p in range(p0, p1):
        if n_act == 0 or ub[p] < floor:
            break
        j = idx[p]
        changed = False
        a = 0
        while a < n_act:
            i = work[lo + a]
            best = value[i]
            if ub[p] < best or best >= cap[i]:
                n_act = _remove_at(work, lo, a, n_act)  # this key is done
                changed = True
                continue
            y = _clean_min(np.inf, _yield_margin(keys, i, opts, j))
            if y < floor:
                break  # later keys: larger T_inst, yield margin <= y < floor <= their best
            visited[i] += 1
            m = _clean_min(ub[p], y)
            if m >= best:
                v = _min_margin_past_yield(keys, i, opts, j, cst, best, m)
                if v > best or (v == best and rank[p] < best_rank[i]):
                    value[i], best_rank[i], pick[i] = v, rank[p], j
                    changed = True
            a += 1
        if changed:
            floor = np.inf
            for b in range(n_act):
                floor = min(floor, value[work[lo + b]])
            if n_act == 0:
                floor = -np.inf


# ---- the kernels: one loop over keys each, serial (range) and threaded (prange, parallel=True); the two
# ---- variants are separate functions because numba's cache keys a function by its name and bytecode


@njit(cache=True, error_model="numpy")
def margins_table(keys, opts, cst, out):
    """(a) ``out[i, j, :]`` = the eight margins of key ``i`` x option ``j`` (order of ``MARGIN_NAMES``)."""
    for i in range(keys.shape[0]):
        _margins_row(keys, i, opts, cst, out)


@njit(cache=True, error_model="numpy")
def margins_table_above(keys, opts, cst, floor, out, low):
    """(a) where a pair may reach ``floor``: ``low[i, j]`` the smallest margin of key ``i`` x option ``j`` and
    ``out[i, j, :]`` its eight margins (as :func:`margins_table`), unless its yield margin or its option-only
    bound (index, section) is below ``floor``: then ``low[i, j]`` is that one (an upper bound of the smallest
    margin, below ``floor``) and ``out[i, j, :]`` is not written."""
    for i in range(keys.shape[0]):
        for j in range(opts.shape[0]):
            m = min(_reg(_yield_margin(keys, i, opts, j)), opts[j, O_UB])
            if m < floor:
                low[i, j] = m
                continue
            row = out[i, j]
            _pair_margins(keys, i, opts, j, cst, row)
            v = row[0]
            for c in range(1, N_MARGINS):
                v = min(v, row[c])
            low[i, j] = v


@njit(cache=True, error_model="numpy", parallel=True)
def margins_table_parallel(keys, opts, cst, out):
    """:func:`margins_table` with the keys shared among numba's threads."""
    for i in prange(keys.shape[0]):
        _margins_row(keys, i, opts, cst, out)


@njit(cache=True, error_model="numpy")
def first_feasible_scan(keys, opts, cst, tol, t_max, ptr, idx, chunk_list, kptr, kperm, score, score_limit, pick,
                        visited, work):
    """(b)/(d) per key ``i``: the first option of its candidate list whose margins are all ``>= -tol``, or -1;
    a key's scan stops at a candidate with ``score[p] > score_limit[i]`` (scores aligned with ``idx``); ``visited[i]`` counts the options the key
    examined (up to and including its hit). Keys come in chunks sharing a list (:func:`_first_feasible_chunk`);
    ``work`` is scratch of one int per key."""
    for c in range(len(kptr) - 1):
        _first_feasible_chunk(c, keys, opts, cst, tol, t_max, ptr, idx, chunk_list, kptr, kperm, score, score_limit,
                              pick, visited, work)


@njit(cache=True, error_model="numpy", parallel=True)
def first_feasible_scan_parallel(keys, opts, cst, tol, t_max, ptr, idx, chunk_list, kptr, kperm, score, score_limit,
                                 pick, visited, work):
    """:func:`first_feasible_scan` with the chunks of keys shared among numba's threads."""
    for c in prange(len(kptr) - 1):
        _first_feasible_chunk(c, keys, opts, cst, tol, t_max, ptr, idx, chunk_list, kptr, kperm, score, score_limit,
                              pick, visited, work)


@njit(cache=True, error_model="numpy")
def max_min_scan(keys, opts, cst, ptr, idx, ub, rank, chunk_list, kptr, kperm, cap, pick, value, visited, best_rank,
                 work):
    """(c) per key: the option of its candidate list with the largest smallest margin (ties: smallest ``rank``,
    the position in the caller's list), its value, and ``visited``: the options whose margins were evaluated
    for it. The lists come sorted by decreasing ``ub``; keys in chunks sharing a list (:func:`_max_min_chunk`);
    ``best_rank`` and ``work`` are scratch of one int per key."""
    for c in range(len(kptr) - 1):
        _max_min_chunk(c, keys, opts, cst, ptr, idx, ub, rank, chunk_list, kptr, kperm, cap, pick, value, visited,
                       best_rank, work)


@njit(cache=True, error_model="numpy", parallel=True)
def max_min_scan_parallel(keys, opts, cst, ptr, idx, ub, rank, chunk_list, kptr, kperm, cap, pick, value, visited,
                          best_rank, work):
    """:func:`max_min_scan` with the chunks of keys shared among numba's threads."""
    for c in prange(len(kptr) - 1):
        _max_min_chunk(c, keys, opts, cst, ptr, idx, ub, rank, chunk_list, kptr, kperm, cap, pick, value, visited,
                       best_rank, work)



@njit(cache=True, error_model="numpy")
def list_order(pre, unit_cost, w_cost, post, stiffness, cand, first, good):
    """Whether a spring list keeps its order for each of many applications, and its first score.

    The score of application ``a`` and candidate ``j`` is ``((pre[j] + w_cost * (unit_cost[j] / max(stiffness[a],
    1e-12))) + post[0, j]) + ...``: the weighted sum of :func:`synth.optimise.objectives.weighted_sum` over the
    goals of the score, in its order of operations (``pre``: the goals before the cost, summed from 0.0; ``post``:
    those after it, one row each), the cost per unit compliance over the stiffness
    (:meth:`synth.design.space.Space.spring_cost_eur`). ``good[a]``: every adjacent pair of candidates ``cand`` is
    in order (the score grows, or ties with a growing index), as ``numpy.diff`` of the row tells it;
    ``first[a]``: the score of ``cand[0]``. One pass over applications x candidates, nothing stored per pair.
    """
    n_post = post.shape[0]
    for a in range(len(stiffness)):
        k = _maximum(stiffness[a], 1e-12)
        ok = True
        prev = 0.0
        for j in range(len(cand)):
            x = pre[j] + w_cost * (unit_cost[j] / k)
            for p in range(n_post):
                x = x + post[p, j]
            if j == 0:
                first[a] = x
            else:
                d = x - prev
                ok = d > 0 or (d == 0 and cand[j] > cand[j - 1])
                if not ok:
                    break
            prev = x
        good[a] = ok


@njit(cache=True, error_model="numpy")
def window_pairs(groups, lo, hi, mbd, excl, excl_row, need, need_row, start, limit, out_g, out_o):
    """The (group, option) pairs of ``groups[start:]`` whose option's mean body diameter lies in the group's window
    (``lo[g] <= mbd[o] <= hi[g]``, a NaN bound admits nothing), not excluded (``excl[excl_row[g], o]``, row ``-1``:
    none) and admitted (``need[need_row[g], o]``, row ``-1``: every option); groups in the given order, options
    ascending (``numpy.nonzero`` of the mask). Whole groups only: stops after the group at which ``limit`` pairs
    are reached (``out_*`` hold at least ``limit + len(mbd)``). Returns the pairs written and the next ``start``."""
    n = 0
    n_opt = len(mbd)
    for t in range(start, len(groups)):
        g = groups[t]
        a = lo[g]
        b = hi[g]
        er = excl_row[g]
        nr = need_row[g]
        for o in range(n_opt):
            x = mbd[o]
            if x >= a and x <= b and (er < 0 or not excl[er, o]) and (nr < 0 or need[nr, o]):
                out_g[n] = g
                out_o[n] = o
                n += 1
        if n >= limit:
            return n, t + 1
    return n, len(groups)


@njit(cache=True, error_model="numpy")
def record_stage(gg, oo, ok, m, b, finite, line, survive, failed, best, best_b):
    """Record a block of stage verdicts, pairs ``(gg[i], oo[i])`` with ``gg`` ascending: a passing pair survives
    (``survive[g, o]``), a failing one of a finite group value fails along its line (``failed[line[g], o]``); per
    run of one group, its largest margin ``m`` (NaN if any is: ``numpy.maximum.reduceat``) replaces ``best[g]``
    when larger, with the binding ``b`` of the first pair reaching it."""
    n = len(gg)
    i = 0
    while i < n:
        g = gg[i]
        j = i
        mx = m[i]
        while j < n and gg[j] == g:
            if ok[j]:
                survive[g, oo[j]] = True
            elif finite[g]:
                failed[line[g], oo[j]] = True
            x = m[j]
            if np.isnan(x) or x > mx:
                mx = x
            j += 1
        if mx > best[g]:
            for k in range(i, j):
                if m[k] == mx:
                    best[g] = mx
                    best_b[g] = b[k]
                    break
        i = j


@njit(cache=True, error_model="numpy")
def _span(mbd, s, e, a, b):
    """``(first, end)``: the options ``s <= o < e`` of a run of non-decreasing ``mbd`` with ``a <= mbd[o] <= b``
    (two bisections: the options :func:`window_pairs`'s test admits there)."""
    lo, hi = s, e
    while lo < hi:   # first mbd >= a
        mid = (lo + hi) // 2
        if mbd[mid] < a:
            lo = mid + 1
        else:
            hi = mid
    first = lo
    hi = e
    while lo < hi:   # first mbd > b
        mid = (lo + hi) // 2
        if mbd[mid] <= b:
            lo = mid + 1
        else:
            hi = mid
    return first, lo


@njit(cache=True, error_model="numpy")
def stage_round(groups, lo, hi, mbd, runs, excl, excl_row, need, need_row, key_of, opt_of, keys, opts, cst, cols,
                bind, no_binding, tol, finite, line, survive, failed, best, best_b):
    """One round of the platform producer's main-spring stages in one pass (:func:`window_pairs`, the margins,
    the stage's smallest margin and :func:`record_stage`, without the pairs' arrays): for each group ``g`` of
    ``groups``, the options ``o`` :func:`window_pairs` gives it, in its order; of key ``key_of[g]`` x option
    ``opt_of[o]`` the smallest of the margins ``cols`` (``M_*`` indices, the first of ties, as the assessment's
    ``argmin``) and its binding ``bind[c]`` (``no_binding`` where that margin is ``+inf``); recorded as
    :func:`record_stage` records a block (a pass is a margin ``>= -tol``). Returns the pairs judged.

    ``runs``: the starts of the runs of non-decreasing ``mbd`` (no NaN), and ``len(mbd)``: a group's window is
    bisected in each run, in option order (the options :func:`window_pairs` tests one by one). The cheap margins of
    ``cols`` come first (the option-only index range and material section, the yield check): a pair one of them
    fails whose bound (their smallest) is below the group's largest smallest margin so far fails and cannot be the
    group's best (nor the first to reach it), so its other margins (fatigue, geometry) are not computed; every
    verdict, best margin and binding is the one of computing them all."""
    n = 0
    n_col = len(cols)
    row = np.empty(N_MARGINS)
    need_y = need_f = need_g = need_c = False
    for q in range(n_col):
        c = cols[q]
        if c == M_YIELD:
            need_y = True
        elif c == M_FATIGUE:
            need_f = True
        elif c == M_OUTER or c == M_INNER or c == M_GAP:
            need_g = True
            need_c = need_c or c != M_GAP
    for t in range(len(groups)):
        g = groups[t]
        a = lo[g]
        b = hi[g]
        if not (a <= b):   # an empty window, or a NaN bound: no option
            continue
        er = excl_row[g]
        nr = need_row[g]
        i = key_of[g]
        seen = False
        mx = 0.0
        mb = no_binding
        for r in range(len(runs) - 1):
            o0, o1 = _span(mbd, runs[r], runs[r + 1], a, b)
            for o in range(o0, o1):
                if not ((er < 0 or not excl[er, o]) and (nr < 0 or need[nr, o])):
                    continue
                n += 1
                j = opt_of[o]
                ub = np.inf   # the option-only margins of the stage: an upper bound of its smallest margin
                for q in range(n_col):
                    c = cols[q]
                    if c == M_SECTION or c == M_IDX_MIN or c == M_IDX_MAX:
                        v = _reg(opts[j, O_SEC if c == M_SECTION else (O_IDX_MIN if c == M_IDX_MIN else O_IDX_MAX)])
                        row[c] = v
                        if v < ub:
                            ub = v
                if need_y:
                    v = _reg(_yield_margin(keys, i, opts, j))
                    row[M_YIELD] = v
                    if v < ub:
                        ub = v
                if seen and ub < mx and not (ub >= -tol):
                    if finite[g]:
                        failed[line[g], o] = True
                    continue
                if need_f:
                    row[M_FATIGUE] = _reg(_fatigue_margin(keys, i, opts, j, cst))
                if need_g:   # _geometry_margins's steps, the contact ones only where the stage reads them
                    n_a, c_inst, c_free_arm, c_nom = _coils(keys, i, opts, j)
                    row[M_GAP] = _reg(_gap_margin(keys, i, opts, j, cst, c_inst, c_free_arm, c_nom))
                    if need_c:
                        m_out, m_in = _contact_margins(keys, i, opts, j, cst, n_a, c_inst)
                        row[M_OUTER] = _reg(m_out)
                        row[M_INNER] = _reg(m_in)
                m = np.inf
                c = -1
                for q in range(n_col):
                    v = row[cols[q]]
                    if v < m:
                        m = v
                        c = q
                bb = no_binding if c < 0 else bind[c]
                if m >= -tol:
                    survive[g, o] = True
                elif finite[g]:
                    failed[line[g], o] = True
                if not seen or m > mx:
                    mx = m
                    mb = bb
                    seen = True
        if seen and mx > best[g]:
            best[g] = mx
            best_b[g] = mb
    return n
