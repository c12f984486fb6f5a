"""``synth demo``: the synthesis on the embedded default application, its 3D model and its report.

The synthesis is the robust one (:mod:`synth.robust.synthesis`, Ppk >= 1.33 under the tolerance model): the best
design meeting the target, or the most standardised nominal design and why no catalog design meets it; its
production capability and the verdicts resting on illustrative limits are printed and reported. The exit code is
the design's nominal verdict (``--no-robust``: the nominal synthesis alone).
"""

from __future__ import annotations

from importlib import resources
from pathlib import Path

import yaml

from synth import schema

__all__ = ["register", "default_input"]


def default_input():
    """The embedded default design input (``synth/data/default_case.yaml``)."""
    text = resources.files("synth").joinpath("data/default_case.yaml").read_text(encoding="utf-8")
    return schema.validate(yaml.safe_load(text)["inputs"])


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
    from synth.optimise import solve
    from synth.report.text import render
    out = Path(args.cad or args.out)
    d = default_input()
    from synth.optimise.objectives import with_margin_tiebreak
    if args.no_robust:
        r = solve(d, with_margin_tiebreak("standard"), "enumerate")
    else:  # the best design meeting Ppk >= 1.33 (or the nominal one and why none does), its capability, and the
        # verdicts resting on illustrative limits
        from synth.robust.settings import RobustSettings
        from synth.robust.synthesis import robust_solve
        from synth.scenes.report import add_capability
        rs = RobustSettings()
        r = robust_solve(d, with_margin_tiebreak("standard"), rs=rs)
        add_capability(r, rs)
    print(render(r, title="synth demo: the most standardised tensioner for the embedded default application"))
    if not args.no_cad:
        from synth.scenes.design import export_cad
        print("\n" + "\n".join(export_cad(r, out, "synth demo (thesis case 3, completed)")))
    if not args.no_report:
        from synth.scenes.report import make_report
        rep = make_report(r, out, show_progress=False)
        print(f"\nreport: {rep['html']} and {rep['xlsx']}")
    return r.exit_code
