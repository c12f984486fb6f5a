"""``synth flowchart INPUT``: the thesis procedure, step by step, with verdicts (or ``--parts``: verify a design)."""

from __future__ import annotations

from pathlib import Path

from synth import flowchart
from synth.io import documents
from synth.io.outputs import json_text
from synth.report.text import render
from synth.scenes._options import add_model_options, load_saved_result, settings_from_args
from synth.io.saved_results import parts_of

__all__ = ["register"]


def register(sub) -> None:
    p = sub.add_parser("flowchart", help="run the thesis design flowchart (steps 0-10) on a design input")
    p.add_argument("input", help="design input (.yaml, .toml, .json, .xlsx; a case file works)")
    p.add_argument("--json", action="store_true", help="print the result as one JSON object (exit code as without)")
    p.add_argument("--parts", metavar="RESULT.json",
                   help="verify a given design instead of selecting one: the --json of any synth scene")
    add_model_options(p)
    p.set_defaults(func=_main)


def _main(args) -> int:
    d = documents.load_input(args.input)
    if args.parts:
        parts = parts_of(load_saved_result(args.parts, "--parts").to_dict(), Path(args.parts).name)
    else:
        parts = None
    r = flowchart.run(d, settings_from_args(args), parts=parts)
    if args.json:
        print(json_text(r.to_dict(), indent=2))
    else:
        print(render(r, title=f"synth flowchart: {args.input}" + (f" (parts of {args.parts})" if args.parts else "")))
    return r.exit_code
