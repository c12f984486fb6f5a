"""One sheet of a workbook as cells: an .xlsx (Excel or LibreOffice) or a LibreOffice .ods.

:func:`read_sheet` returns a :class:`Sheet` whose cells carry the value a
reader should use (a formula's cached result) and the formula itself, so a
formula without a cached value (a workbook written by a program that does
not compute formulas) can be *explained* ("cell E12 holds a formula without
a cached value: type the value") instead of read as an empty cell.

Reading .xlsx uses openpyxl (read-only, streaming, one pass; the cached
results of formula cells, when there are any, from calamine); .ods uses odfpy,
the library pandas reads .ods with (pure Python, installed from PyPI). Both are
bounded: the file size, its unpacked size and the unpacked size of each of its
parts (:attr:`~synth.io.limits.Limits.workbook_part_bytes`) are checked first,
so no XML the readers would take more than about a second over is parsed; at most
:attr:`~synth.io.limits.Limits.sheet_rows` rows and
:attr:`~synth.io.limits.Limits.sheet_columns` columns are read (LibreOffice
writes a run of a million empty rows as one repeated row: it is not expanded).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

from synth.errors import InputError, Problem
from synth.io.files import check_size, check_zip, existing_file, suffix_of
from synth.io.limits import LIMITS

__all__ = ["Cell", "Sheet", "read_sheet", "column_letter", "column_index", "percent_text"]


@dataclass(frozen=True)
class Cell:
    """A cell's value (cached result for a formula; None when empty) and its formula (or None)."""

    value: object = None
    formula: str | None = None


@dataclass
class Sheet:
    """The cells of one sheet by address (``"E12"``), its title and the workbook's sheet names."""

    title: str
    cells: dict[str, Cell] = field(default_factory=dict)
    n_rows: int = 0
    sheetnames: tuple[str, ...] = ()
    path: str = ""

    def cell(self, address: str) -> Cell:
        return self.cells.get(address, _EMPTY)

    def value(self, address: str):
        return self.cell(address).value


_EMPTY = Cell()


def column_letter(index: int) -> str:
    """``1 -> 'A'``, ``27 -> 'AA'``."""
    out = ""
    while index > 0:
        index, rem = divmod(index - 1, 26)
        out = chr(65 + rem) + out
    return out


def column_index(letter: str) -> int:
    """``'A' -> 1``, ``'AA' -> 27``."""
    n = 0
    for ch in letter.upper():
        n = n * 26 + ord(ch) - 64
    return n


def read_sheet(path, what: str, prefer: str, skip: tuple[str, ...] = ()) -> Sheet:
    """Sheet ``prefer`` of the workbook at ``path`` (or its first sheet not in ``skip``).

    ``.xlsx``/``.xlsm`` and ``.ods``; anything else, a damaged file or one
    beyond the limits is an :class:`~synth.errors.InputError` naming the file.
    """
    suffix = suffix_of(path)
    kind = ".ods workbook (LibreOffice)" if suffix == ".ods" else ".xlsx workbook"
    p = existing_file(path, what, f"an existing {kind}")
    check_size(p, what, LIMITS.workbook_bytes, "workbook")
    check_zip(p, what, LIMITS.workbook_unpacked_bytes, kind, LIMITS.workbook_part_bytes)
    try:
        sheet = _read_ods(p, prefer, skip) if suffix == ".ods" else _read_xlsx(p, prefer, skip)
    except InputError:
        raise
    except ImportError:  # pragma: no cover - odfpy is a dependency
        raise InputError(Problem(what, str(p), "an .xlsx workbook (reading .ods needs odfpy: pip install odfpy)")) from None
    except Exception as exc:  # zip/XML errors of a damaged workbook
        raise InputError(Problem(what, str(p), f"a readable {kind} ({type(exc).__name__}: "
                                               f"{' '.join(str(exc).split())[:200]})")) from None
    if sheet is None:
        raise InputError(Problem(what, str(p), f"a workbook with a sheet '{prefer}'"))
    sheet.path = str(p)
    return sheet


def _pick(names: list[str], prefer: str, skip: tuple[str, ...]) -> str | None:
    if prefer in names:
        return prefer
    rest = [n for n in names if n not in skip]
    return rest[0] if rest else None


def _read_xlsx(p: Path, prefer: str, skip: tuple[str, ...]) -> Sheet | None:
    """One openpyxl pass (read-only, formulas as written); the cached values of formula cells, when there are
    any, from calamine (which reads values only, in milliseconds): the styles and shared strings are parsed once."""
    from openpyxl import load_workbook

    wb = load_workbook(p, data_only=False, read_only=True)
    try:
        name = _pick(wb.sheetnames, prefer, skip)
        if name is None:
            return None
        sheet = Sheet(title=name, sheetnames=tuple(wb.sheetnames))
        percent: dict[str, bool] = {}
        rows = wb[name].iter_rows(max_row=LIMITS.sheet_rows, max_col=LIMITS.sheet_columns)
        for r, row in enumerate(rows, start=1):
            for c, cell in enumerate(row, start=1):
                v = getattr(cell, "value", None)
                address = f"{column_letter(c)}{r}"
                pct = "%" in str(getattr(cell, "number_format", ""))
                if isinstance(v, str) and v.startswith("=") and getattr(cell, "data_type", "") == "f":
                    sheet.cells[address] = Cell(None, v)
                    percent[address] = pct
                    continue
                if isinstance(v, (int, float)) and not isinstance(v, bool) and pct:
                    v = percent_text(v)  # a cell typed "4%" holds 0.04: read as typed, "4 %"
                if v is not None:
                    sheet.cells[address] = Cell(v)
            sheet.n_rows = r
    finally:
        wb.close()
    if percent:
        _cached_values(p, sheet, percent)
    return sheet


def _cached_values(p: Path, sheet: Sheet, percent: dict[str, bool]) -> None:
    """The cached results of the formula cells ``percent`` (address -> percent format) of ``sheet``, read with
    calamine (values only); a formula without a cached result keeps the value None."""
    from python_calamine import CalamineWorkbook

    wb = CalamineWorkbook.from_path(str(p))
    try:
        data = wb.get_sheet_by_name(sheet.title)
        r0, c0 = data.start or (0, 0)
        rows = data.to_python(skip_empty_area=False)
    finally:
        wb.close()
    for address, pct in percent.items():
        col = "".join(ch for ch in address if ch.isalpha())
        r, c = int(address[len(col):]) - 1 - r0, column_index(col) - 1 - c0
        v = rows[r][c] if 0 <= r < len(rows) and 0 <= c < len(rows[r]) else None
        if v == "" or v is None:
            continue
        if isinstance(v, float) and v.is_integer() and not pct:
            v = int(v)
        if isinstance(v, (int, float)) and not isinstance(v, bool) and pct:
            v = percent_text(v)
        sheet.cells[address] = Cell(v, sheet.cells[address].formula)


def percent_text(fraction: float) -> str:
    """A cell formatted as a percentage as the user typed it: it holds 0.04 for ``4%``, read as ``"4 %"``, so that
    the one percentage parser (:func:`synth.io.numbers.percentage`) reads it for a field that takes a percentage
    and every other number field refuses it (4 % of a length means nothing).

    >>> percent_text(0.04), percent_text(0.07), percent_text(0.005)
    ('4 %', '7 %', '0.5 %')
    """
    return f"{fraction * 100:.12g} %"


def _read_ods(p: Path, prefer: str, skip: tuple[str, ...]) -> Sheet | None:
    from odf import teletype
    from odf.namespaces import OFFICENS, TABLENS
    from odf.opendocument import load
    from odf.table import Table, TableRow

    doc = load(str(p))
    tables = doc.spreadsheet.getElementsByType(Table)
    names = [t.getAttrNS(TABLENS, "name") for t in tables]
    name = _pick(names, prefer, skip)
    if name is None:
        return None
    table = tables[names.index(name)]
    sheet = Sheet(title=name, sheetnames=tuple(names))
    r = 0
    for row in table.getElementsByType(TableRow):
        if r >= LIMITS.sheet_rows:
            break
        repeat = min(int(row.getAttrNS(TABLENS, "number-rows-repeated") or 1), LIMITS.sheet_rows - r)
        cells = []
        c = 0
        for cell in row.childNodes:
            if c >= LIMITS.sheet_columns:
                break
            if cell.qname[1] not in ("table-cell", "covered-table-cell"):
                continue
            n = min(int(cell.getAttrNS(TABLENS, "number-columns-repeated") or 1), LIMITS.sheet_columns - c)
            content = _ods_value(cell, teletype, OFFICENS, TABLENS) if cell.qname[1] == "table-cell" else Cell()
            for _ in range(n):
                c += 1
                if content.value is not None or content.formula is not None:
                    cells.append((c, content))
        for _ in range(repeat):
            r += 1
            for c, content in cells:
                sheet.cells[f"{column_letter(c)}{r}"] = content
    sheet.n_rows = r
    return sheet


def _ods_value(cell, teletype, OFFICENS, TABLENS) -> Cell:
    """An ODF table cell's value by its value type (float, percentage, currency, string, boolean, date)."""
    formula = cell.getAttrNS(TABLENS, "formula") or None
    vtype = cell.getAttrNS(OFFICENS, "value-type")
    value = None
    if vtype in ("float", "percentage", "currency"):
        raw = cell.getAttrNS(OFFICENS, "value")
        try:
            value = float(raw)
            if vtype == "percentage":
                value = percent_text(value)  # 4 % is stored as 0.04: read as typed, "4 %"
            elif value.is_integer() and "." not in str(raw) and "e" not in str(raw).lower():
                value = int(value)
        except (TypeError, ValueError):
            value = raw
    elif vtype == "boolean":
        value = str(cell.getAttrNS(OFFICENS, "boolean-value")).lower() == "true"
    elif vtype == "date":
        value = cell.getAttrNS(OFFICENS, "date-value")
    elif vtype == "time":
        value = cell.getAttrNS(OFFICENS, "time-value")
    elif vtype == "string" or vtype is None:
        text = "\n".join(teletype.extractText(par) for par in cell.childNodes if par.qname[1] == "p")
        value = text if text != "" else (cell.getAttrNS(OFFICENS, "string-value") or None)
    if formula and vtype is None and value is None:
        return Cell(None, formula)  # a formula without a cached result
    return Cell(value, formula)
