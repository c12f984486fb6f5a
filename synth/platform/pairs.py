"""The evaluated (group, option) pairs of one subsystem in a chunk of applications (:mod:`synth.platform.producer`):
the feasible ones with their margin and binding constraint, and per group the nearest option; the registry index of a
binding constraint and its name."""

from __future__ import annotations

import numpy as np

from synth.design import evaluate
from synth.design.assessment import assess_group
from synth.design.combine import nearest_rank
from synth.design.constraints import REGISTRY

__all__ = ["NO_BINDING", "BLOCK_PAIRS", "margins_and_binding", "binding_names", "binding_name", "segment_best", "Pairs",
           "blocks"]

#: (group, option) pairs per group-function call (bounds the memory of a chunk)
BLOCK_PAIRS = 100_000

#: binding index of "none counted" (an infinite margin); a constraint's index is its place in the registry's order
#: (a check added with ``register`` included)
NO_BINDING = np.iinfo(np.int16).max


def margins_and_binding(g: evaluate.Group, objective_only: bool = True, rows=None) -> tuple[np.ndarray, np.ndarray]:
    """``(smallest margin, binding constraint index into the registry order)`` per row of ``g`` (or of ``rows``).

    The group's assessment (:meth:`synth.design.assessment.Assessment.objective_binding`): the smallest margin of
    the checks counted in the margin objective (with ``objective_only``) or of every counted check, and where it
    is reached (``NO_BINDING`` when none counts; ties: the first in the group's order).
    """
    m, b = assess_group(g, rows).objective_binding(objective_only)
    return m, np.where(b < 0, NO_BINDING, b).astype(np.int16)


def binding_names(b) -> np.ndarray:
    """The constraint ids of binding indices ``b`` ("" for none counted), a whole array at once."""
    names = np.array(list(REGISTRY) + [""], dtype=object)
    return names[np.minimum(b, len(names) - 1)]


def binding_name(b: int) -> str:
    return str(binding_names(int(b)))


def segment_best(gp: np.ndarray, val: np.ndarray):
    """Per run of equal ``gp`` (``gp`` sorted): the group, the largest ``val`` and the position reaching it first."""
    if not len(gp):
        return np.zeros(0, np.int64), np.zeros(0), np.zeros(0, np.int64)
    start = np.flatnonzero(np.r_[True, gp[1:] != gp[:-1]])
    best = np.maximum.reduceat(val, start)
    seg = np.repeat(np.arange(len(start)), np.diff(np.r_[start, len(gp)]))
    hit = np.where(val == best[seg], np.arange(len(gp)), len(gp))
    return gp[start], best, np.minimum.reduceat(hit, start)


class Pairs:
    """Evaluated (group, option) pairs of one subsystem: the feasible ones, and per group the nearest option."""

    def __init__(self, n_groups: int):
        self.g, self.o, self.m, self.b = [], [], [], []
        self.best = np.full(n_groups, -np.inf)                  # per group: largest smallest margin (all constraints)
        self.best_b = np.full(n_groups, NO_BINDING, np.int16)  # and its most violated constraint
        self.evaluated = np.zeros(n_groups, bool)

    def add(self, gp: np.ndarray, op: np.ndarray, grp: evaluate.Group, row=None) -> None:
        """Record the pairs ``(gp[i], op[i])`` evaluated as the rows of ``grp`` (``gp`` sorted); ``row``: the row of
        ``grp`` of each pair, where pairs the group reads alike share one (default: row ``i``)."""
        a = grp.assessment()   # one judgement of the block: its verdicts and smallest margins
        at = (lambda x: x) if row is None else (lambda x: x[row])  # noqa: E731
        ok = at(a.ok)
        sel = np.flatnonzero(ok)
        m, b = margins_and_binding(grp, True, sel if row is None else row[sel])
        self.g.append(gp[sel])
        self.o.append(op[sel])
        self.m.append(m)
        self.b.append(b)
        rank = grp.rank()  # nearest designs: ranked by the search model (fidelity screening: the screening one)
        ma = nearest_rank(ok, at(a.margin_min),
                          at(a.margin_min if rank is grp else rank.min_margin(objective_only=False)))
        gg, mm, first = segment_best(gp, ma)
        upd = mm > self.best[gg]
        if upd.any():
            self.best[gg[upd]] = mm[upd]
            self.best_b[gg[upd]] = margins_and_binding(rank, False, (first if row is None else row[first])[upd])[1]
        self.evaluated[gp] = True

    def by_group(self, n_groups: int):
        """``(ptr, options, margins, bindings)``: the feasible options of each group (CSR, options ascending)."""
        cat = (lambda xs, dt: np.concatenate(xs).astype(dt) if xs else np.zeros(0, dt))  # noqa: E731
        g, o, m, b = cat(self.g, np.int64), cat(self.o, np.int64), cat(self.m, float), cat(self.b, np.int16)
        if len(g) > 1 and not ((g[1:] > g[:-1]) | ((g[1:] == g[:-1]) & (o[1:] >= o[:-1]))).all():
            order = np.lexsort((o, g))   # else already in order (the blocks' pairs come group by group): no gathers
            g, o, m, b = g[order], o[order], m[order], b[order]
        ptr = np.searchsorted(g, np.arange(n_groups + 1))
        return ptr, o, m, b


def blocks(n: int, size: int = BLOCK_PAIRS):
    for lo in range(0, n, size):
        yield np.arange(lo, min(lo + size, n))
