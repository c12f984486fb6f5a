"""The plain data of the selection models (:mod:`formulations.selection`), prepared from one evaluation.

The models never evaluate physics: they read the feasibility, margins and
scores of an :class:`~synth.optimise.product.Evaluation`. Before a model is
built the data are presolved:

* infeasible cores and infeasible (core, option) pairs are dropped;
* options that are **dominated** are dropped: option ``k`` of a subsystem
  goes when another option ``k'`` is feasible with every core ``k`` is
  feasible with, scores no worse on the objective, and (when the margin is
  in play) has a margin at least as large with each of those cores. No
  optimum is lost (an exact presolve), and the models shrink from thousands
  of springs to a few dozen.

>>> from synth.data import case_path
>>> from synth.io.documents import load_input
>>> from synth.optimise.product import evaluate
>>> md, cores, opts = model_data(evaluate(load_input(case_path("case3"))), {"cost": 1.0}, False)
>>> md.n_cores >= 0, sorted(opts)
(True, ['axial', 'bolt', 'bushing', 'spring'])
"""

from __future__ import annotations

import numpy as np

from formulations.selection import SelectionData
from synth import catalog
from synth.design.space import SUBSYSTEMS
from synth.optimise.solvers.enumerate import tables, weights_vec

__all__ = ["model_data"]


def _undominated(feas: np.ndarray, score: np.ndarray, margin: np.ndarray | None) -> np.ndarray:
    """Indices of the options not dominated by another (ties: the first in score order stays)."""
    alive = np.flatnonzero(feas.any(axis=0))
    order = alive[np.lexsort((alive, score[alive]))]
    kept: list = []
    for k in order:  # a loop over catalog options of one subsystem, vectorised over the kept ones
        if kept:
            kk = np.array(kept)
            covers = np.all(feas[:, kk] | ~feas[:, [k]], axis=0) & (score[kk] <= score[k] + 1e-12)
            if margin is not None:
                covers &= np.all((margin[:, kk] >= margin[:, [k]] - 1e-12) | ~feas[:, [k]], axis=0)
            if covers.any():
                continue
        kept.append(k)
    return np.array(sorted(kept), dtype=int)


def model_data(ev, weights: dict, uses_margin: bool, *, presolve: bool = True):
    """``(SelectionData, core positions, {subsystem: option rows})`` of ``ev`` for an objective.

    ``weights``: the additive weights (``standard``, ``cost``) of the objective; ``uses_margin``: whether the
    margin is in play (then dominance also needs a margin at least as large).
    """
    t = tables(ev, {"cost": 1.0})
    lo, hi = catalog.constant("optimise_margin_floor"), catalog.constant("optimise_margin_ceiling")
    keep = np.isfinite(t.core_score)
    for s in SUBSYSTEMS:
        keep &= t.feas[s].any(axis=1)
    ci = np.flatnonzero(keep)
    opts, feas, marg, score = {}, {}, {}, {}
    for s in SUBSYSTEMS:
        f = t.feas[s][ci]
        m = np.clip(t.margin[s][ci], lo, hi)
        comb = weights_vec(ev.score[s], weights) if any(k != "margin" for k in weights) else ev.score[s]["cost"]
        k = _undominated(f, comb, m if uses_margin else None) if presolve else np.flatnonzero(f.any(axis=0))
        opts[s], feas[s], marg[s] = k, f[:, k], m[:, k]
        score[s] = {n: v[k] for n, v in ev.score[s].items()}
    rows = t.rows[ci]
    data = SelectionData(SUBSYSTEMS, feas, marg, np.clip(t.core_margin[ci], lo, hi),
                         {n: v[rows] for n, v in ev.score_core.items()}, score)
    return data, rows, opts
