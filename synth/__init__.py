"""synth: design synthesiser for automotive timing-belt tensioners.

The physics lives in :mod:`synth.model` (one module per step of the thesis
flowchart), standard parts in the ``catalogs/`` CSV files (loaded by
:mod:`synth.catalog`), the validated design input in :mod:`synth.schema`, and
the user-facing scenes (flowchart, compare, shrink fit, ...) in
:mod:`synth.scenes`.
"""

__version__ = "0.1.0"
