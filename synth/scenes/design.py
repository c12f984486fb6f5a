"""``synth design INPUT``: the optimal catalog design, with a table of what binds.

Infeasible inputs get the nearest design, the constraints it violates by how
much, and the smallest input relaxations that would make it feasible.
"""

from __future__ import annotations

import json

from synth.optimise import SOLVERS, solve
from synth.schema import load_input

__all__ = ["register"]


def register(sub) -> None:
    p = sub.add_parser("design", help="optimal tensioner from the catalogs (standardisation, cost or margin)")
    p.add_argument("input", help="design-input YAML (a case file works)")
    p.add_argument("--objective", default="standard",
                   help="standard | cost | margin, a lexicographic list 'a,b' or weights 'cost=1,margin=5'")
    p.add_argument("--solver", default="enumerate", choices=list(SOLVERS))
    p.add_argument("--fidelity", default=None, choices=("screening", "full"),
                   help="cone-spring and plastic-wear model (default: screening; blackbox: full)")
    p.add_argument("--pin-inputs", action="store_true", help="keep the part choices the input names")
    p.add_argument("--trials", type=int, default=200, help="blackbox: number of trials")
    p.add_argument("--json", action="store_true")
    p.add_argument("--cad", metavar="DIR", default=None,
                   help="also export the 3D model of the design (STEP, STL, pictures, geometric checks) into DIR")
    p.set_defaults(func=_main)


def _main(args) -> int:
    d = load_input(args.input)
    kw = {"pin_inputs": args.pin_inputs} if args.solver not in ("blackbox", "flowchart") else {}
    if args.fidelity:
        kw["fidelity"] = args.fidelity
    if args.solver == "blackbox":
        kw["n_trials"] = args.trials
    r = solve(d, args.objective, args.solver, **kw)
    if args.json:
        print(json.dumps(r.to_dict(), indent=2, default=str))
        if args.cad:
            import sys
            print("\n".join(_export_cad(r, d, args.cad)), file=sys.stderr)
        return 0
    print(f"synth design: {args.input} | objective {r.objective} | solver {r.solver} | status {r.status}\n")
    print("parts:")
    for k, v in r.parts.items():
        print(f"  {k:<22} {v}")
    print("\nobjectives: " + ", ".join(f"{k} {v:.4g}" for k, v in r.objectives.items()))
    print("\nwhat binds (smallest margins):\n")
    print(r.binding_table())
    if r.diagnosis:
        print("\n" + r.diagnosis["message"])
        for v in r.diagnosis["violated"]:
            name = v["constraint"] if isinstance(v, dict) else v
            m = v["margin"] if isinstance(v, dict) else r.margins[v]
            print(f"  violated: {name} by {-m:.1%}")
        for rel in r.diagnosis.get("relaxations", []):
            ch = ", ".join(f"{k} {x['from']:g} -> {x['to']:g}" for k, x in rel["inputs"].items())
            print(f"  feasible with: {ch}")
        if not r.diagnosis.get("relaxations"):
            print("  no input relaxation within the searched ranges makes it feasible (see the violated constraints)")
    stats = {k: v for k, v in r.stats.items() if isinstance(v, (int, float))}
    print("\nsolver: " + ", ".join(f"{k} {v:.4g}" for k, v in stats.items()))
    if args.cad:
        print("\n" + "\n".join(_export_cad(r, d, args.cad)))
    return 0 if r.status != "infeasible" else 1


def _export_cad(r, d, out_dir) -> list[str]:
    """Export the design's 3D model (thesis step 11) and return the summary lines."""
    from synth.cad import export_result, summary_lines
    model, checks, info = export_result(r, out_dir, d)
    return [f"3D model written to {out_dir}"] + summary_lines(model, checks, info)
