"""The margin tie-break of a batch's optimum (:meth:`synth.optimise.batch.Batch.optimum_margin_ties`): among the
designs whose score ties the best, the largest design margin, per subsystem the cheapest option reaching it, the
core of the smallest total, as the exact solver breaks them (:func:`synth.optimise.solvers.enumerate.solve_space`),
from the batch search's own state (:attr:`~synth.optimise.batch.Batch.last_search`)."""

from __future__ import annotations

import numpy as np

from synth.design import evaluate
from synth.design.combine import combine
from synth.design.space import SUBSYSTEMS
from synth.design.subsystems import family
from synth.kernels import main_spring
from synth.optimise.objectives import TIE, weighted_sum as wsum
from synth.optimise.product import option_scores
from synth.optimise.scan_arrays import segments, unique_rows

__all__ = ["margin_ties", "SLACK", "MARGIN_EPS"]

#: relative slack of the score cuts (a cut never removes a design within 1e-9 of the best: rounding is far below)
SLACK = 1e-9
#: the margin threshold's tolerance of the exact solver's lexicographic orders with the margin
#: (:data:`synth.optimise.solvers.enumerate._EPS`): an option passes the threshold ``tau`` when its margin is >= tau - 1e-9
MARGIN_EPS = 1e-9


def _n_units(unit) -> int:
    """The number of evaluation units of :func:`tie_units` (core rows, or spring keys)."""
    return len(unit["app"]) if isinstance(unit, dict) else len(unit)


def _restrict(cand, keep):
    """The candidates of :func:`tie_candidates` of the rows ``keep`` (a mask of its rows) only."""
    inv, unit, (ui, oo), sc = cand
    used = np.zeros(_n_units(unit), dtype=bool)
    used[inv[keep]] = True
    m = used[ui]
    return inv[keep], unit, (ui[m], oo[m]), sc[m]


def _tie_pick(found: list, R, a_of, cs, core_m, evaluated: dict) -> list:
    """``found`` with the design of the margin tie-break where the tied cores ``R`` (applications ``a_of``, core
    scores ``cs``, objective margins ``core_m``) and their tied options (``evaluated``: per subsystem, what
    :func:`tie_evaluate` returns) give one, as :func:`synth.optimise.solvers.enumerate.solve_space` takes
    it: the threshold ``tau`` is the largest design margin of a tied design (0 when it is within 1e-9 below 0,
    none when below), per core and subsystem the first option in score order whose margin reaches ``tau - 1e-9``,
    and the core of the smallest total (summed as the solver sums it), the first row of equal totals."""
    n = len(found)
    design_m = np.asarray(core_m, dtype=float).copy()
    unit_app = {}
    for s, (inv, ui, oo, sc, m, nu) in evaluated.items():
        best = np.full(nu, -np.inf)
        np.maximum.at(best, ui, m)
        design_m = combine(design_m, [best[inv]])
        unit_app[s] = np.zeros(nu, dtype=np.int64)
        unit_app[s][inv] = a_of
    m_star = np.full(n, -np.inf)
    np.maximum.at(m_star, a_of, design_m)
    tau = np.where(m_star >= 0, m_star, np.where(m_star >= -MARGIN_EPS, 0.0, -np.inf))
    thr = tau - MARGIN_EPS
    total = np.where(core_m >= thr[a_of], cs, np.inf)
    picks = {}
    for s in SUBSYSTEMS:
        inv, ui, oo, sc, m, nu = evaluated[s]
        reach = np.flatnonzero(m >= thr[unit_app[s][ui]])  # in score order within each unit
        u, at = np.unique(ui[reach], return_index=True)
        ch_o, ch_sc = np.full(nu, -1, dtype=np.int64), np.full(nu, np.inf)
        ch_o[u], ch_sc[u] = oo[reach[at]], sc[reach[at]]
        total = total + ch_sc[inv]
        picks[s] = ch_o[inv]
    o = np.lexsort((R, total, a_of))
    o = o[np.isfinite(total[o])]
    out = list(found)
    for i, j in zip(*np.unique(a_of[o], return_index=True)):
        j = o[j]
        out[int(i)] = (int(R[j]), {s: int(picks[s][j]) for s in SUBSYSTEMS})
    return out


def margin_ties(batch, weights: dict, found: list) -> list:
    """``found`` (:meth:`optimum`'s) with its ties broken by the margin (:meth:`optimum_margin_ties`), from the
    first search's bounds and scores (:attr:`_last`): only the cores it did not finish are searched again,
    and only the applications with more than one tied design evaluate their tied options."""
    last = batch.last_search
    live = np.array([f is not None and i not in batch.redone for i, f in enumerate(found)], dtype=bool)
    if last is None or not live.any():
        return found
    inc = last["inc"]  # the best score, summed as the exact solver sums it
    tol = TIE * np.maximum(1.0, np.abs(np.where(np.isfinite(inc), inc, 0.0)))  # objectives.ties
    lim = inc + tol
    j = tied_rows(batch, weights, live, lim)
    if not len(j):
        return found
    R, a_of = last["R"][j], last["a_of"][j]
    lo = {"bushing": last["b_sc"][j], "axial": last["a_sc"][j], "spring": last["k_sc"][last["kinv"][j]],
          "bolt": last["t_sc"][j]}
    # per subsystem, the options of each tied core whose score ties its first feasible option's (a cheaper
    # one fails: the search took the first that passes in score order), by evaluation unit (what the
    # subsystem reads of the core)
    cand = {s: tie_candidates(batch, s, weights, R, lo[s], lo[s] + tol[a_of]) for s in SUBSYSTEMS}
    # an application with one tied core and one candidate per subsystem has one tied design: found's
    many = np.bincount(a_of, minlength=len(batch)) > 1
    for inv, unit, (ui, _), _ in cand.values():
        many[a_of[np.bincount(ui, minlength=_n_units(unit))[inv] > 1]] = True
    keep = many[a_of]
    if not keep.any():
        return found
    R, a_of = R[keep], a_of[keep]
    evaluated = {s: tie_evaluate(batch, s, *_restrict(c, keep)) for s, c in cand.items()}
    return _tie_pick(found, R, a_of, last["cs"][j][keep], batch.cg.min_margin()[R], evaluated)

def tied_rows(batch, weights: dict, live, lim) -> np.ndarray:
    """Positions in :attr:`_last` of the cores of the applications ``live`` whose best design scores at most
    ``lim`` (per application): the first search's totals where it finished the core, else searched now (its
    spring and axial scans, cut at ``lim``) and kept."""
    last = batch.last_search
    R, a_of, p0, min_a, t_sc, keys, kinv = (last[k] for k in ("R", "a_of", "p0", "min_a", "t_sc", "keys", "kinv"))
    k_sc, k_pk, a_sc, total = last["k_sc"], last["k_pk"], last["a_sc"], last["total"]
    lim_r = lim[a_of]
    cand = np.flatnonzero(live[a_of] & (last["lb"] <= lim_r))
    todo = cand[~last["done"][cand]]
    if len(todo):
        kt = np.unique(kinv[todo])
        kt = kt[np.isnan(k_sc[kt])]
        if len(kt):  # springs of the keys the first search did not scan
            part = np.full(len(keys["app"]), np.inf)
            np.minimum.at(part, kinv[todo], (p0[todo] + min_a[todo]) + t_sc[todo])
            lk = lim[keys["app"][kt]] - part[kt]
            lk = lk + SLACK * np.maximum(1.0, np.abs(lim[keys["app"][kt]]))
            sub = {k: v[kt] for k, v in keys.items()}
            k_sc[kt], k_pk[kt] = batch.springs.first_feasible(sub, np.where(np.isfinite(lk), lk, np.inf), weights)
        s = k_sc[kinv[todo]]
        go = np.isfinite(s) & (((p0[todo] + min_a[todo]) + s) + t_sc[todo] <= lim_r[todo])
        ta, s = todo[go], s[go]
        if len(ta):
            la = lim_r[ta] - ((p0[ta] + s) + t_sc[ta]) + SLACK * np.maximum(1.0, np.abs(lim_r[ta]))
            a_sc[ta], last["a_pk"][ta] = batch.axial.first_feasible(R[ta], np.where(np.isfinite(la), la, np.inf), weights)
            total[ta] = ((p0[ta] + a_sc[ta]) + s) + t_sc[ta]
        last["done"][todo] = True
    return cand[total[cand] <= lim_r[cand]]

def tie_units(batch, s: str, rows):
    """``(inverse, units)``: the evaluation units of subsystem ``s`` for core rows ``rows`` (one per distinct
    application and value of what ``s`` reads of the core: a spring key for the main spring) and each row's."""
    if s == "spring":
        keys, inv = batch.springs.keys(rows)
        return inv, keys
    reads = family(s).core_reads(batch.cg.values)
    extra = tuple(batch.cg.values[cv][rows] for cv, _ in family(s).match if cv not in reads)  # what it matches on
    first, inv = unique_rows(batch.A[rows], *extra, *(batch.cg.values[k][rows] for k in reads))
    return inv, rows[first]

def tie_candidates(batch, s: str, weights: dict, rows, lo, hi):
    """``(row unit, unit, (unit, option) pairs, their scores)``: per evaluation unit (:meth:`_tie_units`) of
    core rows ``rows``, the options of ``s`` the core may take whose score lies in ``[lo, hi]`` (the row's; a
    unit takes the widest), in score order (ties by index, as the exact solver's ``argmin``)."""
    inv, unit = tie_units(batch, s, rows)
    nu = _n_units(unit)
    ulo, uhi = np.full(nu, np.inf), np.full(nu, -np.inf)
    np.minimum.at(ulo, inv, lo)
    np.maximum.at(uhi, inv, hi)
    if s == "spring":  # a range of positions of the application's score-ordered list
        _, list_of, _, _, (flat, start) = batch.springs.app_lists(weights)
        apps_u = unit["app"]
        first = batch.springs.last_within(weights, apps_u, np.nextafter(ulo, -np.inf)) + 1
        cnt = np.maximum(batch.springs.last_within(weights, apps_u, uhi) - first + 1, 0).astype(np.int64)
        ui = np.repeat(np.arange(nu), cnt)
        oo = flat[start[list_of[apps_u]][ui] + first.astype(np.int64)[ui] + segments(np.zeros(nu), cnt)]
        return inv, unit, (ui, oo), batch.springs.scores(weights, apps_u[ui], oo)
    sc = np.asarray(wsum(option_scores(batch.sp, s), weights), dtype=float) + np.zeros(batch.sp.n(s))
    order = np.argsort(sc, kind="stable")
    a, b = np.searchsorted(sc[order], ulo, "left"), np.searchsorted(sc[order], uhi, "right")
    cnt = np.maximum(b - a, 0)
    ui = np.repeat(np.arange(nu), cnt)
    oo = order[np.repeat(a, cnt) + segments(np.zeros(nu), cnt)]
    may = family(s).allows(batch.sp, batch.cg.values, unit[ui], oo)
    ui, oo = ui[may], oo[may]
    return inv, unit, (ui, oo), sc[oo]

def tie_evaluate(batch, s: str, inv, unit, pairs, scores):
    """The candidates of :meth:`_tie_candidates` that pass every check, with their margins counted in the
    margin objective: ``(row unit, unit index, option, score, margin)`` (the pairs in their order); one
    evaluator call (the main spring: the compiled kernels where they cover the registry's checks)."""
    ui, oo = pairs
    sp, st = batch.sp, batch.settings
    ok, marg = np.zeros(len(ui), dtype=bool), np.zeros(len(ui))
    if len(ui):
        with np.errstate(over="ignore", divide="ignore", invalid="ignore"):
            if s == "spring":
                kk = main_spring.keys_of_rows(batch.apps, unit)
                m = main_spring.pair_margins(kk, batch.springs.options(), ui, oo, engine=batch.engine, settings=st)
                g = evaluate.Group("spring", {"app": unit["app"][ui]}, dict(zip(main_spring.checks(), m.T)),
                                   rules=st.rules)
            elif s == "axial":
                pre = batch.axial.passes_before_physics(unit[ui], oo)  # the others fail at any fidelity
                ui, oo, scores, ok, marg = ui[pre], oo[pre], scores[pre], ok[pre], marg[pre]
                g = evaluate.axial_judged(batch.apps, batch.cg, unit[ui], sp.rows(s, oo), st,
                                          engine=batch.axial_engine)
            elif family(s).group is not None:  # judged pair by pair by its declared group (the bushing)
                g = family(s).group(batch.apps, batch.cg, unit[ui], sp.rows(s, oo), st)
            else:
                o = sp.rows(s, oo)
                g = evaluate.bolt(batch.apps, batch.cg, unit[ui], o, st,
                                  fixation=evaluate.fixation_values(batch.apps, batch.A[unit[ui]], o, st))
        if len(ui):
            a = g.assessment()
            ok, marg = a.ok, a.objective_margin
        batch.evaluations += len(ui)
    return inv, ui[ok], oo[ok], scores[ok], marg[ok], _n_units(unit)
