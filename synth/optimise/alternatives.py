"""Ranked alternatives: the K best designs of an application that a buyer or a designer would call different,
in objective order, what differs between them and their margins (``synth design --top K``,
``Result.alternatives``); for an infeasible application its K nearest designs (the near misses).

**What counts as different.** Two designs are the same alternative when they agree on every *distinct* part key
(:data:`DISTINCT_KEYS`, a setting: ``distinct=``): the catalog parts (ball bearing, pivot class, pivot bushing
supplier and length, damper pad, endcap spacer (with or without the cone spring), main-spring material and wire,
bolt format, head and property class). The main spring's mean body diameter (its coil count follows) and the cone
spring's ratios and diameters (:data:`DIMENSION_KEYS`) are dimensions of the same designed part, not other parts:
designs that differ only there collapse to their best representative (the best by the objective). Each
alternative thus differs from every earlier one in at least one distinct key.

**How they are found.** The catalog product decomposes (:mod:`synth.design.space`): given a core, a design's
additive score (standardisation, cost) is the core's plus one option per subsystem, and its margin the smallest of
theirs (:func:`synth.design.combine.combine`). Per core, each subsystem's options are collapsed to the best option
of each distinct signature, the K best of those kept, and the lists merged pairwise keeping the K best at each
merge (exact: a combination outside a merge's K best is beaten by K distinct combinations inside it); the cores'
lists are merged again. The pool holds the K best by the additive score and the K best by the margin; it is ranked
by the objective's own key (:meth:`synth.optimise.objectives.Objective.key`), ties by the larger margin. For
additive objectives and the margin alone the ranking is exact; a lexicographic or weighted mix of both is ranked
within that pool.

**Near misses.** An infeasible application has no alternative; its K nearest designs are ranked by the one key of
near designs (:func:`synth.design.combine.near_key`): the largest smallest margin of every counted check
(:attr:`synth.design.assessment.Assessment.margin_min`), then the largest second smallest, then the fewest failing
checks, then the catalog order, each design's figures joined from its core's and options'
(:meth:`synth.optimise.product.Evaluation.near`), distinct as above. Many designs tie on the first (one check binds
them all by the same amount: case 1's every bolt misses the under-head pressure by 35.2 %, 246 million designs tie
there). The best under the whole key is the diagnosis's nearest design (:meth:`synth.optimise.product.Evaluation.nearest`,
exact over the whole product), so it comes first for every K; the others are the best by the key of a pool of
:data:`NEAR_POOL` times K designs by the smallest margin (ties by the objective): the key is exact within that pool.
Each comes with what binds and by how much, and every check it fails.

Every design listed is verified alone (:func:`synth.design.verify.verify`: the same checks and the same
assessment as the optimum; its margin is the verified one), and the first is the design the solver returned.

>>> from synth.scenes.demo import default_input
>>> from synth.optimise import solve
>>> r = solve(default_input(), "standard")
>>> alts = ranked(default_input(), r, 3)
>>> [a["rank"] for a in alts], alts[0]["parts"] == r.parts, alts[1]["parts"] != r.parts
([1, 2, 3], True, True)
>>> len({signature(a["parts"]) for a in alts})
3
"""

from __future__ import annotations

import heapq
import itertools
import math

import numpy as np

from synth.design.space import PART_KEYS, PART_KEYS_BY_TABLE, SUBSYSTEMS
from synth.design.combine import combine, near_key
from synth.optimise.solvers.enumerate import weights_vec
from synth.design.evaluate import Settings
from synth.errors import InputError, Problem
from synth.optimise.product import evaluate
from synth.optimise.objectives import FALLBACK_WEIGHTS, Objective
from synth.optimise.answer import build_result, design_margin

__all__ = ["ranked", "signature", "distinct_keys", "MAX_TOP", "NEAR_POOL", "DISTINCT_KEYS", "DIMENSION_KEYS",
           "best_combinations"]

#: the largest --top K (each alternative is verified alone)
MAX_TOP = 50
#: near misses: the pool of candidates verified is this many times K (at most :data:`MAX_TOP`), so that designs
#: tying on the binding check can be ordered by the next one (:func:`synth.design.combine.near_key`)
NEAR_POOL = 4
#: part keys that are a dimension of a part, not another part: designs differing only in them are one alternative
#: (the main spring's mean body diameter, its coil count following; the cone spring's variant, a point of the
#: search grid of its ratios and diameters, :func:`synth.design.space.cone_variants`: it is designed, not bought)
DIMENSION_KEYS = ("main_spring_mean_body_diameter_mm", "cone_spring_aspect_ratio", "cone_spring_deflection_ratio",
                  "cone_spring_external_diameter_mm", "cone_spring_internal_diameter_mm")
#: the part keys that make two designs different alternatives (the default of ``distinct=``)
DISTINCT_KEYS = tuple(k for k in PART_KEYS if k not in DIMENSION_KEYS)
#: the option-table column that identifies a part key given the core (the cone spring's diameters are stored
#: relative to the core's bounds: :func:`synth.design.verify.parts_of_rows`)
_COLUMN = {"cone_spring_external_diameter_mm": "cone_spring_de_reduction_mm",
           "cone_spring_internal_diameter_mm": "cone_spring_di_increase_mm"}


def distinct_keys(keys=None) -> tuple:
    """The distinct part keys (:data:`DISTINCT_KEYS` when ``keys`` is None), checked: each a part key."""
    if keys is None:
        return DISTINCT_KEYS
    keys = tuple(k.strip() for k in (keys.split(",") if isinstance(keys, str) else keys) if k.strip())
    bad = [k for k in keys if k not in PART_KEYS]
    if bad or not keys:
        raise InputError(Problem("--distinct", bad[0] if bad else "", "part keys from " + ", ".join(PART_KEYS)))
    return tuple(k for k in PART_KEYS if k in keys)


def signature(parts: dict, keys=DISTINCT_KEYS) -> tuple:
    """A design's identity as an alternative: its values of the distinct part ``keys`` (numbers to 1e-6)."""
    return tuple(round(float(v), 6) if isinstance(v, (int, float)) else v for v in (parts.get(k) for k in keys))


def _codes(sp, table: str, keys: tuple) -> np.ndarray:
    """``(n_options,)`` integer codes of table ``table``'s options: equal codes, equal distinct keys (given the
    core); all 0 when the table holds no distinct key."""
    cols = [np.asarray(sp.tables[table][_COLUMN.get(k, k)]) for k in PART_KEYS_BY_TABLE[table] if k in keys]
    if not cols:
        return np.zeros(sp.n(table), dtype=np.int64)
    inv = np.stack([np.unique(c.astype(str) if c.dtype == object else c, return_inverse=True)[1].reshape(-1)
                    for c in cols], axis=1)
    return np.unique(inv, axis=0, return_inverse=True)[1].reshape(-1)


def _representatives(f: np.ndarray, order_keys: tuple, codes: np.ndarray, k: int) -> np.ndarray:
    """The ``k`` best options of ``f`` (ordered by ``order_keys``, :func:`numpy.lexsort`'s, last key first) after
    collapsing options with equal ``codes`` to their best."""
    order = f[np.lexsort(order_keys)]
    _, first = np.unique(codes[order], return_index=True)
    return order[np.sort(first)[:k]]


def best_combinations(lists: list, k: int, combine, reverse: bool) -> list:
    """The ``k`` best combinations of one item per list (``(value, index)`` items; ``combine`` of two values),
    merged pairwise; returns ``(value, (index, ...))``."""
    acc = [(v, (i,)) for v, i in lists[0]]
    for nxt in lists[1:]:
        pool = [(combine(a, b), ia + (ib,)) for a, ia in acc for b, ib in nxt]
        acc = (heapq.nlargest if reverse else heapq.nsmallest)(k, pool, key=lambda x: x[0])
    return acc


def _by_margin(core_value, sub_values: list) -> tuple:
    """A design's (margin, -score) from its core's and options' (margins combine by :func:`combine`, scores add)."""
    return combine(core_value[0], [v[0] for v in sub_values]), -(core_value[1] + sum(v[1] for v in sub_values))


def _pool(ev, weights: dict, k: int, keys: tuple, codes: dict, near: bool = False) -> set:
    """``{(core position, options tuple)}``: the ``k`` best distinct designs of ``ev`` by the additive score
    ``weights`` (ties: the larger margin) and the ``k`` best by the smallest (objective) margin (ties: the smaller
    score), over the evaluated cores. ``near``: the nearest designs (every core and available option, by the
    smallest margin of every counted check) instead."""
    score = {s: weights_vec(ev.score[s], weights) for s in SUBSYSTEMS}
    core_score = weights_vec(ev.score_core, weights)
    core_margin = ev.core_min_margin() if near else ev.core_margin()
    ok_core = np.ones(len(ev.rows), bool) if near else ev.core_feasible()[ev.rows]
    by_score, by_margin = [], []
    for r, pos in enumerate(ev.rows):
        if not ok_core[r]:
            continue
        sub = {s: ev.subs[s] for s in SUBSYSTEMS}
        feas = {s: np.flatnonzero(sub[s].available[r] if near else sub[s].feasible[r]) for s in SUBSYSTEMS}
        if any(not len(f) for f in feas.values()):
            continue
        margin = {s: (sub[s].min_margin if near else sub[s].margin)[r] for s in SUBSYSTEMS}
        lists = [[((float(core_score[pos]), -float(core_margin[pos])), int(pos))]]
        mlists = [[((float(core_margin[pos]), float(core_score[pos])), int(pos))]]
        for s in SUBSYSTEMS:
            f, sc, mg = feas[s], score[s], margin[s]
            if not near:  # by the score, ties by the larger margin: values (score, -margin) combine as (sum, max)
                top = _representatives(f, (-mg[f], sc[f]), codes[s], k)
                lists.append([((float(sc[o]), -float(mg[o])), int(o)) for o in top])
            topm = _representatives(f, (sc[f], -mg[f]), codes[s], k)
            mlists.append([((float(mg[o]), float(sc[o])), int(o)) for o in topm])
        if not near:
            by_score += best_combinations(lists, k, lambda a, b: (a[0] + b[0], max(a[1], b[1])), False)
        by_margin += best_combinations(mlists, k, lambda a, b: (min(a[0], b[0]), a[1] + b[1]), True)
    core_code = _codes(ev.space, "core", keys)[ev.cores]

    def first_distinct(items, key):  # the k best of distinct codes (cores may share the distinct keys)
        out, seen = [], set()
        for _, idx in sorted(items, key=key):
            sig = (core_code[idx[0]],) + tuple(codes[s][o] for s, o in zip(SUBSYSTEMS, idx[1:]))
            if sig not in seen:
                seen.add(sig)
                out.append(idx)
            if len(out) == k:
                break
        return out
    return set(first_distinct(by_score, lambda x: x[0]) + first_distinct(by_margin, lambda x: (-x[0][0], x[0][1])))


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


def ranked(d, result, k: int, *, settings=None, pin_inputs=False, objective=None, distinct=None) -> list:
    """The ``k`` best distinct designs of input ``d`` in objective order, the first being ``result`` (the
    optimum), or for an infeasible ``result`` the ``k`` nearest distinct designs by the one key of near designs, the
    first being ``result`` (the nearest design, the best under that key), each ``{"rank", "kind", "parts", "objectives", "margin", "binding",
    "binding_id", "failed", "verdict", "differs"}`` (``kind``: ``alternative`` or ``near miss``; ``margin``: the
    smallest margin, a fraction (an alternative: of the margin objective's checks, a near miss: of every counted
    check); ``binding``: the check that sets it; ``failed``: ``[{"id", "label", "margin"}]`` of the checks it
    fails; ``differs``: part -> [the first's, this one's]). ``distinct``: the part keys that make designs
    different (:data:`DISTINCT_KEYS`; see the module docstring). ``pin_inputs``: the parts kept in the search (as
    the synthesis kept them). A result without a design has none; a failing result of a solver that does not
    search the catalog (the flowchart) where the space holds feasible designs: the ``k`` best of those, ``differs``
    from the result."""
    if not (isinstance(k, int) and not isinstance(k, bool) and 1 <= k <= MAX_TOP):
        raise InputError(Problem("--top", k, f"an integer from 1 to {MAX_TOP}"))
    if not result.parts or result.status not in ("optimal", "feasible", "baseline", "infeasible"):
        return []
    keys = distinct_keys(distinct)
    settings = settings or Settings.from_saved(result.settings, result.rules)
    obj = objective or Objective.parse(result.objective or "standard")
    obj = obj if isinstance(obj, Objective) else Objective.parse(obj)
    # an infeasible result: every core evaluated; near misses unless the space holds a feasible design (a
    # solver that does not search it, the flowchart, may fail where the catalog passes)
    ev = evaluate(d, settings, pin_inputs=pin_inputs, prune=result.status != "infeasible")
    near = not ev.any_feasible()
    codes = {s: _codes(ev.space, s, keys) for s in SUBSYSTEMS}
    # near misses tie on one binding check (every bolt of case 1 misses the under-head pressure by 35.2 %): a
    # wider pool gives the one key of near designs (synth.design.combine.near_key) designs to order
    pool = _pool(ev, obj.additive_weights() or FALLBACK_WEIGHTS, min(NEAR_POOL * k, MAX_TOP) if near else k, keys,
                 codes, near=near)
    if near:
        return _near_misses(ev, pool, result, k, keys, obj)
    row_of = {int(p): r for r, p in enumerate(ev.rows)}
    core_margin = ev.core_margin()
    designs = []
    for idx in pool:
        pos, options = idx[0], dict(zip(SUBSYSTEMS, idx[1:]))
        subs = [ev.subs[s].margin[row_of[pos], o] for s, o in options.items()]
        margin = combine(float(core_margin[pos]), [float(m) for m in subs])
        designs.append((obj.key(ev.objective_values(pos, options, margin)) + (-margin,), pos, options))
    designs.sort(key=lambda x: x[0])  # ties of the objective: the larger margin first
    lead = not result.failed()  # the result leads the list (a failing result among feasible designs: not)
    others = (build_result(ev, pos, options, status="alternative", solver=result.solver, objective=obj, stats={},
                           detail=False)
              for pos, options in _distinct(ev, designs, signature(result.parts, keys) if lead else None, keys))
    head = [_entry(1, result, result.parts, False)] if lead else []
    return head + [_entry(len(head) + i + 1, r, result.parts, False)
                   for i, r in enumerate(itertools.islice(others, k - len(head)))]


def _near_misses(ev, pool: set, result, k: int, keys: tuple, obj) -> list:
    """The ``k`` nearest distinct designs of ``ev`` (every core evaluated) by the one key of near designs
    (:func:`synth.design.combine.near_key` of :meth:`~synth.optimise.product.Evaluation.near`, the catalog order
    last): the pool's and the nearest design (:meth:`~synth.optimise.product.Evaluation.nearest`, the best under
    the key: first); the design of ``result`` (the diagnosis's) is ``result`` itself."""
    pos, options, _ = ev.nearest()
    cands = {(pos, *(options[s] for s in SUBSYSTEMS))} | set(pool)
    row_of = {int(p): r for r, p in enumerate(ev.rows)}
    designs = sorted((near_key(ev.near(idx[0], dict(zip(SUBSYSTEMS, idx[1:]))), (row_of[idx[0]], *idx[1:])),
                      idx[0], dict(zip(SUBSYSTEMS, idx[1:]))) for idx in cands)
    own = signature(result.parts, keys)
    out = []
    for pos, options in itertools.islice(_distinct(ev, designs, None, keys), k):
        same = signature(ev.parts(pos, options), keys) == own
        r = result if same else build_result(ev, pos, options, status="near miss", solver=result.solver,
                                             objective=obj, stats={}, detail=False)
        out.append(_entry(len(out) + 1, r, result.parts, True))
    return out


def _distinct(ev, designs: list, first: tuple, keys: tuple):
    """``(core position, options)`` of ``designs`` (in order) whose signature differs from ``first``'s (None: no
    first) and every earlier one's."""
    seen = {first} - {None}
    for _, pos, options in designs:
        sig = signature(ev.parts(pos, options), keys)
        if sig not in seen:
            seen.add(sig)
            yield pos, options


def _near_margin(r) -> float:
    """A verified design's smallest margin of every counted check (what ranks the nearest designs)."""
    return float(r.assessment().margin_min[0])


def _entry(rank: int, r, first: dict, near: bool) -> dict:
    binds = r.binding(1)
    a = r.assessment()
    bid = str(a.binding_ids()[0])
    label = next((c.label for c in r.checks if c.id == bid), binds[0].label if binds else "")
    return {"rank": rank, "kind": "near miss" if near else "alternative", "parts": dict(r.parts),
            "objectives": dict(r.objectives), "margin": _near_margin(r) if near else design_margin(r),
            "binding": label, "binding_id": bid,
            "failed": [{"id": c.id, "label": c.label, "margin": float(c.margin)}
                       for c in sorted(r.failed(), key=lambda c: c.margin)],
            "verdict": r.verdict, "differs": _differs(first, r.parts)}
