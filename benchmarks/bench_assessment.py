"""Benchmark of the one assessment (issue 21): its share of the bulk engine's time, measured inside one run.

    .venv/bin/python benchmarks/bench_assessment.py [--n 1000] [--runs 3] [--seed 0]

Times ``screen_applications`` (no diagnosis) on a generated portfolio and, in the same calls, the time spent in
what reads the assessment (:mod:`synth.design.assessment`): ``Group.ok``, ``Group.min_margin`` (the optimisers'
inner loops), ``fidelity_free_ok`` and the bulk rows (``_rows``). Prints a markdown table: calls per run,
milliseconds per run and the share of the engine's time. Run it on two trees to compare them (alternating runs:
the machine is shared).
"""

from __future__ import annotations

import argparse
import collections
import time

from synth.bulk import engine
from synth.data.generated_applications import generate
from synth.design import evaluate

#: (owner, attribute, label) of the functions timed
TIMED = ((evaluate.Group, "ok", "Group.ok"), (evaluate.Group, "min_margin", "Group.min_margin"),
         (evaluate, "fidelity_free_ok", "evaluate.fidelity_free_ok"), (engine, "_rows", "bulk engine _rows"))


def _timed(acc: dict, calls: collections.Counter) -> list:
    """Wrap each of :data:`TIMED` to add its seconds and calls to ``acc`` and ``calls``; returns the originals."""
    kept = []
    for owner, name, label in TIMED:
        f = getattr(owner, name)
        kept.append((owner, name, f))

        def w(*a, _f=f, _label=label, **k):
            t = time.perf_counter()
            try:
                return _f(*a, **k)
            finally:
                acc[_label] += time.perf_counter() - t
                calls[_label] += 1
        setattr(owner, name, w)
    return kept


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--n", type=int, default=1000, help="applications in the portfolio")
    ap.add_argument("--runs", type=int, default=3, help="engine runs (totals are per run)")
    ap.add_argument("--seed", type=int, default=0)
    args = ap.parse_args(argv)
    apps = generate(args.n, seed=args.seed)
    acc: dict = collections.defaultdict(float)
    calls: collections.Counter = collections.Counter()
    kept = _timed(acc, calls)
    try:
        engine.screen_applications(apps[:20], diagnose=False)  # load the kernels and the design space
        acc.clear()
        calls.clear()
        t0 = time.perf_counter()
        for _ in range(args.runs):
            engine.screen_applications(apps, diagnose=False)
        total = (time.perf_counter() - t0) / args.runs
    finally:
        for owner, name, f in kept:
            setattr(owner, name, f)
    print(f"## The assessment in the bulk engine ({args.n} generated applications, seed {args.seed}, "
          f"screening fidelity, no diagnosis; per run, {args.runs} runs)\n")
    print("| function | calls | ms | share of the engine |")
    print("|---|---|---|---|")
    for _, _, label in TIMED:
        ms = acc[label] / args.runs * 1000.0
        print(f"| {label} | {calls[label] // args.runs} | {ms:.1f} | {ms / 1000.0 / total:.3f} |")
    print(f"| engine (screen_applications) | 1 | {total * 1000.0:.1f} | 1.000 |")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
