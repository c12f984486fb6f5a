"""The scans of the part families judged pair by pair (the bushing; any family whose declaration has a ``group``:
:class:`synth.design.subsystems.Subsystem`): per core row the first feasible option in score order, or the largest
smallest margin, one evaluator call per distinct core key (:class:`synth.optimise.batch.Batch`)."""

from __future__ import annotations

import numpy as np

from synth.design.subsystems import family
from synth.optimise.objectives import weighted_sum as wsum
from synth.optimise.product import option_scores
from synth.optimise.scan_arrays import argmax_value, first_true, unique_rows

__all__ = ["PairedScan"]


class PairedScan:
    """The pair-by-pair scans of a :class:`~synth.optimise.batch.Batch` ``b`` (its applications, space, cores,
    settings; it counts the evaluations on ``b``)."""

    def __init__(self, b):
        self.b = b

    def bushing(self, rows, weights=None):
        """Per core row: with ``weights``, ``(score, option)`` of the first feasible bushing in score order (inf,
        -1 when none); without, ``(value, option)`` of the largest smallest margin (the enumeration's argmax)."""
        return self.scan(family("bushing"), rows, weights)

    def scan(self, fam, rows, weights=None):
        """:meth:`_bushing` for any family judged pair by pair (its declaration's ``group``): its group evaluated
        once per distinct (application, matched core values, what it reads of the core) over the options the
        declaration makes available (:mod:`synth.design.subsystems`)."""
        sp, cg = self.b.sp, self.b.cg
        n_r = len(rows)
        out_v = np.full(n_r, np.inf if weights is not None else -np.inf)
        out_k = np.full(n_r, -1 if weights is not None else 0, dtype=np.int64)
        if not n_r:
            return out_v, out_k
        match = [cg.values[cv][rows] for cv, _ in fam.match]
        first, inv = unique_rows(self.b.A[rows], *match, *(cg.values[k][rows] for k in fam.core_reads(cg.values)))
        rep = rows[first]
        score = wsum(option_scores(sp, fam.name), weights) if weights is not None else None
        res_v = np.empty(len(rep))
        res_k = np.empty(len(rep), dtype=np.int64)
        if match:
            mfirst, minv = unique_rows(*(m[first] for m in match))
        else:
            mfirst, minv = np.zeros(min(len(rep), 1), dtype=np.int64), np.zeros(len(rep), dtype=np.int64)
        for u in range(len(mfirst)):
            sel = np.flatnonzero(minv == u)
            opts = np.flatnonzero(fam.available(sp, cg.values, rep[sel[:1]])[0])  # index order
            rr, oo = np.repeat(rep[sel], len(opts)), np.tile(opts, len(sel))
            with np.errstate(over="ignore", divide="ignore", invalid="ignore"):
                g = fam.group(self.b.apps, cg, rr, sp.rows(fam.name, oo), self.b.settings)
            self.b.evaluations += len(rr)
            if weights is not None and not len(opts):  # none available: no feasible option
                res_k[sel], res_v[sel] = -1, np.inf
            elif weights is not None:
                order = np.argsort(score[opts], kind="stable")
                ok = g.ok().reshape(len(sel), len(opts))[:, order]
                j = first_true(ok)
                res_k[sel] = np.where(j >= 0, opts[order][j], -1)
                res_v[sel] = np.where(j >= 0, score[opts[order][j]], np.inf)
            else:
                v, k = argmax_value(g.min_margin(objective_only=False).reshape(len(sel), len(opts)), opts)
                res_v[sel], res_k[sel] = v, k
        return res_v[inv], res_k[inv]
