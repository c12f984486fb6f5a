"""A design's margin from its parts': the one rule of the decomposed design space (:mod:`synth.design.space`).

A design is a core and one option per subsystem (bushing, axial, spring, bolt); given the core the subsystems share
no constraint, so a design's smallest margin is the smallest of the core's and of each option's, and what binds it
is where that smallest margin is reached (the core first, then the subsystems in :data:`~synth.design.space.SUBSYSTEMS`
order, on ties). :func:`combine` is that rule, on numbers or arrays (one design per element): the exhaustive
enumeration's and the black-box search's margin objectives, the diagnosis's nearest design, the alternatives, the
platform's assignments and the producer's nearest designs all call it.

A search that ranks options for a nearest design ranks a passing option above every failing one
(:func:`nearest_rank`): at fidelity ``screening`` a failing option's margin is the search model's
(:meth:`synth.design.evaluate.Group.rank`) and may be positive where the judge (the full model) fails the option.

>>> combine(0.3, [0.5, 0.1, 0.2, 0.1])
0.1
>>> combine(0.3, [0.5, 0.1, 0.2, 0.1], "arm_wall", ["bushing_p", "cone_sigma", "spring_yield", "thread"])
(0.1, 'cone_sigma')
>>> import numpy as np
>>> combine(np.array([0.3, -0.2]), [np.array([0.5, 0.0]), np.array([0.1, 0.4])]).tolist()
[0.1, -0.2]
"""

from __future__ import annotations

from functools import reduce

import numpy as np

from synth.design.constraints import FEAS_TOL

__all__ = ["combine", "nearest_rank"]


def combine(core, subsystems, core_binding=None, bindings=None):
    """The smallest margin of designs made of a core (margin ``core``) and one option per subsystem (margins
    ``subsystems``, in subsystem order), numbers or arrays broadcast to one shape; with ``core_binding`` and
    ``bindings`` (the constraint binding each, same shapes) also the binding constraint of each design: the part's
    where the smallest margin is reached, the first of ties (the core, then the subsystems in order).
    Returns ``margin`` or ``(margin, binding)``; numbers for numbers.
    """
    parts = [core, *subsystems]
    scalar = all(np.ndim(p) == 0 for p in parts)
    arrays = [np.asarray(p, dtype=float) for p in parts]
    m = reduce(np.minimum, arrays)
    if core_binding is None and bindings is None:
        return float(m) if scalar else m
    labels = [core_binding, *(bindings if bindings is not None else [None] * len(subsystems))]
    if scalar:
        return float(m), next(b for p, b in zip(arrays, labels) if p == m)
    m = np.asarray(m)
    out = np.empty(m.shape, dtype=object)
    done = np.zeros(m.shape, dtype=bool)
    for p, b in zip(arrays, labels):
        hit = ~done & (np.broadcast_to(p, m.shape) == m)
        out[hit] = np.broadcast_to(np.asarray(b, dtype=object), m.shape)[hit]
        done |= hit
    return m, out


def nearest_rank(ok, margin, search_margin=None):
    """The value that ranks options for a nearest design: a passing option (``ok``, the judge's verdict) by its
    smallest margin, at least 0 (a margin within the tolerance is a pass), a failing one by the search model's
    smallest margin (``search_margin``, default ``margin``), at most ``-FEAS_TOL``: every passing option ranks above
    every failing one, whatever the search model says of the failing ones.

    >>> nearest_rank(np.array([True, False, False]), np.array([-1e-10, -0.3, -0.1]),
    ...              np.array([0.2, -0.3, 0.05])).tolist()
    [0.0, -0.3, -1e-09]
    """
    search = margin if search_margin is None else search_margin
    return np.where(ok, np.maximum(margin, 0.0), np.minimum(search, -FEAS_TOL))
