"""Black-box search with optuna: one constrained study per subsystem, batched through the one evaluator.

The search is cut as the exact model is (:mod:`synth.design.space`):

* the inputs and every core are evaluated first, in one vectorised call: each
  core's feasibility, margins and scores, and its bounds: the smallest score
  of a design on it (its own plus each subsystem's cheapest option: the exact
  solvers' bound) and the largest margin (its own);
* given the core, the subsystems share no constraint, so each is searched
  apart by its own study. Optuna asks a batch of proposals (the catalog
  choices of :mod:`synth.optimise.search_space`; a proposal carries the line
  of its dimensions that change no score: the spring's mean diameters, the
  cone spring's h0/t and s/h0), the evaluator's group computes the whole batch
  against every live core in one call
  (:func:`synth.optimise.product.subsystem`), and each proposal is told the
  bound of the best design through it (objective) and its largest margin over
  the cores as the constraint ``-margin <= 0``
  (:meth:`optuna.trial.Trial.set_constraint`), which the TPE sampler ranks
  infeasible trials by: the search moves toward feasibility before it has
  found any;
* every evaluated (core, option) pair is kept: after each round the best
  design over them is the exact combination of
  :func:`synth.optimise.solvers.enumerate.solve_space` (or, while none is
  feasible, :func:`synth.optimise.diagnose.nearest_design`) on that archive;
* cores whose bound cannot beat the best design found are dropped (branch
  and bound); a study stops when it has proposed every choice or reached its
  subsystem's bound on every live core. When all stop, the design is proved
  optimal over the catalog space (``status="optimal"``), otherwise
  ``"feasible"`` (anytime, no proof) or ``"infeasible"`` (nothing feasible
  found: the nearest design found, not a proof);
* ``continuous=True`` then refines the winner's continuous dimensions (the
  main spring's mean diameter, the cone spring's h0/t and s/h0: no score
  depends on them) by a continuous TPE study per subsystem on the winning
  core, for the largest margin (or, while infeasible, the largest smallest
  margin: a design off the grids may pass where every grid design fails).
  The result reports its catalog snap (``stats["catalog_snap"]``: the design
  moved back to the exact solvers' grids, verified).

Warm start: the thesis flowchart's design and each subsystem's cheapest
choice are the first proposals. Seeded: the same input, objective, budget and
seed give the same design (a time limit stops at a time, not at a trial).

>>> from synth.data.generated_applications import generate
>>> from synth.design.evaluate import Settings
>>> r = solve(generate(2, seed=0)[1], "cost", n_trials=60, settings=Settings(fidelity="screening"), seed=1)
>>> r.solver, r.status in ("optimal", "feasible")
('blackbox', True)
"""

from __future__ import annotations

import time

import numpy as np

from synth import catalog
from synth.design.assessment import passes
from synth.design.combine import combine
from synth.design.constraints import FEAS_TOL
from synth.design.evaluate import Settings
from synth.design.space import SUBSYSTEMS, Space
from synth.optimise.batch import wsum
from synth.optimise.product import Evaluation, SubTable, evaluate, option_scores, subsystem, design_scores
from synth.optimise import objectives
from synth.optimise.objectives import FALLBACK_WEIGHTS, Objective, additive_goals, additive_totals, goal
from synth.optimise.answer import build_result, design_margin
from synth.optimise.search_space import refinements, snap_parts, variables
from synth.flowchart import run
from synth.design.verify import verify
from synth.errors import InputError, Problem
from synth.optimise.diagnose import nearest_design, diagnose, violated_of
from synth.optimise.solvers.enumerate import solve_space

__all__ = ["solve", "Search", "BATCH", "SAMPLERS"]

#: proposals a study asks per round (one evaluator call per subsystem and round)
BATCH = 16
#: samplers of the catalog stage: optuna's TPE with constraints (default), random sampling (the reference the
#: benchmark measures TPE against)
SAMPLERS = ("tpe", "random")
#: share of a round's proposals taken best-first (the cheapest choices not tried yet), the rest the sampler's
FILL = 0.25
#: a subsystem with at most this many choices is covered in one round (optuna's exhaustive sampler)
EXHAUSTIVE = 128
_BIG = 1e6   # the value and violation told for a proposal no live core can take


def _worse(a: list, b: tuple) -> np.ndarray:
    """Per entry, whether the sort key ``a`` (one array per tier) is strictly worse than the key ``b``
    (lexicographic, beyond a relative 1e-9 per tier)."""
    worse = np.zeros(np.shape(a[0]), dtype=bool)
    undecided = np.ones(np.shape(a[0]), dtype=bool)
    for x, y in zip(a, b):
        tol = 1e-9 * max(1.0, abs(y))
        worse |= undecided & (x > y + tol)
        undecided &= np.abs(x - y) <= tol
    return worse


def _key(obj: Objective, vals: dict) -> list:
    """:meth:`Objective.key` of arrays: one array per tier (smaller is better)."""
    if obj.weights:
        return [np.asarray(obj.score(vals), dtype=float)]
    return [np.asarray(goal(k).sense * vals[k], dtype=float) for k in obj.order]


def _scalar(obj: Objective, vals: dict) -> np.ndarray:
    """One number to minimise per entry of ``vals`` (arrays ``standard``, ``cost``, ``margin``): the weighted sum,
    or the lexicographic order scalarised with a factor 1e4 per tier (integer part counts, costs far below 1e4
    EUR, margins clipped to the models' range), the margin maximised."""
    lo, hi = catalog.constant("optimise_margin_floor"), catalog.constant("optimise_margin_ceiling")
    v = {**vals, **{g.name: np.clip(vals[g.name], lo, hi) for g in objectives.GOALS if not g.additive}}
    if obj.weights:
        return np.asarray(obj.score(v), dtype=float)
    out, scale = 0.0, 1.0
    for name in reversed(obj.order):
        out = out + scale * (goal(name).sense * v[name])
        scale *= 1e4
    return np.asarray(out, dtype=float)


def _sampler(kind: str, seed: int, size: int, batch: int, n_params: int):
    """The study's sampler: optuna's exhaustive sampler for a table of at most :data:`EXHAUSTIVE` choices, else
    ``kind``."""
    import optuna
    if size <= EXHAUSTIVE:
        class Exhaustive(optuna.samplers.BruteForceSampler):
            """Optuna's exhaustive sampler under ask and tell (the search counts the coverage; the base class
            stops a study from inside ``optimize`` once every choice is taken)."""

            def after_trial(self, study, trial, state, values):
                pass
        import warnings
        with warnings.catch_warnings():  # experimental in optuna since 3.1; its interface here is one keyword
            warnings.simplefilter("ignore", optuna.exceptions.ExperimentalWarning)
            return Exhaustive(seed=seed)
    if kind == "random":
        return optuna.samplers.RandomSampler(seed=seed)
    return optuna.samplers.TPESampler(seed=seed, multivariate=n_params > 1, constant_liar=True,
                                      n_startup_trials=batch)


class Search:
    """One search: the cores, one study per subsystem, the archive of evaluated (core, option) pairs.

    ``ev``: the application's inputs and cores (:func:`synth.optimise.product.evaluate` with
    ``subsystems=False, prune=False``).
    """

    def __init__(self, ev: Evaluation, objective: Objective, *, seed: int = 0, batch: int = BATCH,
                 sampler: str = "tpe"):
        import optuna
        if sampler not in SAMPLERS:
            raise InputError(Problem("sampler", sampler, "one of " + ", ".join(SAMPLERS)))
        optuna.logging.set_verbosity(optuna.logging.WARNING)
        self.ev, self.obj, self.batch, self.seed = ev, objective, int(batch), int(seed)
        self.weights = objective.additive_weights() or FALLBACK_WEIGHTS
        self.stiffness = float(ev.apps.spring_stiffness_nm_per_deg[0])
        self.vars = variables(ev, self.weights)
        self.ok_core = ev.core_feasible()
        self.u_all = ev.core_min_margin()           # no design on the core has a larger smallest margin
        self.u_obj = ev.core_margin()               # nor a larger margin objective
        self.pad = ev.core.values["axial_group_present"] > 0
        self._bounds()
        self.cols = {s: [] for s in SUBSYSTEMS}     # option columns evaluated, per call
        self.subs = {s: [] for s in SUBSYSTEMS}     # their SubTables over every core, per call
        self.seen = {s: {} for s in SUBSYSTEMS}     # proposal key -> (value, violation)
        self.queued = {s: set() for s in SUBSYSTEMS}  # proposal keys enqueued and not yet asked
        n = len(ev.cores)
        # per core, the largest smallest margin of the subsystem's options evaluated there (-inf: none passes
        # there; a core where none was evaluated yet counts as +inf: optimistic)
        self.reach = {s: np.full(n, -np.inf) for s in SUBSYSTEMS}
        self.tried = {s: np.zeros(n, dtype=bool) for s in SUBSYSTEMS}
        # per core, over the passing options evaluated there: the smallest standard and cost, the largest margin
        self.feas_min = {s: {g.name: np.full(n, np.inf) for g in additive_goals()} for s in SUBSYSTEMS}
        self.reach_obj = {s: np.full(n, -np.inf) for s in SUBSYSTEMS}
        self.exact = {s: np.zeros(n, dtype=bool) for s in SUBSYSTEMS}   # every choice evaluated on the core
        self.trials = {s: 0 for s in SUBSYSTEMS}
        self.done = {s: False for s in SUBSYSTEMS}
        self.pairs = 0
        self.rounds = 0
        self.best = None                            # (core position, options, values, feasible)
        self._archive = None
        self.studies = {s: optuna.create_study(direction="minimize", sampler=_sampler(
            sampler, self.seed + i, v.size, self.batch, len(v.distributions)))
            for i, (s, v) in enumerate(self.vars.items())}
        self.done["axial"] = not self.pad.any()
        none = np.flatnonzero(ev.space.tables["axial"]["axial_group_present"] == 0)[:1]
        self._evaluate("axial", ev.space.rows("axial", none), np.flatnonzero(~self.pad))  # not searched: one option
        self.exact["axial"][~self.pad] = True

    # ------------------------------------------------------------------ bounds
    def _bounds(self):
        """Per core and subsystem, the smallest score of each additive goal and the weighted score of the options it may
        take (the space's tables), and the cores' totals: the bound of every design on the core."""
        ev, sp = self.ev, self.ev.space
        cv, n = ev.core.values, len(ev.cores)
        self.lb = {}
        for s in SUBSYSTEMS:
            sc = option_scores(sp, s, self.stiffness)
            sc["weighted"] = np.asarray(wsum(sc, self.weights), dtype=float)
            t = sp.tables[s]
            if s == "bushing":
                groups = [(cv["supplier_code"] == c, t["supplier_code"] == c) for c in np.unique(cv["supplier_code"])]
            elif s == "axial":
                groups = [(self.pad == p, t["axial_group_present"] == p) for p in (False, True)]
            else:
                groups = [(np.ones(n, dtype=bool), np.ones(sp.n(s), dtype=bool))]
            lb = {name: np.full(n, np.inf) for name in sc}
            for rows, opts in groups:
                if opts.any():
                    for name in sc:
                        lb[name][rows] = np.min(sc[name][opts])
            self.lb[s] = lb
        self.lb_total = additive_totals(ev.score_core, [self.lb[s] for s in SUBSYSTEMS])

    def _bound_keys(self) -> list:
        """Per core, the sort key of the best design it could give (one array per tier): lower bounds of the
        scores (a subsystem whose every choice was evaluated on the core counts with its best passing option, the
        others with their cheapest), the upper bound of the margin."""
        ev = self.ev
        vals = additive_totals(ev.score_core, [{name: np.where(self.exact[s], lo, self.lb[s][name])
                                                for name, lo in self.feas_min[s].items()} for s in SUBSYSTEMS])
        vals["margin"] = combine(self.u_obj, [np.where(self.exact[s], self.reach_obj[s], np.inf) for s in SUBSYSTEMS])
        return _key(self.obj, vals)

    def _cap(self) -> np.ndarray:
        """Per core, the upper bound of the smallest margin of a design on it: its own, and that of every
        subsystem whose every choice was evaluated on it."""
        return combine(self.u_all, [np.where(self.exact[s], self.reach[s], np.inf) for s in SUBSYSTEMS])

    # ------------------------------------------------------------------ the archive
    def _evaluate(self, s: str, cols: dict, rows: np.ndarray) -> SubTable:
        """Options ``cols`` of subsystem ``s`` on core positions ``rows`` (one evaluator call), kept in the
        archive (other cores: not available); returns the SubTable over ``rows``."""
        with np.errstate(over="ignore", divide="ignore", invalid="ignore"):
            sub, pairs = subsystem(self.ev.apps, Space({s: cols}, self.ev.space.parts), self.ev.core, rows, s,
                                   self.ev.settings)
        n, k = len(self.ev.cores), len(next(iter(cols.values())))
        full = SubTable(np.zeros((n, k), dtype=bool), np.zeros((n, k), dtype=bool), np.full((n, k), -np.inf),
                        np.full((n, k), -np.inf), np.full((n, k), -np.inf), np.zeros((n, k)))
        for f in ("available", "feasible", "margin", "min_margin", "second", "fails"):
            getattr(full, f)[rows] = getattr(sub, f)
        best = np.where(sub.available, sub.min_margin, -np.inf).max(axis=1, initial=-np.inf)
        self.reach[s][rows] = np.maximum(self.reach[s][rows], best)
        self.tried[s][rows] |= sub.available.any(axis=1)
        sc = option_scores(Space({s: cols}, self.ev.space.parts), s, self.stiffness)
        for name, lo in self.feas_min[s].items():
            lo[rows] = np.minimum(lo[rows], np.where(sub.feasible, sc[name][None, :], np.inf).min(axis=1, initial=np.inf))
        self.reach_obj[s][rows] = np.maximum(self.reach_obj[s][rows], np.where(sub.feasible, sub.margin, -np.inf).max(
            axis=1, initial=-np.inf))
        self.cols[s].append(cols)
        self.subs[s].append(full)
        self.pairs += pairs
        self._archive = None
        return sub

    def archive(self) -> Evaluation:
        """The evaluated pairs as an :class:`~synth.optimise.product.Evaluation` (rows: every core; options: the
        columns evaluated): the exact combination and the nearest design run on it unchanged."""
        if self._archive is None:
            ev = self.ev
            tables, subs = {"core": ev.space.tables["core"]}, {}
            for s in SUBSYSTEMS:
                tables[s] = {c: np.concatenate([b[c] for b in self.cols[s]]) for c in self.cols[s][0]}
                subs[s] = SubTable(*(np.concatenate([getattr(b, f) for b in self.subs[s]], axis=1)
                                     for f in ("available", "feasible", "margin", "min_margin", "second", "fails")))
            sp = Space(tables, ev.space.parts, list(ev.space.notes))
            self._archive = Evaluation(ev.inputs, ev.apps, sp, ev.settings, ev.cores, ev.input, ev.core,
                                       np.arange(len(ev.cores)), subs, ev.score_core,
                                       {s: option_scores(sp, s, self.stiffness) for s in SUBSYSTEMS}, list(ev.notes),
                                       ev.evaluations + self.pairs)
        return self._archive

    # ------------------------------------------------------------------ the catalog stage
    def live_cores(self) -> np.ndarray:
        """Core positions that can still give a better design than the best found (all, before any is found)."""
        if self.best is None:
            return np.arange(len(self.ev.cores))
        cap = self._cap()
        if not self.best[3]:   # nothing feasible yet: the cores that could be nearer than the nearest found
            return np.flatnonzero(cap > self.best[2]["min_margin"] + 1e-12)
        better = ~_worse(self._bound_keys(), self.obj.key(self.best[2]))
        return np.flatnonzero(self.ok_core & passes(cap) & better)

    def warm_start(self, parts: dict | None = None):
        """First proposals: each subsystem's cheapest choice (its bound) and, if given, the choices of design
        ``parts`` (the thesis flowchart's)."""
        wanted = {s: [v.choices[0]] for s, v in self.vars.items()}
        if parts:
            attrs = self.ev.space.design_attributes(parts)
            for s, v in self.vars.items():
                wanted[s].append(v.locate(attrs[s]))
        for s, lst in wanted.items():
            for params in lst:
                if params is not None:
                    self._enqueue(s, params)

    def _enqueue(self, s: str, params: dict):
        key = self.vars[s].key(params)
        if not self.done[s] and key not in self.seen[s] and key not in self.queued[s]:
            self.studies[s].enqueue_trial(params)
            self.queued[s].add(key)

    def _fill(self, s: str, n: int):
        """Enqueue the ``n`` cheapest choices not proposed yet (a study that repeats itself has converged: its
        next proposals close the gap to the bound, as a branch and bound would)."""
        v = self.vars[s]
        for c in v.choices:
            if n <= 0:
                break
            key = v.key(c)
            if key not in self.seen[s] and key not in self.queued[s]:
                self._enqueue(s, c)
                n -= 1

    def _signals(self, s: str, cols: dict, owner: np.ndarray, sub: SubTable, rows: np.ndarray, n: int):
        """Per proposal (``n``; ``owner`` maps columns to proposals): the violation, minus the smallest margin of
        the nearest design it completes with the core and the other subsystems' options found so far (<= 0: it
        completes a feasible design; a subsystem not yet evaluated on a core counts as passing there), and the
        objective, the best bound of a design through it over the cores where it completes a feasible one (or
        where it is available, when it completes none)."""
        sc = option_scores(Space({s: cols}, self.ev.space.parts), s, self.stiffness)
        lb = self.lb[s]
        vals = {g.name: (self.lb_total[g.name] - lb[g.name])[rows][:, None] + sc[g.name][None, :]
                for g in additive_goals()}
        vals["margin"] = np.minimum(self.u_obj[rows][:, None], sub.margin)
        score = _scalar(self.obj, vals)
        others = combine(self.u_all[rows], [np.where(self.tried[o][rows], self.reach[o][rows], np.inf)
                                            for o in SUBSYSTEMS if o != s])
        cap = np.where(sub.available, np.minimum(others[:, None], sub.min_margin), -np.inf)
        feas = sub.feasible & self.ok_core[rows][:, None] & passes(others[:, None])
        col_best = cap.max(axis=0, initial=-np.inf)
        col_feas = np.where(feas, score, np.inf).min(axis=0, initial=np.inf)
        col_any = np.where(sub.available, score, np.inf).min(axis=0, initial=np.inf)
        value, violation, anyfeas = np.full(n, np.inf), np.full(n, np.inf), np.zeros(n, dtype=bool)
        np.minimum.at(violation, owner, -col_best - FEAS_TOL)
        np.logical_or.at(anyfeas, owner, np.isfinite(col_feas))
        fv, av = np.full(n, np.inf), np.full(n, np.inf)
        np.minimum.at(fv, owner, col_feas)
        np.minimum.at(av, owner, col_any)
        value = np.where(anyfeas, fv, av)
        value = np.where(np.isfinite(value), value, _BIG)
        violation = np.where(np.isfinite(violation), violation, _BIG)
        return np.clip(value, -_BIG, _BIG), np.clip(violation, -_BIG, _BIG)

    def _shares(self, live: list, rows: np.ndarray, budget: int) -> dict:
        """Proposals per study this round, within its ``budget`` (trials per study): every untried choice of a
        table of at most :data:`EXHAUSTIVE` (one evaluator call covers it); else a batch where the subsystem
        limits a live core (has the smallest margin there while nothing is feasible), a quarter batch
        otherwise."""
        limits = set(live)
        if self.best is not None and not self.best[3] and len(rows):
            m = np.stack([np.where(self.tried[s][rows], self.reach[s][rows], np.inf) for s in SUBSYSTEMS])
            limits = {SUBSYSTEMS[i] for i in np.unique(np.argmin(m, axis=0))}
        out = {}
        for s in live:
            v = self.vars[s]
            left = v.size - len(self.seen[s])
            want = left if v.size <= EXHAUSTIVE else (self.batch if s in limits else max(1, self.batch // 4))
            out[s] = max(0, min(want, left, budget - self.trials[s]))
        return out

    def round(self, budget: int) -> int:
        """One round: each live study asks its share of proposals (at most ``budget`` trials per study in all),
        evaluated in one call per subsystem; returns the number of trials told."""
        rows = self.live_cores()
        live = sorted((s for s in SUBSYSTEMS if not self.done[s] and not (s == "axial" and not self.pad[rows].any())),
                      key=lambda s: self.vars[s].size)   # the small tables first: the others' signals see them
        told = 0
        for s, n in self._shares(live, rows, budget).items():
            if n <= 0:
                continue
            v, study = self.vars[s], self.studies[s]
            self._fill(s, int(round(FILL * n)) - len(self.queued[s]))
            trials = [study.ask(v.distributions) for _ in range(n)]
            params = [t.params for t in trials]
            fresh = list({v.key(p): p for p in params if v.key(p) not in self.seen[s]}.values())
            self.queued[s] -= {v.key(p) for p in params}
            if fresh:
                cols, owner = v.columns(fresh)
                sub = self._evaluate(s, cols, rows)
                value, violation = self._signals(s, cols, owner, sub, rows, len(fresh))
                for j, p in enumerate(fresh):
                    self.seen[s][v.key(p)] = (float(value[j]), float(violation[j]))
            for t, p in zip(trials, params):
                value, violation = self.seen[s][v.key(p)]
                t.set_constraint("margin", violation)
                study.tell(t, value)
            self.trials[s] += len(trials)
            told += len(trials)
            if len(self.seen[s]) >= v.size:   # every choice evaluated on every core still live
                self.done[s] = True
                self.exact[s][rows] = True
            self._fill(s, len(trials) - len(fresh))
        if told:
            self.rounds += 1
            self._combine()
        return told

    def _design(self, ev: Evaluation, core: int, options: dict) -> dict:
        """``{standard, cost, ..., margin, min_margin}`` of a design of the archive."""
        margin = combine(float(ev.core_margin()[core]), [float(ev.subs[s].margin[core, options[s]]) for s in SUBSYSTEMS])
        mmin = combine(float(ev.core_min_margin()[core]),
                       [float(ev.subs[s].min_margin[core, options[s]]) for s in SUBSYSTEMS])
        return {**ev.objective_values(core, options, margin), "min_margin": mmin}

    def _combine(self):
        """The best design over the archive (exact combination), and the studies that reached their bounds."""
        ev = self.archive()
        core, options, _ = solve_space(ev, self.obj)
        feasible = core is not None
        if not feasible:
            core, options, _ = nearest_design(ev)
        self.best = (core, options, self._design(ev, core, options), feasible)
        if feasible and not self.obj.uses_margin():
            rows = self.live_cores()
            for s in SUBSYSTEMS:
                v = self.vars[s]
                if self.done[s] or not len(rows):
                    continue
                w = np.asarray(wsum(ev.score[s], self.weights), dtype=float)
                got = np.where(ev.subs[s].feasible[rows], w[None, :], np.inf).min(axis=1).max()
                unseen = [sc for c, sc in zip(v.choices, v.scores) if v.key(c) not in self.seen[s]]
                if not unseen or (np.isfinite(got) and min(unseen) >= got - 1e-9 * max(1.0, abs(got))):
                    self.done[s] = True   # no choice left untried could improve any live core

    def finished(self) -> bool:
        rows = self.live_cores()
        return all(self.done[s] or (s == "axial" and not self.pad[rows].any()) for s in SUBSYSTEMS)

    def proved(self) -> bool:
        """Whether the best design is optimal over the catalog space (every study stopped on its bound or by
        covering its choices, the best design feasible)."""
        return self.best is not None and self.best[3] and self.finished()

    # ------------------------------------------------------------------ the continuous stage
    def refine(self, trials: int) -> dict:
        """Refine the continuous dimensions of the best design, subsystem by subsystem on its core (they share
        no constraint): a continuous TPE study each, in batches, for the largest margin among the options that
        pass (the largest smallest margin while none does). The best option found replaces the design's when
        it is better; returns the trials per subsystem."""
        import optuna
        core, options, _, _ = self.best
        ev = self.archive()
        used = {}
        start_col = {}
        for i, (s, ref) in enumerate(refinements(self.ev).items()):
            if s == "axial" and not self.pad[core]:
                continue
            start_col[s] = ev.subs[s].margin.shape[1]
            base = {c: v[[options[s]]] for c, v in ev.space.tables[s].items()}
            study = optuna.create_study(direction="minimize", sampler=optuna.samplers.TPESampler(
                seed=self.seed + 10 + i, multivariate=len(ref.distributions) > 1, constant_liar=True,
                n_startup_trials=self.batch))
            start = {"dm": "main_spring_mean_body_diameter_mm", "h0_t": "cone_spring_aspect_ratio",
                     "s_h0": "cone_spring_deflection_ratio"}
            study.enqueue_trial({k: float(np.clip(base[start[k]][0], d.low, d.high))
                                 for k, d in ref.distributions.items()})
            told = 0
            while told < trials:
                asked = [study.ask(ref.distributions) for _ in range(min(self.batch, trials - told))]
                sub = self._evaluate(s, ref.columns(base, [t.params for t in asked]), np.array([core]))
                for j, t in enumerate(asked):
                    passes = bool(sub.feasible[0, j])
                    t.set_constraint("margin", float(np.clip(-sub.min_margin[0, j] - FEAS_TOL, -_BIG, _BIG)))
                    study.tell(t, float(np.clip(-(sub.margin[0, j] if passes else sub.min_margin[0, j]), -_BIG, _BIG)))
                told += len(asked)
            used[s] = told
        ev = self.archive()
        best = dict(options)
        for s in used:   # the best refined option on the core, passing first, then by margin, if better
            sub, first = ev.subs[s], start_col[s]

            def rank(j):
                return (1, float(sub.margin[core, j])) if sub.feasible[core, j] else (0, float(sub.min_margin[core, j]))
            j = max(range(first, len(sub.margin[core])), key=rank)
            if rank(j) > rank(options[s]):
                best[s] = j
        feasible = bool(ev.core_feasible()[core]) and all(bool(ev.subs[s].feasible[core, best[s]]) for s in SUBSYSTEMS)
        self.best = (core, best, self._design(ev, core, best), feasible)
        return used


def _flowchart_parts(d, settings):
    """The thesis flowchart's design (a warm start), or None when it builds none."""
    try:
        r = run(d, settings, time_points=0)
    except Exception:  # noqa: BLE001 - the warm start is a hint only; the search goes on without it
        return None
    return r.parts or None


def _snap(res, d, settings) -> dict | None:
    """The catalog snap of a continuous result: the design on the exact solvers' grids, verified."""
    snapped = snap_parts(res.parts)
    moved = {k: [res.parts[k], snapped[k]] for k in snapped if snapped[k] != res.parts[k]}
    if not moved:
        return None
    r = verify(d, snapped, settings, detail=False)
    return {"moved": moved, "feasible": not r.failed(), "margin": design_margin(r),
            **design_scores(d, snapped, settings), "failed": [c.id for c in r.failed()]}


def solve(d, objective="standard", *, n_trials: int = 200, settings: Settings = Settings(), seed: int = 0,
          time_limit_s: float | None = None, continuous: bool = True, refine_trials: int = 32,
          warm_start: bool = True, batch: int = BATCH, sampler: str = "tpe", pin_inputs: bool = False, **_):
    """Best design found with at most ``n_trials`` catalog proposals per subsystem study (a subsystem with fewer
    choices proposes each once) or in ``time_limit_s`` seconds (at least one round), then, with ``continuous``,
    ``refine_trials`` continuous proposals per subsystem with continuous dimensions; ``pin_inputs`` keeps the parts
    the input names (the core rows of :func:`synth.design.space.core_rows`, as for every solver); see the module
    docstring."""
    obj = objective if isinstance(objective, Objective) else Objective.parse(objective)
    n_trials = max(1, int(n_trials))
    t0 = time.perf_counter()
    ev = evaluate(d, settings, subsystems=False, prune=False, pin_inputs=pin_inputs)
    if not len(ev.cores):
        return diagnose(d, solver="blackbox", objective=obj, stats={"time_s": time.perf_counter() - t0},
                        settings=settings, relax=False, exhaustive=True, pin_inputs=pin_inputs)
    search = Search(ev, obj, seed=seed, batch=batch, sampler=sampler)
    search.warm_start(_flowchart_parts(d, settings) if warm_start else None)
    deadline = None if time_limit_s is None else t0 + float(time_limit_s)
    while not search.finished():
        if search.round(n_trials) == 0 or (deadline is not None and time.perf_counter() >= deadline):
            break
    told = sum(search.trials.values())
    proved = search.proved()
    stats = {"trials": told, "trials_by_subsystem": dict(search.trials), "rounds": search.rounds,
             "catalog_stage_s": time.perf_counter() - t0, "sampler": sampler, "seed": seed,
             "cores_live": int(len(search.live_cores())), "proof": "bounds attained" if proved else "none"}
    if continuous and (deadline is None or time.perf_counter() < deadline):
        stats["refine_trials"] = search.refine(int(refine_trials))
    core, options, vals, feasible = search.best
    stats.update(designs_evaluated=search.pairs, continuous=continuous)
    status = ("optimal" if proved else "feasible") if feasible else "infeasible"
    res = build_result(search.archive(), core, options, status=status, solver="blackbox", objective=obj,
                       stats=stats)
    if not feasible:   # no "relaxations" key: none were searched (an empty list says none was found)
        res.diagnosis = {"message": f"no feasible design found in {told} trials (not a proof: enumerate proves "
                                    "infeasibility and finds the input relaxations); the nearest design found is shown",
                         "violated": violated_of(res)}
    if continuous:
        snap = _snap(res, d, settings)
        if snap is not None:
            res.stats["catalog_snap"] = snap
            res.notes.append("catalog snap (" + ", ".join(f"{k} {a:g} -> {b:g}" for k, (a, b) in snap["moved"].items())
                             + "): " + ("feasible" if snap["feasible"] else "fails " + ", ".join(snap["failed"]))
                             + f", margin {snap['margin']:+.4f}")
    res.stats["time_s"] = time.perf_counter() - t0
    return res
