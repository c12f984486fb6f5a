"""The bolt's scans of a batch (:class:`synth.optimise.batch.Batch`): the step-10 checks once per application and
bolt as the group reads it (:func:`synth.design.bolt_group.bolt_codes`), the checks that read the core (the pivot wall
of step 2) per core and distinct bolt diameter; per core row the first feasible bolt in score order, or the largest
smallest margin and its bolt."""

from __future__ import annotations

import numpy as np

from synth.design import evaluate
from synth.design.assessment import passes
from synth.design.bolt_group import bolt_codes, fixation_codes
from synth.design.combine import near_figures
from synth.design.constraints import by_group, physics_inputs
from synth.optimise.objectives import weighted_sum as wsum
from synth.optimise.product import option_scores
from synth.optimise.scan_arrays import argmax_value, first_true, unique_rows

__all__ = ["BoltScan", "bolt_ids"]


def bolt_ids(core_values: dict) -> tuple[tuple, tuple]:
    """The bolt group's non-advisory checks as the registry holds them now (a check added with ``register``
    included; read per batch, never frozen at import): ``(per application and bolt, per core and bolt)``, the
    second those that read the core (``core_values``: a core group's values;
    :func:`~synth.design.evaluate.bolt_core_checks`: the pivot wall)."""
    core = {c.id for c in evaluate.bolt_core_checks(core_values)}
    ids = [c.id for c in by_group("bolt") if not c.advisory]
    return tuple(i for i in ids if i not in core), tuple(i for i in ids if i in core)


#: the additive score of many designs (:func:`synth.optimise.objectives.weighted_sum`)


class BoltScan:
    """The bolt scans of a :class:`~synth.optimise.batch.Batch` ``b``; what it evaluates is kept for the batch:
    ``fix`` (per application x bolt: the step-10 checks pass, their smallest margin, done; evaluated once per
    application and bolt as the group reads it, :meth:`bolt_keys`), ``fix_near`` (their
    second smallest margin and failing count), ``wall_d`` (the distinct bolt columns the core checks read)."""

    def __init__(self, b):
        self.b = b
        self.ids, self.core_ids = bolt_ids(b.cg.values)
        self.fix = None
        self.fix_near = None
        self.wall_d = None

    def app(self, which, bolts):
        """Per application x bolt: every step-10 check passes (``ok``), and their smallest margin (``min``),
        the pivot wall apart; evaluated on demand for the applications ``which`` x ``bolts`` not done yet (one
        group call, each application with each distinct bolt as the group reads it) and kept for the batch."""
        sp, n = self.b.sp, len(self.b)
        nb = sp.n("bolt")
        if self.fix is None:
            self.fix = (np.zeros((n, nb), dtype=bool), np.full((n, nb), -np.inf), np.zeros((n, nb), dtype=bool))
            self.fix_near = (np.full((n, nb), -np.inf), np.zeros((n, nb)))
        ok, mn, done = self.fix
        which = np.asarray(which, dtype=np.int64)
        which = which[np.diff(self.b.ptr)[which] > 0]
        bolts = np.asarray(bolts, dtype=np.int64)
        ai, bi = np.nonzero(~done[np.ix_(which, bolts)])
        if len(ai):
            a, b = which[ai], bolts[bi]
            code, rep = self.bolt_keys()
            fcode = self.fixation_codes()
            nk = len(rep)
            # the group once per (application, distinct bolt as the group reads it), its figures gathered per pair
            up, inv = np.unique(a * nk + code[b], return_inverse=True)
            inv = np.asarray(inv).reshape(-1)
            with np.errstate(over="ignore", divide="ignore", invalid="ignore"):
                bolt = rep[up % nk]
                g = evaluate.bolt(self.b.apps, self.b.cg, self.b.ptr[up // nk], sp.rows_read("bolt", bolt),
                                  self.b.settings, codes=fcode[bolt])
            self.b.evaluations += len(up)
            m = np.full(len(up), np.inf)
            for cid in self.ids:
                m = np.minimum(m, g.margins[cid])
            ok[a, b], mn[a, b], done[a, b] = passes(m)[inv], m[inv], True
            if self.ids:  # the second smallest and the failing count, for the nearest design's key
                _, second, failing = near_figures(np.stack([g.margins[cid] for cid in self.ids], axis=1))
                self.fix_near[0][a, b], self.fix_near[1][a, b] = second[inv], failing[inv]
            else:
                self.fix_near[0][a, b] = np.inf
        return ok, mn

    def bolt_keys(self):
        """``(code per bolt, a representative bolt per code)``: bolts equal in every column group ``bolt`` reads
        (:func:`synth.design.bolt_group.bolt_codes`: the fixation's -- format, property class, head form, washer,
        and the tightening method under the VDI 2230 method -- and the diameter, proof stress and bore the checks
        read) share a code, so the same figures for any application and core."""
        if "bolt_keys" not in self.b.memo:
            self.b.memo["bolt_keys"] = bolt_codes(self.b.sp.tables["bolt"], self.b.settings)
        return self.b.memo["bolt_keys"]

    def fixation_codes(self):
        """Each bolt's :func:`synth.design.bolt_group.fixation_codes` (once per batch: the fixation's columns
        factorised over the table, not over every block of rows)."""
        if "fixation_codes" not in self.b.memo:
            self.b.memo["fixation_codes"] = fixation_codes(self.b.sp.tables["bolt"], self.b.settings)[0]
        return self.b.memo["fixation_codes"]

    def wall(self, rows):
        """``(margins (len(rows), n_codes), code per bolt)``: the smallest margin of the bolt checks that read the
        core (the pivot wall of step 2) per core row and distinct value of the bolt columns they read (the
        diameter), and each bolt's code."""
        sp = self.b.sp
        if self.wall_d is None:
            t = sp.tables["bolt"]
            cols = ["bolt_d_mm", *sorted({k for c in by_group("bolt") if c.id in self.core_ids
                                          for k in physics_inputs(c) if k in t and k != "bolt_d_mm"})]
            first, code = unique_rows(*(t[k] for k in cols))
            self.wall_d = ({k: np.asarray(t[k])[first] for k in cols}, code)
        o, code = self.wall_d
        nd, nr = len(o["bolt_d_mm"]), len(rows)
        m = np.full((nr, nd), np.inf)
        if self.core_ids and nr and nd:
            with np.errstate(over="ignore", divide="ignore", invalid="ignore"):
                g = evaluate.bolt_core(self.b.apps, np.broadcast_to(self.b.A[rows][:, None], (nr, nd)),
                                       {k: self.b.cg.values[k][rows][:, None]
                                        for k in evaluate.core_values("bolt", self.b.cg.values)},
                                       {k: v[None, :] for k, v in o.items()}, self.b.settings)
            for cid in self.core_ids:
                m = np.minimum(m, g.margins[cid])
        return m, code

    def scan(self, rows, weights=None):
        """Per core row, as :meth:`_bushing` for the bolt: the first feasible bolt in score order (with
        ``weights``), or the largest smallest margin (its value; :meth:`_bolt_pick` gives the option).

        A bolt is feasible for a core when its step-10 checks pass for the application and the pivot wall
        passes for the core and the bolt's diameter: bolts are scanned in score order in blocks (the step-10
        checks of a block evaluated for the applications still looking). The best margin is the largest, over
        the diameters, of the smaller of the diameter's best step-10 margin and its wall margin.
        """
        wall, code = self.wall(rows)
        a = self.b.A[rows]
        nb = self.b.sp.n("bolt")
        if weights is None:
            ua = np.unique(a)
            _, min_app = self.app(ua, np.arange(nb))
            best = np.full((len(self.b), wall.shape[1]), -np.inf)
            for dc in range(wall.shape[1]):
                if (code == dc).any():
                    best[ua, dc] = min_app[ua][:, code == dc].max(axis=1)
            return np.minimum(best[a], wall).max(axis=1), None
        key = ("bolt", tuple(sorted(weights.items())))
        if key not in self.b.memo:
            score = wsum(option_scores(self.b.sp, "bolt"), weights)
            self.b.memo[key] = (score, np.argsort(score, kind="stable"))
        score, order = self.b.memo[key]
        k = np.full(len(rows), -1, dtype=np.int64)
        active = np.arange(len(rows))
        # a fixation call costs about as much for one application as for a hundred: a few applications take
        # every bolt at once, a chunk the cheap ones first (numerics: the same answer either way)
        pos, block = 0, nb if len(self.b) <= 16 else 8
        while len(active) and pos < nb:
            blk = order[pos:pos + block]
            ua = np.unique(a[active])
            ok_app, _ = self.app(ua, blk)
            # only the rows of an application with a bolt of the block that passes its step-10 checks can hit
            some = np.zeros(len(self.b), dtype=bool)
            some[ua] = ok_app[ua[:, None], blk[None, :]].any(axis=1)
            cand = np.flatnonzero(some[a[active]])
            rows_c = active[cand]
            feas = ok_app[a[rows_c][:, None], blk[None, :]] & passes(wall[rows_c[:, None], code[blk][None, :]])
            j = first_true(feas)
            hit = j >= 0
            k[rows_c[hit]] = blk[j[hit]]
            keep = np.ones(len(active), dtype=bool)
            keep[cand[hit]] = False
            active = active[keep]
            pos += len(blk)
            block *= 4
        return np.where(k >= 0, score[np.maximum(k, 0)], np.inf), k

    def pick(self, rows):
        """The enumeration's argmax bolt of core rows (first index of the largest smallest margin)."""
        wall, code = self.wall(rows)
        a = self.b.A[rows]
        _, min_app = self.app(np.unique(a), np.arange(self.b.sp.n("bolt")))
        vals = np.minimum(min_app[a], wall[:, code])
        return argmax_value(vals, np.arange(vals.shape[1]))[1]
