"""numba helpers shared by the compiled kernels: numpy's element-wise semantics for scalars (a NaN propagates).

Imported only by the kernels' numba modules (it imports numba at import time); they name these ``_maximum`` and
``_minimum`` (numpy's ``maximum`` and ``minimum`` are the array functions).
"""

from __future__ import annotations

from numba import njit


@njit(cache=True, error_model="numpy")
def maximum(a, b):
    """``numpy.maximum`` of two floats (a NaN propagates)."""
    if a > b or a != a:
        return a
    return b


@njit(cache=True, error_model="numpy")
def minimum(a, b):
    """``numpy.minimum`` of two floats (a NaN propagates)."""
    if a < b or a != a:
        return a
    return b
