"""``synth bulk --capability``: throughput, and every row against ``synth design --capability`` (issue 34).

Generated applications (``synth.data.generated_applications.generate``) through the bulk engine with a capability
target in the run's settings (:func:`synth.bulk.engine.screen_applications`), then a sample of rows against the
design's own answer for that application (:func:`synth.optimise.honour.solve_honouring` with ``robust=``, as
``synth design --capability T --samples N`` calls it; ``explain=False`` on both sides: the same design, without the
search of the value that would allow one). Prints a table: applications/s, how many rows take the chunk-wide
shortcut (no design under the made joint), how many meet the target, and the rows that differ (parts, verdict,
capability verdict).

    PYTHONPATH=. python benchmarks/bench_bulk_capability.py --apps 2000 --sample 50 --capability 1.33
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
    a = p.parse_args(argv)
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


if __name__ == "__main__":
    sys.exit(main())
