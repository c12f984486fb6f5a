"""``synth flowchart INPUT``: the thesis procedure, step by step, with verdicts."""

from __future__ import annotations

import json

from synth import flowchart, schema
from synth.checks import FAIL, NOT_VERIFIED
from synth.output_table import ROWS, format_value

__all__ = ["register", "render_text", "add_model_options", "settings_from_args"]


def add_model_options(p) -> None:
    p.add_argument("--fidelity", choices=("full", "screening"), default="full",
                   help="full: time-integrated wear, Almen-Laszlo cone spring (default); screening: closed forms")
    p.add_argument("--linear-friction", action="store_true",
                   help="radial friction on r_p*mu as the thesis tool did (default: friction circle r_p*sin(atan(mu)))")


def settings_from_args(args) -> flowchart.Settings:
    return flowchart.Settings(fidelity=args.fidelity, friction_circle=not args.linear_friction)


def register(sub) -> None:
    p = sub.add_parser("flowchart", help="run the thesis design flowchart (steps 0-10) on a design input")
    p.add_argument("input", help="design input (.yaml, .toml, .json; a case file works)")
    p.add_argument("--json", action="store_true", help="print one JSON object")
    p.add_argument("--parts", metavar="RESULT.json",
                   help="verify a given design instead of selecting one: the JSON of 'synth design --json' "
                        "(its 'parts') or of 'synth flowchart --json'")
    add_model_options(p)
    p.set_defaults(func=_main)


def parts_from_json(path: str) -> dict:
    """The part choices saved in a ``synth design --json`` or ``synth flowchart --json`` file.

    Read through the input gate (:func:`synth.io.results.load_result`: size,
    encoding, shape, carried inputs); a problem names ``--parts`` and the file.
    """
    from pathlib import Path

    from synth.io.results import load_result, parts_of
    return parts_of(load_result(path, "--parts"), Path(path).name, "--parts")


def render_text(r: flowchart.FlowchartResult) -> str:
    """Output table (Tables 10/14 shape), then every check with verdict, margin and correction."""
    lines = ["Output (thesis Tables 10/14)", "-" * 78]
    section = None
    for sec, label, key, unit in ROWS:
        if key not in r.values:
            continue
        if sec != section:
            lines.append(f"{sec}")
            section = sec
        lines.append(f"  {label:<40} [{unit:>4}]  {format_value(r.values[key])}")
    lines += ["", "Checks", "-" * 78]
    for c in r.checks:
        mark = {"pass": "PASS", "fail": "FAIL", "not verified": "N/V "}[c.verdict]
        if c.verdict == NOT_VERIFIED:
            lines.append(f"  [{mark}] step {c.step:>2} {c.name}: {c.note}")
            continue
        rel = "<=" if c.kind == "<=" else ">="
        lines.append(f"  [{mark}] step {c.step:>2} {c.name}: {c.value:.4g} {rel} {c.limit:.4g} {c.unit}"
                     f"  margin {100 * c.margin:+.1f} %  ({c.equation})")
        if c.verdict == FAIL and c.correction:
            lines.append(f"           suggested correction: {c.correction}")
    if r.notes:
        lines += ["", "Notes", "-" * 78] + [f"  - {n}" for n in r.notes]
    failed = r.failed()
    lines += ["", f"Verdict: {r.verdict.upper()}" + (f" ({len(failed)} check(s) failed)" if failed else "")
              + (f"; {len(r.not_verified())} not verified" if r.not_verified() else "")]
    return "\n".join(lines)


def _main(args) -> int:
    d = schema.load_input(args.input)
    r = flowchart.run(d, settings_from_args(args), parts=parts_from_json(args.parts) if args.parts else None)
    if args.json:
        import dataclasses
        out = r.to_dict()
        out["inputs"] = dataclasses.asdict(d)  # the saved JSON is self-contained (synth cad RESULT.json reads it)
        print(json.dumps(out, indent=2, default=str))
    else:
        print(render_text(r))
    return 0 if r.verdict != FAIL else 1
