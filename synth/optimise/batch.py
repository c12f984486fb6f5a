"""The decomposed design space of many applications at once: the exact optimum, the nearest design, feasibility.

:class:`Batch` holds N applications on the applications axis of the one
evaluator (:mod:`synth.design.evaluate`): the input and core groups of every
core of every application (one call each), then, lazily and only where a
bound says it can matter, the subsystems of the cores: each group function
is called once per round for all the rows of all the applications that need
it, never once per application. It answers, per application, exactly what
the exhaustive enumeration (:func:`synth.optimise.solvers.enumerate.solve`
with ``exhaustive=True``: every core x every option evaluated) answers:

* :meth:`Batch.optimum` -- the design with the smallest additive score
  (``standard``, ``cost``, their orders and weighted sums without the
  margin), the same core and options, ties to the same (lowest) rows;
  ``first=True`` stops at any feasible design (a feasibility probe);
* :meth:`Batch.nearest` -- the design with the largest smallest margin
  (every constraint, every core: the nearest design of an infeasible
  application), with the same tie-breaks.

**How the work is cut, exactly.** A design's score is the core's plus one
option per subsystem (bushing, axial, spring, bolt: they share no constraint
given the core), and its smallest margin the minimum of theirs.

* Bushing and bolt are cheap and evaluated for every candidate core: the
  bushing once per distinct value of what it reads of the core
  (:func:`~synth.design.evaluate.core_values`); the bolt's checks
  once per application and bolt, but those that read the core (the pivot wall
  of step 2: :func:`~synth.design.evaluate.bolt_core_checks`) per core and
  distinct value of the bolt columns they read (the diameter).
* Springs go through the compiled kernels (:mod:`synth.kernels.main_spring`)
  once per distinct key, the axial group in blocks of its options in score
  order, once per distinct value of what it reads of the core
  (:func:`~synth.design.evaluate.core_values`).
* Branch and bound over the cores: a core's lower bound is its score, its
  bushing and bolt optima and the smallest axial and spring scores; cores are
  taken in increasing bound, in rounds of growing blocks over all
  applications, until the next bound exceeds the best design found. The sums
  are formed in the enumeration's order, so a bound never exceeds the total
  (IEEE rounding is monotone) and every core that could tie is evaluated.
  Within a spring key or an axial row, options are scanned in score order
  and stop at the first feasible, or where the score cannot beat the best
  (a relative slack of 1e-9 keeps the cut on the safe side of rounding).
* The nearest design the same way with the margins: a core's upper bound is
  the minimum of its own, its bushing's and its bolt's best margins; springs
  and axial options are searched with a cap (they need not beat the bound),
  and the winning core's options exactly (the enumeration's argmax per
  subsystem, first index of the ties).

>>> from synth.data.generated_applications import generate
>>> b = Batch(generate(3, seed=0), spring_engine="numpy")
>>> found = b.optimum({"cost": 1.0})
>>> [f is not None for f in found]
[False, True, True]
"""

from __future__ import annotations

import numpy as np

from synth.design.assessment import assess, passes
from synth.design import evaluate
from synth.design.applications import Applications
from synth.design.constraints import by_group, physics_inputs
from synth.design.space import (SUBSYSTEMS, core_rows, fixed_fields, pinned_diameter, priced_for, space, space_for,
                                spring_window)
from synth.optimise.objectives import FALLBACK_WEIGHTS, TIE, additive_goals, core_reads, weighted_sum, weighted_sum_around
from synth.optimise import product
from synth.optimise.product import DURABILITY_NOTE, core_scores, design_totals, option_scores
from synth.errors import InputError
from synth.kernels import engines, main_spring
from synth import catalog
from synth.design.verify import evaluate_design, parts_of_design
from synth.design.subsystems import SubTable, family, scatter
from synth.design.bolt_group import fixation_codes
from synth.design.combine import join, near_figures

__all__ = ["Batch", "wsum", "SLACK", "MARGIN_EPS", "any_feasible", "designs_pass", "robust"]

#: relative slack of the score cuts (a cut never removes a design within 1e-9 of the best: rounding is far below)
SLACK = 1e-9
#: the margin threshold's tolerance of the exact solver's lexicographic orders with the margin
#: (:data:`synth.optimise.solvers.enumerate._EPS`): an option passes the threshold ``tau`` when its margin is >= tau - 1e-9
MARGIN_EPS = 1e-9


def _bolt_ids(core_values: dict) -> tuple[tuple, tuple]:
    """The bolt group's non-advisory checks as the registry holds them now (a check added with ``register``
    included; read per batch, never frozen at import): ``(per application and bolt, per core and bolt)``, the
    second those that read the core (``core_values``: a core group's values;
    :func:`~synth.design.evaluate.bolt_core_checks`: the pivot wall)."""
    core = {c.id for c in evaluate.bolt_core_checks(core_values)}
    ids = [c.id for c in by_group("bolt") if not c.advisory]
    return tuple(i for i in ids if i not in core), tuple(i for i in ids if i in core)


#: the additive score of many designs (:func:`synth.optimise.objectives.weighted_sum`)
wsum = weighted_sum


def _first_true(mask: np.ndarray) -> np.ndarray:
    """Per row of a 2-D boolean array, the first True column (-1: none)."""
    if mask.shape[1] == 0:
        return np.full(mask.shape[0], -1, dtype=np.int64)
    return np.where(mask.any(axis=1), np.argmax(mask, axis=1), -1)


def _argmax_value(vals: np.ndarray, cols: np.ndarray):
    """Per row, ``(value, option)`` of ``numpy.argmax`` over the full option axis, where only ``cols`` (sorted
    option indices) are available and the others are -inf: the first index of the maximum, option 0 when every
    available value is -inf (as the enumeration's argmax over -inf rows)."""
    if vals.shape[1] == 0:
        return np.full(vals.shape[0], -np.inf), np.zeros(vals.shape[0], dtype=np.int64)
    j = np.argmax(vals, axis=1)
    v = vals[np.arange(len(vals)), j]
    return v, np.where(v > -np.inf, cols[j], 0)


def _unique_rows(*cols):
    """``(first, inverse)``: one representative position per distinct tuple of the columns (floats; NaN equal to
    NaN), and each position's representative index."""
    stack = np.stack([np.asarray(c, dtype=float) for c in cols], axis=1)
    if not len(stack):
        return np.zeros(0, dtype=np.int64), np.zeros(0, dtype=np.int64)
    stack = np.where(np.isnan(stack), np.finfo(float).max, stack)  # NaN keys compare equal
    stack = stack + 0.0  # -0.0 -> 0.0: equal keys, equal bits
    # a stable lexicographic sort and the row changes: np.unique(axis=0)'s groups, in its order, several
    # times faster (np.unique sorts a structured view)
    order = np.lexsort(stack.T[::-1])
    srt = stack[order]
    new = np.ones(len(srt), dtype=bool)
    new[1:] = (srt[1:] != srt[:-1]).any(axis=1)
    inv = np.empty(len(srt), dtype=np.int64)
    inv[order] = np.cumsum(new) - 1
    return order[new].astype(np.int64), inv


def _segments(starts, counts):
    """Concatenated ``arange(start, start + count)`` of every segment."""
    counts = np.asarray(counts, dtype=np.int64)
    tot = int(counts.sum())
    if not tot:
        return np.zeros(0, dtype=np.int64)
    offs = np.repeat(np.asarray(starts, dtype=np.int64) - np.cumsum(counts) + counts, counts)
    return offs + np.arange(tot, dtype=np.int64)


def _rounds(pos, seg_end, block: int, may, still=None):
    """The rounds of a branch and bound over segments of sorted candidates (one segment per application):
    each round takes, in every live segment, the next ``block`` positions (doubling every round) that ``may``
    still win, and yields them (non-empty). A segment is live while it has positions left, its next one may
    win and ``still()`` (evaluated each round: the incumbents change) holds for it. ``pos`` advances in place."""
    while True:
        live = (pos < seg_end) & may(np.minimum(pos, seg_end - 1))
        if still is not None:
            live &= still()
        if not live.any():
            return
        cnt = np.minimum(block, seg_end - pos)
        take = _segments(pos[live], cnt[live])
        take = take[may(take)]
        pos[live] = pos[live] + cnt[live]
        block *= 2
        if len(take):
            yield take


def _n_units(unit) -> int:
    """The number of evaluation units of :meth:`Batch._tie_units` (core rows, or spring keys)."""
    return len(unit["app"]) if isinstance(unit, dict) else len(unit)


def _restrict(cand, keep):
    """The candidates of :meth:`Batch._tie_candidates` of the rows ``keep`` (a mask of its rows) only."""
    inv, unit, (ui, oo), sc = cand
    used = np.zeros(_n_units(unit), dtype=bool)
    used[inv[keep]] = True
    m = used[ui]
    return inv[keep], unit, (ui[m], oo[m]), sc[m]


def _tie_pick(found: list, R, a_of, cs, core_m, evaluated: dict) -> list:
    """``found`` with the design of the margin tie-break where the tied cores ``R`` (applications ``a_of``, core
    scores ``cs``, objective margins ``core_m``) and their tied options (``evaluated``: per subsystem, what
    :meth:`Batch._tie_evaluate` returns) give one, as :func:`synth.optimise.solvers.enumerate.solve_space` takes
    it: the threshold ``tau`` is the largest design margin of a tied design (0 when it is within 1e-9 below 0,
    none when below), per core and subsystem the first option in score order whose margin reaches ``tau - 1e-9``,
    and the core of the smallest total (summed as the solver sums it), the first row of equal totals."""
    n = len(found)
    design_m = np.asarray(core_m, dtype=float).copy()
    unit_app = {}
    for s, (inv, ui, oo, sc, m, nu) in evaluated.items():
        best = np.full(nu, -np.inf)
        np.maximum.at(best, ui, m)
        design_m = np.minimum(design_m, best[inv])
        unit_app[s] = np.zeros(nu, dtype=np.int64)
        unit_app[s][inv] = a_of
    m_star = np.full(n, -np.inf)
    np.maximum.at(m_star, a_of, design_m)
    tau = np.where(m_star >= 0, m_star, np.where(m_star >= -MARGIN_EPS, 0.0, -np.inf))
    thr = tau - MARGIN_EPS
    total = np.where(core_m >= thr[a_of], cs, np.inf)
    picks = {}
    for s in SUBSYSTEMS:
        inv, ui, oo, sc, m, nu = evaluated[s]
        reach = np.flatnonzero(m >= thr[unit_app[s][ui]])  # in score order within each unit
        u, at = np.unique(ui[reach], return_index=True)
        ch_o, ch_sc = np.full(nu, -1, dtype=np.int64), np.full(nu, np.inf)
        ch_o[u], ch_sc[u] = oo[reach[at]], sc[reach[at]]
        total = total + ch_sc[inv]
        picks[s] = ch_o[inv]
    o = np.lexsort((R, total, a_of))
    o = o[np.isfinite(total[o])]
    out = list(found)
    for i, j in zip(*np.unique(a_of[o], return_index=True)):
        j = o[j]
        out[int(i)] = (int(R[j]), {s: int(picks[s][j]) for s in SUBSYSTEMS})
    return out


def _space_of(inputs: list, pin_inputs):
    """The one design space of a batch: the whole catalog product, or the one keeping the parts the inputs name
    (``pin_inputs``), which must then be the same parts for every input (a relaxation's probes change other
    inputs)."""
    if not pin_inputs or not inputs:
        return priced_for(space(), inputs)
    first = [(n, getattr(inputs[0], n)) for n in fixed_fields(inputs[0], pin_inputs)]
    for d in inputs[1:]:
        if [(n, getattr(d, n)) for n in fixed_fields(d, pin_inputs)] != first:
            raise ValueError("a batch keeps one set of input parts: every input must name the same ones")
    return space_for(inputs[0], pin_inputs, inputs)


class Batch:
    """N applications and their decomposed design space on the applications axis (see the module docstring).

    ``spring_engine``: the engine this path takes (:func:`synth.kernels.engines.preferred`): ``"numba"`` (the
    compiled kernels; imports numba on first use) or ``"numpy"`` (their twins, the registry's group on blocks: the
    one-application path, which must not import numba); the configuration ``settings`` may ask for another, and the
    compiled spring kernels run only where they cover the registry's checks under it
    (:func:`synth.kernels.engines.spring`); the axial group's physics runs on the engine asked for
    (:mod:`synth.kernels.axial`).
    """

    def __init__(self, inputs, settings: evaluate.Settings = evaluate.Settings(), *, pin_inputs: bool = False,
                 spring_engine: str = "numba", apps: Applications | None = None):
        self.inputs = list(inputs)
        self.settings = settings
        # the one decision (synth.kernels.engines): the compiled spring kernels only where they cover the
        # registry's checks under the settings (rules, limit basis), the axial twins (physics only) wherever asked
        self.engine = engines.spring(settings, spring_engine)
        self.axial_engine = engines.axial(settings, spring_engine)
        self.score_engine = engines.preferred(settings, spring_engine)  # the spring lists' scores (no limits)
        self.sp = sp = _space_of(self.inputs, pin_inputs)
        self.pin_inputs = pin_inputs
        self.apps = apps if apps is not None else Applications.of(self.inputs)
        n = len(self.inputs)
        per = [core_rows(sp, d) for d in self.inputs]
        counts = np.array([len(c) for c in per], dtype=np.int64)
        self.ptr = np.concatenate([[0], np.cumsum(counts)]).astype(np.int64)
        self.A = np.repeat(np.arange(n, dtype=np.int64), counts)
        self.C = np.concatenate(per).astype(np.int64) if n else np.zeros(0, dtype=np.int64)
        self.evaluations = len(self.C)
        with np.errstate(over="ignore", divide="ignore", invalid="ignore"):
            self.ig = evaluate.inputs(self.apps, np.arange(n), settings)
            self.cg = evaluate.core(self.apps, self.A, sp.rows_read("core", self.C), settings)
        self._bolt_ids, self._bolt_core_ids = _bolt_ids(self.cg.values)
        self.in_ok = self.ig.ok()
        self.in_min = self.ig.min_margin(objective_only=False)
        self.core_ok = self.cg.ok() & self.in_ok[self.A]
        self.pad = np.asarray(self.cg.values["axial_group_present"], dtype=float) > 0
        self._fix = None
        self._wall_d = None
        self._spring_range = None
        self._memo: dict = {}
        self._spring_opts = None
        self._axial_undecided = np.zeros(n, dtype=bool)
        self._ax_slot: dict = {}  # the search model's axial smallest margins, kept (:meth:`_axial_kept`)
        self._ax_mm = np.zeros((0, sp.n("axial")))
        self._ax_known = np.zeros((0, sp.n("axial")), dtype=bool)
        self._screened = None  # the screening settings while optimum() searches with the full model alone
        self._last, self._redone = None, set()  # the last optimum()'s search state and re-searched applications

    def __len__(self) -> int:
        return len(self.inputs)

    # ------------------------------------------------------------------------------------------- bushing
    def _bushing(self, rows, weights=None):
        """Per core row: with ``weights``, ``(score, option)`` of the first feasible bushing in score order (inf,
        -1 when none); without, ``(value, option)`` of the largest smallest margin (the enumeration's argmax)."""
        return self._paired(family("bushing"), rows, weights)

    def _paired(self, fam, rows, weights=None):
        """:meth:`_bushing` for any family judged pair by pair (its declaration's ``group``): its group evaluated
        once per distinct (application, matched core values, what it reads of the core) over the options the
        declaration makes available (:mod:`synth.design.subsystems`)."""
        sp, cg = self.sp, self.cg
        n_r = len(rows)
        out_v = np.full(n_r, np.inf if weights is not None else -np.inf)
        out_k = np.full(n_r, -1 if weights is not None else 0, dtype=np.int64)
        if not n_r:
            return out_v, out_k
        match = [cg.values[cv][rows] for cv, _ in fam.match]
        first, inv = _unique_rows(self.A[rows], *match, *(cg.values[k][rows] for k in fam.core_reads(cg.values)))
        rep = rows[first]
        score = wsum(option_scores(sp, fam.name), weights) if weights is not None else None
        res_v = np.empty(len(rep))
        res_k = np.empty(len(rep), dtype=np.int64)
        if match:
            mfirst, minv = _unique_rows(*(m[first] for m in match))
        else:
            mfirst, minv = np.zeros(min(len(rep), 1), dtype=np.int64), np.zeros(len(rep), dtype=np.int64)
        for u in range(len(mfirst)):
            sel = np.flatnonzero(minv == u)
            opts = np.flatnonzero(fam.available(sp, cg.values, rep[sel[:1]])[0])  # index order
            rr, oo = np.repeat(rep[sel], len(opts)), np.tile(opts, len(sel))
            with np.errstate(over="ignore", divide="ignore", invalid="ignore"):
                g = fam.group(self.apps, cg, rr, sp.rows(fam.name, oo), self.settings)
            self.evaluations += len(rr)
            if weights is not None and not len(opts):  # none available: no feasible option
                res_k[sel], res_v[sel] = -1, np.inf
            elif weights is not None:
                order = np.argsort(score[opts], kind="stable")
                ok = g.ok().reshape(len(sel), len(opts))[:, order]
                j = _first_true(ok)
                res_k[sel] = np.where(j >= 0, opts[order][j], -1)
                res_v[sel] = np.where(j >= 0, score[opts[order][j]], np.inf)
            else:
                v, k = _argmax_value(g.min_margin(objective_only=False).reshape(len(sel), len(opts)), opts)
                res_v[sel], res_k[sel] = v, k
        return res_v[inv], res_k[inv]

    # ------------------------------------------------------------------------------------------- bolt
    def _bolt_app(self, which, bolts):
        """Per application x bolt: every step-10 check passes (``ok``), and their smallest margin (``min``),
        the pivot wall apart; evaluated on demand for the applications ``which`` x ``bolts`` not done yet (one
        fixation call per bolt over its applications) and kept for the batch."""
        sp, n = self.sp, len(self)
        nb = sp.n("bolt")
        if self._fix is None:
            self._fix = (np.zeros((n, nb), dtype=bool), np.full((n, nb), -np.inf), np.zeros((n, nb), dtype=bool))
            self._fix_near = (np.full((n, nb), -np.inf), np.zeros((n, nb)))
        ok, mn, done = self._fix
        which = np.asarray(which, dtype=np.int64)
        which = which[np.diff(self.ptr)[which] > 0]
        bolts = np.asarray(bolts, dtype=np.int64)
        ai, bi = np.nonzero(~done[np.ix_(which, bolts)])
        if len(ai):
            a, b = which[ai], bolts[bi]
            o = sp.rows_read("bolt", b)
            code, rep = self._fixation_keys()
            nk = len(rep)
            # the fixation once per (application, distinct bolt as the fixation reads it), gathered per row
            up, inv = np.unique(a * nk + code[b], return_inverse=True)
            with np.errstate(over="ignore", divide="ignore", invalid="ignore"):
                once = evaluate.fixation_values(self.apps, up // nk, sp.rows_read("bolt", rep[up % nk]), self.settings)
                inv = np.asarray(inv).reshape(-1)
                fix = {k: v[inv] for k, v in once.items()}
                g = evaluate.bolt(self.apps, self.cg, self.ptr[a], o, self.settings, fixation=fix)
            self.evaluations += len(a)
            m = np.full(len(a), np.inf)
            for cid in self._bolt_ids:
                m = np.minimum(m, g.margins[cid])
            ok[a, b], mn[a, b], done[a, b] = passes(m), m, True
            if self._bolt_ids:  # the second smallest and the failing count, for the nearest design's key
                _, self._fix_near[0][a, b], self._fix_near[1][a, b] = near_figures(
                    np.stack([g.margins[cid] for cid in self._bolt_ids], axis=1))
            else:
                self._fix_near[0][a, b] = np.inf
        return ok, mn

    def _fixation_keys(self):
        """``(code per bolt, a representative bolt per code)``: bolts equal in every column the fixation reads
        (:func:`synth.design.bolt_group.fixation_codes`: the format, property class, head form, washer, and the
        tightening method under the VDI 2230 method) share a code, so the same fixation for any application."""
        if "fixation_keys" not in self._memo:
            self._memo["fixation_keys"] = fixation_codes(self.sp.tables["bolt"], self.settings)
        return self._memo["fixation_keys"]

    def _wall(self, rows):
        """``(margins (len(rows), n_codes), code per bolt)``: the smallest margin of the bolt checks that read the
        core (the pivot wall of step 2) per core row and distinct value of the bolt columns they read (the
        diameter), and each bolt's code."""
        sp = self.sp
        if self._wall_d is None:
            t = sp.tables["bolt"]
            cols = ["bolt_d_mm", *sorted({k for c in by_group("bolt") if c.id in self._bolt_core_ids
                                          for k in physics_inputs(c) if k in t and k != "bolt_d_mm"})]
            first, code = _unique_rows(*(t[k] for k in cols))
            self._wall_d = ({k: np.asarray(t[k])[first] for k in cols}, code)
        o, code = self._wall_d
        nd, nr = len(o["bolt_d_mm"]), len(rows)
        m = np.full((nr, nd), np.inf)
        if self._bolt_core_ids and nr and nd:
            with np.errstate(over="ignore", divide="ignore", invalid="ignore"):
                g = evaluate.bolt_core(self.apps, np.broadcast_to(self.A[rows][:, None], (nr, nd)),
                                       {k: self.cg.values[k][rows][:, None]
                                        for k in evaluate.core_values("bolt", self.cg.values)},
                                       {k: v[None, :] for k, v in o.items()}, self.settings)
            for cid in self._bolt_core_ids:
                m = np.minimum(m, g.margins[cid])
        return m, code

    def _bolt(self, rows, weights=None):
        """Per core row, as :meth:`_bushing` for the bolt: the first feasible bolt in score order (with
        ``weights``), or the largest smallest margin (its value; :meth:`_bolt_pick` gives the option).

        A bolt is feasible for a core when its step-10 checks pass for the application and the pivot wall
        passes for the core and the bolt's diameter: bolts are scanned in score order in blocks (the step-10
        checks of a block evaluated for the applications still looking). The best margin is the largest, over
        the diameters, of the smaller of the diameter's best step-10 margin and its wall margin.
        """
        wall, code = self._wall(rows)
        a = self.A[rows]
        nb = self.sp.n("bolt")
        if weights is None:
            ua = np.unique(a)
            _, min_app = self._bolt_app(ua, np.arange(nb))
            best = np.full((len(self), wall.shape[1]), -np.inf)
            for dc in range(wall.shape[1]):
                if (code == dc).any():
                    best[ua, dc] = min_app[ua][:, code == dc].max(axis=1)
            return np.minimum(best[a], wall).max(axis=1), None
        key = ("bolt", tuple(sorted(weights.items())))
        if key not in self._memo:
            score = wsum(option_scores(self.sp, "bolt"), weights)
            self._memo[key] = (score, np.argsort(score, kind="stable"))
        score, order = self._memo[key]
        k = np.full(len(rows), -1, dtype=np.int64)
        active = np.arange(len(rows))
        # a fixation call costs about as much for one application as for a hundred: a few applications take
        # every bolt at once, a chunk the cheap ones first (numerics: the same answer either way)
        pos, block = 0, nb if len(self) <= 16 else 8
        while len(active) and pos < nb:
            blk = order[pos:pos + block]
            ua = np.unique(a[active])
            ok_app, _ = self._bolt_app(ua, blk)
            # only the rows of an application with a bolt of the block that passes its step-10 checks can hit
            some = np.zeros(len(self), dtype=bool)
            some[ua] = ok_app[ua[:, None], blk[None, :]].any(axis=1)
            cand = np.flatnonzero(some[a[active]])
            rows_c = active[cand]
            feas = ok_app[a[rows_c][:, None], blk[None, :]] & passes(wall[rows_c[:, None], code[blk][None, :]])
            j = _first_true(feas)
            hit = j >= 0
            k[rows_c[hit]] = blk[j[hit]]
            keep = np.ones(len(active), dtype=bool)
            keep[cand[hit]] = False
            active = active[keep]
            pos += len(blk)
            block *= 4
        return np.where(k >= 0, score[np.maximum(k, 0)], np.inf), k

    def _bolt_pick(self, rows):
        """The enumeration's argmax bolt of core rows (first index of the largest smallest margin)."""
        wall, code = self._wall(rows)
        a = self.A[rows]
        _, min_app = self._bolt_app(np.unique(a), np.arange(self.sp.n("bolt")))
        vals = np.minimum(min_app[a], wall[:, code])
        return _argmax_value(vals, np.arange(vals.shape[1]))[1]

    # ------------------------------------------------------------------------------------------- spring
    def _ranges(self):
        """Per application, the mean-diameter range of the springs searched (the enumeration's, over every core)
        as a group code, and the groups' option lists (index order)."""
        if self._spring_range is None:
            sp = self.sp
            mbd = sp.tables["spring"]["main_spring_mean_body_diameter_mm"]
            n = len(self)
            lo, hi = np.full(n, np.nan), np.full(n, np.nan)
            has = np.diff(self.ptr) > 0
            inner = self.cg.values["spring_housing_inner_diameter_mm"]
            outer = self.cg.values["spring_housing_outer_diameter_mm"]
            if has.any():
                st = self.ptr[:-1][has]
                lo[has], hi[has] = spring_window(np.minimum.reduceat(inner, st), np.maximum.reduceat(outer, st))
            first, inv = _unique_rows(lo, hi)
            lists = [np.flatnonzero((mbd >= lo[i]) & (mbd <= hi[i]) | pinned_diameter(sp)) for i in first]
            self._spring_range = (inv, lists)
        return self._spring_range

    def _options(self):
        if self._spring_opts is None:
            self._spring_opts = main_spring.options_of_space(self.sp.tables["spring"])
        return self._spring_opts

    def _spring_app_lists(self, weights):
        """The spring candidates of every application in its own score order (ties by index), shared: ``(lists,
        list_of_app, smallest score, positions, (the lists end to end, where each starts))``. The scores follow each application's stiffness (the cost is
        per unit compliance over it); the applications of one mean-diameter range share the range's order when
        their scores keep it (checked per application, every adjacent pair), else get their own stable sort."""
        key = ("spring", tuple(sorted(weights.items())))
        if key in self._memo:
            return self._memo[key]
        sp = self.sp
        inv, ranges = self._ranges()
        k = self.apps.spring_stiffness_nm_per_deg
        base = wsum(option_scores(sp, "spring", 1.0), weights)
        order_all = np.argsort(base, kind="stable")
        lists: list = []
        list_of = np.full(len(self), -1, dtype=np.int64)
        smin = np.full(len(self), np.inf)
        for g, lst in enumerate(ranges):
            apps_g = np.flatnonzero(inv == g)
            if not len(apps_g) or not len(lst):
                continue
            in_rng = np.zeros(sp.n("spring"), dtype=bool)
            in_rng[lst] = True
            cand = order_all[in_rng[order_all]]  # the range's options in the base order
            first, good = self._list_order(weights, k[apps_g], cand)
            lid = len(lists)
            lists.append(cand)
            for j, i in enumerate(apps_g):
                if good[j]:
                    list_of[i], smin[i] = lid, first[j]
                else:  # this stiffness reorders (rounding ties): its own stable sort
                    s_i = wsum(option_scores(sp, "spring", k[i], lst), weights)
                    o = np.argsort(s_i, kind="stable")
                    list_of[i] = len(lists)
                    lists.append(lst[o])
                    smin[i] = s_i[o][0]
        positions = [np.arange(len(x), dtype=float) for x in lists]
        flat = np.concatenate(lists) if lists else np.zeros(0, dtype=np.int64)
        start = np.concatenate([[0], np.cumsum([len(x) for x in lists])]).astype(np.int64)
        self._memo[key] = (lists, list_of, smin, positions, (flat, start))
        return self._memo[key]

    def _list_order(self, weights, stiffness, cand):
        """``(first, good)`` of the springs ``cand`` (a list in the base order) for applications of ``stiffness``:
        ``good[a]`` whether the list keeps its order for that application (the additive score of
        :func:`~synth.optimise.objectives.weighted_sum` grows along it, or ties with a growing index: every
        adjacent pair), ``first[a]`` the score of its first spring. The compiled engine computes both in one pass
        with nothing stored per pair (the score's per-option terms once,
        :func:`~synth.kernels._main_spring_scans_jit.list_order`), the same doubles as numpy's scores."""
        sp = self.sp
        per_k = [g.name for g in additive_goals() if g.per_stiffness]
        if self.score_engine == "numba" and per_k[0] in weights:
            n = len(cand)
            before, w, after = weighted_sum_around(option_scores(sp, "spring", 1.0, cand), weights, per_k[0])
            pre = np.ascontiguousarray(np.broadcast_to(np.asarray(before, dtype=float), (n,)))
            post = np.array([np.broadcast_to(np.asarray(t, dtype=float), (n,)) for t in after],
                            dtype=float).reshape(len(after), n)
            unit = np.ascontiguousarray(sp.tables["spring"]["cost_eur_times_stiffness"][cand], dtype=float)
            first, good = np.full(len(stiffness), np.nan), np.empty(len(stiffness), dtype=bool)
            main_spring.load_scans().list_order(pre, unit, float(w), post,
                                                  np.ascontiguousarray(stiffness, dtype=float),
                                                  np.ascontiguousarray(cand, dtype=np.int64), first, good)
            return first, good
        sc = np.broadcast_to(wsum(option_scores(sp, "spring", stiffness[:, None], cand[None, :]), weights),
                             (len(stiffness), len(cand)))
        d = np.diff(sc, axis=1)
        return sc[:, 0].copy(), ((d > 0) | ((d == 0) & (np.diff(cand) > 0)[None, :])).all(axis=1)

    def _spring_keys(self, rows):
        """``(keys dict, inverse)``: the distinct spring keys of core rows (application and what the spring sees)."""
        kd = evaluate.spring_keys(self.cg, rows)
        first, inv = _unique_rows(kd["app"], *(kd[k] for k in kd if k != "app"))
        return {k: v[first] for k, v in kd.items()}, inv

    def _spring_first(self, keys, limit, weights):
        """Per key: ``(score, option)`` of the first feasible spring of its application's score-ordered list with
        a score at most ``limit`` (inf, -1: none). The score cut is a position cut in the list (the scores
        grow along it): the kernel's score is the position."""
        lists, list_of, _, positions, _ = self._spring_app_lists(weights)
        apps_k = keys["app"]
        grp = list_of[apps_k]
        last = self._last_within(weights, apps_k, limit)
        kk = main_spring.keys_of_rows(self.apps, keys)
        r = main_spring.first_feasible(kk, self._options(), lists, key_group=grp, score=positions, score_limit=last,
                                       engine=self.engine, settings=self.settings)
        self.evaluations += int(r.visited.sum())
        out = np.full(len(apps_k), np.inf)
        hit = np.flatnonzero(r.index >= 0)
        out[hit] = self._spring_scores(weights, apps_k[hit], r.index[hit])  # the chosen option's score
        return out, np.where(r.index >= 0, r.index, -1)

    def _last_within(self, weights, apps_i, limit) -> np.ndarray:
        """Per application of ``apps_i``: the last position of its spring list whose score is at most ``limit``
        (``searchsorted(scores, limit, "right") - 1`` of the list's scores, which never decrease along it; -1 when
        none, inf where the limit is not finite), bisected for all at once: log2(list) scores each."""
        _, list_of, _, _, (flat, start) = self._spring_app_lists(weights)
        grp = list_of[apps_i]
        last = np.full(len(apps_i), np.inf)
        fin = np.flatnonzero(np.isfinite(limit))
        lo, hi = np.zeros(len(fin), dtype=np.int64), start[grp[fin] + 1] - start[grp[fin]]
        act = np.flatnonzero(lo < hi)
        while len(act):
            j, mid = fin[act], (lo[act] + hi[act]) // 2
            right = self._spring_scores(weights, apps_i[j], flat[start[grp[j]] + mid]) <= limit[j]
            lo[act[right]] = mid[right] + 1
            hi[act[~right]] = mid[~right]
            act = act[lo[act] < hi[act]]
        last[fin] = lo - 1.0
        return last

    def _spring_scores(self, weights, apps_i, options) -> np.ndarray:
        """The additive scores of springs ``options`` for applications ``apps_i`` (pairwise): the doubles of the
        lists' scores (the cost per unit compliance over each application's stiffness, summed as
        :func:`~synth.optimise.objectives.weighted_sum`)."""
        return np.asarray(wsum(option_scores(self.sp, "spring", self.apps.spring_stiffness_nm_per_deg[apps_i],
                                             options), weights), dtype=float)

    def _spring_max(self, keys, cap=None):
        """Per key: ``(value, option)`` of the largest smallest margin over its application's range (index
        order, first of the ties; option 0 when every value is -inf); ``cap``: exact below it."""
        inv, lists = self._ranges()
        grp = inv[keys["app"]]
        kk = main_spring.keys_of_rows(self.apps, keys)
        r = main_spring.max_min_margin(kk, self._options(), lists, key_group=grp, cap=cap, engine=self.engine,
                                       settings=self.settings)
        self.evaluations += int(r.visited.sum())
        v = np.asarray(r.value, dtype=float)
        return v, np.where((r.index >= 0) & (v > -np.inf), r.index, 0)

    # ------------------------------------------------------------------------------------------- axial
    def _axial_rows(self, rows):
        first, inv = _unique_rows(self.A[rows], *(self.cg.values[k][rows]
                                                  for k in evaluate.core_values("axial", self.cg.values)))
        return rows[first], inv

    def _axial_slots(self, rep) -> np.ndarray:
        """Per representative core row (:meth:`_axial_rows`), its row in the kept axial margins: one per distinct
        application and value of what the axial group reads of the core, whichever call met it first."""
        vals = np.stack([self.A[rep], *(self.cg.values[k][rep]
                                        for k in evaluate.core_values("axial", self.cg.values))], axis=1)
        vals = np.where(np.isnan(vals), np.finfo(float).max, vals) + 0.0  # as _unique_rows: NaN equal, -0.0 = 0.0
        slot = self._ax_slot
        out = np.array([slot.setdefault(k, len(slot)) for k in
                        np.ascontiguousarray(vals).view(np.dtype((np.void, 8 * vals.shape[1]))).ravel().tolist()],
                       dtype=np.int64)
        if len(slot) > len(self._ax_mm):  # grow (doubling)
            m = max(len(slot), 2 * len(self._ax_mm))
            self._ax_mm = np.concatenate([self._ax_mm, np.zeros((m - len(self._ax_mm), self._ax_mm.shape[1]))])
            self._ax_known = np.concatenate([self._ax_known, np.zeros((m - len(self._ax_known),
                                                                       self._ax_known.shape[1]), dtype=bool)])
        return out

    def _axial_keep(self, slots, cols, g: evaluate.Group) -> None:
        """Keep the smallest margins of an axial group of the search model (slots x options, pairwise)."""
        if self._screened is None:
            self._ax_mm[slots, cols] = g.min_margin(objective_only=False)
            self._ax_known[slots, cols] = True

    def _axial_eval(self, rr, oo, settings: evaluate.Settings | None = None):
        """The axial group of core rows ``rr`` and options ``oo`` (at ``settings``, default the search's; in the
        full model's search of :meth:`optimum`, :func:`~synth.design.evaluate.axial_full`)."""
        with np.errstate(over="ignore", divide="ignore", invalid="ignore"):
            if settings is None and self._screened is not None:
                g = evaluate.axial_full(self.apps, self.cg, rr, self.sp.rows_read("axial", oo), self._screened,
                                        engine=self.axial_engine)
            else:
                g = evaluate.axial(self.apps, self.cg, rr, self.sp.rows_read("axial", oo), settings or self.settings,
                                   engine=self.axial_engine)
        self.evaluations += len(rr)
        return g

    def _axial_passes_before_physics(self, rr, oo) -> np.ndarray:
        """Per pair of core rows ``rr`` and axial options ``oo``: whether it passes the axial checks that read
        nothing of the physics (:func:`~synth.design.evaluate.axial_before_physics`: Table 4's spacer, the belt
        plane, the cone spring's diameters; most pairs of a scan fail one). A pair that fails one fails at any
        fidelity, and its smallest margin is at most that check's: a search need not size its cone spring."""
        with np.errstate(over="ignore", divide="ignore", invalid="ignore"):
            return evaluate.axial_before_physics(self.apps, self.cg, rr, self.sp.rows_read("axial", oo),
                                                 self.settings).ok()

    def _undecided(self, rr, g: evaluate.Group, ok) -> None:
        """Mark the applications of rows ``rr`` (axial group ``g``, its verdicts ``ok`` after the judge) where the
        screening model may have rejected what the full model passes: a row that passes every constraint the
        fidelity does not change (:func:`~synth.design.evaluate.fidelity_free_ok`) and is not kept."""
        if self.settings.judge is not self.settings:
            self._axial_undecided[self.A[np.asarray(rr)[~np.asarray(ok) & evaluate.fidelity_free_ok(g)]]] = True

    def _judged(self, ok: np.ndarray, rr, cols) -> np.ndarray:
        """``ok`` (rows ``rr`` x axial options ``cols``: the search model's verdicts) judged by the full model
        (:attr:`~synth.design.evaluate.Settings.judge`, fidelity ``screening``): every passing pair evaluated again,
        in one call (a full evaluation costs about 10 ms a call and 5 us a row: one call per block of the scan),
        and kept where the full model passes it too. The screening model orders and prunes; the full model
        decides."""
        judge = self.settings.judge
        if judge is self.settings or not ok.any():
            return ok
        ri, ci = np.nonzero(ok)
        out = np.zeros_like(ok)
        out[ri, ci] = self._axial_eval(np.asarray(rr)[ri], np.asarray(cols)[ci], judge).ok()
        return out

    def _axial_blocks(self):
        return int(catalog.constant("bulk_axial_first_block")), max(int(catalog.constant("bulk_axial_block_growth")), 1)

    def _axial_first(self, rows, limit, weights):
        """Per core row: ``(score, option)`` of the first feasible axial option in score order with a score at
        most ``limit`` (the none option for a core without a damper pad)."""
        sp = self.sp
        t = sp.tables["axial"]
        score = wsum(option_scores(sp, "axial"), weights)
        rep, inv = self._axial_rows(rows)
        slots = self._axial_slots(rep) if self._screened is None else None
        lim = np.full(len(rep), -np.inf)
        np.maximum.at(lim, inv, limit)
        out_v, out_k = np.full(len(rep), np.inf), np.full(len(rep), -1, dtype=np.int64)
        pad = self.pad[rep]
        none = np.flatnonzero(~t["axial_group_present"])
        real = np.flatnonzero(t["axial_group_present"])
        order = real[np.argsort(score[real], kind="stable")]
        sel = np.flatnonzero(~pad)
        if len(sel):  # one option: none (it may still fail, e.g. the belt plane)
            g = self._axial_eval(rep[sel], np.full(len(sel), none[0]))
            okn = self._judged((g.ok() & (score[none[0]] <= lim[sel]))[:, None], rep[sel], none[:1])[:, 0]
            self._undecided(rep[sel], g, okn)
            out_v[sel] = np.where(okn, score[none[0]], np.inf)
            out_k[sel] = np.where(okn, none[0], -1)
        active = np.flatnonzero(pad)
        pos, (block, growth) = 0, self._axial_blocks()
        while len(active) and pos < len(order):
            blk = order[pos:pos + block]
            within = score[blk][None, :] <= lim[active][:, None]
            active = active[within[:, 0]]  # scores grow along the order: a row past its limit is done
            within = within[within[:, 0]]
            if not len(active):
                break
            ai, bi = np.nonzero(within)
            pre = self._axial_passes_before_physics(rep[active[ai]], blk[bi])  # the others fail: no physics
            ai, bi = ai[pre], bi[pre]
            ok = np.zeros(within.shape, dtype=bool)
            if len(ai):
                g = self._axial_eval(rep[active[ai]], blk[bi])
                if slots is not None:
                    self._axial_keep(slots[active[ai]], blk[bi], g)
                ok[ai, bi] = g.ok()
                ok = self._judged(ok, rep[active], blk)
                self._undecided(rep[active[ai]], g, ok[ai, bi])
            j = _first_true(ok)
            hit = j >= 0
            out_k[active[hit]] = blk[j[hit]]
            out_v[active[hit]] = score[blk[j[hit]]]
            keep = ~hit & within[:, -1]
            active = active[keep]
            pos += len(blk)
            block *= growth
        return out_v[inv], out_k[inv]

    def _axial_max(self, rows, cap=None):
        """Per core row: ``(value, option)`` of the largest smallest margin over its axial options (the none
        option without a pad); ``cap``: the search stops once a row reaches it (exact below it); without a cap
        the enumeration's argmax (index order, first of the ties)."""
        sp = self.sp
        t = sp.tables["axial"]
        rep, inv = self._axial_rows(rows)
        cp = np.full(len(rep), np.inf)
        if cap is not None:
            cp = np.full(len(rep), -np.inf)
            np.maximum.at(cp, inv, cap)
        pad = self.pad[rep]
        none = np.flatnonzero(~t["axial_group_present"])
        real = np.flatnonzero(t["axial_group_present"])
        out_v, out_k = np.full(len(rep), -np.inf), np.zeros(len(rep), dtype=np.int64)
        sel = np.flatnonzero(~pad)
        if len(sel):
            g = self._axial_eval(rep[sel], np.full(len(sel), none[0]))
            v = g.min_margin(objective_only=False)
            out_v[sel], out_k[sel] = v, np.where(v > -np.inf, none[0], 0)
        active = np.flatnonzero(pad)
        best_pos = np.full(len(rep), len(real), dtype=np.int64)
        pos, (block, growth) = 0, self._axial_blocks()
        slots = self._axial_slots(rep)
        while len(active) and pos < len(real):
            blk = real[pos:pos + block]
            # the pairs the optimum's scan (or an earlier call) evaluated are read back; the others evaluated, kept
            sl = slots[active]
            known = self._ax_known[sl[:, None], blk[None, :]]
            m = self._ax_mm[sl[:, None], blk[None, :]]
            ai, bi = np.nonzero(~known)
            if len(ai):
                g = self._axial_eval(rep[active[ai]], blk[bi])
                m[ai, bi] = g.min_margin(objective_only=False)
                self._axial_keep(sl[ai], blk[bi], g)
            j = np.argmax(m, axis=1)
            v = m[np.arange(len(active)), j]
            better = v > out_v[active]  # strictly: an earlier option keeps a tie (argmax's first index)
            out_v[active[better]] = v[better]
            best_pos[active[better]] = pos + j[better]
            active = active[~(out_v[active] >= cp[active])]
            pos += len(blk)
            block *= growth
        has = pad & (best_pos < len(real)) & (out_v > -np.inf)
        out_k[pad] = np.where(has[pad], real[np.minimum(best_pos[pad], len(real) - 1)], 0)
        return out_v[inv], out_k[inv]

    # ------------------------------------------------------------------------------------------- searches
    def optimum(self, weights: dict, *, first: bool = False, which=None) -> list:
        """Per application (``which``: a subset, default all): ``(core row, {subsystem: option row})`` of the
        smallest additive score ``weights`` (over ``standard``/``cost``), or None when no design is feasible.
        ``first=True``: any feasible design (a feasibility probe), not the best.

        At fidelity ``screening`` the axial options are scanned with the screening model and the passing ones
        judged by the full model (:meth:`_judged`): every design returned passes the full model, and is the best
        that both models pass. An
        application left without a design where the screening model rejected an axial option that passes every
        constraint the fidelity does not change (:meth:`_undecided`) is searched again with the full model alone,
        so that "no design" is the full model's verdict too (elsewhere it cannot depend on the model); that search
        evaluates the full model only where those constraints pass (:func:`~synth.design.evaluate.axial_full`)."""
        out = self._optimum(weights, first=first, which=which)
        judge = self.settings.judge
        redo = ()
        if judge is not self.settings:
            redo = np.flatnonzero(self._axial_undecided & np.array([o is None for o in out], dtype=bool))
            if len(redo):
                last = self._last
                search = self._screened = self.settings
                self.settings = judge
                try:
                    again = self._optimum(weights, first=first, which=redo)
                finally:
                    self.settings, self._screened, self._last = search, None, last
                for i in redo:
                    out[i] = again[i]
        self._redone = set(int(i) for i in redo)  # searched by the full model alone: no tie-break (_last: the first)
        return out

    def optimum_margin_ties(self, weights: dict, which=None) -> list:
        """:meth:`optimum` with its ties broken as the exact solver breaks them for the order ``weights`` then the
        margin (``synth design``'s ``standard,cost,margin``: :func:`synth.optimise.objectives.with_margin_tiebreak`,
        :func:`synth.optimise.solvers.enumerate.solve_space`): among the designs whose score ties the best
        (:func:`synth.optimise.objectives.ties`), the largest design margin (the smallest margin counted in the
        margin objective); among those reaching it, per subsystem the cheapest option in score order whose margin
        reaches it (first index of equal scores), and the core of the smallest total (first row of equal totals).

        From the search's own state (:meth:`_margin_ties`): the cores it finished keep their totals, the others
        whose bound ties the best score are searched now; per tied core and subsystem the candidates are the options
        scoring from the first feasible one's score (a cheaper one failed the scan) to the tie, once per distinct
        value of what the subsystem reads of the core; only the applications with more than one tied design
        evaluate them (one evaluator call per subsystem; the main springs on the compiled kernels where they cover
        the registry's checks).

        >>> from synth.data.generated_applications import generate
        >>> b = Batch(generate(8, seed=7), spring_engine="numpy")
        >>> w = {"cost": 1.0, "standard": 1e4}
        >>> sum(f != t for f, t in zip(b.optimum(w), b.optimum_margin_ties(w)))  # designs of equal score, more margin
        5
        """
        found = self.optimum(weights, which=which)
        return self._margin_ties(weights, found)

    def _margin_ties(self, weights: dict, found: list) -> list:
        """``found`` (:meth:`optimum`'s) with its ties broken by the margin (:meth:`optimum_margin_ties`), from the
        first search's bounds and scores (:attr:`_last`): only the cores it did not finish are searched again,
        and only the applications with more than one tied design evaluate their tied options."""
        last = self._last
        live = np.array([f is not None and i not in self._redone for i, f in enumerate(found)], dtype=bool)
        if last is None or not live.any():
            return found
        inc = last["inc"]  # the best score, summed as the exact solver sums it
        tol = TIE * np.maximum(1.0, np.abs(np.where(np.isfinite(inc), inc, 0.0)))  # objectives.ties
        lim = inc + tol
        j = self._tied_rows(weights, live, lim)
        if not len(j):
            return found
        R, a_of = last["R"][j], last["a_of"][j]
        lo = {"bushing": last["b_sc"][j], "axial": last["a_sc"][j], "spring": last["k_sc"][last["kinv"][j]],
              "bolt": last["t_sc"][j]}
        # per subsystem, the options of each tied core whose score ties its first feasible option's (a cheaper
        # one fails: the search took the first that passes in score order), by evaluation unit (what the
        # subsystem reads of the core)
        cand = {s: self._tie_candidates(s, weights, R, lo[s], lo[s] + tol[a_of]) for s in SUBSYSTEMS}
        # an application with one tied core and one candidate per subsystem has one tied design: found's
        many = np.bincount(a_of, minlength=len(self)) > 1
        for inv, unit, (ui, _), _ in cand.values():
            many[a_of[np.bincount(ui, minlength=_n_units(unit))[inv] > 1]] = True
        keep = many[a_of]
        if not keep.any():
            return found
        R, a_of = R[keep], a_of[keep]
        evaluated = {s: self._tie_evaluate(s, *_restrict(c, keep)) for s, c in cand.items()}
        return _tie_pick(found, R, a_of, last["cs"][j][keep], self.cg.min_margin()[R], evaluated)

    def _tied_rows(self, weights: dict, live, lim) -> np.ndarray:
        """Positions in :attr:`_last` of the cores of the applications ``live`` whose best design scores at most
        ``lim`` (per application): the first search's totals where it finished the core, else searched now (its
        spring and axial scans, cut at ``lim``) and kept."""
        last = self._last
        R, a_of, p0, min_a, t_sc, keys, kinv = (last[k] for k in ("R", "a_of", "p0", "min_a", "t_sc", "keys", "kinv"))
        k_sc, k_pk, a_sc, total = last["k_sc"], last["k_pk"], last["a_sc"], last["total"]
        lim_r = lim[a_of]
        cand = np.flatnonzero(live[a_of] & (last["lb"] <= lim_r))
        todo = cand[~last["done"][cand]]
        if len(todo):
            kt = np.unique(kinv[todo])
            kt = kt[np.isnan(k_sc[kt])]
            if len(kt):  # springs of the keys the first search did not scan
                part = np.full(len(keys["app"]), np.inf)
                np.minimum.at(part, kinv[todo], (p0[todo] + min_a[todo]) + t_sc[todo])
                lk = lim[keys["app"][kt]] - part[kt]
                lk = lk + SLACK * np.maximum(1.0, np.abs(lim[keys["app"][kt]]))
                sub = {k: v[kt] for k, v in keys.items()}
                k_sc[kt], k_pk[kt] = self._spring_first(sub, np.where(np.isfinite(lk), lk, np.inf), weights)
            s = k_sc[kinv[todo]]
            go = np.isfinite(s) & (((p0[todo] + min_a[todo]) + s) + t_sc[todo] <= lim_r[todo])
            ta, s = todo[go], s[go]
            if len(ta):
                la = lim_r[ta] - ((p0[ta] + s) + t_sc[ta]) + SLACK * np.maximum(1.0, np.abs(lim_r[ta]))
                a_sc[ta], last["a_pk"][ta] = self._axial_first(R[ta], np.where(np.isfinite(la), la, np.inf), weights)
                total[ta] = ((p0[ta] + a_sc[ta]) + s) + t_sc[ta]
            last["done"][todo] = True
        return cand[total[cand] <= lim_r[cand]]

    def _tie_units(self, s: str, rows):
        """``(inverse, units)``: the evaluation units of subsystem ``s`` for core rows ``rows`` (one per distinct
        application and value of what ``s`` reads of the core: a spring key for the main spring) and each row's."""
        if s == "spring":
            keys, inv = self._spring_keys(rows)
            return inv, keys
        reads = family(s).core_reads(self.cg.values)
        extra = tuple(self.cg.values[cv][rows] for cv, _ in family(s).match if cv not in reads)  # what it matches on
        first, inv = _unique_rows(self.A[rows], *extra, *(self.cg.values[k][rows] for k in reads))
        return inv, rows[first]

    def _tie_candidates(self, s: str, weights: dict, rows, lo, hi):
        """``(row unit, unit, (unit, option) pairs, their scores)``: per evaluation unit (:meth:`_tie_units`) of
        core rows ``rows``, the options of ``s`` the core may take whose score lies in ``[lo, hi]`` (the row's; a
        unit takes the widest), in score order (ties by index, as the exact solver's ``argmin``)."""
        inv, unit = self._tie_units(s, rows)
        nu = _n_units(unit)
        ulo, uhi = np.full(nu, np.inf), np.full(nu, -np.inf)
        np.minimum.at(ulo, inv, lo)
        np.maximum.at(uhi, inv, hi)
        if s == "spring":  # a range of positions of the application's score-ordered list
            _, list_of, _, _, (flat, start) = self._spring_app_lists(weights)
            apps_u = unit["app"]
            first = self._last_within(weights, apps_u, np.nextafter(ulo, -np.inf)) + 1
            cnt = np.maximum(self._last_within(weights, apps_u, uhi) - first + 1, 0).astype(np.int64)
            ui = np.repeat(np.arange(nu), cnt)
            oo = flat[start[list_of[apps_u]][ui] + first.astype(np.int64)[ui] + _segments(np.zeros(nu), cnt)]
            return inv, unit, (ui, oo), self._spring_scores(weights, apps_u[ui], oo)
        sc = np.asarray(wsum(option_scores(self.sp, s), weights), dtype=float) + np.zeros(self.sp.n(s))
        order = np.argsort(sc, kind="stable")
        a, b = np.searchsorted(sc[order], ulo, "left"), np.searchsorted(sc[order], uhi, "right")
        cnt = np.maximum(b - a, 0)
        ui = np.repeat(np.arange(nu), cnt)
        oo = order[np.repeat(a, cnt) + _segments(np.zeros(nu), cnt)]
        may = family(s).allows(self.sp, self.cg.values, unit[ui], oo)
        ui, oo = ui[may], oo[may]
        return inv, unit, (ui, oo), sc[oo]

    def _tie_evaluate(self, s: str, inv, unit, pairs, scores):
        """The candidates of :meth:`_tie_candidates` that pass every check, with their margins counted in the
        margin objective: ``(row unit, unit index, option, score, margin)`` (the pairs in their order); one
        evaluator call (the main spring: the compiled kernels where they cover the registry's checks)."""
        ui, oo = pairs
        sp, st = self.sp, self.settings
        ok, marg = np.zeros(len(ui), dtype=bool), np.zeros(len(ui))
        if len(ui):
            with np.errstate(over="ignore", divide="ignore", invalid="ignore"):
                if s == "spring":
                    kk = main_spring.keys_of_rows(self.apps, unit)
                    m = main_spring.pair_margins(kk, self._options(), ui, oo, engine=self.engine, settings=st)
                    g = evaluate.Group("spring", {"app": unit["app"][ui]}, dict(zip(main_spring.checks(), m.T)),
                                       rules=st.rules)
                elif s == "axial":
                    pre = self._axial_passes_before_physics(unit[ui], oo)  # the others fail at any fidelity
                    ui, oo, scores, ok, marg = ui[pre], oo[pre], scores[pre], ok[pre], marg[pre]
                    g = evaluate.axial_judged(self.apps, self.cg, unit[ui], sp.rows(s, oo), st,
                                              engine=self.axial_engine)
                elif family(s).group is not None:  # judged pair by pair by its declared group (the bushing)
                    g = family(s).group(self.apps, self.cg, unit[ui], sp.rows(s, oo), st)
                else:
                    o = sp.rows(s, oo)
                    g = evaluate.bolt(self.apps, self.cg, unit[ui], o, st,
                                      fixation=evaluate.fixation_values(self.apps, self.A[unit[ui]], o, st))
            if len(ui):
                a = g.assessment()
                ok, marg = a.ok, a.objective_margin
            self.evaluations += len(ui)
        return inv, ui[ok], oo[ok], scores[ok], marg[ok], _n_units(unit)


    def _optimum(self, weights: dict, *, first: bool = False, which=None) -> list:
        n = len(self)
        want = np.ones(n, dtype=bool) if which is None else np.isin(np.arange(n), which)
        R = np.flatnonzero(self.core_ok & want[self.A])
        out: list = [None] * n
        self._axial_undecided = np.zeros(n, dtype=bool)
        if not len(R):
            return out
        sp, cg = self.sp, self.cg
        cs = wsum(core_scores(sp, self.C[R], {k: cg.values[k][R] for k in core_reads()}), weights)
        b_sc, b_pk = self._bushing(R, weights)
        t_sc, t_pk = self._bolt(R, weights)
        ax_sc = wsum(option_scores(sp, "axial"), weights)
        real = sp.tables["axial"]["axial_group_present"]
        min_a = np.where(self.pad[R], ax_sc[real].min() if real.any() else np.inf, ax_sc[~real].min())
        smin = self._spring_app_lists(weights)[2]
        a_of = self.A[R]
        p0 = cs + b_sc
        lb = ((p0 + min_a) + smin[a_of]) + t_sc
        alive = np.isfinite(lb)
        R, a_of, cs, b_sc, b_pk, t_sc, t_pk, min_a, p0, lb = (x[alive] for x in (R, a_of, cs, b_sc, b_pk, t_sc, t_pk,
                                                                                   min_a, p0, lb))
        if not len(R):
            return out
        o = np.lexsort((R, lb, a_of))  # per application, by bound, then row
        R, a_of, cs, b_sc, b_pk, t_sc, t_pk, min_a, p0, lb = (x[o] for x in (R, a_of, cs, b_sc, b_pk, t_sc, t_pk,
                                                                               min_a, p0, lb))
        keys, kinv = self._spring_keys(R)
        # the smallest partial score of each key's rows: its spring scan can stop where no row can win
        k_part = np.full(len(keys["app"]), np.inf)
        np.minimum.at(k_part, kinv, (p0 + min_a) + t_sc)
        k_sc = np.full(len(keys["app"]), np.nan)  # NaN: not scanned yet
        k_pk = np.full(len(keys["app"]), -1, dtype=np.int64)
        a_sc, a_pk = np.full(len(R), np.inf), np.full(len(R), -1, dtype=np.int64)
        total = np.full(len(R), np.inf)
        done = np.zeros(len(R), dtype=bool)  # the rows whose total is known (inf: none within the cut)
        inc = np.full(n, np.inf)
        best = np.full(n, -1, dtype=np.int64)  # position in R
        seg = np.flatnonzero(np.r_[True, a_of[1:] != a_of[:-1]])
        seg_app = a_of[seg]
        seg_end = np.r_[seg[1:], len(R)]
        pos = seg.copy()
        block = 1

        def may_win(j):  # rows sorted by (bound, row): a row whose bound can still beat or tie the best
            i = a_of[j]
            bj = np.maximum(best[i], 0)
            return (lb[j] < inc[i]) | ((lb[j] == inc[i]) & ((best[i] < 0) | (R[j] < R[bj])))

        for take in _rounds(pos, seg_end, block, may_win,
                            (lambda: ~np.isfinite(inc[seg_app])) if first else None):
            # springs of the keys not scanned yet
            kt = np.unique(kinv[take])
            kt = kt[np.isnan(k_sc[kt])]
            if len(kt):
                lim = inc[keys["app"][kt]] - k_part[kt]
                lim = lim + SLACK * np.maximum(1.0, np.abs(inc[keys["app"][kt]]))
                if first:
                    lim = np.full(len(kt), np.inf)
                sub = {k: v[kt] for k, v in keys.items()}
                k_sc[kt], k_pk[kt] = self._spring_first(sub, np.where(np.isfinite(lim), lim, np.inf), weights)
            s = k_sc[kinv[take]]
            lb2 = ((p0[take] + min_a[take]) + s) + t_sc[take]
            inc_t = inc[a_of[take]]
            go = np.isfinite(lb2) & (lb2 <= inc_t)
            ta = take[go]
            if len(ta):
                lim_a = inc[a_of[ta]] - ((p0[ta] + s[go]) + t_sc[ta]) + SLACK * np.maximum(1.0, np.abs(inc[a_of[ta]]))
                if first:
                    lim_a = np.full(len(ta), np.inf)
                a_sc[ta], a_pk[ta] = self._axial_first(R[ta], np.where(np.isfinite(lim_a), lim_a, np.inf), weights)
                total[ta] = ((p0[ta] + a_sc[ta]) + s[go]) + t_sc[ta]
                done[ta] = True
                fin = ta[np.isfinite(total[ta])]
                for j in fin[np.lexsort((R[fin], total[fin]))]:  # few: the finite totals of this round
                    i = a_of[j]
                    if total[j] < inc[i] or (total[j] == inc[i] and R[j] < R[best[i]]):
                        inc[i], best[i] = total[j], j
        for i in np.flatnonzero(best >= 0):
            j = best[i]
            out[i] = (int(R[j]), {"bushing": int(b_pk[j]), "axial": int(a_pk[j]), "spring": int(k_pk[kinv[j]]),
                                  "bolt": int(t_pk[j])})
        # the search's state, for the margin tie-break (:meth:`_margin_ties`): rows per application by bound
        self._last = None if first else {
            "R": R, "a_of": a_of, "cs": cs, "b_sc": b_sc, "p0": p0, "min_a": min_a, "t_sc": t_sc, "lb": lb,
            "keys": keys, "kinv": kinv, "k_sc": k_sc, "k_pk": k_pk, "a_sc": a_sc, "a_pk": a_pk, "total": total,
            "done": done, "inc": inc}
        return out

    def nearest(self, which=None) -> list:
        """Per application (``which``: a subset, default all): ``(core row, {subsystem: option row}, value)`` of
        the design with the largest smallest margin over every core and option (every non-advisory constraint,
        the input-only ones included), as the enumeration's ``nearest_design``; None without any core.

        Nearest designs are ranked by the search model (at fidelity ``screening`` the screening one, as
        :meth:`synth.design.evaluate.Group.rank`); the design reported is verified by the full model."""
        n = len(self)
        want = np.ones(n, dtype=bool) if which is None else np.isin(np.arange(n), which)
        R = np.flatnonzero(want[self.A])
        out: list = [None] * n
        if not len(R):
            return out
        u0 = np.minimum(self.cg.min_margin(objective_only=False)[R], self.in_min[self.A[R]])
        vb, pb = self._bushing(R)
        vt, _ = self._bolt(R)
        v1 = np.minimum(np.minimum(u0, vb), vt)
        a_of = self.A[R]
        o = np.lexsort((R, -v1, a_of))
        R, a_of, v1, pb = (x[o] for x in (R, a_of, v1, pb))
        keys, kinv = self._spring_keys(R)
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

        for take in _rounds(pos, seg_end, block, could_win):
            kt_all = kinv[take]
            need = np.full(len(keys["app"]), -np.inf)
            np.maximum.at(need, kt_all, v1[take])
            kt = np.unique(kt_all)
            kt = kt[np.isnan(k_val[kt]) | (k_cap[kt] < need[kt])]
            if len(kt):  # the springs of these keys, exact up to the largest bound of their rows
                sub = {k: v[kt] for k, v in keys.items()}
                v, k_pk[kt] = self._spring_max(sub, need[kt])
                k_val[kt], k_cap[kt] = np.minimum(v, need[kt]), need[kt]
            v2 = np.minimum(v1[take], k_val[kt_all])
            go = could_win_value(v2, take)
            ta = take[go]
            if len(ta):
                va, _ = self._axial_max(R[ta], v2[go])
                val[ta] = np.minimum(v2[go], va)
            for j in ta[np.lexsort((R[ta], -val[ta]))]:
                i = a_of[j]
                if best[i] < 0 or val[j] > best_v[i] or (val[j] == best_v[i] and R[j] < R[best[i]]):
                    best_v[i], best[i] = val[j], j
        # the winners under the whole key (synth.design.combine.near_key): the cores whose smallest margin reaches
        # the largest (within round-off of the compiled kernels) tie there; their subsystems' near figures (the
        # bolt's and the spring's from the batch, the others by the enumeration's evaluator) choose the best
        # design exactly as the enumeration's nearest design (synth.optimise.product.Evaluation.nearest)
        for i in np.flatnonzero(best >= 0):
            sel = a_of == i
            tol = SLACK * max(1.0, abs(best_v[i]))
            rows_i = np.sort(R[sel & (val >= best_v[i] - tol)]) - self.ptr[i]
            tables, cols = self._near_tables(i, self.ptr[i] + rows_i, best_v[i] - tol)
            ev = product.evaluate(self.inputs[i], self.settings, pin_inputs=self.pin_inputs, prune=False,
                                  only=rows_i, tables=tables)
            self.evaluations += ev.evaluations
            pos, options, value = ev.nearest()
            options["spring"] = int(cols[options["spring"]])  # the spring table's columns are springs ``cols``
            out[i] = (int(self.ptr[i] + pos), options, value)
        return out

    def _near_tables(self, i: int, rows, floor: float = -np.inf) -> tuple:
        """The bolt's and the main spring's :class:`~synth.design.subsystems.SubTable` (with the near figures; the
        margin objective's column not computed) of core rows ``rows`` of application ``i``, from what the batch
        keeps (the bolt's step-10 checks per application, the pivot wall per core and diameter) and the compiled
        spring margins (:func:`synth.kernels.main_spring.margins`) of the rows' keys over the application's
        springs: the figures the enumeration's evaluation gives, at a fraction of its cost. A spring whose smallest
        margin is below ``floor`` (the application's largest smallest margin) keeps only that margin (no design
        under the key takes it). Returns ``(tables, columns)``: the spring table's columns are the springs
        ``columns`` (:meth:`_near_springs`: those a nearest design may take), the others' the whole tables'."""
        sp, nr = self.sp, len(rows)
        nb = sp.n("bolt")
        self._bolt_app([i], np.arange(nb))
        app = (self._fix[1][i], self._fix_near[0][i], self._fix_near[1][i])
        wall, code = self._wall(rows)
        if self._bolt_core_ids:
            with np.errstate(over="ignore", divide="ignore", invalid="ignore"):
                g = evaluate.bolt_core(self.apps, np.broadcast_to(self.A[rows][:, None], wall.shape),
                                       {k: self.cg.values[k][rows][:, None]
                                        for k in evaluate.core_values("bolt", self.cg.values)},
                                       {k: v[None, :] for k, v in self._wall_d[0].items()}, self.settings)
            w = near_figures(np.stack([g.margins[c].reshape(-1) for c in self._bolt_core_ids], axis=1))
            w = tuple(x.reshape(wall.shape)[:, code] for x in w)
        else:
            w = (np.full((nr, nb), np.inf), np.full((nr, nb), np.inf), np.zeros((nr, nb)))
        a, b, f = join(tuple(np.broadcast_to(x[None, :], (nr, nb)) for x in app), w)
        every = np.ones((nr, nb), dtype=bool)
        out = {"bolt": SubTable(every, f == 0, np.full((nr, nb), -np.inf), a, b, f)}
        for fam in (family(name) for name in SUBSYSTEMS):  # the families judged pair by pair: once per distinct
            if fam.group is None:                           # (application, what the family reads of the core)
                continue
            first, inv_f = _unique_rows(self.A[rows], *(self.cg.values[k][rows] for k, _ in fam.match),
                                        *(self.cg.values[k][rows] for k in fam.core_reads(self.cg.values)))
            rep = rows[first]
            avail = fam.available(sp, self.cg.values, rep)
            ri, oi = np.nonzero(avail)
            if fam.name == "axial":  # the search model on the batch's axial engine (its twins), as the scans
                g = self._axial_eval(rep[ri], oi)
            else:
                with np.errstate(over="ignore", divide="ignore", invalid="ignore"):
                    g = fam.group(self.apps, self.cg, rep[ri], sp.rows(fam.name, oi), self.settings)
                self.evaluations += len(ri)
            out[fam.name] = scatter(avail, ri, oi, g)
            out[fam.name] = SubTable(*(getattr(out[fam.name], k)[inv_f] for k in ("available", "feasible", "margin",
                                                                                  "min_margin", "second", "fails")))
        keys, inv = self._spring_keys(rows)
        rng, lists = self._ranges()
        k_fig, cols, avail = self._near_springs(i, keys, rng[i], floor)
        fig = [x.reshape(len(keys["app"]), len(cols))[inv] for x in k_fig]
        avail = np.broadcast_to(avail, (len(inv), len(cols)))
        out["spring"] = SubTable(avail, avail & (fig[2] == 0), np.full((len(inv), len(cols)), -np.inf), *fig)
        return out, cols

    def _near_springs(self, i: int, keys, group: int, floor: float):
        """The near figures of application ``i``'s spring ``keys`` over the springs of its range ``lst`` (range
        ``group`` of :meth:`_ranges`) that a
        nearest design may take: ``(figures per key x column (flattened), columns (spring rows, increasing),
        available per column)``. The enumeration's table has every spring as a column, available on ``lst``;
        here the columns are the springs whose smallest margin reaches ``floor`` for some key (every spring of
        ``lst`` when a key has none), and spring 0 (unavailable unless it is one of them: the option a row
        without any design gets).

        Why the springs left out change no choice of :func:`synth.design.combine.nearest_choice` (the whole key
        and the options it picks), given that each key has a spring reaching ``floor``: a spring below ``floor``
        (for every key) has the near figures ``(smallest, -inf, inf)`` in the table (its second and failing
        count are not computed). It is never a key's best smallest (a reaching spring is above it); it is
        admissible only for a core whose smallest ``m1`` is below ``floor``, and there its second (-inf) never
        raises the best second (a reaching spring's is at least ``floor``) and its failing count (inf) never is
        the fewest (a reaching spring's is finite), and a pick among infinite counts is discarded (option 0
        where no count is finite: column 0). The same holds of a pair below ``floor`` within a kept column, so
        such a pair's smallest margin need only be known to be below ``floor``
        (:func:`synth.kernels.main_spring.margins_above`: its yield margin or its option-only bound)."""
        nk = len(keys["app"])
        lst = np.asarray(self._ranges()[1][group], dtype=np.int64)
        kk = main_spring.keys_of_rows(self.apps, keys) if len(lst) else None
        memo = ("near springs", group)  # the range's options, shared by its applications
        if memo not in self._memo:
            self._memo[memo] = self._options().take(lst)
        opts = self._memo[memo]
        if len(lst):
            low, m = main_spring.margins_above(kk, opts, floor, engine=self.engine, settings=self.settings)
        else:
            low, m = np.zeros((nk, 0)), np.zeros((nk, 0, 0))
        self.evaluations += low.size
        reach = low >= floor
        if reach.any(axis=1).all():
            keep = reach.any(axis=0)
        else:  # a key without a reaching spring: every spring, each with its smallest margin (as the table)
            keep = np.ones(len(lst), dtype=bool)
            if len(lst):
                m = main_spring.margins(kk, opts, engine=self.engine, settings=self.settings)
                low = np.full(m.shape[:2], np.inf)
                for c in range(m.shape[2]):  # a strided minimum per check: faster than a reduction over the last axis
                    np.minimum(low, m[:, :, c], out=low)
        kept = lst[keep]
        cols = kept if len(kept) and kept[0] == 0 else np.r_[0, kept].astype(np.int64)
        at = np.searchsorted(cols, kept)
        fig = [np.full((nk, len(cols)), -np.inf), np.full((nk, len(cols)), -np.inf), np.full((nk, len(cols)), np.inf)]
        if len(kept):
            fig[0][:, at] = low[:, keep]
            # a spring whose smallest margin is below the application's nearest design's cannot be in it
            # (synth.design.combine.nearest_choice: not admissible): its other figures are not needed
            ki, ci = np.nonzero(reach[:, keep])
            if len(ki):
                _, b, f = near_figures(m[ki, np.flatnonzero(keep)[ci]])
                fig[1][ki, at[ci]] = b
                fig[2][ki, at[ci]] = f
        avail = np.zeros(len(cols), dtype=bool)
        avail[at] = True
        return [x.reshape(-1) for x in fig], cols, avail

    # ------------------------------------------------------------------------------------------- designs
    def parts(self, i: int, core_row: int, options: dict) -> dict:
        """The part keys of a design of application ``i`` (core row of this batch, option rows of the space)."""
        return parts_of_design(self.sp, self.C[core_row], options, self.cg.values, core_row)

    def objective_values(self, core_row: int, options: dict) -> dict:
        """The additive goals (``{standard, cost, ...}``) of a design, summed as
        :meth:`synth.optimise.product.Evaluation.objective_values`."""
        sp = self.sp
        cv = {k: self.cg.values[k][[core_row]] for k in core_reads()}
        sc = core_scores(sp, self.C[[core_row]], cv)
        k = float(self.apps.spring_stiffness_nm_per_deg[self.A[core_row]])
        opt = {s: option_scores(sp, s, k) for s in SUBSYSTEMS}
        return design_totals({n: float(v[0]) for n, v in sc.items()},
                             [{n: v[options[s]] for n, v in opt[s].items()} for s in SUBSYSTEMS])

    def notes(self, i: int) -> list:
        """The notes the enumeration's evaluation gives application ``i``."""
        if not self.apps.met("durability")[i]:
            return [DURABILITY_NOTE]
        return []

    def view(self, i: int) -> "_View":
        """Application ``i`` as :func:`synth.optimise.answer.build_result` reads an evaluation."""
        return _View(self, i)

    def candidates(self, i: int) -> int:
        """Whole-tensioner designs of application ``i``'s catalog product (every core x every option)."""
        return int(self.ptr[i + 1] - self.ptr[i]) * int(np.prod([self.sp.n(s) for s in SUBSYSTEMS]))



class _View:
    """One application of a :class:`Batch` with the attributes :func:`synth.optimise.answer.build_result` reads of
    an :class:`~synth.optimise.product.Evaluation` (positions are core rows of the batch)."""

    def __init__(self, b: Batch, i: int):
        self.b, self.i = b, i
        self.inputs, self.settings, self.notes = b.inputs[i], b.settings, b.notes(i)

    def parts(self, pos: int, options: dict) -> dict:
        return self.b.parts(self.i, pos, options)

    def objective_values(self, pos: int, options: dict, margin: float) -> dict:
        return {**self.b.objective_values(pos, options), "margin": margin}


def robust(fn, items: list, on_error):
    """``fn(items)`` (a list, one entry per item); where it raises :class:`~synth.errors.InputError` (one item's
    data the physics refuses), the halves again, down to single items, whose entry is ``on_error(item, exc)``:
    one bad application never decides the others' answers."""
    if not items:
        return []
    try:
        return list(fn(items))
    except InputError as exc:
        if len(items) == 1:
            return [on_error(items[0], exc)]
        half = len(items) // 2
        return robust(fn, items[:half], on_error) + robust(fn, items[half:], on_error)


def any_feasible(inputs: list, settings: evaluate.Settings = evaluate.Settings(), *, spring_engine: str = "numba",
                 pin_inputs: bool = False, designs: bool = False) -> list:
    """Per input, whether some design of its catalog product (``pin_inputs``: with the parts it names) meets every
    constraint (the enumeration's ``is_feasible``; an input the physics refuses is not feasible).

    ``designs=True``: per input the design found instead (``(space, core row, {subsystem: option row})``, for
    :func:`designs_pass`), or None where there is none: the same verdicts (``is not None``). Every design found
    passes the judge (:attr:`~synth.design.evaluate.Settings.judge`), and a "no" is the judge's too (the screening
    model only orders and bounds the search: :meth:`Batch.optimum`)."""
    def run(items):
        b = Batch(items, settings, spring_engine=spring_engine, pin_inputs=pin_inputs)
        found = b.optimum(FALLBACK_WEIGHTS, first=True)
        if not designs:
            return [f is not None for f in found]
        return [None if f is None else (b.sp, int(b.C[f[0]]), f[1]) for f in found]
    return robust(run, list(inputs), lambda item, exc: None if designs else False)


def designs_pass(inputs: list, found: list, settings: evaluate.Settings = evaluate.Settings()) -> np.ndarray:
    """Per input, whether design ``found[i]`` (an :func:`any_feasible` design, usually of another input) meets
    every constraint at input ``inputs[i]``: all of them evaluated at once by the judge
    (:func:`synth.design.verify.evaluate_design`, one row per design). A pass proves :func:`any_feasible`'s yes
    (which is the judge's verdict of some design); a fail proves nothing (another design may pass). An input the
    physics refuses does not pass."""
    out = np.zeros(len(inputs), dtype=bool)
    by_space: dict = {}
    for i, (sp, core, opts) in enumerate(found):
        by_space.setdefault(id(sp), (sp, []))[1].append(i)
    for sp, idx in by_space.values():
        def run(rows):
            attrs = {"core": sp.rows("core", np.array([found[i][1] for i in rows], dtype=np.int64))}
            attrs.update({s: sp.rows(s, np.array([found[i][2][s] for i in rows], dtype=np.int64))
                          for s in SUBSYSTEMS})
            apps = Applications.of([inputs[i] for i in rows])
            with np.errstate(over="ignore", divide="ignore", invalid="ignore"):
                groups = evaluate_design(apps, attrs, settings, detail=False)
            return list(assess(groups, apps).ok)
        out[idx] = robust(run, idx, lambda item, exc: False)
    return out
