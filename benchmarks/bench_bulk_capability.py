"""``synth bulk --capability``: throughput, and every row against ``synth design --capability`` (issue 34).

Generated applications (``synth.data.generated_applications.generate``) through the bulk engine with a capability
target in the run's settings (:func:`synth.bulk.engine.screen_applications`), then a sample of rows against the
design's own answer for that application (:func:`synth.optimise.honour.solve_honouring` with ``robust=``, as
``synth design --capability T --samples N`` calls it; ``explain=False`` on both sides: the same design, without the
search of the value that would allow one). Prints a table: applications/s, how many rows take the chunk-wide
shortcut (no design under the made joint), how many meet the target, and the rows that differ (parts, verdict,
capability verdict).

    PYTHONPATH=. python benchmarks/bench_bulk_capability.py --apps 2000 --sample 50 --capability 1.33

``--engines``: instead, the same applications twice in one run, the production samples' axial group on the numpy
reference and then on the compiled twin (:data:`synth.robust.sampling.AXIAL_ENGINE`), each with applications/s,
CPU, the candidate designs sampled (capabilities assembled) and the production samples evaluated, and the cells
of the two result tables that differ (timings aside; the claim: none).

    PYTHONPATH=. python benchmarks/bench_bulk_capability.py --engines --apps 8
"""

from __future__ import annotations

import argparse
import sys
import time
import warnings


def main(argv=None) -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--apps", type=int, default=2000)
    p.add_argument("--sample", type=int, default=50)
    p.add_argument("--capability", type=float, default=1.33)
    p.add_argument("--samples", type=int, default=1024)
    p.add_argument("--seed", type=int, default=0)
    p.add_argument("--fidelity", default="full")
    p.add_argument("--engines", action="store_true", help="the samples' axial engine, numpy against numba")
    a = p.parse_args(argv)
    if a.engines:
        return engines_ab(a)
    warnings.simplefilter("ignore")
    from synth.bulk.engine import screen_applications
    from synth.data.generated_applications import generate
    from synth.design.settings import Settings
    from synth.design.space import PART_KEYS
    from synth.optimise.batch import any_feasible
    from synth.optimise.honour import solve_honouring
    from synth.robust.synthesis import robust_for
    from synth.robust.sampling import production
    from synth.robust.settings import RobustSettings
    rs = RobustSettings(capability=a.capability, samples=a.samples)
    settings = Settings(fidelity=a.fidelity, capability=rs)
    apps = generate(a.apps, seed=a.seed)
    screen_applications(apps[:2], objective="standard", settings=settings.replace(capability=None))  # warm
    made = any_feasible(apps, production(settings))
    t0 = time.perf_counter()
    df = screen_applications(apps, objective="standard", settings=settings, diagnose=False)
    wall = time.perf_counter() - t0
    verdicts = df["capability_verdict"].value_counts()
    print(f"| {a.apps} applications, Ppk >= {a.capability:g}, {a.samples} samples, fidelity {a.fidelity} | value |")
    print("|---|---|")
    print(f"| wall [s] | {wall:.1f} |")
    print(f"| applications/s | {a.apps / wall:.3g} |")
    print(f"| rows by the shortcut (no design under the made joint) | {sum(not m for m in made)} |")
    print(f"| rows through the robust synthesis | {sum(bool(m) for m in made)} |")
    print(f"| rows meeting the target (PASS) / not (FAIL) | {int(verdicts.get('PASS', 0))} / "
          f"{int(verdicts.get('FAIL', 0))} |")
    step = max(1, a.apps // max(1, a.sample))
    idx = list(range(0, a.apps, step))[:a.sample]
    differ, tie = [], 0
    t1 = time.perf_counter()
    for i in idx:
        r = solve_honouring(apps[i], "standard", "enumerate", settings=settings.replace(capability=None),
                            explain=False, robust=robust_for(rs))
        row = df.iloc[i]
        keys = [k for k in PART_KEYS if r.parts.get(k) != row[f"part_{k}"]]
        if r.verdict != row["verdict"]:
            keys.append("verdict")
        if ("PASS" if r.stats.get("robust_found") else "FAIL") != row["capability_verdict"]:
            keys.append("capability_verdict")
        if keys:
            same_obj = (abs(r.objectives.get("standard", 0) - row["objective_standard"]) < 1e-9
                        and abs(r.objectives.get("cost", 0) - row["objective_cost_eur"]) < 1e-6)
            tie += bool(same_obj)
            differ.append((i, keys, "objective tie" if same_obj else ""))
    print(f"| rows compared with synth design --capability (every {step}th) | {len(idx)} ({time.perf_counter() - t1:.0f} s) |")
    print(f"| rows differing | {len(differ)} (of which at an objective tie: {tie}) |")
    for i, keys, why in differ:
        print(f"|   row {i} | {', '.join(keys)} {why} |")
    return 0


def _runs(apps, settings, count) -> tuple:
    """``(timings, frames)``: the applications with the samples' axial group on numpy, then on numba."""
    from synth.bulk.engine import screen_applications
    from synth.robust import sampling
    sampling.AXIAL_ENGINE = "numba"  # warm: the design space, the kernels (the axial twins on a robust row's samples)
    screen_applications(apps[:2], objective="standard", settings=settings, diagnose=False)
    out, frames = [], []
    for engine in ("numpy", "numba"):
        sampling.AXIAL_ENGINE = engine
        count.update(candidates=0, samples=0)
        t0, c0 = time.perf_counter(), time.process_time()
        frames.append(screen_applications(apps, objective="standard", settings=settings, diagnose=False))
        out.append((engine, time.perf_counter() - t0, time.process_time() - c0, dict(count)))
    return out, frames


def engines_ab(a) -> int:
    """The samples' axial engine A (numpy reference) against B (compiled twin) on the same applications."""
    warnings.simplefilter("ignore")
    import numpy as np

    from synth.data.generated_applications import generate
    from synth.design.settings import Settings
    from synth.robust import capability, sampling
    from synth.robust.settings import RobustSettings
    settings = Settings(fidelity=a.fidelity, capability=RobustSettings(capability=a.capability, samples=a.samples))
    apps = generate(a.apps, seed=a.seed)
    count = {"candidates": 0, "samples": 0}
    assemble, deviations, engine = capability._assemble, sampling.evaluate_deviations, sampling.AXIAL_ENGINE

    def counted_assemble(*args, **kw):
        count["candidates"] += 1
        return assemble(*args, **kw)

    def counted_deviations(base, dev, *args, **kw):
        count["samples"] += len(next(iter(dev.values()))) if dev else 1
        return deviations(base, dev, *args, **kw)
    capability._assemble = counted_assemble
    capability.evaluate_deviations = sampling.evaluate_deviations = counted_deviations
    try:
        out, frames = _runs(apps, settings, count)
    finally:  # the functions the counts wrap, and the module's engine, as they were
        capability._assemble, capability.evaluate_deviations = assemble, deviations
        sampling.evaluate_deviations, sampling.AXIAL_ENGINE = deviations, engine
    keep = [c for c in frames[0].columns if "time" not in c]
    x, y = (f[keep] for f in frames)
    same = ((x == y) | (x.isna() & y.isna())).to_numpy()  # NaN (an empty cell) equals NaN
    x, y = x.to_numpy(), y.to_numpy()
    cells = int(np.sum(~same))
    print(f"| {a.apps} applications, Ppk >= {a.capability:g}, {a.samples} samples, fidelity {a.fidelity}: "
          f"the samples' axial engine | wall [s] | CPU [s] | applications/s | candidates sampled | "
          f"production samples |")
    print("|---|---|---|---|---|---|")
    for name, wall, cpu, c in out:
        print(f"| {name} | {wall:.1f} | {cpu:.1f} | {a.apps / wall:.3g} | {c['candidates']} | {c['samples']:,} |")
    print(f"| CPU ratio numpy / numba | | {out[0][2] / out[1][2]:.2f}x | | | |")
    print(f"| result cells that differ (of {x.size}, timings aside) | {cells} | | | | |")
    for j in np.flatnonzero((~same).any(axis=0)):
        i = int(np.flatnonzero(~same[:, j])[0])
        print(f"|   {keep[j]} (row {i}) | {str(x[i, j])[:60]} | {str(y[i, j])[:60]} | | | |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
