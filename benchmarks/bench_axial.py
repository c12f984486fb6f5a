"""Benchmark of the axial group's compiled twins (issue 19, :mod:`synth.kernels.axial`): the group on many rows on
the reference and on the twin in one process, and the bulk engine of this tree against a base checkout side by side.

    .venv/bin/python benchmarks/bench_axial.py [--rows 20000] [--n 2000] [--runs 3] [--base /path/to/checkout]

Table 1: :func:`synth.design.evaluate.axial` on ``--rows`` (core, real axial option) rows of generated applications
at each fidelity, on the numpy reference and on the compiled twins (``engine="numba"``; warm; median of
``--runs``), with the largest difference of a margin. Table 2 (with ``--base``): ``screen_applications`` on ``--n``
generated applications, each run a fresh process of this tree and of the base checkout in turn (A B A B ...; the
ratio is taken pair by pair), with whether the two results are equal (every column; floats to 1e-9).
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]

_CHILD = """
import json, sys, time
import numpy as np
from synth.bulk.engine import screen_applications
from synth.data.generated_applications import generate
n, seed, fid, out = int(sys.argv[1]), int(sys.argv[2]), sys.argv[3], sys.argv[4]
apps = generate(n, seed=seed)
screen_applications(apps[:20], fidelity=fid, diagnose=False)   # kernels and design space loaded, not timed
t0, c0 = time.perf_counter(), time.process_time()
df = screen_applications(apps, fidelity=fid, diagnose=False)
dt, cpu = time.perf_counter() - t0, time.process_time() - c0
df.to_pickle(out)
print(json.dumps({"seconds": dt, "cpu": cpu, "feasible": float(df["feasible"].mean())}))
"""


def _rows(n_rows: int, seed: int, fidelity: str):
    from synth.data.generated_applications import generate
    from synth.design import evaluate as E
    from synth.design.applications import Applications
    from synth.design.space import core_rows, space
    inputs = generate(max(n_rows // 100, 20), seed=seed, vary=True)
    sp, apps = space(), Applications.of(inputs)
    per = [core_rows(sp, d) for d in inputs]
    a = np.concatenate([np.full(len(c), i) for i, c in enumerate(per)]).astype(np.int64)
    st = E.Settings(fidelity=fidelity)
    with np.errstate(all="ignore"):
        cg = E.core(apps, a, sp.rows("core", np.concatenate(per)), st)
    pad = np.flatnonzero(np.asarray(cg.values["axial_group_present"], dtype=float) > 0)
    real = np.flatnonzero(sp.tables["axial"]["axial_group_present"])
    rng = np.random.default_rng(seed)
    return apps, cg, rng.choice(pad, n_rows), sp.rows("axial", rng.choice(real, n_rows)), st


def _median_time(fn, runs: int):
    times, out = [], None
    for _ in range(runs):
        t0 = time.perf_counter()
        out = fn()
        times.append(time.perf_counter() - t0)
    return out, statistics.median(times)


def group_table(n_rows: int, runs: int, seed: int) -> None:
    from synth.design import evaluate as E
    print(f"## The axial group on {n_rows} rows (warm, median of {runs})\n")
    print("| fidelity | numpy reference s | numba twin s | ratio | us/row (twin) | largest margin difference | "
          "verdicts equal |")
    print("|---|---|---|---|---|---|---|")
    for fid in ("screening", "full"):
        apps, cg, rr, o, st = _rows(n_rows, seed, fid)
        with np.errstate(all="ignore"):
            E.axial(apps, cg, rr[:50], {k: np.asarray(v)[:50] for k, v in o.items()}, st, engine="numba")  # load
            ref, t_ref = _median_time(lambda: E.axial(apps, cg, rr, o, st), runs)
            twin, t_twin = _median_time(lambda: E.axial(apps, cg, rr, o, st, engine="numba"), runs)
        diff = 0.0
        for k, m in ref.margins.items():
            m, t = np.asarray(m, dtype=float), np.asarray(twin.margins[k], dtype=float)
            fin = np.isfinite(m) & np.isfinite(t)
            if fin.any():
                diff = max(diff, float(np.max(np.abs(m[fin] - t[fin]))))
        same = bool((ref.ok() == twin.ok()).all())
        print(f"| {fid} | {t_ref:.3f} | {t_twin:.3f} | {t_ref / t_twin:.2f} | {1e6 * t_twin / n_rows:.2f} | "
              f"{diff:.1e} | {'yes' if same else 'NO'} |")
    print()


def same_table(a, b) -> bool:
    """Every column equal (floats to 1e-9, NaN equal to NaN), the same columns in the same order."""
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


def engine_table(n: int, runs: int, seed: int, base: Path) -> None:
    import pandas as pd
    sys.path.insert(0, str(Path(__file__).resolve().parent))
    print(f"## Bulk engine (`screen_applications`, {n} generated applications, no diagnosis): this tree (A) against "
          f"{base} (B), fresh processes in turn, warm inside each\n")
    print("| fidelity | A s (median) | B s (median) | A apps/s | B apps/s | speed-up B/A (median of pairs) | "
          "A apps per CPU s | B apps per CPU s | CPU B/A (median of pairs) | results equal |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    with tempfile.TemporaryDirectory() as tmp:
        for fid in ("screening", "full"):
            ta, tb, ca, cb, equal = [], [], [], [], True
            for r in range(runs):
                res = {}
                for label, tree in (("A", ROOT), ("B", base)):
                    out = Path(tmp) / f"{label}{r}{fid}.pkl"
                    env = {**os.environ, "PYTHONPATH": str(tree)}
                    p = subprocess.run([sys.executable, "-c", _CHILD, str(n), str(seed), fid, str(out)], env=env,
                                       capture_output=True, text=True, check=True, cwd=tree)
                    got = json.loads(p.stdout.strip().splitlines()[-1])
                    res[label] = (got["seconds"], pd.read_pickle(out), got["cpu"])
                ta.append(res["A"][0])
                tb.append(res["B"][0])
                ca.append(res["A"][2])
                cb.append(res["B"][2])
                equal &= same_table(res["A"][1], res["B"][1])
            ratio = statistics.median(b / a for a, b in zip(ta, tb))
            a, b = statistics.median(ta), statistics.median(tb)
            cpu_ratio = statistics.median(y / x for x, y in zip(ca, cb))
            print(f"| {fid} | {a:.2f} | {b:.2f} | {n / a:.0f} | {n / b:.0f} | {ratio:.2f} | "
                  f"{n / statistics.median(ca):.0f} | {n / statistics.median(cb):.0f} | {cpu_ratio:.2f} | "
                  f"{'yes' if equal else 'NO'} |")
    print()


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--rows", type=int, default=20000, help="rows of the axial group (table 1)")
    ap.add_argument("--n", type=int, default=2000, help="applications of the bulk engine (table 2)")
    ap.add_argument("--runs", type=int, default=3)
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--base", type=Path, help="a checkout of the base commit (table 2 is skipped without it)")
    args = ap.parse_args(argv)
    group_table(args.rows, args.runs, args.seed)
    if args.base is not None:
        engine_table(args.n, args.runs, args.seed, args.base.resolve())
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
