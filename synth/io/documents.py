"""Design inputs, shrink-fit cases and scene tables: a file the user named, as a mapping or rows.

* :func:`read_document` -- a YAML, TOML or JSON file as plain data (limits of
  :mod:`synth.io.structured`);
* :func:`read_design_mapping` -- a design input (YAML/TOML/JSON, the .xlsx
  template, or the template saved by LibreOffice as .ods or .xlsx): the
  mapping :func:`synth.schema.validate` takes (a case file's ``inputs:`` block);
* :func:`read_rows` -- a scene result table for ``synth report --optimum /
  --pareto / --solvers`` (CSV, JSON or YAML rows).

>>> from synth.data import case_path
>>> sorted(read_design_mapping(case_path("case3")))[:3]
['application_type', 'belt_loading_type', 'belt_width_mm']
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

from synth.errors import InputError, Problem
from synth.io.files import existing_file, read_text, suffix_of
from synth.io.limits import LIMITS
from synth.io.structured import FORMAT_OF_SUFFIX, parse

__all__ = ["DESIGN_SUFFIXES", "WORKBOOK_SUFFIXES", "read_document", "read_design_mapping", "read_rows"]

WORKBOOK_SUFFIXES = (".xlsx", ".xlsm", ".ods")
DESIGN_SUFFIXES = (".yaml", ".yml", ".toml", ".json") + WORKBOOK_SUFFIXES
_DESIGN_ACCEPTED = ("an existing design input: .yaml, .yml, .toml, .json, or the Excel template "
                    "(.xlsx, or .ods saved by LibreOffice)")


def read_document(path, what: str, *, accepted: str = "an existing .yaml, .yml, .toml or .json file",
                  allow_nonfinite: bool = False) -> Any:
    """The data of a YAML, TOML or JSON file (by extension), within the gate's limits."""
    fmt = FORMAT_OF_SUFFIX.get(suffix_of(path))
    if fmt is None:
        raise InputError(Problem(what, str(path), accepted + " (by its extension)"))
    text = read_text(path, what, accepted=accepted)
    return parse(text, fmt, Path(path).name, allow_nonfinite=allow_nonfinite, what=what)


def read_design_mapping(path, what: str = "input file") -> dict:
    """The design-input mapping of file ``path`` (not validated: :func:`synth.schema.validate` does that).

    A workbook is read by :func:`synth.excel.reader.read_workbook` (which
    validates it and names the sheet and cell of each problem).
    """
    suffix = suffix_of(path)
    if suffix not in DESIGN_SUFFIXES:
        existing_file(path, what, _DESIGN_ACCEPTED)
        raise InputError(Problem(what, str(path), _DESIGN_ACCEPTED + " (by its extension)"))
    if suffix in WORKBOOK_SUFFIXES:
        from synth.excel.reader import read_workbook
        return read_workbook(path)
    data = read_document(path, what, accepted=_DESIGN_ACCEPTED)
    if data is None:
        raise InputError(Problem(what, str(path), "a mapping of design-input fields (the file is empty)"))
    if not isinstance(data, dict):
        raise InputError(Problem(what, str(path), f"a mapping of field names to values (the file holds a "
                                                  f"{type(data).__name__})"))
    if "inputs" in data:
        data = data["inputs"]
        if data is None:
            return {}
        if not isinstance(data, dict):
            raise InputError(Problem(f"inputs ({Path(path).name})", type(data).__name__,
                                     "a mapping of field names to values"))
    return {k: v for k, v in data.items() if k != "rules"}  # a flat file's design rules (synth.design.rules)


def read_rules_mapping(path, what: str = "--rules", *, section_only: bool = False):
    """The design-rules mapping of file ``path`` (:mod:`synth.design.rules`): a design input's (or a saved
    result's) ``rules:`` section, or a rules file's mapping (at the top, or under ``rules:``); None when a design
    input has none (``section_only``: the ``rules:`` section or None). A workbook has none."""
    suffix = suffix_of(path)
    if suffix in WORKBOOK_SUFFIXES:
        return None
    accepted = "a YAML, TOML or JSON file of design rules (or a design input with a rules: section)"
    if section_only:  # a design input: its own reader reports what is wrong with it, the rules reader nothing
        try:
            data = read_document(path, what, accepted=accepted)
        except InputError:
            return None
        return data.get("rules") or None if isinstance(data, dict) else None
    data = read_document(path, what, accepted=accepted)
    if not isinstance(data, dict):
        raise InputError(Problem(what, str(path), accepted))
    if "rules" in data:
        return data["rules"] or None
    if section_only or "inputs" in data or any(k in data for k in ("application_type", "pulley_diameter_mm")):
        return None  # a design input without rules
    return data


def read_rows(path, what: str) -> list[dict]:
    """Rows of a scene result file: CSV, JSON or YAML (a list of mappings or one mapping)."""
    accepted = "an existing .csv, .json or .yaml file of rows"
    suffix = suffix_of(path)
    if suffix == ".csv":
        from synth.io.tables import read_csv_text
        p = existing_file(path, what, accepted)
        df = read_csv_text(p, what, limit=LIMITS.text_input_bytes, max_rows=LIMITS.sheet_rows, typed=True)
        return df.to_dict(orient="records")
    if suffix not in (".json", ".yaml", ".yml"):
        raise InputError(Problem(what, str(path), accepted + " (by its extension)"))
    data = read_document(path, what, accepted=accepted)
    if isinstance(data, dict):
        return [data]
    if isinstance(data, list) and data and all(isinstance(r, dict) for r in data):
        return data
    raise InputError(Problem(what, str(path), "a list of mappings (rows) or one mapping"))
