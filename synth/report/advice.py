"""The words a designer acts on, once for every output: the objective line, the parts not kept, the relaxations
(what the tensioner designer changes, what to ask the belt-drive or engine specification for), the correction of a
failing check that agrees with the catalog search, the design rules and the ranked alternatives.

The terminal (:mod:`synth.report.text`), the report's digest (:mod:`synth.report.html`), the results workbook and
``synth ui`` print these lines; margins are percent here (words for people), fractions in the data.

>>> objective_line({"standard": 2.0, "cost": 1.5723, "margin": 0.0002545})
'objectives: non-standard parts 2 (weighted count), cost 1.572 EUR, smallest margin +0.03 %'
"""

from __future__ import annotations
from synth import formatting as fmt
from synth.design.constraints import REGISTRY
from synth.optimise.objectives import UNITS
from synth.design.rules import Rules

__all__ = ["objective_line", "change_lines", "relaxation_lines", "relaxation_text", "relaxation_kind", "correction",
           "search_lines", "is_header", "NO_DESIGNER", "ASK_SPECIFICATION", "TOGETHER", "margin_pct", "shortfall_of",
           "alternative_rows", "rule_lines"]

#: the header of the relaxations when none is the tensioner designer's alone
NO_DESIGNER = ("no change the tensioner designer controls alone (space, lock-up pin, bolt seat, the parts) makes a "
               "design feasible")
#: the header of the relaxations of the belt-drive or engine specification alone
ASK_SPECIFICATION = "ask the belt-drive or engine specification for one of:"
#: the header of the relaxations that need a change of the designer's and one of the specification together
TOGETHER = "a change of yours that works only together with a change of the specification, one of:"


def margin_pct(m) -> str:
    """A margin (a fraction) as people read it: ``+12.3 %`` (:func:`synth.formatting.percent`)."""
    return fmt.percent(m)


def shortfall_of(failed: dict) -> str:
    """How far a failing check ``{"constraint" or "id", "margin"}`` (the diagnosis's violated, a near miss's
    failed) misses its limit: :func:`synth.formatting.shortfall` of its registry entry (``35.2 %``; against a zero
    limit the distance with the unit)."""
    con = REGISTRY.get(failed.get("constraint", failed.get("id")))
    return fmt.shortfall(con, failed["margin"]) if con is not None else fmt.percent(-failed["margin"], signed=False)


def objective_line(objectives: dict) -> str:
    """The objective values with their units (:data:`synth.optimise.objectives.UNITS`)."""
    parts = []
    for k, v in objectives.items():
        if not isinstance(v, (int, float)) or isinstance(v, bool):
            continue
        name, unit = UNITS.get(k, (k, ""))
        if k == "margin":
            parts.append(f"{name} {margin_pct(v)}")
        else:
            parts.append(f"{name} {v:.4g}" + (f" {unit}" if unit else ""))
    return "objectives: " + ", ".join(parts)


def _value(v, unit: str = "") -> str:
    if isinstance(v, (list, tuple)):
        text = " x ".join(f"{float(x):g}" for x in v)
    elif isinstance(v, float):
        text = f"{v:.4g}"
    else:
        text = str(v)
    return f"{text} {unit}".strip()


def change_lines(r) -> list[str]:
    """One line per part the input names that the design does not keep (:attr:`Result.changes`), and a line
    saying which named parts are kept."""
    lines = []
    for c in r.changes or []:
        lines.append(f"{c['field']}: input {_value(c['input'], c.get('unit', ''))}, design "
                     f"{_value(c['design'], c.get('unit', ''))} ({c['how']}): {c['why']}")
    ctl = r.control or {}
    named = list(ctl.get("fixed", [])) + list(ctl.get("kept_when_possible", []))
    changed = {c["field"] for c in r.changes or []}
    kept = [n for n in named if n not in changed]
    if kept:
        lines.append("kept as the input names: " + ", ".join(kept)
                     + (" (fixed: " + ", ".join(ctl["fixed"]) + ")" if ctl.get("fixed") else ""))
        if ctl.get("why") and not ctl.get("freed"):
            lines.append(ctl["why"])
    return lines


def _distinct(a: float, b: float) -> tuple[str, str]:
    """``a`` and ``b`` to 4 significant figures, more where 4 would print them alike (40.001 -> 40, not 40 -> 40).

    >>> _distinct(40.001, 40.0), _distinct(0.018, 0.0197)
    (('40.001', '40'), ('0.018', '0.0197'))
    """
    for n in range(4, 12):
        x, y = f"{a:.{n}g}", f"{b:.{n}g}"
        if x != y or a == b:
            return x, y
    return x, y


def _owner(rel: dict, x: dict) -> str:
    return x.get("owner", "specification" if rel.get("specification") else "designer")


def relaxation_kind(rel: dict) -> str:
    """``designer`` (only inputs the tensioner designer controls, or parts to free), ``specification`` (only values
    of the belt-drive or engine specification) or ``both``."""
    owners = {_owner(rel, x) for x in rel.get("inputs", {}).values()} | ({"designer"} if rel.get("free") else set())
    return "both" if len(owners) > 1 else (owners.pop() if owners else "designer")


def relaxation_text(rel: dict) -> str:
    """One relaxation in words: ``change X a -> b unit (+p %)`` for the designer's inputs, ``ask for Y b unit
    instead of a (+p %)`` for a specification value, ``free Z`` for a part the input fixes; its note (a layout
    switch of eq. (17)-(18)) in brackets. The designer's changes and the specification's are never one sentence: a
    relaxation that needs both says the designer's, then ``Ask the specification for ...``.

    >>> relaxation_text({"inputs": {"bolt_head_contact_external_diameter_mm": {"from": 11.0, "to": 12.03,
    ...     "owner": "designer"}, "spring_stiffness_nm_per_deg": {"from": 0.018, "to": 0.0197,
    ...     "owner": "specification"}}})
    'change bolt_head_contact_external_diameter_mm 11 -> 12.03 mm (+9.4 %). Ask the specification for \
spring_stiffness_nm_per_deg 0.0197 Nm/deg instead of 0.018 (+9.4 %)'
    """
    from synth.schema import field_by_name
    mine, ask = [], []
    for name, x in rel.get("inputs", {}).items():
        unit = x.get("unit") or field_by_name(name).unit or ""
        frm, to = x["from"], x["to"]
        a, b = _distinct(frm, to)
        pct = f"{100 * (to - frm) / frm:+.1f} %" if frm and abs(to - frm) >= 5e-4 * abs(frm) else \
            (f"{100 * (to - frm) / frm:+.2g} %" if frm else "")
        if _owner(rel, x) == "designer":
            mine.append(f"change {name} {a} -> {b} {unit} ({pct})".replace("  ", " "))
        else:
            ask.append(f"{name} {b} {unit} instead of {a} ({pct})".replace("  ", " "))
    for name in rel.get("free", []):
        mine.append(f"free {name} (--free {name})")
    if mine and ask:
        text = " and ".join(mine) + ". Ask the specification for " + " and ".join(ask)
    else:
        text = " and ".join(mine) if mine else "ask for " + " and ".join(ask)
    return text + (f" ({rel['note']})" if rel.get("note") else "")


def relaxation_lines(r) -> list[str]:
    """The diagnosis's relaxations in words, in three lists that never contradict each other: the designer's alone
    first; then, under :data:`ASK_SPECIFICATION`, the specification's alone; then, under :data:`TOGETHER`, those
    that need both (each says the designer's change, then what to ask for). Where none is the designer's alone,
    :data:`NO_DESIGNER` says so first; a line where no relaxation exists. Headers end with ``:`` or start with
    ``no``; the catalog search's summary (:func:`search_lines`) comes first."""
    dg = r.diagnosis or {}
    if "relaxations" not in dg:
        return []
    rel = dg["relaxations"]
    head = search_lines(r)
    if not rel:
        return head + ["no relaxation of one input, two inputs or all of them together (within the searched ranges) "
                       "makes a design feasible"]
    kinds = {k: [relaxation_text(x) for x in rel if relaxation_kind(x) == k] for k in ("designer", "specification",
                                                                                        "both")}
    lines = head + (kinds["designer"] or [NO_DESIGNER])
    if kinds["specification"]:
        lines += [ASK_SPECIFICATION if not kinds["designer"] else "or " + ASK_SPECIFICATION] + kinds["specification"]
    if kinds["both"]:
        lines += ["or " + TOGETHER if kinds["designer"] or kinds["specification"] else TOGETHER]
        lines += kinds["both"]
    return lines


def is_header(text: str) -> bool:
    """Whether a line of :func:`relaxation_lines` is a header or a statement (else a relaxation)."""
    return text.endswith(":") or text.startswith(("no ", "every catalog "))


def _searched(group: str) -> str:
    from synth.design.space import PART_KEYS_BY_TABLE
    return ", ".join(k.removesuffix("_mm").replace("_", " ") for k in PART_KEYS_BY_TABLE[group])


def search_lines(r) -> list[str]:
    """What the catalog search of an infeasible synthesis tried, per group of a failing check: ``every catalog
    bolt format, ... was tried with the rest of the design, none making it feasible (...)`` (the diagnosis's, not a
    correction)."""
    from synth.design.space import PART_KEYS_BY_TABLE
    if not r.diagnosis or r.solver in ("", "flowchart"):
        return []
    failing: dict = {}
    for c in r.checks:
        if c.verdict == "fail" and c.constraint.group in PART_KEYS_BY_TABLE:
            failing.setdefault(c.constraint.group, []).append(c.label)
    return [f"every catalog {_searched(g)} was tried with the rest of the design, none making it feasible (the "
            "nearest design fails: " + "; ".join(labels) + ")" for g, labels in failing.items()]


def correction(r, c) -> str:
    """The suggested correction of check ``c`` of result ``r``, in agreement with how ``r`` was found: after a
    catalog search (an infeasible synthesis) the parts of the check's group were all tried, so no other part is
    offered: the correction is the relaxations that relax the check (or freeing a part the input fixes), smallest
    first, else ``none within the catalog`` and where the input changes are (what was searched is the diagnosis's,
    :func:`search_lines`); otherwise the registry's correction."""
    from synth.design.space import PART_KEYS_BY_TABLE
    from synth.schema import field_by_name
    con = c.constraint
    dg = r.diagnosis
    if not dg or r.solver in ("", "flowchart") or con.group not in PART_KEYS_BY_TABLE:
        return con.correction
    fixed = [n for n in (r.control or {}).get("fixed", []) if field_by_name(n).pins[0] == con.group]
    ways = [relaxation_text(x) for x in dg.get("relaxations", []) if c.id in x.get("relaxes", [])
            or any(f in fixed for f in x.get("free", []))]
    ways += [f"free {n} (fixed by the input)" for n in fixed]
    if ways:
        return "; or ".join(dict.fromkeys(ways))
    if dg.get("relaxations"):
        return ("none within the catalog; each input change of the diagnosis makes a whole design feasible, this "
                "check included")
    return "none within the catalog, nor by relaxing the inputs searched"


def alternative_rows(r) -> list[dict]:
    """The ranked alternatives (:attr:`Result.alternatives`) as rows of words: ``{"rank", "kind", "objectives",
    "cost_change", "margin", "binding", "failed", "verdict", "differs"}`` (``differs``: what differs from the
    design shown, the optimum or for near misses the nearest design; ``cost_change``: the cost against the optimum's
    (a near miss: against the design shown), in EUR and percent, :func:`synth.formatting.difference`, empty for
    that design itself; ``failed``: the checks a near miss fails, each by how much)."""
    rows = []
    alts = r.alternatives or []
    near_list = bool(alts) and alts[0].get("kind") == "near miss"
    # the cost against the optimum (the first alternative), a near miss's against the nearest design shown
    ref = (getattr(r, "objectives", None) or {}).get("cost") if near_list else (alts[0].get("objectives", {}).get("cost") if alts
                                                               else None)
    for a in alts:
        near = a.get("kind") == "near miss"
        objs = objective_line({k: v for k, v in a.get("objectives", {}).items() if k != "margin"})
        diff = ", ".join(f"{k} {_value(x[0])} -> {_value(x[1])}" for k, x in a.get("differs", {}).items())
        first = "the nearest design shown" if near else "the optimum"
        cost = a.get("objectives", {}).get("cost")
        same = not a.get("differs") if near else a is alts[0]
        change = "" if same or cost is None else fmt.difference(cost, ref, "EUR")
        rows.append({"rank": a["rank"], "kind": a.get("kind", "alternative"),
                     "objectives": objs.removeprefix("objectives: ") + (f", {change} against {first}" if change
                                                                        and change != "-" else ""),
                     "cost_change": change,
                     "margin": margin_pct(a.get("margin")), "binding": a.get("binding", ""),
                     "failed": "; ".join(f"{f['label']} by {shortfall_of(f)}" for f in a.get("failed", []))
                     or "none", "verdict": a.get("verdict", ""),
                     "differs": diff or first})
    return rows


def rule_lines(r) -> list[str]:
    """The design rules the result's checks were made under (:attr:`Result.rules`), in words; none without."""
    return Rules.from_mapping(r.rules).lines() if r.rules else []
