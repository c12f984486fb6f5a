"""Benchmark of the compiled main-spring kernels (issue 13): pairs/s of numpy vs numba, applications/s of the spring
subsystem, and what numba costs a process.

    .venv/bin/python benchmarks/bench_kernels.py [--apps 2000] [--pair-apps 50] [--numpy-apps 200] [--quick]

Prints three markdown tables:

1. the numba costs, each in a fresh process: ``python -c "import numpy"``, ``import numba``, the first call of each
   kernel with an empty cache (compilation) and with the on-disk cache (load), and whether ``import synth.kernels``
   imported numba (it must not);
2. (a)-(d) on the spring keys of ``--pair-apps`` generated applications x their catalog springs: seconds, pairs
   evaluated, pairs/s, keys/s, numpy reference vs the numba kernel (serial and ``parallel=True``), ratio in one run;
3. the spring subsystem of a ``--apps`` generated-application sample: per application, every spring key of its
   core-feasible cores scans the application's catalog springs in cost order and stops at the first feasible
   (``first_feasible``): applications/s of the numba kernel, and of the numpy twin on the first ``--numpy-apps``.

The keys and options are built beforehand (the spaces and core evaluations; their time is printed apart): the
tables time the spring physics alone. ``--quick`` runs small sizes (a smoke test).
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
sys.path.insert(0, str(ROOT))

from synth.data.generated_applications import generate  # noqa: E402
from synth.design.constraints import FEAS_TOL  # noqa: E402
from synth.design.evaluate import Settings  # noqa: E402
from synth.kernels import main_spring  # noqa: E402

# --------------------------------------------------------------------------------------- 1. numba costs

_CHILD = r"""
import json, sys, time
if sys.argv[1:] == ["bulk"]:
    import synth.optimise.batch  # what the bulk path has imported before it calls a kernel (pandas, scipy)
t0 = time.perf_counter()
import numpy as np
t1 = time.perf_counter()
from synth.kernels import main_spring
t2 = time.perf_counter()
out = {"import_numpy_s": t1 - t0, "import_synth_kernels_s": t2 - t1, "numba_after_import": "numba" in sys.modules}
t = time.perf_counter(); import numba; out["import_numba_s"] = time.perf_counter() - t
t = time.perf_counter(); main_spring.load_kernels(); out["load_kernel_module_s"] = time.perf_counter() - t
opts = main_spring.spring_options(E_mpa=206000, Rm_mpa=2004, sigma_y_mpa=1763.5, sigma_A0_mpa=701.4, b_mm=2.3, h_mm=2.3,
                        round_wire=True, mbd_mm=np.arange(30.0, 50.0))
keys = main_spring.spring_keys(spring_torque_nominal_nm=np.linspace(0.5, 3, 8), housing_height_mm=9.0, housing_outer_diameter_mm=50.0,
                     housing_inner_diameter_mm=30.0, stiffness_nm_per_deg=0.02, torque_tolerance_pct=5, theta_pp_deg=16)
calls = [("margins", lambda p: main_spring.margins(keys, opts, parallel=p)),
         ("first_feasible", lambda p: main_spring.first_feasible(keys, opts, parallel=p)),
         ("max_min_margin", lambda p: main_spring.max_min_margin(keys, opts, parallel=p))]
for par in (False, True):
    for name, fn in calls:
        t = time.perf_counter(); fn(par); out[name + ("_parallel" if par else "") + "_first_call_s"] = time.perf_counter() - t
print(json.dumps(out))
"""


def _child(cache_dir: str, bulk: bool = False) -> dict:
    env = {**os.environ, "PYTHONPATH": str(ROOT), "NUMBA_CACHE_DIR": cache_dir}
    cmd = [sys.executable, "-c", _CHILD] + (["bulk"] if bulk else [])
    r = subprocess.run(cmd, env=env, capture_output=True, text=True, timeout=600)
    if r.returncode:
        raise RuntimeError(r.stderr)
    return json.loads(r.stdout.strip().splitlines()[-1])


def _wall(cmd: list[str], runs: int) -> float:
    ts = []
    for _ in range(runs):
        t = time.perf_counter()
        subprocess.run(cmd, capture_output=True, check=True, env={**os.environ, "PYTHONPATH": str(ROOT)})
        ts.append(time.perf_counter() - t)
    return statistics.median(ts)


def numba_costs(runs: int) -> None:
    with tempfile.TemporaryDirectory() as cache:  # an empty numba cache: the first child compiles, the others load
        cold = _child(cache)
        bare = [_child(cache) for _ in range(runs)]
        bulk = [_child(cache, bulk=True) for _ in range(runs)]
    keys = [k for k in cold if k != "numba_after_import"]
    med = {k: statistics.median(w[k] for w in bare) for k in keys}
    medb = {k: statistics.median(w[k] for w in bulk) for k in keys}
    numpy_wall = _wall([sys.executable, "-c", "import numpy"], runs)
    numba_wall = _wall([sys.executable, "-c", "import numpy, numba"], runs)
    print("## numba costs per process (fresh processes; cached: median of %d)\n" % runs)
    print(f"Whole processes: `python -c \"import numpy\"` {numpy_wall:.3f} s, `python -c \"import numpy, numba\"` "
          f"{numba_wall:.3f} s. `import synth.kernels` imports numba: {cold['numba_after_import']}.\n")
    print("| step | empty cache (compiles) s | cached, bare process s | cached, after `synth.optimise` (the bulk path) s |")
    print("|---|---|---|---|")
    label = {"import_synth_kernels_s": "`import synth.kernels.main_spring` (pandas, synth.model; not numba)",
             "import_numba_s": "`import numba`", "load_kernel_module_s": "load the kernel module (decorators)"}
    tot = [0.0, 0.0, 0.0]
    for k in keys:
        if k == "import_numpy_s":
            continue
        name = label.get(k, f"first call `{k[:-len('_first_call_s')]}`")
        print(f"| {name} | {cold[k]:.3f} | {med[k]:.3f} | {medb[k]:.3f} |")
        if k != "import_synth_kernels_s" and "parallel" not in k:
            tot = [tot[0] + cold[k], tot[1] + med[k], tot[2] + medb[k]]
    print(f"| **once per process: import numba, the module, the three serial kernels' first calls** | "
          f"{tot[0]:.3f} | {tot[1]:.3f} | {tot[2]:.3f} |")
    print()


# --------------------------------------------------------------------------------------- keys of generated applications


def sample(n_apps: int, seed: int):
    """Spring keys of the core-feasible cores of ``n_apps`` generated applications, as the bulk engine builds
    them (:class:`synth.optimise.batch.Batch`: the distinct keys of every feasible core row, each application's
    catalog springs of its mean-diameter range in cost order)."""
    from synth.optimise.batch import Batch
    t0 = time.perf_counter()
    b = Batch(generate(n_apps, seed=seed), Settings(fidelity="screening"))
    rows = np.flatnonzero(b.core_ok)
    keys, _ = b.springs.keys(rows)
    lists, list_of, _, _, _ = b.springs.app_lists({"cost": 1.0})
    app = np.asarray(keys["app"], dtype=np.int64)
    kk = main_spring.keys_of_rows(b.apps, keys)
    grp = list_of[app]
    keep = np.flatnonzero(grp >= 0)   # applications whose range holds springs
    prep = time.perf_counter() - t0
    return kk.take(keep), b.springs.options(), lists, grp[keep], prep, app[keep]


def _warm(keys, options) -> None:
    """Load every kernel (serial and parallel) once, so no timing below includes numba's load or compile."""
    k = keys.take(np.arange(2))
    for par in (False, True):
        main_spring.margins(k, options, parallel=par)
        main_spring.first_feasible(k, options, parallel=par)
        main_spring.max_min_margin(k, options, parallel=par)


def _best(fn, repeat):
    best, out = np.inf, None
    for _ in range(repeat):
        t = time.perf_counter()
        out = fn()
        best = min(best, time.perf_counter() - t)
    return best, out


# --------------------------------------------------------------------------------------- 2. pairs/s


def pairs_table(keys, options, orders, key_group, repeat: int) -> None:
    n = len(keys)
    full = sum(len(orders[g]) for g in key_group)  # pairs of the whole table (each key x its application's springs)
    rows = []

    chunks = [keys.take(np.arange(lo, min(lo + 100, n))) for lo in range(0, n, 100)]  # (a): 56 bytes per pair
    buf = np.empty((100, len(options), len(main_spring.MARGIN_NAMES)))

    def margins_all(engine, parallel=False):
        for sub in chunks:
            main_spring.margins(sub, options, engine=engine, parallel=parallel, out=buf[:len(sub)] if engine == "numba" else None)
        return n * len(options)

    _warm(keys, options)
    for label, fn in [
        ("(a) margins (every key x every catalog spring)", lambda e, p: margins_all(e, p)),
        ("(b) first feasible in cost order", lambda e, p: int(main_spring.first_feasible(
            keys, options, orders, key_group=key_group, tol=FEAS_TOL, engine=e, parallel=p).visited.sum())),
        ("(c) max-min margin (nearest design)", lambda e, p: int(main_spring.max_min_margin(
            keys, options, orders, key_group=key_group, engine=e, parallel=p).visited.sum())),
        ("(d) any feasible", lambda e, p: int(main_spring.any_feasible(
            keys, options, orders, key_group=key_group, tol=FEAS_TOL, engine=e, parallel=p).visited.sum())),
    ]:
        t_np, pairs_np = _best(lambda: fn("numpy", False), 1)
        t_nb, pairs_nb = _best(lambda: fn("numba", False), repeat)
        t_par, _ = _best(lambda: fn("numba", True), repeat)
        rows.append((label, "numpy (reference, blocks)", t_np, pairs_np, 1.0))
        rows.append((label, "numba", t_nb, pairs_nb, t_np / t_nb))
        rows.append((label, "numba parallel=True", t_par, pairs_nb, t_np / t_par))
    print(f"## (a)-(d): {n} spring keys x their applications' catalog springs ({full:,} pairs in the table; "
          f"(a) uses all {len(options)} union options)\n")
    print("| kernel | engine | seconds | pairs examined | pairs/s | keys/s | table pairs/s | speed-up vs numpy |")
    print("|---|---|---|---|---|---|---|---|")
    for label, eng, t, pairs, ratio in rows:
        table = n * len(options) if label.startswith("(a)") else full
        print(f"| {label} | {eng} | {t:.4f} | {pairs:,} | {pairs / t:.3g} | {n / t:.3g} | {table / t:.3g} | {ratio:.1f} |")
    print("\nPairs examined: numpy, the pairs the reference evaluated (whole blocks); numba (a) and (c), the pairs "
          "whose margins were computed (at least the yield margin); numba (b) and (d), the options each key's scan "
          "reached, most of them settled by one comparison with the option's exact installation-torque threshold "
          "(so their pairs/s is not a physics rate: (a) is). Table pairs/s: the key x option table covered per second.\n")


# --------------------------------------------------------------------------------------- 3. applications/s


def apps_table(keys, options, orders, key_group, n_apps, n_numpy, prep, repeat, app) -> None:
    _warm(keys, options)
    rows = []
    t_nb, r_nb = _best(lambda: main_spring.first_feasible(keys, options, orders, key_group=key_group, tol=FEAS_TOL), repeat)
    rows.append(("numba", n_apps, len(keys), t_nb, int(r_nb.visited.sum())))
    t_par, r_par = _best(lambda: main_spring.first_feasible(keys, options, orders, key_group=key_group, tol=FEAS_TOL,
                                                  parallel=True), repeat)
    rows.append(("numba parallel=True", n_apps, len(keys), t_par, int(r_par.visited.sum())))
    sel = np.flatnonzero(app < n_numpy)
    sub = keys.take(sel)
    t_np, r_np = _best(lambda: main_spring.first_feasible(sub, options, orders, key_group=key_group[sel],
                                                tol=FEAS_TOL, engine="numpy"), 1)
    rows.append(("numpy (reference, blocks)", n_numpy, len(sub), t_np, int(r_np.visited.sum())))
    same = np.array_equal(r_np.index, r_nb.index[sel]) and np.array_equal(r_par.index, r_nb.index)
    with_keys = np.unique(app).size
    print(f"## Spring subsystem of {n_apps} generated applications (first feasible in cost order, early exit)\n")
    print(f"{len(keys):,} spring keys ({len(keys) / n_apps:.1f} per application; {with_keys} applications have a "
          f"core-feasible core), {len(options):,} union options. Building the spaces and core evaluations "
          f"beforehand: {prep:.1f} s ({n_apps / prep:.0f} applications/s, not part of the table). "
          f"Same chosen springs numba / parallel / numpy: {'yes' if same else 'NO'}.\n")
    print("| engine | applications | keys | seconds | pairs examined | applications/s | speed-up vs numpy |")
    print("|---|---|---|---|---|---|---|")
    rate_np = n_numpy / t_np
    for eng, na, nk, t, pairs in rows:
        print(f"| {eng} | {na} | {nk:,} | {t:.4f} | {pairs:,} | {na / t:,.0f} | {na / t / rate_np:.1f} |")
    print()


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--apps", type=int, default=2000, help="applications of the spring-subsystem sample")
    ap.add_argument("--pair-apps", type=int, default=50, help="applications whose keys make the (a)-(d) table")
    ap.add_argument("--numpy-apps", type=int, default=200, help="applications the numpy twin runs in table 3")
    ap.add_argument("--runs", type=int, default=3, help="fresh processes / repeats per timing")
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--quick", action="store_true", help="small sizes (smoke test)")
    args = ap.parse_args(argv)
    if args.quick:
        args.apps, args.pair_apps, args.numpy_apps, args.runs = 20, 4, 4, 1
    print(f"# Main-spring kernels benchmark (generated applications, seed {args.seed}; "
          f"numba threads {os.environ.get('NUMBA_NUM_THREADS', os.cpu_count())})\n")
    numba_costs(args.runs)
    keys, options, orders, kg, _, _ = sample(args.pair_apps, args.seed)
    pairs_table(keys, options, orders, kg, args.runs)
    keys, options, orders, kg, prep, app = sample(args.apps, args.seed)
    apps_table(keys, options, orders, kg, args.apps, min(args.numpy_apps, args.apps), prep, args.runs, app)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
