"""numba kernels of the platform producer's main-spring rounds (:func:`synth.platform.producer.spring_group`'s
stages); imported only through :mod:`synth.kernels.spring_tables`' loaders. Every margin comes from the pair physics
of :mod:`synth.kernels._main_spring_jit` (written there once).

* :func:`window_pairs` -- the (group, option) pairs of many groups whose option lies in the group's housing window
  and passes a per-group row of two boolean tables, flat (``numpy.nonzero``'s order), a block at a time;
* :func:`record_stage` -- a block of those rounds' verdicts written into the survivor and failed tables and the
  groups' best margins, one pass;
* :func:`stage_round` -- a whole round of those stages in one pass (the window pairs, their margins, the stage's
  smallest margin and the record), nothing of the size of the pairs: the producer's path where the compiled
  kernels cover the registry's spring checks (``window_pairs`` and ``record_stage`` remain the numpy twin's).
"""

from __future__ import annotations

import numpy as np
from numba import njit

from synth.kernels._main_spring_jit import (M_FATIGUE, M_GAP, M_IDX_MAX, M_IDX_MIN, M_INNER, M_OUTER, M_SECTION,
                                            M_YIELD, N_MARGINS, as_registry, coils, contact_margins, fatigue_margin,
                                            gap_margin, option_margin, yield_margin)
from synth.kernels.numba_setup import announce_compiles

announce_compiles()  # a line on stderr when this process compiles a kernel (synth.kernels.numba_setup)


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
                        v = option_margin(opts, j, c)
                        row[c] = v
                        if v < ub:
                            ub = v
                if need_y:
                    v = as_registry(yield_margin(keys, i, opts, j))
                    row[M_YIELD] = v
                    if v < ub:
                        ub = v
                if seen and ub < mx and not (ub >= -tol):
                    if finite[g]:
                        failed[line[g], o] = True
                    continue
                if need_f:
                    row[M_FATIGUE] = as_registry(fatigue_margin(keys, i, opts, j, cst))
                if need_g:   # geometry_margins's steps, the contact ones only where the stage reads them
                    n_a, c_inst, c_free_arm, c_nom = coils(keys, i, opts, j)
                    row[M_GAP] = as_registry(gap_margin(keys, i, opts, j, cst, c_inst, c_free_arm, c_nom))
                    if need_c:
                        m_out, m_in = contact_margins(keys, i, opts, j, cst, n_a, c_inst)
                        row[M_OUTER] = as_registry(m_out)
                        row[M_INNER] = as_registry(m_in)
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
