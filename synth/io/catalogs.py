"""User catalogs (``synth --catalogs DIR``, ``SYNTH_CATALOGS``): a folder of CSVs checked like any input.

A user CSV overrides the built-in catalog of the same file name (see
:mod:`synth.catalog`). Before it is merged, :func:`read_user_catalog` checks
it against the built-in one and reports every problem with the file, the
data row (and its line in the file) and the column:

* the file: UTF-8 text, at most :attr:`~synth.io.limits.Limits.catalog_bytes`,
  parseable (a row with too many fields names its line), not empty;
* the columns: the built-in key column first, every built-in column present,
  a ``source`` column (every row of every catalog says where its values come from);
* the cells: a number (finite) in every column that is numeric in the
  built-in catalog (positive, or not negative, where every built-in value
  is: a negative stress area is refused naming the file, row, line and
  column), ``true``/``false`` in a boolean column, a key and a source on
  every row, no key twice.

:func:`check_user_dir` checks a whole folder at once: that it exists, that
every CSV in it is named like a built-in catalog (a misspelt file name would
otherwise be ignored silently), and every file as above.
"""

from __future__ import annotations

import difflib
import importlib
import io
import math
from pathlib import Path

from synth.errors import InputError, Problem
from synth.io.files import read_text
from synth.io.limits import LIMITS, short
from synth.io.numbers import percentage
from synth.io.tables import parser_problem, check_field_counts

__all__ = ["check_user_dir", "read_user_catalog", "read_catalog_text"]

_TRUE = ("true", "1", "yes", "y")
#: catalogs whose rows have rules beyond their cells' types: file stem -> "module:function(table, at) -> problems"
_ROW_CHECKS = {"prices": "synth.cost.prices:check_rows"}
_FALSE = ("false", "0", "no", "n")


def check_user_dir(folder, builtin_names: list[str], builtin_loader, option: str = "--catalogs") -> Path:
    """Check user catalog folder ``folder``; ``builtin_loader(name)`` gives the built-in DataFrame."""
    p = Path(folder)
    try:
        ok = p.is_dir()
    except (OSError, ValueError):
        ok = False
    if not ok:
        state = "a file, not a folder" if p.exists() else "no such folder"
        raise InputError(Problem(option, str(folder), f"an existing folder of catalog CSV files ({state})"))
    problems: list[Problem] = []
    for f in sorted(p.glob("*.csv")):
        if f.stem not in builtin_names:
            near = difflib.get_close_matches(f.stem, builtin_names, n=1)
            hint = f" (did you mean {near[0]}.csv?)" if near else ""
            problems.append(Problem(f"{option} {f.name}", str(f),
                                    "a CSV named like a built-in catalog, or it would be ignored" + hint))
            continue
        try:
            read_user_catalog(f, builtin_loader(f.stem))
        except InputError as exc:
            problems.extend(exc.problems)
    if problems:
        raise InputError(problems)
    return p


def read_catalog_text(text: str, path: Path):
    """Parse catalog CSV text (comments ``#``, key column as text, spaces stripped); raise a Problem on error."""
    import pandas as pd


    check_field_counts(text, path, "catalog", comment="#")
    try:
        df = pd.read_csv(io.StringIO(text), comment="#", skipinitialspace=True, dtype=str, keep_default_na=False,
                         nrows=LIMITS.catalog_rows + 1)
    except Exception as exc:  # ParserError, EmptyDataError
        raise InputError(parser_problem(exc, path, "catalog")) from None
    if len(df) > LIMITS.catalog_rows:
        raise InputError(Problem("catalog", str(path), f"a catalog of at most {LIMITS.catalog_rows} rows"))
    df.columns = [str(c).strip() for c in df.columns]
    return df


def _data_lines(text: str) -> list[int]:
    """File line number of every data row (after the header), skipping blank and ``#`` comment lines."""
    lines = [i for i, line in enumerate(text.splitlines(), start=1) if line.strip() and not line.lstrip().startswith("#")]
    return lines[1:]


def read_user_catalog(path, builtin):
    """User catalog file ``path`` checked against the built-in DataFrame ``builtin``; typed like it.

    Returns the DataFrame to merge (numeric columns as floats, boolean columns
    as bools, the key column as stripped text).
    """
    import pandas as pd

    p = Path(path)
    text = read_text(p, f"catalog {p.name}", limit=LIMITS.catalog_bytes, accepted="a UTF-8 CSV file")
    raw = read_catalog_text(text, p)
    lines = _data_lines(text)
    where = f"catalog {p.name}"
    if raw.empty and not len(raw.columns):
        raise InputError(Problem(where, str(p), "a CSV file with a header line (this file is empty)"))
    key = builtin.columns[0]
    problems: list[Problem] = []
    if raw.columns[0] != key:
        problems.append(Problem(f"{where}, column 1", short(raw.columns[0]), f"the key column '{key}' first, as in "
                                                                             "the built-in catalog"))
    missing = [c for c in builtin.columns if c not in raw.columns and c != "source"]
    if missing:
        problems.append(Problem(f"{where}, columns", None, "every column of the built-in catalog (a row replaces a "
                                                           "built-in row whole); missing: " + ", ".join(missing)))
    if "source" not in raw.columns:
        problems.append(Problem(f"{where}, column source", None, "a 'source' column: where each row's values "
                                                                 "come from (standard and clause, data sheet, or "
                                                                 "'illustrative')"))
    if raw.empty:
        problems.append(Problem(where, str(p), "at least one data row"))
    if problems:
        raise InputError(problems)

    def at(i: int, col: str) -> str:
        line = f", line {lines[i]}" if i < len(lines) else ""
        return f"{where}, row {i + 1}{line}, column {col}"

    out = raw.copy()
    seen: dict[str, int] = {}
    for i, k in enumerate(raw[key]):
        k = str(k).strip()
        if not k:
            problems.append(Problem(at(i, key), None, "a key (designation) on every row"))
        elif k in seen:
            problems.append(Problem(at(i, key), short(k), f"a key not already given (row {seen[k] + 1} has it)"))
        else:
            seen[k] = i
    out[key] = raw[key].astype(str).str.strip()
    if "source" in raw.columns:
        for i, v in enumerate(raw["source"]):
            if not str(v).strip():
                problems.append(Problem(at(i, "source"), None, "the source of the row's values (standard and "
                                                               "clause, data sheet, or 'illustrative')"))
    for col in builtin.columns[1:]:
        kind = builtin[col].dtype.kind if builtin[col].notna().any() else "O"  # an empty column: text
        if kind == "b":
            vals = []
            for i, v in enumerate(raw[col]):
                t = str(v).strip().lower()
                if t in _TRUE or t in _FALSE:
                    vals.append(t in _TRUE)
                else:
                    problems.append(Problem(at(i, col), short(v), "true or false"))
                    vals.append(False)
            out[col] = vals
        elif kind in "if":
            may_be_empty = bool(builtin[col].isna().any())
            known = builtin[col].dropna()
            sign = (">", 0.0) if len(known) and bool((known > 0).all()) else \
                (">=", 0.0) if len(known) and bool((known >= 0).all()) else None
            vals = []
            for i, v in enumerate(raw[col]):
                t = str(v).strip()
                if not t:
                    if not may_be_empty:
                        problems.append(Problem(at(i, col), None, f"a number (column {col} is never empty in the "
                                                                  "built-in catalog)"))
                    vals.append(math.nan)
                    continue
                in_percent = col.endswith("_pct") or (col == "value" and "unit" in raw.columns
                                                      and str(raw["unit"].iloc[i]).strip() == "%")
                if in_percent:  # a value in percent: 8, "8 %" or 8% (the one percentage parser)
                    x = percentage(t, "%")
                else:
                    try:
                        x = float(t)
                    except ValueError:
                        x = None
                if x is None or not math.isfinite(x):
                    problems.append(Problem(at(i, col), short(t), f"a finite number (column {col} is numeric"
                                                                  + (", in percent: 8 or 8 %)" if in_percent
                                                                     else ")")))
                    vals.append(math.nan)
                elif sign is not None and (x <= sign[1] if sign[0] == ">" else x < sign[1]):
                    problems.append(Problem(at(i, col), short(t), f"a number {sign[0]} 0 (every value of column {col} "
                                                                  "in the built-in catalog is; a negative area, "
                                                                  "length, load or cost is no part)"))
                    vals.append(math.nan)
                else:
                    vals.append(x)
            out[col] = pd.Series(vals, index=raw.index, dtype=float)
        else:
            out[col] = raw[col].astype(str).str.strip().replace("", math.nan)
        if len(problems) >= 50:
            break
    if not problems and p.stem in _ROW_CHECKS:  # a catalog with rules beyond its cells' types
        module, name = _ROW_CHECKS[p.stem].split(":")
        problems = getattr(importlib.import_module(module), name)(out, at)
    if problems:
        raise InputError(problems)
    return out
