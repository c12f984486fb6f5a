"""``synth demo``: the synthesis on the embedded default application, its 3D model and its report.

The synthesis is the robust one (:mod:`synth.robust.synthesis`, Ppk >= 1.33 under the tolerance model): the best
design meeting the target, or the most standardised nominal design and why no catalog design meets it; its
production capability and the verdicts resting on illustrative limits are printed and reported. The verdict (the
last line, and the exit code) is the result's one verdict: it includes the capability target the demo sets, so a
design that misses Ppk 1.33 is a FAIL with the checks that miss it (``--no-robust``: the nominal synthesis alone,
judged on its checks).
"""

from __future__ import annotations

from importlib import resources
from pathlib import Path

import yaml

from synth import schema
from synth.errors import InputError, Problem
from synth.report.text import render, verdict_line
from synth.scenes._options import default_args, synthesise
from synth.cad import require_cadquery
from synth.robust.settings import RobustSettings
from synth.robust.capability import add_capability
from synth.scenes.report import make_report
from synth.scenes.design import export_cad

__all__ = ["register", "default_input"]


def default_path():
    """The embedded default application's file (``synth/data/default_case.yaml``)."""
    return resources.files("synth").joinpath("data/default_case.yaml")


def default_input():
    """The embedded default design input (``synth/data/default_case.yaml``)."""
    return schema.validate(yaml.safe_load(default_path().read_text(encoding="utf-8"))["inputs"])


def default_name() -> str:
    """The embedded default application's name (its file's ``name:``)."""
    return str(yaml.safe_load(default_path().read_text(encoding="utf-8")).get("name") or "default")


def register(sub) -> None:
    p = sub.add_parser("demo", help="synthesise the most standardised tensioner for the embedded default application")
    p.add_argument("--out", metavar="DIR", default="out",
                   help="folder for the 3D model (tensioner.step, STL, pictures) and the report (default: out)")
    p.add_argument("--no-cad", action="store_true", help="skip the 3D model")
    p.add_argument("--no-report", action="store_true", help="skip the report")
    p.add_argument("--no-robust", action="store_true",
                   help="skip the robust synthesis and the production capability (Ppk >= 1.33 under "
                        "catalogs/tolerances.csv): the nominal synthesis only")
    p.add_argument("--cad", metavar="DIR", default=None, help=argparse_suppress())
    p.set_defaults(func=_main)


def argparse_suppress():
    import argparse
    return argparse.SUPPRESS


def _main(args) -> int:
    out = Path(args.cad or args.out)
    d, path, name = default_input(), default_path(), default_name()
    if not args.no_cad:  # before the work: the 3D model needs CadQuery (synth[cad])
        try:
            require_cadquery()
        except InputError as exc:
            p = exc.problems[0]
            raise InputError(Problem(p.field, p.value, p.accepted + "; or run synth demo --no-cad")) from None
    a = default_args()
    if not args.no_robust:  # the best design meeting Ppk >= 1.33 (or the nominal one and why none does)
        rs = RobustSettings()
        a.capability = rs.capability
    r = synthesise(d, a)
    if not args.no_robust and r.parts:  # its capability and the verdicts resting on illustrative limits
        add_capability(r, rs)
    pictures: list = []
    cad_lines: list = []
    if not args.no_cad:  # before the print: the 3D model's geometric checks are checks of the design
        cad = export_cad(r, out, f"synth demo: {name}", what="--out")
        cad_lines, pictures = cad.lines, cad.pictures
    print(render(r, title=f"synth demo: the most standardised tensioner for {name} ({path})", verdict=False))
    if cad_lines:
        print("\n" + "\n".join(cad_lines))
    if not args.no_report:
        rep = make_report(r, out, show_progress=False, cad=pictures, cad_pictures=False, source_name=str(path),
                          application=name)
        written = [rep["html"]] + ([rep["pdf"]] if rep["pdf"] else []) + [rep["xlsx"]]
        print("\nreport: " + ", ".join(str(p) for p in written)
              + (f" (PDF not written: {rep['pdf_note']})" if rep["pdf"] is None and rep["pdf_note"] else ""))
    print("\n" + verdict_line(r))
    return r.exit_code  # the one verdict: the design's checks, its 3D model's and the capability target
