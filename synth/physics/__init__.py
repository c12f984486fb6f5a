"""Physics of the thesis design flowchart: one module per step.

Conventions: pure functions on numpy arrays (scalars broadcast), units in
argument names (``_mm``, ``_n``, ``_nm``, ``_mpa``, ``_deg``), docstrings that
cite the thesis equation (``eq. (n)``) or the standard they implement.
Constants come from :mod:`synth.catalog`, never bare literals.
"""
