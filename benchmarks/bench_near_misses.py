"""Near misses of an infeasible input (``synth design CASE --top K``): what the wider pool of the second-level rank
costs and what it buys (issue 35).

For each pool factor (``synth.optimise.alternatives.NEAR_POOL``: the pool holds factor x K designs by the smallest
margin, each verified) it prints the seconds of ``ranked()`` (the synthesis itself excluded, best of ``--runs``),
the pool size (designs verified, at most), and the K near misses' second smallest margins and failing counts (the second-level rank:
larger second margin, then fewer failing checks, is nearer). Factor 1 is the pool of ab57224 ranked by the new key.

    python benchmarks/bench_near_misses.py [--case case1] [--top 5] [--factors 1 4] [--runs 2]
"""

from __future__ import annotations

import argparse
import time

import numpy as np


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--case", default="case1")
    ap.add_argument("--top", type=int, default=5)
    ap.add_argument("--factors", type=int, nargs="+", default=[1, 4])
    ap.add_argument("--runs", type=int, default=2)
    args = ap.parse_args(argv)
    import synth
    from synth.data import case_path
    from synth.optimise import alternatives as al
    d = synth.load(str(case_path(args.case)))
    r = synth.synthesise(d)
    print(f"{args.case}: status {r.status}, --top {args.top}")
    print(f"{'pool factor':>11} {'pool':>9} {'seconds':>8}  second margin / failing checks of #1..#{args.top}")
    for factor in args.factors:
        al.NEAR_POOL = factor
        best, alts = float("inf"), []
        for _ in range(args.runs):
            t = time.perf_counter()
            alts = al.ranked(d, r, args.top)
            best = min(best, time.perf_counter() - t)
        keys = []
        for a in alts:
            asm = synth.verify(d, a["parts"]).assessment()
            m = np.sort(asm.margins[0][asm.counted[0]])
            keys.append(f"{100 * m[1]:+.1f} %/{int(asm.failed[0].sum())}")
        print(f"{factor:>11} {min(factor * args.top, al.MAX_TOP):>9} {best:>8.2f}  " + ", ".join(keys))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
