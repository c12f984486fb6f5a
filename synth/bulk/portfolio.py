"""Portfolio tables: one application per row, design-input fields as columns.

A portfolio is a CSV, Excel (``.xlsx``), OpenDocument (``.ods``) or Parquet file whose column names
are the field names (or aliases) of :data:`synth.schema.FIELDS`; other
columns (an application id, a customer...) are carried through untouched.
Cells are cleaned before validation: empty cells and NaN are ``None`` (the
field is not given), text is stripped, and the list-valued field
``main_spring_wire_size_mm`` is parsed from ``"2.3"``, ``"2.3x4.0"``,
``"2.3; 4.0"`` or ``"[2.3, 4.0]"`` as the Excel template reader does.

Every row is validated on its own with :func:`synth.schema.validate`; an
:class:`~synth.errors.InputError` becomes the row's ``error`` text (one
``field: got value; accepted: ...`` per problem, ``' | '``-joined) and never
stops the other rows.

>>> import pandas as pd
>>> from synth.data.generated_applications import generate
>>> table = to_table(generate(2, seed=0)).astype(object)
>>> table.loc[1, "working_arm_mm"] = "abc"
>>> apps, errors = validate_rows(table)
>>> apps[0] is not None, apps[1] is None, errors[1].startswith("working_arm_mm: got 'abc'")
(True, True, True)
"""

from __future__ import annotations

import difflib
import math
from pathlib import Path

import numpy as np
import pandas as pd

from synth import schema
from synth.errors import InputError, Problem
from synth.io.numbers import is_not_given, NUMBER_RE, NOT_GIVEN
from synth.io.tables import read_table, duplicate_columns
from synth.io.outputs import output_file, write_csv
from synth.excel.cells import write_frame

__all__ = ["FORMATS", "read_portfolio", "check_columns", "write_table", "to_table", "plain_cell", "clean_cell", "row_record", "records",
           "validate_record", "validate_rows", "validate_table", "field_columns", "column_warnings", "format_problems"]

#: file suffix -> format name
FORMATS = {".csv": "csv", ".xlsx": "excel", ".xlsm": "excel", ".ods": "ods", ".parquet": "parquet", ".pq": "parquet"}

_NAMES = {f.name for f in schema.FIELDS}
_ALIASES = {a: f.name for f in schema.FIELDS for a in f.aliases}
_LIST_FIELDS = {f.name for f in schema.FIELDS if f.kind == "list"}
#: usual identification columns, carried through without a "did you mean" warning
PASSTHROUGH = ("application_id", "id", "name", "application_name", "project", "customer", "engine", "comment",
               "comments", "note", "notes", "row")


def _format(path: Path, what: str) -> str:
    fmt = FORMATS.get(path.suffix.lower())
    if fmt is None:
        raise InputError(Problem(what, str(path), "a file ending in " + ", ".join(sorted(FORMATS))))
    return fmt


def read_portfolio(path) -> pd.DataFrame:
    """Read a portfolio table (CSV, Excel, LibreOffice .ods or Parquet, by extension) as it is in the file.

    The file goes through the input gate (:func:`synth.io.tables.read_table`:
    size, rows, encoding, parser errors with their line). CSV cells are read
    as text (the validator converts them, so ``"3,5"`` or ``"abc"`` reach it
    and are reported, not turned into NaN by pandas); workbook and Parquet
    cells keep their types. Raises :class:`~synth.errors.InputError` (exit
    code 2 in the CLI) for a missing, unreadable or empty file, one without
    any design-input column, or one that names a field twice (a repeated
    column, or a field and its alias: ``application`` and ``application_type``).
    """

    p = Path(path)
    _format(p, "portfolio")
    df = read_table(p, "portfolio")
    check_columns(df, p.name)
    return df


def check_columns(df: pd.DataFrame, where: str = "portfolio") -> None:
    """A Problem for a table without design-input columns or naming one field twice."""

    problems = []
    for first, again in duplicate_columns(df):
        if first in _NAMES or first in _ALIASES:
            problems.append(Problem(f"column {first} ({where})", "given twice",
                                    "each design-input field in one column"))
    by_field: dict[str, list[str]] = {}
    for c in field_columns(df):
        by_field.setdefault(_ALIASES.get(c, c), []).append(c)
    for name, cols in by_field.items():
        if len(cols) > 1:
            problems.append(Problem(f"columns {' and '.join(cols)} ({where})", "both given",
                                    f"only one of them: both name the field {name} (remove one column)"))
    if not field_columns(df):
        problems.append(Problem("portfolio", where, "a table whose columns are design-input field names "
                                "(e.g. " + ", ".join(f.name for f in schema.FIELDS[:3]) + ")"))
    if problems:
        raise InputError(problems)


def field_columns(df: pd.DataFrame) -> list[str]:
    """The columns of ``df`` that are design-input fields (by name or alias)."""
    return [c for c in df.columns if c in _NAMES or c in _ALIASES]


def column_warnings(df: pd.DataFrame) -> list[str]:
    """Warnings about columns that look like misspelt field names (they are carried through, not used).

    >>> column_warnings(pd.DataFrame(columns=["working_arm_mm", "wroking_arm", "application_id"]))
    ["column 'wroking_arm' is not a design-input field and is not used (did you mean working_arm_mm?)"]
    """
    used = set(field_columns(df))
    out = []
    for c in df.columns:
        if c in used or c.lower() in PASSTHROUGH:
            continue
        near = difflib.get_close_matches(c, sorted(_NAMES), n=1, cutoff=0.75)
        if near:
            out.append(f"column {c!r} is not a design-input field and is not used (did you mean {near[0]}?)")
    return out


_parse_list = schema.parse_number_list


def plain_cell(value):
    """A table cell as plain Python data: numpy scalars as Python, empty (None, NA, NaT, NaN) as None."""
    if value is None or value is pd.NA or value is pd.NaT:
        return None
    if isinstance(value, np.generic):
        value = value.item()
    if isinstance(value, float) and math.isnan(value):
        return None
    return value


def clean_cell(value, name: str | None = None):
    """One cell as the validator expects it: empty/NaN -> None, text stripped, numpy scalars as Python.

    >>> clean_cell("  "), clean_cell(float("nan")), clean_cell(" dry "), clean_cell("2.3x4.0", "main_spring_wire_size_mm")
    (None, None, 'dry', [2.3, 4.0])
    """
    value = plain_cell(value)
    if isinstance(value, str):
        value = value.strip()
        if is_not_given(value):
            return None
    if name is not None and _ALIASES.get(name, name) in _LIST_FIELDS:
        return _parse_list(value)
    return value


def row_record(row: dict) -> dict:
    """The design-input mapping of one table row (only field columns, cells cleaned, empty cells left out)."""
    out = {}
    for k, v in row.items():
        if k in _NAMES or k in _ALIASES:
            v = clean_cell(v, k)
            if v is not None:
                out[k] = v
    return out


def records(df: pd.DataFrame) -> list[dict]:
    """:func:`row_record` of every row of ``df``, in order."""
    cols = field_columns(df)
    return [row_record(r) for r in df[cols].to_dict(orient="records")]


def format_problems(exc: InputError) -> str:
    """``field: got 'x'; accepted: ...`` for every problem of ``exc``, joined with ``' | '``."""
    return " | ".join(str(p) for p in exc.problems)


def validate_record(rec: dict):
    """``(DesignInput, "")`` for a valid record, ``(None, error text)`` otherwise (never raises for bad data)."""
    try:
        return schema.validate(rec), ""
    except InputError as exc:
        return None, format_problems(exc)


def validate_rows(df: pd.DataFrame) -> tuple[list, list[str]]:
    """Validate every row of ``df``: ``(apps, errors)``, ``apps[i]`` None where ``errors[i]`` says why."""
    out = [validate_record(r) for r in records(df)]
    return [a for a, _ in out], [e for _, e in out]


def _coerce_column(f, name: str, col: pd.Series, problems: list) -> list:
    """The values of field ``f`` (column ``name``) as :func:`synth.schema.validate` coerces them, column by column:
    plain numbers (the text of :data:`synth.io.numbers` ``NUMBER_RE``, or a numeric column) parsed and range-checked
    at once, other fields once per distinct cell; any other cell (a decimal comma, a unit, a bad value) goes
    through the validator's own ``coerce`` (its problems appended to ``problems[row]``). None: not given."""
    n = len(col)
    raw = col.to_numpy(dtype=object)
    out = [None] * n
    slow = np.zeros(n, dtype=bool)
    if f.kind in ("float", "int") and not f.choices and not f.catalog:
        if pd.api.types.is_numeric_dtype(col.dtype) and not pd.api.types.is_bool_dtype(col.dtype):
            x = col.to_numpy(dtype=float, na_value=np.nan)
            given = ~np.isnan(x)
        else:
            t = col.astype("string").str.strip()
            given = ~(t.isna() | t.str.lower().str.replace(" ", "", regex=False).isin(NOT_GIVEN)).to_numpy()
            plain = (t.str.fullmatch(NUMBER_RE.pattern).fillna(False).to_numpy(dtype=bool)) & given
            x = np.full(n, np.nan)
            x[plain] = t[plain].astype(float).to_numpy()
            slow = given & ~plain
        ok = given & ~slow & np.isfinite(x)
        with np.errstate(invalid="ignore"):
            ok &= ~((x <= f.lo) if f.lo_open else (x < f.lo)) & ~((x >= f.hi) if f.hi_open else (x > f.hi))
            if f.kind == "int":
                ok &= x == np.floor(x)
        slow |= given & ~ok
        vals = x[ok].astype(int).tolist() if f.kind == "int" else x[ok].tolist()
        for i, v in zip(np.flatnonzero(ok).tolist(), vals):
            out[i] = v
        for i in np.flatnonzero(slow).tolist():
            found: list = []
            out[i] = schema.coerce(f, clean_cell(raw[i], name), found)
            problems[i].extend(found)
        return out
    seen: dict = {}
    for i, v in enumerate(raw):
        try:
            hit = seen.get(v)
        except TypeError:  # an unhashable cell (a list from a typed table): on its own
            hit = None
        if hit is None:
            found = []
            value = schema.coerce(f, clean_cell(raw[i], name), found)
            hit = (value, found)
            try:
                seen[v] = hit
            except TypeError:
                pass
        value, found = hit
        out[i] = list(value) if isinstance(value, list) else value
        if found:
            problems[i].extend(found)
    return out


def validate_table(df: pd.DataFrame) -> tuple[list, list[str]]:
    """:func:`validate_rows` column by column: the same inputs and the same error texts.

    Each field column is coerced at once (:func:`_coerce_column`: plain numbers parsed and range-checked as
    arrays, the other fields once per distinct cell, anything unusual through the validator's own per-value
    code); then each row takes the validator's rules on its coerced values (defaults, required fields,
    selectors, cross-field consistency: :func:`synth.schema.finish`, the one copy of them)."""
    n = len(df)
    cols = field_columns(df)
    problems: list = [[] for _ in range(n)]
    names, columns = [], []
    for c in cols:
        name = _ALIASES.get(c, c)
        names.append(name)
        columns.append(_coerce_column(schema.field_by_name(name), c, df[c], problems))
    apps: list = [None] * n
    errors = [""] * n
    for i, row in enumerate(zip(*columns) if columns else [()] * n):
        try:
            apps[i] = schema.finish(dict(zip(names, row)), problems[i])
        except InputError as exc:
            errors[i] = format_problems(exc)
    return apps, errors


def _list_text(v) -> str:
    return "x".join(f"{float(x):g}" for x in v)


def to_table(apps) -> pd.DataFrame:
    """A portfolio table of validated inputs: one column per field (all fields, in :data:`FIELDS` order).

    List values are written as ``"2.3x4"`` so that every format (CSV, Excel, Parquet) stores them.
    """
    rows = []
    for a in apps:
        d = a.as_dict() if hasattr(a, "as_dict") else dict(a)
        rows.append({f.name: (_list_text(d[f.name]) if f.name in _LIST_FIELDS and d.get(f.name) is not None
                              else d.get(f.name)) for f in schema.FIELDS})
    return pd.DataFrame(rows, columns=[f.name for f in schema.FIELDS])


def arrow_safe(df: pd.DataFrame) -> pd.DataFrame:
    """A copy Parquet can store: object columns mixing types (numbers and text) become text, None kept."""
    out = df.copy()
    for c in out.columns:
        if out[c].dtype != object:
            continue
        kinds = {type(v) for v in out[c] if v is not None and not (isinstance(v, float) and math.isnan(v))}
        if len(kinds) > 1 and not kinds <= {int, float, np.float64, np.int64}:
            out[c] = [None if v is None or (isinstance(v, float) and math.isnan(v)) else str(v) for v in out[c]]
    return out


#: numbers in the CSV files synth writes: 6 significant figures (a margin to 1e-4 %, a stress to 0.01 MPa)
CSV_FLOAT = "%.6g"


def write_table(df: pd.DataFrame, path, *, float_format: str | None = None) -> Path:
    """Write ``df`` as CSV, Excel or Parquet by the extension of ``path`` (folders created), through the output
    gate (:func:`synth.io.outputs.output_file`: a temporary file renamed when complete; CSV text cells made
    formula-safe by :func:`synth.io.outputs.csv_safe`); ``float_format``: the numbers of a CSV (:data:`CSV_FLOAT`
    for results; a portfolio of inputs keeps every digit)."""
    p = Path(path)
    fmt = _format(p, "output")
    if fmt == "csv":
        return write_csv(df, p, float_format=float_format)
    if fmt == "excel":  # text as text, significant figures, print setup (synth.excel.cells)
        write_frame(df, p, sheet="portfolio")
        return p
    with output_file(p) as tmp:
        if fmt == "ods":  # OpenDocument (odfpy): strings are string cells, never formulas
            df.to_excel(tmp, index=False, engine="odf")
        else:
            arrow_safe(df).to_parquet(tmp, index=False)
    return p
