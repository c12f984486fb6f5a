"""Benchmark of the bulk engine (issues 7 and 13): applications per second at each fidelity, with and without
the relaxation diagnosis, the agreement between fidelities, the reference (``solve`` per application), one
optimum inside a process, and the whole ``synth bulk`` command on a ``synth portfolio-sample``.

    .venv/bin/python benchmarks/bench_bulk.py [--n 2000] [--quick] [--seed 0] [--no-command] [--base CHECKOUT]

Prints markdown tables. ``--quick`` runs a small portfolio (for a smoke test). The aims of issue 13: the
engine >= 1,000 applications/s and the whole command >= 300/s at screening fidelity without diagnosis,
>= 200/s with it; one optimum (enumerate) < 50 ms.
"""

from __future__ import annotations

import argparse
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path


from synth.bulk.engine import screen_applications, screen_applications_reference

sys.path.insert(0, str(Path(__file__).resolve().parent))
from bench_axial import engine_table, same_table  # noqa: E402  (a sibling script: the engine table, the comparison)
from synth.data.generated_applications import generate


def _time(fn, runs: int = 1):
    """``(result, median seconds)`` of ``runs`` calls of ``fn``."""
    times = []
    for _ in range(runs):
        t0 = time.perf_counter()
        out = fn()
        times.append(time.perf_counter() - t0)
    return out, statistics.median(times)


def _optimum_ms(apps, runs: int = 20) -> tuple:
    """Median time [ms] of ``solve(d, "standard", "enumerate")`` on the first feasible application (warm)."""
    from synth.optimise import solve
    d = next(a for a in apps if solve(a, "standard", "enumerate", relax=False).status == "optimal")
    times = []
    for _ in range(runs):
        t0 = time.perf_counter()
        solve(d, "standard", "enumerate", relax=False)
        times.append(time.perf_counter() - t0)
    return 1e3 * statistics.median(times), 1e3 * min(times)


def _command_rates(n: int, seed: int) -> list:
    """Whole ``synth bulk`` processes (start-up, reading, the engine, writing the CSV and the summary)."""
    root = Path(__file__).resolve().parents[1]
    env = {**os.environ, "PYTHONPATH": str(root) + os.pathsep + os.environ.get("PYTHONPATH", "")}
    synth = [sys.executable, "-m", "synth"]
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        port = Path(tmp) / "portfolio.csv"
        subprocess.run(synth + ["portfolio-sample", str(n), "--seed", str(seed), "--out", str(port)], env=env,
                       check=True, stdout=subprocess.DEVNULL)
        for label, extra in (("screening, no diagnosis", ["--no-diagnose"]), ("screening, diagnosis", []),
                             ("full, no diagnosis", ["--no-diagnose", "--fidelity", "full"])):
            out = Path(tmp) / f"r{len(rows)}.csv"
            t0 = time.perf_counter()
            subprocess.run(synth + ["bulk", str(port), "--out", str(out)] + extra, env=env, check=False,
                           stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
            dt = time.perf_counter() - t0
            rows.append((label, n, dt, n / dt))
    return rows


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--n", type=int, default=2000, help="applications in the portfolio")
    ap.add_argument("--no-command", action="store_true", help="skip the whole-command timing")
    ap.add_argument("--runs", type=int, default=3, help="runs per engine row (the median is printed)")
    ap.add_argument("--quick", action="store_true", help="small portfolio and reference sample")
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--objective", default="standard")
    ap.add_argument("--base", type=Path, help="a checkout of the base commit: only the engine, this tree against it "
                    "side by side (fresh processes in turn, benchmarks/bench_axial.py's table)")
    args = ap.parse_args(argv)
    if args.base is not None:
        engine_table(args.n, args.runs, args.seed, args.base.resolve())
        return 0
    n = 12 if args.quick else args.n
    args.runs = 1 if args.quick else max(args.runs, 1)
    n_ref = 4 if args.quick else 12
    n_diag = n if args.quick else max(n // 4, 10)
    apps = generate(n, seed=args.seed)

    rows, results = [], {}
    # the first call of a process loads the compiled kernels (numba's on-disk cache) and the design space:
    # timed apart, then every row below is warm
    _, warm = _time(lambda: screen_applications(apps[:20], objective=args.objective, diagnose=True))
    for fid in ("screening", "full"):
        df, dt = _time(lambda: screen_applications(apps, objective=args.objective, fidelity=fid, diagnose=False),
                       args.runs)
        results[fid] = df
        rows.append((fid, "off", n, dt, n / dt, df["feasible"].mean()))
    sub = apps[:n_diag]
    for fid in ("screening", "full"):
        df, dt = _time(lambda: screen_applications(sub, objective=args.objective, fidelity=fid, diagnose=True),
                       args.runs)
        rows.append((fid, "on", len(sub), dt, len(sub) / dt, df["feasible"].mean()))
    ref_apps = apps[:n_ref]
    ref, dt_ref = _time(lambda: screen_applications_reference(ref_apps, objective=args.objective, diagnose=False))
    rows.append(("screening (reference: solve per app)", "off", n_ref, dt_ref, n_ref / dt_ref, ref["feasible"].mean()))
    equal = same_table(results["screening"].iloc[:n_ref].reset_index(drop=True), ref)

    print(f"## Bulk engine benchmark (objective {args.objective}, generated applications seed {args.seed}; "
          f"engine rows: median of {args.runs} warm runs)\n")
    print("| fidelity | diagnose | n apps | seconds | apps/s | share feasible |")
    print("|---|---|---|---|---|---|")
    for fid, dg, k, dt, rate, feas in rows:
        print(f"| {fid} | {dg} | {k} | {dt:.2f} | {rate:.2f} | {feas:.3f} |")
    s, f = results["screening"], results["full"]
    parts = [c for c in s.columns if c.startswith("part_")]
    verdict = float((s["feasible"] != f["feasible"]).mean())
    design = float((s[parts].astype(str) != f[parts].astype(str)).any(axis=1).mean())
    print()
    print("| agreement screening vs full (same portfolio) | share |")
    print("|---|---|")
    print(f"| verdicts that differ | {verdict:.3f} |")
    print(f"| chosen (or nearest) designs that differ | {design:.3f} |")
    print(f"| feasible at screening, infeasible at full | {float((s['feasible'] & ~f['feasible']).mean()):.3f} |")
    print(f"| infeasible at screening, feasible at full | {float((~s['feasible'] & f['feasible']).mean()):.3f} |")
    print()
    print(f"Fast engine equals the reference on the first {n_ref} applications: {'yes' if equal else 'NO'}; "
          f"speed-up {rows[0][4] / rows[4][4]:.1f}x (screening, no diagnosis).")
    print(f"\nFirst call of the process (20 applications, loading the kernels and the design space): {warm:.2f} s.")
    ms, best = _optimum_ms(apps)
    print(f"\nOne optimum inside a process (solve(d, 'standard', 'enumerate'), warm, median of 20): {ms:.1f} ms "
          f"(fastest {best:.1f} ms).")
    if not args.no_command and not args.quick:
        print("\n| whole command `synth bulk` (portfolio-sample) | n apps | seconds | apps/s |")
        print("|---|---|---|---|")
        for label, k, dt, rate in _command_rates(n, args.seed):
            print(f"| {label} | {k} | {dt:.2f} | {rate:.0f} |")
    return 0 if equal else 1


if __name__ == "__main__":
    raise SystemExit(main())
