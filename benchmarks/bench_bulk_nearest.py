"""Benchmark of the bulk engine's nearest designs (:meth:`synth.optimise.batch.Batch.nearest`, the one key of near
designs): on generated applications, one chunk as ``synth bulk`` runs it (the search, then the nearest design of
each application without a feasible design), the process CPU seconds of each step and the milliseconds per
infeasible application of the nearest designs.

    .venv/bin/python benchmarks/bench_bulk_nearest.py [--n 2000] [--seed 0] [--chunk 500]

Run it with ``PYTHONPATH`` set to another checkout to time that checkout's engine (this file only calls
``Batch``); the nearest designs are printed as a digest to check that two checkouts choose the same ones.
Prints a markdown table.
"""

from __future__ import annotations

import argparse
import hashlib
import time

from synth.data.generated_applications import generate
from synth.design.evaluate import Settings
from synth.optimise.batch import Batch
from synth.optimise.objectives import Objective


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--n", type=int, default=2000)
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--chunk", type=int, default=500)
    args = ap.parse_args(argv)
    apps = generate(args.n, seed=args.seed)
    settings = Settings(fidelity="screening")
    w = Objective.parse("standard").additive_weights()
    Batch(apps[:8], settings).nearest()  # the kernels loaded
    search = near = 0.0
    bad_total = 0
    digest = hashlib.sha256()
    for s in range(0, len(apps), args.chunk):
        t0 = time.process_time()
        b = Batch(apps[s:s + args.chunk], settings)
        found = b.optimum(w)
        t1 = time.process_time()
        bad = [i for i, f in enumerate(found) if f is None]
        out = b.nearest(bad) if bad else []
        t2 = time.process_time()
        search, near, bad_total = search + t1 - t0, near + t2 - t1, bad_total + len(bad)
        digest.update(repr([out[i] for i in bad]).encode())
    print("| applications | infeasible | search CPU s | nearest CPU s | nearest ms per infeasible | designs digest |")
    print("|---|---|---|---|---|---|")
    print(f"| {len(apps)} | {bad_total} | {search:.1f} | {near:.1f} | {1000 * near / max(bad_total, 1):.1f} "
          f"| {digest.hexdigest()[:12]} |")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
