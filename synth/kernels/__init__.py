"""Compiled kernels for bulk screening (issue 13): the hot loops of the physics over keys x options.

Importing this package does not import numba: the kernels are compiled (or
loaded from numba's on-disk cache) on their first call, so the
one-application path keeps its start-up time. Each kernel has a numpy twin
(``engine="numpy"``) built on the registry's group function, for tests,
benchmarks and the one-application path.

Importing it configures numba's cache folder and pool (:mod:`synth.kernels.numba_setup`; numba stays unloaded).

* :mod:`synth.kernels.main_spring` -- the main spring of thesis step 9:
  the registry's spring-group margins, first feasible option in score order,
  max-min margin, any feasible.
"""

from synth.kernels import numba_setup

numba_setup.configure()  # before any kernel module imports numba: the cache folder, the pool size

from synth.kernels.main_spring import (  # noqa: E402, F401
    MARGIN_NAMES, FirstFeasible, MaxMin, SpringKeys, SpringOptions, any_feasible, first_feasible, keys_of_rows,
    margins, max_min_margin, options_of_space, reference_margins, spring_keys, spring_options,
)

__all__ = ["MARGIN_NAMES", "FirstFeasible", "MaxMin", "SpringKeys", "SpringOptions", "any_feasible", "first_feasible",
           "keys_of_rows", "margins", "max_min_margin", "options_of_space", "reference_margins", "spring_keys",
           "spring_options"]
