"""HTML fragments of a :class:`~synth.design.result.Result` for ``synth ui`` (every text escaped for HTML).

The rows are the report's own (:func:`synth.report.html.check_steps`, :func:`synth.report.html.digest_html`),
coloured with the one verdict palette :data:`synth.report.palette.VERDICT_FILLS`; each check row carries
``data-check`` and ``data-verdict`` as the report's rows do, so a test reads the verdict and the colour
the browser computes.

>>> from synth.design.result import Check, Result
>>> r = Result("verified", parts={"ball_bearing": "6006"}, checks=[Check("bearing_load", 462.5, 900.0, 0.49, "pass")])
>>> 'data-check="bearing_load" data-verdict="pass" style="background:#c6efce"' in checks_table(r)
True
>>> "<td>6006</td>" in parts_table(r)
True
"""

from __future__ import annotations

from html import escape

from synth.report.palette import VERDICT_FILLS
from synth.report.html import check_steps, part_label, check_row
from synth.report.advice import relaxation_lines, alternative_rows

__all__ = ["checks_table", "parts_table", "binding_table", "diagnosis_html", "alternatives_html", "fill"]

def fill(verdict) -> str:
    """The background of a verdict (``#c6efce`` for pass), white for none."""
    return "#" + VERDICT_FILLS[verdict].lower() if verdict in VERDICT_FILLS else "#ffffff"


def _e(x) -> str:
    return escape("" if x is None else str(x), quote=True)


def checks_table(result) -> str:
    """Every check, by thesis step: value, sense, limit, unit, margin, verdict, equation, correction or note."""
    steps, not_applicable = check_steps(result)
    head = ("<tr><th>check</th><th>value</th><th></th><th>limit</th><th>unit</th><th>margin</th><th>verdict</th>"
            "<th>equation</th><th>correction / note</th></tr>")
    body = []
    for s in steps:
        body.append(f'<tr class="group"><td colspan="9">Step {_e(s["step"])}: {_e(s["name"])}</td></tr>')
        for r in s["rows"]:
            body.append(f'<tr data-check="{_e(r["id"])}" data-verdict="{_e(r["verdict"])}" '
                        f'style="background:{fill(r["verdict"])}"><td>{_e(r["label"])}</td>'
                        f'<td class="num">{_e(r["value"])}</td><td>{_e(r["sense"])}</td>'
                        f'<td class="num">{_e(r["limit"])}</td><td>{_e(r["unit"])}</td>'
                        f'<td class="num">{_e(r["margin"])}</td><td>{_e(r["verdict"])}</td>'
                        f'<td>{_e(r["equation"])}</td><td>{_e(r["extra"])}</td></tr>')
    na = ""
    if not_applicable:
        na = (f'<p class="small" style="background:{fill("not applicable")}">Not applicable to this design: '
              + _e(", ".join(not_applicable)) + "</p>")
    return f'<table class="checks"><thead>{head}</thead><tbody>{"".join(body)}</tbody></table>{na}'


def parts_table(result) -> str:
    """The design's parts (part key, in words, value)."""
    rows = "".join(f"<tr><th>{_e(part_label(k))}</th><td>{_e(v)}</td></tr>" for k, v in (result.parts or {}).items())
    return f'<table class="kv parts"><tbody>{rows}</tbody></table>'


def binding_table(result, n: int = 8) -> str:
    """What binds: the ``n`` smallest margins of the checks the margin objective counts (``Result.binding``)."""
    rows = "".join(f'<tr style="background:{fill(r["verdict"])}"><td>{_e(r["label"])}</td>'
                   f'<td class="num">{_e(r["margin"])}</td><td>{_e(r["correction"])}</td></tr>'
                   for r in map(check_row, result.binding(n)))
    return ("<table class=\"binding\"><thead><tr><th>check</th><th>margin</th><th>what relaxes it</th></tr></thead>"
            f"<tbody>{rows}</tbody></table>")


def diagnosis_html(result) -> str:
    """The diagnosis of an infeasible input (what binds, the smallest input relaxations), else a line saying none."""
    dg = result.diagnosis
    if not dg:
        return "<p>No diagnosis: the design is feasible (a diagnosis is made when no catalog design is).</p>"
    rel = [f"<li>{_e(x)}</li>" for x in relaxation_lines(result)]
    return (f"<p>{_e(dg.get('message', ''))}</p>"
            + (f"<p>Smallest input relaxations that make a design feasible:</p><ul>{''.join(rel)}</ul>" if rel else ""))


def alternatives_html(result) -> str:
    """The ranked alternative designs (``Result.alternatives``, ``synth design --top K``): rank, objectives, the
    smallest margin and the check that sets it, what differs from the optimum; a line when the result has none."""
    rows = alternative_rows(result)
    if not rows:
        return "<p>No alternatives: the design above is the only one asked for (or no design is feasible).</p>"
    cols = ("rank", "objectives", "margin", "binding", "differs")
    head = "".join(f"<th>{_e(c)}</th>" for c in ("#", "objectives", "smallest margin", "set by", "differs from #1"))
    body = "".join("<tr>" + "".join(f"<td>{_e(a[c])}</td>" for c in cols) + "</tr>" for a in rows)
    return f"<table class=\"alternatives\"><thead><tr>{head}</tr></thead><tbody>{body}</tbody></table>"
