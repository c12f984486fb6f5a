"""Dask against in-process for ``synth bulk`` (issue 19): speed-up per worker of a LocalCluster, and an existing
scheduler.

    .venv/bin/python benchmarks/bench_dask.py [--n 2000] [--chunk 250] [--workers 1 2 4] [--runs 1]

One generated portfolio (``synth.bulk.sample.sample_portfolio(n)``) through ``run_portfolio`` (no diagnosis, the
default fidelity), in turn: in-process, then ``--engine dask`` on a ``LocalCluster`` of each number of one-thread
worker processes (started by the run, its start-up included), then on an existing cluster through its scheduler
address (started beforehand, not timed). The rows are measured one after the other in one process on the shared
machine (the ratios, not the seconds, are the result). Dask's choice to run in-process where it cannot help
(:func:`synth.bulk.run.dask_pointless`) is switched off here so that one worker is measured too; the table says
what the command does by default.
"""

from __future__ import annotations

import argparse
import statistics
import tempfile
import time
from pathlib import Path


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--n", type=int, default=2000)
    ap.add_argument("--chunk", type=int, default=250)
    ap.add_argument("--workers", type=int, nargs="*", default=[1, 2, 4])
    ap.add_argument("--runs", type=int, default=1)
    args = ap.parse_args(argv)
    from synth.bulk import execution, run
    from synth.bulk.portfolio import write_table
    from synth.bulk.sample import sample_portfolio
    cores = run.usable_cores()
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        path = write_table(sample_portfolio(args.n, seed=0), Path(tmp) / "p.parquet")
        run.run_portfolio(path, Path(tmp) / "warm.parquet", chunk_size=args.chunk, diagnose=False)  # kernels, caches

        def timed(label, **kw):
            t = []
            for r in range(args.runs):
                t0 = time.perf_counter()
                rep = run.run_portfolio(path, Path(tmp) / f"r{len(rows)}_{r}.parquet", chunk_size=args.chunk,
                                      diagnose=False, **kw)
                t.append(time.perf_counter() - t0)
                assert rep.complete
            rows.append((label, statistics.median(t), rep.engine))

        timed("in-process")
        default_choice = {w: run.dask_pointless(None, w, -(-args.n // args.chunk)) for w in args.workers}
        real = run.dask_pointless
        run.dask_pointless = execution.dask_pointless = lambda *a, **k: None  # measure Dask even where the command
        # would not use it (the run asks before starting Dask, the execution once connected)
        try:
            for w in args.workers:
                timed(f"LocalCluster, {w} worker{'s' if w > 1 else ''}", engine="dask", workers=w)
            from dask.distributed import LocalCluster
            with LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as cl:
                timed("existing cluster (--scheduler), 2 workers", engine="dask", scheduler=cl.scheduler_address)
        finally:
            run.dask_pointless = execution.dask_pointless = real
    base = rows[0][1]
    print(f"## synth bulk: in-process against Dask ({args.n} generated applications, chunks of {args.chunk}, no "
          f"diagnosis; {cores} usable cores, shared with other jobs)\n")
    print("| run | seconds | apps/s | speed-up vs in-process | speed-up per worker | the command's default |")
    print("|---|---|---|---|---|---|")
    for label, t, _ in rows:
        w = next((x for x in args.workers if label.startswith("LocalCluster") and f", {x} worker" in label), None)
        if label.startswith("existing"):
            w = 2
        per = f"{base / t / w:.2f}" if w else "-"
        default = "-" if not label.startswith("LocalCluster") else (
            "in-process (" + default_choice[w].split(": ", 1)[1].split(":")[0] + ")" if default_choice[w] else "Dask")
        print(f"| {label} | {t:.1f} | {args.n / t:.0f} | {base / t:.2f} | {per} | {default} |")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
