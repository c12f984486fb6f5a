"""A solver's answer as the one :class:`~synth.design.result.Result`: verified, with objectives and what binds.

Every solver ends here: :func:`build_result` verifies the chosen design alone
through :func:`synth.design.verify.verify` (the same evaluator, the same
checks as the flowchart) and attaches the objective values and statistics.
"""

from __future__ import annotations

from synth.design.result import Result
from synth.design.verify import verify

__all__ = ["build_result", "design_margin", "objective_name"]


def design_margin(r: Result) -> float:
    """The margin objective of a verified design: its assessment's (:attr:`~synth.design.assessment.Assessment.
    objective_margin`, the smallest margin counted in it)."""
    return float(r.assessment().objective_margin[0])


def objective_name(obj) -> str:
    if getattr(obj, "weights", None):
        return ",".join(f"{k}={v:g}" for k, v in obj.weights.items())
    return ",".join(getattr(obj, "order", (str(obj),)))


def build_result(ev, pos: int, options: dict, *, status: str, solver: str, objective, stats: dict,
                 notes: list | None = None, detail: bool = True) -> Result:
    """Verify the design of core position ``pos`` and option rows ``options`` of evaluation ``ev``."""
    parts = ev.parts(pos, options)
    r = verify(ev.inputs, parts, ev.settings, status=status, solver=solver, detail=detail,
               notes=list(notes or []) + list(ev.notes))
    r.objective = objective_name(objective)
    r.objectives = ev.objective_values(pos, options, design_margin(r))
    r.stats = dict(stats)
    if r.failed() and status in ("optimal", "feasible"):
        r.notes.append("verification failed: " + ", ".join(f"{c.id} {c.margin:+.3g}" for c in r.failed()))
    if status == "infeasible" and not r.failed():  # the search said no design meets every constraint
        raise RuntimeError(f"solver {solver}: status infeasible, but its nearest design passes every check "
                           "(the search and the verification disagree: a synth bug)")
    return r
