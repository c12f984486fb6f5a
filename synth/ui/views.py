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
>>> eng(62.96956885569824), eng(13880.4), eng(-2.096e-16), eng(0.0164), pct(0.0312)
('62.97', '13 880', '-2.096e-16', '0.0164', '+3.1 %')
"""

from __future__ import annotations

from html import escape

from synth.design.result import part_note
from synth.report.palette import VERDICT_FILLS
from synth.report.html import check_steps, part_label, check_row, digest_css, digest_html
from synth.report.advice import relaxation_lines, alternative_rows
from synth.ui.portfolio import verdict_word

__all__ = ["digest", "checks_table", "parts_table", "binding_table", "diagnosis_html", "alternatives_html", "fill", "eng", "pct",
           "part_value", "part_label", "fit_view",
           "capability_summary", "capability_table", "contributors", "compare_alternatives"]


def fill(verdict) -> str:
    """The background of a verdict (``#c6efce`` for pass), white for none."""
    return "#" + VERDICT_FILLS[verdict].lower() if verdict in VERDICT_FILLS else "#ffffff"


def _e(x) -> str:
    return escape("" if x is None else str(x), quote=True)


def _finite(x) -> bool:
    import math
    return isinstance(x, (int, float)) and not isinstance(x, bool) and math.isfinite(x)


def eng(x, digits: int = 4) -> str:
    """A number for people: ``digits`` significant digits, thousands grouped by a thin space from 10 000, an
    exponent only outside [1e-3, 1e9); text and None as they are (None: ``-``)."""
    if x is None:
        return "-"
    if isinstance(x, bool) or not isinstance(x, (int, float)):
        return str(x)
    if not _finite(x):
        return "inf" if x > 0 else "-inf" if x < 0 else "-"
    a = abs(x)
    if a == 0:
        return "0"
    if 1e4 <= a < 1e9:
        return f"{x:,.0f}".replace(",", " ")
    if 1e-3 <= a < 1e4:
        return f"{x:.{digits}g}"
    return f"{x:.{digits - 1}e}"


def pct(fraction, digits: int = 1) -> str:
    """A fraction (a margin, a share) in percent with its sign (``+3.1 %``); None ``-``."""
    return f"{100 * fraction:+.{digits}f} %" if _finite(fraction) else "-"


def digest(result) -> tuple[str, str]:
    """``(style sheet, digest)``: the report's digest (:func:`synth.report.html.digest_html`) without the style sheet
    it carries, which is the same for every result (a page holds it once: a ``<style>`` element in an edit's update
    makes the browser restyle the whole page).

    >>> from synth.design.result import Result
    >>> css, body = digest(Result("verified", parts={"ball_bearing": "6006"}))
    >>> ".synth" in css, "<style>" in body, digest(Result("optimal", parts={}))[0] == css
    (True, False, True)
    """
    return digest_css(), digest_html(result, styles=False)


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
    """The design's parts (part key in words, value; ``none`` for a class the design does not have)."""
    rows = "".join(f"<tr><th>{_e(part_label(k))}</th><td>{_e(part_value(v))}"
                   + (f' <span class="note">({_e(note)})</span>' if (note := part_note(result, k)) else "") + "</td></tr>"
                   for k, v in (result.parts or {}).items())
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


# --- production capability (``synth.capability``: ``Result.robust``) ----------------------------------------------------
#: the capability record's figures the table knows, in its order: (key, heading, format); any other figure a record
#: carries follows as a column of its own (the robust API grows: a new figure is shown, not dropped)
_CAPABILITY_COLUMNS = (("target", "counted", "yes"), ("meets", "meets the target", "meets"), ("ppk", "Ppk", "3g"),
                       ("ppm", "ppm", "eng"), ("p_violation", "P(violation) [95 %]", "p"),
                       ("nominal_margin", "nominal margin", "pct"), ("worst_case_margin", "worst case", "pct"),
                       ("rss_margin", "RSS", "pct"), ("method", "method", "text"),
                       ("contributors", "scatter from", "contributors"), ("note", "note", "text"))
#: figures folded into others or kept for the charts
_CAPABILITY_HIDDEN = {"id", "label", "group", "samples", "failures", "p_lo", "p_hi", "r2", "centre_margin",
                      "mean_margin", "sd_margin"}


def _cell(kind: str, value, rec: dict) -> str:
    if kind == "yes":
        return "" if value is None else ("yes" if value else "no")
    if kind == "meets":  # a check the target does not count is neither
        return ("yes" if value else "no") if rec.get("target") and value is not None else ""
    if kind == "3g":
        return "-" if value is None else (f"{value:.3g}" if _finite(value) else eng(value))
    if kind == "eng":
        return eng(value)
    if kind == "pct":
        return pct(value)
    if kind == "p":
        if value is None:
            return "-"
        lo, hi = rec.get("p_lo"), rec.get("p_hi")
        return f"{value:.2g}" + (f" [{lo:.2g}, {hi:.2g}]" if _finite(lo) and _finite(hi) else "")
    if kind == "contributors":
        return ", ".join(f"{q} {100 * sh:.0f} %" for q, sh in (value or [])[:3])
    if isinstance(value, (dict, list, tuple)):
        return ""
    return eng(value) if isinstance(value, (int, float)) and not isinstance(value, bool) else _e(value)


def _shown_checks(robust: dict) -> list[dict]:
    """The check records a page shows: every counted one and every one that scatters (a constant is no study)."""
    return [c for c in robust.get("checks") or [] if c.get("target") or c.get("method") != "deterministic"]


def capability_summary(robust: dict) -> str:
    """One paragraph: whether the design meets the target, the target, the sample, the worst figures, what fails."""
    if not robust.get("checks"):
        return "<p>No capability study yet.</p>"
    st = robust.get("settings") or {}
    meets = robust.get("meets")
    labels = {c["id"]: c.get("label", c["id"]) for c in robust["checks"]}
    parts = []
    if robust.get("min_ppk") is not None:
        parts.append(f"smallest Ppk {_cell('3g', robust['min_ppk'], {})}")
    if robust.get("max_p_violation") is not None:
        parts.append(f"largest P(violation) {robust['max_p_violation']:.2g}")
    failing = [labels.get(f, f) for f in robust.get("failing") or []]
    head = "" if meets is None else ("Meets" if meets else "MISSES")
    sample = ", ".join(x for x in (f"{st['samples']} samples" if st.get("samples") else "",
                                   f"seed {st['seed']}" if st.get("seed") is not None else "") if x)
    return (f'<p data-testid="capability-verdict" data-meets="{_e(meets)}"><b>{_e(head)} the target</b> '
            f"({_e(robust.get('targets', ''))}{'; ' + _e(sample) if sample else ''}): {_e('; '.join(parts))}"
            + (f"; failing: {_e(', '.join(failing))}" if failing else "") + ".</p>")


def capability_table(robust: dict) -> str:
    """One row per check a page shows (:func:`_shown_checks`): the figures its record carries, known ones first
    (Ppk, ppm, P(violation), margins, the contributors), then any other; a counted check in its verdict's colour."""
    rows = _shown_checks(robust)
    known = [c for c in _CAPABILITY_COLUMNS if any(c[0] in r for r in rows)]
    named = {k for k, _, _ in _CAPABILITY_COLUMNS} | _CAPABILITY_HIDDEN
    extra = [k for k in dict.fromkeys(k for r in rows for k in r) if k not in named
             and all(not isinstance(r.get(k), (dict, list, tuple)) for r in rows)]
    cols = known + [(k, k.replace("_", " "), "pct" if k.endswith("_margin") else "other") for k in extra]
    head = "<th>check</th>" + "".join(f"<th>{_e(h)}</th>" for _, h, _ in cols)
    body = []
    for r in rows:
        verdict = ("pass" if r.get("meets", True) else "fail") if r.get("target") else None
        style = f' style="background:{fill(verdict)}"' if verdict else ""
        cells = "".join(f'<td class="num">{_cell(kind, r.get(k), r)}</td>' if kind in ("3g", "eng", "pct", "p")
                        else f"<td>{_cell(kind, r.get(k), r)}</td>" for k, _, kind in cols)
        body.append(f'<tr data-check="{_e(r.get("id"))}"{style}><td>{_e(r.get("label", r.get("id")))}</td>{cells}</tr>')
    return f'<table class="capability"><thead><tr>{head}</tr></thead><tbody>{"".join(body)}</tbody></table>'


def contributors(robust: dict) -> dict[str, list]:
    """``{check id: [(quantity, share)]}`` of the checks shown that name what drives their scatter."""
    return {r["id"]: [(str(q), float(sh)) for q, sh in r["contributors"]] for r in _shown_checks(robust)
            if r.get("contributors")}


# --- alternatives side by side ------------------------------------------------------------------------------------------
def compare_alternatives(alternatives: list[dict], applied: int | None = None) -> str:
    """The ranked designs (``Result.alternatives``) side by side: one column per design, rows for the verdict, the
    objectives, the smallest margin and what sets it, then every part; a part that differs from #1 is marked."""
    from types import SimpleNamespace
    if not alternatives:
        return "<p>No alternatives: synthesise to rank designs (K above).</p>"
    words = {a["rank"]: a for a in alternative_rows(SimpleNamespace(alternatives=alternatives))}
    ranks = [a["rank"] for a in alternatives]
    head = "<th></th>" + "".join(
        f'<th data-rank="{r}">#{r}{" (in view)" if r == applied else ""}</th>' for r in ranks)
    rows = [("verdict", [verdict_word(a.get("verdict")) for a in alternatives], None),
            ("objectives", [words[r]["objectives"] for r in ranks], None),
            ("smallest margin", [words[r]["margin"] for r in ranks], None),
            ("set by", [words[r]["binding"] for r in ranks], None)]
    first = alternatives[0].get("parts") or {}
    for k in dict.fromkeys(k for a in alternatives for k in (a.get("parts") or {})):
        vals = [(a.get("parts") or {}).get(k) for a in alternatives]
        rows.append((part_label(k), [part_value(v) for v in vals], [str(v) != str(first.get(k)) for v in vals]))
    body = []
    for name, vals, differs in rows:
        cells = "".join(f"<td{' class=differs' if differs and differs[i] else ''}>{_e(v)}</td>"
                        for i, v in enumerate(vals))
        body.append(f"<tr><th>{_e(name)}</th>{cells}</tr>")
    return (f'<table class="compare"><thead><tr>{head}</tr></thead><tbody>{"".join(body)}</tbody></table>'
            '<p class="small">Marked: a part that differs from #1, the optimum.</p>')


def part_value(v) -> str:
    """A part's value: ``none`` for an absent class (``none``, 0, empty), numbers without trailing zeros."""
    if v is None or (isinstance(v, str) and v.strip().lower() in ("", "none", "nan")):
        return "none"
    if isinstance(v, (int, float)) and not isinstance(v, bool):
        return "none" if v == 0 else eng(v)
    return str(v)


# --- the 3D view -------------------------------------------------------------------------------------------------------
def fit_view(bbox, *, size: float = 4.0, fov_deg: float = 75.0, direction=(1.0, -1.3, 1.1), margin: float = 1.15
             ) -> dict:
    """How the 3D view frames a model of bounding box ``bbox`` (mm: xmin, ymin, zmin, xmax, ymax, zmax): the
    ``scale`` (mm to scene units: the model ``size`` units across) and ``offset`` that put its centre at the origin,
    and the ``camera`` position along ``direction`` from which its bounding sphere fills the view's height
    (``fov_deg``, three.js's vertical field of view) with ``margin``.

    >>> v = fit_view([-30, -30, -10, 30, 30, 40])
    >>> v["scale"], v["offset"], [round(c, 2) for c in v["camera"]]
    (0.066667, [0.0, 0.0, -1.0], [3.14, -4.08, 3.45])
    """
    import math
    lo, hi = bbox[:3], bbox[3:]
    centre = [(a + b) / 2 for a, b in zip(lo, hi)]
    extent = max(b - a for a, b in zip(lo, hi)) or 1.0
    scale = size / extent
    radius = 0.5 * scale * math.sqrt(sum((b - a) ** 2 for a, b in zip(lo, hi)))
    dist = margin * radius / math.sin(math.radians(fov_deg) / 2)
    norm = math.sqrt(sum(d * d for d in direction))
    return {"scale": round(scale, 6), "offset": [round(-c * scale, 6) + 0.0 for c in centre],
            "camera": [dist * d / norm for d in direction]}
