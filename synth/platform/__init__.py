"""Platform rationalisation: the fewest standard parts that serve a whole portfolio (issue 16).

``options`` (the part families on the real catalogs), ``producer`` (a portfolio's
feasibility through the evaluator, or synthetic data), ``data`` (the feasibility
interface), ``synthetic`` (data shaped like the real one), ``compile`` and ``prune``
(plain arrays for :mod:`formulations.platform`, reduced provably), ``greedy`` (baseline and
warm start), ``assign`` (each application's design from a platform), ``verified`` (every
assigned design checked again through the evaluator), ``rationalise`` (the chain and the
trade-off sweep), ``outputs`` (files, plot and the HTML report's section).
"""

__all__ = ["options", "producer", "data", "synthetic", "compile", "prune", "greedy", "assign", "verified",
           "rationalise", "outputs"]
