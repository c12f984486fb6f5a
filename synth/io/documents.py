"""Design inputs, shrink-fit cases and scene tables: a file the user named, as a mapping or rows.

* :func:`read_design_mapping` -- a design input (YAML/TOML/JSON, the .xlsx
  template, or the template saved by LibreOffice as .ods or .xlsx): the
  mapping :func:`synth.schema.validate` takes (a case file's ``inputs:`` block);
* :func:`load_input` -- a design-input file, read and validated (:func:`read_mapping`: the mapping);
* :func:`read_rows` -- a scene result table for ``synth report --optimum /
  --pareto / --solvers`` (CSV, JSON or YAML rows).

>>> from synth.data import case_path
>>> sorted(read_design_mapping(case_path("case3")))[:3]
['application_type', 'belt_loading_type', 'belt_width_mm']
"""

from __future__ import annotations

from pathlib import Path

from synth.errors import InputError, Problem
from synth.io.files import WORKBOOK_SUFFIXES, existing_file, suffix_of
from synth.io.limits import LIMITS
from synth.io.structured import read_document
from synth.schema import DesignInput, validate
from synth.io.tables import read_csv_text

__all__ = ["DESIGN_SUFFIXES", "read_design_mapping", "read_mapping", "load_input", "read_rows"]

DESIGN_SUFFIXES = (".yaml", ".yml", ".toml", ".json") + WORKBOOK_SUFFIXES
_DESIGN_ACCEPTED = ("an existing design input: .yaml, .yml, .toml, .json, or the Excel template "
                    "(.xlsx, or .ods saved by LibreOffice)")


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


def read_rows(path, what: str) -> list[dict]:
    """Rows of a scene result file: CSV, JSON or YAML (a list of mappings or one mapping)."""
    accepted = "an existing .csv, .json or .yaml file of rows"
    suffix = suffix_of(path)
    if suffix == ".csv":
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


def read_mapping(path) -> dict:
    """Read a design input (YAML, TOML, JSON, the .xlsx template or a LibreOffice .ods) into a dict.

    The file goes through the input gate (:func:`read_design_mapping`): size, encoding, YAML aliases, nesting,
    huge and non-finite numbers are checked before anything is built; a case file's ``inputs:`` block is read.
    """
    return read_design_mapping(path)


def load_input(path) -> DesignInput:
    """Read and validate a design-input file (YAML, TOML or JSON; a case file works; the Excel template)."""
    return validate(read_mapping(path))
