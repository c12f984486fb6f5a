"""Benchmark of the bulk engine (issue 7): applications per second at each fidelity, with and without the
relaxation diagnosis, the agreement between fidelities, and the reference (``solve`` per application).

    .venv/bin/python benchmarks/bench_bulk.py [--n 200] [--quick] [--seed 0]

Prints a markdown table. ``--quick`` runs a small portfolio (for a smoke test).
"""

from __future__ import annotations

import argparse
import time

import numpy as np

from synth.bulk.engine import screen_applications, screen_applications_reference
from synth.data.generated_applications import generate


def _time(fn):
    t0 = time.perf_counter()
    out = fn()
    return out, time.perf_counter() - t0


def _same(a, b) -> bool:
    if list(a.columns) != list(b.columns) or len(a) != len(b):
        return False
    for c in a.columns:
        x, y = a[c].to_numpy(), b[c].to_numpy()
        if a[c].dtype == float:
            with np.errstate(invalid="ignore"):
                ok = ((np.isnan(x) & np.isnan(y)) | (x == y) | (np.abs(x - y) <= 1e-9)).all()
            if not ok:
                return False
        elif [str(v) for v in x] != [str(v) for v in y]:
            return False
    return True


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--n", type=int, default=200, help="applications in the portfolio")
    ap.add_argument("--quick", action="store_true", help="small portfolio and reference sample")
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--objective", default="standard")
    args = ap.parse_args(argv)
    n = 12 if args.quick else args.n
    n_ref = 4 if args.quick else 12
    n_diag = n if args.quick else max(n // 4, 10)
    apps = generate(n, seed=args.seed)

    rows, results = [], {}
    for fid in ("screening", "full"):
        df, dt = _time(lambda: screen_applications(apps, objective=args.objective, fidelity=fid, diagnose=False))
        results[fid] = df
        rows.append((fid, "off", n, dt, n / dt, df["feasible"].mean()))
    sub = apps[:n_diag]
    for fid in ("screening", "full"):
        df, dt = _time(lambda: screen_applications(sub, objective=args.objective, fidelity=fid, diagnose=True))
        rows.append((fid, "on", len(sub), dt, len(sub) / dt, df["feasible"].mean()))
    ref_apps = apps[:n_ref]
    ref, dt_ref = _time(lambda: screen_applications_reference(ref_apps, objective=args.objective, diagnose=False))
    rows.append(("screening (reference: solve per app)", "off", n_ref, dt_ref, n_ref / dt_ref, ref["feasible"].mean()))
    equal = _same(results["screening"].iloc[:n_ref].reset_index(drop=True), ref)

    print(f"## Bulk engine benchmark (objective {args.objective}, generated applications seed {args.seed})\n")
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
    return 0 if equal else 1


if __name__ == "__main__":
    raise SystemExit(main())
