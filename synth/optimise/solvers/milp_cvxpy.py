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


def _runner(md, backend, time_limit_s=None, status: dict | None = None):
    status = {} if status is None else status

    def run(weights, margin_weight, with_margin, t_lb, add_ub):
        prob, x, ws, t, additive, pairs = milp_problem(md, weights, margin_weight, with_margin, t_lb, add_ub)
        kw = {}
        if time_limit_s is not None:
            kw = {"time_limit": float(time_limit_s)} if backend == "HIGHS" else \
                {"scip_params": {"limits/time": float(time_limit_s)}}
        prob.solve(solver=backend, **kw)
        if prob.status not in (cp.OPTIMAL, cp.OPTIMAL_INACCURATE):
            if x.value is None:
                return None
            status["proved"] = False
        c = int(np.argmax(x.value))
        opts = {}
        for s in SUBSYSTEMS:
            ci, ki = pairs[s]
            j = np.flatnonzero(ci == c)
            opts[s] = int(ki[j[np.argmax(ws[s].value[j])]])
        return c, opts, float(additive.value), float(t.value)
    return run


def solve(d, objective="standard", *, backend: str = "HIGHS", time_limit_s: float | None = None, **kw):
    """Optimum by the cvxpy MILP (``backend``: ``HIGHS`` or ``SCIP``); ``time_limit_s`` per stage."""
    status: dict = {}
    return solve_with(d, objective, lambda md: _runner(md, backend, time_limit_s, status), solver="milp-cvxpy",
                      run_status=status, **kw)
