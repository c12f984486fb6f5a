"""Benchmark of the production capability (issue 22): one design's capability against its nominal check, the
small-probability method against brute force, the robust synthesis against the nominal one, the bulk capability.

    .venv/bin/python benchmarks/bench_robust.py [--apps 200] [--repeat 5] [--quick]

Prints markdown tables, every ratio measured side by side in one run (the machine is shared: wall time and the
process's CPU time are both shown):

1. one design (the demo's): the nominal evaluation (one row), 10,000 identical rows of the evaluator, the capability
   from 10,000 samples (Monte Carlo only: Ppk and P(violation) of every check) and the full capability (worst case,
   RSS, contributors, importance sampling); the target is < 50 ms for the 10,000-sample capability;
2. a probability of about 1e-3 (the demo's bolt stress under the tightening scatter): FORM + importance sampling
   (2000 samples) against brute-force Monte Carlo (131072 samples), and OpenTURNS doing the same two steps when it
   is installed (it is not a dependency: ``pip install --target DIR openturns`` and ``PYTHONPATH=DIR``);
3. the design scene: the nominal synthesis (``standard,cost,margin``) against the robust one (``--capability 1.33``);
4. ``--apps`` generated applications: the bulk capability of their chosen designs (1024 samples each), in one
   process and in two, against the nominal bulk screening of the same applications (target: >= 100 applications/s
   on 2 cores).
"""

from __future__ import annotations

import argparse
import statistics
import sys
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from synth.robust.capability import capability, clopper_pearson  # noqa: E402
from synth.robust.sampling import base_of, evaluate_u, sobol_u  # noqa: E402
from synth.robust.settings import RobustSettings  # noqa: E402


def _time(fn, repeat: int) -> tuple:
    """``(median wall s, median CPU s, last value)`` over ``repeat`` runs."""
    walls, cpus, value = [], [], None
    for _ in range(repeat):
        w, c = time.perf_counter(), time.process_time()
        value = fn()
        walls.append(time.perf_counter() - w)
        cpus.append(time.process_time() - c)
    return statistics.median(walls), statistics.median(cpus), value


def one_design(repeat: int) -> list:
    from synth.design.verify import evaluate_design
    from synth.optimise import solve
    from synth.scenes.demo import default_input
    d = default_input()
    r = solve(d, "standard,cost,margin")
    base = base_of(d, r.parts)
    n = 10_000
    rows = {t: {k: np.repeat(np.asarray(v), n) for k, v in cols.items()} for t, cols in base.attrs.items()}
    apps_n = base.apps.subset(np.zeros(n, dtype=np.int64))
    rs = RobustSettings(samples=n)
    capability(base, rs, rare=False, details=False)  # warm: imports, the Sobol points
    cases = [("nominal evaluation of the design (1 row)", lambda: evaluate_design(base.apps, base.attrs, detail=False), 1),
             (f"evaluator, {n} identical rows", lambda: evaluate_design(apps_n, rows, detail=False), n),
             (f"capability, {n} samples (Ppk, P of every check)",
              lambda: capability(base, rs, rare=False, details=False), n),
             (f"capability, {n} samples, full (worst case, RSS, contributors, importance sampling)",
              lambda: capability(base, rs), n)]
    out = ["| what | rows | wall [ms] | CPU [ms] | ratio to the nominal row (wall) |", "|---|---|---|---|---|"]
    ref = None
    for name, fn, rows_ in cases:
        w, c, _ = _time(fn, repeat)
        ref = ref or w
        out.append(f"| {name} | {rows_} | {1e3 * w:.1f} | {1e3 * c:.1f} | {w / ref:.1f} |")
    return out


def rare(repeat: int) -> list:
    from synth.optimise import solve
    from synth.robust.rare import form_is
    from synth.robust.tolerances import tolerances
    from synth.scenes.demo import default_input
    d = default_input()
    tab = {k: v for k, v in tolerances().items() if k in ("bolt_preload", "spring_torque")}
    base = base_of(d, solve(d, "standard,cost,margin").parts, table=tab)
    dim = len(base.scatter)

    def brute():
        m = evaluate_u(base, sobol_u(131072, dim, 5), ("bolt_yield",)).margins["bolt_yield"]
        k = int(np.sum(m < 0))
        return k / len(m), clopper_pearson(k, len(m)), len(m)

    def isamp():
        r = form_is(lambda p: evaluate_u(base, p, ("bolt_yield",)).margins["bolt_yield"][:, None], dim, n_is=2000,
                    seed=2)[0]
        return r["p"], (r["p_lo"], r["p_hi"]), r["evaluations"]
    def with_openturns():  # the same two steps with OpenTURNS (FORM with Cobyla, then importance sampling), if installed
        import openturns as ot
        calls = [0]

        def fs(x):
            calls[0] += len(x)
            return evaluate_u(base, np.asarray(x), ("bolt_yield",)).margins["bolt_yield"][:, None]
        event = ot.ThresholdEvent(ot.CompositeRandomVector(ot.PythonFunction(dim, 1, func_sample=fs),
                                                           ot.RandomVector(ot.Normal(dim))), ot.Less(), 0.0)
        form = ot.FORM(ot.Cobyla(), event, ot.Point(dim, 0.0))
        form.run()
        ot.RandomGenerator.SetSeed(2)
        dp = form.getResult().getStandardSpaceDesignPoint()
        sim = ot.ProbabilitySimulationAlgorithm(ot.StandardEvent(event), ot.ImportanceSamplingExperiment(
            ot.Normal(dp, ot.CovarianceMatrix(dim))))
        sim.setMaximumOuterSampling(1)
        sim.setBlockSize(2000)
        sim.setMaximumCoefficientOfVariation(-1)
        sim.run()
        r = sim.getResult()
        p, sd = r.getProbabilityEstimate(), r.getStandardDeviation()
        return p, (p - 1.96 * sd, p + 1.96 * sd), calls[0]
    out = ["| method | P(violation) | 95 % interval | evaluations | wall [s] | CPU [s] |", "|---|---|---|---|---|---|"]
    methods = [("Monte Carlo, 131072 Sobol samples", brute), ("FORM + importance sampling (2000), synth.robust.rare", isamp)]
    try:
        import openturns  # noqa: F401
        methods.append(("OpenTURNS: FORM (Cobyla) + importance sampling (2000)", with_openturns))
    except ImportError:
        out.append("| OpenTURNS | not installed: the comparison row is skipped | | | | |")
    for name, fn in methods:
        w, c, (p, (lo, hi), ev) = _time(fn, max(1, repeat // 2))
        out.append(f"| {name} | {p:.3g} | [{lo:.3g}, {hi:.3g}] | {ev} | {w:.3f} | {c:.3f} |")
    return out


def synthesis(repeat: int) -> list:
    from synth.optimise import solve
    from synth.robust.synthesis import robust_solve
    from synth.scenes.demo import default_input
    d = default_input()
    out = ["| synthesis of the demo | wall [s] | CPU [s] | candidates checked | result |", "|---|---|---|---|---|"]
    w0, c0, r0 = _time(lambda: solve(d, "standard,cost,margin"), repeat)
    out.append(f"| nominal (standard,cost,margin) | {w0:.2f} | {c0:.2f} | - | {r0.status} |")
    for samples in (2048, 8192):
        w, c, r = _time(lambda: robust_solve(d, "standard", rs=RobustSettings(capability=1.33, samples=samples),
                                             details=False), 1)
        out.append(f"| robust, Ppk >= 1.33, {samples} samples per candidate | {w:.2f} ({w / w0:.0f}x) | {c:.2f} | "
                   f"{r.stats['robust_candidates']} | {'meets' if not r.notes[-1].startswith('no catalog') else 'none meets'} |")
    return out


def main(argv=None) -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--apps", type=int, default=200)
    p.add_argument("--repeat", type=int, default=5)
    p.add_argument("--quick", action="store_true", help="small sizes (a smoke test)")
    a = p.parse_args(argv)
    if a.quick:
        a.apps, a.repeat = 12, 1
    print("## 1. One design: capability against the nominal evaluation\n")
    print("\n".join(one_design(a.repeat)))
    print("\n## 2. A probability of about 1e-3: importance sampling against brute force\n")
    print("\n".join(rare(a.repeat)))
    if not a.quick:
        print("\n## 3. Robust synthesis against the nominal synthesis\n")
        print("\n".join(synthesis(max(1, a.repeat // 2))))
    # the bulk's capability (each row re-selected for the target): benchmarks/bench_bulk_capability.py
    return 0


if __name__ == "__main__":
    sys.exit(main())
