"""Bulk feasibility over a portfolio of applications (issue 7).

:func:`screen_applications` evaluates a chunk of validated design inputs,
vectorised over applications x candidate designs, and returns one row per
application (feasible or not, the best design, its margins, the binding
constraint, violated constraints and the smallest relaxation).
"""

from synth.bulk.engine import screen_applications

__all__ = ["screen_applications"]
