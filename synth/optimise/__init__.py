"""Catalog optimisation: one design space, exact and black-box solvers, cost against margin.

:func:`solve` dispatches to the solvers by name (:data:`SOLVERS`); every one
returns a :class:`~synth.optimise.answer.DesignResult`.
"""

from __future__ import annotations

import importlib

__all__ = ["SOLVERS", "solve"]

#: solver name -> (module, keyword arguments)
SOLVERS = {
    "enumerate": ("synth.optimise.solvers.enumerate", {}),
    "minlp": ("synth.optimise.solvers.minlp", {"variant": "minlp"}),
    "milp-highs": ("synth.optimise.solvers.minlp", {"variant": "milp-highs"}),
    "milp-cvxpy": ("synth.optimise.solvers.milp_cvxpy", {}),
    "blackbox": ("synth.optimise.solvers.blackbox", {}),
    "flowchart": ("synth.optimise.solvers.flowchart", {}),
}


def solve(d, objective="standard", solver: str = "enumerate", **kw):
    """Optimise input ``d`` with ``solver`` (a name of :data:`SOLVERS`) for ``objective``.

    >>> from synth.data.generated_applications import generate
    >>> solve(generate(2, seed=0)[1], "cost", "enumerate").status
    'optimal'
    """
    if solver not in SOLVERS:
        from synth.errors import InputError, Problem
        raise InputError(Problem("solver", solver, "one of " + ", ".join(SOLVERS)))
    from synth.optimise.objectives import Objective
    objective = objective if isinstance(objective, Objective) else Objective.parse(objective)  # for every solver
    module, extra = SOLVERS[solver]
    return importlib.import_module(module).solve(d, objective, **extra, **kw)
