"""Provable reductions of the platform problem: every optimum of the reduced problem is an
optimum of the full one (same objective value; a platform of the reduced problem serves
every application of the full one).

Notation as in :mod:`formulations.platform`: a platform ``P`` is a set of parts; pattern
``k`` (a set of parts) is *usable* when ``k`` is a subset of ``P``; application ``a`` is
served through core ``c`` when ``c``'s pattern is usable and every row of ``c`` (one per
subsystem) holds a usable option. The reductions, each with its proof:

R1 **Dominated option in a row.** Option ``o`` of row ``r`` goes when another option ``o'``
   of ``r`` has ``parts(o') <= parts(o)`` (subset) and, for the cost objective, a unit
   cost no higher (ties: the first stays). *Proof*: whenever ``o`` is usable, so is ``o'``
   (its parts are among ``o``'s), at no higher cost; swapping changes no part of ``P``.
   The "no axial group" option is the empty pattern: it dominates every option of its
   row in the variants objective, and the row (always covered) is dropped; in the cost
   objective its cost folds into the row's cores.

R2 **Dominated variant across the portfolio (part substitution).** For two parts ``j``
   and ``k`` of one subsystem family (a main spring, a bolt, a bushing, a cone spring, an
   endcap spacer): ``j`` goes, with every option that contains it, when ``k`` can stand
   in for it everywhere: for every row ``r`` and every option ``o`` of ``r`` containing
   ``j``, the option ``o - {j} + {k}`` is in ``r`` too (for the cost objective, at no
   higher unit cost), and ``k``'s weight and per-variant fixed cost are no higher (ties
   between mutual substitutes: the lower index stays). For one-part options (springs,
   bolts, bushings) this reads "``k`` is feasible in every row ``j`` is"; for the axial
   options (spacer and cone spring) it compares cone springs with the spacer held, and
   spacers with the cone spring held. *Proof*: in a solution using ``j``, replace part
   ``j`` by part ``k``: every design that used an option with ``j`` uses its counterpart
   with ``k``, in the same row, on the same core, at no higher cost; no other design
   changes; no family gains a variant (``max_variants`` and the part-count budget stay
   met) and the objective does not increase. Substitution is transitive, so the relation
   (ties broken by index) is a strict partial order: removing every dominated part of
   one family at once leaves, for each, a kept dominator. The families are reduced one
   after the other (an option holds one part of each), so a counterpart is never removed
   in the same pass.

R3 **Dominated core of an application.** Core ``c`` goes when another core ``c'`` of the
   same application has ``parts(c') <= parts(c)``, for every subsystem a row whose
   option set contains ``c``'s row's set (a dropped row counts as containing everything:
   it is always covered) and, for the cost objective, a core cost no higher. *Proof*:
   whenever ``c`` serves the application, ``c'`` does, at no higher cost (option costs
   are per application, the same in every row). Same order argument as R2.

R4 **Identical rows** of one application and subsystem merge (also done when compiling).
   *Proof*: the application uses one core, so both rows are covered or neither.

R5 **Implied row** (variants objective, every application must be served). If the
   only row of an application and subsystem (all its cores are in it: the row is
   unconditional) has option set ``S``, any row ``r`` of the same subsystem, of any
   application, whose set contains ``S`` is dropped (of two equal unconditional rows the
   first stays). *Proof*: ``S`` must hold a usable option in every feasible platform,
   which then covers ``r`` too.

The reductions run in rounds until none removes anything (each can enable the others).
The tests compare the optimum with and without them on small portfolios.

**Pooled prices.** Where a part's unit price falls with the summed volume of the applications it serves
(:func:`synth.platform.volume.pool_prices`: volume breaks left to the MILP), R1-R3 compare the dominator's cost
without any break against the dominated one's with every break of its parts reached (its largest discount), and
R1 and R3 ask in addition that the parts the dominated option or core has beyond the other's have no break (moving
an application off them takes no volume from a part another application's break needs). *Proof*: the swap then
costs the application no more at any volumes, moves no volume off a part with a break (R2 moves all of part
``j``'s volume onto ``k``, whose price can only fall), and changes no other application's design.
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp

from synth.platform.compile import Work
from synth.platform.data import SUBSYSTEMS, SUBSYSTEM_FAMILIES, FAMILIES

__all__ = ["prune", "dominated_options", "dominated_variants", "dominated_cores", "implied_rows", "merge_rows"]

_AX = SUBSYSTEMS.index("axial")
_I32 = np.iinfo(np.int32).max


def _live_rows(w: Work, si: int | None = None) -> list:
    """The live rows (of subsystem ``si``), ascending."""
    live = np.fromiter(w.row_alive, bool, len(w.row_alive))
    if si is not None:
        live &= np.fromiter(w.row_sub, np.int64, len(w.row_sub)) == si
    return np.flatnonzero(live).tolist()


def _overlaps(sets: list) -> tuple[np.ndarray, np.ndarray]:
    """``(inter, lens)`` of integer arrays ``sets``: ``inter[a, b]`` counts the entries of ``sets[a]`` that
    ``sets[b]`` holds (multiplicities multiply, as in the product of their indicator rows), ``lens[a]`` the entries
    of ``sets[a]``. Dense over the values present: the handful of sets of one application, where building a sparse
    matrix cost 20x the product; the counts are exact integers (as floats), so every comparison is the sparse
    product's."""
    n = len(sets)
    lens = np.array([len(x) for x in sets], dtype=np.int64)
    if not lens.sum():
        return np.zeros((n, n)), lens
    vals, col = np.unique(np.concatenate(sets), return_inverse=True)
    m = np.zeros((n, len(vals)))
    np.add.at(m, (np.repeat(np.arange(n), lens), col.ravel()), 1.0)
    return m @ m.T, lens


def _subset_matrix(w: Work, pats: np.ndarray) -> np.ndarray:
    """``S[i, j]``: pattern ``pats[i]`` is a subset of pattern ``pats[j]``."""
    if len(pats) == 0:
        return np.zeros((0, 0), bool)
    inter, lens = _overlaps([w.patterns[k] for k in pats])
    return inter >= lens[:, None] - 0.5


def _pooled(w: Work):
    """``(largest discount per piece, number of parts with a volume break)`` per pattern where parts are priced at
    their pooled volume (:func:`synth.platform.volume.pool_prices`), else None."""
    if w.objective != "cost" or w.breaks is None or not len(w.breaks[2]):
        return None
    _, ptr, _, step = w.breaks
    disc = np.add.reduceat(np.r_[step, 0.0], ptr[:-1]) * (np.diff(ptr) > 0)      # per part: the sum of its steps
    has = (np.diff(ptr) > 0).astype(np.int64)
    vd = np.array([disc[p].sum() for p in w.patterns])
    nbp = np.array([has[p].sum() for p in w.patterns], np.int64)
    return vd, nbp


def dominated_options(w: Work) -> int:
    """R1 (and the empty-pattern rows). Returns the number of (row, option) entries removed."""
    removed = 0
    cost_obj = w.objective == "cost"
    pooled = _pooled(w)
    plen = np.fromiter((len(x) for x in w.patterns), np.int64, len(w.patterns))
    multi = {si for si in range(len(SUBSYSTEMS))   # subsystems with an option of other than one part
             if (plen[np.concatenate([w.row_pats[i] for i in _live_rows(w, si)] or [np.zeros(0, np.int64)])] != 1).any()}
    for i in _live_rows(w):
        if w.row_sub[i] not in multi:
            continue
        p, c = w.row_pats[i], w.row_cost[i]
        if len(p) < 2:
            continue
        lens = plen[p]
        if lens.min() == lens.max() and lens.min() > 0:
            continue                                   # distinct patterns of one size: none is a subset of another
        S = _subset_matrix(w, p)                       # S[a, b]: p[a] subset of p[b]
        if cost_obj and pooled is not None:            # a's dearest against b's cheapest, b's extra parts priceless
            vd, nbp = pooled
            c_lo = c - w.pf_volume(w.row_app[i]) * vd[p]
            better = S & (c[:, None] <= c_lo[None, :] + 1e-9) & (nbp[p][:, None] == nbp[p][None, :])
        else:
            better = S & ((c[:, None] <= c[None, :] + 1e-9) if cost_obj else True)
        np.fill_diagonal(better, False)
        mutual = better & better.T
        idx = np.arange(len(p))
        dom = (better & ~mutual).any(axis=0) | (mutual & (idx[:, None] < idx[None, :])).any(axis=0)
        if dom.any():
            removed += int(dom.sum())
            w.row_pats[i], w.row_cost[i] = p[~dom], c[~dom]
    # rows whose only option is the empty pattern: always covered
    for i in _live_rows(w):
        p = w.row_pats[i]
        if len(p) and len(w.patterns[p[0]]) == 0 and (w.objective == "variants" or len(p) == 1):
            if w.objective == "cost":
                w.core_cost[w.row_cores[i]] += w.row_cost[i][0]
            w.row_alive[i] = False
            removed += len(p)
    return removed


def _row_matrix(w: Work, rows: list, pats: np.ndarray) -> sp.csr_matrix:
    """Boolean rows x patterns (columns: positions in ``pats``)."""
    col = np.full(len(w.patterns), -1)
    col[pats] = np.arange(len(pats))
    lens = [len(w.row_pats[i]) for i in rows]
    r = np.repeat(np.arange(len(rows)), lens)
    c = col[np.concatenate([w.row_pats[i] for i in rows])] if rows else np.zeros(0, int)
    return sp.csr_matrix((np.ones(len(r), np.float32), (r, c)), shape=(len(rows), len(pats)))


def dominated_variants(w: Work) -> int:
    """R2 (part substitution, family by family). Returns the number of parts removed."""
    removed = 0
    cost_obj = w.objective == "cost"
    for si, s in enumerate(SUBSYSTEMS):
        for fam in SUBSYSTEM_FAMILIES[s]:
            removed += _substitute(w, si, FAMILIES.index(fam), cost_obj)
    return removed


def _unique_ints(x: np.ndarray, bound: int) -> tuple[np.ndarray, np.ndarray]:
    """``np.unique(x, return_inverse=True)`` of whole numbers ``0 <= x < bound``: by a table of ``bound`` flags when
    it is not much longer than ``x`` (one pass instead of a sort), else by ``np.unique``; the same arrays either way.

    >>> [a.tolist() for a in _unique_ints(np.array([5, 2, 5, 9]), 10)]
    [[2, 5, 9], [1, 0, 1, 2]]
    """
    x = np.asarray(x, np.int64)
    if bound > 4 * len(x) + 65536:
        u, inv = np.unique(x, return_inverse=True)
        return u, np.asarray(inv).reshape(-1)
    present = np.zeros(bound, bool)
    present[x] = True
    return np.flatnonzero(present), (np.cumsum(present) - 1)[x]


def _token_bits(part: np.ndarray, tok: np.ndarray, n_parts: int, n_tok: int) -> np.ndarray:
    """``(n_parts, ceil(n_tok / 64))`` bit sets: bit ``tok`` of row ``part`` set for each pair (compiled:
    :func:`synth.kernels.bitsets.set_bits`).

    >>> _token_bits(np.array([0, 1, 0]), np.array([3, 64, 0]), 2, 65).tolist()
    [[9, 0], [0, 1]]
    """
    from synth.kernels import bitsets
    bits = np.zeros((n_parts, (n_tok + 63) // 64), np.uint64)
    bitsets.set_bits(np.ascontiguousarray(part, np.int64), np.ascontiguousarray(tok, np.int64), bits)
    return bits


def _subset_mask(bits: np.ndarray, pj: np.ndarray, pk: np.ndarray) -> np.ndarray:
    """Per pair ``(pj[p], pk[p])``: whether the bit set ``bits[pj[p]]`` lies inside ``bits[pk[p]]`` (compiled, each
    pair stopping at the first word that refutes it: :func:`synth.kernels.bitsets.subset_pairs`).

    >>> b = np.array([[1, 2], [3, 2], [1, 0]], np.uint64)
    >>> _subset_mask(b, np.array([0, 0, 2, 1]), np.array([1, 2, 0, 0])).tolist()
    [True, False, True, False]
    """
    from synth.kernels import bitsets
    ok = np.empty(len(pj), bool)
    bitsets.subset_pairs(np.ascontiguousarray(bits), np.ascontiguousarray(pj, np.int64),
                         np.ascontiguousarray(pk, np.int64), ok)
    return ok


def _subsets(bits: np.ndarray, pj: np.ndarray, pk: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The pairs ``(pj, pk)`` whose bit set ``bits[pj]`` lies inside ``bits[pk]``, in their order
    (:func:`_subset_mask`).

    >>> b = np.array([[1, 2], [3, 2], [1, 0]], np.uint64)
    >>> [x.tolist() for x in _subsets(b, np.array([0, 0, 2, 1]), np.array([1, 2, 0, 0]))]
    [[0, 2], [1, 0]]
    """
    ok = _subset_mask(bits, pj, pk)
    return pj[ok], pk[ok]


def _split_patterns(w: Work, upat: np.ndarray, fi: int) -> tuple[np.ndarray, np.ndarray]:
    """Per pattern ``upat[n]``: its part of family ``fi`` (the first; -1: none) and the id of the pattern of its other
    parts ("rest", numbered in order of first appearance), every pattern at once: the rests are the rows of a
    table padded with -1 (parts are >= 0, so two rows are equal exactly when the part lists are).

    >>> from types import SimpleNamespace
    >>> w = SimpleNamespace(patterns=[np.array([0, 3]), np.array([1, 3]), np.array([3]), np.array([1, 2])],
    ...                     part_family=np.array([0, 0, 1, 1]))
    >>> [x.tolist() for x in _split_patterns(w, np.array([0, 1, 2, 3]), 0)]
    [[0, 1, -1, 1], [0, 0, 0, 1]]
    """
    n_u = len(upat)
    lens = np.fromiter((len(w.patterns[k]) for k in upat), np.int64, n_u)
    flat = np.concatenate([w.patterns[k] for k in upat]).astype(np.int64) if lens.sum() else np.zeros(0, np.int64)
    pid = np.repeat(np.arange(n_u), lens)
    mine = np.asarray(w.part_family)[flat] == fi
    part_u = np.full(n_u, -1, np.int64)
    at = np.flatnonzero(mine)
    first = np.unique(pid[at], return_index=True)[1]
    part_u[pid[at[first]]] = flat[at[first]]
    other = np.flatnonzero(~mine)
    o_pid = pid[other]
    col = np.arange(len(other)) - np.searchsorted(o_pid, o_pid)
    table = np.full((n_u, int(col.max()) + 2 if len(col) else 1), -1, np.int64)
    table[o_pid, col] = flat[other]
    _, first_at, inv = np.unique(table, axis=0, return_index=True, return_inverse=True)
    order = np.empty(len(first_at), np.int64)
    order[np.argsort(first_at, kind="stable")] = np.arange(len(first_at))
    return part_u, order[np.asarray(inv).reshape(-1)]


def _substitute(w: Work, si: int, fi: int, cost_obj: bool) -> int:
    rows = _live_rows(w, si)
    if not rows:
        return 0
    pats = np.concatenate([w.row_pats[i] for i in rows])
    cost = np.concatenate([w.row_cost[i] for i in rows])
    assert len(rows) < _I32 and len(w.patterns) < _I32, "_substitute: row or pattern ids beyond int32"
    r_of = np.repeat(np.arange(len(rows), dtype=np.int32), [len(w.row_pats[i]) for i in rows])   # int32: half the memory
    pooled = _pooled(w) if cost_obj else None
    cost_lo = cost if pooled is None else cost - np.array([w.pf_volume(w.row_app[i]) for i in rows])[r_of] * \
        pooled[0][pats]                          # an option's cheapest at its parts' best breaks
    # per option: its part of family fi (-1: none) and the pattern of its other parts ("rest")
    upat, inv = _unique_ints(pats, len(w.patterns))
    part_u, rest_u = _split_patterns(w, upat, fi)
    part, rest = part_u[inv].astype(np.int32), rest_u[inv].astype(np.int32)   # < number of parts, of patterns
    del inv
    has = part >= 0
    if not has.any():
        return 0
    # tokens: (row, rest); part j "is in" token t when the option rest + j is in the row (each (row, pattern) once)
    tok_ids, tok = _unique_ints(r_of[has].astype(np.int64) * (int(rest.max()) + 1) + rest[has],
                                len(rows) * (int(rest.max()) + 1))
    cand, pcol = _unique_ints(part[has], len(w.part_family))
    if len(cand) < 2:
        return 0
    nt, nc = len(tok_ids), len(cand)
    # each (token, part) pair once (a row holds a pattern once, and rest + part is the pattern): per part its
    # tokens, per token its parts, by counting
    cnt = np.bincount(pcol, minlength=nc)
    tok_len = np.bincount(tok, minlength=nt)
    bits = _token_bits(pcol, tok, nc, nt)                                      # the token set of each part
    weight, fixed = w.part_weight[cand], w.part_fixed_cost[cand]
    if cost_obj:
        # per (application, rest, part) the lowest and highest cost over the application's tokens with that rest:
        # k is no dearer than j in all of them when its highest cost is at most j's lowest (exact when the rows of
        # an application price an option alike, as the producer's data do; otherwise it prunes less)
        app_t = np.asarray(w.row_app)[np.asarray(rows)][r_of[has]].astype(np.int64)
        _, cls = np.unique(app_t * (int(rest.max()) + 1) + rest[has], return_inverse=True)
        cls = np.asarray(cls).reshape(-1)
        n_app = int(cls.max()) + 1
        cmin, cmax = np.full((n_app, nc), np.inf), np.full((n_app, nc), -np.inf)
        np.minimum.at(cmin, (cls, pcol), cost_lo[has])
        np.maximum.at(cmax, (cls, pcol), cost[has])
        in_app = sp.csc_matrix((np.ones(len(cls), bool), (cls, pcol)), shape=(n_app, nc))
    # per part j: its smallest token (the first in its column on ties: a dominator is in it), and the parts of that
    # token as candidate dominators k, kept when no worse on count, weight and fixed cost and when j's tokens are
    # all k's (bit sets, a compiled test per pair stopping at the first word refuting it); no Python loop over j
    t0 = np.full(nc, np.iinfo(np.int64).max)                 # the smallest (token size, token) of each part
    np.minimum.at(t0, pcol, tok_len[tok].astype(np.int64) * nt + tok)
    t0 %= nt
    n_k = tok_len[t0]
    pj = np.repeat(np.arange(nc), n_k)
    sel = np.zeros(nt, bool)
    sel[t0] = True
    at = np.flatnonzero(sel[tok])                             # the pairs of those tokens, by token then part
    at = at[np.lexsort((pcol[at], tok[at]))]
    first = np.searchsorted(tok[at], t0)
    pk = pcol[at][np.repeat(first, n_k) + np.arange(len(pj)) - np.repeat(np.cumsum(n_k) - n_k, n_k)]
    keep = (pk != pj) & (cnt[pk] >= cnt[pj]) & (weight[pk] <= weight[pj]) & (fixed[pk] <= fixed[pj])
    pj, pk = pj[keep], pk[keep]
    same = (cnt[pk] == cnt[pj]) & (weight[pk] == weight[pj]) & (fixed[pk] == fixed[pj])
    dom = np.zeros(nc, bool)
    if not cost_obj:
        # strict order with index tie-break: a mutual substitute of higher index does not remove j. One dominator
        # is enough: each j's first candidate is tried alone, the others only for the j it does not settle
        q = ~same | (pk < pj)
        pj, pk = pj[q], pk[q]
        first = np.r_[True, pj[1:] != pj[:-1]] if len(pj) else np.zeros(0, bool)
        dom[_subsets(bits, pj[first], pk[first])[0]] = True
        later = ~first & ~dom[pj]
        dom[_subsets(bits, pj[later], pk[later])[0]] = True
    else:
        pj, pk = _subsets(bits, pj, pk)
        same = (cnt[pk] == cnt[pj]) & (weight[pk] == weight[pj]) & (fixed[pk] == fixed[pj])
        starts = np.flatnonzero(np.r_[True, pj[1:] != pj[:-1]]) if len(pj) else np.zeros(0, np.int64)
        for lo, hi in zip(starts, np.append(starts[1:], len(pj)).astype(np.int64)):
            j, ks, sm = int(pj[lo]), pk[lo:hi], same[lo:hi]
            apps_j = in_app.indices[in_app.indptr[j]:in_app.indptr[j + 1]]
            hi_k, lo_j = cmax[np.ix_(apps_j, ks)], cmin[apps_j, j][:, None]
            ok = np.all(hi_k <= lo_j + 1e-9, axis=0)
            sm = sm & np.all((cmin[np.ix_(apps_j, ks)] >= lo_j - 1e-9) & (hi_k <= lo_j + 1e-9)
                             & (cmax[apps_j, j][:, None] <= lo_j + 1e-9), axis=0)
            dom[j] = bool(np.any(ok & (~sm | (ks < j))))
    gone = cand[dom]
    bad_pat = np.zeros(len(w.patterns), bool)
    bad_pat[upat[np.isin(part_u, gone)]] = True
    # the rows that lose an option take their kept options from one filtering of the concatenation (``pats`` and
    # ``cost`` are the rows' arrays end to end, unchanged since: the same values and order as filtering each row,
    # in each row's own types; the new arrays share one buffer holding those rows' options only)
    kept = ~bad_pat[pats]
    lose = np.zeros(len(rows), bool)
    lose[r_of[~kept]] = True
    if lose.any():
        sel = kept & lose[r_of]
        end = np.cumsum(np.bincount(r_of[sel], minlength=len(rows)))
        new_p, new_c = pats[sel], cost[sel]
        for n in np.flatnonzero(lose).tolist():
            i, lo, hi = rows[n], int(end[n - 1]) if n else 0, int(end[n])
            w.row_pats[i] = new_p[lo:hi].astype(w.row_pats[i].dtype, copy=False)
            w.row_cost[i] = new_c[lo:hi].astype(w.row_cost[i].dtype, copy=False)
    return int(dom.sum())


def _core_rows(w: Work) -> np.ndarray:
    """``(C, n_subsystems)`` live row of each core (-1: none, the core's row was dropped as covered)."""
    out = np.full((len(w.core_alive), len(SUBSYSTEMS)), -1, np.int64)
    for i in _live_rows(w):
        out[w.row_cores[i], w.row_sub[i]] = i
    return out


def _set_bits_of(sets: list) -> np.ndarray:
    """The bit sets of integer arrays ``sets`` (one row each; bit ``n``: the ``n``-th smallest value present in any
    of them), for :func:`_subset_mask`.

    >>> _subset_mask(_set_bits_of([np.array([7, 3]), np.array([3, 5, 7]), np.array([5])]), np.array([0, 1, 2]),
    ...              np.array([1, 0, 1])).tolist()
    [True, False, True]
    """
    lens = np.fromiter((len(x) for x in sets), np.int64, len(sets))
    flat = np.concatenate(sets).astype(np.int64) if lens.sum() else np.zeros(0, np.int64)
    vals, tok = np.unique(flat, return_inverse=True)
    return _token_bits(np.repeat(np.arange(len(sets)), lens), np.asarray(tok).reshape(-1), len(sets), len(vals))


def _within_pairs(bounds: np.ndarray, take: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Every ordered pair ``(a, b)``, ``a != b``, of positions in one segment ``bounds[s]:bounds[s + 1]`` with
    ``take[s]``, in the order of the nested loops (``a``, then ``b``, ascending).

    >>> [x.tolist() for x in _within_pairs(np.array([0, 2, 3, 6]), np.array([True, True, False]))]
    [[0, 1], [1, 0]]
    """
    start, size = bounds[:-1][take], np.diff(bounds)[take]
    a = np.concatenate([np.arange(s0, s0 + n) for s0, n in zip(start.tolist(), size.tolist())]) if len(start) \
        else np.zeros(0, np.int64)
    per = np.repeat(size, size)                                  # the segment size of each a
    first = np.repeat(np.repeat(start, size), per)               # its segment's start, per pair
    b = first + np.arange(int(per.sum())) - np.repeat(np.cumsum(per) - per, per)
    a = np.repeat(a, per)
    keep = a != b
    return a[keep].astype(np.int64), b[keep].astype(np.int64)


#: the pairs of cores :func:`dominated_cores` judges at once (about 50 B each in its transient arrays: 2 million,
#: about 100 MB, bounds its memory at any number of applications)
CORE_PAIRS = 1 << 21


def _dominated_in(w: Work, cr, alive, bounds, take, pat_bits, at, cost_obj, pooled) -> np.ndarray:
    """The cores R3 removes among the applications ``take`` (segments ``bounds`` of ``alive``; positions in
    ``alive``, ascending): see :func:`dominated_cores`."""
    a, b = _within_pairs(bounds, take)                                 # positions in ``alive``
    sub = _subset_mask(pat_bits, at[a], at[b])
    a, b = a[sub], b[sub]
    for si in range(len(SUBSYSTEMS)):
        ra, rb = cr[alive[a], si], cr[alive[b], si]
        test = (ra != rb) & (ra >= 0) & (rb >= 0)                  # two live rows: b's options among a's
        ok = (ra == rb) | (ra < 0)                                 # one row, or a's row dropped (always covered)
        if test.any():
            ur, rinv = np.unique(np.r_[ra[test], rb[test]], return_inverse=True)
            rinv = np.asarray(rinv).reshape(-1)
            n_t = int(test.sum())
            ok[np.flatnonzero(test)] = _subset_mask(_set_bits_of([w.row_pats[i] for i in ur.tolist()]), rinv[n_t:],
                                                    rinv[:n_t])
        a, b = a[ok], b[ok]
    if cost_obj:
        ca, cb = alive[a], alive[b]
        cc = w.core_cost
        if pooled is not None:     # a's dearest against b's cheapest, b's extra parts priceless
            kp = w.core_pattern
            lo = cc[cb] - w.pf_volume(w.core_app[cb]) * pooled[0][kp[cb]]
            keep = (cc[ca] <= lo + 1e-9) & (pooled[1][kp[ca]] == pooled[1][kp[cb]])
        else:
            keep = cc[ca] <= cc[cb] + 1e-9
        a, b = a[keep], b[keep]
    # b goes when some a is better and not the reverse, or both and a comes first
    n = len(alive)
    key, rev = a * n + b, b * n + a                                  # ``key`` ascending (pairs in loop order)
    if not len(key):
        return np.zeros(0, np.int64)
    mutual = key[np.minimum(np.searchsorted(key, rev), len(key) - 1)] == rev
    return np.unique(b[~mutual | (a < b)]).astype(np.int64)


def dominated_cores(w: Work) -> int:
    """R3. Returns the number of cores removed.

    Every pair of cores of one application at once (no loop over applications): ``a`` dominates-or-ties ``b``
    (``better``) when ``parts(a) <= parts(b)``, for every subsystem ``a``'s row holds ``b``'s options (a dropped
    row holds everything, a live row not a dropped one's "everything") and, for the cost objective, ``a`` costs no
    more; ``b`` goes when some ``a`` does so strictly or ties with it at a lower index. Subset tests on bit sets
    (:func:`_subsets`), every comparison that of the per-application matrices it replaces."""
    cr = _core_rows(w)
    cost_obj = w.objective == "cost"
    pooled = _pooled(w) if cost_obj else None
    alive = np.flatnonzero(w.core_alive)
    if not len(alive):
        return 0
    bounds = np.flatnonzero(np.r_[True, np.diff(w.core_app[alive]) != 0, True])
    # an application whose cores have distinct patterns of one size has no core whose parts are among another's
    # (a subset of equal size is equal): nothing to test there
    seg = np.repeat(np.arange(len(bounds) - 1), np.diff(bounds))
    pat = w.core_pattern[alive].astype(np.int64)
    n_pat = np.bincount(np.unique(seg * (int(pat.max()) + 1) + pat) // (int(pat.max()) + 1), minlength=len(bounds) - 1)
    up, at = np.unique(pat, return_inverse=True)
    at = np.asarray(at).reshape(-1)
    size = np.fromiter((len(w.patterns[k]) for k in up), np.int64, len(up))[at]
    plain = (n_pat == np.diff(bounds)) & (np.minimum.reduceat(size, bounds[:-1]) == np.maximum.reduceat(size, bounds[:-1]))
    take = ~plain & (np.diff(bounds) >= 2)
    if not take.any():
        return 0
    pat_bits = _set_bits_of([w.patterns[k] for k in up])      # parts(a) <= parts(b): patterns as bit sets of parts
    # the applications in batches of at most CORE_PAIRS pairs (one application may hold more): each application's
    # cores are judged among themselves, so a batch is judged alone
    size2 = np.where(take, np.diff(bounds) ** 2, 0)
    cut = [0]
    acc = 0
    for k, x in enumerate(size2.tolist()):
        if acc and acc + x > CORE_PAIRS:
            cut.append(k)
            acc = 0
        acc += x
    cut.append(len(size2))
    seg_no = np.arange(len(size2))
    gone = np.concatenate([_dominated_in(w, cr, alive, bounds, take & (seg_no >= lo) & (seg_no < hi), pat_bits, at,
                                         cost_obj, pooled) for lo, hi in zip(cut[:-1], cut[1:])])
    if len(gone):
        w.core_alive[alive[gone]] = False
        for i in _live_rows(w):
            if not w.core_alive[w.row_cores[i]].any():
                w.row_alive[i] = False
    return int(len(gone))


def merge_rows(w: Work) -> int:
    """R4. Returns the number of rows merged away."""
    removed = 0
    seen: dict = {}
    for i in _live_rows(w):
        cores = w.row_cores[i][w.core_alive[w.row_cores[i]]]
        if not len(cores):
            w.row_alive[i] = False
            continue
        w.row_cores[i] = cores
        key = (w.row_app[i], w.row_sub[i], w.row_pats[i].tobytes())
        if key in seen:
            j = seen[key]
            w.row_cores[j] = np.concatenate([w.row_cores[j], cores])
            w.row_alive[i] = False
            removed += 1
        else:
            seen[key] = i
    return removed


def implied_rows(w: Work) -> int:
    """R5 (variants objective only). Returns the number of rows dropped."""
    if w.objective != "variants":
        return 0
    n_app_cores = np.bincount(w.core_app[w.core_alive], minlength=len(w.app_index))
    removed = 0
    for si in range(len(SUBSYSTEMS)):
        rows = _live_rows(w, si)
        if not rows:
            continue
        ncore = np.array([int(w.core_alive[w.row_cores[i]].sum()) for i in rows])
        uncond = np.array([ncore[n] == n_app_cores[w.row_app[i]] for n, i in enumerate(rows)], bool)
        if not uncond.any():
            continue
        pats = np.unique(np.concatenate([w.row_pats[i] for i in rows]))
        M = _row_matrix(w, rows, pats)
        U = M[np.flatnonzero(uncond)]
        lens_u = np.asarray(U.sum(axis=1)).ravel()
        lens = np.asarray(M.sum(axis=1)).ravel()
        G = (U @ M.T).tocoo()                          # G[u, r] = |S_u & S_r|
        ui = np.flatnonzero(uncond)[G.row]
        sub = (G.data >= lens_u[G.row] - 0.5) & (ui != G.col)
        equal = sub & (lens[G.col] <= lens_u[G.row] + 0.5)
        drop = sub & ~(equal & (G.col < ui) & uncond[G.col])   # of two equal unconditional rows the first stays
        for n in np.unique(G.col[drop]):
            w.row_alive[rows[n]] = False
            removed += 1
    return removed


def prune(w: Work, *, allow_unserved: bool = False, max_rounds: int = 6) -> Work:
    """Apply R1-R5 in rounds until nothing changes (R5 only when every application must be served).

    ``w.log`` records what each round removed. Returns ``w`` (edited in place).
    """
    w.log.append({"round": 0, **w.sizes()})
    for rnd in range(1, max_rounds + 1):
        n = {"R1_options": dominated_options(w), "R2_variants": dominated_variants(w), "R3_cores": dominated_cores(w),
             "R4_merged_rows": merge_rows(w), "R5_implied_rows": 0 if allow_unserved else implied_rows(w)}
        w.log.append({"round": rnd, **n, **w.sizes()})
        if not any(n.values()):
            break
    return w
