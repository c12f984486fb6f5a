"""The input gate: every file synth reads goes through here.

* :mod:`synth.io.limits` -- the limits (file size, nesting, text length,
  rows) and the bounds of every count option;
* :mod:`synth.io.files` -- a file exists, is not too big, is UTF-8 text or a
  sound workbook;
* :mod:`synth.io.structured` -- YAML/TOML/JSON within the limits (alias bombs,
  deep nesting, huge numbers, non-finite numbers);
* :mod:`synth.io.numbers` -- cell text to numbers: decimal commas, "N/A";
* :mod:`synth.io.workbook` -- a sheet of an .xlsx or LibreOffice .ods
  workbook as cells (values, cached formula results, formulas);
* :mod:`synth.io.documents` -- design inputs, shrink-fit cases and scene
  tables as mappings;
* :mod:`synth.io.tables` -- portfolio tables (CSV, xlsx, ods, Parquet);
* :mod:`synth.io.saved_results` -- saved ``synth design/flowchart --json`` results,
  shape-checked;
* :mod:`synth.io.catalogs` -- user catalog folders (``--catalogs DIR``);
* :mod:`synth.io.outputs` -- the output gate: every file synth writes (a
  temporary file renamed when complete, never through a link), CSV cells
  formula-safe, JSON always valid, STEP strings escaped.

Every problem is an :class:`~synth.errors.InputError` naming the file,
sheet, cell, row or column the user wrote; nothing here lets a parser's
exception through.
"""

from synth.io.limits import COUNTS, LIMITS, check_count, short

__all__ = ["COUNTS", "LIMITS", "check_count", "short"]
