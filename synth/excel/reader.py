"""Read a filled design-input workbook (the template of :mod:`synth.excel.template`).

The workbook may be the .xlsx synth writes, the same template saved by
LibreOffice as .xlsx or as .ods (its default format), or saved by Excel;
cells are read through the input gate (:func:`synth.io.workbook.read_sheet`:
size and unpacked-size limits, at most 2,000 rows). A formula cell is read
by its cached value; a formula without one is explained, not reported as
missing. Text cells may use a decimal comma (``2,5``, ``2,5 x 2,5``) and
the thesis's words (``N/A``, ``Belt In Oil``, ``Autosetting``).

The reader finds the field rows by their key in column B (so rows may be
moved or sections re-ordered), reads the value cell of each field (column D
for fields with choices, column E otherwise; column D's standard/custom
selector set to ``standard`` reads as empty, the thesis Table 2 value), and
returns the same mapping that a YAML ``inputs:`` block gives. It validates the
mapping with :func:`synth.schema.validate` and reports every problem with its
cell, e.g. ``differential_angle_deg (sheet Input, cell E14)``.

>>> _parse_list("2.3 x 2.3"), _parse_list("3"), _parse_list(2.5), _parse_list("2,5 x 2,5")
([2.3, 2.3], [3.0], [2.5], [2.5, 2.5])
"""

from __future__ import annotations

from pathlib import Path

from synth import schema
from synth.errors import InputError, Problem
from synth.excel.template import COL, LIST_SHEET, SHEET, selector_kind
from synth.io.limits import short
from synth.io.numbers import is_not_given
from synth.io.workbook import Sheet, read_sheet

__all__ = ["locate", "read_cells", "read_workbook", "cell_label"]

_ALIASES = {a: f.name for f in schema.FIELDS for a in f.aliases}
_NAMES = {f.name for f in schema.FIELDS}


_parse_list = schema.parse_number_list


def _clean(value):
    """Empty strings and whitespace to None; strings stripped (``N/A`` stays: the validator reads it as not given)."""
    if isinstance(value, str):
        value = value.strip()
        return value or None
    return value


def cell_label(sheet: str, cell: str | None) -> str:
    """``(sheet Input, cell E14)``, or ``(sheet Input: no row)`` when the field has no row."""
    return f"(sheet {sheet}, cell {cell})" if cell else f"(sheet {sheet}: no row for this field)"


def locate(ws: Sheet) -> dict[str, int]:
    """Row of every field key found in column B (aliases resolved); unknown keys as ``?key``."""
    rows: dict[str, int] = {}
    started = False
    for r in range(1, ws.n_rows + 1):
        key = _clean(ws.value(f"{COL['field']}{r}"))
        if key is None:
            continue
        if not started:
            started = str(key).strip().lower() == "field"
            continue
        key = str(key)
        name = _ALIASES.get(key, key)
        name = name if name in _NAMES else f"?{key}"
        if name in rows:  # the same field twice (or a field and its alias): reported by read_cells
            rows[f"!{key}!{rows[name]}!{r}"] = r
            continue
        rows[name] = r
    return rows


def _formula_problem(name: str, ws: Sheet, cell: str) -> Problem:
    return Problem(f"{name} {cell_label(ws.title, cell)}", short(ws.cell(cell).formula),
                   f"a value: cell {cell} holds a formula without a cached value (the workbook was saved by a "
                   "program that does not compute formulas); type the value, or open and save the workbook in "
                   "Excel or LibreOffice")


def read_cells(path: str | Path) -> tuple[dict, dict[str, str], str, list[Problem]]:
    """Read a workbook without validating.

    Returns ``(data, cells, sheet_name, problems)``: ``data`` maps field names
    to raw cell values (None when empty or standard), ``cells`` maps field names
    to the cell read (``"E14"``), ``problems`` are the layout problems found
    (unknown keys, a custom selector without a value).
    """
    p = Path(path)
    ws = read_sheet(p, "input file", SHEET, skip=(LIST_SHEET,))
    rows = locate(ws)
    if not rows:
        raise InputError(Problem("input file", str(p), f"a sheet '{ws.title}' with a 'Field' header in column "
                                                       f"{COL['field']} and field keys below it (synth template)"))
    data: dict = {}
    cells: dict[str, str] = {}
    problems: list[Problem] = []
    for name, r in rows.items():
        if name.startswith("!"):
            key, first, again = name[1:].split("!")
            problems.append(Problem(f"{short(key)} {cell_label(ws.title, COL['field'] + again)}", "a second row",
                                    f"each field in one row (row {first} already gives "
                                    f"{_ALIASES.get(key, key)}; remove one)"))
            continue
        if name.startswith("?"):
            cell = f"{COL['field']}{r}"
            problems.append(Problem(f"{short(name[1:])} {cell_label(ws.title, cell)}", short(name[1:]),
                                    "a known design-input field key (see synth template)"))
            continue
        f = schema.field_by_name(name)
        kind = selector_kind(f)
        sel_cell, val_cell = f"{COL['selector']}{r}", f"{COL['value']}{r}"
        sel, val = _clean(ws.value(sel_cell)), _clean(ws.value(val_cell))
        pending = [c for c, v in ((sel_cell, sel), (val_cell, val)) if v is None and ws.cell(c).formula]
        if pending:
            problems.append(_formula_problem(name, ws, pending[0]))
            cells[name] = pending[0]
            continue
        if kind == "choice":
            cells[name] = sel_cell if sel is not None or val is None else val_cell
            value = sel if sel is not None else val
        elif kind == "standard/custom":
            cells[name] = val_cell
            choice = str(sel).strip().lower() if sel is not None else (
                "custom" if val is not None and not is_not_given(val) else "standard")
            if choice not in ("standard", "custom"):
                problems.append(Problem(f"{name} selector {cell_label(ws.title, sel_cell)}", short(sel), "standard or custom"))
                value = None
            elif choice == "standard":
                value = None
            else:
                value = val
                if val is None or is_not_given(val):
                    problems.append(Problem(f"{name} {cell_label(ws.title, val_cell)}", None,
                                            f"a value (the selector in {sel_cell} is 'custom'; "
                                            "set it to 'standard' for the Table 2 value)"))
        else:
            cells[name] = val_cell
            value = val
        if value is not None and f.kind == "list":
            value = _parse_list(value)
        data[name] = value
    return data, cells, ws.title, problems


def read_workbook(path: str | Path, *, validate: bool = True) -> dict:
    """The design-input mapping of a filled workbook (what :func:`synth.schema.validate` takes).

    With ``validate`` (default) the mapping is validated and every problem is
    raised at once in an :class:`~synth.errors.InputError` whose fields name
    the cell, e.g. ``working_arm_mm (sheet Input, cell E12)``.
    """
    data, cells, sheet, problems = read_cells(path)
    if validate:
        try:
            schema.validate(data)
        except InputError as exc:
            for prob in exc.problems:
                name = _ALIASES.get(prob.field, prob.field)
                if any(q.field.split(" ")[0] in (prob.field, name) for q in problems):
                    continue  # already reported with its cell
                problems.append(Problem(f"{prob.field} {cell_label(sheet, cells.get(name))}", prob.value,
                                        prob.accepted))
    if problems:
        raise InputError(problems)
    return data
