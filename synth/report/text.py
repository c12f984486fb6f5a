"""The terminal view of a :class:`~synth.design.result.Result` (flowchart, design, demo print the same).

One presentation for every scene: the parts, the output table in the shape of
the thesis's Tables 10 and 14, every check with its readable label (from the
registry), value, limit and margin in percent, what binds, the diagnosis of an
infeasible input, the assumptions and notes, and the verdict.
"""

from __future__ import annotations

from synth.design.result import FAIL, INCOMPLETE, NOT_APPLICABLE, NOT_VERIFIED, PASS, WARNING, Result
from synth.output_table import ROWS, format_value

__all__ = ["render", "verdict_line", "MARKS"]

MARKS = {PASS: "PASS", FAIL: "FAIL", WARNING: "WARN", NOT_VERIFIED: "N/V "}


def verdict_line(r: Result) -> str:
    """``Verdict: PASS``, ``Verdict: FAIL (2 checks failed)`` or ``Verdict: INCOMPLETE (...)``."""
    failed, nv, assumed = r.failed(), r.not_verified(), r.assumptions()
    extra = []
    if failed:
        extra.append(f"{len(failed)} check(s) failed")
    if nv:
        extra.append(f"{len(nv)} not verified")
    if assumed:
        extra.append(f"{len(assumed)} input(s) assumed")
    text = {PASS: "PASS", FAIL: "FAIL", INCOMPLETE: "INCOMPLETE: passed what was checked, not everything was"}[r.verdict]
    return f"Verdict: {text}" + (f" ({'; '.join(extra)})" if extra else "")


def _check_line(c) -> list[str]:
    con = c.constraint
    mark = MARKS[c.verdict]
    if c.verdict == NOT_VERIFIED:
        return [f"  [{mark}] step {con.step:>2} {con.label}: {c.note}"]
    out = [f"  [{mark}] step {con.step:>2} {con.label}: {c.value:.4g} {con.sense} {c.limit:.4g} {con.unit}"
           f"  margin {100 * c.margin:+.1f} %  ({con.equation})"]
    if c.verdict == FAIL and con.correction:
        out.append(f"           suggested correction: {con.correction}")
    if c.verdict == WARNING:
        out.append(f"           advisory: {con.correction}")
    return out


def render(r: Result, *, title: str = "") -> str:
    """The whole terminal report of ``r``."""
    lines = [title] if title else []
    if r.solver and r.solver != "flowchart":
        lines.append(f"solver {r.solver} | objective {r.objective} | status {r.status}")
        if r.objectives:
            lines.append("objectives: " + ", ".join(f"{k} {v:.4g}" for k, v in r.objectives.items()
                                                      if isinstance(v, (int, float))))
        lines.append("")
    fid = (r.settings or {}).get("fidelity", "full")
    if fid != "full":
        from synth.design.evaluate import FIDELITY_TEXT
        lines += [f"fidelity {FIDELITY_TEXT.get(fid, fid)}", ""]
    lines += ["Design (part keys)", "-" * 78]
    lines += [f"  {k:<36} {format_value(v)}" for k, v in r.parts.items()]
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
    lines += ["", "Checks (margin: the relative distance to the limit; >= 0 passes)", "-" * 78]
    for c in sorted((c for c in r.checks if c.verdict != NOT_APPLICABLE), key=lambda c: c.constraint.step):
        lines += _check_line(c)
    binds = r.binding(5)
    if binds:
        lines += ["", "What binds (smallest margins)", "-" * 78]
        lines += [f"  {100 * c.margin:+7.1f} %  {c.label} (step {c.step})" for c in binds]
    if r.diagnosis:
        lines += ["", "Diagnosis", "-" * 78, f"  {r.diagnosis['message']}"]
        for v in r.diagnosis.get("violated", []):
            lines.append(f"  violated: {v['label']} (step {v['step']}) by {-100 * v['margin']:.1f} %")
        for rel in r.diagnosis.get("relaxations", []):
            ch = ", ".join(f"{k} {x['from']:g} -> {x['to']:g}" for k, x in rel["inputs"].items())
            tag = " (a specification value)" if rel.get("specification") else ""
            lines.append(f"  feasible with: {ch}{tag}")
        if "relaxations" in r.diagnosis and not r.diagnosis["relaxations"]:
            lines.append("  no single input relaxation within the searched ranges makes it feasible")
    if r.assumptions():
        lines += ["", "Assumed (documented defaults for inputs not given)", "-" * 78]
        lines += [f"  - {a}" for a in r.assumptions()]
    if r.notes:
        lines += ["", "Notes", "-" * 78] + [f"  - {n}" for n in r.notes]
    lines += ["", verdict_line(r)]
    return "\n".join(lines)
