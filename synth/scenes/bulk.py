"""``synth bulk PORTFOLIO --out RESULT``: feasibility of a whole portfolio of applications.

A portfolio is a CSV, Excel or Parquet table with one application per row and
the design-input fields as columns (``synth portfolio-sample`` writes one).
The result is the same table with, per application, the verdict, the best
catalog design under ``--objective``, its margins, the binding constraint, the
violated constraints and the smallest input relaxation of infeasible ones,
and an ``error`` column for rows with bad data (the other rows still run).

Chunks are saved as they finish in ``RESULT.chunks/``; ``--resume`` continues
an interrupted run without recomputing them. A run holds a lock on that
folder (a second run on the same ``--out`` is refused while the first runs),
every chunk carries its run id and a checksum, and ``--resume`` refuses,
naming them, chunks of another run or with a bad checksum. Exit code 0 when
the run completed (even with infeasible or broken rows: the last line, ``Run: COMPLETE (...)``, counts each row
verdict; a row's ``verdict`` is its one verdict, a capability target missed included), 2 for a bad command
line, an unreadable portfolio or a refused folder, 130 when interrupted, 143 when terminated (SIGTERM).
"""

from __future__ import annotations

import sys

from synth.bulk.run import ENGINES, FIDELITIES, run_portfolio, sidecar, usable_cores
from synth.errors import InputError, Terminated
from synth.io.outputs import output_files
from synth.io.limits import check_count
from synth.robust.settings import BULK_SAMPLES
from synth.scenes._options import add_robust_options, add_rules_options, robust_settings_from_args, rules_of
from synth.bulk.summary import summarise, text, write_summary
from synth.design.evaluate import Settings

__all__ = ["register"]


def _count(option: str):
    """An argparse type: an integer within the documented bounds of ``option`` (:data:`synth.io.limits.COUNTS`)."""
    import argparse


    def parse(text: str) -> int:
        try:
            return check_count(option, text)
        except InputError as exc:
            raise argparse.ArgumentTypeError(exc.problems[0].accepted) from None
    parse.__name__ = option.lstrip("-").replace("-", "_")
    return parse


def register(sub) -> None:
    p = sub.add_parser("bulk", help="feasibility of a portfolio of applications (CSV, Excel or Parquet table)")
    p.add_argument("portfolio", help="portfolio table (.csv, .xlsx, .ods, .parquet): one application per row, "
                                     "design-input fields as columns")
    p.add_argument("--out", required=True, metavar="RESULT",
                   help="result table (.csv, .xlsx, .ods or .parquet); chunks are kept in RESULT.chunks/")
    p.add_argument("--objective", default="standard",
                   help="standard | cost | margin, a lexicographic list 'a,b' or weights 'cost=1,margin=5'")
    p.add_argument("--fidelity", default="screening", choices=FIDELITIES,
                   help="screening (default): designs searched with the closed-form models, every reported design "
                        "verified at full fidelity; full: the full model throughout; screening-only: closed forms, "
                        "unverified (every row says so)")
    p.add_argument("--chunk-size", type=_count("--chunk-size"), default=None, metavar="N",
                   help="applications per chunk, 1-10000 (default: the engine's memory budget over its memory per "
                        "application, catalogs/constants_bulk.csv)")
    p.add_argument("--resume", action="store_true", help="continue an interrupted run, reusing its finished chunks")
    p.add_argument("--engine", default="inprocess", choices=ENGINES, help="run the chunks in this process or on Dask")
    p.add_argument("--scheduler", metavar="ADDRESS", help="Dask scheduler address (default: a local cluster)")
    p.add_argument("--workers", type=_count("--workers"), default=None, metavar="N",
                   help="local Dask cluster: worker processes, 1-64 (default 2)")
    p.add_argument("--summary", metavar="DIR", help="write the portfolio summary (markdown, CSV, PNG plots) into DIR")
    p.add_argument("--no-diagnose", action="store_true", help="skip the relaxation search of infeasible applications")
    add_rules_options(p, "every application is judged by them")
    add_robust_options(p)
    for a in p._actions:  # the bulk's own sample count (per application)
        if a.dest == "samples":
            a.help = (f"Monte Carlo samples per candidate design with --capability/--ppm (default {BULK_SAMPLES}; "
                      "synth design --capability --samples N gives the same row)")
    p.set_defaults(func=_main, samples=BULK_SAMPLES)


def _main(args) -> int:
    if args.scheduler and args.engine != "dask":
        args.engine = "dask"
    rs = robust_settings_from_args(args, samples="bulk --samples")  # --capability/--ppm, else the rules' targets
    if args.workers is not None and not args.scheduler:  # a local cluster: no more worker processes than cores
        check_count("--workers", args.workers, hi=max(1, usable_cores()))
    targeted = rs.capability is not None or rs.ppm is not None
    # the run's one configuration: each row re-selected for the capability target when one is set
    settings = Settings(fidelity=args.fidelity, rules=rules_of(args), spring_limit_basis=args.spring_limit,
                        capability=rs if targeted else None)
    try:
        rep = run_portfolio(args.portfolio, args.out, objective=args.objective, fidelity=args.fidelity,
                            chunk_size=args.chunk_size, resume=args.resume, engine=args.engine,
                            scheduler=args.scheduler, workers=args.workers, diagnose=not args.no_diagnose,
                            settings=settings)
    except KeyboardInterrupt as exc:
        how = "terminated (SIGTERM)" if isinstance(exc, Terminated) else "interrupted"
        print(f"\nsynth bulk: {how}; finished chunks are kept in {sidecar(args.out)}; "
              "rerun the same command with --resume to continue", file=sys.stderr)
        return 143 if isinstance(exc, Terminated) else 130
    for w in rep.warnings:
        print(f"synth bulk: note: {w}", file=sys.stderr)
    said = {"screening": " (every design reported verified at full fidelity)",
            "screening-only": " (designs NOT verified at full fidelity)"}.get(args.fidelity, "")
    print(f"synth bulk: {args.portfolio} -> {rep.out} | objective {args.objective} | fidelity {args.fidelity}{said}")
    for line in settings.rules.lines():  # the rules every row was judged by (also in the sidecar's manifest)
        print(line)
    if targeted:
        print(_capability_line(rep, rs))
    print(rep.message() + (f", {rep.apps_per_s:.3g} applications/s" if rep.computed else ""))
    from synth.bulk.summary import COLUMNS
    s = summarise(rep.columns(COLUMNS))  # the columns the summary reads, not the whole table
    print(text(s))
    if args.summary:
        with output_files(args.summary, "--summary") as stage:  # one output: every file, or none
            paths = write_summary(s, stage, rules=settings.rules)
        print(f"summary: {len(paths)} files in {args.summary}")
    print(run_line(rep))
    return 0


def run_line(rep, table=None) -> str:
    """The last line of ``synth bulk``: the run completed (exit 0, whatever the rows' verdicts), with the count of
    each row verdict (the result's ``verdict`` column: the one verdict of each application, its capability target
    included)."""
    t = table if table is not None else rep.columns(["verdict", "status"])
    parts = []
    if t is not None and "verdict" in t.columns and "status" in t.columns:
        err = t["status"] == "error"
        counts = t.loc[~err, "verdict"].value_counts()
        parts = [f"{int(counts[k])} {k}" for k in ("pass", "incomplete", "fail") if counts.get(k)]
        if err.any():
            parts.append(f"{int(err.sum())} with input errors")
    return f"Run: COMPLETE ({', '.join(parts) or 'no rows'}; each application's verdict is in {rep.out})"


def _capability_line(rep, rs) -> str:
    """The line of a run with a capability target: how many rows' designs meet it (re-selected for it)."""
    t = rep.columns(["capability_verdict"])
    got = t["capability_verdict"].value_counts() if t is not None else {}
    return (f"capability: {rs.targets()}, {rs.samples} samples per design: each application's design re-selected "
            f"for it at full fidelity unless screening-only (synth design --capability): {int(got.get('PASS', 0))} meet it, {int(got.get('FAIL', 0))} "
            "cannot (capability_why says what prevents it)")
