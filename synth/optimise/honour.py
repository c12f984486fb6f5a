"""The inputs honoured: which parts the input names are kept, which synth may change, and why each change.

An input field that names a part or a class (:data:`synth.schema.PART_FIELDS`: the pivot class, the bushing's
radial thickness, the main spring's material, wire and mean diameter, the bolt's format and property class) is
one of three kinds in a synthesis, after ODOP's *fix* and *free*:

* **fixed** (``--fix FIELD``, or every named part with ``--pin-inputs``): the design keeps it, feasible or not
  (an infeasible input then gets its nearest design and relaxations with the part kept);
* **free** (``--free FIELD``): synth chooses it for the objective, whatever the input says;
* **kept when it can be** (every other named part, the default): the design keeps it unless no catalog design
  with it passes every check; then synth frees the fewest parts (the pivot class, the bushing thickness, the
  main spring and the bolt each count as one part, whatever number of fields name them), the set whose optimum
  is best, and says which and why. When no design passes with them or without them, they are freed and the
  nearest design of the whole catalog and its relaxations are shown (``--fix`` keeps them there too).

Every part of the design that differs from the input gets one line of :attr:`Result.changes
<synth.design.result.Result.changes>` (field, the input's value, the design's, why). The feasibility probes are the
exact batched search of the diagnosis (:func:`synth.optimise.batch.any_feasible`), the same for every solver;
the design itself is then the chosen solver's, on the space that keeps the chosen parts
(:func:`synth.design.space.space_for`).

>>> from synth import schema
>>> from synth.scenes.demo import default_input    # thesis case 3 at its own travel, pivot class 26 asked
>>> d = schema.validate({**{k: v for k, v in default_input().as_dict().items() if v is not None},
...                      "pivot_class_diameter_mm": 26.0})    # its arm wall fails whatever the other parts
>>> r = solve_honouring(d, "standard", "enumerate")
>>> [(c["field"], c["input"], c["design"], c["how"]) for c in r.changes]
[('pivot_class_diameter_mm', 26.0, 19.0, 'freed: no design keeps it')]
"""

from __future__ import annotations

import itertools

from synth.errors import InputError, Problem
from synth.optimise import solve as solve_nominal
from synth.optimise.objectives import Objective, with_margin_tiebreak

__all__ = ["solve_honouring", "changes_of", "parse_fields", "part_of"]


def part_of(name: str) -> str:
    """The part a part field names: the main spring and the bolt are one part each (their fields are freed
    together), a core field is its own."""
    from synth.schema import field_by_name
    table = field_by_name(name).pins[0]
    return table if table in ("spring", "bolt") else name


def parse_fields(values, option: str) -> tuple[str, ...]:
    """Field names of a ``--fix``/``--free`` option (repeatable, comma or space separated), each a part field."""
    from synth.schema import PART_FIELDS
    names: list[str] = []
    for v in values or ():
        names += [x.strip() for x in str(v).replace(",", " ").split() if x.strip()]
    for n in names:
        if n not in PART_FIELDS:
            import difflib
            near = difflib.get_close_matches(n, PART_FIELDS, n=1)
            raise InputError(Problem(option, n, "a field that names a part or a class: " + ", ".join(PART_FIELDS)
                                     + (f" (did you mean {near[0]}?)" if near else "")))
    return tuple(dict.fromkeys(names))


def _feasible(d, settings, keep) -> bool:
    from synth.optimise.batch import any_feasible
    return bool(any_feasible([d], settings, spring_engine="numpy", pin_inputs=tuple(keep))[0])


def _why_not(d, settings, keep) -> str:
    """Why the parts ``keep`` cannot all be kept: the checks the nearest design keeping them fails, worst first."""
    from synth.optimise.diagnose import diagnose
    try:
        r = diagnose(d, relax=False, settings=settings, pin_inputs=tuple(keep))
    except InputError as exc:
        return str(exc)
    failed = sorted(r.failed(), key=lambda c: c.margin)
    if not failed:
        return "no catalog design keeps them all"
    text = "; ".join(f"{c.label} by {-100 * c.margin:.1f} %" for c in failed[:3])
    more = f" and {len(failed) - 3} more" if len(failed) > 3 else ""
    return f"kept, the nearest design fails {text}{more}"


def solve_honouring(d, objective="standard", solver: str = "enumerate", *, fix=(), free=(), pin_inputs=False,
                    top: int = 1, distinct=None, robust=None, explain: bool = True, **kw):
    """The synthesis of ``d`` (:func:`synth.optimise.solve` with ``solver`` and ``kw``) that keeps the parts the
    input names as the module docstring says; the result carries :attr:`changes` and :attr:`control`, and with
    ``top`` K > 1 the K best designs (:attr:`alternatives`, :func:`synth.optimise.alternatives.ranked`) in the
    same space (``distinct``: the part keys that make them different, :data:`synth.optimise.alternatives.
    DISTINCT_KEYS`; an infeasible input: its K nearest designs). The exact solver (``enumerate``) takes the margin as the objective's last tie-break
    (:func:`synth.optimise.objectives.with_margin_tiebreak`). ``robust``: the robust synthesis in place of the
    nominal one (enumerate only), honouring the same parts, a function ``robust(d, objective, *, settings,
    pin_inputs, explain) -> Result`` its caller binds (:func:`synth.robust.synthesis.robust_solve` with its
    :class:`~synth.robust.settings.RobustSettings`: the robust layer sits above the optimiser); ``explain=False``:
    without the search of the one input or tolerance that prevents the target
    (:func:`synth.robust.synthesis.prevented_by`; the same design, the bulk's rows)."""
    from synth.design.evaluate import Settings
    from synth.design.space import fixed_fields
    settings = kw.get("settings") or Settings()
    if distinct is not None:
        from synth.optimise.alternatives import distinct_keys
        distinct = distinct_keys(distinct)  # a bad key is said before the synthesis
    if solver == "enumerate":
        objective = with_margin_tiebreak(objective)
    if robust is not None and solver != "enumerate":
        raise InputError(Problem("--solver", solver, "enumerate with --capability/--ppm (the robust synthesis "
                                                     "searches the catalog exhaustively)"))

    def solve(d, objective, solver, *, pin_inputs, **kw):
        if robust is None:
            return solve_nominal(d, objective, solver, pin_inputs=pin_inputs, **kw)
        return robust(d, objective, settings=settings, pin_inputs=pin_inputs, explain=explain)

    named = fixed_fields(d, True)
    fix = set(fixed_fields(d, parse_fields(fix, "--fix")))
    free = set(parse_fields(free, "--free"))
    if pin_inputs:
        fix |= set(named)
        pin_inputs = False
    both = sorted(fix & free)
    if both:
        raise InputError(Problem("--free", both[0], "a field not also given to --fix (or --pin-inputs): keep it or "
                                                    "free it"))
    if solver == "flowchart" and free:
        raise InputError(Problem("--free", sorted(free)[0], "not with --solver flowchart: the thesis procedure "
                                                            "takes the parts the input names"))
    prefer = [n for n in named if n not in fix and n not in free]
    order = [n for n in named if n in fix] + prefer
    released: tuple = ()
    why = ""
    reasons: dict = {}
    if solver != "flowchart" and prefer and not _feasible(d, settings, order):
        why = _why_not(d, settings, order)
        parts = list(dict.fromkeys(part_of(n) for n in prefer))
        found = []
        for k in range(1, len(parts) + 1):
            for group in itertools.combinations(parts, k):
                rel = tuple(n for n in prefer if part_of(n) in group)
                if _feasible(d, settings, [n for n in order if n not in rel]):
                    found.append(rel)
            if found:
                break
        if found:
            obj = objective if isinstance(objective, Objective) else Objective.parse(objective)
            best = None
            for rel in found:
                r = solve(d, obj, solver, pin_inputs=tuple(n for n in order if n not in rel), **kw)
                key = obj.key(r.objectives) if r.objectives and not r.failed() else (float("inf"),)
                if best is None or key < best[0]:
                    best = (key, rel, r)
            released, res = best[1], best[2]
            # why each freed part: the nearest design that keeps it (and every part kept) and what it fails
            reasons = {g: ("freed: no design keeps it",
                           _why_not(d, settings, [n for n in order if n not in released or part_of(n) == g]))
                       for g in dict.fromkeys(part_of(n) for n in released)}
        else:  # no design passes with them or without: the whole catalog's nearest design and relaxations
            released = tuple(prefer)
            res = solve(d, objective, solver, pin_inputs=tuple(n for n in order if n in fix), **kw)
            reasons = {g: ("freed: no design passes either way",
                           why + "; freed too, none passes: the nearest design of the whole catalog and its "
                                 "relaxations are shown") for g in dict.fromkeys(part_of(n) for n in released)}
    else:
        res = solve(d, objective, solver, pin_inputs=tuple(order) if solver != "flowchart" else False, **kw)
    res.control = {"fixed": sorted(fix, key=named.index), "free": sorted(free),
                   "kept_when_possible": prefer, "freed": list(released), "why": why, "top": top}
    res.changes = changes_of(d, res, free=free, released=released, reasons=reasons)
    if top != 1:
        from synth.optimise.alternatives import ranked
        res.alternatives = ranked(d, res, top, settings=settings, objective=objective, distinct=distinct,
                                  pin_inputs=tuple(n for n in order if n not in released) if solver != "flowchart"
                                  else False)
    return res


def changes_of(d, r, *, free=(), released=(), reasons: dict | None = None) -> list:
    """One entry per part field the input names and design ``r`` does not keep: ``{"field", "label", "unit",
    "input", "design", "how", "why"}`` (``how``: ``free`` (asked with --free), ``freed: no design keeps it``, or
    ``not kept`` by a solver that chooses its own parts); ``reasons``: part (:func:`part_of`) -> why it was freed."""
    from synth.design.space import design_inputs, same_input
    from synth.schema import PART_FIELDS, field_by_name
    if not r.parts:
        return []
    try:
        have = design_inputs(r.parts)
    except InputError:
        return []
    out = []
    for name in PART_FIELDS:
        given = getattr(d, name)
        if given is None or same_input(given, have[name]):
            continue
        f = field_by_name(name)
        if name in free:
            how, text = "free", "--free: synth chose it for the objective"
        elif name in released:
            how, text = (reasons or {}).get(part_of(name), ("freed: no design keeps it", ""))
            if how == "freed: no design keeps it":
                text += "; freed, a design passes"
            text += f" (--fix {name} keeps it)"
        else:
            how, text = "not kept", f"the {r.solver} solver chose another part"
        out.append({"field": name, "label": f.label, "unit": f.unit if f.unit != "-" else "",
                    "input": given, "design": have[name], "how": how, "why": text})
    return out
