"""The linearised selection MILP in cvxpy (same data and structure as :func:`..pyomo_models.milp_model`).

Variables: ``x`` (one binary per core) and ``w`` (one binary per feasible
(core, option) pair, stacked over the subsystems); ``t`` the margin.
Constraints: ``sum x = 1``; ``L_s w = x`` per subsystem (``L_s`` maps pairs to
their core); ``t <= m_core @ x``; ``t <= m_s @ w_s``; the stage floor on ``t``
and ceiling on the additive score.
"""

from __future__ import annotations

import cvxpy as cp
import numpy as np
import scipy.sparse as sps

from synth.optimise.space import SUBSYSTEMS

__all__ = ["milp_problem"]


def milp_problem(md, weights: dict, margin_weight: float, with_margin: bool, t_lb: float, add_ub: float):
    """``(problem, x, w_by_subsystem, t, additive_expression, pairs)`` for one stage."""
    n = md.n_cores
    x = cp.Variable(n, boolean=True)
    t = cp.Variable()
    cons = [cp.sum(x) == 1, t >= t_lb]
    additive = md.add(weights, "core") @ x
    ws, pairs = {}, {}
    for s in SUBSYSTEMS:
        ci, ki = md.pairs(s)
        pairs[s] = (ci, ki)
        w = cp.Variable(len(ci), boolean=True)
        ws[s] = w
        link = sps.csr_matrix((np.ones(len(ci)), (ci, np.arange(len(ci)))), shape=(n, len(ci)))
        cons.append(link @ w == x)
        cons.append(t <= md.margin[s][ci, ki] @ w)
        additive = additive + md.add(weights, "opt", s)[ki] @ w
    cons.append(t <= md.core_margin @ x)
    cons.append(additive <= add_ub)
    obj = -t if (with_margin and not weights) else additive - margin_weight * t
    return cp.Problem(cp.Minimize(obj), cons), x, ws, t, additive, pairs
