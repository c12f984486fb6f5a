"""Compiled kernels for bulk screening (issue 13): the hot loops of the physics over keys x options.

Importing this package does not import numba: the kernels are compiled (or
loaded from numba's on-disk cache) on their first call, so the
one-application path keeps its start-up time. Each kernel has a numpy twin
(``engine="numpy"``) built on the registry's group function, for tests,
benchmarks and the one-application path.

Importing it configures numba's cache folder and pool (:mod:`synth.kernels.numba_setup`; numba stays unloaded) and
nothing else: the physics' compiled twins (:mod:`synth.kernels.axial`) sit below the evaluator, which calls them,
and the scans (:mod:`synth.kernels.main_spring`, :mod:`synth.kernels.engines`) above it.

* :mod:`synth.kernels.main_spring` -- the main spring of thesis step 9:
  the registry's spring-group margins, first feasible option in score order,
  max-min margin, any feasible.
"""

from synth.kernels import numba_setup

numba_setup.configure()  # before any kernel module imports numba: the cache folder, the pool size

__all__: list = []
