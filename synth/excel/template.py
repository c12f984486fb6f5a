"""The design-input Excel template, in the shape of the thesis's input table (Fig. 22-26).

The workbook is built from :data:`synth.schema.FIELDS` (one row per field, in
the schema's sections, which are the thesis's themes by rows), so a new field
in the schema appears in the template without touching this module.

Sheet ``Input``, columns (the thesis: selector C, values D/E, data read F):

====  =====================  ==================================================
col   header                 content
====  =====================  ==================================================
A     Parameter              the field's label; section titles on their own rows
B     Field                  the machine key (as in the YAML ``inputs:`` block)
C     Unit                   unit of the value
D     Selector               drop-down: standard/custom (``pivot_class_diameter_mm``,
                             ``loading_arm_mm``), defined/assumed, automatic/manual
                             and every other field with choices (its value is the
                             choice); otherwise the information "Custom only" or
                             "Standard only" (a catalog designation)
E     Value                  the value (numbers, catalog drop-downs, wire size
                             ``2.3 x 2.3``); ignored when D says ``standard``
F     Required               ``required`` / ``optional``
G     Data read              echo of the value synth read (results workbook)
H     Suggested correction   filled by synth in the results workbook
====  =====================  ==================================================

A hidden sheet ``Lists`` holds the drop-down lists (catalog designations from
:func:`synth.catalog.keys`, so user catalogs show up). The colour legend
(Fig. 24) sits to the right of the table. Example values are those of thesis
case study 1 (Table 9, ``example_case1.yaml``).

>>> [c.header for c in COLUMNS][:5]
['Parameter', 'Field', 'Unit', 'Selector', 'Value']
"""

from __future__ import annotations

from dataclasses import dataclass
from importlib import resources
from pathlib import Path

import yaml

from synth import catalog, schema
from synth.report.palette import VERDICT_FILLS
from synth.excel.cells import page_setup, put, wrap
from synth.schema import Field
from synth.io.outputs import output_file

__all__ = ["COLUMNS", "COL", "STANDARD_CUSTOM", "FILLS", "LEGEND", "SHEET", "LIST_SHEET", "selector_kind",
           "value_column", "example_values", "format_cell_value", "build_workbook", "write_template"]

SHEET = "Input"
LIST_SHEET = "Lists"


@dataclass(frozen=True)
class Column:
    letter: str
    header: str
    width: float


COLUMNS: tuple[Column, ...] = (
    Column("A", "Parameter", 44), Column("B", "Field", 36), Column("C", "Unit", 7), Column("D", "Selector", 16),
    Column("E", "Value", 14), Column("F", "Required", 10), Column("G", "Data read", 12),
    Column("H", "Suggested correction", 36),
)
#: Column letter by role.
COL = {"label": "A", "field": "B", "unit": "C", "selector": "D", "value": "E", "required": "F", "read": "G",
       "correction": "H"}

#: Fields with a standard/custom selector: empty (``null``) takes the thesis Table 2 standard
#: (see the :mod:`synth.schema` docstring).
STANDARD_CUSTOM = ("pivot_class_diameter_mm", "loading_arm_mm")

#: Cell colours (ARGB hex without alpha), after the thesis's legend (Fig. 24-25).
FILLS = {
    "title": "1F4E78",
    "section": "BDD7EE",
    "header": "D9D9D9",
    "required": "DDEBF7",
    "optional": "F2F2F2",
    "selector": "FFF2CC",
    "info": "E7E6E6",
    **{k: VERDICT_FILLS[k] for k in ("pass", "fail", "not verified", "warning")},  # the one verdict palette
}

#: The colour legend (Fig. 24): (fill key, meaning).
LEGEND = (
    ("required", "mandatory input: give a value"),
    ("optional", "optional input: may be left empty (checks that need it are 'not verified')"),
    ("selector", "selector or catalog choice: pick from the drop-down"),
    ("info", "information only (not read)"),
    ("pass", "data read / verified (green)"),
    ("not verified", "not verified: data missing (orange)"),
    ("warning", "advisory range left (Table 7): a warning, never a failure (yellow)"),
    ("fail", "problem: invalid data or failed check (red)"),
)


def selector_kind(f: Field) -> str:
    """What column D holds for field ``f``: ``standard/custom``, ``choice`` or ``info``.

    >>> selector_kind(schema.field_by_name("pivot_class_diameter_mm")), selector_kind(schema.field_by_name("bolt_mode"))
    ('standard/custom', 'choice')
    """
    if f.name in STANDARD_CUSTOM:
        return "standard/custom"
    if f.choices:
        return "choice"
    return "info"


def value_column(f: Field) -> str:
    """Column letter where the value of field ``f`` is read (D for choices, E otherwise).

    >>> value_column(schema.field_by_name("durability_test")), value_column(schema.field_by_name("working_arm_mm"))
    ('D', 'E')
    """
    return COL["selector"] if selector_kind(f) == "choice" else COL["value"]


def example_values() -> dict:
    """The example inputs written into the template: thesis case study 1 (Table 9)."""
    text = resources.files("synth.excel").joinpath("example_case1.yaml").read_text(encoding="utf-8")
    return dict(yaml.safe_load(text)["inputs"])


def format_cell_value(f: Field, value):
    """A field value as written into a cell (lists as ``2.3 x 2.3``; None as empty).

    >>> format_cell_value(schema.field_by_name("main_spring_wire_size_mm"), [2.3, 2.3])
    '2.3 x 2.3'
    """
    if value is None:
        return None
    if f.kind == "list":
        items = value if isinstance(value, (list, tuple)) else [value]
        return " x ".join(f"{float(v):g}" for v in items)
    if f.choices or f.catalog or f.kind == "str":
        return str(value)
    return value


def _fill(key):
    from openpyxl.styles import PatternFill
    return PatternFill("solid", start_color=FILLS[key], end_color=FILLS[key])


def fixed_sets() -> dict[str, list]:
    """Every field with a fixed set of values, and the values: the choices, the catalog keys, the supplier
    thicknesses of the pivot bushing (``pivot_bushings.csv``) and the wire sizes of ``spring_wires.csv``.

    >>> s = fixed_sets()
    >>> s["pivot_bushing_radial_thickness_mm"], "2.3" in s["main_spring_wire_size_mm"], s["bolt_mode"]
    ([0.5, 1.0], True, ['automatic', 'manual'])
    """
    out: dict[str, list] = {}
    for f in schema.FIELDS:
        if f.choices:
            out[f.name] = list(f.choices)
        elif f.catalog:
            out[f.name] = [str(k) for k in catalog.keys(f.catalog)]
    out["pivot_bushing_radial_thickness_mm"] = sorted({float(t) for t in catalog.load("pivot_bushings")["radial_thickness_mm"]})
    wires = catalog.load("spring_wires")
    size = schema.field_by_name("main_spring_wire_size_mm")
    out["main_spring_wire_size_mm"] = [format_cell_value(size, [b] if sec == "round" else [b, h])
                                       for sec, b, h in zip(wires["section"], wires["b_mm"], wires["h_mm"])]
    return out


def comment_text(f: Field) -> str:
    """The cell comment of a field: what it means, its unit and what is accepted (and why, where the schema
    says)."""
    unit = f" [{f.unit}]" if f.unit not in ("-", "") else ""
    text = f"{f.label or f.name}{unit}. {'Required' if f.required else 'Optional'}; accepted: {f.accepted()}."
    if f.basis:
        text += f" Bounds: {f.basis}."
    return text[:1000]


def _list_ranges(wb) -> dict[str, str]:
    """Write the drop-down lists to the hidden ``Lists`` sheet; return ``{name: range formula}``."""
    from openpyxl.utils import get_column_letter
    ws = wb.create_sheet(LIST_SHEET)
    lists: dict[str, list] = {"standard/custom": ["standard", "custom"], **fixed_sets()}
    out = {}
    for j, (name, items) in enumerate(lists.items(), start=1):
        letter = get_column_letter(j)
        put(ws, 1, j, name)
        for i, item in enumerate(items, start=2):
            put(ws, i, j, item)
        # stored as Excel stores it in <formula1>: no leading "="
        out[name] = f"{LIST_SHEET}!${letter}$2:${letter}${len(items) + 1}"
    ws.sheet_state = "hidden"
    return out


def _number_validation(f: Field):
    """A decimal/whole-number validation with the field's finite bounds (None if unbounded)."""
    from openpyxl.worksheet.datavalidation import DataValidation
    import math
    lo, hi = (f.lo if math.isfinite(f.lo) else None), (f.hi if math.isfinite(f.hi) else None)
    kind = "whole" if f.kind == "int" else "decimal"
    if lo is not None and hi is not None:
        dv = DataValidation(type=kind, operator="between", formula1=f"{lo:g}", formula2=f"{hi:g}")
    elif lo is not None:
        dv = DataValidation(type=kind, operator="greaterThanOrEqual", formula1=f"{lo:g}")
    elif hi is not None:
        dv = DataValidation(type=kind, operator="lessThanOrEqual", formula1=f"{hi:g}")
    else:
        return None
    dv.allow_blank, dv.showErrorMessage = True, True
    dv.errorStyle = "warning"
    dv.error, dv.errorTitle = f"{f.name}: accepted {f.accepted()}"[:255], "synth: value out of range"
    return dv


def build_workbook(values: dict | None = None, *, title: str = "synth design input"):
    """The template as an :class:`openpyxl.Workbook`, filled with ``values`` (default: case 1).

    Returns ``(workbook, cells)`` with ``cells[field] = "E14"`` (the cell read
    for each field).
    """
    from openpyxl import Workbook
    from openpyxl.comments import Comment
    from openpyxl.styles import Alignment, Font
    from openpyxl.worksheet.datavalidation import DataValidation

    values = example_values() if values is None else dict(values)
    wb = Workbook()
    ws = wb.active
    ws.title = SHEET
    lists = _list_ranges(wb)
    for c in COLUMNS:
        ws.column_dimensions[c.letter].width = c.width
    put(ws, 1, 1, title + " (thesis Fig. 22-23)").font = Font(bold=True, size=14, color="FFFFFF")
    for c in COLUMNS:
        ws[f"{c.letter}1"].fill = _fill("title")
    put(ws, 2, 1, "Fill column E (values) and the drop-downs of column D; leave optional cells empty when unknown "
        "(each value cell's comment says what it means, its unit and range). Run: synth design THIS.xlsx (the best "
        "catalog design)   or   synth report THIS.xlsx --out DIR   or   synth flowchart THIS.xlsx (the thesis "
        "procedure)").alignment = Alignment(wrap_text=False)
    header_row = 4
    for c in COLUMNS:
        cell = put(ws, header_row, ord(c.letter) - 64, c.header)
        cell.font = Font(bold=True)
        cell.fill = _fill("header")
    ws.freeze_panes = f"A{header_row + 1}"
    row = header_row + 1
    cells: dict[str, str] = {}
    validations: dict[str, DataValidation] = {}

    def list_dv(key: str) -> DataValidation:
        if key not in validations:
            dv = DataValidation(type="list", formula1=lists[key], allow_blank=True, showErrorMessage=True)
            dv.errorStyle = "stop"
            dv.errorTitle, dv.error = "synth: not in the list", f"pick one of the drop-down entries ({key})"
            validations[key] = dv
            ws.add_data_validation(dv)
        return validations[key]

    for section in schema.SECTIONS:
        put(ws, row, 1, section).font = Font(bold=True)
        for c in COLUMNS:
            ws[f"{c.letter}{row}"].fill = _fill("section")
        row += 1
        for f in (f for f in schema.FIELDS if f.section == section):
            need = "required" if f.required else "optional"
            put(ws, row, 1, f.label or f.name)
            put(ws, row, 2, f.name).font = Font(color="595959")
            put(ws, row, 3, f.unit)
            put(ws, row, 6, need)
            kind = selector_kind(f)
            sel, val = ws[f"D{row}"], ws[f"E{row}"]
            value = values.get(f.name, f.default)
            if kind == "choice":
                put(ws, sel.row, sel.column, format_cell_value(f, value))
                sel.fill = _fill("selector")
                list_dv(f.name).add(sel.coordinate)
                val.fill = _fill("info")
            else:
                if kind == "standard/custom":
                    put(ws, sel.row, sel.column, "standard" if value is None else "custom")
                    sel.fill = _fill("selector")
                    list_dv("standard/custom").add(sel.coordinate)
                else:
                    put(ws, sel.row, sel.column, "Standard only" if f.catalog else "Custom only")
                    sel.fill = _fill("info")
                    sel.font = Font(italic=True, color="595959")
                put(ws, val.row, val.column, format_cell_value(f, value), number_format="General")  # as typed
                if f.catalog or f.name in lists:
                    val.fill = _fill("selector")
                    list_dv(f.name).add(val.coordinate)
                else:
                    val.fill = _fill(need)
                    dv = _number_validation(f) if f.kind in ("float", "int") else None
                    if dv is not None:
                        dv.add(val.coordinate)
                        ws.add_data_validation(dv)
            cells[f.name] = f"{value_column(f)}{row}"
            note = Comment(comment_text(f), "synth")
            note.width, note.height = 320, 140
            ws[cells[f.name]].comment = note
            row += 1
    # colour legend (Fig. 24), right of the table
    ws.column_dimensions["J"].width = 4
    ws.column_dimensions["K"].width = 70
    put(ws, header_row, 10, "Legend").font = Font(bold=True)
    for i, (key, meaning) in enumerate(LEGEND, start=header_row + 1):
        ws[f"J{i}"].fill = _fill(key)
        put(ws, i, 11, meaning)
    wrap(ws, "A", header_row + 1, row - 1)
    page_setup(ws, title, header_rows=f"{header_row}:{header_row}", subtitle="fill columns D and E")
    ws.print_area = [f"A1:H{row - 1}", f"J{header_row}:K{header_row + len(LEGEND)}"]  # the table, then the legend
    return wb, cells


def write_template(path: str | Path, values: dict | None = None) -> Path:
    """Write the input template to ``path`` (.xlsx); example values of case 1 unless ``values``."""
    p = Path(path)
    wb, _ = build_workbook(values)
    with output_file(p) as tmp:
        wb.save(tmp)
    return p
