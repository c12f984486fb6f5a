"""The results workbook: the output table (thesis Tables 10/14) with verdict colours, and more.

Sheets:

* ``Output``: the rows of :data:`synth.output_table.ROWS` (section, parameter,
  unit, value) with the verdict of the flowchart step that produced the row,
  coloured as in the thesis (green verified, red failed, orange not verified
  because data is missing), and the suggested corrections of the failed checks;
* ``Checks``: every check in the flowchart's step order with value, limit,
  margin, verdict, equation and suggested correction (:mod:`synth.formatting`:
  a yes/no check's value is ``yes`` or ``no``, without limit or margin; a
  margin against a zero limit is the distance in the check's unit, not a
  percentage);
* ``Input``: the echo of the data read (thesis column F), with the cell it was
  read from when the input is a workbook, and the suggested correction of
  each field (thesis column G);
* ``Notes``; and one sheet per other scene result given (``Optimum``,
  ``Pareto``, ``Solvers``...: tables of rows).

Row verdicts (:func:`synth.design.result.row_verdict`): the worst verdict of
the checks that compare the row's value (the registry says which); no colour
when no check reads it.

>>> from synth.design.result import Result
>>> _row_fill_key(Result("verified", values={"pulley_width_mm": 20.0}), "pulley_width_mm") is None
True
"""

from __future__ import annotations

import math
from pathlib import Path

from synth import formatting as fmt
from synth import schema
from synth.design.constraints import FEAS_TOL
from synth.design.result import FAIL, NOT_VERIFIED, PASS, WARNING, field_corrections, row_verdict
from synth.excel.cells import page_setup, put, wrap
from synth.excel.template import FILLS
from synth.output_table import ROWS, format_value
from synth.report.advice import correction, rule_lines
from synth.flowchart import STEP_NAMES
from synth.io.outputs import output_file

__all__ = ["build_results", "write_results"]

def _missing(v) -> bool:
    return v is None or (isinstance(v, float) and not math.isfinite(v))


def _row_fill_key(result, key):
    return row_verdict(result, key)


def _fill(key):
    from openpyxl.styles import PatternFill
    colour = FILLS.get(key)
    return PatternFill("solid", start_color=colour, end_color=colour) if colour else PatternFill()


def _cell_value(v):
    """A value as a cell can hold it (numbers stay numbers; lists and booleans formatted)."""
    if _missing(v):
        return None
    if isinstance(v, bool) or isinstance(v, (list, tuple)):
        return format_value(v)
    if hasattr(v, "item"):
        v = v.item()
    if isinstance(v, (int, float, str)):
        return v
    return str(v)


def _header(ws, row: int, headers: list[str], widths: list[float]) -> None:
    from openpyxl.styles import Font
    from openpyxl.utils import get_column_letter
    for j, (h, w) in enumerate(zip(headers, widths), start=1):
        cell = put(ws, row, j, h)
        cell.font = Font(bold=True)
        cell.fill = _fill("header")
        ws.column_dimensions[get_column_letter(j)].width = w
    ws.freeze_panes = ws.cell(row=row + 1, column=1)


def _title(ws, text: str, verdict: str | None = None) -> None:
    from openpyxl.styles import Font
    put(ws, 1, 1, text).font = Font(bold=True, size=13)
    if verdict:
        put(ws, 2, 1, f"Verdict: {verdict.upper()}").font = Font(bold=True)
        _verdict_colours(ws, "A2", "$A$2", contains=True)


def _rule(formula: str, key: str):
    from openpyxl.formatting.rule import FormulaRule
    from openpyxl.styles import PatternFill
    colour = FILLS[key]
    return FormulaRule(formula=[formula], fill=PatternFill("solid", start_color=colour, end_color=colour,
                                                           bgColor=colour), stopIfTrue=True)


def _verdict_colours(ws, cells: str, ref: str, *, contains: bool = False) -> None:
    """Colour ``cells`` by the verdict text in ``ref`` (a conditional format: editing the verdict recolours).

    ``ref`` is the first row's verdict cell (``$E5``: relative row); ``contains``
    matches ``Verdict: FAIL``-style text.
    """
    for key in (FAIL, NOT_VERIFIED, WARNING, PASS):
        word = key.upper() if contains else key
        formula = f'ISNUMBER(SEARCH("{word}",{ref}))' if contains else f'{ref}="{word}"'
        ws.conditional_formatting.add(cells, _rule(formula, key))


def _output_sheet(ws, result) -> None:
    _title(ws, "Output table (thesis Tables 10/14)", result.verdict)
    rules = rule_lines(result)
    put(ws, 3, 1, "; ".join(x.strip() for x in rules) if rules else "design rules: none given (the catalogs' limits)")
    _header(ws, 4, ["Section", "Parameter", "Unit", "Value", "Verdict", "Suggested correction"], [24, 36, 8, 14, 13, 70])
    r = 5
    for section, label, key, unit in ROWS:
        v = result.get(key)
        verdict = row_verdict(result, key)
        corr = "; ".join(dict.fromkeys(correction(result, c) for c in result.failed()
                                       if key in (c.constraint.value, c.constraint.limit) and correction(result, c)))
        for j, val in enumerate([section, label, unit, _cell_value(v), verdict or "", corr or None], start=1):
            put(ws, r, j, val)
        r += 1
    _verdict_colours(ws, f"D5:E{max(r - 1, 5)}", "$E5")
    wrap(ws, "F", 5, r - 1)
    page_setup(ws, "synth results: output table", header_rows="4:4", subtitle=_subtitle(result))


def _checks_sheet(ws, result) -> None:
    _title(ws, "Checks (every verdict with its margin)", result.verdict)
    _header(ws, 4, ["Step", "Step name", "Check", "Value", "Relation", "Limit", "Unit", "Margin [%]", "Verdict",
                    "Equation", "Suggested correction", "Note"], [6, 20, 42, 11, 8, 11, 8, 14, 12, 13, 50, 40])
    r = 4
    # in the flowchart's step order (the registry's within a step), as the terminal and the report list them
    rows = sorted((c for c in result.checks if c.verdict != "not applicable"), key=lambda c: c.constraint.step)
    for r, c in enumerate(rows, start=5):
        con = c.constraint
        note = "; ".join([c.note] + c.assumed).strip("; ") if (c.note or c.assumed) else None
        if fmt.is_logical(con, c.value, c.limit):  # a condition met or not: yes/no, no limit, no margin
            value, sense, limit, unit, margin = fmt.check_relation(c), None, None, None, None
        else:
            value, sense, limit, unit = _cell_value(c.value), con.sense if c.value is not None else None, \
                _cell_value(c.limit), con.unit
            # a percentage of the limit; against a zero limit the distance in the check's unit, in words
            margin = (fmt.check_margin(c) if fmt.zero_limit(con, c.limit) else 100.0 * c.margin) \
                if c.margin is not None else None
        row = [con.step, STEP_NAMES.get(con.step, ""), con.label, value, sense, limit, unit, margin, c.verdict,
               con.equation, correction(result, c) if c.verdict == FAIL else None, note]
        for j, val in enumerate(row, start=1):
            put(ws, r, j, val)
    last = max(r, 5)
    # the colour follows value against limit (editing a value recolours), the verdict text for "not verified";
    # pass when the value is on the limit's side; FEAS_TOL of |limit| (of 1 for a zero limit) absorbs round-off
    # as the registry's margin does (its scale may differ from |limit|: that changes nothing but round-off)
    over = "($D5-$F5)" + '*IF($E5="<=",1,-1)'
    tol = f"{FEAS_TOL:.0E}*IF($F5=0,1,ABS($F5))"
    numbers = "ISNUMBER($D5),ISNUMBER($F5)"
    cells = f"D5:D{last} H5:I{last}"
    ws.conditional_formatting.add(cells, _rule('$I5="not verified"', NOT_VERIFIED))
    ws.conditional_formatting.add(cells, _rule('$I5="warning"', WARNING))  # advisory: amber whatever the value
    ws.conditional_formatting.add(cells, _rule(f"AND({numbers},{over}>{tol})", FAIL))
    ws.conditional_formatting.add(cells, _rule(f"AND({numbers},{over}<={tol})", PASS))
    # a yes/no check has no number to compare: its verdict colours it
    ws.conditional_formatting.add(cells, _rule('AND(NOT(ISNUMBER($D5)),$I5="fail")', FAIL))
    ws.conditional_formatting.add(cells, _rule('AND(NOT(ISNUMBER($D5)),$I5="pass")', PASS))
    wrap(ws, "C", 5, last)  # the whole check name (it was cut at the column's edge)
    wrap(ws, "K", 5, last)
    wrap(ws, "L", 5, last)
    page_setup(ws, "synth results: checks", header_rows="4:4", subtitle=_subtitle(result))


def _input_sheet(ws, result, cells: dict | None, source: str | None) -> None:
    _title(ws, "Data read (echo of the design input)" + (f": {source}" if source else ""))
    _header(ws, 4, ["Parameter", "Field", "Unit", "Required", "Data read", "Read from cell", "Suggested correction"],
            [50, 40, 8, 10, 14, 12, 60])
    corr = field_corrections(result)
    values = result.inputs or {}
    r = 5
    for section in schema.SECTIONS:
        put(ws, r, 1, section).fill = _fill("section")
        r += 1
        for f in (f for f in schema.FIELDS if f.section == section):
            v = values.get(f.name)
            row = [f.label or f.name, f.name, f.unit, "required" if f.required else "optional", _cell_value(v),
                   (cells or {}).get(f.name), corr.get(f.name)]
            for j, val in enumerate(row, start=1):
                put(ws, r, j, val)
            status = "fail" if f.name in corr and not _missing(v) else ("pass" if not _missing(v) else
                                                                       ("not verified" if f.name in corr else None))
            if status:
                ws.cell(row=r, column=5).fill = _fill(status)
            r += 1
    wrap(ws, "G", 5, r - 1)
    page_setup(ws, "synth results: data read", header_rows="4:4", subtitle=source or "")


def _table_sheet(ws, title: str, rows) -> None:
    """A scene result as a plain table: a DataFrame, a list of dicts, or a dict (one row)."""
    from openpyxl.utils import get_column_letter
    if hasattr(rows, "to_dict"):
        rows = rows.to_dict(orient="records")
    if isinstance(rows, dict):
        rows = [rows]
    rows = list(rows or [])
    _title(ws, title)
    headers = list(dict.fromkeys(str(k) for row in rows for k in row))
    _header(ws, 3, headers, [max(12, min(40, len(h) + 2)) for h in headers])
    for r, row in enumerate(rows, start=4):
        row = {str(k): v for k, v in row.items()}
        for j, h in enumerate(headers, start=1):
            put(ws, r, j, _cell_value(row.get(h)))
    if "verdict" in headers and rows:
        col = get_column_letter(headers.index("verdict") + 1)
        _verdict_colours(ws, f"{col}4:{col}{len(rows) + 3}", f"${col}4")
    page_setup(ws, f"synth results: {title}", header_rows="3:3")


def _subtitle(result) -> str:
    return f"verdict {result.verdict.upper()}"


def build_results(result=None, *, cells: dict | None = None, source: str | None = None, scenes: dict | None = None):
    """The results :class:`openpyxl.Workbook` of a flowchart result and other scene results.

    ``result``: a :class:`synth.design.result.Result` (Output, Checks,
    Input, Notes sheets); ``cells``: ``{field: "E14"}`` when the input was a
    workbook; ``scenes``: ``{"Optimum": rows, "Pareto": rows, "Solvers":
    rows}`` (each a DataFrame, list of dicts or one dict), one sheet each.
    """
    from openpyxl import Workbook
    wb = Workbook()
    first = wb.active
    if result is not None:
        first.title = "Output"
        _output_sheet(first, result)
        _checks_sheet(wb.create_sheet("Checks"), result)
        _input_sheet(wb.create_sheet("Input"), result, cells, source)
        notes = wb.create_sheet("Notes")
        _title(notes, "Notes")
        for r, n in enumerate(result.notes, start=3):
            put(notes, r, 1, n)
        notes.column_dimensions["A"].width = 120
        wrap(notes, "A", 3, len(result.notes) + 2)
        page_setup(notes, "synth results: notes", subtitle=_subtitle(result))
    for name, rows in (scenes or {}).items():
        if rows is None:
            continue
        ws = first if result is None and first.max_row == 1 and first["A1"].value is None else wb.create_sheet()
        ws.title = str(name)[:31]
        _table_sheet(ws, str(name), rows)
    return wb


def write_results(path: str | Path, result=None, **kw) -> Path:
    """Write :func:`build_results` to ``path`` (.xlsx) and return the path."""
    p = Path(path)
    wb = build_results(result, **kw)
    with output_file(p) as tmp:
        wb.save(tmp)
    return p
