"""``synth pareto INPUT --out DIR``: the cost-against-margin front, as a table and a plot."""

from __future__ import annotations

import json

from synth.optimise.pareto import pareto_front, plot_front
from synth.schema import load_input

__all__ = ["register"]


def register(sub) -> None:
    p = sub.add_parser("pareto", help="cost against margin: the Pareto front of the catalog designs")
    p.add_argument("input", help="design-input YAML")
    p.add_argument("--out", default="pareto_out", help="folder for front.md, front.json and front.png")
    p.add_argument("--points", default=40, metavar="N",
                   help="margin thresholds probed, 2-500 (each is one catalog solve; default 40)")
    p.set_defaults(func=_main)


def _main(args) -> int:
    from synth.io.limits import check_count
    from synth.scenes.report import out_folder
    points = check_count("--points", args.points)
    out = out_folder(args.out)  # checked before the work: an existing file is not a folder
    front = pareto_front(load_input(args.input), n_points=points)
    out.mkdir(parents=True, exist_ok=True)
    from synth.design.constraints import words
    from synth.design.result import plain
    lines = ["| cost [EUR] | smallest margin [%] | non-standard parts | binding constraint |", "|---|---|---|---|"]
    lines += [f"| {p['cost_eur']:.4f} | {100 * p['margin']:+.2f} | {p['standard']:g} | {words(p['binding'])} |"
              for p in front]
    inputs = front[0]["inputs"] if front else {}
    if inputs:
        lines += ["", "Input-only constraints (no design changes them; not in the margin above):"]
        from synth.design.constraints import REGISTRY
        lines += [f"- {REGISTRY[k].label}: margin {100 * v:+.2f} %" for k, v in inputs.items()]
    table = "\n".join(lines)
    (out / "front.md").write_text(table + "\n")
    (out / "front.json").write_text(json.dumps(plain(front, 6), indent=2, default=str))  # margins as fractions
    if front:
        plot_front(front, out / "front.png")
    print(table if front else "no feasible design: no front (run synth design for the diagnosis)")
    print(f"\nwritten: {out / 'front.md'}, {out / 'front.json'}" + (f", {out / 'front.png'}" if front else ""))
    return 0 if front else 1
