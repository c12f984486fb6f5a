"""Benchmark of the drive's speed sweep (issue 26): 50 speeds of the example timing drive on one core.

    OPENBLAS_NUM_THREADS=1 .venv/bin/python benchmarks/bench_drive.py [--speeds 50] [--repeat 3] [--quick] [--grid]

BLAS is held to one thread (set before numpy is imported): the matrices are small and the target is one core.
Prints one markdown table, measured side by side in one run: the sweep at the default settings (24 harmonics,
regularisation 1 %), the tolerance check's sweep (48 harmonics, 0.5 %), and the linear response alone (the
arm held: no friction solve), with seconds (best of ``--repeat``), speeds/s and the ratio to the default.

``--grid``: the solves' robustness instead. The example drive's sweep at damping 0.10 to 0.75 Nm in steps of 0.05
(the hard solves are just under each speed's critical friction, where the arm barely slips), at the default
settings and at the tolerance check's, each sweep on its own; one table row per setting: solves, unconverged ones,
their largest residual and how far under the critical friction they were, seconds. ``--quick``: three dampings at
the default settings.
"""

from __future__ import annotations

import os

for _v in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_v, "1")

import argparse  # noqa: E402
import time  # noqa: E402

import numpy as np  # noqa: E402


def _best(fn, repeat):
    out = []
    for _ in range(repeat):
        t = time.perf_counter()
        fn()
        out.append(time.perf_counter() - t)
    return min(out)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--speeds", type=int, default=50)
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--quick", action="store_true", help="5 speeds, one repeat (a smoke test)")
    ap.add_argument("--grid", action="store_true", help="count the unconverged solves over a grid of dampings")
    a = ap.parse_args(argv)
    if a.grid:
        return grid(np.array([0.35, 0.45, 0.55]) if a.quick else np.round(np.arange(0.10, 0.76, 0.05), 2),
                    check=not a.quick)
    n, repeat = (5, 1) if a.quick else (a.speeds, a.repeat)
    from synth.drive.inputs import example_drive
    from synth.drive.modes import linear_drive
    from synth.drive.response import sweep
    d = example_drive()
    m = linear_drive(d)
    speeds = np.linspace(d.speed_min_rpm, d.speed_max_rpm, n)
    fr = d.tensioner.friction_torque_nm
    rows = [("default (24 harmonics, eps 1 %)", lambda: sweep(m, d, fr, speeds)),
            ("check (48 harmonics, eps 0.5 %)", lambda: sweep(m, d, fr, speeds, harmonics=48, eps_rel=0.005)),
            ("arm held (no friction solve)", lambda: sweep(m, d, 1e3, speeds))]
    times = [(name, _best(fn, repeat)) for name, fn in rows]
    base = times[0][1]
    print(f"Drive sweep of {n} speeds, {d.name}, one core (best of {repeat})\n")
    print("| sweep | seconds | speeds/s | ratio to default |\n|---|---:|---:|---:|")
    for name, t in times:
        print(f"| {name} | {t:.3f} | {n / t:.1f} | {t / base:.2f} |")
    return 0


def grid(dampings, check: bool = True) -> int:
    """The unconverged solves of the example drive's sweep at each of ``dampings`` [N m] (see the module docstring),
    at the default settings and (``check``) at the tolerance check's."""
    from synth.drive.inputs import example_drive
    from synth.drive.modes import linear_drive
    from synth.drive.response import sweep
    d = example_drive()
    m = linear_drive(d)
    speeds = d.speeds_rpm()
    print(f"Unconverged solves of {d.name}: {len(speeds)} speeds x {len(dampings)} dampings "
          f"({dampings.min():.2f}-{dampings.max():.2f} Nm), each sweep on its own\n")
    print("| settings | solves | unconverged | largest residual | under the critical friction | seconds |")
    print("|---|---:|---:|---:|---|---:|")
    settings = [("default (24 harmonics, eps 1 %)", 24, 0.01), ("check (48 harmonics, eps 0.5 %)", 48, 0.005)]
    for name, h, eps in settings[:2 if check else 1]:
        t = time.perf_counter()
        bad = [(f, r) for f in dampings for r in sweep(m, d, float(f), speeds, harmonics=h, eps_rel=eps)["rows"]
               if not r["converged"]]
        el = time.perf_counter() - t
        res = max((r["residual"] for _, r in bad), default=0.0)
        under = [1.0 - f / r["critical_friction_nm"] for f, r in bad]
        span = f"{100 * min(under):.1f}-{100 * max(under):.1f} %" if under else "-"
        print(f"| {name} | {len(speeds) * len(dampings)} | {len(bad)} | {res:.1e} | {span} | {el:.1f} |")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
