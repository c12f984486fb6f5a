"""numba kernels of the main-spring searches (thesis step 9): per key, the first feasible option of a score-ordered
list and the option with the largest smallest margin; imported only through :mod:`synth.kernels.spring_tables`'
loaders. Every margin comes from the pair physics of :mod:`synth.kernels._main_spring_jit` (written there once).

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
  first score (the bulk engine's score-ordered lists).
"""

from __future__ import annotations

import numpy as np
from numba import njit, prange

from synth.kernels._ieee import maximum as _maximum
from synth.kernels._main_spring_jit import (K_T_INST, O_UB, clean_min, min_margin_past_yield,
                                            pair_feasible_past_yield, yield_margin)
from synth.kernels.numba_setup import announce_compiles

announce_compiles()  # a line on stderr when this process compiles a kernel (synth.kernels.numba_setup)


@njit(cache=True, error_model="numpy")
def _chunk_span(c, chunk_list, kptr, ptr):
    """Chunk ``c``'s keys ``kperm[lo:hi]`` and its candidate list's options ``idx[p0:p1]``."""
    g = chunk_list[c]
    return kptr[c], kptr[c + 1], ptr[g], ptr[g + 1]


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
    lo, hi, p0, p1 = _chunk_span(c, chunk_list, kptr, ptr)
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
            elif pair_feasible_past_yield(keys, i, opts, j, cst, tol):
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
    lo, hi, p0, p1 = _chunk_span(c, chunk_list, kptr, ptr)
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
            y = clean_min(np.inf, yield_margin(keys, i, opts, j))
            if y < floor:
                break  # later keys: larger T_inst, yield margin <= y < floor <= their best
            visited[i] += 1
            m = clean_min(ub[p], y)
            if m >= best:
                v = min_margin_past_yield(keys, i, opts, j, cst, best, m)
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
