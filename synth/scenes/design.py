"""``synth design INPUT``: the optimal catalog design, with every check and what binds.

Infeasible inputs get the nearest design, the constraints it violates by how
much, and the smallest input relaxations that would make it feasible. The exit
code is the verdict's (0 pass, 1 fail or infeasible, 3 incomplete), with or
without ``--json``.
"""

from __future__ import annotations

import json
import sys

from synth.report.text import render
from synth.scenes._options import add_design_options, add_robust_options, synthesise

__all__ = ["register"]


def register(sub) -> None:
    p = sub.add_parser("design", help="optimal tensioner from the catalogs (standardisation, cost or margin)")
    p.add_argument("input", help="design input (.yaml, .toml, .json, .xlsx; a case file works)")
    add_design_options(p)
    add_robust_options(p)
    p.add_argument("--assumptions", action="store_true",
                   help="also list the verdicts that flip inside the illustrative limits' plausible ranges "
                        "(catalogs/assumption_ranges.csv)")
    p.add_argument("--json", action="store_true", help="print the result as one JSON object (exit code as without)")
    p.add_argument("--cad", metavar="DIR", default=None,
                   help="also export the 3D model of the design (STEP, STL, pictures, geometric checks) into DIR")
    p.set_defaults(func=_main)


def _main(args) -> int:
    from synth.schema import load_input
    d = load_input(args.input)
    r = synthesise(d, args)
    if args.assumptions and r.parts:
        from synth.robust.assumptions import flips
        from synth.scenes._options import settings_from_args
        r.robust = {**r.robust, "assumptions": flips(d, r.parts, settings_from_args(args))}
    if args.json:
        print(json.dumps(r.to_dict(), indent=2))
    else:
        print(render(r, title=f"synth design: {args.input}"))
    if args.cad:
        from pathlib import Path
        print("\n".join(export_cad(r, args.cad, Path(args.input).stem)), file=sys.stderr if args.json else sys.stdout)
    if r.robust.get("checks") and not r.robust.get("meets", True):
        return 1  # the capability target is missed: the design fails it
    return r.exit_code


def export_cad(r, out_dir, application: str | None = None) -> list[str]:
    """Export the design's 3D model (thesis step 11) and return the summary lines."""
    from synth.cad import export_result, summary_lines
    model, checks, info = export_result(r, out_dir, application=application)
    return [f"3D model written to {out_dir}"] + summary_lines(model, checks, info)
