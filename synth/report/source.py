"""What a report is made of: a :class:`~synth.design.result.Result` as it is, a saved result file (the ``--json`` of
any scene) or a design-input file (YAML, JSON, TOML or an Excel sheet, with its cells for the workbook), the input
synthesised by the caller's synthesis.

The command line (:func:`synth.scenes.report.result_for_report`) and the Python API (:func:`synth.write_report`)
both read their source here, each with its own synthesis (the scene's options; the API's defaults).
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Callable

from synth import schema
from synth.design.result import Result
from synth.io import documents
from synth.io.saved_results import load_result

__all__ = ["is_result_file", "read_source"]


def is_result_file(path: Path) -> bool:
    """Whether ``path`` is a saved result (a ``.json`` mapping of kind ``synth.result``), not an input."""
    if path.suffix.lower() != ".json" or not path.is_file():
        return False
    try:
        return isinstance(json.loads(path.read_text(encoding="utf-8")), dict) and \
            json.loads(path.read_text(encoding="utf-8")).get("kind") == "synth.result"
    except (OSError, ValueError, UnicodeDecodeError):
        return False


def read_source(source, synthesise: Callable) -> tuple:
    """``(result, cells, source name)`` of ``source``: a :class:`Result` (``cells`` None, name ``"result"``), a saved
    result file (read through the input gate, :func:`synth.io.saved_results.load_result`), or an input file
    validated (:func:`synth.schema.validate`) and given to ``synthesise(design input) -> Result`` (an Excel input's
    cells kept for the workbook)."""
    if isinstance(source, Result):
        return source, None, "result"
    src = Path(source)
    if is_result_file(src):
        return Result.from_dict(load_result(src, "input"), source=str(src.name)), None, str(src)
    data = documents.read_mapping(src)
    cells = None
    if src.suffix.lower() in (".xlsx", ".xlsm"):
        from synth.excel.reader import read_cells
        cells = read_cells(src)[1]
    return synthesise(schema.validate(data)), cells, str(src)
