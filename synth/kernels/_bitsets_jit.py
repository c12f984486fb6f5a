"""numba kernels of word-packed bit sets (the platform reductions' part substitution, :mod:`synth.platform.prune`).

Imported lazily (the first call of :func:`synth.platform.prune._token_bits` or ``_subsets``), as the other
``_*_jit`` modules: importing the platform package never imports numba. Integer bit operations only, so the
results are those of the numpy expressions they replace, exactly:

* :func:`set_bits` -- ``bits[row[i], col[i] // 64] |= 1 << (col[i] % 64)`` for every pair;
* :func:`subset_pairs` -- per pair ``(j, k)``, whether every bit of row ``j`` is set in row ``k`` (no word of
  ``bits[j] & ~bits[k]`` non-zero), stopping at the first word that refutes it.
"""

from __future__ import annotations

import numpy as np
from numba import njit

from synth.kernels.numba_setup import announce_compiles

announce_compiles()  # a line on stderr when this process compiles a kernel (synth.kernels.numba_setup)


@njit(cache=True)
def set_bits(row, col, bits):
    """Set bit ``col[i]`` of row ``row[i]`` of the ``(rows, words)`` uint64 table ``bits``, for every ``i``."""
    one = np.uint64(1)
    for i in range(len(row)):
        c = col[i]
        bits[row[i], c >> 6] |= one << np.uint64(c & 63)


@njit(cache=True)
def subset_pairs(bits, pj, pk, out):
    """``out[p]``: the bit set ``bits[pj[p]]`` lies inside ``bits[pk[p]]``."""
    n_w = bits.shape[1]
    for p in range(len(pj)):
        a = pj[p]
        b = pk[p]
        ok = True
        for t in range(n_w):
            if bits[a, t] & ~bits[b, t]:
                ok = False
                break
        out[p] = ok
