"""Tables the user gives: portfolios (CSV, .xlsx, LibreOffice .ods, Parquet) and CSV files.

Every reader checks the file's size (and a workbook's unpacked size, and a
Parquet file's row count from its footer) before pandas builds anything, and
turns every parser error into an :class:`~synth.errors.InputError` naming the
file, and the line or column where the parser says it is.

>>> import tempfile, pathlib
>>> p = pathlib.Path(tempfile.mkdtemp()) / "t.csv"
>>> _ = p.write_text("a,b\\n1,2\\n3,4,5\\n")
>>> try:
...     read_csv_text(p, "portfolio")
... except InputError as exc:
...     print(exc.problems[0])
portfolio (t.csv, line 3): got '3 fields'; accepted: 2 fields as in the header line (a value with a comma needs "quotes")
"""

from __future__ import annotations

import io
import re
from pathlib import Path

from synth.errors import InputError, Problem
from synth.io.files import check_size, check_zip, existing_file, read_text, suffix_of
from synth.io.limits import LIMITS

__all__ = ["TABLE_FORMATS", "read_csv_text", "read_table", "duplicate_columns", "check_field_counts"]

#: file suffix -> table format
TABLE_FORMATS = {".csv": "csv", ".xlsx": "excel", ".xlsm": "excel", ".ods": "ods", ".parquet": "parquet",
                 ".pq": "parquet"}


def parser_problem(exc: Exception, p: Path, what: str) -> Problem:
    """The problem of CSV file ``p`` (``what``) that pandas' parser raised ``exc`` for, naming the line."""
    text = " ".join(str(exc).split())
    m = re.search(r"Expected (\d+) fields in line (\d+), saw (\d+)", text)
    if m:
        return Problem(f"{what} ({p.name}, line {m.group(2)})", f"{m.group(3)} fields",
                       f"{m.group(1)} fields as in the header line (a value with a comma needs \"quotes\")")
    if "No columns to parse" in text or type(exc).__name__ == "EmptyDataError":
        return Problem(what, str(p), "a CSV file with a header line (this file is empty)")
    return Problem(what, str(p), f"a readable CSV file ({type(exc).__name__}: {text[:200]})")


def check_field_counts(text: str, p: Path, what: str, comment: str | None = None) -> None:
    """Every record of CSV ``text`` has as many fields as its header (pandas would take extra ones as an index)."""
    import csv

    lines = (line for line in io.StringIO(text) if not (comment and line.lstrip().startswith(comment)))
    reader = csv.reader(lines, skipinitialspace=True)
    n = None
    try:
        for rec in reader:
            if not rec or (len(rec) == 1 and not rec[0].strip()):
                continue
            if n is None:
                n = len(rec)
            elif len(rec) != n:
                raise InputError(Problem(f"{what} ({p.name}, line {reader.line_num})", f"{len(rec)} fields",
                                         f"{n} fields as in the header line (a value with a comma needs \"quotes\")"))
    except csv.Error as exc:
        raise InputError(Problem(f"{what} ({p.name}, line {reader.line_num})", "not valid CSV", str(exc))) from None


def read_csv_text(path, what: str, *, limit: int | None = None, max_rows: int | None = None, typed: bool = False,
                  comment: str | None = None):
    """A CSV file as a DataFrame: UTF-8, at most ``limit`` bytes and ``max_rows`` rows.

    Cells are text (``typed=False``, for validators that report the text the
    user wrote) or pandas' types.
    """
    import pandas as pd

    p = existing_file(path, what, "an existing CSV file")
    text = read_text(p, what, limit=LIMITS.portfolio_bytes if limit is None else limit,
                     accepted="a UTF-8 CSV file")
    max_rows = LIMITS.portfolio_rows if max_rows is None else max_rows
    check_field_counts(text, p, what, comment)
    try:
        df = pd.read_csv(io.StringIO(text), dtype=None if typed else str, skipinitialspace=True, comment=comment,
                         nrows=max_rows + 1)
    except Exception as exc:  # ParserError, EmptyDataError, UnicodeError...: the file is named, the line kept
        raise InputError(parser_problem(exc, p, what)) from None
    if len(df) > max_rows:
        raise InputError(Problem(what, str(p), f"a table of at most {max_rows} rows"))
    if len(df.columns) > LIMITS.portfolio_columns:
        raise InputError(Problem(what, str(p), f"a table of at most {LIMITS.portfolio_columns} columns"))
    return df


def duplicate_columns(df) -> list[tuple[str, str]]:
    """Pairs ``(name, name.1)`` of columns pandas renamed because the header repeats ``name``."""
    cols = [str(c) for c in df.columns]
    out = []
    for c in cols:
        m = re.match(r"^(.*)\.(\d+)$", c)
        if m and m.group(1) in cols:
            out.append((m.group(1), c))
    return out


def read_table(path, what: str = "portfolio"):
    """A portfolio table (CSV, .xlsx/.xlsm, .ods or Parquet, by extension), as it is in the file.

    CSV cells are read as text (the validator converts them, so ``"3,5"`` or
    ``"abc"`` reach it and are reported, not turned into NaN by pandas);
    workbook and Parquet cells keep their types (a formula cell: its cached
    value). The index is reset to 0..n-1.
    """
    import pandas as pd

    accepted = "an existing portfolio table: " + ", ".join(sorted(TABLE_FORMATS)) + " (one application per row)"
    fmt = TABLE_FORMATS.get(suffix_of(path))
    if fmt is None:
        raise InputError(Problem(what, str(path), "a file ending in " + ", ".join(sorted(TABLE_FORMATS))))
    p = existing_file(path, what, accepted)
    rows = LIMITS.portfolio_rows
    if fmt == "csv":
        df = read_csv_text(p, what)
    elif fmt in ("excel", "ods"):
        check_size(p, what, LIMITS.portfolio_bytes, "workbook")
        kind = ".ods workbook (LibreOffice)" if fmt == "ods" else ".xlsx workbook"
        check_zip(p, what, LIMITS.portfolio_unpacked_bytes, kind)
        try:  # calamine (Rust): 10-30 times faster than openpyxl or odfpy, values only (benchmarks/bench_readers.py)
            df = pd.read_excel(p, dtype=object, nrows=rows + 1, engine="calamine")
        except ImportError:  # pragma: no cover - python-calamine is a dependency
            raise InputError(Problem(what, str(p), "a .csv or .parquet table (reading workbooks needs "
                                                   "python-calamine: pip install python-calamine)")) from None
        except Exception as exc:  # zip/XML errors: the file is named
            raise InputError(Problem(what, str(p), f"a readable {kind} ({type(exc).__name__}: "
                                                   f"{' '.join(str(exc).split())[:200]})")) from None
    else:
        check_size(p, what, LIMITS.portfolio_bytes, "Parquet file")
        import pyarrow.parquet as pq
        try:
            meta = pq.ParquetFile(p).metadata
            if meta.num_rows > rows or meta.num_columns > LIMITS.portfolio_columns:
                raise InputError(Problem(what, str(p), f"a table of at most {rows} rows and "
                                                       f"{LIMITS.portfolio_columns} columns (this one has "
                                                       f"{meta.num_rows} rows, {meta.num_columns} columns)"))
            df = pd.read_parquet(p)
        except InputError:
            raise
        except Exception as exc:
            raise InputError(Problem(what, str(p), f"a readable parquet table ({type(exc).__name__}: "
                                                   f"{' '.join(str(exc).split())[:200]})")) from None
    if len(df) > rows:
        raise InputError(Problem(what, str(p), f"a table of at most {rows} rows"))
    if len(df.columns) > LIMITS.portfolio_columns:
        raise InputError(Problem(what, str(p), f"a table of at most {LIMITS.portfolio_columns} columns"))
    df.columns = [str(c).strip() for c in df.columns]
    return df.reset_index(drop=True)
