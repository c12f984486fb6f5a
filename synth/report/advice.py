"""The words a designer acts on, once for every output: the objective line, the parts not kept, the relaxations
(what the tensioner designer changes, what to ask the belt-drive or engine specification for), the correction of a
failing check that agrees with the catalog search, the design rules and the ranked alternatives.

The terminal (:mod:`synth.report.text`), the report's digest (:mod:`synth.report.html`), the results workbook and
``synth ui`` print these lines; margins are percent here (words for people), fractions in the data.

>>> objective_line({"standard": 2.0, "cost": 1.5723, "margin": 0.0002545})
'objectives: non-standard parts 2 (weighted count), cost 1.572 EUR, smallest margin +0.03 %'
"""

from __future__ import annotations
from synth.optimise.objectives import UNITS
from synth.design.rules import Rules

__all__ = ["objective_line", "change_lines", "relaxation_lines", "relaxation_text", "correction", "NO_DESIGNER",
           "margin_pct", "alternative_rows", "rule_lines"]

#: the header of the relaxations when none is the tensioner designer's
NO_DESIGNER = ("no change the tensioner designer controls (space, lock-up pin, bolt seat, the parts) makes a design "
               "feasible; ask the belt-drive or engine specification for one of:")


def margin_pct(m) -> str:
    """A margin (a fraction) as people read it: ``+12.3 %``."""
    return "-" if m is None else f"{100 * float(m):+.1f} %" if abs(float(m)) >= 0.001 else f"{100 * float(m):+.2f} %"


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


def relaxation_text(rel: dict) -> str:
    """One relaxation in words: ``change X a -> b unit (+p %)`` for the designer's inputs, ``ask for Y b unit
    instead of a (+p %)`` for a specification value, ``free Z`` for a part the input fixes; its note (a layout
    switch of eq. (17)-(18)) in brackets."""
    from synth.schema import field_by_name
    mine, ask = [], []
    for name, x in rel.get("inputs", {}).items():
        unit = x.get("unit") or field_by_name(name).unit or ""
        frm, to = x["from"], x["to"]
        a, b = _distinct(frm, to)
        pct = f"{100 * (to - frm) / frm:+.1f} %" if frm and abs(to - frm) >= 5e-4 * abs(frm) else \
            (f"{100 * (to - frm) / frm:+.2g} %" if frm else "")
        if x.get("owner", "specification" if rel.get("specification") else "designer") == "designer":
            mine.append(f"change {name} {a} -> {b} {unit} ({pct})".replace("  ", " "))
        else:
            ask.append(f"ask for {name} {b} {unit} instead of {a} ({pct})".replace("  ", " "))
    for name in rel.get("free", []):
        mine.append(f"free {name} (--free {name})")
    return " and ".join(mine + ask) + (f" ({rel['note']})" if rel.get("note") else "")


def relaxation_lines(r) -> list[str]:
    """The diagnosis's relaxations in words, the designer's first; a header where none is his, or a line where
    none exists."""
    dg = r.diagnosis or {}
    if "relaxations" not in dg:
        return []
    rel = dg["relaxations"]
    if not rel:
        return ["no relaxation of one input, two inputs or all of them together (within the searched ranges) makes "
                "a design feasible"]
    lines = [] if rel[0].get("owner", "designer") == "designer" else [NO_DESIGNER]
    return lines + [relaxation_text(x) for x in rel]


def correction(r, c) -> str:
    """The suggested correction of check ``c`` of result ``r``, in agreement with how ``r`` was found: after a
    catalog search (an infeasible synthesis) the parts of the check's group were all tried, so the correction is
    the relaxations that relax it (or freeing a part the input fixes), not another part; otherwise the registry's
    correction."""
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
    searched = ", ".join(k.removesuffix("_mm").replace("_", " ") for k in PART_KEYS_BY_TABLE[con.group])
    head = f"every catalog {searched} was tried with the rest of the design"
    return head + ("; " + "; or ".join(dict.fromkeys(ways)) if ways else "; see the diagnosis for the inputs to relax")


def alternative_rows(r) -> list[dict]:
    """The ranked alternatives (:attr:`Result.alternatives`) as rows of words: ``{"rank", "objectives",
    "margin", "binding", "verdict", "differs"}`` (``differs``: what differs from the first, the optimum)."""
    rows = []
    for a in r.alternatives or []:
        objs = objective_line({k: v for k, v in a.get("objectives", {}).items() if k != "margin"})
        diff = ", ".join(f"{k} {_value(x[0])} -> {_value(x[1])}" for k, x in a.get("differs", {}).items())
        rows.append({"rank": a["rank"], "objectives": objs.removeprefix("objectives: "),
                     "margin": margin_pct(a.get("margin")), "binding": a.get("binding", ""),
                     "verdict": a.get("verdict", ""), "differs": diff or ("the optimum" if a["rank"] == 1 else "-")})
    return rows


def rule_lines(r) -> list[str]:
    """The design rules the result's checks were made under (:attr:`Result.rules`), in words; none without."""
    return Rules.from_mapping(r.rules).lines() if r.rules else []
