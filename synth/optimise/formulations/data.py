"""Precomputed per-choice coefficients for the MILP and MINLP models.

The models never evaluate physics: they read the margins and scores of an
:class:`~synth.optimise.evaluate.Evaluation`. Before a model is built the
data are presolved:

* infeasible cores and infeasible (core, option) pairs are dropped;
* options that are **dominated** are dropped: option ``k`` of a subsystem
  goes when another option ``k'`` is feasible with every core ``k`` is
  feasible with, scores no worse on the objective, and (when the margin is
  in play) has a margin at least as large with each of those cores. No
  optimum is lost (an exact presolve), and the models shrink from thousands
  of springs to a few dozen.

>>> from synth.schema import load_input

>>> from synth.data import case_path
>>> from synth.optimise.space import build_space
>>> from synth.optimise.evaluate import evaluate
>>> md = model_data(evaluate(build_space(load_input(case_path("case3")))), {"cost": 1.0}, False)
>>> md.n_cores >= 0
True
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from synth import catalog
from synth.optimise.evaluate import Evaluation
from synth.optimise.space import SUBSYSTEMS

__all__ = ["ModelData", "model_data", "score_vectors"]


@dataclass
class ModelData:
    """Coefficients of the selection models.

    ``cores``: core indices (into ``space.cores``); ``opts[s]``: option
    indices of subsystem ``s`` kept; ``feas[s]``: bool ``(n_cores, n_opts)``;
    ``margin[s]``: objective margins ``(n_cores, n_opts)`` clipped to
    ``[optimise_margin_floor, optimise_margin_ceiling]``; ``core_margin``;
    ``score_core[name]``/``score[s][name]`` for ``name`` in ``standard``, ``cost``.
    """

    cores: np.ndarray
    opts: dict
    feas: dict
    margin: dict
    core_margin: np.ndarray
    score_core: dict
    score: dict
    sizes_before: dict

    @property
    def n_cores(self) -> int:
        return len(self.cores)

    def pairs(self, s):
        """``(i, j)`` index arrays of the feasible (core, option) pairs of subsystem ``s``."""
        return np.nonzero(self.feas[s])

    def add(self, weights: dict, which: str, s: str | None = None) -> np.ndarray:
        src = self.score_core if s is None else self.score[s]
        out = np.zeros(len(src["cost"]))
        for k, w in weights.items():
            if k != "margin":
                out = out + w * src[k]
        return out


def score_vectors(table) -> dict:
    return {"standard": table["nonstandard"].to_numpy(float), "cost": table["cost_eur"].to_numpy(float)}


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


def model_data(ev: Evaluation, weights: dict, uses_margin: bool, *, presolve: bool = True) -> ModelData:
    """Presolved coefficients of ``ev`` for an objective with additive ``weights`` (and the margin or not)."""
    from synth.optimise.solvers.enumerate import tables
    t = tables(ev, {"cost": 1.0})
    lo, hi = catalog.constant("optimise_margin_floor"), catalog.constant("optimise_margin_ceiling")
    keep = np.isfinite(t.core_score)
    for s in SUBSYSTEMS:
        keep &= t.feas[s].any(axis=1)
    ci = np.flatnonzero(keep)
    sp = ev.space
    sizes = {s: int(t.feas[s].shape[1]) for s in SUBSYSTEMS}
    sizes["cores"] = int(len(sp.cores))
    opts, feas, marg, score = {}, {}, {}, {}
    for s in SUBSYSTEMS:
        f = t.feas[s][ci]
        m = np.clip(t.margin[s][ci], lo, hi)
        sv = score_vectors(sp.subsystems[s])
        comb = sum(w * sv[k] for k, w in weights.items() if k != "margin") if weights else sv["cost"]
        k = _undominated(f, np.asarray(comb, float) if not np.isscalar(comb) else sv["cost"], m if uses_margin else None) \
            if presolve else np.flatnonzero(f.any(axis=0))
        opts[s], feas[s], marg[s] = k, f[:, k], m[:, k]
        score[s] = {n: v[k] for n, v in sv.items()}
    cs = score_vectors(sp.cores)
    return ModelData(t.rows[ci], opts, feas, marg, np.clip(t.core_margin[ci], lo, hi),
                     {n: v[t.rows[ci]] for n, v in cs.items()}, score, sizes)
