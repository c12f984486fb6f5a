"""``synth rationalise PORTFOLIO --out DIR``: the fewest standard parts that serve a whole portfolio.

Chooses a platform (a set of parts per family) and gives every application one design
built only from platform parts, feasible for it, minimising the weighted number of
distinct parts (``--objective variants``) or the total cost (``cost``: unit cost x volume
plus a per-variant fixed cost). Writes ``platform.csv``, ``assignment.csv``,
``summary.md`` and the trade-off curve (``tradeoff.csv``, ``tradeoff.png``).
See :mod:`synth.platform.rationalise`.

``PORTFOLIO`` is a portfolio table (the one ``synth bulk`` reads; an optional
``annual_volume`` column weighs the cost objective): its feasibility comes from the
evaluator (:mod:`synth.platform.portfolio_feasibility`, ``--fidelity``, ``--engine dask`` for the
chunks); ``synthetic:N[:SEED]`` gives illustrative data of the same shape.
"""

from __future__ import annotations

from pathlib import Path

from formulations.platform import NODE_LIMIT, TIME_LIMIT_S
from synth.errors import InputError, Problem
from synth.io.limits import check_count
from synth.io.outputs import output_files
from synth.platform.data import FAMILIES
from synth.progress import Progress, phase
from synth.robust.settings import BULK_SAMPLES
from synth.scenes._options import add_robust_options, add_rules_options, robust_settings_from_args, rules_of

__all__ = ["register", "parse_max_variants"]


def parse_max_variants(items: list) -> dict:
    """``["ball_bearing=3", ...]`` -> ``{"ball_bearing": 3}``; bad items name themselves.

    >>> parse_max_variants(["ball_bearing=3", "main_spring=12"])
    {'ball_bearing': 3, 'main_spring': 12}
    """
    out, probs = {}, []
    for it in items or []:
        fam, _, n = str(it).partition("=")
        if fam not in FAMILIES:
            probs.append(Problem("--max-variants", it, f"FAMILY=N with FAMILY one of {', '.join(FAMILIES)}"))
            continue
        try:
            out[fam] = int(n)
            if out[fam] < 1:
                raise ValueError
        except ValueError:
            probs.append(Problem("--max-variants", it, "FAMILY=N with N a whole number >= 1"))
    if probs:
        raise InputError(probs)
    return out


def register(sub) -> None:
    p = sub.add_parser("rationalise", help="the fewest standard parts that serve a whole portfolio (platform rationalisation)")
    p.add_argument("portfolio", metavar="PORTFOLIO",
                   help="portfolio table, or synthetic:N[:SEED] for synthetic feasibility data")
    p.add_argument("--out", required=True, metavar="DIR", help="folder for platform.csv, assignment.csv, summary.md")
    p.add_argument("--objective", default="variants", choices=["variants", "cost"],
                   help="variants: the fewest distinct parts, weighted per family (default); cost: unit cost times "
                        "annual volume plus a fixed cost per variant")
    p.add_argument("--max-variants", nargs="*", default=[], metavar="FAMILY=N",
                   help="cap the variants of families: FAMILY=N, several after one option (FAMILY one of "
                        + ", ".join(FAMILIES) + ")")
    p.add_argument("--node-limit", type=int, default=NODE_LIMIT, metavar="N",
                   help=f"branch-and-bound nodes per MILP solve (default {NODE_LIMIT:,}): the limit that gives the same "
                        "platform for the same input on any machine and load; where it binds, the best platform found "
                        "in N nodes, and the output says so")
    p.add_argument("--time-limit", type=float, default=TIME_LIMIT_S, metavar="S",
                   help=f"wall-clock seconds per MILP solve (default {TIME_LIMIT_S:g}), a safety net: where it binds, "
                        "the best platform found, which depends on the machine and its load (the output says \"stopped "
                        "at the time limit: not reproducible\")")
    p.add_argument("--solver", default="highs", choices=["highs", "scip"],
                   help="MILP solver: highs (default, built from arrays for highspy) or scip (through the Pyomo "
                        "reference model)")
    p.add_argument("--tradeoff", default="margin", choices=["margin", "cost", "none"],
                   help="trade-off curve written to tradeoff.csv and .png: platform size against the worst margin "
                        "(default), against the total cost, or none")
    p.add_argument("--points", type=int, default=5, metavar="N",
                   help="points of the trade-off curve, 2 to 50 (default 5; each is one MILP solve)")
    p.add_argument("--fidelity", default="full", choices=["full", "screening", "screening-only"],
                   help="model fidelity of the feasibility data (full: the design scenes' default; screening: the "
                        "options the closed forms pass, judged at full fidelity; screening-only: unverified)")
    p.add_argument("--engine", default="inprocess", choices=["inprocess", "dask"],
                   help="evaluate the chunks of applications in this process or on Dask")
    p.add_argument("--workers", type=int, default=None, metavar="N",
                   help="with --engine dask and no --scheduler: the local cluster's worker processes, one thread "
                        "each, at most the usable cores (default 2)")
    p.add_argument("--scheduler", metavar="ADDRESS",
                   help="with --engine dask: the address of a running Dask scheduler (default: a local cluster)")
    add_rules_options(p, "every application's options are judged by them; their capability targets, like "
                         "--capability, keep only assigned designs that meet them")
    add_robust_options(p)
    for a in p._actions:  # the bulk's sample count (per assigned design)
        if a.dest == "samples":
            a.help = (f"Monte Carlo samples per assigned design with --capability/--ppm (default {BULK_SAMPLES}, as "
                      "synth bulk; synth design --capability --samples N gives the same Ppk)")
        if a.dest == "capability":
            a.help += ("; every design the platform assigns is checked and those that miss it are excluded and the "
                       "platform chosen again (synth.platform.capable)")
    p.add_argument("--diagnose", action="store_true",
                   help="applications with no feasible design: the nearest design of synth.optimise.diagnose "
                        "(about 1 s each) instead of the nearest evaluated one")
    p.set_defaults(func=_main, samples=BULK_SAMPLES)


def _main(args) -> int:
    from synth.platform.outputs import gap_text, solve_text, write_all
    from synth.platform.volume import saving_text
    from synth.platform.portfolio_feasibility import load_feasibility
    from synth.platform.rationalise import rationalise, tradeoff
    caps = parse_max_variants(args.max_variants)
    check_count("rationalise --points", args.points)
    from synth.design.evaluate import Settings
    from synth.bulk.run import usable_cores
    if args.workers is not None:  # a local cluster: no more worker processes than cores
        check_count("--workers", args.workers, hi=None if args.scheduler else max(1, usable_cores()))
    if not 0 < args.time_limit <= 86_400:
        raise InputError(Problem("--time-limit", args.time_limit, "seconds in (0, 86400] per MILP solve"))
    check_count("rationalise --node-limit", args.node_limit)
    engine = "dask" if args.scheduler else args.engine
    # the design rules; load_feasibility refuses those the platform cannot honour
    rs = robust_settings_from_args(args, samples="bulk --samples")  # --capability/--ppm, else the rules' targets
    targeted = rs.capability is not None or rs.ppm is not None
    settings = Settings(fidelity=args.fidelity, rules=rules_of(args), spring_limit_basis=args.spring_limit,
                        capability=rs if targeted else None)
    for line in settings.rules.lines():  # the rules every option was judged by (also in summary.md)
        print(line)
    with Progress(total=None, desc="synth rationalise: feasibility") as bar:
        bar.update(0, "running")
        pf = load_feasibility(args.portfolio, settings, engine=engine, workers=args.workers,
                              scheduler=args.scheduler, diagnose=args.diagnose,
                              progress=lambda done, total: bar.update(done - bar.n))
    import sys
    for note in pf.notes:
        if note.startswith("--engine dask"):
            print(f"synth rationalise: note: {note}", file=sys.stderr)
    label = f"{args.solver} MILP"

    def stage(name):   # a progress line per stage of the platform (synth.platform.rationalise.STAGES)
        return phase(f"synth rationalise: platform, {label if name == 'MILP' else name} ({len(pf.apps)} applications)")

    def run(data):
        return rationalise(data, args.objective, max_variants=caps, time_limit=args.time_limit,
                           node_limit=args.node_limit, solver=args.solver, stage=stage)
    from synth.platform.capable import choose
    r, pf = choose(pf, run, settings)  # with a target: the designs that miss it excluded, chosen again
    rows = None
    if args.tradeoff != "none":
        with Progress(total=args.points, desc=f"synth rationalise: trade-off curve ({args.tradeoff})") as bar:
            rows = tradeoff(pf, args.tradeoff, points=args.points, time_limit=args.time_limit,
                            node_limit=args.node_limit, progress=lambda done, total: bar.update(done - bar.n))
    r.tradeoff = rows
    with output_files(args.out, "--out") as out, phase("synth rationalise: writing the outputs"):
        paths = [Path(args.out) / q.relative_to(out) for q in write_all(pf, r, out, rows, args.tradeoff)]
    p = r.price
    print(f"synth rationalise: {p['applications_served']} of {len(r.records)} applications served by "
          f"{r.n_parts} distinct parts (union of per-application optima: {p['parts_union_of_optima']}); "
          f"{saving_text(p['volume'])}; "
          f"unit cost {p['unit_cost_increase']:+.2%} against the per-application optima; MILP {solve_text(r)}; "
          f"greedy {gap_text(r.greedy_gap)}")
    if r.capability_line:
        print(r.capability_line)
    print("written: " + ", ".join(str(x) for x in paths))
    ok = r.status in ("optimal", "node_limit", "time_limit", "greedy")
    print(f"Run: {'COMPLETE' if ok else 'FAILED'} (MILP {r.status}; {p['applications_served']} of {len(r.records)} "
          f"applications served; each application's verified verdict is in {Path(args.out) / 'assignment.csv'})")
    return 0 if ok else 1
