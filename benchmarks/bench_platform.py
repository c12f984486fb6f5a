"""Platform rationalisation at 100, 300 and 1,000 applications (synthetic feasibility data).

Prints one table row per portfolio size: time to make the feasibility data, to compile
and prune it, the MILP's size (before and after the reductions R1-R5), the solve time,
status and gap, the platform size and the gap of the greedy baseline against the MILP.
The data are :func:`synth.platform.synthetic.synthetic_portfolio` (16 bearings, 20 pivot
classes, 3 x 8 bushings, 5 pads, 5 x 3 axial options, 3,000 main springs, 40 bolts).

    python benchmarks/bench_platform.py [--sizes 100 300 1000] [--objective variants|cost] [--time-limit S]
"""

from __future__ import annotations

import argparse
import time

from synth.platform.rationalise import rationalise
from synth.platform.synthetic import synthetic_portfolio


def main(argv=None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--sizes", type=int, nargs="+", default=[100, 300, 1000])
    ap.add_argument("--objective", default="variants", choices=["variants", "cost"])
    ap.add_argument("--time-limit", type=float, default=120.0)
    ap.add_argument("--seed", type=int, default=0)
    args = ap.parse_args(argv)
    print(f"objective: {args.objective}; time limit {args.time_limit:g} s; seed {args.seed}\n")
    print("| apps | servable | data [s] | compile+prune [s] | row options before -> after | MILP vars / bin / cons / nnz "
          "| build+solve [s] | status | gap | platform parts | MILP objective | greedy | greedy gap | total [s] |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    for n in args.sizes:
        t0 = time.perf_counter()
        pf = synthetic_portfolio(n, seed=args.seed)
        t_data = time.perf_counter() - t0
        r = rationalise(pf, args.objective, time_limit=args.time_limit)
        s, t = r.size, r.times
        served = sum(x["feasible"] for x in r.records)
        print(f"| {n} | {served} | {t_data:.2f} | {t['compile_s'] + t['prune_s']:.2f} "
              f"| {r.sizes_before_prune['row_options']:,} -> {r.prune_log[-1]['row_options']:,} "
              f"| {s['variables']:,} / {s['binaries']} / {s['constraints']:,} / {s['nonzeros']:,} "
              f"| {t['build_s']:.2f} + {t['solve_s']:.2f} | {r.status} | {r.gap:.2%} | {r.n_parts} "
              f"| {r.objective_value:,.6g} | {r.greedy_value:,.6g} | {r.greedy_gap:+.1%} | {t_data + t['total_s']:.1f} |",
              flush=True)


if __name__ == "__main__":
    main()
