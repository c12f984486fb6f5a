"""Infeasible inputs: the nearest design, what truly binds and by how much, and the smallest input relaxation.

* The **nearest design** maximises the smallest normalised margin over the
  whole catalog product (every core evaluated, nothing pruned, every
  non-advisory constraint counted): the design that misses the requirements by
  the least. Its **violated constraints** are listed with their margins (a
  margin of -0.35 on a stress means the stress is 35 % above its limit).
* **Relaxations**: for every input a designer can change that can relax a
  violated constraint (:func:`relaxable`: space limits, lock-up pin, head
  diameter, active threads, travels, tolerances first; the specification
  values last, marked as such), the smallest change that makes the
  application feasible, found by bisection on that one input (each probe is
  one exhaustive feasibility check); each relaxation found is verified again.

>>> from synth.data import case_path
>>> from synth.io.documents import load_input
>>> r = diagnose(load_input(case_path("case1")), relax=False)
>>> r.status, len(r.diagnosis["violated"]) > 0
('infeasible', True)
"""

from __future__ import annotations

import dataclasses
import itertools
import time

import numpy as np

from synth.design import constraints
from synth.design.evaluate import DEFAULT, Settings
from synth.design.space import space
from synth.errors import InputError, Problem
from synth.optimise.product import evaluate
from synth.schema import FIELDS, field_by_name, consistency
from synth.optimise.batch import any_feasible, designs_pass, Batch
from synth.optimise.answer import build_result
from synth.model.layout import layout_of

__all__ = ["relaxable", "nearest_design", "is_feasible", "relaxations", "relaxations_batch", "probe_batch",
           "diagnose", "layout_switch", "layout_switches", "reference_probe", "violated_of"]

_RELAXABLE: dict = {}


def relaxable() -> dict:
    """Input field -> (direction: +1 raise / -1 lower, the registry constraints it relaxes, a specification value?),
    in the schema's field order: the constraints that name the field in their ``relaxed_by``
    (:attr:`synth.design.constraints.Constraint.relaxed_by`, a check added with ``register`` included), the
    direction and the owner from the field's own declaration (:attr:`synth.schema.Field.relax`, ``owner``).

    >>> relaxable()["number_of_active_threads"]
    (1, ('thread',), False)
    """
    got = _RELAXABLE.get(constraints.version())
    if got is None:
        by_field: dict = {}
        for c in constraints.REGISTRY.values():
            for n in c.relaxed_by:
                by_field.setdefault(n, []).append(c.id)
        got = {f.name: (f.relax, tuple(by_field.get(f.name, ())), f.owner == "specification")
               for f in FIELDS if f.relax}
        _RELAXABLE.clear()
        _RELAXABLE[constraints.version()] = got
    return got


def is_feasible(d, settings: Settings = DEFAULT, *, pin_inputs: bool = False) -> bool:
    """Whether any design of the catalog product (``pin_inputs``: with the parts the input names) meets every
    constraint for input ``d``."""
    try:
        ev = evaluate(d, settings, pin_inputs=pin_inputs)
    except InputError:
        return False
    return ev.any_feasible()


def nearest_design(ev):
    """``(core position, options, min_margin)`` of the nearest design of evaluation ``ev`` (every core evaluated):
    the best under the one key of near designs (:meth:`synth.optimise.product.Evaluation.nearest`)."""
    return ev.nearest()


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
    problems: list = []
    consistency({**vars(d), **changes}, problems)
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


def _far_joint(d, cands: dict, each=None) -> dict:
    """The far probe of all inputs ``cands`` moved together (each :func:`_far`; ``each``: their far values, in
    ``cands``' order, when known), short of the cross-field rules."""
    far = dict(zip(cands, each)) if each is not None else {n: _far(d, n, s) for n, s in cands.items()}
    lam = _within_rules(d, far)
    return {n: getattr(d, n) + lam * (v - getattr(d, n)) for n, v in far.items()}


def _candidates(d, violated) -> dict:
    return {n: sign for n, (sign, rel, _) in relaxable().items()
            if getattr(d, n, None) is not None and set(rel) & set(violated)}


def _entry(d, names, far: dict, lam: float, violated) -> dict:
    """One relaxation: the inputs ``names`` moved by the fraction ``lam`` of the way to ``far``, each with its unit
    and who controls it; ``relative_change`` is the largest relative change of its inputs."""
    out, rel = {}, 0.0
    for n in names:
        cur = getattr(d, n)
        to = round(float(cur + lam * (far[n] - cur)), 4)
        f = field_by_name(n)
        out[n] = {"from": cur, "to": to, "unit": f.unit if f.unit != "-" else "", "owner": f.owner}
        rel = max(rel, abs(to - cur) / max(abs(cur), 1e-9))
    spec = any(relaxable()[n][2] for n in names)
    return {"inputs": out, "relative_change": round(rel, 4), "specification": spec,
            "owner": "specification" if spec else "designer",
            "relaxes": sorted(set().union(*(relaxable()[n][1] for n in names)) & set(violated))}


def _order(out: list) -> list:
    """What the tensioner designer controls first, then fewer inputs, then the smaller change."""
    return sorted(out, key=lambda r: (r["specification"], len(r["inputs"]), r["relative_change"]))


def _designer(names) -> bool:
    return not any(relaxable()[n][2] for n in names)


def _levels(cands: dict) -> list:
    """The sets of inputs tried, level by level: each alone, every pair, then the designer's inputs all together
    and every input together."""
    names = list(cands)
    mine = [n for n in names if _designer((n,))]
    last = [tuple(mine)] if len(mine) > 2 else []
    last += [tuple(names)] if len(names) > 2 and len(names) > len(mine) else []
    return [[(n,) for n in names], list(itertools.combinations(names, 2)), last]


def relaxations(d, violated: list, *, settings: Settings = DEFAULT, steps: int = 7, probe=None,
                pin_inputs: bool = False) -> list:
    """Smallest input changes that make ``d`` feasible, for the inputs that relax ``violated``.

    First each input alone (bisection between its value and a far value: x2 or /4 within the schema's range);
    when no single input suffices, every pair of them, each pair moved by a common fraction of its ranges;
    when no pair does, all the relevant inputs together (one entry with several ``"inputs"``). What the tensioner
    designer controls comes before the specification values (``"owner"``, ``"specification": True``; declared
    on the schema's fields). ``probe(d, changes, settings) -> bool`` replaces the feasibility check (one probe at a
    time, the reference); ``pin_inputs`` keeps the parts the input names in it.
    """
    one = probe or reference_probe(pin_inputs)
    return relaxations_batch([d], [violated], settings=settings, steps=steps,
                             probe=lambda items: [one(x, ch, settings) for x, ch in items])[0]


def probe_batch(settings: Settings = DEFAULT, spring_engine: str = "numba", *, pin_inputs: bool = False):
    """A batched feasibility probe: ``probe([(d, changes), ...]) -> [bool, ...]``, every probe of a bisection
    step in one vectorised feasibility search (:func:`synth.optimise.batch.any_feasible`); the same answers as
    the reference probe (``is_feasible`` of the changed input; an input the physics refuses is not feasible).
    ``probe.designs(items, hints)`` answers the same, trying the designs ``hints`` first (:func:`relaxations_batch`);
    ``probe.counts``: how many of its probes a reused design answered and how many were searched."""

    def probe(items):
        return any_feasible([dataclasses.replace(d, **ch) for d, ch in items], settings, spring_engine=spring_engine,
                            pin_inputs=pin_inputs)

    def designs(items, hints):
        """``(answers, designs)`` of ``items``: where ``hints[k]`` (a design found feasible for the same
        application nearby, or None) passes at item ``k`` (:func:`~synth.optimise.batch.designs_pass`), yes with
        that design; the others searched (:func:`~synth.optimise.batch.any_feasible`, its design or None)."""
        xs = [dataclasses.replace(d, **ch) for d, ch in items]
        out: list = [None] * len(xs)
        h = [k for k, x in enumerate(hints) if x is not None]
        if h:
            for k, y in zip(h, designs_pass([xs[k] for k in h], [hints[k] for k in h], settings)):
                out[k] = hints[k] if y else None
        rest = [k for k in range(len(xs)) if out[k] is None]
        probe.counts["reused"] += len(xs) - len(rest)
        probe.counts["searched"] += len(rest)
        for k, f in zip(rest, any_feasible([xs[k] for k in rest], settings, spring_engine=spring_engine,
                                           pin_inputs=pin_inputs, designs=True)):
            out[k] = f
        return [f is not None for f in out], out
    probe.designs = designs
    probe.counts = {"reused": 0, "searched": 0}  # probes answered by a reused design, and searched
    return probe


def relaxations_batch(ds: list, violated: list, *, settings: Settings = DEFAULT, steps: int = 7,
                      probe=None) -> list:
    """:func:`relaxations` of many applications at once: per application the same candidate inputs, the same
    far probes and the same bisections, hence the same relaxations; but each round probes every pending
    (application, set of inputs) together (``probe``, default :func:`probe_batch`), the levels (alone, pairs,
    all) overlapped: a level is tried while the tensioner designer has no relaxation of his own (the sets of his
    inputs until one is found, the sets with a specification value until any is), which its far probes already
    decide (every set whose far probe passes gives one relaxation, its bisection only says how far), so the next
    level's far probes go with the previous level's first bisection step: 3 + ``steps`` probe rounds in all,
    whatever the number of applications (not 3 x (1 + ``steps``)). With a probe that returns its designs
    (:func:`probe_batch`), each bisection step first verifies, at its new point, the design its set's last
    feasible probe found (a pass proves the yes; only the others are searched): the same answers."""
    probe = probe or probe_batch(settings)
    reuse = getattr(probe, "designs", None)  # a probe that returns its designs (:func:`probe_batch`)
    last: dict = {}  # (level, set) -> the design its last feasible probe found
    cands = [_candidates(d, v) for d, v in zip(ds, violated)]
    levels = [_levels(c) for c in cands]
    far_of: dict = {}  # (application, input) -> its far value (:func:`_far`), shared by the levels

    def far1(i, n):
        if (i, n) not in far_of:
            far_of[i, n] = _far(ds[i], n, cands[i][n])
        return far_of[i, n]
    found: list = [[] for _ in ds]  # per application, the sets whose far probe passed (each a relaxation)
    got: list = [[[] for _ in ds] for _ in range(3)]  # per level and application, its relaxations
    jobs: list = []  # per level under way: [level, todo, far, live (set, good fraction, bad fraction), step]
    level = 0
    while True:
        new = None
        while new is None and level < 3:
            todo = [(i, names) for i in range(len(ds)) if not any(_designer(n) for n in found[i])
                    for names in levels[i][level] if not found[i] or _designer(names)]
            if todo:
                far = [{names[0]: far1(i, names[0])} if len(names) == 1
                       else _far_joint(ds[i], {n: cands[i][n] for n in names}, [far1(i, n) for n in names])
                       for i, names in todo]
                new = [level, todo, far, [], 0]
            level += 1
        items, asked, keys = [], [], []
        if new is not None:
            items += [(ds[i], new[2][k]) for k, (i, _) in enumerate(new[1])]
        for job in jobs:
            lv, todo, far, live, _ = job
            keys += [(lv, k) for k, _, _ in live]
            for k, good, bad in live:
                i, names = todo[k]
                mid = 0.5 * (good + bad)
                items.append((ds[i], {n: getattr(ds[i], n) + mid * (far[k][n] - getattr(ds[i], n)) for n in names}))
                asked.append(mid)
        if not items and new is None:
            break
        if reuse is None:
            res = list(probe(items)) if items else []
        else:  # each bisection step first tries the design its set's last feasible probe found
            heads = [(new[0], k) for k in range(len(new[1]))] if new is not None else []
            res, des = reuse(items, [None] * len(heads) + [last.get(key) for key in keys]) if items else ([], [])
            last.update((key, f) for key, f in zip(heads + keys, des) if f is not None)
        if new is not None:
            ok, res = res[:len(new[1])], res[len(new[1]):]
            new[3] = [(k, 1.0, 0.0) for k, good in enumerate(ok) if good]
            for k, _, _ in new[3]:
                found[new[1][k][0]].append(new[1][k][1])
        at = 0
        for job in jobs:
            live = job[3]
            r, mids = res[at:at + len(live)], asked[at:at + len(live)]
            at += len(live)
            job[3] = [(k, mid, bad) if y else (k, good, mid) for (k, good, bad), mid, y in zip(live, mids, r)]
            job[4] += 1
        if new is not None:
            jobs.append(new)
        for job in [j for j in jobs if j[4] >= steps]:
            lv, todo, far, live, _ = job
            for k, good, _ in live:  # in the candidates' order
                i, names = todo[k]
                got[lv][i].append(_entry(ds[i], names, far[k], good, violated[i]))
            jobs.remove(job)
    return [_order(got[0][i] + got[1][i] + got[2][i]) for i in range(len(ds))]


def _no_core(d):
    """The problem of an input whose pinned parts (``--pin-inputs``) leave no core design of the catalogs."""
    t = space().tables["core"]
    classes = ", ".join(f"{x:g}" for x in sorted(set(map(float, t["pivot_class_diameter_mm"]))))
    return Problem("--pin-inputs", f"pivot class {d.pivot_class_diameter_mm}, bushing thickness "
                                   f"{d.pivot_bushing_radial_thickness_mm}",
                   f"parts the catalogs hold (pivot classes {classes} mm): no design of the catalogs keeps these")
def violated_of(res) -> list:
    """The failed checks of a verified design, smallest margin first, as a diagnosis lists them."""
    return [{"constraint": c.id, "label": c.label, "step": c.step, "margin": c.margin}
            for c in sorted(res.failed(), key=lambda c: c.margin)]


def diagnose(d, ev=None, *, solver: str = "enumerate", objective=None, stats: dict | None = None,
             relax: bool = True, settings: Settings = DEFAULT, exhaustive: bool = False, batch=None,
             pin_inputs: bool = False):
    """A :class:`~synth.design.result.Result` with ``status="infeasible"`` and its ``diagnosis``.

    The nearest design and the relaxations come from the batched searches (:meth:`synth.optimise.batch.Batch.nearest`,
    :func:`relaxations_batch` with the numpy spring twins) unless ``exhaustive=True`` (the reference: the
    exhaustive evaluation and one probe at a time; the same answer) or an evaluation ``ev`` is given (the nearest
    design from it, evaluated over every core, and the relaxations batched: the margin objectives' path). ``pin_inputs``: the search the solver ran kept the parts the input names, and so do the nearest
    design and the relaxations (every solver answers the same question).
    """
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
        b = batch if batch is not None else Batch([d], settings, spring_engine="numpy", pin_inputs=pin_inputs)
        near = b.nearest([0])[0]
        if near is None:  # no core at all: as the exhaustive search (its argmax of nothing raises)
            return diagnose(d, solver=solver, objective=objective, stats=stats, relax=relax, settings=settings,
                            exhaustive=True, pin_inputs=pin_inputs)
        res = build_result(b.view(0), near[0], near[1], status="infeasible", solver=solver, objective=obj,
                           stats=stats or {})
    ids = [c.id for c in res.failed()]
    if not relax:
        rel = []
    elif exhaustive:
        rel = relaxations(d, ids, settings=settings, pin_inputs=pin_inputs)
    else:
        rel = relaxations_batch([d], [ids], settings=settings,
                                probe=probe_batch(settings, spring_engine="numpy", pin_inputs=pin_inputs))[0]
    res.diagnosis = {
        "message": "no design of the catalog product meets every constraint; the nearest design is shown",
        "violated": violated_of(res),
        "relaxations": rel,
    }
    switch = layout_switch(d, settings, pin_inputs=pin_inputs) if relax else None
    if switch is not None:
        res.diagnosis["message"] += "; " + switch["message"]
        res.diagnosis["layout"] = switch
        res.diagnosis["relaxations"] = [switch["relaxation"]] + rel
    res.stats["diagnosis_time_s"] = time.perf_counter() - t0
    return res


def layout_switch(d, settings: Settings = DEFAULT, *, pin_inputs: bool = False) -> dict | None:
    """The layout switch of eq. (17)-(18) that makes ``d`` infeasible, explained, or None
    (:func:`layout_switches` of one application with the reference probe)."""
    single = reference_probe(pin_inputs)
    return layout_switches([d], lambda items: [single(x, ch, settings) for x, ch in items])[0]


def layout_switches(ds: list, probe) -> list:
    """Per application of ``ds``, the layout switch of eq. (17)-(18) that makes it infeasible, explained, or None.

    Eq. (17) selects the standard layout when the middle plane belt height is at least half the maximum axial
    displacement, eq. (18) the reverse one otherwise: *raising* the axial space limit past twice the belt height
    switches to the reverse layout, whose packaging differs (the spring housing under the bearing, eq. (27)'s
    crankcase clearance), so loosening a limit can lose feasibility (40.0 -> 40.001 mm did, silently). When an
    application is reverse by eq. (18) with a given maximum, and the largest maximum that keeps the standard layout
    (twice the belt height) has a feasible design, this says so: ``{"message", "layout", "relaxation"}``. Every
    such probe goes to ``probe([(d, changes), ...]) -> [bool, ...]`` at once (:func:`probe_batch` for a portfolio).
    """
    todo = []
    for i, d in enumerate(ds):
        h, h_max = d.middle_plane_belt_height_mm, d.max_axial_displacement_mm
        if h is None or h_max is None or layout_of(h, h_max) != "reverse":
            continue
        changes = {"max_axial_displacement_mm": 2.0 * float(h)}  # eq. (17) at equality is standard
        if _consistent(d, changes):
            todo.append((i, changes))
    ok = probe([(ds[i], ch) for i, ch in todo]) if todo else []
    out: list = [None] * len(ds)
    f = field_by_name("max_axial_displacement_mm")
    for (i, changes), good in zip(todo, ok):
        if not good:
            continue
        h, h_max, edge = ds[i].middle_plane_belt_height_mm, ds[i].max_axial_displacement_mm, \
            changes["max_axial_displacement_mm"]
        message = (f"the layout is the reverse one (eq. (18)): the middle plane belt height {h:g} mm is below half "
                   f"the maximum axial displacement {h_max:g} mm (eq. (17)); with max_axial_displacement_mm at most "
                   f"{edge:g} mm (twice the belt height) eq. (17) selects the standard layout, which has a feasible "
                   "design: a larger axial space changed the layout, it did not only loosen a limit")
        relaxation = {"inputs": {"max_axial_displacement_mm": {"from": h_max, "to": round(edge, 4), "unit": f.unit,
                                                               "owner": f.owner}},
                      "relative_change": round(abs(h_max - edge) / max(abs(h_max), 1e-9), 4),
                      "specification": False, "owner": f.owner, "relaxes": ["layout (eq. (17)-(18))"],
                      "note": "the standard layout (eq. (17))"}
        out[i] = {"message": message, "layout": "reverse", "standard_up_to_mm": edge, "relaxation": relaxation}
    return out
