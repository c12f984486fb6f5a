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

from synth.design import evaluate
from synth.design.applications import Applications
from synth.design.assessment import assess
from synth.design.space import SUBSYSTEMS, core_rows, fixed_fields, priced_for, space, space_for
from synth.design.verify import evaluate_design, parts_of_design
from synth.errors import InputError
from synth.kernels import engines
from synth.optimise.axial_scan import AxialScan
from synth.optimise.batch_nearest import nearest
from synth.optimise.bolt_scan import BoltScan
from synth.optimise.margin_ties import MARGIN_EPS, SLACK, margin_ties
from synth.optimise.objectives import FALLBACK_WEIGHTS, core_reads, weighted_sum
from synth.optimise.paired_scan import PairedScan
from synth.optimise.product import DURABILITY_NOTE, core_scores, design_totals, option_scores
from synth.optimise.scan_arrays import rounds
from synth.optimise.spring_scan import SpringScan

__all__ = ["Batch", "wsum", "SLACK", "MARGIN_EPS", "any_feasible", "designs_pass", "robust"]

#: the additive score of many designs (:func:`synth.optimise.objectives.weighted_sum`)
wsum = weighted_sum


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
        self.in_ok = self.ig.ok()
        self.in_min = self.ig.min_margin(objective_only=False)
        self.core_ok = self.cg.ok() & self.in_ok[self.A]
        self.pad = np.asarray(self.cg.values["axial_group_present"], dtype=float) > 0
        self.memo: dict = {}  # what the scans compute once per batch (spring lists, bolt scores, ...)
        # the scanners of the subsystems, each reading the batch's cores and counting its evaluations
        self.paired, self.bolts = PairedScan(self), BoltScan(self)
        self.springs, self.axial = SpringScan(self), AxialScan(self)
        self.screened = None  # the screening settings while optimum() searches with the full model alone
        self.last_search, self.redone = None, set()  # the last optimum()'s search state and re-searched applications

    def __len__(self) -> int:
        return len(self.inputs)

    # ------------------------------------------------------------------------------------------- bushing

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
            redo = np.flatnonzero(self.axial.undecided & np.array([o is None for o in out], dtype=bool))
            if len(redo):
                last = self.last_search
                search = self.screened = self.settings
                self.settings = judge
                try:
                    again = self._optimum(weights, first=first, which=redo)
                finally:
                    self.settings, self.screened, self.last_search = search, None, last
                for i in redo:
                    out[i] = again[i]
        self.redone = set(int(i) for i in redo)  # searched by the full model alone: no tie-break (_last: the first)
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
        return margin_ties(self, weights, found)

    def _optimum(self, weights: dict, *, first: bool = False, which=None) -> list:
        n = len(self)
        want = np.ones(n, dtype=bool) if which is None else np.isin(np.arange(n), which)
        R = np.flatnonzero(self.core_ok & want[self.A])
        out: list = [None] * n
        self.axial.undecided = np.zeros(n, dtype=bool)
        if not len(R):
            return out
        sp, cg = self.sp, self.cg
        cs = wsum(core_scores(sp, self.C[R], {k: cg.values[k][R] for k in core_reads()}), weights)
        b_sc, b_pk = self.paired.bushing(R, weights)
        t_sc, t_pk = self.bolts.scan(R, weights)
        ax_sc = wsum(option_scores(sp, "axial"), weights)
        real = sp.tables["axial"]["axial_group_present"]
        min_a = np.where(self.pad[R], ax_sc[real].min() if real.any() else np.inf, ax_sc[~real].min())
        smin = self.springs.app_lists(weights)[2]
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
        keys, kinv = self.springs.keys(R)
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

        for take in rounds(pos, seg_end, block, may_win,
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
                k_sc[kt], k_pk[kt] = self.springs.first_feasible(sub, np.where(np.isfinite(lim), lim, np.inf), weights)
            s = k_sc[kinv[take]]
            lb2 = ((p0[take] + min_a[take]) + s) + t_sc[take]
            inc_t = inc[a_of[take]]
            go = np.isfinite(lb2) & (lb2 <= inc_t)
            ta = take[go]
            if len(ta):
                lim_a = inc[a_of[ta]] - ((p0[ta] + s[go]) + t_sc[ta]) + SLACK * np.maximum(1.0, np.abs(inc[a_of[ta]]))
                if first:
                    lim_a = np.full(len(ta), np.inf)
                a_sc[ta], a_pk[ta] = self.axial.first_feasible(R[ta], np.where(np.isfinite(lim_a), lim_a, np.inf), weights)
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
        self.last_search = None if first else {
            "R": R, "a_of": a_of, "cs": cs, "b_sc": b_sc, "p0": p0, "min_a": min_a, "t_sc": t_sc, "lb": lb,
            "keys": keys, "kinv": kinv, "k_sc": k_sc, "k_pk": k_pk, "a_sc": a_sc, "a_pk": a_pk, "total": total,
            "done": done, "inc": inc}
        return out

    def nearest(self, which=None) -> list:
        """Per application (``which``: a subset, default all): ``(core row, {subsystem: option row}, value)`` of
        the design with the largest smallest margin (:func:`synth.optimise.batch_nearest.nearest`)."""
        return nearest(self, which)

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
