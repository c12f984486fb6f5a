"""Flatten a portfolio's feasibility into the plain arrays of the platform MILP.

:func:`compile_portfolio` turns :class:`~synth.platform.data.PortfolioFeasibility` into a
:class:`Work` (lists that the reductions of :mod:`synth.platform.prune` edit) and
:meth:`Work.instance` packs it into :class:`formulations.platform.PlatformInstance`.

* Parts of every family get one global index ``j`` (family by family, code order).
* A **pattern** is the set of parts of one core or one subsystem option; options with the
  same parts share a pattern (the "no axial group" option is the empty pattern).
* Per application: the cores that can be completed (every subsystem has at least one
  feasible option for the core's group; the others are dropped: no design uses them) and
  one **row** per (subsystem, group) in use. Rows of one application and subsystem with
  the same feasible pattern set are merged (an application uses one core, and a platform
  covers both rows or neither). In a row, options with the same pattern keep the cheapest.
* ``min_margin`` drops cores and options whose margin is below it (the margin sweep).
* Applications with no complete design are listed in ``unservable`` with the reason.

>>> from synth.platform.synthetic import synthetic_portfolio
>>> w = compile_portfolio(synthetic_portfolio(3, seed=0), "variants")
>>> inst = w.instance()
>>> inst.n_apps == len(w.app_index), inst.n_parts == sum(len(v) for v in w.pf.parts.values())
(True, True)
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from formulations.platform import PlatformInstance
from synth.platform.data import CORE_FAMILIES, FAMILIES, SUBSYSTEM_FAMILIES, SUBSYSTEMS, PortfolioFeasibility, \
    default_weights

__all__ = ["Work", "Precompiled", "precompile", "compile_portfolio", "app_option_cost"]


def app_option_cost(pf: PortfolioFeasibility, app, s: str) -> np.ndarray:
    """Unit cost of every option of subsystem ``s`` for ``app`` (its own costs when given)."""
    if app.option_cost_eur is not None and s in app.option_cost_eur:
        return np.asarray(app.option_cost_eur[s], float)
    return np.asarray(pf.option_cost_eur[s], float)


@dataclass
class Work:
    """The compiled, editable problem (see the module docstring); ``instance()`` packs it."""

    pf: PortfolioFeasibility
    objective: str
    part_offset: dict            # family -> first global part index
    part_family: np.ndarray      # (J,)
    part_weight: np.ndarray
    part_fixed_cost: np.ndarray
    patterns: list               # pattern id -> sorted int array of global parts
    option_pattern: dict         # subsystem -> (n_options,) pattern id
    app_index: np.ndarray        # instance application -> index into pf.apps
    core_app: np.ndarray         # (C,) instance application
    core_local: np.ndarray       # (C,) core index inside its application
    core_pattern: np.ndarray
    core_cost: np.ndarray        # x volume (plus costs folded in from dropped rows)
    core_alive: np.ndarray       # bool
    row_app: list
    row_sub: list                # subsystem index
    row_cores: list              # int arrays of global cores
    row_pats: list               # int arrays of patterns (unique in a row)
    row_cost: list               # float arrays: unit cost x volume of each pattern's cheapest option
    row_alive: list
    unservable: list = field(default_factory=list)   # (pf app index, reason)
    log: list = field(default_factory=list)          # what each reduction removed

    @property
    def n_parts(self) -> int:
        return int(len(self.part_family))

    def part_of(self, j: int) -> tuple:
        """``(family, code)`` of global part ``j``."""
        f = FAMILIES[int(self.part_family[j])]
        return f, int(j - self.part_offset[f])

    def sizes(self) -> dict:
        rows = [i for i, a in enumerate(self.row_alive) if a]
        return {"applications": int(len(self.app_index)), "cores": int(self.core_alive.sum()), "rows": len(rows),
                "row_options": int(sum(len(self.row_pats[i]) for i in rows))}

    def instance(self) -> PlatformInstance:
        """Pack the live cores and rows into a :class:`~formulations.platform.PlatformInstance`."""
        alive = np.flatnonzero(self.core_alive)
        new = np.full(len(self.core_alive), -1)
        new[alive] = np.arange(len(alive))
        rows = [i for i, a in enumerate(self.row_alive) if a]
        rc = [new[self.row_cores[i][self.core_alive[self.row_cores[i]]]] for i in rows]
        keep = [k for k, i in enumerate(rows) if len(rc[k])]
        rows, rc = [rows[k] for k in keep], [rc[k] for k in keep]
        ptr = np.zeros(len(self.patterns) + 1, np.int64)
        ptr[1:] = np.cumsum([len(p) for p in self.patterns])
        def cat(xs, dt):
            return np.concatenate(xs).astype(dt) if xs else np.zeros(0, dt)
        return PlatformInstance(
            family_names=list(FAMILIES), part_family=self.part_family, part_weight=self.part_weight,
            part_fixed_cost=self.part_fixed_cost, pattern_ptr=ptr, pattern_parts=cat(self.patterns, np.int64),
            n_apps=int(len(self.app_index)), core_app=self.core_app[alive], core_pattern=self.core_pattern[alive],
            core_cost=self.core_cost[alive],
            row_app=np.array([self.row_app[i] for i in rows], np.int64),
            row_sub=np.array([self.row_sub[i] for i in rows], np.int64),
            row_core_ptr=np.concatenate([[0], np.cumsum([len(c) for c in rc])]).astype(np.int64),
            row_core=cat(rc, np.int64),
            row_opt_ptr=np.concatenate([[0], np.cumsum([len(self.row_pats[i]) for i in rows])]).astype(np.int64),
            row_opt_pattern=cat([self.row_pats[i] for i in rows], np.int64),
            row_opt_cost=cat([self.row_cost[i] for i in rows], float))


class _Patterns:
    def __init__(self):
        self.ids: dict = {}
        self.list: list = []

    def get(self, parts: np.ndarray) -> int:
        key = tuple(sorted(int(p) for p in parts if p >= 0))
        if key not in self.ids:
            self.ids[key] = len(self.list)
            self.list.append(np.array(key, np.int64))
        return self.ids[key]

    def many(self, codes: np.ndarray) -> np.ndarray:
        """Pattern id per row of ``codes`` (``(n, n_fam)`` global part ids, ``-1`` none)."""
        if len(codes) == 0:
            return np.zeros(0, np.int64)
        uniq, inv = np.unique(codes, axis=0, return_inverse=True)
        ids = np.array([self.get(u) for u in uniq], np.int64)
        return ids[np.asarray(inv).reshape(-1)]


def _why_unservable(a, dead_by: dict, n_cores: int, floor: bool) -> str:
    if a.note and not floor:
        return a.note          # the producer's reason (no feasible design at all)
    if n_cores == 0:
        return a.note or "no feasible core: no bearing, pivot class, bushing supplier and damper pad pass their own constraints"
    parts = [f"{s} ({n} of {n_cores} cores)" for s, n in sorted(dead_by.items(), key=lambda t: -t[1]) if n]
    return "no core has a feasible option of every subsystem; missing: " + ", ".join(parts)


@dataclass
class Precompiled:
    """What :func:`compile_portfolio` computes whatever the margin floor and objective: the options'
    patterns and, per application, subsystem and group, the feasible options sorted by (pattern, cost) with
    their margins (a floor then keeps a subsequence: the sort of the kept options is the same). The trade-off
    sweep compiles a portfolio once with :func:`precompile` and each floor from it."""

    pf: PortfolioFeasibility
    offset: dict
    part_family: np.ndarray
    part_fixed: np.ndarray
    patterns: _Patterns          # after the empty pattern and every option's pattern
    option_pattern: dict
    groups: list                 # per app: {subsystem: (patterns, costs x volume, margins, group, n_groups)}, the
    #                              groups' options one after the other (``group``: the group of each)
    assign_groups: dict | None = None   # synth.platform.assign.option_groups(pf), filled by the first assignment


def precompile(pf: PortfolioFeasibility) -> Precompiled:
    """The floor- and objective-independent part of :func:`compile_portfolio` (see :class:`Precompiled`)."""
    offset, j = {}, 0
    for f in FAMILIES:
        offset[f] = j
        j += len(pf.parts[f])
    part_family = np.concatenate([np.full(len(pf.parts[f]), i) for i, f in enumerate(FAMILIES)]).astype(np.int64)
    part_fixed = np.concatenate([np.asarray(pf.part_cost_eur[f], float) for f in FAMILIES])
    pats = _Patterns()
    pats.get(np.zeros(0))  # pattern 0: the empty pattern
    option_pattern = {s: pats.many(np.stack([_glob(offset, f, pf.options[s][f]) for f in fams], axis=1))
                      for s, fams in SUBSYSTEM_FAMILIES.items()}
    groups = []
    for a in pf.apps:
        ga = {}
        for s in SUBSYSTEMS:
            cost = app_option_cost(pf, a, s) * float(a.volume)
            parts = []
            for idx, mar in zip(a.feasible[s], a.option_margin[s]):
                idx = np.asarray(idx, np.int64)
                p, cst = option_pattern[s][idx], cost[idx]
                order = np.lexsort((cst, p))                      # per pattern the cheapest first (stable)
                parts.append((p[order], cst[order], np.asarray(mar, float)[order]))
            n_g = len(parts)
            ga[s] = (np.concatenate([x[0] for x in parts]).astype(np.int64) if n_g else np.zeros(0, np.int64),
                     np.concatenate([x[1] for x in parts]).astype(float) if n_g else np.zeros(0),
                     np.concatenate([x[2] for x in parts]).astype(float) if n_g else np.zeros(0),
                     np.repeat(np.arange(n_g), [len(x[0]) for x in parts]).astype(np.int64), n_g)
        groups.append(ga)
    return Precompiled(pf=pf, offset=offset, part_family=part_family, part_fixed=part_fixed, patterns=pats,
                       option_pattern=option_pattern, groups=groups)


def _glob(offset: dict, f: str, codes) -> np.ndarray:
    codes = np.asarray(codes)
    return np.where(codes < 0, -1, codes + offset[f])


def compile_portfolio(pf: PortfolioFeasibility, objective: str = "variants", *, min_margin: float | None = None,
                      weights: dict | None = None, pre: Precompiled | None = None) -> Work:
    """Compile ``pf`` for ``objective`` (``variants`` or ``cost``); ``weights``: per-family weights
    (defaults :func:`~synth.platform.data.default_weights`); ``min_margin``: the margin floor; ``pre``: the
    :func:`precompile` of ``pf`` when compiling it for several floors (the same result, faster)."""
    if pre is None:
        pre = precompile(pf)
    elif pre.pf is not pf:
        raise ValueError("compile_portfolio: pre was precompiled from another portfolio")
    w = {**default_weights(), **(weights or {})}
    offset = pre.offset
    part_family = pre.part_family
    part_weight = np.concatenate([np.full(len(pf.parts[f]), float(w[f])) for f in FAMILIES])
    part_fixed = pre.part_fixed
    pats = _Patterns()
    pats.ids, pats.list = dict(pre.patterns.ids), list(pre.patterns.list)
    option_pattern = pre.option_pattern
    tau = -np.inf if min_margin is None else float(min_margin)
    app_index, c_app, c_loc, c_pat, c_cost = [], [], [], [], []
    r_app, r_sub, r_cores, r_pats, r_cost = [], [], [], [], []
    unservable = []
    n_c = 0
    for ai, a in enumerate(pf.apps):
        nc = a.n_cores
        ok = np.asarray(a.core_margin, float) >= tau
        ok0 = ok.copy()
        # options per group after the margin floor
        gp, gc = {}, {}
        dead_by = {}
        for s in SUBSYSTEMS:
            p, cst, mar, grp, n_g = pre.groups[ai][s]
            keep = mar >= tau
            p, cst, grp = p[keep], cst[keep], grp[keep]
            first = np.ones(len(p), bool)                         # per group and pattern the cheapest kept
            first[1:] = (p[1:] != p[:-1]) | (grp[1:] != grp[:-1])
            p, cst, grp = p[first], cst[first], grp[first]
            cut = np.searchsorted(grp, np.arange(n_g + 1))
            gp[s] = [p[cut[i]:cut[i + 1]] for i in range(n_g)]
            gc[s] = [cst[cut[i]:cut[i + 1]] for i in range(n_g)]
            g = np.asarray(a.group[s], np.int64)
            empty = cut[1:] == cut[:-1]
            dead = empty[g] if nc else np.zeros(0, bool)
            dead_by[s] = int(np.sum(dead & ok0))
            ok &= ~dead
        if not ok.any():
            unservable.append((ai, _why_unservable(a, dead_by, int(np.sum(np.asarray(a.core_margin) >= tau)),
                                              min_margin is not None)))
            continue
        inst_a = len(app_index)
        app_index.append(ai)
        loc = np.flatnonzero(ok)
        codes = np.stack([_glob(offset, f, np.asarray(a.core_parts[f])[loc]) for f in CORE_FAMILIES], axis=1)
        c_app.append(np.full(len(loc), inst_a))
        c_loc.append(loc)
        c_pat.append(pats.many(codes))
        c_cost.append(np.asarray(a.core_cost_eur, float)[loc] * float(a.volume))
        gl = np.arange(n_c, n_c + len(loc))
        n_c += len(loc)
        for si, s in enumerate(SUBSYSTEMS):
            g = np.asarray(a.group[s], np.int64)[loc]
            merged: dict = {}
            for gid in np.unique(g):
                key = gp[s][gid].tobytes()
                if key in merged:
                    r = merged[key]
                    r_cores[r] = np.concatenate([r_cores[r], gl[g == gid]])
                    continue
                merged[key] = len(r_app)
                r_app.append(inst_a)
                r_sub.append(si)
                r_cores.append(gl[g == gid])
                r_pats.append(gp[s][gid])
                r_cost.append(gc[s][gid])

    def cat(xs, dt):
        return np.concatenate(xs).astype(dt) if xs else np.zeros(0, dt)
    work = Work(pf=pf, objective=objective, part_offset=offset, part_family=part_family, part_weight=part_weight,
                part_fixed_cost=part_fixed, patterns=pats.list, option_pattern=option_pattern,
                app_index=np.array(app_index, np.int64), core_app=cat(c_app, np.int64), core_local=cat(c_loc, np.int64),
                core_pattern=cat(c_pat, np.int64), core_cost=cat(c_cost, float),
                core_alive=np.ones(n_c, bool), row_app=r_app, row_sub=r_sub, row_cores=r_cores, row_pats=r_pats,
                row_cost=r_cost, row_alive=[True] * len(r_app), unservable=unservable)
    return work
