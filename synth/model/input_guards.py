"""Input guards of the physics functions: a value outside its range is an :class:`~synth.errors.InputError` naming
the field, the value and what is accepted (never a traceback).

>>> require("clamp length [mm]", [3.0, 4.5]).tolist()
[3.0, 4.5]
"""

from __future__ import annotations

import numpy as np

from synth.errors import InputError, Problem

__all__ = ["as_array", "require"]


def as_array(x):
    """``x`` as a float array."""
    return np.asarray(x, dtype=float)


def require(name, x, *, low=0.0, inclusive=False, high=None, accepted=None):
    """Raise InputError if any element of ``x`` is outside (low, high] (NaN fails)."""
    a = as_array(x)
    ok = (a >= low) if inclusive else (a > low)
    if high is not None:
        ok &= a <= high
    ok &= np.isfinite(a)
    if not np.all(ok):
        bad = a[~ok] if a.ndim else a
        value = float(np.ravel(bad)[0])
        if accepted is None:
            accepted = f"a finite number {'>=' if inclusive else '>'} {low:g}" + (
                f" and <= {high:g}" if high is not None else "")
        raise InputError(Problem(name, value, accepted))
    return a
