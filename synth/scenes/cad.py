"""``synth cad RESULT.json --out DIR``: the simplified 3D model of a saved result (thesis step 11).

Accepts the ``--json`` of any scene (it carries its ``inputs``); a result
without inputs needs ``--input`` with the design input. Writes the STEP assembly, one STL per part, the
exploded and section pictures and ``cad_report.json``; prints the geometric
checks. Exit code 1 if a geometric check fails, else 0.
"""

from __future__ import annotations

from synth.design.result import FAIL
from synth.cad import export_result, summary_lines
from pathlib import Path

from synth.errors import InputError, Problem
from synth.io.saved_results import INPUTS_ACCEPTED, load_result

__all__ = ["register", "add_cad_options"]


def add_cad_options(p) -> None:
    p.add_argument("--no-stl", action="store_true", help="skip the STL files")
    p.add_argument("--no-pictures", action="store_true", help="skip the exploded and section pictures")


def register(sub) -> None:
    p = sub.add_parser("cad", help="export the 3D model (STEP, STL, pictures) of a saved design/flowchart result")
    p.add_argument("result", help="JSON of synth design --json or synth flowchart --json")
    p.add_argument("--out", required=True, metavar="DIR", help="folder for the STEP assembly, one STL per part, the pictures and cad_report.json")
    p.add_argument("--input", default=None, help="design input (needed for a flowchart JSON, which lacks it)")
    add_cad_options(p)
    p.set_defaults(func=_main)


def _main(args) -> int:
    result = load_result(args.result, "result")  # the gate: size, encoding, shape, carried inputs
    if args.input is None and result.get("inputs") is None:
        raise InputError(Problem(f"inputs ({Path(args.result).name})", None,
                                 INPUTS_ACCEPTED + "; or pass --input INPUT.yaml, the input it was made from"))
    model, checks, info = export_result(result, args.out, args.input,
                                        stl=not args.no_stl, pictures=not args.no_pictures)
    print(f"synth cad: {args.result} -> {args.out}")
    print("\n".join(summary_lines(model, checks, info)))
    failed = [c.label for c in checks if c.verdict == FAIL]
    own = str(result.get("verdict") or "") if isinstance(result, dict) else ""
    also = f"; the design's own verdict, of its saved result: {own.upper()}" if own and own != "pass" else ""
    print("\nVerdict: " + (f"FAIL (geometric checks failed: {'; '.join(failed)}{also})" if failed
                           else f"PASS (every geometric check of the 3D model passes{also})"))
    return 1 if failed else 0
