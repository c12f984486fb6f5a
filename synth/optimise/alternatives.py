"""Ranked alternatives: the K best designs of an application in objective order, what differs between them and
their margins (``synth design --top K``, ``Result.alternatives``).

The catalog product decomposes (:mod:`synth.design.space`): given a core, a design's additive score
(standardisation, cost) is the core's plus one option per subsystem, and its margin the smallest of theirs.
The K best of a sum (or of a minimum) of independent lists are among the K best of each list, so per core the
K best options of each subsystem are merged pairwise, keeping the K best at each merge (exact: a combination
outside a merge's K best is beaten by K combinations inside it), and the cores' lists are merged again. The
pool holds the K best by the additive score and the K best by the margin; it is ranked by the objective's own
key (:meth:`synth.optimise.objectives.Objective.key`). For additive objectives and the margin alone the ranking
is exact; a lexicographic or weighted mix of both is ranked within that pool.

Every alternative is verified alone (:func:`synth.design.verify.verify`, the same checks as the optimum), and the
first is the optimum the solver returned.

>>> from synth.scenes.demo import default_input
>>> from synth.optimise import solve
>>> r = solve(default_input(), "standard")
>>> alts = ranked(default_input(), r, 3)
>>> [a["rank"] for a in alts], alts[0]["parts"] == r.parts, alts[1]["objectives"]["standard"] >= 2
([1, 2, 3], True, True)
"""

from __future__ import annotations

import heapq
import math

import numpy as np

from synth.design.space import SUBSYSTEMS
from synth.design.combine import combine
from synth.optimise.solvers.enumerate import weights_vec
from synth.design.evaluate import Settings
from synth.errors import InputError, Problem
from synth.optimise.product import evaluate
from synth.optimise.objectives import Objective
from synth.optimise.answer import build_result, design_margin

__all__ = ["ranked", "MAX_TOP"]

#: the largest --top K (each alternative is verified alone)
MAX_TOP = 50


def _best(lists: list, k: int, combine, reverse: bool) -> list:
    """The ``k`` best combinations of one item per list (``(value, index)`` items; ``combine`` of two values),
    merged pairwise; returns ``(value, (index, ...))``."""
    acc = [(v, (i,)) for v, i in lists[0]]
    for nxt in lists[1:]:
        pool = [(combine(a, b), ia + (ib,)) for a, ia in acc for b, ib in nxt]
        acc = (heapq.nlargest if reverse else heapq.nsmallest)(k, pool, key=lambda x: x[0])
    return acc


def _pool(ev, weights: dict, k: int) -> set:
    """``{(core position, options tuple)}``: the ``k`` best designs of ``ev`` by the additive score ``weights``
    (ties: the larger margin) and the ``k`` best by the smallest (objective) margin, over the evaluated cores."""
    ok_core = ev.core_feasible()[ev.rows]
    score = {s: weights_vec(ev.score[s], weights) for s in SUBSYSTEMS}
    core_score = weights_vec(ev.score_core, weights)
    core_margin = ev.core_margin()
    by_score, by_margin = [], []
    for r, pos in enumerate(ev.rows):
        if not ok_core[r]:
            continue
        feas = {s: np.flatnonzero(ev.subs[s].feasible[r]) for s in SUBSYSTEMS}
        if any(not len(f) for f in feas.values()):
            continue
        # by the score, ties by the larger margin: values (score, -margin) combine as (sum, max)
        lists = [[((float(core_score[pos]), -float(core_margin[pos])), int(pos))]]
        mlists = [[(float(core_margin[pos]), int(pos))]]
        for s in SUBSYSTEMS:
            f = feas[s]
            sc, mg = score[s][f], ev.subs[s].margin[r, f]
            top = f[np.lexsort((-mg, sc))[:k]]
            lists.append([((float(score[s][o]), -float(ev.subs[s].margin[r, o])), int(o)) for o in top])
            topm = f[np.argsort(-mg, kind="stable")[:k]]
            mlists.append([(float(ev.subs[s].margin[r, o]), int(o)) for o in topm])
        by_score += _best(lists, k, lambda a, b: (a[0] + b[0], max(a[1], b[1])), False)
        by_margin += _best(mlists, k, min, True)
    pick = heapq.nsmallest(k, by_score, key=lambda x: x[0]) + heapq.nlargest(k, by_margin, key=lambda x: x[0])
    return {idx for _, idx in pick}


def _differs(first: dict, parts: dict) -> dict:
    """The part keys whose value differs from the first design's: ``{key: [first, this]}``."""
    out = {}
    for key, v in parts.items():
        a = first.get(key)
        same = (isinstance(v, (int, float)) and isinstance(a, (int, float)) and math.isclose(float(a), float(v),
                                                                                            abs_tol=1e-9)) or a == v
        if not same:
            out[key] = [a, v]
    return out


def ranked(d, result, k: int, *, settings=None, pin_inputs=False, objective=None) -> list:
    """The ``k`` best designs of input ``d`` in objective order, the first being ``result`` (the optimum), each
    ``{"rank", "parts", "objectives", "margin", "binding", "verdict", "differs"}`` (``margin``: the smallest
    margin, a fraction; ``binding``: the check that sets it; ``differs``: part -> [the optimum's, this one's]).
    ``pin_inputs``: the parts kept in the search (as the synthesis kept them). An infeasible ``result`` has none."""
    if not (isinstance(k, int) and not isinstance(k, bool) and 1 <= k <= MAX_TOP):
        raise InputError(Problem("--top", k, f"an integer from 1 to {MAX_TOP}"))
    if not result.parts or result.status not in ("optimal", "feasible", "baseline"):
        return []
    settings = settings or Settings.from_saved(result.settings, result.rules)
    obj = objective or Objective.parse(result.objective or "standard")
    obj = obj if isinstance(obj, Objective) else Objective.parse(obj)
    ev = evaluate(d, settings, pin_inputs=pin_inputs)
    pool = _pool(ev, obj.additive_weights() or {"cost": 1.0}, k)
    designs = []
    row_of = {int(p): r for r, p in enumerate(ev.rows)}
    core_margin = ev.core_margin()
    for idx in pool:
        pos, options = idx[0], dict(zip(SUBSYSTEMS, idx[1:]))
        margin = combine(float(core_margin[pos]), [float(ev.subs[s].margin[row_of[pos], o]) for s, o in options.items()])
        designs.append((obj.key(ev.objective_values(pos, options, margin)) + (-margin,), pos, options))
    designs.sort(key=lambda x: x[0])  # ties of the objective: the larger margin first
    out = [_entry(1, result, result.parts, design_margin)]
    for _, pos, options in designs:
        if len(out) >= k:
            break
        parts = ev.parts(pos, options)
        if parts == result.parts:
            continue
        r = build_result(ev, pos, options, status="alternative", solver=result.solver, objective=obj, stats={},
                         detail=False)
        out.append(_entry(len(out) + 1, r, result.parts, design_margin))
    return out


def _entry(rank: int, r, first: dict, design_margin) -> dict:
    binds = r.binding(1)
    return {"rank": rank, "parts": dict(r.parts), "objectives": dict(r.objectives),
            "margin": design_margin(r), "binding": binds[0].label if binds else "", "verdict": r.verdict,
            "differs": _differs(first, r.parts)}
