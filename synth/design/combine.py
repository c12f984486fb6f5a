"""A design's margin from its parts': the one rule of the decomposed design space (:mod:`synth.design.space`).

A design is a core and one option per subsystem (bushing, axial, spring, bolt); given the core the subsystems share
no constraint, so a design's smallest margin is the smallest of the core's and of each option's, and what binds it
is where that smallest margin is reached (the core first, then the subsystems in :data:`~synth.design.space.SUBSYSTEMS`
order, on ties). :func:`combine` is that rule, on numbers or arrays (one design per element): the exhaustive
enumeration's and the black-box search's margin objectives, the diagnosis's nearest design, the alternatives, the
platform's assignments and the producer's nearest designs all call it.

**The one ranking of near designs** (an infeasible application's nearest design, the bulk's, and the near misses
of ``--top K``): the larger smallest margin of every counted check, then the larger second smallest, then fewer
failing checks, then the catalog order (the lowest core row, then the first option of each subsystem in order):
:func:`near_key`. It decomposes as the margin does: a part's (the core's with the input-only checks, an option's)
*near figures* are its smallest margin, its second smallest and its number of failing checks
(:func:`near_figures`); a design's are their join (:func:`join`: the smallest of the smallest, the second smallest of
the parts' two smallest, the sum of the failing counts). :func:`nearest_choice` finds, per core, the best options
under the whole key from the options' figures alone (exact, see its docstring), so that no search enumerates the
combinations that tie on the smallest margin (case 1: 246 million designs tie at -35.2 %).

A search that ranks options for a nearest design ranks a passing option above every failing one
(:func:`nearest_rank`): at fidelity ``screening`` a failing option's margin is the search model's
(:meth:`synth.design.evaluate.Group.rank`) and may be positive where the judge (the full model) fails the option.

>>> combine(0.3, [0.5, 0.1, 0.2, 0.1])
0.1
>>> combine(0.3, [0.5, 0.1, 0.2, 0.1], "arm_wall", ["bushing_p", "cone_sigma", "spring_yield", "thread"])
(0.1, 'cone_sigma')
>>> import numpy as np
>>> combine(np.array([0.3, -0.2]), [np.array([0.5, 0.0]), np.array([0.1, 0.4])]).tolist()
[0.1, -0.2]
"""

from __future__ import annotations

from functools import reduce

import numpy as np

from synth.design.constraints import FEAS_TOL

__all__ = ["combine", "nearest_rank", "near_figures", "join", "near_key", "nearest_choice", "best_row"]


def combine(core, subsystems, core_binding=None, bindings=None):
    """The smallest margin of designs made of a core (margin ``core``) and one option per subsystem (margins
    ``subsystems``, in subsystem order), numbers or arrays broadcast to one shape; with ``core_binding`` and
    ``bindings`` (the constraint binding each, same shapes) also the binding constraint of each design: the part's
    where the smallest margin is reached, the first of ties (the core, then the subsystems in order).
    Returns ``margin`` or ``(margin, binding)``; numbers for numbers.
    """
    parts = [core, *subsystems]
    scalar = all(np.ndim(p) == 0 for p in parts)
    arrays = [np.asarray(p, dtype=float) for p in parts]
    m = reduce(np.minimum, arrays)
    if core_binding is None and bindings is None:
        return float(m) if scalar else m
    labels = [core_binding, *(bindings if bindings is not None else [None] * len(subsystems))]
    if scalar:
        return float(m), next(b for p, b in zip(arrays, labels) if p == m)
    m = np.asarray(m)
    out = np.empty(m.shape, dtype=object)
    done = np.zeros(m.shape, dtype=bool)
    for p, b in zip(arrays, labels):
        hit = ~done & (np.broadcast_to(p, m.shape) == m)
        out[hit] = np.broadcast_to(np.asarray(b, dtype=object), m.shape)[hit]
        done |= hit
    return m, out


def nearest_rank(ok, margin, search_margin=None):
    """The value that ranks options for a nearest design: a passing option (``ok``, the judge's verdict) by its
    smallest margin, at least 0 (a margin within the tolerance is a pass), a failing one by the search model's
    smallest margin (``search_margin``, default ``margin``), at most ``-FEAS_TOL``: every passing option ranks above
    every failing one, whatever the search model says of the failing ones.

    >>> nearest_rank(np.array([True, False, False]), np.array([-1e-10, -0.3, -0.1]),
    ...              np.array([0.2, -0.3, 0.05])).tolist()
    [0.0, -0.3, -1e-09]
    """
    search = margin if search_margin is None else search_margin
    return np.where(ok, np.maximum(margin, 0.0), np.minimum(search, -FEAS_TOL))


def near_figures(margins, failed=None):
    """A part's near figures from its counted checks' ``margins`` (``(n, k)``, or ``(k,)`` for one part; ``+inf``
    where a check does not count): ``(smallest, second smallest, number of failing checks)`` per row, the count the
    checks below ``-FEAS_TOL`` unless ``failed`` gives it.

    >>> near_figures(np.array([0.2, -0.35, -0.04, np.inf]))
    (-0.35, -0.04, 2)
    """
    m = np.asarray(margins, dtype=float)
    one = m.ndim == 1
    m = np.atleast_2d(m)
    if m.shape[1] >= 2:
        two = np.partition(m, 1, axis=1)
        a, b = two[:, 0].copy(), two[:, 1].copy()
    else:
        a, b = (m[:, 0].copy() if m.shape[1] else np.full(len(m), np.inf)), np.full(len(m), np.inf)
    f = (~(m >= -FEAS_TOL)).sum(axis=1) if failed is None else np.asarray(failed)
    return (float(a[0]), float(b[0]), int(np.asarray(f).reshape(-1)[0])) if one else (a, b, f)


def join(*parts):
    """The near figures of parts taken together (numbers or arrays, broadcast): the smallest of their smallest,
    the second smallest of their two smallest (``min(max(a1, a2), b1, b2)`` for two), the sum of the failing counts.

    >>> join((-0.35, 0.1, 1), (-0.04, -0.01, 2))
    (-0.35, -0.04, 3)
    """
    a, b, f = parts[0]
    for a2, b2, f2 in parts[1:]:
        a, b, f = np.minimum(a, a2), np.minimum(np.maximum(a, a2), np.minimum(b, b2)), f + f2
    scalar = all(np.ndim(x) == 0 for p in parts for x in p)
    return (float(a), float(b), int(f)) if scalar else (a, b, f)


def near_key(figures, order=()) -> tuple:
    """The sort key of a near design (smaller first) from its near figures ``(smallest, second, failing)``
    (:func:`join` of its parts') and its catalog ``order`` (core row, option rows): ``(-smallest, -second, failing,
    order)`` (the failing count a float: ``inf`` for no design).

    >>> sorted([near_key((-0.35, -0.33, 5), (0,)), near_key((-0.35, -0.04, 3), (1,))])[0]
    (0.35, 0.04, 3.0, (1,))
    """
    a, b, f = figures
    return (-float(a), -float(b), float(f), tuple(int(x) for x in order))


def _first(mask: np.ndarray) -> np.ndarray:
    """Per row the first column where ``mask`` holds (0 where none)."""
    return np.argmax(mask, axis=1) if mask.shape[1] else np.zeros(len(mask), dtype=np.int64)


def nearest_choice(core, options: list):
    """Per core row, the best design under the one key (:func:`near_key`) and its options: ``((smallest, second,
    failing) per row, [option per row, one array per subsystem])``.

    ``core``: the core rows' near figures (arrays ``(n,)``); ``options``: per subsystem ``(smallest, second,
    failing, available)``, arrays ``(n, n_options)``. A row with a subsystem without an available option gets
    ``(-inf, -inf, inf)`` and option 0.

    Exact, without enumerating combinations. With ``a`` a part's smallest margin and ``b`` its second:
    the design's smallest is ``m1 = min(core a, max over options of each subsystem's a)``, reached by exactly the
    *admissible* choices (every option's ``a >= m1``). The second smallest of a design is
    ``max over parts p of min(b_p, min over q != p of a_q)`` (the multiset's minimum once ``a_p`` is removed), so
    its largest over admissible choices is ``max_p min(best b_p, min_q!=p best a_q)``, each part maximised alone
    (the terms separate): ``m2``. A choice reaches ``m2`` exactly when at most one of its parts' ``a``, ``b`` lies
    below ``m2``; the fewest failing checks is then the core's plus either every subsystem's fewest among options
    with none below, or one subsystem allowed one below: the smallest of those sums. The options are the first
    (index order) of the sets that reach that sum, the lexicographically first tuple over the sums that reach it.
    """
    ca, cb, cf = (np.asarray(x, dtype=float) for x in core)
    n = len(ca)
    subs = []
    for a, b, f, av in options:
        av = np.asarray(av, dtype=bool)
        subs.append((np.where(av, a, -np.inf), np.where(av, b, -np.inf), np.where(av, f, np.inf), av))
    best_a = [s[0].max(axis=1, initial=-np.inf) for s in subs]
    m1 = ca.copy()
    for ba in best_a:
        m1 = np.minimum(m1, ba)
    adm = [s[3] & (s[0] >= m1[:, None]) for s in subs]
    best_b = [np.where(ok, s[1], -np.inf).max(axis=1, initial=-np.inf) for s, ok in zip(subs, adm)]
    pa, pb = [ca, *best_a], [cb, *best_b]
    m2 = np.full(n, -np.inf)
    for p in range(len(pa)):
        v = pb[p]
        for q in range(len(pa)):
            if q != p:
                v = np.minimum(v, pa[q])
        m2 = np.maximum(m2, v)
    below = [(s[0] < m2[:, None]).astype(int) + (s[1] < m2[:, None]) for s in subs]
    core_below = (ca < m2).astype(int) + (cb < m2)
    set0 = [ok & (c == 0) for ok, c in zip(adm, below)]
    set1 = [ok & (c <= 1) for ok, c in zip(adm, below)]
    f0 = [np.where(m, s[2], np.inf).min(axis=1, initial=np.inf) for s, m in zip(subs, set0)]
    f1 = [np.where(m, s[2], np.inf).min(axis=1, initial=np.inf) for s, m in zip(subs, set1)]
    total0 = cf + sum(f0)
    totals = [total0]
    for s in range(len(subs)):
        t = cf + f1[s] + sum(f0[t] for t in range(len(subs)) if t != s)
        totals.append(np.where(core_below == 0, t, np.inf))
    fails = np.minimum.reduce(totals) if totals else cf
    pick0 = [_first(m & (s[2] == f[:, None])) for s, m, f in zip(subs, set0, f0)]
    pick1 = [_first(m & (s[2] == f[:, None])) for s, m, f in zip(subs, set1, f1)]
    best = [p.copy() for p in pick0]
    code = np.full(n, np.iinfo(np.int64).max)
    sizes = [s[0].shape[1] for s in subs]
    for j, t in enumerate(totals):
        picks = [pick1[s] if j == s + 1 else pick0[s] for s in range(len(subs))]
        c = np.zeros(n, dtype=np.int64)
        for p, size in zip(picks, sizes):
            c = c * max(size, 1) + p
        take = np.isfinite(fails) & (t == fails) & (c < code)
        code = np.where(take, c, code)
        for s in range(len(subs)):
            best[s] = np.where(take, picks[s], best[s])
    for s in range(len(subs)):
        best[s] = np.where(np.isfinite(fails), best[s], 0)
    return (m1, m2, fails), best


def best_row(figures) -> int:
    """The row of the best near figures ``(smallest, second, failing)`` (arrays) under :func:`near_key`, ties the
    first row."""
    a, b, f = (np.asarray(x, dtype=float) for x in figures)
    return int(np.lexsort((np.arange(len(a)), f, -b, -a))[0])
