"""Compiled kernels for bulk screening (issue 13): the hot loops of the physics over keys x options.

Importing this package does not import numba: the kernels are compiled (or
loaded from numba's on-disk cache) on their first call, so the
one-application path keeps its start-up time. Each kernel has a numpy twin
(``engine="numpy"``) built on the reference function, for tests and benchmarks.

* :mod:`synth.kernels.torsion_spring` -- the main spring of thesis step 9:
  margins, first feasible option in score order, max-min margin, any feasible.
"""

from synth.kernels.torsion_spring import (  # noqa: F401
    MARGIN_NAMES, FirstFeasible, MaxMin, SpringKeys, SpringOptions, any_feasible, first_feasible, margins,
    max_min_margin, options_from_table, reference_margins, spring_keys, spring_options,
)

__all__ = ["MARGIN_NAMES", "FirstFeasible", "MaxMin", "SpringKeys", "SpringOptions", "any_feasible", "first_feasible",
           "margins", "max_min_margin", "options_from_table", "reference_margins", "spring_keys", "spring_options"]
