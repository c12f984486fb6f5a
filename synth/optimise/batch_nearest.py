"""The nearest design of each application of a batch (:meth:`synth.optimise.batch.Batch.nearest`): branch and
bound over the cores on their smallest margins, then the winning cores' designs under the whole key of near designs
(:func:`synth.design.combine.near_key`) from the subsystems' near figures."""

from __future__ import annotations


import numpy as np

from synth import catalog
from synth.design import evaluate
from synth.design.combine import combine, join, near_figures
from synth.design.space import SUBSYSTEMS
from synth.design.subsystems import SubTable, family, scatter
from synth.optimise import product
from synth.optimise.margin_ties import SLACK
from synth.optimise.scan_arrays import rounds, unique_rows

__all__ = ["nearest", "near_tables"]


def nearest(batch, which=None) -> list:
    """Per application (``which``: a subset, default all): ``(core row, {subsystem: option row}, value)`` of
    the design with the largest smallest margin over every core and option (every non-advisory constraint,
    the input-only ones included), as the enumeration's ``nearest_design``; None without any core.

    Nearest designs are ranked by the search model (at fidelity ``screening`` the screening one, as
    :meth:`synth.design.evaluate.Group.rank`); the design reported is verified by the full model."""
    n = len(batch)
    want = np.ones(n, dtype=bool) if which is None else np.isin(np.arange(n), which)
    R = np.flatnonzero(want[batch.A])
    out: list = [None] * n
    if not len(R):
        return out
    u0 = np.minimum(batch.cg.min_margin(objective_only=False)[R], batch.in_min[batch.A[R]])
    vb, pb = batch.paired.bushing(R)
    vt, _ = batch.bolts.scan(R)
    v1 = combine(u0, [vb, vt])  # the design margin so far: the core's with its bushing's and bolt's
    a_of = batch.A[R]
    o = np.lexsort((R, -v1, a_of))
    R, a_of, v1, pb = (x[o] for x in (R, a_of, v1, pb))
    keys, kinv = batch.springs.keys(R)
    k_val = np.full(len(keys["app"]), np.nan)
    k_cap = np.full(len(keys["app"]), -np.inf)
    k_pk = np.zeros(len(keys["app"]), dtype=np.int64)
    val = np.full(len(R), -np.inf)
    best_v = np.full(n, -np.inf)
    best = np.full(n, -1, dtype=np.int64)
    seg = np.flatnonzero(np.r_[True, a_of[1:] != a_of[:-1]])
    seg_end = np.r_[seg[1:], len(R)]
    pos = seg.copy()
    block = 1

    def could_win_value(v, j):  # a row whose value (so far) can still reach the best (within round-off): the
        i = a_of[j]               # ties on the smallest margin go on to the whole key
        return (best[i] < 0) | (v >= best_v[i] - SLACK * np.maximum(1.0, np.abs(best_v[i])))

    def could_win(j):  # rows sorted by (-v1, row): a row can still reach the best
        return could_win_value(v1[j], j)

    for take in rounds(pos, seg_end, block, could_win):
        kt_all = kinv[take]
        need = np.full(len(keys["app"]), -np.inf)
        np.maximum.at(need, kt_all, v1[take])
        kt = np.unique(kt_all)
        kt = kt[np.isnan(k_val[kt]) | (k_cap[kt] < need[kt])]
        if len(kt):  # the springs of these keys, exact up to the largest bound of their rows
            sub = {k: v[kt] for k, v in keys.items()}
            v, k_pk[kt] = batch.springs.best_margin(sub, need[kt])
            k_val[kt], k_cap[kt] = np.minimum(v, need[kt]), need[kt]
        v2 = combine(v1[take], [k_val[kt_all]])  # and its spring's
        go = could_win_value(v2, take)
        ta = take[go]
        if len(ta):
            va, _ = batch.axial.best_margin(R[ta], v2[go])
            val[ta] = combine(v2[go], [va])  # and its axial group's: the design's margin
        for j in ta[np.lexsort((R[ta], -val[ta]))]:
            i = a_of[j]
            if best[i] < 0 or val[j] > best_v[i] or (val[j] == best_v[i] and R[j] < R[best[i]]):
                best_v[i], best[i] = val[j], j
    # the winners under the whole key (synth.design.combine.near_key): the cores whose smallest margin reaches
    # the largest (within round-off of the compiled kernels) tie there; their subsystems' near figures (the
    # bolt's and the spring's from the batch, the others by the enumeration's evaluator) choose the best
    # design exactly as the enumeration's nearest design (synth.optimise.product.Evaluation.nearest)
    won = np.flatnonzero(best >= 0)
    tol = SLACK * np.maximum(1.0, np.abs(best_v))
    rows_of = {}
    for i, j, c in zip(*np.unique(a_of, return_index=True, return_counts=True)):  # R is sorted by application
        if best[i] >= 0:
            rows_of[i] = np.sort(R[j:j + c][val[j:j + c] >= best_v[i] - tol[i]])
    step = max(int(catalog.constant("bulk_nearest_pair_block")), 1)
    for b in range(0, len(won), step):  # the families judged pair by pair: the winners of a block of applications
        block = won[b:b + step]
        rows = np.concatenate([rows_of[i] for i in block])
        pair = pairwise(batch, rows)
        # the rows' near figures with their application's input-only checks, from the batch's own groups
        core = product.core_near(batch.cg.take(rows), batch.ig, batch.A[rows])
        ends = np.cumsum([len(rows_of[i]) for i in block])
        for i, e in zip(block, ends):
            own = slice(e - len(rows_of[i]), e)
            out[i] = _nearest_of(batch, i, rows_of[i], best_v[i] - tol[i], {n: t.take(own) for n, t in pair.items()},
                                 tuple(x[own] for x in core))
    return out


def _nearest_of(batch, i: int, rows, floor: float, pair: dict, core: tuple) -> tuple:
    """Application ``i``'s nearest design among its winning core rows ``rows`` (the batch's), ``(core row,
    {subsystem: option row}, value)``; ``pair``: their rows of :func:`pairwise`, ``core`` their near figures.

    What :func:`synth.optimise.product.evaluate` (``only``, ``tables``) gives, from the batch's own core and input
    groups (an evaluation of every core of the application again was a third of this loop's time): the full
    model's axial verdicts where no core is complete, then the nearest design under the one key."""
    tables, cols = near_tables(batch, i, rows, floor, pair)
    product.judge_undecided(batch.apps, batch.sp, batch.cg, rows, batch.core_ok[rows], batch.settings, tables)
    pos, options, value = product.nearest_of(core, tables, rows)
    options["spring"] = int(cols[options["spring"]])  # the spring table's columns are springs ``cols``
    return pos, options, value


def near_tables(batch, i: int, rows, floor: float = -np.inf, pair_tables: dict | None = None) -> tuple:
    """The bolt's and the main spring's :class:`~synth.design.subsystems.SubTable` (with the near figures; the
    margin objective's column not computed) of core rows ``rows`` of application ``i``, from what the batch
    keeps (the bolt's step-10 checks per application, the pivot wall per core and diameter) and the compiled
    spring margins (:func:`synth.kernels.main_spring.margins`) of the rows' keys over the application's
    springs: the figures the enumeration's evaluation gives, at a fraction of its cost. A spring whose smallest
    margin is below ``floor`` (the application's largest smallest margin) keeps only that margin (no design
    under the key takes it). Returns ``(tables, columns)``: the spring table's columns are the springs
    ``columns`` (:meth:`_near_springs`: those a nearest design may take), the others' the whole tables'.
    ``pair_tables``: the families judged pair by pair, :func:`pairwise` of ``rows``, when already evaluated."""
    sp, nr = batch.sp, len(rows)
    nb = sp.n("bolt")
    batch.bolts.app([i], np.arange(nb))
    app = (batch.bolts.fix[1][i], batch.bolts.fix_near[0][i], batch.bolts.fix_near[1][i])
    wall, code = batch.bolts.wall(rows)
    if batch.bolts.core_ids:
        with np.errstate(over="ignore", divide="ignore", invalid="ignore"):
            g = evaluate.bolt_core(batch.apps, np.broadcast_to(batch.A[rows][:, None], wall.shape),
                                   {k: batch.cg.values[k][rows][:, None]
                                    for k in evaluate.core_values("bolt", batch.cg.values)},
                                   {k: v[None, :] for k, v in batch.bolts.wall_d[0].items()}, batch.settings)
        w = near_figures(np.stack([g.margins[c].reshape(-1) for c in batch.bolts.core_ids], axis=1))
        w = tuple(x.reshape(wall.shape)[:, code] for x in w)
    else:
        w = (np.full((nr, nb), np.inf), np.full((nr, nb), np.inf), np.zeros((nr, nb)))
    a, b, f = join(tuple(np.broadcast_to(x[None, :], (nr, nb)) for x in app), w)
    every = np.ones((nr, nb), dtype=bool)
    out = {"bolt": SubTable(every, f == 0, np.full((nr, nb), -np.inf), a, b, f)}
    out.update(pairwise(batch, rows) if pair_tables is None else pair_tables)
    keys, inv = batch.springs.keys(rows)
    rng, lists = batch.springs.ranges()
    k_fig, cols, avail = batch.springs.near(i, keys, rng[i], floor)
    fig = [x.reshape(len(keys["app"]), len(cols))[inv] for x in k_fig]
    avail = np.broadcast_to(avail, (len(inv), len(cols)))
    out["spring"] = SubTable(avail, avail & (fig[2] == 0), np.full((len(inv), len(cols)), -np.inf), *fig)
    return out, cols


def pairwise(batch, rows) -> dict:
    """``{family: SubTable}`` of the families judged pair by pair (the bushing, the axial group) over core rows
    ``rows`` (of one or several applications) and every option: each distinct (application, what the family
    reads of the core) once, in one evaluator call per family. A row's figures depend on its own values only, so
    the rows of many applications evaluated together give each application's own (the nearest design evaluates the
    winners of every application at once: one call instead of one per application)."""
    sp, out = batch.sp, {}
    for fam in (family(name) for name in SUBSYSTEMS):  # once per distinct (application, what the family reads)
        if fam.group is None:
            continue
        first, inv_f = unique_rows(batch.A[rows], *(batch.cg.values[k][rows] for k, _ in fam.match),
                                    *(batch.cg.values[k][rows] for k in fam.core_reads(batch.cg.values)))
        rep = rows[first]
        avail = fam.available(sp, batch.cg.values, rep)
        ri, oi = np.nonzero(avail)
        if fam.name == "axial":  # the search model on the batch's axial engine (its twins), as the scans
            g = batch.axial.group(rep[ri], oi)
        else:
            with np.errstate(over="ignore", divide="ignore", invalid="ignore"):
                g = fam.group(batch.apps, batch.cg, rep[ri], sp.rows(fam.name, oi), batch.settings)
            batch.evaluations += len(ri)
        out[fam.name] = scatter(avail, ri, oi, g).take(inv_f)
    return out
