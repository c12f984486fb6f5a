"""``synth robust INPUT|RESULT.json``: how much of a production run a design would lose, and why.

The design is the one ``synth design INPUT`` returns (or a saved result's). For it: the tolerance model
(``catalogs/tolerances.csv``), per checked constraint the probability of violation with its 95 % interval,
the process performance index Ppk, the worst case and the RSS of the bands, the contributors, and which
verdicts rest on an illustrative limit (they flip inside its plausible range, ``catalogs/assumption_ranges.csv``).
``--out DIR`` also writes ``capability.json``, ``capability.csv`` and the histograms. The verdict (the last line and
the exit code) is the result's one verdict: 0 when the design passes its checks and meets the target, 1 when it
fails a check or misses the target (the line says which), 3 when checks were not verified.
To search the catalog for the best design meeting the target: ``synth design INPUT --capability 1.33``.
"""

from __future__ import annotations

import sys
from pathlib import Path

from synth.scenes._options import add_design_options, add_robust_options, load_saved_result
from synth.scenes._options import robust_settings_from_args, settings_from_args, synthesise
from synth.io.outputs import json_text, output_file, output_files, write_text
from synth.report.robust import capability_rows, histogram_png, HISTOGRAM_TITLES

__all__ = ["register", "robust_result"]


def register(sub) -> None:
    p = sub.add_parser("robust", help="production capability of a design: P(violation), Ppk, contributors, "
                                      "the verdicts resting on illustrative limits")
    p.add_argument("input", help="design input (.yaml, .toml, .json, .xlsx) or a saved result (--json of any scene)")
    add_robust_options(p, default_capability=1.33)
    add_design_options(p)
    p.add_argument("--no-assumptions", action="store_true",
                   help="skip the verdicts that flip inside the illustrative limits' ranges")
    p.add_argument("--out", metavar="DIR", help="also write capability.json, capability.csv and the histograms here")
    p.add_argument("--json", action="store_true", help="print the result (with its capability) as one JSON object")
    p.set_defaults(func=_main)


def robust_result(source, args):
    """The :class:`~synth.design.result.Result` of ``source`` (an input or a saved result) with ``robust`` set."""
    from synth import schema
    from synth.io import documents
    from synth.design.evaluate import Settings
    from synth.design.verify import verify
    from synth.robust.capability import capability
    from synth.robust.sampling import base_of
    from synth.scenes.report import is_result_file
    rs = robust_settings_from_args(args, default_capability=1.33)
    src = Path(source)
    if is_result_file(src):
        saved = load_saved_result(src, "input", needs_inputs=True)  # re-verified: its inputs are needed
        settings = Settings.from_saved(saved.settings, saved.rules)  # the result's own configuration
        d = schema.validate({k: v for k, v in (saved.inputs or {}).items() if v is not None})
        r = verify(d, saved.parts, settings, status=saved.status, solver=saved.solver, notes=saved.notes)
        r.objective, r.objectives, r.stats = saved.objective, saved.objectives, saved.stats
    else:
        d = documents.load_input(source)
        settings = settings_from_args(args)
        r = synthesise(d, _nominal(args))  # the design synth design returns, then its capability
    if not r.parts:
        return r
    r.robust = capability(base_of(d, r.parts, settings), rs).to_dict()
    if not getattr(args, "no_assumptions", False):
        from synth.robust.assumptions import flips
        r.robust["assumptions"] = flips(d, r.parts, settings)
    return r


def _nominal(args):
    """The design options of ``args`` without a capability target (``synth robust`` reports the nominal design)."""
    import copy
    a = copy.copy(args)
    a.capability = a.ppm = None
    return a


def _main(args) -> int:
    from synth.report.text import render, verdict_line
    from synth.scenes.report import out_folder
    out = out_folder(args.out) if args.out else None
    r = robust_result(args.input, args)
    if args.json:
        print(json_text(r.to_dict(), indent=2))
    else:
        print(render(r, title=f"synth robust: {args.input}", verdict=False))
    if out is not None and r.robust.get("checks"):
        import pandas as pd
        from synth.bulk.portfolio import write_table
        with output_files(out, "--out") as stage:  # one output: every file, or none
            write_text(stage / "capability.json", json_text(r.robust, indent=2))
            write_table(pd.DataFrame(capability_rows(r.robust)), stage / "capability.csv")
            for key, values in (r.robust.get("histograms") or {}).items():
                title, unit = HISTOGRAM_TITLES.get(key, (key, ""))
                with output_file(stage / f"hist_{key}.png") as tmp:
                    tmp.write_bytes(histogram_png(values, (r.robust.get("limits") or {}).get(key), title, unit))
        print(f"\nwritten: {out / 'capability.json'}, {out / 'capability.csv'} and the histograms",
              file=sys.stderr if args.json else sys.stdout)
    if not args.json:
        print("\n" + verdict_line(r))
    return r.exit_code  # the one verdict: the design's checks and the capability target (Result.judgement)
