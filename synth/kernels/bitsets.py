"""Word-packed bit sets of integer tokens (the platform reductions' part substitution, :mod:`synth.platform.prune`):
the compiled loops of :mod:`synth.kernels._bitsets_jit`, loaded on the first call (importing this module never
imports numba). Integer bit operations only: the results are those of the numpy expressions they replace, exactly.
"""

from __future__ import annotations

__all__ = ["set_bits", "subset_pairs"]


def set_bits(row, col, bits) -> None:
    """Set bit ``col[i]`` of row ``row[i]`` of the ``(rows, words)`` uint64 table ``bits``, for every ``i`` (int64
    ``row`` and ``col``, C-ordered)."""
    from synth.kernels import _bitsets_jit
    _bitsets_jit.set_bits(row, col, bits)


def subset_pairs(bits, pj, pk, out) -> None:
    """``out[p]``: whether every bit of row ``pj[p]`` of ``bits`` is set in row ``pk[p]``, each pair stopping at the
    first word that refutes it."""
    from synth.kernels import _bitsets_jit
    _bitsets_jit.subset_pairs(bits, pj, pk, out)
