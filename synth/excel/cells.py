"""Cells of every workbook synth writes: text stays text, numbers show significant figures, pages print.

One helper for every ``.xlsx`` synth writes (the results workbook, the input
template, portfolio and bulk result tables):

* :func:`put` writes one cell. A string is always a text cell, never a live
  formula: openpyxl would store ``"=HYPERLINK(...)"`` from a portfolio or an
  optimum file as a formula, so the cell is typed as text, and a string that a
  spreadsheet would read as a formula when the user re-edits it (leading
  ``= + - @``, tab or carriage return, :data:`FORMULA_LEADS`) also gets Excel's
  ``quotePrefix`` flag (the apostrophe prefix). Numbers keep their full value
  and get a display format of :data:`SIGNIFICANT_FIGURES` significant figures
  (:func:`sig_format`), not General's ``1.71334077115234``.
* :func:`page_setup` prints a sheet landscape on A4, fitted to the page width,
  the header rows repeated on every page, with a header (title) and footer
  (date, page ``n of N``).
* :func:`write_frame` writes a table (a :class:`pandas.DataFrame`) through
  :func:`put`: the ``.xlsx`` of ``synth bulk --out`` and ``synth portfolio-sample``.

>>> sig_format(1.71334077115234), sig_format(1234.5), sig_format(0.012345), sig_format(123456789.0)
('0.000', '0', '0.00000', '0.000E+00')
>>> from openpyxl import Workbook
>>> ws = Workbook().active
>>> c = put(ws, 1, 1, "=1+1")
>>> c.data_type, c.value, c.quotePrefix
('s', '=1+1', True)
>>> put(ws, 2, 1, 1.71334077115234).number_format
'0.000'
"""

from __future__ import annotations

import datetime as _dt
import math
from pathlib import Path

from synth.io.outputs import FORMULA_LEADS, output_file
from synth.version import __version__

__all__ = ["SIGNIFICANT_FIGURES", "FORMULA_LEADS", "sig_format", "put", "wrap", "page_setup", "write_frame"]

#: Significant figures displayed for numbers (the value stored keeps full precision). A display choice
#: (issue 15: "not General 1.71334077115234"), four figures as the thesis's output tables print them.
SIGNIFICANT_FIGURES = 4

# Fixed-point formats span these powers of ten; outside, scientific notation.
_FIXED_DECADES = (-4, 7)


def sig_format(value, sig: int = SIGNIFICANT_FIGURES) -> str:
    """Excel/LibreOffice number format showing ``value`` with ``sig`` significant figures.

    Whole numbers (``int``) get ``0``; floats between ``1e-4`` and ``1e7`` a fixed
    number of decimals, ``sig - 1 - floor(log10(|value|))`` (at least 0); others
    ``0.000E+00``. A format per magnitude: an edited value keeps the decimals of the
    value written.
    """
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        return "General"
    if isinstance(value, int):
        return "0"
    if not math.isfinite(value) or value == 0.0:
        return "0" if value == 0.0 else "General"
    decade = math.floor(math.log10(abs(value)))
    if not _FIXED_DECADES[0] <= decade < _FIXED_DECADES[1]:
        return "0." + "0" * (sig - 1) + "E+00"
    decimals = max(sig - 1 - decade, 0)
    return "0." + "0" * decimals if decimals else "0"


def _plain(value):
    """numpy scalars to Python; NaN and None to an empty cell."""
    if hasattr(value, "item") and not isinstance(value, (str, bytes)):
        value = value.item()
    if value is None or (isinstance(value, float) and math.isnan(value)):
        return None
    return value


def put(ws, row: int, column: int, value, *, sig: int = SIGNIFICANT_FIGURES, number_format: str | None = None):
    """Write ``value`` into ``ws`` at (``row``, ``column``) safely and formatted; returns the cell.

    Strings become text cells (never formulas), numbers get :func:`sig_format`
    (or ``number_format``: ``"General"`` for a value the user typed, shown as typed),
    ``None``/NaN an empty cell; anything else is written as its ``str``.
    """
    value = _plain(value)
    cell = ws.cell(row=row, column=column)
    if value is None:
        cell.value = None
    elif isinstance(value, str):
        cell.value = value
        cell.data_type = "s"  # openpyxl types a leading "=" as a formula; a text cell it stays
        if value.startswith(FORMULA_LEADS):
            cell.quotePrefix = True
    elif isinstance(value, (bool, int, float)):
        cell.value = value
        if math.isfinite(value):
            cell.number_format = number_format or sig_format(value, sig)
        else:  # inf cannot be stored as a number in .xlsx
            cell.value = str(value)
            cell.data_type = "s"
    else:
        cell.value = str(value)
        cell.data_type = "s"
        if cell.value.startswith(FORMULA_LEADS):
            cell.quotePrefix = True
    return cell


def wrap(ws, column: str, first: int, last: int, *, line_height_pt: float = 15.0) -> None:
    """Wrap the text of ``column`` in rows ``first..last`` and give each row the height of its lines.

    openpyxl stores no automatic heights and spreadsheet programs do not recompute them on
    opening, so a wrapped cell would overlap the next row: the lines are estimated from the
    text length over the column width (characters).
    """
    from openpyxl.styles import Alignment
    width = ws.column_dimensions[column].width or 10
    for r in range(first, last + 1):
        cell = ws[f"{column}{r}"]
        cell.alignment = Alignment(wrap_text=True, vertical="top")
        lines = math.ceil(1.1 * len(str(cell.value or "")) / max(width - 1, 1)) or 1
        current = ws.row_dimensions[r].height or line_height_pt
        if lines > 1:
            ws.row_dimensions[r].height = max(current, lines * line_height_pt)


def page_setup(ws, title: str, *, header_rows: str | None = None, subtitle: str = "") -> None:
    """Landscape A4, fit to the page width (any number of pages down), print titles, header and footer.

    ``header_rows`` (``"4:4"``) repeat on every printed page; the header shows
    ``title`` (left) and ``subtitle`` (right), the footer the date the workbook was
    written and ``page n of N``.
    """
    ws.page_setup.orientation = "landscape"
    ws.page_setup.paperSize = ws.PAPERSIZE_A4
    ws.page_setup.fitToWidth = 1
    ws.page_setup.fitToHeight = 0
    ws.sheet_properties.pageSetUpPr.fitToPage = True
    ws.print_options.gridLines = True
    ws.page_margins.left = ws.page_margins.right = 0.4
    # the header and footer (0.3 in from the paper's edge, one 8-9 pt line: about 0.45 in) clear of the table
    ws.page_margins.top = ws.page_margins.bottom = 0.75
    ws.page_margins.header = ws.page_margins.footer = 0.3
    if header_rows:
        ws.print_title_rows = header_rows
    for hf in (ws.oddHeader, ws.evenHeader, ws.firstHeader):
        hf.left.text = _hf_text(title)
        hf.right.text = _hf_text(subtitle)
    for hf in (ws.oddFooter, ws.evenFooter, ws.firstFooter):
        hf.left.text = f"synth {__version__}, written {_dt.date.today().isoformat()}"
        hf.right.text = "page &P of &N"


def _hf_text(text: str) -> str:
    """Header/footer text: ``&`` is a field code there, so doubled; at most 120 characters."""
    return text.replace("&", "&&")[:120]


def write_frame(df, path, *, sheet: str = "Sheet1", title: str | None = None) -> Path:
    """Write the table ``df`` to ``path`` (.xlsx) through :func:`put`: bold frozen header, print setup."""
    from openpyxl import Workbook
    from openpyxl.styles import Font
    from openpyxl.utils import get_column_letter
    p = Path(path)
    wb = Workbook()
    ws = wb.active
    ws.title = sheet[:31]
    columns = [str(c) for c in df.columns]
    for j, name in enumerate(columns, start=1):
        put(ws, 1, j, name).font = Font(bold=True)
        ws.column_dimensions[get_column_letter(j)].width = max(10, min(40, len(name) + 2))
    for i, row in enumerate(df.itertuples(index=False, name=None), start=2):
        for j, value in enumerate(row, start=1):
            put(ws, i, j, value)
    ws.freeze_panes = "A2"
    page_setup(ws, title or p.name, header_rows="1:1")
    with output_file(p) as tmp:
        wb.save(tmp)
    return p
