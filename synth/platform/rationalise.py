"""Choose a platform for a portfolio: compile, prune, greedy warm start, MILP, assignment.

:func:`rationalise` runs the whole chain on feasibility data and returns a
:class:`PlatformResult`; :func:`tradeoff` sweeps it (platform size against total cost,
or against the worst margin).

>>> from synth.platform.synthetic import synthetic_portfolio
>>> r = rationalise(synthetic_portfolio(12, seed=4), "variants", time_limit=30)
>>> r.status, r.n_parts <= r.n_parts_union_optima, r.greedy_value >= r.objective_value - 1e-9
('optimal', True, True)
"""

from __future__ import annotations

import time
from contextlib import nullcontext
from dataclasses import dataclass, field

import numpy as np

from formulations.platform import NODE_LIMIT, TIME_LIMIT_S, solve as solve_milp
from synth.errors import InputError, Problem
from synth.io.limits import COUNTS
from synth.platform.assign import assign, full_platform, objective_value, option_groups, platform_from_y
from synth.platform.compile import Precompiled, compile_portfolio, end_to_end, precompile
from synth.platform.data import CORE_FAMILIES, FAMILIES, SUBSYSTEM_FAMILIES, SUBSYSTEMS, PortfolioFeasibility, \
    default_weights
from synth.platform.greedy import greedy
from synth.platform.prune import prune as prune_work
from synth.platform.verified import verify_records
from synth.platform.outputs import platform_table, price_of_standardisation
from synth.platform.volume import pool_prices, price_curves

__all__ = ["PlatformResult", "rationalise", "tradeoff", "OBJECTIVES", "STAGES"]

OBJECTIVES = ("variants", "cost")
#: the stages of :func:`rationalise`, in order (the names its ``stage`` callback receives; ``verify`` only with
#: ``verify=True`` (it checks nothing on synthetic data), the last two only with ``details``)
STAGES = ("compile", "prune", "greedy", "MILP", "assign", "verify", "per-application optima", "price of standardisation")


@dataclass
class PlatformResult:
    """A chosen platform, each application's design, and how the choice was made."""

    objective: str
    status: str                   # optimal | node_limit | time_limit | greedy (the MILP found no platform) | ...
    platform: dict                # family -> set of part codes
    records: list                 # synth.platform.assign.assign records, one per application
    objective_value: float        # MILP objective of the platform (weighted part count or total cost)
    bound: float
    gap: float
    greedy_value: float
    greedy_gap: float             # (greedy - MILP) / MILP
    size: dict
    sizes_before_prune: dict
    prune_log: list
    times: dict
    per_app_optima: list          # assign records on the full catalog (each application's own optimum)
    weights: dict
    max_variants: dict = field(default_factory=dict)
    notes: list = field(default_factory=list)
    price: dict = field(default_factory=dict)     # synth.platform.outputs.price_of_standardisation
    table: list = field(default_factory=list)     # platform.csv rows: family, part, applications
    tradeoff: list | None = None                  # trade-off rows when a sweep was made (the report section)
    curves: object = None                         # synth.platform.volume.PriceCurves the parts were priced by
    limits: dict = field(default_factory=dict)    # node_limit, time_limit_s, nodes taken, milp_status (the MILP's own)
    capability_line: str = ""                     # the capability target's summary (synth.platform.capable.choose)

    @property
    def n_parts(self) -> int:
        return sum(len(v) for v in self.platform.values())

    @property
    def reproducible(self) -> bool:
        """Whether the platform is the same on every run of the same input: False only where the MILP stopped at the
        wall-clock safety net (its status ``time_limit``, also under ``greedy``), where the platform depends on the
        machine and its load; an optimum and a platform stopped at the node limit are reproducible."""
        return self.limits.get("milp_status", self.status) != "time_limit"

    @property
    def n_parts_union_optima(self) -> int:
        union = {f: set() for f in FAMILIES}
        for r in self.per_app_optima:
            if r["feasible"]:
                for f, code in r["codes"].items():
                    if code >= 0:
                        union[f].add(code)
        return sum(len(v) for v in union.values())


def milp_designs(work, inst, sol) -> dict:
    """``{application index: {family: part code}}``: the design of every application the MILP's solution serves
    (its core ``x`` and option entries ``z``), what :func:`~synth.platform.assign.assign` keeps where a part's price
    depends on which applications use it."""
    parts = [inst.pattern_parts[inst.pattern_ptr[k]:inst.pattern_ptr[k + 1]] for k in range(inst.n_patterns)]
    out: dict = {}

    def put(d, fams, pattern):
        d.update({f: -1 for f in fams})
        for j in parts[int(pattern)]:
            f, code = work.part_of(int(j))
            d[f] = code
    for c in np.flatnonzero(sol.x):
        out[int(work.app_index[int(inst.core_app[c])])] = d = {}
        put(d, CORE_FAMILIES, inst.core_pattern[c])
    entry_row = np.repeat(np.arange(len(inst.row_app)), np.diff(inst.row_opt_ptr))
    for i in np.flatnonzero(sol.z):   # a subsystem with no option at 1 (an LP's tie) is left to the assignment
        d = out.get(int(work.app_index[int(inst.row_app[entry_row[i]])]))
        if d is not None:
            put(d, SUBSYSTEM_FAMILIES[SUBSYSTEMS[int(inst.row_sub[entry_row[i]])]], inst.row_opt_pattern[i])
    return out


def _group_maxima(pf: PortfolioFeasibility, s: str) -> tuple[np.ndarray, np.ndarray]:
    """``(largest margin of each option group of subsystem s, where each application's groups start)``: every
    application's groups one after the other (``-inf`` for a group without an option), by one reduction.

    >>> from synth.platform.synthetic import synthetic_portfolio
    >>> pf = synthetic_portfolio(4, seed=2)
    >>> gm, gptr = _group_maxima(pf, "bolt")
    >>> a = pf.apps[3]
    >>> gm[gptr[3]:gptr[4]].tolist() == [float(np.max(x)) if len(x) else -np.inf for x in a.option_margin["bolt"]]
    True
    """
    ms = [m for a in pf.apps for m in a.option_margin.get(s, [])]
    gptr = np.r_[0, np.cumsum([len(a.option_margin.get(s, [])) for a in pf.apps])].astype(np.int64)
    lens = np.fromiter((len(m) for m in ms), np.int64, len(ms))
    gm = np.full(len(ms), -np.inf)
    if lens.sum():
        flat = end_to_end(ms, float, int(lens.sum()))
        gm[lens > 0] = np.maximum.reduceat(flat, (np.cumsum(lens) - lens)[lens > 0])
    return gm, gptr


def _check(objective, max_variants, time_limit, weights, node_limit=None):
    probs = []
    if objective not in OBJECTIVES:
        probs.append(Problem("objective", objective, " or ".join(OBJECTIVES)))
    for f, n in (max_variants or {}).items():
        if f not in FAMILIES:
            probs.append(Problem("--max-variants family", f, ", ".join(FAMILIES)))
        elif not (isinstance(n, (int, np.integer)) and n >= 1):
            probs.append(Problem(f"--max-variants {f}", n, "a whole number >= 1"))
    if not (np.isfinite(time_limit) and time_limit > 0):
        probs.append(Problem("--time-limit", time_limit, "a number of seconds > 0"))
    lim = COUNTS["rationalise --node-limit"]
    if node_limit is not None and not (isinstance(node_limit, (int, np.integer)) and not isinstance(node_limit, bool)
                                       and lim.lo <= node_limit <= lim.hi):
        probs.append(Problem("--node-limit", node_limit, f"a whole number of branch-and-bound nodes in "
                                                         f"[{lim.lo}, {lim.hi}], or None (no node limit)"))
    for f, w in (weights or {}).items():
        if f not in FAMILIES:
            probs.append(Problem("weight family", f, ", ".join(FAMILIES)))
        elif not (np.isfinite(w) and w >= 0):
            probs.append(Problem(f"weight {f}", w, "a number >= 0"))
    if probs:
        raise InputError(probs)


def rationalise(pf: PortfolioFeasibility, objective: str = "variants", *, max_variants: dict | None = None,
                time_limit: float = TIME_LIMIT_S, node_limit: int | None = NODE_LIMIT, weights: dict | None = None,
                solver: str = "highs", prune: bool = True,
                min_margin: float | None = None, budget: float | None = None, verify: bool = True,
                pre: Precompiled | None = None, details: bool = True, build: str = "arrays",
                stage=None, curves="auto") -> PlatformResult:
    """The platform of ``pf`` minimising ``objective`` (``variants``: weighted count of distinct
    parts; ``cost``: unit cost x volume plus per-variant fixed cost).

    ``max_variants``: ``{family: N}`` caps (applications no capped platform serves are
    reported, not an error); ``node_limit``: branch-and-bound nodes the MILP may take (default
    :data:`formulations.platform.NODE_LIMIT`; None: no limit), the limit that keeps the platform the same on every
    machine and under any load (status ``node_limit`` where it binds); ``time_limit``: wall-clock seconds the MILP may
    take (default :data:`formulations.platform.TIME_LIMIT_S`), a safety net: where it binds (status ``time_limit``)
    the platform is not reproducible and the outputs say so (:attr:`PlatformResult.reproducible`); ``min_margin``: only cores and options with at least this
    margin; ``budget``: a ceiling on the weighted part count (the trade-off sweep);
    ``verify``: check every assigned design again through the evaluator
    (:func:`synth.platform.verified.verify_records`, real data only); ``pre``: ``pf``'s
    :func:`~synth.platform.compile.precompile` (several solves of one portfolio compile it once);
    ``details=False`` leaves out what only the platform's own report reads (the per-application optima on the
    full catalog, ``price`` and ``table``): the trade-off rows do not need them. ``build``: how HiGHS gets the MILP
    (:data:`formulations.platform.BUILDS`: from arrays through highspy, or through Pyomo, the reference).
    ``stage(name)``: a context manager around each stage (:data:`STAGES`: the command line's progress line per
    stage, :class:`synth.progress.phase`); none by default. ``curves``: the parts' unit prices against their
    volume (:class:`synth.platform.volume.PriceCurves`; ``"auto"``: :func:`~synth.platform.volume.price_curves` of
    ``pf``, None without annual volumes; None: each part at the price the feasibility data hold): the cost objective
    prices each part at the summed volume of the applications it serves (:func:`~synth.platform.volume.pool_prices`).
    """
    _check(objective, max_variants, time_limit, weights, node_limit)
    step = stage or (lambda name: nullcontext())
    w_all = {**default_weights(), **(weights or {})}
    t0 = time.perf_counter()
    with step("compile"):
        pre = pre if pre is not None else precompile(pf)   # the compilation and the assignments share its groups
        work = compile_portfolio(pf, objective, min_margin=min_margin, weights=w_all, pre=pre)
        if isinstance(curves, str):
            curves = price_curves(pf)
        if objective == "cost" and curves is not None:
            pool_prices(work, curves)
        if pre.assign_groups is None:
            pre.assign_groups = option_groups(pf)
    groups = pre.assign_groups   # the two assignments below share them
    pre = None                   # what is left of it is not needed (one solve: its memory back for the MILP)
    before = work.sizes()
    t1 = time.perf_counter()
    capped = bool(max_variants) or budget is not None
    with step("prune"):
        if prune:
            prune_work(work, allow_unserved=capped)
        inst = work.instance()
    t2 = time.perf_counter()
    with step("greedy"):
        y_g = greedy(inst, objective)
        g_val = objective_value(inst, y_g, objective)
    t3 = time.perf_counter()
    warm = y_g if not capped else None   # the uncapped greedy platform may break a cap
    with step("MILP"):
        sol = solve_milp(inst, objective, solver=solver, time_limit=time_limit, node_limit=node_limit,
                         max_variants=max_variants, budget=budget, allow_unserved=capped, warm_start=warm, build=build)
    t4 = time.perf_counter()
    notes = list(pf.notes)
    if sol.y is not None:
        y, status = sol.y, sol.status
    elif not capped:
        y, status = y_g, "greedy"
        notes.append(f"MILP {sol.status} after {sol.time_s:.1f} s: the greedy platform is reported")
    else:
        y, status = np.zeros(inst.n_parts, bool), sol.status
    platform = platform_from_y(work, y)
    with step("assign"):
        designs = milp_designs(work, inst, sol) if sol.y is not None and sol.x is not None else None
        records = assign(pf, platform, min_margin=min_margin, groups=groups, designs=designs)
    t_v = time.perf_counter()
    if verify:
        with step("verify"):
            verify_records(pf, records)
    t_v = time.perf_counter() - t_v
    reasons = dict(work.unservable)
    for i, r in enumerate(records):
        if not r["feasible"] and i in reasons:
            r["reason"] = reasons[i]
        elif not r["feasible"] and capped:
            r["reason"] = "not served within --max-variants: " + r["reason"]
    # drop platform parts no assigned design uses (a solver may keep an unused part at zero weight)
    used = {f: set() for f in FAMILIES}
    for r in records:
        if r["feasible"]:
            for f, code in r["codes"].items():
                if code >= 0:
                    used[f].add(code)
    platform = {f: platform[f] & used[f] for f in FAMILIES}
    with step("per-application optima") if details else nullcontext():
        per_app = assign(pf, full_platform(pf), min_margin=min_margin, groups=groups) if details else []
    t5 = time.perf_counter()
    obj = sol.objective if sol.y is not None else g_val
    res = PlatformResult(
        objective=objective, status=status, platform=platform, records=records, objective_value=float(obj),
        bound=float(sol.bound), gap=float(sol.gap), greedy_value=float(g_val),
        greedy_gap=float((g_val - obj) / max(abs(obj), 1e-9)) if np.isfinite(g_val) and np.isfinite(obj) and not capped
        else np.nan,   # the greedy platform ignores caps: no baseline for a capped MILP
        size=dict(sol.size), sizes_before_prune=before, prune_log=list(work.log),
        times={"compile_s": t1 - t0, "prune_s": t2 - t1, "greedy_s": t3 - t2, "build_s": sol.build_s,
               "solve_s": sol.time_s, "milp_s": t4 - t3, "assign_s": t5 - t4 - t_v, "verify_s": t_v,
               "total_s": t5 - t0},
        per_app_optima=per_app, weights=w_all, max_variants=dict(max_variants or {}), notes=notes, curves=curves,
        limits={"node_limit": node_limit, "time_limit_s": float(time_limit), "nodes": int(sol.nodes),
                "milp_status": sol.status})
    if not details:
        return res
    with step("price of standardisation"):
        res.price = price_of_standardisation(pf, res)
        res.table = platform_table(pf, res).to_dict(orient="records")
    return res


def tradeoff(pf: PortfolioFeasibility, kind: str = "margin", *, points: int = 6, time_limit: float = TIME_LIMIT_S,
             node_limit: int | None = NODE_LIMIT, weights: dict | None = None, progress=None, share: bool = True,
             build: str = "arrays") -> list:
    """Platform size against worst margin (``kind="margin"``) or against total cost (``"cost"``).

    ``margin``: for margin floors from 0 up to the lower quartile of the applications' best
    margins, the smallest platform (variants objective), over the applications that can
    meet the highest floor (the same applications at every floor, so the curve rises). ``cost``: for part budgets from
    the smallest platform up to the size of the cost-optimal one, the cheapest platform
    (unit cost x volume + per-variant fixed cost) within the budget (an epsilon constraint).
    Returns rows ``{"parts", "cost_eur", "worst_margin", "served", "status", ...}``. ``progress(done, total)`` is
    called after each platform solved. ``share``: the rounds compile the portfolio once
    (:func:`~synth.platform.compile.precompile`) and leave out the reports' details; ``False`` solves each round
    afresh (the same rows, slower: the benchmark's and the tests' yardstick). ``build``, ``time_limit`` and
    ``node_limit``: as in :func:`rationalise`, per round; a round stopped at the time limit says "not reproducible"
    in its status.
    """
    if kind not in ("margin", "cost"):
        raise InputError(Problem("trade-off", kind, "margin or cost"))
    rows = []
    tick = progress or (lambda done, total: None)
    curves = price_curves(pf)

    def row(r: PlatformResult, **extra):
        ok = [x for x in r.records if x["feasible"]]
        vol = {a.app_id: a.volume for a in pf.apps}
        cost = sum(x["unit_cost_eur"] * vol[x["app_id"]] for x in ok)
        fixed = sum(float(pf.part_cost_eur[f][c]) for f, cs in r.platform.items() for c in cs)
        return {"parts": r.n_parts, "weighted_parts": sum(r.weights[f] * len(cs) for f, cs in r.platform.items()),
                "cost_eur": cost + fixed, "unit_cost_volume_eur": cost, "fixed_cost_eur": fixed,
                "worst_margin": min((x["margin"] for x in ok), default=np.nan), "served": len(ok),
                "status": r.status if r.reproducible else f"{r.status} (time limit: not reproducible)", **extra}

    if kind == "margin":
        # the largest floor every servable application can meet: the smallest per-application best margin
        best = []
        gmax = {s: _group_maxima(pf, s) for s in {s for a in pf.apps for s in a.feasible}}
        for i, a in enumerate(pf.apps):
            if a.n_cores:
                m = np.full(a.n_cores, np.inf)
                for s in a.feasible:
                    gm, gptr = gmax[s]
                    m = np.minimum(m, gm[gptr[i]:gptr[i + 1]][np.asarray(a.group[s])])
                m = np.minimum(m, a.core_margin)
                if m.size and m.max() >= 0:
                    best.append((float(m.max()), a))
        # floors up to the lower quartile of the positive best margins (an application whose every design has a
        # margin of 0, e.g. a bolt that exactly fits the engine's bore, cannot take part in the curve)
        pos = [b for b, _ in best if b > 0]
        top = float(np.quantile(np.minimum(pos, 1e6), 0.25)) if pos else 0.0
        import dataclasses
        pf = dataclasses.replace(pf, apps=[a for b, a in best if b >= top])   # one set of applications for every floor
        pre = precompile(pf) if share else None   # compiled once: each floor keeps a subset of its options
        base = rationalise(pf, "variants", time_limit=time_limit, node_limit=node_limit, weights=weights,
                           verify=False, pre=pre, details=not share, build=build)
        tick(1, points)
        n_served = len(pf.apps)
        for tau in np.linspace(0.0, top, points):
            r = base if tau == 0.0 else rationalise(pf, "variants", time_limit=time_limit, node_limit=node_limit,
                                                    weights=weights, min_margin=float(tau), verify=False, pre=pre,
                                                    details=not share, build=build)
            tick(len(rows) + 1, points)
            rows.append(row(r, margin_floor=float(tau)))
            if rows[-1]["served"] < n_served:
                rows[-1]["status"] += " (fewer served)"
        return rows
    pre = precompile(pf) if share else None
    small = rationalise(pf, "variants", time_limit=time_limit, node_limit=node_limit, weights=weights, verify=False,
                        pre=pre, details=not share, build=build)
    cheap = rationalise(pf, "cost", time_limit=time_limit, node_limit=node_limit, weights=weights, verify=False,
                        pre=pre, details=not share, build=build, curves=curves)
    lo, hi = sum(small.weights[f] * len(c) for f, c in small.platform.items()), \
        sum(cheap.weights[f] * len(c) for f, c in cheap.platform.items())
    budgets = np.unique(np.round(np.linspace(lo, max(hi, lo), points), 6))
    for b in budgets:
        r = cheap if b >= hi else rationalise(pf, "cost", time_limit=time_limit, node_limit=node_limit, weights=weights,
                                              budget=float(b), verify=False, pre=pre, details=not share, build=build,
                                              curves=curves)
        rows.append(row(r, budget=float(b)))
        tick(len(rows), len(budgets))
    return rows
