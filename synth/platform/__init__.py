"""Platform rationalisation: the fewest standard parts that serve a whole portfolio (issue 16).

``data`` (the feasibility interface), ``synthetic`` (data shaped like the real one),
``compile`` and ``prune`` (plain arrays for :mod:`formulations.platform`, reduced
provably), ``greedy`` (baseline and warm start), ``assign`` (each application's design
from a platform), ``rationalise`` (the chain and the trade-off sweep), ``outputs``
(files and plot), ``producer`` (where the command gets its data).
"""

__all__ = ["data", "synthetic", "compile", "prune", "greedy", "assign", "rationalise", "outputs", "producer"]
