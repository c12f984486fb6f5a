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

__all__ = ["Work", "Precompiled", "precompile", "compile_portfolio", "app_option_cost", "flat_groups", "end_to_end"]


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
    breaks: tuple | None = None  # (app volume, break ptr, qty, step): synth.platform.volume.pool_prices

    @property
    def n_parts(self) -> int:
        return int(len(self.part_family))

    def part_of(self, j: int) -> tuple:
        """``(family, code)`` of global part ``j``."""
        f = FAMILIES[int(self.part_family[j])]
        return f, int(j - self.part_offset[f])

    def pf_volume(self, a) -> np.ndarray:
        """The annual volume of instance application(s) ``a``."""
        vol = self.breaks[0] if self.breaks is not None else np.array([float(self.pf.apps[i].volume)
                                                                       for i in self.app_index])
        return vol[np.asarray(a, np.int64)]

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
            row_opt_cost=cat([self.row_cost[i] for i in rows], float),
            **({} if self.breaks is None else dict(zip(("app_volume", "break_ptr", "break_qty", "break_step"),
                                                       self.breaks))))


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


_I32 = np.iinfo(np.int32).max   # indices below this are held as int32 (asserted where made)


def end_to_end(xs: list, dtype, n: int) -> np.ndarray:
    """The 1-d arrays (or lists) ``xs`` end to end (``n`` entries; ``dtype``: as ``np.asarray`` takes it, then the
    result's): one concatenation, or each flattened first where one is not a flat sequence (the same values).

    >>> end_to_end([np.array([1, 2]), [3]], float, 3).tolist(), end_to_end([np.array([[1], [2]])], None, 2).tolist()
    ([1.0, 2.0, 3.0], [1, 2])
    """
    out = np.concatenate(xs)
    if out.ndim != 1 or len(out) != n:
        out = np.concatenate([np.asarray(x, dtype).reshape(-1) for x in xs])
    return out if dtype is None else out.astype(dtype, copy=False)


def flat_groups(pf: PortfolioFeasibility, s: str):
    """Every application's option groups of subsystem ``s`` one after the other: ``(idx, margin, cost, group,
    gptr)``, the options' indices, margins and unit costs (each application's own), the group of each (numbered over
    the whole portfolio) and where each application's groups start (``gptr[i]:gptr[i + 1]``)."""
    feas = [x for a in pf.apps for x in a.feasible[s]]
    gptr = np.r_[0, np.cumsum([len(a.feasible[s]) for a in pf.apps])].astype(np.int64)
    if not feas:
        z = np.zeros(0, np.int32)
        return z, np.zeros(0), np.zeros(0), z, gptr
    lens = [len(x) for x in feas]
    # no copy beyond the concatenations (at 10,000 applications a copy of one of these is 350 MB); option indices
    # and group numbers as int32 (half the memory; every use indexes with them or widens them to int64 first)
    assert len(pf.options[s][SUBSYSTEM_FAMILIES[s][0]]) < _I32 and len(feas) < _I32, "flat_groups: int32 overflow"
    idx = end_to_end(feas, None, sum(lens)).astype(np.int32)
    mar = end_to_end([m for a in pf.apps for m in a.option_margin[s]], float, sum(lens))
    grp = np.repeat(np.arange(len(feas), dtype=np.int32), lens)
    optr = np.r_[0, np.cumsum(lens)][gptr]
    cost = np.concatenate([app_option_cost(pf, a, s)[idx[optr[i]:optr[i + 1]]] for i, a in enumerate(pf.apps)])
    return idx, mar.astype(float, copy=False), cost.astype(float, copy=False), grp, gptr


@dataclass
class Precompiled:
    """What :func:`compile_portfolio` computes whatever the margin floor and objective: the options' patterns and,
    per subsystem, the feasible options of every (application, group) sorted by (pattern, cost) with their margins,
    the groups numbered across the portfolio one application after the other (a floor then keeps a subsequence:
    the sort of the kept options is the same); and the cores of every application, one after the other. The
    trade-off sweep compiles a portfolio once with :func:`precompile` and each floor from it."""

    pf: PortfolioFeasibility
    offset: dict
    part_family: np.ndarray
    part_fixed: np.ndarray
    patterns: _Patterns          # after the empty pattern and every option's pattern
    option_pattern: dict
    options: dict                # subsystem -> (patterns, costs x volume, margins, group, n_groups, app of each group)
    cores: dict                  # app, local, margin, cost (x volume), codes (global parts), group (subsystem -> group)
    assign_groups: dict | None = None   # synth.platform.assign.option_groups(pf)


def _by_key_then_cost(key: np.ndarray, cost: np.ndarray) -> np.ndarray:
    """``np.lexsort((cost, key))`` (by key, then cost, then position), by one stable sort of the keys and a
    lexsort of the runs of equal keys only (most keys are distinct: a group holds a pattern once).

    >>> _by_key_then_cost(np.array([3, 1, 3, 1, 2]), np.array([5.0, 2.0, 1.0, 2.0, 0.0])).tolist()
    [1, 3, 4, 2, 0]
    """
    order = np.argsort(key, kind="stable")
    k = key[order]
    dup = np.zeros(len(k), bool)
    if len(k) > 1:
        same = k[1:] == k[:-1]
        dup[1:] |= same
        dup[:-1] |= same
    at = np.flatnonzero(dup)
    if len(at):
        sub = order[at]
        order[at] = sub[np.lexsort((cost[sub], key[sub]))]
    return order


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
    apps = pf.apps
    cat = (lambda xs, dt: np.concatenate(xs).astype(dt) if len(xs) else np.zeros(0, dt))  # noqa: E731
    groups = {s: flat_groups(pf, s) for s in SUBSYSTEMS}      # also what the assignments read
    vol = np.array([float(a.volume) for a in apps])
    options, first_group = {}, {}
    for s in SUBSYSTEMS:
        idx, mar, cost, grp, first_group[s] = groups[s]
        n = int(first_group[s][-1])
        group_app = np.repeat(np.arange(len(apps)), np.diff(first_group[s])).astype(np.int64)
        cst = cost * vol[group_app][grp]
        p = option_pattern[s][idx]
        n_p = int(p.max(initial=0)) + 1
        assert n_p < _I32, "precompile: pattern ids beyond int32"
        p = p.astype(np.int32)
        # the key in int64: groups x patterns may exceed int32 (asserted below int64's range)
        assert (n + 1) * n_p < np.iinfo(np.int64).max, "precompile: group x pattern key beyond int64"
        order = _by_key_then_cost(grp.astype(np.int64) * n_p + p, cst)   # per group and pattern the cheapest first
        if len(order) and not (order[1:] > order[:-1]).all():   # else already in order (the main springs): no copies
            p, cst, mar = p[order], cst[order], mar[order]
        del order
        options[s] = (p, cst, mar, grp, n, group_app)
    n_c = [a.n_cores for a in apps]
    cores = {"app": np.repeat(np.arange(len(apps)), n_c).astype(np.int64),
             "local": cat([np.arange(n) for n in n_c], np.int64),
             "margin": cat([np.asarray(a.core_margin, float) for a in apps], float),
             "cost": cat([np.asarray(a.core_cost_eur, float) * float(a.volume) for a in apps], float),
             "codes": np.stack([_glob(offset, f, cat([np.asarray(a.core_parts[f]) for a in apps], np.int64))
                                for f in CORE_FAMILIES], axis=1).reshape(-1, len(CORE_FAMILIES)).astype(np.int64),
             "group": {s: cat([np.asarray(a.group[s], np.int64) + first_group[s][i] for i, a in enumerate(apps)],
                              np.int64) for s in SUBSYSTEMS}}
    return Precompiled(pf=pf, offset=offset, part_family=part_family, part_fixed=part_fixed, patterns=pats,
                       option_pattern=option_pattern, options=options, cores=cores,
                       assign_groups=groups)


def _glob(offset: dict, f: str, codes) -> np.ndarray:
    codes = np.asarray(codes)
    return np.where(codes < 0, -1, codes + offset[f])


def _core_patterns(pats: _Patterns, codes: np.ndarray, app: np.ndarray) -> np.ndarray:
    """Pattern id of each core (rows of ``codes``, grouped by application ``app``), new patterns numbered as
    :meth:`_Patterns.many` application by application numbers them: in order of first appearance, an application's
    own in the order of their sorted rows."""
    if not len(codes):
        return np.zeros(0, np.int64)
    uniq, inv = np.unique(codes, axis=0, return_inverse=True)
    inv = np.asarray(inv).reshape(-1)
    seq = np.unique(app * len(uniq) + inv) % len(uniq)             # the rows met, application by application
    u, at = np.unique(seq, return_index=True)
    ids = np.empty(len(uniq), np.int64)
    for k in u[np.argsort(at, kind="stable")]:
        ids[k] = pats.get(uniq[k])
    return ids[inv]


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
    n_apps, cores = len(pf.apps), pre.cores
    ok0 = cores["margin"] >= tau
    ok = ok0.copy()
    kept, dead_by = {}, {}
    for s in SUBSYSTEMS:                                          # options per group after the margin floor
        p, cst, mar, grp, n_g, _ = pre.options[s]
        keep = mar >= tau
        if not keep.all():                                        # (no floor: every option, no copies)
            p, cst, grp = p[keep], cst[keep], grp[keep]
        first = np.ones(len(p), bool)                             # per group and pattern the cheapest kept
        first[1:] = (p[1:] != p[:-1]) | (grp[1:] != grp[:-1])
        if not first.all():
            p, cst, grp = p[first], cst[first], grp[first]
        del keep, first
        cut = np.searchsorted(grp, np.arange(n_g + 1))
        kept[s] = (p, cst, cut)
        dead = (cut[1:] == cut[:-1])[cores["group"][s]]
        dead_by[s] = np.bincount(cores["app"][dead & ok0], minlength=n_apps)
        ok &= ~dead
    served = np.bincount(cores["app"][ok], minlength=n_apps) > 0
    n_ok0 = np.bincount(cores["app"][ok0], minlength=n_apps)
    unservable = [(int(ai), _why_unservable(pf.apps[ai], {s: int(dead_by[s][ai]) for s in SUBSYSTEMS},
                                            int(n_ok0[ai]), min_margin is not None))
                  for ai in np.flatnonzero(~served)]
    app_index = np.flatnonzero(served).astype(np.int64)
    inst = np.cumsum(served) - 1                                  # instance application of each application
    live = np.flatnonzero(ok)                                     # the cores kept, application by application
    c_app = inst[cores["app"][live]].astype(np.int64)
    gl = np.arange(len(live), dtype=np.int64)
    # rows: per application and subsystem one row per distinct option list of its cores' groups (in the order of
    # the first group holding it; the cores of merged groups one group after the other)
    r_a, r_s, r_rep, r_cores = [], [], [], []
    for si, s in enumerate(SUBSYSTEMS):
        p, cst, cut = kept[s]
        gg = cores["group"][s][live]
        ug = np.unique(gg)
        ids: dict = {}
        kid = np.array([ids.setdefault(p[cut[g]:cut[g + 1]].tobytes(), len(ids)) for g in ug], np.int64)
        ga = inst[pre.options[s][5][ug]]
        _, first, rinv = np.unique(ga * max(len(ids), 1) + kid, return_index=True, return_inverse=True)
        rinv = np.asarray(rinv).reshape(-1)
        core_row = rinv[np.searchsorted(ug, gg)]
        order = np.lexsort((gg, core_row))
        if len(first):
            r_cores.extend(np.split(gl[order], np.cumsum(np.bincount(core_row, minlength=len(first)))[:-1]))
        r_a.append(ga[first])
        r_s.append(np.full(len(first), si, np.int64))
        r_rep.append(ug[first])
    r_a, r_s, r_rep = (np.concatenate(x) for x in (r_a, r_s, r_rep))
    order = np.lexsort((r_rep, r_s, r_a))
    r_cores = [r_cores[i] for i in order]
    r_app, r_sub, r_rep = r_a[order].tolist(), r_s[order].tolist(), r_rep[order]
    r_pats, r_cost = [], []
    for si, g in zip(r_sub, r_rep.tolist()):
        p, cst, cut = kept[SUBSYSTEMS[si]]
        r_pats.append(p[cut[g]:cut[g + 1]])
        r_cost.append(cst[cut[g]:cut[g + 1]])
    c_pat = _core_patterns(pats, cores["codes"][live], c_app)
    n_c = len(live)
    c_loc, c_cost = cores["local"][live], cores["cost"][live]

    work = Work(pf=pf, objective=objective, part_offset=offset, part_family=part_family, part_weight=part_weight,
                part_fixed_cost=part_fixed, patterns=pats.list, option_pattern=option_pattern,
                app_index=app_index, core_app=c_app, core_local=c_loc, core_pattern=c_pat, core_cost=c_cost,
                core_alive=np.ones(n_c, bool), row_app=r_app, row_sub=r_sub, row_cores=r_cores, row_pats=r_pats,
                row_cost=r_cost, row_alive=[True] * len(r_app), unservable=unservable)
    return work
