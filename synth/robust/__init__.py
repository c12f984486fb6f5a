"""Designs that survive production: tolerance-aware verdicts, capability indices and robust synthesis.

* :mod:`synth.robust.tolerances`: the tolerance model, declared once (``catalogs/tolerances.csv``);
* :mod:`synth.robust.sampling`: production samples of a design through the one evaluator;
* :mod:`synth.robust.capability`: per check the probability of violation, Ppk, worst case, RSS, contributors;
* :mod:`synth.robust.rare`: small probabilities (FORM design point and importance sampling);
* :mod:`synth.robust.assumptions`: the illustrative limits that decide verdicts, and which verdicts flip;
* :mod:`synth.robust.synthesis`: the best design of an objective among those meeting a capability target;
* :mod:`synth.robust.settings`: the targets and estimator settings.
"""
