"""Greedy platform: the baseline the MILP is measured against, and its warm start.

1. Applications in order of difficulty (the largest increment of the cheapest design on
   an empty platform first). Each takes its cheapest design *given the parts already
   chosen*: a part already in the platform is free, a new one costs its weight (variants
   objective) or its per-variant fixed cost plus the design's unit cost x volume (cost
   objective). Parts of the core and of the subsystems belong to distinct families, so
   the increment of a core is its own plus the cheapest increment of each of its rows.
2. Reverse delete: parts are taken out one at a time (heaviest, then least used first)
   when every application stays served and the objective does not grow.

No guarantee of optimality; the MILP's gap to it is reported (``synth rationalise`` and
``benchmarks/bench_platform.py``).

>>> from synth.platform.synthetic import synthetic_portfolio
>>> from synth.platform.compile import compile_portfolio
>>> from synth.platform.assign import serve
>>> inst = compile_portfolio(synthetic_portfolio(5, seed=3), "variants").instance()
>>> y = greedy(inst, "variants")
>>> bool(serve(inst, y)[0].all())
True
"""

from __future__ import annotations

import numpy as np

from formulations.platform import PlatformInstance
from synth.platform.assign import objective_value, serve

__all__ = ["greedy"]


def _increments(inst: PlatformInstance, y: np.ndarray, price: np.ndarray) -> np.ndarray:
    pid = np.repeat(np.arange(inst.n_patterns), inst.pattern_len())
    return np.bincount(pid, weights=(price * ~y)[inst.pattern_parts], minlength=inst.n_patterns)


def _best_core(inst, a_cores, a_rows, core_rows, inc, cost_obj):
    """Cheapest increment over the cores ``a_cores`` of one application; ``(core, {row: option entry})``."""
    best_row = {}
    rval = {}
    for r in a_rows:
        lo, hi = inst.row_opt_ptr[r], inst.row_opt_ptr[r + 1]
        v = inc[inst.row_opt_pattern[lo:hi]] + (inst.row_opt_cost[lo:hi] if cost_obj else 0.0)
        i = int(np.argmin(v))
        best_row[r], rval[r] = lo + i, float(v[i])
    val = inc[inst.core_pattern[a_cores]] + (inst.core_cost[a_cores] if cost_obj else 0.0)
    for rows in core_rows:
        val = val + np.array([rval[r] if r >= 0 else 0.0 for r in rows[a_cores]])
    c = int(np.argmin(val))
    return a_cores[c], float(val[c]), best_row


def greedy(inst: PlatformInstance, objective: str = "variants", *, max_rounds: int = 2) -> np.ndarray:
    """A platform (bool per part of ``inst``) serving every application of ``inst``."""
    cost_obj = objective == "cost"
    price = (inst.part_fixed_cost if cost_obj else inst.part_weight).astype(float)
    J, C, R = inst.n_parts, len(inst.core_app), len(inst.row_app)
    n_sub = int(inst.row_sub.max()) + 1 if R else 0
    core_rows = [np.full(C, -1) for _ in range(n_sub)]
    r_of = np.repeat(np.arange(R), np.diff(inst.row_core_ptr))
    for s in range(n_sub):
        sel = inst.row_sub[r_of] == s
        core_rows[s][inst.row_core[sel]] = r_of[sel]
    app_c = np.searchsorted(inst.core_app, np.arange(inst.n_apps + 1))
    app_r = np.searchsorted(inst.row_app, np.arange(inst.n_apps + 1))   # rows are stored application by application
    y = np.zeros(J, bool)
    inc0 = _increments(inst, y, price)
    hard = np.array([_best_core(inst, np.arange(app_c[a], app_c[a + 1]), range(app_r[a], app_r[a + 1]), core_rows,
                                inc0, cost_obj)[1] for a in range(inst.n_apps)])
    order = np.argsort(-hard, kind="stable")
    parts_of = lambda k: inst.pattern_parts[inst.pattern_ptr[k]:inst.pattern_ptr[k + 1]]  # noqa: E731
    for a in order:
        inc = _increments(inst, y, price)
        c, _, best_row = _best_core(inst, np.arange(app_c[a], app_c[a + 1]), range(app_r[a], app_r[a + 1]),
                                    core_rows, inc, cost_obj)
        y[parts_of(inst.core_pattern[c])] = True
        for rows in core_rows:
            r = rows[c]
            if r >= 0:
                y[parts_of(inst.row_opt_pattern[best_row[r]])] = True
    # reverse delete
    best = objective_value(inst, y, objective)
    for _ in range(max_rounds):
        changed = False
        _, _, core = serve(inst, y)
        use = np.zeros(J)
        for c in core[core >= 0]:
            use[parts_of(inst.core_pattern[c])] += 1
        for j in sorted(np.flatnonzero(y), key=lambda j: (-price[j], use[j], j)):
            y[j] = False
            v = objective_value(inst, y, objective)
            if v <= best + 1e-9:
                best, changed = v, True
            else:
                y[j] = True
        if not changed:
            break
    return y
