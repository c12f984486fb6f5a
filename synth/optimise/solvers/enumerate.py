"""Exhaustive, vectorised evaluation of the catalog product: the exact reference solver.

The margins of the core and of each subsystem are evaluated once
(:func:`synth.optimise.product.evaluate`); because subsystems share no
constraint given the core (:mod:`synth.optimise.space`), every design of
the catalog product is covered by combining the tables: for an additive
objective the best design of a core is its own score plus each subsystem's
best feasible option; for the margin the subsystems combine by the minimum.
Thresholds of the margin (:func:`additive_curve`) give the lexicographic
orders with the margin, weighted sums with the margin, and the Pareto front.
No Python loop runs over candidates: the loops are over the four
subsystems, the (few) cores and the margin thresholds.

>>> from synth.data.generated_applications import generate
>>> r = solve(generate(2, seed=0)[1], "cost")
>>> r.status, r.parts["damper_pad_class"], r.objectives["cost"] > 0
('optimal', 'none', True)
"""

from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np

from synth.design.evaluate import Settings
from synth.design.combine import combine
from synth.design.result import Result
from synth.design.space import SUBSYSTEMS
from synth.optimise.product import Evaluation, evaluate
from synth.optimise.objectives import FALLBACK_WEIGHTS, Objective, ties, weighted_sum
from synth.optimise.answer import build_result
from synth.optimise.batch import Batch
from synth.optimise.diagnose import diagnose

__all__ = ["Tables", "tables", "best_additive", "additive_curve", "max_margin", "solve", "solve_space"]

_EPS = 1e-9


@dataclass
class Tables:
    """Per-core and per-option arrays the combination works on (cores: the evaluated rows only)."""

    ev: Evaluation
    rows: np.ndarray            # core positions (into ev.cores) whose subsystems were evaluated
    core_score: np.ndarray      # (nR,)
    core_margin: np.ndarray     # (nR,) objective margin
    score: dict                 # s -> (nk,)
    feas: dict                  # s -> (nR, nk)
    margin: dict                # s -> (nR, nk) objective margin

    def candidates(self) -> int:
        """Number of whole-tensioner designs covered: every core times every option of each subsystem."""
        return int(len(self.ev.cores)) * int(np.prod([self.ev.space.n(s) for s in SUBSYSTEMS]))


def weights_vec(scores: dict, weights: dict) -> np.ndarray:
    """:func:`synth.optimise.objectives.weighted_sum` of a score dict (one array per name), as an array."""
    return np.zeros(len(next(iter(scores.values())))) + weighted_sum(scores, weights)


def tables(ev: Evaluation, weights: dict) -> Tables:
    """Score vectors (``weights`` over ``standard``/``cost``), feasibility and margin tables of ``ev``."""
    rows = ev.rows
    ok_core = ev.core_feasible()[rows]
    score = {s: weights_vec(ev.score[s], weights) for s in SUBSYSTEMS}
    feas = {s: ev.subs[s].feasible & ok_core[:, None] for s in SUBSYSTEMS}
    marg = {s: ev.subs[s].margin for s in SUBSYSTEMS}
    core_score = np.where(ok_core, weights_vec(ev.score_core, weights)[rows], np.inf)
    return Tables(ev, rows, core_score, ev.core_margin()[rows], score, feas, marg)


def best_additive(t: Tables, tau: float = -np.inf):
    """Best additive score over designs whose margins are all ``>= tau``.

    Returns ``(value, core_row, {subsystem: option_row})``; value ``inf`` when none.
    """
    total = np.where(t.core_margin >= tau - _EPS, t.core_score, np.inf)
    pick = {}
    for s in SUBSYSTEMS:
        ok = t.feas[s] & (t.margin[s] >= tau - _EPS)
        sc = np.where(ok, t.score[s][None, :], np.inf)
        k = np.argmin(sc, axis=1) if sc.shape[1] else np.zeros(len(sc), int)
        total = total + (sc[np.arange(len(sc)), k] if sc.shape[1] else np.inf)
        pick[s] = k
    if not len(total) or not np.isfinite(total).any():
        return np.inf, None, None
    r = int(np.argmin(total))
    return float(total[r]), int(t.rows[r]), {s: int(pick[s][r]) for s in SUBSYSTEMS}


def max_margin(t: Tables):
    """The largest achievable objective margin over feasible designs (``-inf`` when none)."""
    core = np.where(np.isfinite(t.core_score), t.core_margin, -np.inf)
    best = [np.max(np.where(t.feas[s], t.margin[s], -np.inf), axis=1) if t.feas[s].shape[1]
            else np.full(len(core), -np.inf) for s in SUBSYSTEMS]
    m = combine(core, best)
    return float(np.max(m)) if len(m) else -np.inf


def additive_curve(t: Tables, taus) -> np.ndarray:
    """Best additive score for each margin threshold of ``taus`` (vectorised over thresholds and options)."""
    taus = np.asarray(taus, float)
    total = np.where(t.core_margin[:, None] >= taus[None, :] - _EPS, t.core_score[:, None], np.inf)
    for s in SUBSYSTEMS:
        m = np.where(t.feas[s], t.margin[s], -np.inf)
        order = np.argsort(-m, axis=1)                       # options by decreasing margin, per core
        m_sorted = np.take_along_axis(m, order, axis=1)
        cummin = np.minimum.accumulate(t.score[s][order], axis=1)
        # number of options with margin >= tau, per core and threshold (a loop over the few cores)
        count = np.stack([np.searchsorted(-row, -taus + _EPS, side="right") for row in m_sorted]) \
            if len(m_sorted) else np.zeros((0, len(taus)), int)
        best = np.where(count > 0, np.take_along_axis(cummin, np.maximum(count - 1, 0), axis=1), np.inf)
        total = total + best
    return total.min(axis=0) if len(total) else np.full(len(taus), np.inf)


def margin_thresholds(t: Tables, n: int | None = None) -> np.ndarray:
    """The distinct margins (at least 0) of the core rows and the feasible options of ``t``, ascending, each a
    threshold of the margin objective (``n``: at most that many, by quantile)."""
    vals = [t.core_margin[np.isfinite(t.core_margin)]]
    for s in SUBSYSTEMS:
        m = t.margin[s][t.feas[s]]
        vals.append(m[np.isfinite(m) & (m >= 0)])
    v = np.unique(np.concatenate(vals + [np.array([0.0])]))
    v = v[v >= 0]
    if n is not None and len(v) > n:
        v = np.unique(np.quantile(v, np.linspace(0, 1, n)))
    return v


def solve_space(ev: Evaluation, objective: Objective) -> tuple:
    """Optimum over the evaluated space ``ev``: ``(core position, options, stats)`` or ``(None, None, stats)``."""
    t0 = time.perf_counter()
    w = objective.additive_weights()
    t = tables(ev, w if w else FALLBACK_WEIGHTS)
    if objective.weights and "margin" in objective.weights:
        taus = margin_thresholds(t)
        curve = additive_curve(t, taus)
        score = curve - objective.weights["margin"] * taus
        i = int(np.argmin(score)) if np.isfinite(score).any() else None
        tau = taus[i] if i is not None else np.inf
    elif objective.uses_margin():
        pre = objective.order[:objective.order.index("margin")]
        if not pre:
            tau = max_margin(t)
        else:
            taus = margin_thresholds(t)
            curve = additive_curve(tables(ev, Objective(order=pre).additive_weights()), taus)
            best = np.min(curve) if len(curve) else np.inf
            good = np.flatnonzero(ties(curve, best))  # 1e-7 here tied cost 1e-3 EUR apart (1e4 x standard)
            tau = taus[good[-1]] if len(good) and np.isfinite(best) else -np.inf
    else:
        tau = -np.inf
    value, core, options = best_additive(t, tau) if np.isfinite(tau) or tau == -np.inf else (np.inf, None, None)
    elapsed = time.perf_counter() - t0
    n = t.candidates()
    stats = {"combination_time_s": elapsed, "candidates": n, "physics_evaluations": ev.evaluations}
    return core, options, stats


def solve(d, objective="standard", *, settings: Settings = Settings(), pin_inputs: bool = False,
          relax: bool = True, exhaustive: bool = False, **_) -> Result:
    """Exact optimum of input ``d`` for ``objective`` (name, :class:`Objective` or spec string).

    Additive objectives (standardisation, cost, their orders and weighted sums) search the decomposed space
    with branch and bound (:class:`synth.optimise.batch.Batch` with one application and the numpy spring
    twins: no numba on this path): the same optimum as the exhaustive evaluation, proved by bounds. Objectives
    with the margin, and ``exhaustive=True`` (the reference the tests compare with), evaluate every core and
    option (:func:`synth.optimise.product.evaluate`) and combine the tables.
    """
    obj = objective if isinstance(objective, Objective) else Objective.parse(objective)
    t0 = time.perf_counter()
    # the compiled spring kernels of the branch and bound check the thesis's spring limit; another design rule
    # (Settings.spring_limit_basis) takes the exhaustive path, whose springs go through the numpy evaluator
    if not exhaustive and not obj.uses_margin() and settings.spring_limit_basis == "thesis":
        b = Batch([d], settings, pin_inputs=pin_inputs, spring_engine="numpy")
        w = obj.additive_weights()
        found = b.optimum(w if w else FALLBACK_WEIGHTS)[0]
        stats = {"time_s": time.perf_counter() - t0, "candidates": b.candidates(0), "physics_evaluations": b.evaluations,
                 "method": "branch and bound"}
        stats["candidates_per_s"] = stats["candidates"] / max(stats["time_s"], 1e-9)
        if found is None:
            return diagnose(d, solver="enumerate", objective=obj, stats=stats, relax=relax, settings=settings,
                            batch=b, pin_inputs=pin_inputs)
        return build_result(b.view(0), found[0], found[1], status="optimal", solver="enumerate", objective=obj,
                            stats=stats)
    ev = evaluate(d, settings, pin_inputs=pin_inputs)
    t_eval = time.perf_counter() - t0
    core, options, stats = solve_space(ev, obj)
    stats.update(evaluation_time_s=t_eval, time_s=time.perf_counter() - t0)
    stats["candidates_per_s"] = stats["candidates"] / max(stats["time_s"], 1e-9)
    if core is None:  # the nearest design from this evaluation; the reference's probes only when asked for
        return diagnose(d, ev, solver="enumerate", objective=obj, stats=stats, relax=relax, settings=settings,
                        exhaustive=exhaustive, pin_inputs=pin_inputs)
    return build_result(ev, core, options, status="optimal", solver="enumerate", objective=obj, stats=stats)
