"""The terminal view of a :class:`~synth.design.result.Result` (flowchart, design, demo print the same).

One presentation for every scene: the parts, the output table in the shape of
the thesis's Tables 10 and 14, every check with its readable label (from the
registry), value, limit and margin in percent, what binds, the diagnosis of an
infeasible input, the assumptions and notes, and the verdict.
"""

from __future__ import annotations

from synth import formatting as fmt
from synth.design.result import FAIL, NOT_APPLICABLE, NOT_VERIFIED, PASS, WARNING, Result, absent_part, part_note
from synth.output_table import ROWS, format_value
from synth.report.advice import alternative_rows, change_lines, correction, is_header, objective_line, \
    relaxation_lines, rule_lines, shortfall_of
from synth.design.evaluate import FIDELITY_TEXT
from synth.report.robust import text_lines
from synth.report import cost as cost_words

__all__ = ["render", "verdict_line", "MARKS"]

MARKS = {PASS: "PASS", FAIL: "FAIL", WARNING: "WARN", NOT_VERIFIED: "N/V "}


def verdict_line(r: Result) -> str:
    """The last line of every scene that judges a design: ``Verdict: PASS``, ``Verdict: FAIL (...)`` or ``Verdict:
    INCOMPLETE (...)``, with why (the result's one verdict, :attr:`Result.judgement`: failed checks, a capability
    target missed or not assessed, checks not verified, inputs assumed)."""
    return r.judgement.line()


def _check_line(c, r=None) -> list[str]:
    con = c.constraint
    mark = MARKS[c.verdict]
    if c.verdict == NOT_VERIFIED:
        return [f"  [{mark}] step {con.step:>2} {con.label}: {c.note}"]
    margin = fmt.check_margin(c)  # none for a yes/no check; the distance with its unit against a zero limit
    out = [f"  [{mark}] step {con.step:>2} {con.label}: {fmt.check_relation(c)}"
           + (f"  margin {margin}" if margin != "-" else "") + f"  ({con.equation})"]
    fix = correction(r, c) if r is not None else con.correction
    if c.verdict == FAIL and fix:
        out.append(f"           suggested correction: {fix}")
    if c.verdict == WARNING:
        out.append(f"           advisory: {con.correction}")
    return out


def render(r: Result, *, title: str = "", verdict: bool = True) -> str:
    """The whole terminal report of ``r``, ending with its verdict line (``verdict=False``: without it, for a scene
    that prints more before its last line, :func:`verdict_line`)."""
    lines = [title] if title else []
    lines += rule_lines(r)
    if r.solver and r.solver != "flowchart":
        lines.append(f"solver {r.solver} | objective {r.objective} | status {r.status}")
        if r.objectives:
            lines.append(objective_line(r.objectives))
        lines.append("")
    fid = (r.settings or {}).get("fidelity", "full")
    if fid != "full":
        lines += [f"fidelity {FIDELITY_TEXT.get(fid, fid)}", ""]
    changes = change_lines(r)
    if changes:
        lines += ["Parts the input names (kept unless no design with them passes; --fix keeps, --free frees)",
                  "-" * 78] + [f"  {x}" for x in changes] + [""]
    lines += ["Design (part keys)", "-" * 78]
    lines += [f"  {k:<36} {fmt.ABSENT if absent_part(r.parts, k) else format_value(v)}"
              + (f"  ({note})" if (note := part_note(r, k)) else "") for k, v in r.parts.items()]
    lines += ["", "Output (thesis Tables 10/14)", "-" * 78]
    section = None
    for sec, label, key, unit in ROWS:
        v = r.get(key)
        if v is None:
            continue
        if sec != section:
            lines.append(sec)
            section = sec
        lines.append(f"  {label:<40} [{unit:>4}]  {format_value(v)}")
    lines += ["", "Checks (margin: the relative distance to the limit, >= 0 passes; yes/no: a condition met or "
                  "not; against a zero limit: the distance in the check's unit)", "-" * 78]
    for c in sorted((c for c in r.checks if c.verdict != NOT_APPLICABLE), key=lambda c: c.constraint.step):
        lines += _check_line(c, r)
    alts = alternative_rows(r)
    if alts and alts[0]["kind"] == "near miss":
        lines += ["", f"Near misses (no feasible design): the {len(alts)} nearest distinct designs by the smallest "
                      "margin, ties by the next smallest, then the fewer failing checks (what binds; every check each "
                      "fails)", "-" * 78]
        for a in alts:
            lines.append(f"  #{a['rank']:<2} margin {a['margin']} ({a['binding']}), {a['objectives']}")
            lines.append(f"       fails: {a['failed']}")
            lines.append(f"       differs: {a['differs']}")
    elif alts:
        lines += ["", f"Alternatives: the {len(alts)} best distinct designs in objective order (each differs from "
                      "every earlier one in a catalog part; cost against the optimum's; margin: the smallest, and "
                      "the check that sets it)",
                  "-" * 78]
        for a in alts:
            lines.append(f"  #{a['rank']:<2} {a['objectives']}, margin {a['margin']} ({a['binding']})")
            lines.append(f"       differs: {a['differs']}")
    elif r.alternatives == [] and (r.control or {}).get("top", 1) > 1:
        lines += ["", "Alternatives: none (no design to rank)"]
    lines += cost_words.text_lines(getattr(r, "cost", None) or {})
    binds = r.binding(5)
    if binds:
        lines += ["", "What binds (smallest margins)", "-" * 78]
        lines += [f"  {fmt.check_margin(c):>9}  {c.label} (step {c.step})" for c in binds]
    if r.diagnosis:
        lines += ["", "Diagnosis", "-" * 78, f"  {r.diagnosis['message']}"]
        for v in r.diagnosis.get("violated", []):
            lines.append(f"  violated: {v['label']} (step {v['step']}) by {shortfall_of(v)}")
        for text in relaxation_lines(r):
            lines.append(f"  {text}" if is_header(text) else f"  feasible if you {text}")
    if r.assumptions():
        lines += ["", "Assumed (documented defaults for inputs not given)", "-" * 78]
        lines += [f"  - {a}" for a in r.assumptions()]
    if getattr(r, "robust", None):
        lines += text_lines(r.robust)
    if r.notes:
        lines += ["", "Notes", "-" * 78] + [f"  - {n}" for n in r.notes]
    if verdict:
        lines += ["", verdict_line(r)]
    return "\n".join(lines)
