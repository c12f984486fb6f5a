"""Platform rationalisation on real portfolios of 100, 300 and 1,000 applications.

The portfolios are ``synth portfolio-sample N --seed S`` tables (the applications of
:mod:`synth.data.generated_applications`, inputs over the ranges of the thesis's
applications); their feasibility comes from the evaluator
(:mod:`synth.platform.producer`, full fidelity by default). One table row per size:

* data: time to read, validate and evaluate the portfolio (``--engine``; the rows the
  group functions evaluated, by group, are printed below the table: where the time goes);
* the reductions (row options before -> after), the MILP's size (variables / binaries /
  constraints / non-zeros), its build and solve time, status and gap;
* the platform's distinct parts against the union of the per-application optima,
  the greedy baseline's gap to the MILP, the total time (data + rationalisation).

    python benchmarks/bench_platform.py [--sizes 100 300 1000] [--objective variants|cost]
        [--engine inprocess|dask] [--workers 2] [--fidelity full|screening] [--time-limit S]
        [--synthetic] [--plot PNG]

``--synthetic`` times :func:`synth.platform.synthetic.synthetic_portfolio` instead (the
illustrative data the model was first built on). ``--plot`` writes the margin trade-off
curve of the largest size (the README's figure). The machine's load average is printed
with the table: the 2 cores are shared, and the times are wall-clock.

``--tradeoff margin|cost`` adds a second table: the trade-off sweep (``--points``) with its
rounds sharing one compile (:func:`synth.platform.rationalise.tradeoff`, ``share=True``)
against each round solved afresh (``share=False``, as before), alternating ``--repeat``
times on the same feasibility data; wall and process CPU seconds (medians), their ratios,
and whether the rows are identical.

``--builds`` adds a table: the rationalisation with its default trade-off (the whole ``synth rationalise`` after the
feasibility data: the platform, then the margin sweep) with the MILP built from arrays for highspy (B, the default)
against built through Pyomo and appsi (A, the reference), alternating ``--repeat`` times; and whether the results
(objective, platform, assignment, trade-off rows) are identical. ``--axial`` adds one for the feasibility data:
the producer's axial group on the compiled wear (B, :data:`synth.platform.producer.AXIAL_ENGINE`) against the
numpy reference (A), alternating, with the largest option-margin difference and whether the feasible options are
the same.
"""

from __future__ import annotations

import argparse
import os
import time


def _row(n, t_data, pf, r, served):
    s, t = r.size, r.times
    return (f"| {n:,} | {served} | {t_data:.1f} | {t['compile_s'] + t['prune_s']:.1f} "
            f"| {r.sizes_before_prune['row_options']:,} -> {r.prune_log[-1]['row_options']:,} "
            f"| {s['variables']:,} / {s['binaries']} / {s['constraints']:,} / {s['nonzeros']:,} "
            f"| {t['build_s']:.1f} + {t['solve_s']:.1f} | {r.status} | {r.gap:.2%} "
            f"| {r.n_parts} / {r.n_parts_union_optima} | {r.greedy_gap:+.1%} | {t['verify_s']:.1f} "
            f"| {t_data + t['total_s']:.1f} |")


def main(argv=None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--sizes", type=int, nargs="+", default=[100, 300, 1000])
    ap.add_argument("--objective", default="variants", choices=["variants", "cost"])
    ap.add_argument("--engine", default="dask", choices=["inprocess", "dask"])
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("--fidelity", default="full", choices=["full", "screening"])
    ap.add_argument("--time-limit", type=float, default=120.0)
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--synthetic", action="store_true", help="synthetic feasibility data instead of real portfolios")
    ap.add_argument("--plot", help="write the margin trade-off plot of the largest size to this PNG")
    ap.add_argument("--tradeoff", choices=["margin", "cost"], help="also time the trade-off sweep, shared vs afresh")
    ap.add_argument("--points", type=int, default=5, help="points of the trade-off sweep (the CLI's default)")
    ap.add_argument("--repeat", type=int, default=3, help="alternating runs of each trade-off variant")
    ap.add_argument("--builds", action="store_true", help="also time the MILP built from arrays against Pyomo")
    ap.add_argument("--axial", action="store_true", help="also time the feasibility data's axial engines")
    args = ap.parse_args(argv)
    from synth.bulk.sample import sample_portfolio
    from synth.design.evaluate import Settings
    from synth.platform.portfolio_feasibility import from_table
    from synth.platform.rationalise import rationalise
    from synth.platform.synthetic import synthetic_portfolio
    what = "synthetic feasibility data" if args.synthetic else (
        f"portfolio-sample (seed {args.seed}), fidelity {args.fidelity}, engine {args.engine}"
        + (f" ({args.workers} workers)" if args.engine == "dask" else ""))
    print(f"{what}; objective {args.objective}; MILP time limit {args.time_limit:g} s; "
          f"load average before: {os.getloadavg()[0]:.1f} on {os.cpu_count()} cores\n")
    print("| apps | served | data [s] | compile+prune [s] | row options before -> after "
          "| MILP vars / bin / cons / nnz | build+solve [s] | status | gap | parts (platform / union of optima) "
          "| greedy gap | verify [s] | total [s] |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    notes, last, sweeps, builds, axial = [], None, [], [], []
    for n in args.sizes:
        t0 = time.perf_counter()
        if args.synthetic:
            pf = synthetic_portfolio(n, seed=args.seed)
        else:
            pf = from_table(sample_portfolio(n, seed=args.seed), Settings(fidelity=args.fidelity),
                            engine=args.engine, workers=args.workers)
        t_data = time.perf_counter() - t0
        r = rationalise(pf, args.objective, time_limit=args.time_limit)
        served = sum(x["feasible"] for x in r.records)
        print(_row(n, t_data, pf, r, served), flush=True)
        st = pf.stats
        if st:
            groups = [g for g in ("core", "bushing", "axial", "spring", "bolt") if f"{g}_s" in st]
            notes.append(f"- {n:,}: evaluator CPU time by group (summed over workers): "
                         + ", ".join(f"{g} {st[g + '_s']:.1f} s ({st[g + '_pairs']:,} rows)" for g in groups)
                         + f"; main-spring stages {st.get('spring_stage1_pairs', 0):,} rows")
        last = (pf, r)
        if args.tradeoff:
            sweeps.append((n, _sweep(pf, args)))
        if args.builds:
            builds.append((n, _builds(pf, args)))
        if args.axial and not args.synthetic:
            axial.append((n, _axial(n, args)))
    print(f"\nload average after: {os.getloadavg()[0]:.1f}")
    if notes:
        print("\n" + "\n".join(notes))
    if sweeps:
        _ab_table(f"trade-off sweep ({args.tradeoff}, {args.points} points), rounds sharing one compile (B) against "
                  f"each round afresh (A), {args.repeat} alternating runs, medians:", sweeps, "rows identical")
    if builds:
        _ab_table(f"rationalise with the margin trade-off ({args.points} points), MILP through Pyomo (A) against from "
                  f"arrays through highspy (B), {args.repeat} alternating runs, medians:", builds, "results identical")
    if axial:
        print(f"\nfeasibility data, the axial group on the numpy wear (A) against the compiled wear (B), engine "
              f"{args.engine}, {args.repeat} alternating runs, medians (axial: the group's own seconds):\n")
        print("| apps | A data [s] | B data [s] | B/A | A axial [s] | B axial [s] | B/A axial | largest margin difference "
              "| feasible options identical |")
        print("|---|---|---|---|---|---|---|---|---|")
        for n, (da, db, xa, xb, diff, same) in axial:
            print(f"| {n:,} | {da:.1f} | {db:.1f} | {db / da:.2f} | {xa:.1f} | {xb:.1f} | {xb / xa:.2f} | {diff:.1e} "
                  f"| {same} |")
    if args.plot and last:
        from synth.platform.outputs import plot_tradeoff
        from synth.platform.rationalise import tradeoff
        rows = tradeoff(last[0], "margin", points=6, time_limit=args.time_limit)
        plot_tradeoff(rows, args.plot, "margin")
        print(f"\ntrade-off ({len(last[0].apps)} applications): "
              + "; ".join(f"floor {x['margin_floor']:.3f}: {x['parts']} parts, {x['served']} served" for x in rows)
              + f" -> {args.plot}")


def _ab_table(title: str, results: list, same: str) -> None:
    print(f"\n{title}\n")
    print(f"| apps | A wall [s] | B wall [s] | B/A wall | A CPU [s] | B CPU [s] | B/A CPU | {same} |")
    print("|---|---|---|---|---|---|---|---|")
    for n, (wa, wb, ca, cb, eq) in results:
        print(f"| {n:,} | {wa:.1f} | {wb:.1f} | {wb / wa:.2f} | {ca:.1f} | {cb:.1f} | {cb / ca:.2f} | {eq} |")


def _alternate(repeat: int, a, b) -> tuple:
    """``a()`` and ``b()`` in turn ``repeat`` times: median wall and CPU seconds of each, and whether their last
    answers are equal."""
    import statistics
    wall, cpu, out = ([], []), ([], []), [None, None]
    for _ in range(repeat):
        for i, fn in enumerate((a, b)):
            t0, c0 = time.perf_counter(), time.process_time()
            out[i] = fn()
            wall[i].append(time.perf_counter() - t0)
            cpu[i].append(time.process_time() - c0)
    med = statistics.median
    return med(wall[0]), med(wall[1]), med(cpu[0]), med(cpu[1]), out[0] == out[1]


def _sweep(pf, args) -> tuple:
    """Median wall and CPU seconds of the trade-off sweep afresh (A) and shared (B), alternating."""
    from synth.platform.rationalise import tradeoff
    return _alternate(args.repeat, *(lambda share=share: tradeoff(pf, args.tradeoff, points=args.points,
                                                                   time_limit=args.time_limit, share=share)
                                     for share in (False, True)))


def _builds(pf, args) -> tuple:
    """Median wall and CPU seconds of rationalise + margin sweep through Pyomo (A) and from arrays (B), alternating."""
    from synth.platform.rationalise import rationalise, tradeoff

    def run(build):
        r = rationalise(pf, args.objective, time_limit=args.time_limit, build=build)
        return (r.objective_value, r.platform, r.records,
                tradeoff(pf, "margin", points=args.points, time_limit=args.time_limit, build=build))
    return _alternate(args.repeat, lambda: run("pyomo"), lambda: run("arrays"))


def _axial(n, args) -> tuple:
    """Median data and axial-group seconds on the numpy wear (A) and the compiled wear (B), alternating; the largest
    option-margin difference and whether every application's feasible options are the same."""
    import statistics
    import numpy as np
    from synth.bulk.sample import sample_portfolio
    from synth.design.evaluate import Settings
    from synth.platform import portfolio_feasibility, producer
    table = sample_portfolio(n, seed=args.seed)
    data, ax, pfs = {"numpy": [], "numba": []}, {"numpy": [], "numba": []}, {}
    try:
        for _ in range(args.repeat):
            for eng in ("numpy", "numba"):
                producer.AXIAL_ENGINE = eng
                t0 = time.perf_counter()
                pfs[eng] = portfolio_feasibility.from_table(table, Settings(fidelity=args.fidelity), engine=args.engine,
                                                            workers=args.workers)
                data[eng].append(time.perf_counter() - t0)
                ax[eng].append(pfs[eng].stats.get("axial_s", np.nan))
    finally:
        producer.AXIAL_ENGINE = "numba"
    diff, same = 0.0, True
    for a, b in zip(pfs["numpy"].apps, pfs["numba"].apps):
        for s in a.feasible:
            for fa, fb, ma, mb in zip(a.feasible[s], b.feasible[s], a.option_margin[s], b.option_margin[s]):
                same &= np.array_equal(fa, fb)
                if same and len(ma):
                    diff = max(diff, float(np.max(np.abs(np.asarray(ma) - np.asarray(mb)))))
    med = statistics.median
    return med(data["numpy"]), med(data["numba"]), med(ax["numpy"]), med(ax["numba"]), diff, same


if __name__ == "__main__":
    main()
