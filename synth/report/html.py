"""The design report: one self-contained HTML file (inline CSS, PNG graphs embedded as base64), and its digest.

Built from a :class:`synth.design.result.Result` with the Jinja2 templates of
``synth/report/templates`` (autoescaped). In order:

1. the **digest**: the verdict, then the failing checks worst first (value,
   limit, margin, the suggested correction), the diagnosis of an infeasible
   input, the warnings (advisory checks), the checks not verified with what is
   missing, and the documented defaults assumed;
2. the table of contents and the **document** block: synth version and
   catalog hash (:func:`synth.fingerprint.version_text`), input file and its SHA-256,
   the design input's own SHA-256 (the same for a YAML file and the saved
   result of it), date, author and revision;
3. the design (parts, what binds), the model settings in words, the output
   table of thesis Tables 10/14 and every check, each row coloured with its
   own verdict (:func:`synth.design.result.row_verdict` for an output row,
   the check's verdict for a check row: :data:`VERDICT_COLOURS`);
4. the 3D model's section and exploded pictures, the graphs of
   :mod:`synth.report.plots`, a platform section (the hook
   :func:`platform_section`), other scenes' tables, notes and the data read;
5. an appendix with the derivation of each failing check and of the five
   smallest margins (:func:`derivation_rows`, :mod:`synth.design.derivation`).

Print: A4 landscape or portrait (``page``), a title block on every page (page
margin boxes: title and verdict on top; input, revision, author, synth version
and page n of N below), a page break before each main section, table headers
repeated, no row or figure split across pages, verdict colours printed.

Each graph is a ``<figure id="fig-<graph id>" data-verdict=... data-points="N">``
whose image is ``data:image/png;base64,...``; output rows carry ``data-key``,
check rows ``data-check``, both ``data-verdict``, so tests and scripts find them.

>>> VERDICT_COLOURS["fail"], verdict_class("not verified")
('#ffc7ce', 'v-nv')
>>> css_string('rev "B"\\nA. Person')
'"rev \\\\000022B\\\\000022\\\\00000AA. Person"'
"""

from __future__ import annotations

import base64
import datetime as _dt
import functools
import hashlib
import json
import os
from pathlib import Path

from synth.design.result import FAIL, INCOMPLETE, NOT_APPLICABLE, NOT_VERIFIED, PASS, WARNING, field_corrections, \
    row_verdict, absent_part, part_note
from synth import formatting as fmt
from synth.fingerprint import file_sha256
from synth.report.palette import VERDICT_FILLS
from synth.output_table import ROWS, format_value
from synth.fingerprint import version_text
from synth.design.evaluate import FIDELITY_TEXT
from synth.report.advice import correction
from synth.report.advice import relaxation_lines
from synth.report.advice import change_lines, objective_line, rule_lines
from synth.report.text import verdict_line
from synth.flowchart import STEP_NAMES
from synth import schema
from synth.report.plots import GRAPH_CHECKS, ON_REQUEST
from synth.errors import InputError, Problem
from synth.report.advice import alternative_rows
from synth.report import cost as cost_words
from synth.report.robust import robust_section
from synth.io.outputs import write_text

__all__ = ["render_html", "write_html", "digest_html", "digest_css", "metadata", "document_date", "settings_in_words", "platform_section",
           "VERDICT_COLOURS", "verdict_class", "css_string", "check_steps", "check_row", "part_label", "derivation_rows",
           "listed_skips"]

#: background colour of a row per verdict (thesis colours: green verified, red failed, orange not verified);
#: ``None``: a row no check reads
VERDICT_COLOURS = {**{k: f"#{v.lower()}" for k, v in VERDICT_FILLS.items()}, None: "#ffffff"}
_CLASSES = {PASS: "v-pass", FAIL: "v-fail", WARNING: "v-warning", NOT_VERIFIED: "v-nv", NOT_APPLICABLE: "v-na",
            None: "v-none", INCOMPLETE: "v-nv"}
_INK = {PASS: "#1b5e20", FAIL: "#9c0006", INCOMPLETE: "#7f6000"}

_TEMPLATES = Path(__file__).resolve().parent / "templates"

_CSS = """
body.synth{font-family:"Segoe UI",Roboto,"Helvetica Neue",Arial,"DejaVu Sans",sans-serif;margin:1.5em auto;
  max-width:1200px;color:#222;line-height:1.35}
.synth h1{margin:.1em 0 .2em;font-size:1.7em} .synth h2{border-bottom:2px solid #1f4e78;padding-bottom:.15em;
  margin-top:1.4em;color:#1f4e78} .synth h3{margin:1em 0 .3em;font-size:1.05em}
.synth table{border-collapse:collapse;width:100%;font-size:.88em;margin:.4em 0}
.synth th,.synth td{border:1px solid #c8c8c8;padding:2px 6px;text-align:left;vertical-align:top}
.synth thead th{background:#d9e2ec} .synth table.kv th{background:#eef2f6;width:24%;font-weight:600}
.synth td.num{text-align:right;font-variant-numeric:tabular-nums;white-space:nowrap}
.synth tr.group td{background:#bdd7ee;font-weight:bold}
.synth tr.v-pass{background:@pass@} .synth tr.v-fail{background:@fail@} .synth tr.v-warning{background:@warning@}
.synth tr.v-nv{background:@not verified@} .synth tr.v-na{background:@not applicable@;color:#666} .synth tr.v-none{background:#ffffff}
.synth .banner{display:inline-block;padding:.3em .9em;font-weight:bold;border-radius:4px;font-size:1.15em;margin-right:.6em}
.synth .banner.v-pass{background:@pass@;color:#1b5e20} .synth .banner.v-fail{background:@fail@;color:#9c0006}
.synth .banner.v-nv{background:@not verified@;color:#7f6000}
.synth figure{display:inline-block;margin:.5em;border:3px solid #bbb;padding:4px;vertical-align:top;width:46%}
.synth figure.v-pass{border-color:#2e7d32} .synth figure.v-fail{border-color:#c62828}
.synth figure.v-warning{border-color:#ef6c00} .synth figure.cad{width:47%;border-color:#1f4e78}
.synth figure img{width:100%} .synth figcaption{font-size:.85em}
.synth .small{font-size:.85em;color:#555} .synth nav ol{columns:3;font-size:.92em}
.synth code{font-size:.9em}
.synth pre.derivation{font-size:.78em;white-space:pre-wrap;overflow-wrap:anywhere;background:#f7f7f7;padding:.4em}
@media print{
  body.synth{max-width:none;margin:0;font-size:8.5pt}
  .synth *{-webkit-print-color-adjust:exact;print-color-adjust:exact}
  .synth header.title{display:none}
  .synth section.page{break-before:page}
  .synth h2,.synth h3{break-after:avoid}
  .synth thead{display:table-header-group}
  .synth tr,.synth figure,.synth img{break-inside:avoid}
  .synth figure{width:47%}
  .synth figure.cad{display:block;width:auto;margin:.3em 0;text-align:center}
  .synth figure.cad img{width:auto;max-width:100%;max-height:@cad_height@mm}
  .synth a{color:inherit;text-decoration:none}
}
"""
#: the largest printed height of a CAD picture [mm]: alone across the page (A4 landscape leaves 174 mm between the
#: margins), its text at 6 pt or more (synth.cad.pictures.DIMENSION_PT, LABEL_PT)
CAD_PRINT_MAX_HEIGHT_MM = 150.0
_CSS = _CSS.replace("@cad_height@", f"{CAD_PRINT_MAX_HEIGHT_MM:g}")
for _verdict, _colour in VERDICT_COLOURS.items():  # the palette's colours into the style sheet
    _CSS = _CSS.replace(f"@{_verdict}@", _colour)


def verdict_class(verdict) -> str:
    """The CSS class of a verdict (``v-pass``, ``v-fail``, ``v-warning``, ``v-nv``, ``v-na``, ``v-none``)."""
    return _CLASSES.get(verdict, "v-none")


_CSS_PLAIN = frozenset("ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789 .,_-:")


def css_string(text) -> str:
    r"""``text`` as a CSS string literal, safe by construction inside a ``<style>`` element: letters, digits,
    spaces and ``.,_-:`` as they are, every other character as a six-digit CSS escape (CSS Syntax Level 3,
    4.3.7: ``<`` is ``\00003C``), so no text can close the string, the rule or the ``<style>`` element.

    >>> css_string('</style><script>x</script> "a" rev. 2')
    '"\\00003C\\00002Fstyle\\00003E\\00003Cscript\\00003Ex\\00003C\\00002Fscript\\00003E \\000022a\\000022 rev. 2"'
    """
    return '"' + "".join(ch if ch in _CSS_PLAIN else f"\\{ord(ch):06X}" for ch in str(text).replace("\r", "")) + '"'


def _num(v) -> str:
    return format_value(v)


def _now() -> _dt.datetime:
    """Now, or ``SOURCE_DATE_EPOCH`` (reproducible builds) when set."""
    epoch = os.environ.get("SOURCE_DATE_EPOCH", "")
    if epoch.isdigit():
        return _dt.datetime.fromtimestamp(int(epoch), tz=_dt.timezone.utc)
    return _dt.datetime.now().astimezone()


def document_date() -> str:
    """The date a document made now carries (minutes; ``SOURCE_DATE_EPOCH`` when set)."""
    return _now().strftime("%Y-%m-%d %H:%M %Z").strip()


def metadata(result, source=None, *, author: str = "", revision: str = "", date: str | None = None,
             catalog_dirs=()) -> dict:
    """The document block: synth version and catalog hash, input file and SHA-256, inputs hash, date, author, revision.

    ``inputs_sha256`` hashes the design input itself (canonical JSON of ``result.inputs``): a YAML file
    and the saved result of it give the same value.
    """
    src = Path(source) if source not in (None, "", "result") else None
    inputs = {k: v for k, v in (result.inputs or {}).items() if v is not None}
    return {
        "synth": version_text(catalog_dirs),
        "input": str(src) if src else "(a Result given in Python)",
        "input_sha256": file_sha256(src) if src and src.is_file() else "-",
        "inputs_sha256": hashlib.sha256(json.dumps(inputs, sort_keys=True, default=str).encode()).hexdigest()
        if inputs else "-",
        "date": date or document_date(),
        "author": author or "", "revision": revision or "",
    }


def settings_in_words(result) -> list[tuple[str, str]]:
    """The model settings and how the design was found, as ``(setting, sentence)`` rows."""
    s = result.settings or {}
    rows = []
    if result.solver == "flowchart":
        how = ("the thesis flowchart's sequential selection (steps 0-10 and their iterations)"
               if result.status != "verified" else "a given design checked through every step (nothing selected)")
    elif result.solver:
        how = (f"synthesis by the {result.solver} solver, objective {result.objective or '-'} "
               f"(status {result.status})")
    else:
        how = f"a given design verified through the evaluator (status {result.status})"
    rows.append(("Design", how))
    rows.append(("Fidelity", FIDELITY_TEXT.get(s.get("fidelity", "full"), str(s.get("fidelity")))))
    rows.append(("Radial friction", "on the friction circle r_p sin(atan mu) (physics)"
                 if s.get("friction_circle", True) else "on r_p mu, as the thesis tool's tables"))
    rows.append(("Bushing wear", "with the running-in of the pivot clearance integrated (an extension, "
                 "illustrative constants)" if s.get("bushing_running_in") else "closed form, eq. (32)"))
    if result.solver == "flowchart" and result.status != "verified":
        rows.append(("Bushing length", "the thesis tool's trial lengths (multiples of half the pivot diameter), "
                     "then the next catalog length" if s.get("bushing_length_scheme", "thesis") == "thesis"
                     else "the shortest catalog length that passes"))
    rows.append(("Bolt check", "VDI 2230-1 permissible assembly preload (plastic torsion factor, tightening "
                 "factor, embedding loss)" if s.get("bolt_method") == "vdi2230"
                 else "elastic von Mises check of the nominal preload, eq. (103)-(107) (the thesis tool)"))
    return rows


def platform_section(platform) -> str | None:
    """The platform section's HTML (a fragment synth made) of a rationalisation output, or None.

    The hook of :func:`synth.platform.outputs.report_section` (the rationalisation result in Python,
    its output folder from the command line); where that function does not exist yet, a sentence says so.
    """
    if platform is None:
        return None
    from markupsafe import Markup, escape
    try:
        from synth.platform.outputs import report_section
    except ImportError:
        return Markup(f"<p>A platform output was given ({escape(str(platform))}), but this version of synth has no "
                      "<code>synth.platform.outputs.report_section</code> to draw it.</p>")
    return Markup(report_section(platform))


def check_row(c, result=None) -> dict:
    """One check as the report shows it (formatted value, limit, margin; verdict and its class; the correction,
    in agreement with how ``result`` was found: :func:`synth.report.advice.correction`)."""
    con = c.constraint
    fix = correction(result, c) if result is not None else con.correction
    extra = fix if c.verdict in (FAIL, WARNING) and fix else \
        "; ".join(x for x in [c.note, *c.assumed] if x)
    logical = fmt.is_logical(con, c.value, c.limit)  # a condition met or not: yes/no, no limit, no margin
    return {"id": c.id, "label": con.label, "step": con.step,
            "value": fmt.check_relation(c) if logical else fmt.number(c.value),
            "sense": con.sense if c.value is not None and not logical else "",
            "limit": "" if logical else fmt.number(c.limit), "unit": "" if logical else con.unit,
            "margin": fmt.check_margin(c), "verdict": c.verdict, "cls": verdict_class(c.verdict),
            "equation": con.equation, "correction": fix, "note": c.note, "extra": extra}


def _diagnosis(result):
    dg = result.diagnosis
    if not dg:
        return None
    return {"message": dg.get("message", ""), "relaxations": relaxation_lines(result)}


def digest_context(result) -> dict:
    """What the digest shows, as plain rows (the template's data)."""
    by_margin = sorted(result.failed(), key=lambda c: (c.margin if c.margin is not None else 0.0))
    p = result.parts or {}
    design = f"Design: {fmt.design_label(p)}." if p else ""
    line = verdict_line(result)
    line = line[line.index("(") + 1:-1] if line.endswith(")") and "(" in line else ""
    return {"verdict": result.verdict, "cls": verdict_class(result.verdict), "line": line,
            "design": design, "failed": [check_row(c, result) for c in by_margin],
            "warnings": [check_row(c, result) for c in sorted(result.warnings(), key=lambda c: c.margin or 0.0)],
            "not_verified": [check_row(c, result) for c in result.not_verified()], "changes": change_lines(result),
            "objectives": objective_line(result.objectives) if result.objectives else "",
            "rules": "; ".join(x.strip() for x in rule_lines(result)),
            "assumed": result.assumptions(), "diagnosis": _diagnosis(result)}


@functools.lru_cache(maxsize=1)
def _environment():
    """The report's Jinja environment, made once per process: it keeps the compiled templates (an edit in ``synth ui``
    renders the digest again; compiling it each time was half of that)."""
    import jinja2
    env = jinja2.Environment(loader=jinja2.FileSystemLoader(str(_TEMPLATES)), autoescape=True,
                             undefined=jinja2.StrictUndefined, trim_blocks=False, lstrip_blocks=False)
    env.filters["css_string"] = lambda s: jinja2.utils.markupsafe.Markup(css_string(s))
    return env


@functools.lru_cache(maxsize=1)
def _digest_template():
    return _environment().from_string('{% from "digest.html.j2" import digest %}<div class="synth">{{ digest(d) }}'
                                      '</div>')


def digest_html(result, *, styles: bool = True) -> str:
    """The digest alone, with its own styles (``Result._repr_html_``: a notebook shows it); ``styles=False``: without
    them (:func:`digest_css`, the same for every result: a page that shows many digests holds them once)."""
    body = _digest_template().render(d=digest_context(result))
    return f"<style>{_CSS}</style>" + body if styles else body


def digest_css() -> str:
    """The style sheet :func:`digest_html` carries (the report's)."""
    return _CSS


def _output_rows(result) -> list:
    readers: dict = {}
    for c in result.checks:
        if c.verdict == NOT_APPLICABLE:
            continue
        for k in {c.constraint.value, c.constraint.limit}:
            readers.setdefault(k, []).append(c.id)
    out, cur = [], None
    for section, label, key, unit in ROWS:
        if cur is None or cur["name"] != section:
            cur = {"name": section, "rows": []}
            out.append(cur)
        v = row_verdict(result, key)
        cur["rows"].append({"key": key, "label": label, "unit": unit, "value": _num(result.get(key)),
                            "verdict": v or "", "cls": verdict_class(v), "checks": ", ".join(readers.get(key, []))})
    return out


def check_steps(result) -> tuple[list, list]:
    """The checks as the report lists them: ``([{"step", "name", "rows"}], labels not applicable)``, each row
    formatted (value, limit, margin, verdict and its CSS class, equation, correction or note); ``synth ui``
    shows the same rows."""
    steps: dict = {}
    na = []
    for c in sorted(result.checks, key=lambda c: c.constraint.step):
        if c.verdict == NOT_APPLICABLE:
            na.append(c.constraint.label)
            continue
        steps.setdefault(c.step, []).append(check_row(c, result))
    names = {**STEP_NAMES, 11: "3D model"}
    return [{"step": s, "name": names.get(s, ""), "rows": rows} for s, rows in steps.items()], na


def _inputs(result) -> list:
    d = result.inputs or {}
    corr = field_corrections(result)
    out = []
    for section in schema.SECTIONS:
        rows = []
        for f in (f for f in schema.FIELDS if f.section == section):
            val = d.get(f.name)
            cls = "" if f.name not in corr else ("v-nv" if val is None else "v-fail")
            rows.append({"name": f.name, "label": f.label or f.name, "unit": f.unit, "required": f.required,
                         "value": format_value(val), "correction": corr.get(f.name, ""), "cls": cls})
        out.append({"name": section, "rows": rows})
    return out


def _scene(name: str, rows) -> dict | None:
    if rows is None:
        return None
    if hasattr(rows, "to_dict"):
        rows = rows.to_dict(orient="records")
    if isinstance(rows, dict):
        rows = [rows]
    rows = list(rows or [])
    if not rows:
        return None
    cols = list(dict.fromkeys(k for r in rows for k in r))
    return {"id": name.lower().replace(" ", "-"), "name": name, "columns": cols,
            "rows": [[_num(r.get(c)) for c in cols] for r in rows]}


def _figure(g) -> dict:
    n = max((len(v) for v in g.series.values()), default=0)
    return {"id": g.id, "title": g.title, "figure": g.figure, "verdict": g.verdict or "",
            "cls": verdict_class(g.verdict) if g.verdict else "", "points": n,
            "checks": ", ".join(GRAPH_CHECKS.get(g.id, ())), "b64": base64.b64encode(g.png).decode("ascii")}


def render_html(result, graphs, skipped, *, source: str | None = None, title: str | None = None,
                scenes: dict | None = None, author: str = "", revision: str = "", page: str = "landscape",
                platform=None, cad_note: str = "", date: str | None = None, application: str | None = None) -> str:
    """The report of ``result`` as one HTML string (self-contained; see the module docstring).

    ``application``: the application's name (a case file's ``name``), in the title and the document block.

    ``graphs``/``skipped``: :func:`synth.report.plots.build_graphs` (graphs whose id starts with ``cad_``
    go to the 3D model section); ``scenes``: ``{name: rows}`` tables of other scenes; ``page``:
    ``landscape`` or ``portrait`` (A4); ``platform``: a rationalisation output (:func:`platform_section`).
    """
    if page not in ("landscape", "portrait"):
        raise InputError(Problem("--page", page, "landscape or portrait"))
    name = Path(source).name if source not in (None, "", "result") else ""
    shown = " - ".join(x for x in (application, name) if x)
    title = title or f"synth design report{': ' + shown if shown else ''}"
    meta = metadata(result, source, author=author, revision=revision, date=date)
    meta_rows = [("synth and catalogs", meta["synth"])] + ([("Application", application)] if application else []) + [
                 ("Input file", meta["input"]),
                 ("Input file SHA-256", meta["input_sha256"]), ("Design input SHA-256", meta["inputs_sha256"]),
                 ("Date", meta["date"]), ("Author", meta["author"] or "-"), ("Revision", meta["revision"] or "-")]
    if result.solver and result.solver != "flowchart":
        meta_rows.append(("Solver", f"{result.solver}, objective {result.objective or '-'}, status {result.status}"))
    rules = rule_lines(result)
    meta_rows.append(("Design rules", "; ".join(x.strip() for x in rules) if rules else
                      "none given: the catalogs' limits, every check passes at a margin of 0"))
    checks, na = check_steps(result)
    cad = [_figure(g) for g in graphs if g.id.startswith("cad_")]
    figs = [_figure(g) for g in graphs if not g.id.startswith("cad_")]
    scenes = {**cost_words.tables(getattr(result, "cost", None) or {}), **(scenes or {})}
    scene_rows = [s for s in (_scene(k, v) for k, v in scenes.items()) if s]
    plat = platform_section(platform)
    robust = robust_section(result)
    digest = digest_context(result)
    toc = [("digest", "Digest"), ("metadata", "Document"), ("model", "Model settings"), ("design", "Design"),
           ("output", "Output table"), ("checks", "Checks")]
    if cad or cad_note:
        toc.append(("cad", "3D model"))
    toc.append(("graphs", "Graphs"))
    if robust is not None:
        toc.append(("robust", "Production scatter"))
    if plat is not None:
        toc.append(("platform", "Platform rationalisation"))
    toc += [(f"scene-{s['id']}", s["name"]) for s in scene_rows]
    if result.notes:
        toc.append(("notes", "Notes"))
    toc.append(("inputs", "Design input"))
    derived = derivation_rows(result)
    if derived:
        toc.append(("derivations", "Appendix: derivations"))
    block = "  ".join(x for x in (shown or meta["input"], f"rev. {revision}" if revision else "", author,
                                  meta["date"]) if x)
    block += f"\n{meta['synth']}  inputs sha256 {meta['inputs_sha256'][:16]}"
    verdict_text = f"Verdict: {result.verdict.upper()}"
    parts = [(part_label(key), key, fmt.ABSENT if absent_part(result.parts, key) else _num(v), part_note(result, key))
             for key, v in (result.parts or {}).items()]
    return _environment().get_template("report.html.j2").render(
        title=title, css=_CSS, page=page, page_title=title, verdict_text=verdict_text,
        banner_ink=_INK.get(result.verdict, "#222"), title_block=block, meta=meta, meta_rows=meta_rows,
        d=digest, toc=toc, parts=parts, binding=[check_row(c, result) for c in result.binding(5)],
        settings=settings_in_words(result), output=_output_rows(result), legend_na="grey (not applicable)",
        checks=checks, not_applicable=na, cad=cad, cad_note=cad_note, graphs=figs,
        skipped=listed_skips(skipped), platform=plat, robust=robust,
        scenes=scene_rows, notes=list(result.notes), inputs=_inputs(result), alternatives=alternative_rows(result),
        derivations=derived)


def listed_skips(skipped) -> list[dict]:
    """The graphs the report lists as not drawn, with why: not those drawn only from a file the user gives
    (:data:`synth.report.plots.ON_REQUEST`: without the file nothing is missing)."""
    return [{"id": s.id, "title": s.title, "reason": s.reason} for s in skipped if s.id not in ON_REQUEST]


def derivation_rows(result) -> list:
    """The appendix: ``[{"check", "label", "text"}]``, the derivations (:mod:`synth.design.derivation`) of the
    result's failing checks and of its five smallest margins; [] for a result without a design."""
    from synth.design.constraints import EVALUATED_GROUPS, REGISTRY
    from synth.design.derivation import derive_result
    if not result.parts or result.inputs is None:
        return []
    ids = [c.id for c in result.checks if c.verdict == FAIL] + [c.id for c in result.binding(5)]
    ids = [i for i in dict.fromkeys(ids) if i in REGISTRY and REGISTRY[i].group in EVALUATED_GROUPS]
    if not ids:
        return []
    return [{"check": x.check, "label": x.label, "text": x.text()} for x in derive_result(result, ids)]


def part_label(key: str) -> str:
    """A part key in words: its input field's label, else the key itself in words."""
    try:
        f = schema.field_by_name(key)
        return f.label or key
    except Exception:  # noqa: BLE001 - a part key that is not an input field: its words
        return key.replace("_mm", " [mm]").replace("_", " ")


def write_html(path: str | Path, result, graphs, skipped, **kw) -> Path:
    """Write :func:`render_html` to ``path`` (through :func:`synth.io.outputs.write_text`)."""
    return write_text(path, render_html(result, graphs, skipped, **kw))
