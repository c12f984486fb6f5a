"""Pyomo solvers: the bilinear MINLP solved globally by SCIP, and the linearised MILP solved by HiGHS.

Both read precomputed, presolved per-choice coefficients
(:mod:`synth.optimise.model_data`, models in :mod:`formulations.selection`); SCIP is called through Pyomo's
``scip_direct`` interface (PySCIPOpt), HiGHS through ``appsi_highs`` (highspy).

>>> from synth.io.documents import load_input
>>> from synth.data.generated_applications import generate
>>> r = solve(generate(3, seed=0)[1], "cost", variant="milp-highs")
>>> r.solver
'milp-highs'
"""

from __future__ import annotations

import numpy as np
import pyomo.environ as pyo

from formulations.selection import milp_model, minlp_model
from synth.design.space import SUBSYSTEMS
from synth.optimise.solvers._staged import solve_with

__all__ = ["solve", "VARIANTS"]

VARIANTS = {"minlp": ("scip_direct", minlp_model), "milp-highs": ("appsi_highs", milp_model)}


def _runner(md, variant, time_limit_s=None, status: dict | None = None):
    """The stage runner of ``variant``; ``status["proved"]`` turns False when a time limit stops a stage."""
    solver_name, builder = VARIANTS[variant]
    status = {} if status is None else status

    def run(weights, margin_weight, with_margin, t_lb, add_ub):
        m = builder(md, weights, margin_weight, with_margin)
        m.t_lb = t_lb
        m.add_ub = add_ub
        opt = pyo.SolverFactory(solver_name)
        if solver_name == "scip_direct":
            options = {"limits/gap": 0.0}
            if time_limit_s is not None:
                options["limits/time"] = float(time_limit_s)
            res = opt.solve(m, options=options, load_solutions=False)
        else:
            opt.config.mip_gap = 0.0
            if time_limit_s is not None:
                opt.config.time_limit = float(time_limit_s)
            opt.config.load_solution = False
            res = opt.solve(m, load_solutions=False)
        tc = str(res.solver.termination_condition).split(".")[-1]
        if tc not in ("optimal", "globallyOptimal", "locallyOptimal"):
            if "time" not in tc.lower() or not len(res.solution):
                return None
            status["proved"] = False  # the incumbent at the time limit
        m.solutions.load_from(res)
        c = int(np.argmax([pyo.value(m.x[i]) for i in m.C]))
        if variant == "minlp":
            opts = {s: int(np.argmax([pyo.value(m.z[s, k]) for k in range(md.n_options(s))])) for s in SUBSYSTEMS}
        else:
            opts = {}
            for s in SUBSYSTEMS:
                best = max(((pyo.value(m.w[s2, c2, k]), k) for (s2, c2, k) in m.P if s2 == s and c2 == c))
                opts[s] = best[1]
        return c, opts, float(pyo.value(m.additive)), float(pyo.value(m.t))
    return run


def solve(d, objective="standard", *, variant: str = "minlp", time_limit_s: float | None = None, **kw):
    """Optimum by the Pyomo ``variant`` (``minlp``: SCIP; ``milp-highs``: HiGHS); ``time_limit_s`` per stage."""
    status: dict = {}
    return solve_with(d, objective, lambda md: _runner(md, variant, time_limit_s, status), solver=variant,
                      run_status=status, **kw)
