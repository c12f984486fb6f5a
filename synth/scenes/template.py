"""``synth template FILE.xlsx``: write the design-input Excel template (thesis Fig. 22-26)."""

from __future__ import annotations

import sys

from synth import schema
from synth.io import documents
from synth.excel import template
from synth.errors import InputError, Problem

__all__ = ["register"]


def register(sub) -> None:
    p = sub.add_parser("template", help="write the design-input Excel template (example values: thesis case 1)")
    p.add_argument("file", help="the workbook to write (.xlsx)")
    p.add_argument("--from", dest="source", metavar="INPUT",
                   help="fill the template with the values of this design input (.yaml, .toml, .json, .xlsx)")
    p.add_argument("--force", action="store_true", help="overwrite an existing file")
    p.set_defaults(func=_main)


def _main(args) -> int:
    from pathlib import Path
    out = Path(args.file)
    if out.suffix.lower() != ".xlsx":
        raise InputError(Problem("template file", str(out), "a file name ending in .xlsx"))
    if out.exists() and not args.force:
        raise InputError(Problem("template file", str(out), "a new file (or --force to overwrite)"))
    values = None
    if args.source:
        values = schema.validate(documents.read_mapping(args.source)).as_dict()
    template.write_template(out, values)
    print(f"wrote {out}", file=sys.stderr)
    return 0
