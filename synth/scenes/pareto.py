"""``synth pareto INPUT --out DIR``: the cost-against-margin front, as a table and a plot.

Every point of the front is a catalog design, verified through the evaluator: the table and the plot say which
design each point is and what binds it. The verdict (the last line and the exit code) is the front's designs':
``PASS`` when every one passes its checks (and, with a capability target, meets it), ``INCOMPLETE`` when they rest on
a documented default of an input not given or on checks not verified, ``FAIL`` when no design is feasible.
"""

from __future__ import annotations

from synth import formatting as fmt
from synth.optimise.pareto import pareto_front
from synth.io.documents import load_input
from synth.scenes._options import add_robust_options, robust_settings_from_args
from synth.io.limits import check_count
from synth.io.outputs import json_text, output_files, write_text
from synth.scenes.report import out_folder
from synth.design.constraints import words, REGISTRY
from synth.robust.synthesis import robust_front
from synth.cost.decision import band_of
from synth.cost.book import volume_of

__all__ = ["register", "front_verdict"]


def register(sub) -> None:
    p = sub.add_parser("pareto", help="cost against margin: the Pareto front of the catalog designs")
    p.add_argument("input", help="design input (.yaml, .toml, .json, .xlsx; a case file works)")
    p.add_argument("--out", default="pareto_out", help="folder for front.md, front.json and front.png")
    p.add_argument("--points", default=40, metavar="N",
                   help="margin thresholds probed, 2-500 (each is one catalog solve; default 40)")
    add_robust_options(p)
    p.set_defaults(func=_main)


def front_verdict(d, front: list, none_text: str) -> tuple[str, int]:
    """``(last line, exit code)`` of a front: the verdicts of its designs (each verified through the evaluator: the
    worst of them decides, :mod:`synth.design.verdict`), FAIL with ``none_text`` for an empty front."""
    if not front:
        return f"Verdict: FAIL ({none_text})", 1
    from synth.design.verify import verify
    from synth.design.verdict import Verdict
    verdicts = [verify(d, p["parts"]).judgement for p in front]
    worst = max(verdicts, key=lambda v: (v.exit_code == 1, v.exit_code == 3))
    n = len(front)
    head = f"{n} design{'s' if n > 1 else ''} on the front"
    if worst.state == "pass":
        return f"Verdict: PASS ({head}, each passing every check)", 0
    summary = Verdict(worst.state, worst.reasons).summary()
    return f"Verdict: {worst.state.upper()} ({head}; {summary})", worst.exit_code


def _main(args) -> int:
    points = check_count("--points", args.points)
    out = out_folder(args.out)  # checked before the work: an existing file is not a folder
    d = load_input(args.input)
    if args.capability is not None or args.ppm is not None:
        return _robust_front(args, d, out, min(points, 12))
    front = pareto_front(d, n_points=points)
    for p in front:  # the cost axis with its band: the 5 % and 95 % quantiles under the price bands
        p["cost_band_eur"] = band_of(d, p["parts"])
    lines = [f"Cost at {volume_of(d):,.0f} a year, its 90 % band under the price bands (synth.cost.decision)", "",
             "| point | cost [EUR] | 90 % band [EUR] | smallest margin | non-standard parts | what binds | design |",
             "|---|---|---|---|---|---|---|"]
    lines += [f"| {i} | {fmt.number(p['cost_eur'])} | {fmt.number(p['cost_band_eur'][0])}-"
              f"{fmt.number(p['cost_band_eur'][1])} | {fmt.percent(p['margin'])} | {fmt.number(p['standard'])} | "
              f"{words(p['binding'])} | {fmt.design_label(p['parts'])} |" for i, p in enumerate(front, start=1)]
    inputs = front[0]["inputs"] if front else {}
    if inputs:
        lines += ["", "Input-only constraints (no design changes them; not in the margin above):"]
        lines += [f"- {REGISTRY[k].label}: margin {fmt.percent(v)}" for k, v in inputs.items()]
    table = "\n".join(lines)
    with output_files(out, "--out") as stage:  # one output: every file, or none
        write_text(stage / "front.md", table + "\n")
        write_text(stage / "front.json", json_text(front, indent=2, digits=6))  # margins as fractions
        if front:
            from synth.report.plots import pareto_figure
            pareto_figure(front, stage / "front.png")
    print(table if front else "no feasible design: no front (run synth design for the diagnosis)")
    print(f"\nwritten: {out / 'front.md'}, {out / 'front.json'}" + (f", {out / 'front.png'}" if front else ""))
    line, code = front_verdict(d, front, "no feasible design: synth design INPUT diagnoses it")
    print("\n" + line)
    return code


def _robust_front(args, d, out, points: int) -> int:
    """``--capability``/``--ppm``: cost against capability (Ppk and ppm), from the target up (one robust search per
    point: synth.robust.synthesis.robust_front)."""
    rs = robust_settings_from_args(args)
    front = robust_front(d, rs=rs, n_points=points)
    lines = [f"Cost against capability ({rs.targets()} and better; {rs.samples} samples per design)", "",
             "| point | cost [EUR] | smallest Ppk | largest P(violation) | lowest Ppk of | design |",
             "|---|---|---|---|---|---|"]
    lines += [f"| {i} | {fmt.number(p['cost_eur'])} | {fmt.number(p['ppk'], 3)} | "
              f"{fmt.probability(p['ppm'] * 1e-6)} | {words(p['binding'])} | {fmt.design_label(p['parts'])} |"
              for i, p in enumerate(front, start=1)]
    table = "\n".join(lines)
    with output_files(out, "--out") as stage:  # one output: every file, or none
        write_text(stage / "front.md", table + "\n")
        write_text(stage / "front.json", json_text(front, indent=2))
        if front:
            from synth.report.plots import pareto_figure
            pareto_figure(front, stage / "front.png", y="ppk", ylabel="smallest Ppk of the checked constraints [-]",
                          title="cost against production capability",
                          note=lambda p: f"lowest: {words(p['binding'])}, up to {fmt.probability(p['ppm'] * 1e-6)}")
    print(table if front else f"no catalog design meets {rs.targets()} (synth design --capability says why)")
    print(f"\nwritten: {out / 'front.md'}, {out / 'front.json'}" + (f", {out / 'front.png'}" if front else ""))
    line, code = front_verdict(d, front, f"no catalog design meets {rs.targets()}: synth design --capability says "
                                         "why")
    print("\n" + line)
    return code
