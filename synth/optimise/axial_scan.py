"""The axial group's scans of a batch (:class:`synth.optimise.batch.Batch`): its options in blocks in score order
(the first feasible within a score cut) or in index order (the largest smallest margin), once per distinct value of
what the group reads of the core; at fidelity ``screening`` searched with the screening model and the passing pairs
judged by the full model; the search model's smallest margins kept between the scans."""

from __future__ import annotations

import numpy as np

from synth import catalog
from synth.design import evaluate
from synth.optimise.objectives import weighted_sum as wsum
from synth.optimise.product import option_scores
from synth.optimise.scan_arrays import first_true, unique_rows

__all__ = ["AxialScan"]


class AxialScan:
    """The axial scans of a :class:`~synth.optimise.batch.Batch` ``b``. ``slot``, ``mm``, ``known``: the search
    model's smallest margins kept (one row per distinct application and core value read); ``undecided``: the
    applications where the screening model may have rejected what the full model passes (:meth:`mark_undecided`)."""

    def __init__(self, b):
        self.b = b
        n_ax = b.sp.n("axial")
        self.undecided = np.zeros(len(b), dtype=bool)
        self.slot: dict = {}
        self.mm = np.zeros((0, n_ax))
        self.known = np.zeros((0, n_ax), dtype=bool)

    def rows(self, rows):
        first, inv = unique_rows(self.b.A[rows], *(self.b.cg.values[k][rows]
                                                  for k in evaluate.core_values("axial", self.b.cg.values)))
        return rows[first], inv

    def slots(self, rep) -> np.ndarray:
        """Per representative core row (:meth:`_axial_rows`), its row in the kept axial margins: one per distinct
        application and value of what the axial group reads of the core, whichever call met it first."""
        vals = np.stack([self.b.A[rep], *(self.b.cg.values[k][rep]
                                        for k in evaluate.core_values("axial", self.b.cg.values))], axis=1)
        vals = np.where(np.isnan(vals), np.finfo(float).max, vals) + 0.0  # as unique_rows: NaN equal, -0.0 = 0.0
        slot = self.slot
        out = np.array([slot.setdefault(k, len(slot)) for k in
                        np.ascontiguousarray(vals).view(np.dtype((np.void, 8 * vals.shape[1]))).ravel().tolist()],
                       dtype=np.int64)
        if len(slot) > len(self.mm):  # grow (doubling)
            m = max(len(slot), 2 * len(self.mm))
            self.mm = np.concatenate([self.mm, np.zeros((m - len(self.mm), self.mm.shape[1]))])
            self.known = np.concatenate([self.known, np.zeros((m - len(self.known),
                                                                       self.known.shape[1]), dtype=bool)])
        return out

    def keep(self, slots, cols, g: evaluate.Group) -> None:
        """Keep the smallest margins of an axial group of the search model (slots x options, pairwise)."""
        if self.b.screened is None:
            self.mm[slots, cols] = g.min_margin(objective_only=False)
            self.known[slots, cols] = True

    def group(self, rr, oo, settings: evaluate.Settings | None = None):
        """The axial group of core rows ``rr`` and options ``oo`` (at ``settings``, default the search's; in the
        full model's search of :meth:`optimum`, :func:`~synth.design.evaluate.axial_full`)."""
        with np.errstate(over="ignore", divide="ignore", invalid="ignore"):
            if settings is None and self.b.screened is not None:
                g = evaluate.axial_full(self.b.apps, self.b.cg, rr, self.b.sp.rows_read("axial", oo), self.b.screened,
                                        engine=self.b.axial_engine)
            else:
                g = evaluate.axial(self.b.apps, self.b.cg, rr, self.b.sp.rows_read("axial", oo), settings or self.b.settings,
                                   engine=self.b.axial_engine)
        self.b.evaluations += len(rr)
        return g

    def passes_before_physics(self, rr, oo) -> np.ndarray:
        """Per pair of core rows ``rr`` and axial options ``oo``: whether it passes the axial checks that read
        nothing of the physics (:func:`~synth.design.evaluate.axial_before_physics`: Table 4's spacer, the belt
        plane, the cone spring's diameters; most pairs of a scan fail one). A pair that fails one fails at any
        fidelity, and its smallest margin is at most that check's: a search need not size its cone spring."""
        with np.errstate(over="ignore", divide="ignore", invalid="ignore"):
            return evaluate.axial_before_physics(self.b.apps, self.b.cg, rr, self.b.sp.rows_read("axial", oo),
                                                 self.b.settings).ok()

    def mark_undecided(self, rr, g: evaluate.Group, ok) -> None:
        """Mark the applications of rows ``rr`` (axial group ``g``, its verdicts ``ok`` after the judge) where the
        screening model may have rejected what the full model passes: a row that passes every constraint the
        fidelity does not change (:func:`~synth.design.evaluate.fidelity_free_ok`) and is not kept."""
        if self.b.settings.judge is not self.b.settings:
            self.undecided[self.b.A[np.asarray(rr)[~np.asarray(ok) & evaluate.fidelity_free_ok(g)]]] = True

    def judged(self, ok: np.ndarray, rr, cols) -> np.ndarray:
        """``ok`` (rows ``rr`` x axial options ``cols``: the search model's verdicts) judged by the full model
        (:attr:`~synth.design.evaluate.Settings.judge`, fidelity ``screening``): every passing pair evaluated again,
        in one call (a full evaluation costs about 10 ms a call and 5 us a row: one call per block of the scan),
        and kept where the full model passes it too. The screening model orders and prunes; the full model
        decides."""
        judge = self.b.settings.judge
        if judge is self.b.settings or not ok.any():
            return ok
        ri, ci = np.nonzero(ok)
        out = np.zeros_like(ok)
        out[ri, ci] = self.group(np.asarray(rr)[ri], np.asarray(cols)[ci], judge).ok()
        return out

    def blocks(self):
        return int(catalog.constant("bulk_axial_first_block")), max(int(catalog.constant("bulk_axial_block_growth")), 1)

    def first_feasible(self, rows, limit, weights):
        """Per core row: ``(score, option)`` of the first feasible axial option in score order with a score at
        most ``limit`` (the none option for a core without a damper pad)."""
        sp = self.b.sp
        t = sp.tables["axial"]
        score = wsum(option_scores(sp, "axial"), weights)
        rep, inv = self.rows(rows)
        slots = self.slots(rep) if self.b.screened is None else None
        lim = np.full(len(rep), -np.inf)
        np.maximum.at(lim, inv, limit)
        out_v, out_k = np.full(len(rep), np.inf), np.full(len(rep), -1, dtype=np.int64)
        pad = self.b.pad[rep]
        none = np.flatnonzero(~t["axial_group_present"])
        real = np.flatnonzero(t["axial_group_present"])
        order = real[np.argsort(score[real], kind="stable")]
        sel = np.flatnonzero(~pad)
        if len(sel):  # one option: none (it may still fail, e.g. the belt plane)
            g = self.group(rep[sel], np.full(len(sel), none[0]))
            okn = self.judged((g.ok() & (score[none[0]] <= lim[sel]))[:, None], rep[sel], none[:1])[:, 0]
            self.mark_undecided(rep[sel], g, okn)
            out_v[sel] = np.where(okn, score[none[0]], np.inf)
            out_k[sel] = np.where(okn, none[0], -1)
        active = np.flatnonzero(pad)
        pos, (block, growth) = 0, self.blocks()
        while len(active) and pos < len(order):
            blk = order[pos:pos + block]
            within = score[blk][None, :] <= lim[active][:, None]
            active = active[within[:, 0]]  # scores grow along the order: a row past its limit is done
            within = within[within[:, 0]]
            if not len(active):
                break
            ai, bi = np.nonzero(within)
            pre = self.passes_before_physics(rep[active[ai]], blk[bi])  # the others fail: no physics
            ai, bi = ai[pre], bi[pre]
            ok = np.zeros(within.shape, dtype=bool)
            if len(ai):
                g = self.group(rep[active[ai]], blk[bi])
                if slots is not None:
                    self.keep(slots[active[ai]], blk[bi], g)
                ok[ai, bi] = g.ok()
                ok = self.judged(ok, rep[active], blk)
                self.mark_undecided(rep[active[ai]], g, ok[ai, bi])
            j = first_true(ok)
            hit = j >= 0
            out_k[active[hit]] = blk[j[hit]]
            out_v[active[hit]] = score[blk[j[hit]]]
            keep = ~hit & within[:, -1]
            active = active[keep]
            pos += len(blk)
            block *= growth
        return out_v[inv], out_k[inv]

    def best_margin(self, rows, cap=None):
        """Per core row: ``(value, option)`` of the largest smallest margin over its axial options (the none
        option without a pad); ``cap``: the search stops once a row reaches it (exact below it); without a cap
        the enumeration's argmax (index order, first of the ties)."""
        sp = self.b.sp
        t = sp.tables["axial"]
        rep, inv = self.rows(rows)
        cp = np.full(len(rep), np.inf)
        if cap is not None:
            cp = np.full(len(rep), -np.inf)
            np.maximum.at(cp, inv, cap)
        pad = self.b.pad[rep]
        none = np.flatnonzero(~t["axial_group_present"])
        real = np.flatnonzero(t["axial_group_present"])
        out_v, out_k = np.full(len(rep), -np.inf), np.zeros(len(rep), dtype=np.int64)
        sel = np.flatnonzero(~pad)
        if len(sel):
            g = self.group(rep[sel], np.full(len(sel), none[0]))
            v = g.min_margin(objective_only=False)
            out_v[sel], out_k[sel] = v, np.where(v > -np.inf, none[0], 0)
        active = np.flatnonzero(pad)
        best_pos = np.full(len(rep), len(real), dtype=np.int64)
        pos, (block, growth) = 0, self.blocks()
        slots = self.slots(rep)
        while len(active) and pos < len(real):
            blk = real[pos:pos + block]
            # the pairs the optimum's scan (or an earlier call) evaluated are read back; the others evaluated, kept
            sl = slots[active]
            known = self.known[sl[:, None], blk[None, :]]
            m = self.mm[sl[:, None], blk[None, :]]
            ai, bi = np.nonzero(~known)
            if len(ai):
                g = self.group(rep[active[ai]], blk[bi])
                m[ai, bi] = g.min_margin(objective_only=False)
                self.keep(sl[ai], blk[bi], g)
            j = np.argmax(m, axis=1)
            v = m[np.arange(len(active)), j]
            better = v > out_v[active]  # strictly: an earlier option keeps a tie (argmax's first index)
            out_v[active[better]] = v[better]
            best_pos[active[better]] = pos + j[better]
            active = active[~(out_v[active] >= cp[active])]
            pos += len(blk)
            block *= growth
        has = pad & (best_pos < len(real)) & (out_v > -np.inf)
        out_k[pad] = np.where(has[pad], real[np.minimum(best_pos[pad], len(real) - 1)], 0)
        return out_v[inv], out_k[inv]
