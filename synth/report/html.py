"""The design report: one self-contained HTML file (inline CSS, PNG graphs embedded as base64).

Sections: the design summary (input data read, overall verdict), the output
table of thesis Tables 10/14 with row verdicts, every check with its value,
limit, margin and suggested correction, the notes of the flowchart, and the
graphs of :mod:`synth.report.plots` (with the list of graphs that do not
apply and why). Colours as in the thesis: green verified, red failed, orange
not verified (data missing).

Each graph is a ``<figure id="fig-<graph id>" data-points="N">`` whose image
is ``data:image/png;base64,...``, so tests and scripts can find them.

>>> _esc("a < b & c")
'a &lt; b &amp; c'
"""

from __future__ import annotations

import base64
import datetime as _dt
import html
from pathlib import Path

from synth import schema
from synth.design.result import FAIL, NOT_APPLICABLE, NOT_VERIFIED, PASS, WARNING, field_corrections, row_verdict
from synth.output_table import ROWS, format_value

__all__ = ["render_html", "write_html"]

_CSS = """
body{font-family:system-ui,-apple-system,Segoe UI,Roboto,sans-serif;margin:2em auto;max-width:1100px;color:#222}
h1{margin-bottom:.2em} h2{border-bottom:2px solid #1f4e78;padding-bottom:.2em;margin-top:1.6em}
table{border-collapse:collapse;width:100%;font-size:.9em;margin:.5em 0}
th,td{border:1px solid #ccc;padding:3px 6px;text-align:left;vertical-align:top}
th{background:#d9d9d9} td.num{text-align:right;font-variant-numeric:tabular-nums}
tr.section td{background:#bdd7ee;font-weight:bold}
.pass{background:#c6efce} .fail{background:#ffc7ce} .nv{background:#ffd966} .na{background:#f2f2f2;color:#777}
.banner{display:inline-block;padding:.3em .8em;font-weight:bold;border-radius:4px}
figure{display:inline-block;margin:.6em;border:3px solid #ccc;padding:4px;vertical-align:top;width:46%}
figure.pass{border-color:#2e7d32;background:none} figure.fail{border-color:#c62828;background:none}
figure img{width:100%} figcaption{font-size:.85em}
.small{font-size:.85em;color:#555}
"""

_CLS = {PASS: "pass", FAIL: "fail", NOT_VERIFIED: "nv", NOT_APPLICABLE: "na", WARNING: "nv", None: "",
        "incomplete": "nv"}


def _esc(x) -> str:
    return html.escape(str(x), quote=True)


def _num(v, digits: int = 4) -> str:
    if v is None:
        return "-"
    if isinstance(v, float):
        return f"{v:.{digits}g}"
    return format_value(v)


def _summary(result, source: str | None) -> str:
    v = {**result.values, **result.parts}
    failed, nv = result.failed(), result.not_verified()
    cls = _CLS[result.verdict]
    items = [("Input", source or "-"), ("Architecture", v.get("architecture", "-")),
             ("Ball bearing", v.get("ball_bearing", "-")), ("Pivot diameter", _num(v.get("pivot_diameter_mm")) + " mm"),
             ("Axial damping", "yes" if v.get("axial_damping_present") else "no"),
             ("Main spring", f"{v.get('main_spring_material', '-')} {format_value(v.get('main_spring_wire_size_mm'))}"),
             ("Bolt", f"{v.get('bolt_format', '-')} class {v.get('bolt_property_class', '-')}"),
             ("Checks", f"{len(result.checks)} ({len(failed)} failed, {len(nv)} not verified)"),
             ("Steps run", ", ".join(str(s) for s in result.steps_run)),
             ("Model", f"fidelity {result.settings.get('fidelity')}; radial friction "
                       + ("on the friction circle r_p sin(atan mu)" if result.settings.get("friction_circle", True)
                          else "on r_p mu (the thesis tool's tables)"))]
    rows = "".join(f"<tr><th>{_esc(k)}</th><td>{_esc(val)}</td></tr>" for k, val in items)
    return (f'<p><span class="banner {cls}">Verdict: {_esc(result.verdict.upper())}</span></p>'
            f"<table>{rows}</table>")


def _inputs(result) -> str:
    d = result.inputs or {}
    corr = field_corrections(result)
    out = ["<table><tr><th>Parameter</th><th>Field</th><th>Unit</th><th>Data read</th><th>Suggested correction</th></tr>"]
    for section in schema.SECTIONS:
        out.append(f'<tr class="section"><td colspan="5">{_esc(section)}</td></tr>')
        for f in (f for f in schema.FIELDS if f.section == section):
            val = d.get(f.name)
            cls = "nv" if val is None and f.name in corr else ("fail" if f.name in corr else "")
            opt = "" if f.required else ' <span class="small">(optional)</span>'
            out.append(f"<tr><td>{_esc(f.label or f.name)}{opt}</td><td><code>{_esc(f.name)}</code></td>"
                       f"<td>{_esc(f.unit)}</td><td class='num {cls}'>{_esc(format_value(val))}</td>"
                       f"<td>{_esc(corr.get(f.name, ''))}</td></tr>")
    out.append("</table>")
    return "".join(out)


def _output(result) -> str:
    out = ["<table><tr><th>Section</th><th>Parameter</th><th>Unit</th><th>Value</th><th>Verdict</th></tr>"]
    for section, label, key, unit in ROWS:
        verdict = row_verdict(result, key)
        out.append(f"<tr data-key='{_esc(key)}' data-verdict='{_esc(verdict or '')}'><td>{_esc(section)}</td>"
                   f"<td>{_esc(label)}</td><td>{_esc(unit)}</td>"
                   f"<td class='num {_CLS[verdict]}'>{_esc(_num(result.get(key)))}</td>"
                   f"<td class='{_CLS[verdict]}'>{_esc(verdict or '')}</td></tr>")
    out.append("</table>")
    return "".join(out)


def _checks(result) -> str:
    from synth.flowchart import STEP_NAMES
    out = ["<table><tr><th>Step</th><th>Check</th><th>Value</th><th></th><th>Limit</th><th>Unit</th>"
           "<th>Margin</th><th>Verdict</th><th>Equation</th><th>Suggested correction / note</th></tr>"]
    for c in sorted((c for c in result.checks if c.verdict != NOT_APPLICABLE), key=lambda c: c.step):
        con = c.constraint
        cls = _CLS[c.verdict]
        margin = "-" if c.margin is None else f"{100 * c.margin:+.1f} %"
        extra = con.correction if c.verdict == FAIL and con.correction else "; ".join([c.note] + c.assumed).strip("; ")
        out.append(f"<tr data-check='{_esc(c.id)}' data-verdict='{_esc(c.verdict)}'>"
                   f"<td>{c.step} {_esc(STEP_NAMES.get(c.step, ''))}</td><td>{_esc(con.label)}</td>"
                   f"<td class='num'>{_esc(_num(c.value))}</td><td>{_esc(con.sense if c.value is not None else '')}</td>"
                   f"<td class='num'>{_esc(_num(c.limit))}</td><td>{_esc(con.unit)}</td>"
                   f"<td class='num {cls}'>{margin}</td><td class='{cls}'>{_esc(c.verdict)}</td>"
                   f"<td>{_esc(con.equation)}</td><td>{_esc(extra or '')}</td></tr>")
    out.append("</table>")
    return "".join(out)


def _graphs(graphs, skipped) -> str:
    out = []
    for g in graphs:
        b64 = base64.b64encode(g.png).decode("ascii")
        n = max((len(v) for v in g.series.values()), default=0)
        cls = f' class="{_CLS[g.verdict]}"' if g.verdict in (PASS, FAIL) else ""
        verdict = f" &mdash; {_esc(g.verdict)}" if g.verdict else ""
        out.append(f'<figure id="fig-{_esc(g.id)}"{cls} data-points="{n}">'
                   f'<img alt="{_esc(g.title)}" src="data:image/png;base64,{b64}">'
                   f"<figcaption>{_esc(g.title)} ({_esc(g.figure)}){verdict}</figcaption></figure>")
    if skipped:
        out.append("<h3>Graphs not drawn</h3><ul>")
        out += [f'<li id="skip-{_esc(s.id)}">{_esc(s.title)}: {_esc(s.reason)}</li>' for s in skipped]
        out.append("</ul>")
    return "".join(out)


def _table(rows) -> str:
    if hasattr(rows, "to_dict"):
        rows = rows.to_dict(orient="records")
    if isinstance(rows, dict):
        rows = [rows]
    rows = list(rows or [])
    if not rows:
        return ""
    cols = list(dict.fromkeys(k for r in rows for k in r))
    head = "".join(f"<th>{_esc(c)}</th>" for c in cols)
    body = "".join("<tr>" + "".join(f"<td>{_esc(_num(r.get(c)))}</td>" for c in cols) + "</tr>" for r in rows)
    return f"<table><tr>{head}</tr>{body}</table>"


def render_html(result, graphs, skipped, *, source: str | None = None, title: str | None = None,
                scenes: dict | None = None) -> str:
    """The report as one HTML string (self-contained)."""
    title = title or f"synth design report{': ' + Path(source).name if source else ''}"
    parts = [f"<!DOCTYPE html><html lang='en'><head><meta charset='utf-8'><title>{_esc(title)}</title>"
             f"<style>{_CSS}</style></head><body>",
             f"<h1>{_esc(title)}</h1><p class='small'>generated {_dt.datetime.now():%Y-%m-%d %H:%M} by synth</p>",
             "<h2 id='summary'>Design summary</h2>", _summary(result, source),
             "<h2 id='output'>Output table (thesis Tables 10/14)</h2>", _output(result),
             "<h2 id='checks'>Verdicts and margins</h2>", _checks(result)]
    if result.notes:
        parts += ["<h2 id='notes'>Notes</h2><ul>", *(f"<li>{_esc(n)}</li>" for n in result.notes), "</ul>"]
    parts += ["<h2 id='graphs'>Graphs</h2>", _graphs(graphs, skipped)]
    for name, rows in (scenes or {}).items():
        if rows is not None:
            parts += [f"<h2 id='scene-{_esc(name.lower())}'>{_esc(name)}</h2>", _table(rows)]
    parts += ["<h2 id='inputs'>Design input (data read)</h2>", _inputs(result), "</body></html>"]
    return "\n".join(parts)


def write_html(path: str | Path, result, graphs, skipped, **kw) -> Path:
    """Write :func:`render_html` to ``path``."""
    p = Path(path)
    p.parent.mkdir(parents=True, exist_ok=True)
    p.write_text(render_html(result, graphs, skipped, **kw), encoding="utf-8")
    return p
