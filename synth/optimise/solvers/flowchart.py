"""The thesis flowchart as a solver: its own sequential design, verified like every solver's.

The baseline is :func:`synth.flowchart.run` itself (one procedure, not a
second greedy): bearing from Table 1, pivot class from the input or Table 2,
the damping split, the thesis's bushing length, pad and spacer classes from
the axial damping (enlarged while the end-of-life damping fails), a round-wire
main spring before a rectangular one and the bolt escalation. Each choice is
final: a later failure is not repaired.

>>> from synth.data.generated_applications import generate
>>> r = solve(generate(2, seed=0)[1])
>>> r.solver, r.status in ("baseline", "infeasible")
('flowchart', True)
"""

from __future__ import annotations

import time

from synth.design.evaluate import Settings
from synth.optimise.answer import design_margin
from synth.flowchart import run
from synth.optimise.product import design_scores
from synth.optimise.diagnose import violated_of

__all__ = ["solve"]


def solve(d, objective="standard", *, settings: Settings = Settings(), **_):
    """The thesis flowchart's design (status ``baseline``, or ``infeasible`` when a check fails)."""
    t0 = time.perf_counter()
    r = run(d, settings, time_points=0)
    r.stats = {"time_s": time.perf_counter() - t0}
    r.objective = "thesis procedure"
    if r.parts:
        r.objectives = {**design_scores(d, r.parts, settings), "margin": design_margin(r)}
    if r.failed():
        r.status = "infeasible"
        r.diagnosis = {"message": "the thesis flowchart's sequential design fails a check",
                       "violated": violated_of(r)}   # no relaxations searched: no "relaxations" key
    return r
