"""The linearised MILP written in cvxpy, solved by HiGHS (default) or SCIP.

>>> from synth.data.generated_applications import generate
>>> solve(generate(3, seed=0)[1], "cost").solver
'milp-cvxpy'
"""

from __future__ import annotations

import cvxpy as cp
import numpy as np

from formulations.selection import milp_problem
from synth.design.space import SUBSYSTEMS
from synth.optimise.solvers._staged import solve_with

__all__ = ["solve"]


def _runner(md, backend):
    def run(weights, margin_weight, with_margin, t_lb, add_ub):
        prob, x, ws, t, additive, pairs = milp_problem(md, weights, margin_weight, with_margin, t_lb, add_ub)
        prob.solve(solver=backend)
        if prob.status not in (cp.OPTIMAL, cp.OPTIMAL_INACCURATE):
            return None
        c = int(np.argmax(x.value))
        opts = {}
        for s in SUBSYSTEMS:
            ci, ki = pairs[s]
            j = np.flatnonzero(ci == c)
            opts[s] = int(ki[j[np.argmax(ws[s].value[j])]])
        return c, opts, float(additive.value), float(t.value)
    return run


def solve(d, objective="standard", *, backend: str = "HIGHS", **kw):
    """Optimum by the cvxpy MILP (``backend``: ``HIGHS`` or ``SCIP``)."""
    return solve_with(d, objective, lambda md: _runner(md, backend), solver="milp-cvxpy", **kw)
