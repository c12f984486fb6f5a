"""The mathematical programs of synth as functions of plain data (numpy arrays, dicts, floats).

No module here imports ``synth``: :mod:`synth.optimise` and :mod:`synth.platform`
prepare the data from the one evaluator and call these builders, so the
arrow runs one way (see ``formulations/README.md``): ``formulations.selection``
(one tensioner's catalog selection) and ``formulations.platform`` (the fewest
parts that serve a portfolio).
"""
