"""The array moves of the batched scans (:class:`synth.optimise.batch.Batch`): first hits, argmaxes over available
options, distinct rows, segments and the rounds of a branch and bound over per-application segments."""

from __future__ import annotations

import numpy as np

__all__ = ["first_true", "argmax_value", "unique_rows", "segments", "rounds"]


def first_true(mask: np.ndarray) -> np.ndarray:
    """Per row of a 2-D boolean array, the first True column (-1: none)."""
    if mask.shape[1] == 0:
        return np.full(mask.shape[0], -1, dtype=np.int64)
    return np.where(mask.any(axis=1), np.argmax(mask, axis=1), -1)


def argmax_value(vals: np.ndarray, cols: np.ndarray):
    """Per row, ``(value, option)`` of ``numpy.argmax`` over the full option axis, where only ``cols`` (sorted
    option indices) are available and the others are -inf: the first index of the maximum, option 0 when every
    available value is -inf (as the enumeration's argmax over -inf rows)."""
    if vals.shape[1] == 0:
        return np.full(vals.shape[0], -np.inf), np.zeros(vals.shape[0], dtype=np.int64)
    j = np.argmax(vals, axis=1)
    v = vals[np.arange(len(vals)), j]
    return v, np.where(v > -np.inf, cols[j], 0)


def unique_rows(*cols):
    """``(first, inverse)``: one representative position per distinct tuple of the columns (floats; NaN equal to
    NaN), and each position's representative index."""
    stack = np.stack([np.asarray(c, dtype=float) for c in cols], axis=1)
    if not len(stack):
        return np.zeros(0, dtype=np.int64), np.zeros(0, dtype=np.int64)
    stack = np.where(np.isnan(stack), np.finfo(float).max, stack)  # NaN keys compare equal
    stack = stack + 0.0  # -0.0 -> 0.0: equal keys, equal bits
    # a stable lexicographic sort and the row changes: np.unique(axis=0)'s groups, in its order, several
    # times faster (np.unique sorts a structured view)
    order = np.lexsort(stack.T[::-1])
    srt = stack[order]
    new = np.ones(len(srt), dtype=bool)
    new[1:] = (srt[1:] != srt[:-1]).any(axis=1)
    inv = np.empty(len(srt), dtype=np.int64)
    inv[order] = np.cumsum(new) - 1
    return order[new].astype(np.int64), inv


def segments(starts, counts):
    """Concatenated ``arange(start, start + count)`` of every segment."""
    counts = np.asarray(counts, dtype=np.int64)
    tot = int(counts.sum())
    if not tot:
        return np.zeros(0, dtype=np.int64)
    offs = np.repeat(np.asarray(starts, dtype=np.int64) - np.cumsum(counts) + counts, counts)
    return offs + np.arange(tot, dtype=np.int64)


def rounds(pos, seg_end, block: int, may, still=None):
    """The rounds of a branch and bound over segments of sorted candidates (one segment per application):
    each round takes, in every live segment, the next ``block`` positions (doubling every round) that ``may``
    still win, and yields them (non-empty). A segment is live while it has positions left, its next one may
    win and ``still()`` (evaluated each round: the incumbents change) holds for it. ``pos`` advances in place."""
    while True:
        live = (pos < seg_end) & may(np.minimum(pos, seg_end - 1))
        if still is not None:
            live &= still()
        if not live.any():
            return
        cnt = np.minimum(block, seg_end - pos)
        take = segments(pos[live], cnt[live])
        take = take[may(take)]
        pos[live] = pos[live] + cnt[live]
        block *= 2
        if len(take):
            yield take
