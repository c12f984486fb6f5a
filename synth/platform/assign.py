"""Which design each application gets from a platform, and what a platform costs.

Two independent evaluations of a platform:

* :func:`serve` works on the compiled arrays (:class:`formulations.platform.PlatformInstance`),
  fully vectorised; the greedy heuristic calls it many times.
* :func:`assign` works on the raw feasibility data (:class:`~synth.platform.data.PortfolioFeasibility`)
  application by application: for each, the cheapest design whose core and options use
  only platform parts (subsystems are independent given the core, so the best design
  of a core is the core plus the cheapest platform option of each of its groups). It
  is what the outputs report and what the tests check the MILP's platform with.

>>> from synth.platform.synthetic import synthetic_portfolio
>>> pf = synthetic_portfolio(3, seed=0)
>>> rows = assign(pf, full_platform(pf))
>>> [(r["app_id"], r["feasible"]) for r in rows]
[('APP-0000', False), ('APP-0001', True), ('APP-0002', True)]
"""

from __future__ import annotations

import numpy as np

from formulations.platform import PlatformInstance
from synth.design.combine import combine
from synth.platform.compile import flat_groups
from synth.platform.data import CORE_FAMILIES, FAMILIES, SUBSYSTEM_FAMILIES, SUBSYSTEMS, PortfolioFeasibility

__all__ = ["serve", "objective_value", "assign", "option_groups", "full_platform", "platform_from_y", "platform_parts_used"]


def _pattern_ok(inst: PlatformInstance, y: np.ndarray) -> np.ndarray:
    pid = np.repeat(np.arange(inst.n_patterns), inst.pattern_len())
    have = np.bincount(pid, weights=y[inst.pattern_parts].astype(float), minlength=inst.n_patterns)
    return have >= inst.pattern_len() - 0.5


def serve(inst: PlatformInstance, y: np.ndarray, objective: str = "cost"):
    """``(served, cost, core)`` per application of ``inst`` under the platform ``y`` (bool per part).

    ``cost``: the volume-weighted unit cost of the cheapest design (``inf`` when not
    served); ``core``: its core index in ``inst`` (``-1``).
    """
    ok = _pattern_ok(inst, np.asarray(y, bool))
    C, R = len(inst.core_app), len(inst.row_app)
    val = np.where(ok[inst.row_opt_pattern], inst.row_opt_cost, np.inf)
    nonempty = np.diff(inst.row_opt_ptr) > 0
    row_best = np.full(R, np.inf)
    if val.size:
        row_best[nonempty] = np.minimum.reduceat(val, inst.row_opt_ptr[:-1][nonempty])
    core_val = np.where(ok[inst.core_pattern], inst.core_cost, np.inf)
    r_of = np.repeat(np.arange(R), np.diff(inst.row_core_ptr))
    np.add.at(core_val, inst.row_core, row_best[r_of])
    served = np.zeros(inst.n_apps, bool)
    cost = np.full(inst.n_apps, np.inf)
    core = np.full(inst.n_apps, -1)
    if C:
        start = np.searchsorted(inst.core_app, np.arange(inst.n_apps))
        has = np.bincount(inst.core_app, minlength=inst.n_apps) > 0
        cost[has] = np.minimum.reduceat(core_val, start[has])
        served = np.isfinite(cost)
        order = np.lexsort((core_val, inst.core_app))
        first = np.r_[True, inst.core_app[order][1:] != inst.core_app[order][:-1]]
        core[inst.core_app[order][first]] = order[first]
        core[~served] = -1
    return served, cost, core


def objective_value(inst: PlatformInstance, y: np.ndarray, objective: str) -> float:
    """The MILP objective of platform ``y`` (``inf`` when an application is not served); with volume breaks, of
    each application's cheapest design at the unit costs with the breaks their volumes reach
    (:func:`formulations.platform.designs_start`: an upper bound of the platform's cost)."""
    served, cost, _ = serve(inst, y)
    if not served.all():
        return np.inf
    y = np.asarray(y, bool)
    if objective == "variants":
        return float(np.sum(inst.part_weight[y]))
    if inst.n_breaks:
        from formulations.platform import designs_start
        x, z, pooled, _ = designs_start(inst, y)
        return float(np.sum(inst.part_fixed_cost[y]) + x @ inst.core_cost + z @ inst.row_opt_cost
                     - np.asarray(inst.break_step, float) @ pooled)
    return float(np.sum(inst.part_fixed_cost[y]) + np.sum(cost))


def full_platform(pf: PortfolioFeasibility) -> dict:
    """Every part of every family: ``{family: set of codes}`` (each application's own optimum)."""
    return {f: set(range(len(pf.parts[f]))) for f in FAMILIES}


def platform_from_y(work, y: np.ndarray) -> dict:
    """``{family: set of codes}`` of the bool per global part ``y`` of a compiled ``work``."""
    out = {f: set() for f in FAMILIES}
    for j in np.flatnonzero(y):
        f, code = work.part_of(int(j))
        out[f].add(code)
    return out


def _in(platform: dict, f: str, codes: np.ndarray) -> np.ndarray:
    codes = np.asarray(codes)
    allowed = np.array(sorted(platform.get(f, ())), dtype=np.int64)
    return (codes < 0) | np.isin(codes, allowed)


def _cheapest(idx: np.ndarray, mar: np.ndarray, cost: np.ndarray, grp: np.ndarray, n_groups: int,
              usable: np.ndarray, tau: float, entry_ok: np.ndarray | None = None):
    """Per group of options (option ``idx[i]`` of group ``grp[i]``, margin ``mar[i]``, unit cost ``cost[i]``) the
    cheapest usable option with a margin of at least ``tau`` (the first of equal costs) and its cost: ``(choice,
    cost)``, ``-1`` and ``inf`` for a group with none. Every group at once (one sort), not a loop over them.

    >>> c, g = _cheapest(np.array([0, 2, 1, 3, 0]), np.array([1, 1, 1, 1, -1]), np.array([3.0, 1, 1, 2, 3]),
    ...                  np.array([0, 0, 0, 1, 2]), 3, np.array([True, True, True, False]), 0.0)
    >>> c.tolist(), g.tolist()
    ([2, -1, -1], [1.0, inf, inf])
    """
    choice, best = np.full(n_groups, -1, np.int64), np.full(n_groups, np.inf)
    m = usable[idx] & (mar >= tau)
    if entry_ok is not None:                                   # per entry (a design an application must keep)
        m &= entry_ok
    idx, grp, c = idx[m], grp[m], cost[m]
    if not len(idx):
        return choice, best
    start = np.flatnonzero(np.r_[True, grp[1:] != grp[:-1]])   # the groups' runs (grp ascends)
    low = np.minimum.reduceat(c, start)
    hit = np.flatnonzero(c == np.repeat(low, np.diff(np.r_[start, len(c)])))
    first = hit[np.r_[True, grp[hit][1:] != grp[hit][:-1]]]    # the first of equal costs
    choice[grp[first]], best[grp[first]] = idx[first], c[first]
    return choice, best


def option_groups(pf: PortfolioFeasibility) -> dict:
    """``{subsystem: flat_groups(pf, subsystem)}``: what :func:`assign` reads of ``pf``'s options whatever the
    platform (several assignments of one portfolio compute it once)."""
    return {s: flat_groups(pf, s) for s in SUBSYSTEMS}


def assign(pf: PortfolioFeasibility, platform: dict, *, min_margin: float | None = None,
           groups: dict | None = None, designs: dict | None = None) -> list:
    """One record per application of ``pf``: its cheapest design built only from ``platform`` parts.

    Record keys: ``app_id``, ``feasible``, ``core`` (index into the application's cores or
    None), ``options`` (``{subsystem: option index}``), ``parts`` (``{family: part key}``),
    ``codes`` (``{family: part code}``, ``-1`` none), ``unit_cost_eur``, ``margin`` (the smallest of the core's and the options' margins),
    ``binding`` (the constraint with that margin, when the data name it), ``reason`` (why
    not feasible). ``min_margin`` ignores cores and options with a smaller margin. ``groups``: ``pf``'s
    :func:`option_groups` when already computed (the same records). ``designs``: ``{application index:
    {family: part code}}``, the parts an application's design must have (the MILP's designs where a part's price
    depends on which applications use it: :func:`synth.platform.volume.pool_prices`); its cheapest design with
    exactly those parts.
    """
    tau = -np.inf if min_margin is None else float(min_margin)
    opt_ok = {s: np.all([_in(platform, f, pf.options[s][f]) for f in fams], axis=0)
              for s, fams in SUBSYSTEM_FAMILIES.items()}
    cheap = {}
    groups = groups if groups is not None else option_groups(pf)
    target = None
    if designs:   # per family the code each application must use (-2: free)
        target = {f: np.full(len(pf.apps), -2, np.int64) for f in FAMILIES}
        for ai, d in designs.items():
            for f in FAMILIES:
                target[f][ai] = int(d.get(f, -2))
    for s in SUBSYSTEMS:
        idx, mar, cost, grp, gptr = groups[s]
        entry_ok = None
        if target is not None:
            app = np.repeat(np.arange(len(pf.apps)), np.diff(gptr))[grp]
            entry_ok = np.ones(len(idx), bool)
            for f in SUBSYSTEM_FAMILIES[s]:
                t = target[f][app]
                entry_ok &= (t == -2) | (np.asarray(pf.options[s][f])[idx] == t)
        cheap[s] = (*_cheapest(idx, mar, cost, grp, int(gptr[-1]), opt_ok[s], tau, entry_ok), gptr)
    # every application's cores one after the other: which the platform builds, and their cheapest designs' costs
    apps = pf.apps
    n_c = np.array([a.n_cores for a in apps], np.int64)
    cptr = np.r_[0, np.cumsum(n_c)]
    app_of = np.repeat(np.arange(len(apps)), n_c)
    cat = (lambda xs, dt: np.concatenate(xs).astype(dt, copy=False) if xs else np.zeros(0, dt))  # noqa: E731
    ok = cat([np.asarray(a.core_margin, float) for a in apps], float) >= tau
    for f in CORE_FAMILIES:
        codes = cat([np.asarray(a.core_parts[f]).reshape(-1) for a in apps], np.int64)
        ok &= _in(platform, f, codes)
        if target is not None:
            ok &= (target[f][app_of] == -2) | (codes == target[f][app_of])
    total = cat([np.asarray(a.core_cost_eur, float) for a in apps], float).copy()
    missing, best_opt = {}, {}
    for s in SUBSYSTEMS:
        ch, cb, gptr = cheap[s]
        g = cat([np.asarray(a.group[s], np.int64).reshape(-1) for a in apps], np.int64) + gptr[:-1][app_of]
        missing[s] = np.bincount(app_of[ok & ~np.isfinite(cb[g])], minlength=len(apps))
        total += cb[g]
        best_opt[s] = ch[g]                                       # per core: its group's cheapest usable option
    total[~ok] = np.inf
    any_ok = np.bincount(app_of[ok], minlength=len(apps)) > 0
    any_finite = np.bincount(app_of[np.isfinite(total)], minlength=len(apps)) > 0
    out = []
    for ai, a in enumerate(apps):
        rec = {"app_id": a.app_id, "feasible": False, "core": None, "options": {}, "parts": {}, "codes": {},
               "unit_cost_eur": np.nan, "margin": np.nan, "binding": "", "reason": ""}
        out.append(rec)
        if a.n_cores == 0:
            rec["reason"] = a.note or "no feasible core"
            continue
        if not any_finite[ai]:
            if not any_ok[ai]:
                rec["reason"] = "no core built from platform parts" + ("" if tau == -np.inf else f" with margin >= {tau:g}")
            else:
                miss = ", ".join(f"{s} ({n} cores)" for s, n in sorted(((s, int(missing[s][ai])) for s in SUBSYSTEMS),
                                                                      key=lambda t: -t[1]) if n)
                rec["reason"] = f"no platform option for every subsystem of a platform core; missing: {miss}"
            continue
        lo = cptr[ai]
        c = int(np.argmin(total[lo:cptr[ai + 1]]))
        rec.update(feasible=True, core=c, unit_cost_eur=float(total[lo + c]))
        rec["codes"] = {f: int(a.core_parts[f][c]) for f in CORE_FAMILIES}
        opt_m, opt_b = [], []
        for s in SUBSYSTEMS:
            gi = int(a.group[s][c])
            k = int(best_opt[s][lo + c])
            rec["options"][s] = k
            rec["codes"].update({f: int(pf.options[s][f][k]) for f in SUBSYSTEM_FAMILIES[s]})
            pos = int(np.flatnonzero(np.asarray(a.feasible[s][gi]) == k)[0])
            opt_b.append("" if a.option_binding is None else str(a.option_binding[s][gi][pos]))
            opt_m.append(float(a.option_margin[s][gi][pos]))
        rec["parts"] = {f: pf.part_key(f, rec["codes"][f]) for f in FAMILIES}
        rec["margin"], rec["binding"] = combine(float(a.core_margin[c]), opt_m,
                                                "" if a.core_binding is None else str(a.core_binding[c]), opt_b)
    return out


def platform_parts_used(pf: PortfolioFeasibility, records: list) -> dict:
    """``{family: {part key: number of applications using it}}`` of the assigned designs."""
    use = {f: {} for f in FAMILIES}
    for r in records:
        if r["feasible"]:
            for f, code in r["codes"].items():
                if code >= 0:
                    key = pf.part_key(f, code)
                    use[f][key] = use[f].get(key, 0) + 1
    return use
