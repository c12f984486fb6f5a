"""``synth pareto INPUT --out DIR``: the cost-against-margin front, as a table and a plot."""

from __future__ import annotations

import json
from pathlib import Path

from synth.optimise.pareto import pareto_front, plot_front
from synth.schema import load_input

__all__ = ["register"]


def register(sub) -> None:
    p = sub.add_parser("pareto", help="cost against margin: the Pareto front of the catalog designs")
    p.add_argument("input", help="design-input YAML")
    p.add_argument("--out", default="pareto_out", help="folder for front.md, front.json and front.png")
    p.add_argument("--points", type=int, default=40, help="margin thresholds probed")
    p.set_defaults(func=_main)


def _main(args) -> int:
    from synth.errors import InputError, Problem
    if not 1 <= args.points <= 10_000:
        raise InputError(Problem("--points", args.points, "an integer from 1 to 10000"))
    front = pareto_front(load_input(args.input), n_points=args.points)
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    lines = ["| cost [EUR] | margin | non-standard | binding constraint |", "|---|---|---|---|"]
    lines += [f"| {p['cost_eur']:.4f} | {p['margin']:+.4f} | {p['standard']:g} | {p['binding']} |" for p in front]
    inputs = front[0]["inputs"] if front else {}
    if inputs:
        lines += ["", "Input-only constraints (no design changes them; not in the margin above):"]
        from synth.design.constraints import REGISTRY
        lines += [f"- {REGISTRY[k].label}: margin {v:+.4f}" for k, v in inputs.items()]
    table = "\n".join(lines)
    (out / "front.md").write_text(table + "\n")
    (out / "front.json").write_text(json.dumps(front, indent=2, default=str))
    if front:
        plot_front(front, out / "front.png")
    print(table if front else "no feasible design: no front (run synth design for the diagnosis)")
    print(f"\nwritten: {out / 'front.md'}, {out / 'front.json'}" + (f", {out / 'front.png'}" if front else ""))
    return 0 if front else 1
