"""``synth pareto INPUT --out DIR``: the cost-against-margin front, as a table and a plot."""

from __future__ import annotations


from synth.optimise.pareto import pareto_front, plot_front
from synth.io.documents import load_input
from synth.scenes._options import add_robust_options, robust_settings_from_args
from synth.io.limits import check_count
from synth.io.outputs import json_text, output_files, write_text
from synth.scenes.report import out_folder
from synth.design.constraints import words, REGISTRY
from synth.robust.synthesis import robust_front
from synth.cost.decision import band_of
from synth.cost.book import volume_of

__all__ = ["register"]


def register(sub) -> None:
    p = sub.add_parser("pareto", help="cost against margin: the Pareto front of the catalog designs")
    p.add_argument("input", help="design-input YAML")
    p.add_argument("--out", default="pareto_out", help="folder for front.md, front.json and front.png")
    p.add_argument("--points", default=40, metavar="N",
                   help="margin thresholds probed, 2-500 (each is one catalog solve; default 40)")
    add_robust_options(p)
    p.set_defaults(func=_main)


def _main(args) -> int:
    points = check_count("--points", args.points)
    out = out_folder(args.out)  # checked before the work: an existing file is not a folder
    if args.capability is not None or args.ppm is not None:
        return _robust_front(args, out, min(points, 12))
    d = load_input(args.input)
    front = pareto_front(d, n_points=points)
    for p in front:  # the cost axis with its band: the 5 % and 95 % quantiles under the price bands
        p["cost_band_eur"] = band_of(d, p["parts"])
    lines = [f"Cost at {volume_of(d):,.0f} a year, its 90 % band under the price bands (synth.cost.decision)", "",
             "| cost [EUR] | 90 % band [EUR] | smallest margin [%] | non-standard parts | binding constraint |",
             "|---|---|---|---|---|"]
    lines += [f"| {p['cost_eur']:.4f} | {p['cost_band_eur'][0]:.4f}-{p['cost_band_eur'][1]:.4f} | "
              f"{100 * p['margin']:+.2f} | {p['standard']:g} | {words(p['binding'])} |" for p in front]
    inputs = front[0]["inputs"] if front else {}
    if inputs:
        lines += ["", "Input-only constraints (no design changes them; not in the margin above):"]
        lines += [f"- {REGISTRY[k].label}: margin {100 * v:+.2f} %" for k, v in inputs.items()]
    table = "\n".join(lines)
    with output_files(out, "--out") as stage:  # one output: every file, or none
        write_text(stage / "front.md", table + "\n")
        write_text(stage / "front.json", json_text(front, indent=2, digits=6))  # margins as fractions
        if front:
            plot_front(front, stage / "front.png")
    print(table if front else "no feasible design: no front (run synth design for the diagnosis)")
    print(f"\nwritten: {out / 'front.md'}, {out / 'front.json'}" + (f", {out / 'front.png'}" if front else ""))
    return 0 if front else 1


def _robust_front(args, out, points: int) -> int:
    """``--capability``/``--ppm``: cost against capability (Ppk and ppm), from the target up (one robust search per
    point: synth.robust.synthesis.robust_front)."""
    rs = robust_settings_from_args(args)
    front = robust_front(load_input(args.input), rs=rs, n_points=points)
    lines = [f"Cost against capability ({rs.targets()} and better; {rs.samples} samples per design)", "",
             "| cost [EUR] | smallest Ppk | largest P(violation) [ppm] | binding check |", "|---|---|---|---|"]
    lines += [f"| {p['cost_eur']:.4f} | {p['ppk']:.3g} | {p['ppm']:.3g} | {words(p['binding'])} |" for p in front]
    table = "\n".join(lines)
    with output_files(out, "--out") as stage:  # one output: every file, or none
        write_text(stage / "front.md", table + "\n")
        write_text(stage / "front.json", json_text(front, indent=2))
        if front:
            plot_front(front, stage / "front.png", y="ppk", ylabel="smallest Ppk of the checked constraints [-]",
                       title="cost against production capability",
                       label=lambda p: f"{words(p['binding'], 36)} ({p['ppm']:.2g} ppm)")
    print(table if front else f"no catalog design meets {rs.targets()} (synth design --capability says why)")
    print(f"\nwritten: {out / 'front.md'}, {out / 'front.json'}" + (f", {out / 'front.png'}" if front else ""))
    return 0 if front else 1
