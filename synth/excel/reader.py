"""Read a filled design-input workbook (the template of :mod:`synth.excel.template`).

The reader finds the field rows by their key in column B (so rows may be
moved or sections re-ordered), reads the value cell of each field (column D
for fields with choices, column E otherwise; column D's standard/custom
selector set to ``standard`` reads as empty, the thesis Table 2 value), and
returns the same mapping that a YAML ``inputs:`` block gives. It validates the
mapping with :func:`synth.schema.validate` and reports every problem with its
cell, e.g. ``differential_angle_deg (sheet Input, cell E14)``.

>>> _parse_list("2.3 x 2.3"), _parse_list("3"), _parse_list(2.5)
([2.3, 2.3], [3.0], [2.5])
"""

from __future__ import annotations

from pathlib import Path

from synth import schema
from synth.errors import InputError, Problem
from synth.excel.template import COL, LIST_SHEET, SHEET, selector_kind

__all__ = ["locate", "read_cells", "read_workbook", "cell_label"]

_ALIASES = {a: f.name for f in schema.FIELDS for a in f.aliases}
_NAMES = {f.name for f in schema.FIELDS}


_parse_list = schema.parse_number_list


def _clean(value):
    """Empty strings and whitespace to None; strings stripped."""
    if isinstance(value, str):
        value = value.strip()
        return value or None
    return value


def cell_label(sheet: str, cell: str | None) -> str:
    """``(sheet Input, cell E14)``, or ``(sheet Input: no row)`` when the field has no row."""
    return f"(sheet {sheet}, cell {cell})" if cell else f"(sheet {sheet}: no row for this field)"


def _sheet(wb, path):
    if SHEET in wb.sheetnames:
        return wb[SHEET]
    candidates = [n for n in wb.sheetnames if n != LIST_SHEET]
    if not candidates:
        raise InputError(Problem("input file", str(path), f"a workbook with a sheet '{SHEET}' (synth template)"))
    return wb[candidates[0]]


def locate(ws) -> dict[str, int]:
    """Row of every field key found in column B (aliases resolved); unknown keys as ``?key``."""
    rows: dict[str, int] = {}
    started = False
    for r in range(1, ws.max_row + 1):
        key = _clean(ws[f"{COL['field']}{r}"].value)
        if key is None:
            continue
        if not started:
            started = str(key).strip().lower() == "field"
            continue
        key = str(key)
        name = _ALIASES.get(key, key)
        rows[name if name in _NAMES else f"?{key}"] = r
    return rows


def read_cells(path: str | Path) -> tuple[dict, dict[str, str], str, list[Problem]]:
    """Read a workbook without validating.

    Returns ``(data, cells, sheet_name, problems)``: ``data`` maps field names
    to raw cell values (None when empty or standard), ``cells`` maps field names
    to the cell read (``"E14"``), ``problems`` are the layout problems found
    (unknown keys, a custom selector without a value).
    """
    from openpyxl import load_workbook

    p = Path(path)
    if not p.is_file():
        raise InputError(Problem("input file", str(p), "an existing .xlsx workbook"))
    try:
        wb = load_workbook(p, data_only=True, read_only=False)
    except Exception as exc:  # zip/XML errors: keep the reason
        raise InputError(Problem("input file", str(p), f"a valid .xlsx workbook ({exc})")) from None
    ws = _sheet(wb, p)
    rows = locate(ws)
    if not rows:
        raise InputError(Problem("input file", str(p), f"a sheet '{ws.title}' with a 'Field' header in column "
                                                       f"{COL['field']} and field keys below it (synth template)"))
    data: dict = {}
    cells: dict[str, str] = {}
    problems: list[Problem] = []
    for name, r in rows.items():
        if name.startswith("?"):
            cell = f"{COL['field']}{r}"
            problems.append(Problem(f"{name[1:]} {cell_label(ws.title, cell)}", name[1:],
                                    "a known design-input field key (see synth template)"))
            continue
        f = schema.field_by_name(name)
        kind = selector_kind(f)
        sel_cell, val_cell = f"{COL['selector']}{r}", f"{COL['value']}{r}"
        sel, val = _clean(ws[sel_cell].value), _clean(ws[val_cell].value)
        if kind == "choice":
            cells[name] = sel_cell if sel is not None or val is None else val_cell
            value = sel if sel is not None else val
        elif kind == "standard/custom":
            cells[name] = val_cell
            choice = str(sel).strip().lower() if sel is not None else ("custom" if val is not None else "standard")
            if choice not in ("standard", "custom"):
                problems.append(Problem(f"{name} selector {cell_label(ws.title, sel_cell)}", sel, "standard or custom"))
                value = None
            elif choice == "standard":
                value = None
            else:
                value = val
                if val is None:
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
                if any(prob.field.startswith(q.field.split(" ")[0] + " ") for q in problems):
                    continue  # already reported with its cell
                problems.append(Problem(f"{prob.field} {cell_label(sheet, cells.get(name))}", prob.value,
                                        prob.accepted))
    if problems:
        raise InputError(problems)
    return data
