"""Infeasible inputs: the nearest design, what truly binds and by how much, and the smallest input relaxation.

* The **nearest design** maximises the smallest normalised margin over the
  whole catalog product (every core evaluated, nothing pruned, every
  non-advisory constraint counted): the design that misses the requirements by
  the least. Its **violated constraints** are listed with their margins (a
  margin of -0.35 on a stress means the stress is 35 % above its limit).
* **Relaxations**: for every input a designer can change that can relax a
  violated constraint (:data:`RELAXABLE`: space limits, lock-up pin, head
  diameter, active threads, travels, tolerances first; the specification
  values last, marked as such), the smallest change that makes the
  application feasible, found by bisection on that one input (each probe is
  one exhaustive feasibility check); each relaxation found is verified again.

>>> from synth.data import case_path
>>> from synth.schema import load_input
>>> r = diagnose(load_input(case_path("case1")), relax=False)
>>> r.status, len(r.diagnosis["violated"]) > 0
('infeasible', True)
"""

from __future__ import annotations

import dataclasses
import time

import numpy as np

from synth.design.evaluate import Settings
from synth.design.space import SUBSYSTEMS
from synth.errors import InputError
from synth.optimise.evaluate import evaluate
from synth.schema import FIELDS, field_by_name

__all__ = ["RELAXABLE", "nearest_design", "is_feasible", "relaxations", "relaxations_batch", "probe_batch",
           "diagnose"]

#: input field -> (direction: +1 raise / -1 lower, the constraints it relaxes, a specification value?), derived from
#: the fields' own declaration (:attr:`synth.schema.Field.relax`, ``relaxes``, ``owner``)
RELAXABLE = {f.name: (f.relax, f.relaxes, f.owner == "specification") for f in FIELDS if f.relax}


def is_feasible(d, settings: Settings = Settings(), *, pin_inputs: bool = False) -> bool:
    """Whether any design of the catalog product (``pin_inputs``: with the parts the input names) meets every
    constraint for input ``d``."""
    from synth.optimise.solvers.enumerate import max_margin, tables
    try:
        ev = evaluate(d, settings, pin_inputs=pin_inputs)
    except InputError:
        return False
    return bool(len(ev.rows)) and max_margin(tables(ev, {"cost": 1.0})) > -np.inf


def nearest_design(ev):
    """``(core position, options, min_margin)`` of the design with the largest smallest margin (all constraints)."""
    core_m = np.where(np.ones(len(ev.cores), bool), ev.core_min_margin(), -np.inf)[ev.rows]
    best_k = {}
    for s in SUBSYSTEMS:
        sub = ev.subs[s]
        m = np.where(sub.available, sub.min_margin, -np.inf)
        best_k[s] = np.argmax(m, axis=1)
        core_m = np.minimum(core_m, m[np.arange(len(m)), best_k[s]])
    r = int(np.argmax(core_m))
    return int(ev.rows[r]), {s: int(best_k[s][r]) for s in SUBSYSTEMS}, float(core_m[r])


def reference_probe(pin_inputs: bool = False):
    """The reference feasibility probe ``probe(d, changes, settings) -> bool`` (one exhaustive check)."""
    def probe(d, changes: dict, settings):
        try:
            return is_feasible(dataclasses.replace(d, **changes), settings, pin_inputs=pin_inputs)
        except InputError:
            return False
    return probe


def _consistent(d, changes: dict) -> bool:
    """Whether input ``d`` with ``changes`` still meets the schema's cross-field rules (a bolt head wider than
    the support's bore, a support bore narrower than its outer diameter, ...): a probe outside them is not an
    input a user could give."""
    from synth.schema import _consistency
    problems: list = []
    _consistency({**vars(d), **changes}, problems)
    return not problems


def _within_rules(d, far: dict, steps: int = 30) -> float:
    """The largest fraction ``lam`` in [0, 1] of the move from ``d`` to ``far`` (field -> value) that keeps the
    cross-field rules (:func:`_consistent`; 1 when the whole move does), by bisection."""
    at = (lambda lam: {n: getattr(d, n) + lam * (v - getattr(d, n)) for n, v in far.items()})  # noqa: E731
    if _consistent(d, at(1.0)):
        return 1.0
    good, bad = 0.0, 1.0
    for _ in range(steps):
        mid = 0.5 * (good + bad)
        good, bad = (mid, bad) if _consistent(d, at(mid)) else (good, mid)
    return good


def _far(d, name, sign):
    """The far probe of input ``name``: x2 (raise) or /4 (lower) within the schema's range of the field, and
    short of the first cross-field rule it would break."""
    cur = getattr(d, name)
    f = field_by_name(name)
    if sign > 0:
        far = min(2.0 * cur, f.hi) if np.isfinite(f.hi) else 2.0 * cur
    else:
        far = max(0.25 * cur, f.lo if np.isfinite(f.lo) else 0.0)
        far = f.lo + 1e-3 * abs(cur) if f.lo_open and far <= f.lo else far
    return cur + _within_rules(d, {name: far}) * (far - cur)


def _far_joint(d, cands: dict) -> dict:
    """The far probe of all inputs ``cands`` moved together (each :func:`_far`), short of the cross-field rules."""
    far = {n: _far(d, n, s) for n, s in cands.items()}
    lam = _within_rules(d, far)
    return {n: getattr(d, n) + lam * (v - getattr(d, n)) for n, v in far.items()}


def _candidates(d, violated) -> dict:
    return {n: sign for n, (sign, rel, _) in RELAXABLE.items()
            if getattr(d, n, None) is not None and set(rel) & set(violated)}


def _single(d, name, good, violated) -> dict:
    cur = getattr(d, name)
    return {"inputs": {name: {"from": cur, "to": round(float(good), 4)}},
            "relative_change": round(abs(good - cur) / max(abs(cur), 1e-9), 4),
            "specification": RELAXABLE[name][2],
            "relaxes": sorted(set(RELAXABLE[name][1]) & set(violated))}


def _joint(d, cands, far, good, violated) -> dict:
    at = {n: getattr(d, n) + good * (far[n] - getattr(d, n)) for n in cands}
    return {"inputs": {n: {"from": getattr(d, n), "to": round(float(v), 4)} for n, v in at.items()},
            "relative_change": round(good, 4),
            "specification": any(RELAXABLE[n][2] for n in cands), "relaxes": sorted(set(violated))}


def _order(out: list) -> list:
    return sorted(out, key=lambda r: (r["specification"], r["relative_change"]))


def relaxations(d, violated: list, *, settings: Settings = Settings(), steps: int = 7, probe=None,
                pin_inputs: bool = False) -> list:
    """Smallest input changes that make ``d`` feasible, for the inputs that relax ``violated``.

    First each input alone (bisection between its value and a far value:
    x2 or /4 within the schema's range); when no single input suffices, all
    the relevant inputs together, moved by a common fraction of their range
    (one entry with several ``"inputs"``). Design inputs come before the
    specification values (``"specification": True``). ``probe(d, changes,
    settings) -> bool`` replaces the feasibility check; ``pin_inputs`` keeps the parts the input names in it.
    """
    _probe = probe or reference_probe(pin_inputs)
    out = []
    cands = _candidates(d, violated)
    for name, sign in cands.items():
        cur, far = getattr(d, name), _far(d, name, sign)
        if not _probe(d, {name: far}, settings):
            continue
        good, bad = far, cur
        for _ in range(steps):
            mid = 0.5 * (good + bad)
            if _probe(d, {name: mid}, settings):
                good = mid
            else:
                bad = mid
        out.append(_single(d, name, good, violated))
    if not out and len(cands) > 1:
        far = _far_joint(d, cands)

        def at(lam):
            return {n: getattr(d, n) + lam * (far[n] - getattr(d, n)) for n in cands}
        if _probe(d, at(1.0), settings):
            good, bad = 1.0, 0.0
            for _ in range(steps):
                mid = 0.5 * (good + bad)
                good, bad = (mid, bad) if _probe(d, at(mid), settings) else (good, mid)
            out.append(_joint(d, cands, far, good, violated))
    return _order(out)


def probe_batch(settings: Settings = Settings(), spring_engine: str = "numba", *, pin_inputs: bool = False):
    """A batched feasibility probe: ``probe([(d, changes), ...]) -> [bool, ...]``, every probe of a bisection
    step in one vectorised feasibility search (:func:`synth.optimise.batch.any_feasible`); the same answers as
    the reference probe (``is_feasible`` of the changed input; an input the physics refuses is not feasible)."""
    from synth.optimise.batch import any_feasible

    def probe(items):
        return any_feasible([dataclasses.replace(d, **ch) for d, ch in items], settings, spring_engine=spring_engine,
                            pin_inputs=pin_inputs)
    return probe


def relaxations_batch(ds: list, violated: list, *, settings: Settings = Settings(), steps: int = 7,
                      probe=None) -> list:
    """:func:`relaxations` of many applications at once: per application the same candidate inputs, the same
    far probe and the same bisection, hence the same relaxations; but each step probes every pending
    (application, input) pair together (``probe``, default :func:`probe_batch`): 1 + ``steps`` probe rounds for
    the inputs alone, 1 + ``steps`` for the inputs together, whatever the number of applications."""
    probe = probe or probe_batch(settings)
    cands = [_candidates(d, v) for d, v in zip(ds, violated)]
    out: list = [[] for _ in ds]
    pairs = [(i, name, getattr(ds[i], name), _far(ds[i], name, sign)) for i, c in enumerate(cands)
             for name, sign in c.items()]
    ok = probe([(ds[i], {name: far}) for i, name, _, far in pairs]) if pairs else []
    live = [(i, name, far, cur) for (i, name, cur, far), good in zip(pairs, ok) if good]  # (i, name, good, bad)
    for _ in range(steps):
        mids = [0.5 * (good + bad) for _, _, good, bad in live]
        res = probe([(ds[i], {name: mid}) for (i, name, _, _), mid in zip(live, mids)]) if live else []
        live = [(i, name, mid, bad) if r else (i, name, good, mid)
                for (i, name, good, bad), mid, r in zip(live, mids, res)]
    found = {(i, name): good for i, name, good, _ in live}
    for i, c in enumerate(cands):  # in the candidates' order, as relaxations() appends
        for name in c:
            if (i, name) in found:
                out[i].append(_single(ds[i], name, found[(i, name)], violated[i]))
    joint = [i for i, c in enumerate(cands) if not out[i] and len(c) > 1]
    far = {i: _far_joint(ds[i], cands[i]) for i in joint}

    def at(i, lam):
        return {n: getattr(ds[i], n) + lam * (far[i][n] - getattr(ds[i], n)) for n in cands[i]}
    ok = probe([(ds[i], at(i, 1.0)) for i in joint]) if joint else []
    live = [(i, 1.0, 0.0) for i, good in zip(joint, ok) if good]
    for _ in range(steps):
        mids = [0.5 * (good + bad) for _, good, bad in live]
        res = probe([(ds[i], at(i, mid)) for (i, _, _), mid in zip(live, mids)]) if live else []
        live = [(i, mid, bad) if r else (i, good, mid) for (i, good, bad), mid, r in zip(live, mids, res)]
    for i, good, _ in live:
        out[i].append(_joint(ds[i], cands[i], far[i], good, violated[i]))
    return [_order(o) for o in out]


def _no_core(d):
    """The problem of an input whose pinned parts (``--pin-inputs``) leave no core design of the catalogs."""
    from synth.design.space import space
    from synth.errors import Problem
    t = space().tables["core"]
    classes = ", ".join(f"{x:g}" for x in sorted(set(map(float, t["pivot_class_diameter_mm"]))))
    return Problem("--pin-inputs", f"pivot class {d.pivot_class_diameter_mm}, bushing thickness "
                                   f"{d.pivot_bushing_radial_thickness_mm}",
                   f"parts the catalogs hold (pivot classes {classes} mm): no design of the catalogs keeps these")


def diagnose(d, ev=None, *, solver: str = "enumerate", objective=None, stats: dict | None = None,
             relax: bool = True, settings: Settings = Settings(), exhaustive: bool = False, batch=None,
             pin_inputs: bool = False):
    """A :class:`~synth.design.result.Result` with ``status="infeasible"`` and its ``diagnosis``.

    The nearest design and the relaxations come from the batched searches (:meth:`synth.optimise.batch.Batch.nearest`,
    :func:`relaxations_batch` with the numpy spring twins) unless ``exhaustive=True`` or an evaluation ``ev`` of
    every core is given: then from the exhaustive evaluation and one probe at a time (the reference; the same
    answer). ``pin_inputs``: the search the solver ran kept the parts the input names, and so do the nearest
    design and the relaxations (every solver answers the same question).
    """
    from synth.optimise.result import build_result
    t0 = time.perf_counter()
    obj = objective if objective is not None else "standard,cost"
    if exhaustive or ev is not None:
        ev = ev if ev is not None and len(ev.rows) == len(ev.cores) else evaluate(d, settings, prune=False,
                                                                                  pin_inputs=pin_inputs)
        if not len(ev.rows):
            raise InputError(_no_core(d))
        pos, options, _ = nearest_design(ev)
        res = build_result(ev, pos, options, status="infeasible", solver=solver, objective=obj, stats=stats or {})
    else:
        from synth.optimise.batch import Batch
        b = batch if batch is not None else Batch([d], settings, spring_engine="numpy", pin_inputs=pin_inputs)
        near = b.nearest([0])[0]
        if near is None:  # no core at all: as the exhaustive search (its argmax of nothing raises)
            return diagnose(d, solver=solver, objective=objective, stats=stats, relax=relax, settings=settings,
                            exhaustive=True, pin_inputs=pin_inputs)
        res = build_result(b.view(0), near[0], near[1], status="infeasible", solver=solver, objective=obj,
                           stats=stats or {})
    violated = [c for c in res.failed()]
    ids = [c.id for c in violated]
    if not relax:
        rel = []
    elif exhaustive or ev is not None:
        rel = relaxations(d, ids, settings=settings, pin_inputs=pin_inputs)
    else:
        rel = relaxations_batch([d], [ids], settings=settings,
                                probe=probe_batch(settings, spring_engine="numpy", pin_inputs=pin_inputs))[0]
    res.diagnosis = {
        "message": "no design of the catalog product meets every constraint; the nearest design is shown",
        "violated": [{"constraint": c.id, "label": c.label, "step": c.step, "margin": c.margin}
                     for c in sorted(violated, key=lambda c: c.margin)],
        "relaxations": rel,
    }
    res.stats["diagnosis_time_s"] = time.perf_counter() - t0
    return res
