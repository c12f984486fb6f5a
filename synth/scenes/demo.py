"""``synth demo``: the flowchart on the embedded default case (thesis case study 1 as run)."""

from __future__ import annotations

from importlib import resources

import yaml

from synth import flowchart, schema
from synth.scenes.flowchart import render_text

__all__ = ["register", "default_input"]


def default_input():
    """The embedded default design input (``synth/data/default_case.yaml``)."""
    text = resources.files("synth").joinpath("data/default_case.yaml").read_text(encoding="utf-8")
    return schema.validate(yaml.safe_load(text)["inputs"])


def register(sub) -> None:
    p = sub.add_parser("demo", help="run the flowchart on the embedded default case (thesis case 1)")
    p.add_argument("--cad", metavar="DIR", default=None,
                   help="also export the 3D model (STEP assembly, STL, exploded and section pictures) into DIR")
    p.set_defaults(func=_main)


def _main(args) -> int:
    print("synth demo: thesis case study 1 (inputs as the thesis tool ran them)\n")
    r = flowchart.run(default_input())
    print(render_text(r))
    if getattr(args, "cad", None):
        from synth.cad import export_result, summary_lines
        model, checks, info = export_result(r, args.cad)
        print(f"\n3D model (thesis step 11) written to {args.cad}")
        print("\n".join(summary_lines(model, checks, info)))
    return 0
