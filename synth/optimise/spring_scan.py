"""The main spring's scans of a batch (:class:`synth.optimise.batch.Batch`) on the compiled kernels
(:mod:`synth.kernels.main_spring`) or their numpy twins: the springs of each application's mean-diameter range in its
own score order, the first feasible spring per distinct key within a score cut, the largest smallest margin per key,
and the near figures of the springs a nearest design may take."""

from __future__ import annotations

import numpy as np

from synth.design import evaluate
from synth.design.space import pinned_diameter, spring_window
from synth.kernels import main_spring
from synth.optimise.objectives import additive_goals, weighted_sum as wsum, weighted_sum_around
from synth.optimise.product import option_scores
from synth.optimise.scan_arrays import unique_rows

__all__ = ["SpringScan"]


class SpringScan:
    """The main-spring scans of a :class:`~synth.optimise.batch.Batch` ``b`` (its engines, applications, cores and
    memo); ``range_lists`` and ``opts`` are computed on first use."""

    def __init__(self, b):
        self.b = b
        self.range_lists = None
        self.opts = None

    def ranges(self):
        """Per application, the mean-diameter range of the springs searched (the enumeration's, over every core)
        as a group code, and the groups' option lists (index order)."""
        if self.range_lists is None:
            sp = self.b.sp
            mbd = sp.tables["spring"]["main_spring_mean_body_diameter_mm"]
            n = len(self.b)
            lo, hi = np.full(n, np.nan), np.full(n, np.nan)
            has = np.diff(self.b.ptr) > 0
            inner = self.b.cg.values["spring_housing_inner_diameter_mm"]
            outer = self.b.cg.values["spring_housing_outer_diameter_mm"]
            if has.any():
                st = self.b.ptr[:-1][has]
                lo[has], hi[has] = spring_window(np.minimum.reduceat(inner, st), np.maximum.reduceat(outer, st))
            first, inv = unique_rows(lo, hi)
            lists = [np.flatnonzero((mbd >= lo[i]) & (mbd <= hi[i]) | pinned_diameter(sp)) for i in first]
            self.range_lists = (inv, lists)
        return self.range_lists

    def options(self):
        if self.opts is None:
            self.opts = main_spring.options_of_space(self.b.sp.tables["spring"])
        return self.opts

    def app_lists(self, weights):
        """The spring candidates of every application in its own score order (ties by index), shared: ``(lists,
        list_of_app, smallest score, positions, (the lists end to end, where each starts))``. The scores follow each application's stiffness (the cost is
        per unit compliance over it); the applications of one mean-diameter range share the range's order when
        their scores keep it (checked per application, every adjacent pair), else get their own stable sort."""
        key = ("spring", tuple(sorted(weights.items())))
        if key in self.b.memo:
            return self.b.memo[key]
        sp = self.b.sp
        inv, ranges = self.ranges()
        k = self.b.apps.spring_stiffness_nm_per_deg
        base = wsum(option_scores(sp, "spring", 1.0), weights)
        order_all = np.argsort(base, kind="stable")
        lists: list = []
        list_of = np.full(len(self.b), -1, dtype=np.int64)
        smin = np.full(len(self.b), np.inf)
        for g, lst in enumerate(ranges):
            apps_g = np.flatnonzero(inv == g)
            if not len(apps_g) or not len(lst):
                continue
            in_rng = np.zeros(sp.n("spring"), dtype=bool)
            in_rng[lst] = True
            cand = order_all[in_rng[order_all]]  # the range's options in the base order
            first, good = self.list_order(weights, k[apps_g], cand)
            lid = len(lists)
            lists.append(cand)
            for j, i in enumerate(apps_g):
                if good[j]:
                    list_of[i], smin[i] = lid, first[j]
                else:  # this stiffness reorders (rounding ties): its own stable sort
                    s_i = wsum(option_scores(sp, "spring", k[i], lst), weights)
                    o = np.argsort(s_i, kind="stable")
                    list_of[i] = len(lists)
                    lists.append(lst[o])
                    smin[i] = s_i[o][0]
        positions = [np.arange(len(x), dtype=float) for x in lists]
        flat = np.concatenate(lists) if lists else np.zeros(0, dtype=np.int64)
        start = np.concatenate([[0], np.cumsum([len(x) for x in lists])]).astype(np.int64)
        self.b.memo[key] = (lists, list_of, smin, positions, (flat, start))
        return self.b.memo[key]

    def list_order(self, weights, stiffness, cand):
        """``(first, good)`` of the springs ``cand`` (a list in the base order) for applications of ``stiffness``:
        ``good[a]`` whether the list keeps its order for that application (the additive score of
        :func:`~synth.optimise.objectives.weighted_sum` grows along it, or ties with a growing index: every
        adjacent pair), ``first[a]`` the score of its first spring. The compiled engine computes both in one pass
        with nothing stored per pair (the score's per-option terms once,
        :func:`~synth.kernels._main_spring_scans_jit.list_order`), the same doubles as numpy's scores."""
        sp = self.b.sp
        per_k = [g.name for g in additive_goals() if g.per_stiffness]
        if self.b.score_engine == "numba" and per_k[0] in weights:
            n = len(cand)
            before, w, after = weighted_sum_around(option_scores(sp, "spring", 1.0, cand), weights, per_k[0])
            pre = np.ascontiguousarray(np.broadcast_to(np.asarray(before, dtype=float), (n,)))
            post = np.array([np.broadcast_to(np.asarray(t, dtype=float), (n,)) for t in after],
                            dtype=float).reshape(len(after), n)
            unit = np.ascontiguousarray(sp.tables["spring"]["cost_eur_times_stiffness"][cand], dtype=float)
            first, good = np.full(len(stiffness), np.nan), np.empty(len(stiffness), dtype=bool)
            main_spring.load_scans().list_order(pre, unit, float(w), post,
                                                np.ascontiguousarray(stiffness, dtype=float),
                                                np.ascontiguousarray(cand, dtype=np.int64), first, good)
            return first, good
        sc = np.broadcast_to(wsum(option_scores(sp, "spring", stiffness[:, None], cand[None, :]), weights),
                             (len(stiffness), len(cand)))
        d = np.diff(sc, axis=1)
        return sc[:, 0].copy(), ((d > 0) | ((d == 0) & (np.diff(cand) > 0)[None, :])).all(axis=1)

    def keys(self, rows):
        """``(keys dict, inverse)``: the distinct spring keys of core rows (application and what the spring sees)."""
        kd = evaluate.spring_keys(self.b.cg, rows)
        first, inv = unique_rows(kd["app"], *(kd[k] for k in kd if k != "app"))
        return {k: v[first] for k, v in kd.items()}, inv

    def first_feasible(self, keys, limit, weights):
        """Per key: ``(score, option)`` of the first feasible spring of its application's score-ordered list with
        a score at most ``limit`` (inf, -1: none). The score cut is a position cut in the list (the scores
        grow along it): the kernel's score is the position."""
        lists, list_of, _, positions, _ = self.app_lists(weights)
        apps_k = keys["app"]
        grp = list_of[apps_k]
        last = self.last_within(weights, apps_k, limit)
        kk = main_spring.keys_of_rows(self.b.apps, keys)
        r = main_spring.first_feasible(kk, self.options(), lists, key_group=grp, score=positions, score_limit=last,
                                       engine=self.b.engine, settings=self.b.settings)
        self.b.evaluations += int(r.visited.sum())
        out = np.full(len(apps_k), np.inf)
        hit = np.flatnonzero(r.index >= 0)
        out[hit] = self.scores(weights, apps_k[hit], r.index[hit])  # the chosen option's score
        return out, np.where(r.index >= 0, r.index, -1)

    def last_within(self, weights, apps_i, limit) -> np.ndarray:
        """Per application of ``apps_i``: the last position of its spring list whose score is at most ``limit``
        (``searchsorted(scores, limit, "right") - 1`` of the list's scores, which never decrease along it; -1 when
        none, inf where the limit is not finite), bisected for all at once: log2(list) scores each."""
        _, list_of, _, _, (flat, start) = self.app_lists(weights)
        grp = list_of[apps_i]
        last = np.full(len(apps_i), np.inf)
        fin = np.flatnonzero(np.isfinite(limit))
        lo, hi = np.zeros(len(fin), dtype=np.int64), start[grp[fin] + 1] - start[grp[fin]]
        act = np.flatnonzero(lo < hi)
        while len(act):
            j, mid = fin[act], (lo[act] + hi[act]) // 2
            right = self.scores(weights, apps_i[j], flat[start[grp[j]] + mid]) <= limit[j]
            lo[act[right]] = mid[right] + 1
            hi[act[~right]] = mid[~right]
            act = act[lo[act] < hi[act]]
        last[fin] = lo - 1.0
        return last

    def scores(self, weights, apps_i, options) -> np.ndarray:
        """The additive scores of springs ``options`` for applications ``apps_i`` (pairwise): the doubles of the
        lists' scores (the cost per unit compliance over each application's stiffness, summed as
        :func:`~synth.optimise.objectives.weighted_sum`)."""
        return np.asarray(wsum(option_scores(self.b.sp, "spring", self.b.apps.spring_stiffness_nm_per_deg[apps_i],
                                             options), weights), dtype=float)

    def best_margin(self, keys, cap=None):
        """Per key: ``(value, option)`` of the largest smallest margin over its application's range (index
        order, first of the ties; option 0 when every value is -inf); ``cap``: exact below it."""
        inv, lists = self.ranges()
        grp = inv[keys["app"]]
        kk = main_spring.keys_of_rows(self.b.apps, keys)
        r = main_spring.max_min_margin(kk, self.options(), lists, key_group=grp, cap=cap, engine=self.b.engine,
                                       settings=self.b.settings)
        self.b.evaluations += int(r.visited.sum())
        v = np.asarray(r.value, dtype=float)
        return v, np.where((r.index >= 0) & (v > -np.inf), r.index, 0)

    def near(self, i: int, keys, group: int, floor: float):
        """The near figures of application ``i``'s spring ``keys`` over the springs of its range ``lst`` (range
        ``group`` of :meth:`_ranges`) that a
        nearest design may take: ``(figures per key x column (flattened), columns (spring rows, increasing),
        available per column)``. The enumeration's table has every spring as a column, available on ``lst``;
        here the columns are the springs whose smallest margin reaches ``floor`` for some key (every spring of
        ``lst`` when a key has none), and spring 0 (unavailable unless it is one of them: the option a row
        without any design gets).

        Why the springs left out change no choice of :func:`synth.design.combine.nearest_choice` (the whole key
        and the options it picks), given that each key has a spring reaching ``floor``: a spring below ``floor``
        (for every key) has the near figures ``(smallest, -inf, inf)`` in the table (its second and failing
        count are not computed). It is never a key's best smallest (a reaching spring is above it); it is
        admissible only for a core whose smallest ``m1`` is below ``floor``, and there its second (-inf) never
        raises the best second (a reaching spring's is at least ``floor``) and its failing count (inf) never is
        the fewest (a reaching spring's is finite), and a pick among infinite counts is discarded (option 0
        where no count is finite: column 0). The same holds of a pair below ``floor`` within a kept column, so
        such a pair's smallest margin need only be known to be below ``floor``
        (:func:`synth.kernels.main_spring.near_above`: its yield margin or its option-only bound)."""
        nk = len(keys["app"])
        lst = np.asarray(self.ranges()[1][group], dtype=np.int64)
        kk = main_spring.keys_of_rows(self.b.apps, keys) if len(lst) else None
        memo = ("near springs", group)  # the range's options, shared by its applications
        if memo not in self.b.memo:
            self.b.memo[memo] = self.options().take(lst)
        opts = self.b.memo[memo]
        if len(lst):
            low, second, failing = main_spring.near_above(kk, opts, floor, engine=self.b.engine,
                                                          settings=self.b.settings)
        else:
            low = second = failing = np.zeros((nk, 0))
        self.b.evaluations += low.size
        reach = low >= floor
        if reach.any(axis=1).all():
            keep = reach.any(axis=0)
        else:  # a key without a reaching spring: every spring, each with its smallest margin (as the table)
            keep = np.ones(len(lst), dtype=bool)
            if len(lst):
                low = main_spring.near_above(kk, opts, -np.inf, engine=self.b.engine, settings=self.b.settings)[0]
        kept = lst[keep]
        cols = kept if len(kept) and kept[0] == 0 else np.r_[0, kept].astype(np.int64)
        at = np.searchsorted(cols, kept)
        fig = [np.full((nk, len(cols)), -np.inf), np.full((nk, len(cols)), -np.inf), np.full((nk, len(cols)), np.inf)]
        if len(kept):
            fig[0][:, at] = low[:, keep]
            # a spring whose smallest margin is below the application's nearest design's cannot be in it
            # (synth.design.combine.nearest_choice: not admissible): its other figures are not needed
            r = reach[:, keep]
            fig[1][:, at] = np.where(r, second[:, keep], -np.inf)
            fig[2][:, at] = np.where(r, failing[:, keep], np.inf)
        avail = np.zeros(len(cols), dtype=bool)
        avail[at] = True
        return [x.reshape(-1) for x in fig], cols, avail
