"""The black-box solver against the exact optimum: its speed-accuracy curve; prints markdown tables.

    .venv/bin/python benchmarks/bench_blackbox.py [--apps 200] [--budgets 25,50,100,200] [--samplers tpe,random]
                                                  [--objective standard] [--grid] [--seed 0]

For the thesis cases, the embedded default case and generated applications
(synth.data.generated_applications, seed 0): enumerate's answer (the exact
optimum, or the nearest design when none is feasible) and, at each trial
budget, the black-box solver's (``synth.optimise.solvers.blackbox``), run one
after the other in one process (the machine is shared: compare the times side
by side, not across runs). Reported:

* objective reached: every tier of the objective no worse than the optimum's
  beyond 1 % (a part count equal or lower, a cost at most 1 % above); for an
  application without a feasible design, the nearest design's smallest margin
  within 1 % of enumerate's (or above it: a continuous design may pass where
  every grid design fails);
* gap: the relative difference of the last tier (cost) where the optimum is feasible and the tiers before it
  are equal (positive: dearer than the optimum), with the number of applications where it compares (a result
  with another part count has no cost gap: it is counted as not reached);
* feasible found: a feasible design where enumerate finds one;
* times: the whole ``solve`` call, after one warm-up solve (imports, caches), wall and CPU seconds of the
  process (on a shared machine the wall time grows with the load; the CPU time is what the call costs).

``--grid`` adds the runs on the exact solvers' grids only (``continuous=False``); ``--samplers tpe,random``
measures what the TPE sampler buys against random proposals with the same budget.
"""

from __future__ import annotations

import argparse
import statistics
import sys
import time
import warnings
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from synth.data import case_path  # noqa: E402
from synth.data.generated_applications import generate  # noqa: E402
from synth.optimise import solve  # noqa: E402
from synth.io.documents import load_input  # noqa: E402

LIMIT_S = 2.0
TOL = 0.01


def smallest_margin(r) -> float:
    """The smallest margin of every checked, non-advisory constraint (what the nearest design maximises)."""
    return min(r.margins.values(), default=float("inf"))


def reached(ref, r, order) -> bool:
    """Whether result ``r`` reaches the exact answer ``ref`` within 1 % (see the module docstring)."""
    if ref.status == "optimal":
        if r.status not in ("optimal", "feasible"):
            return False
        for name in order:
            a, b = r.objectives[name], ref.objectives[name]
            if name == "margin":
                if a < b - TOL * max(abs(b), 1e-9):
                    return False
            elif a > b + TOL * max(abs(b), 1e-9):
                return False
            elif a < b - TOL * max(abs(b), 1e-9):
                return True
        return True
    if r.status in ("optimal", "feasible"):
        return True
    m, mr = smallest_margin(r), smallest_margin(ref)
    return m >= mr - TOL * abs(mr)


def gap(ref, r, order) -> float | None:
    """The relative gap [%] of the last tier (cost) of a feasible result whose tiers before it equal the
    optimum's (positive: dearer than the optimum); None where not comparable (no feasible optimum or result,
    another part count)."""
    if ref.status != "optimal" or r.status not in ("optimal", "feasible"):
        return None
    for name in order[:-1]:
        if abs(r.objectives[name] - ref.objectives[name]) > 1e-9 * max(1.0, abs(ref.objectives[name])):
            return None
    last = order[-1]
    sign = -1.0 if last == "margin" else 1.0
    return 100.0 * sign * (r.objectives[last] - ref.objectives[last]) / max(abs(ref.objectives[last]), 1e-12)


def describe(r, order) -> str:
    if r.status in ("optimal", "feasible"):
        return " / ".join(f"{r.objectives[k]:.4g}" for k in order)
    return f"nearest {smallest_margin(r):+.4f}"


def timed(d, objective, solver, **kw):
    """``(result, wall seconds, CPU seconds of this process)``: on a shared machine the CPU time is what the
    call costs, the wall time what it took."""
    t0, c0 = time.perf_counter(), time.process_time()
    r = solve(d, objective, solver, **kw)
    return r, time.perf_counter() - t0, time.process_time() - c0


def run(apps, objective, budgets, samplers, modes, seed):
    from synth.optimise.objectives import Objective
    order = Objective.parse(objective).order
    solve(apps[0][1], objective, "blackbox", n_trials=20)   # warm-up: imports, catalog caches
    rows = []
    for name, d in apps:
        ref, t_ref, c_ref = timed(d, objective, "enumerate", relax=False)
        row = {"name": name, "ref": ref, "t_ref": t_ref, "c_ref": c_ref, "bb": {}}
        for smp in samplers:
            for cont in modes:
                for b in budgets:
                    row["bb"][(smp, cont, b)] = timed(d, objective, "blackbox", n_trials=b, sampler=smp,
                                                      continuous=cont, seed=seed)
        rows.append(row)
    return rows, order


def _pct(n: int, of: int) -> str:
    return f"{n} of {of} ({100 * n / max(of, 1):.1f} %)"


def tables(rows, order, budgets, samplers, modes, thesis):
    out = []
    for smp in samplers:
        for cont in modes:
            label = f"{smp}, {'continuous' if cont else 'grid'}"
            out += [f"### sampler {label}: cases (time: wall / CPU seconds)", "",
                    "| case | enumerate | time [s] | " + " | ".join(f"{b} trials | time [s]" for b in budgets) + " |",
                    "|---|---|---|" + "---|---|" * len(budgets)]
            for row in rows[:thesis]:
                cells = [row["name"], describe(row["ref"], order), f"{row['t_ref']:.2f} / {row['c_ref']:.2f}"]
                for b in budgets:
                    r, t, c = row["bb"][(smp, cont, b)]
                    cells += [describe(r, order) + ("" if reached(row["ref"], r, order) else " (not reached)"),
                              f"{t:.2f} / {c:.2f}"]
                out.append("| " + " | ".join(cells) + " |")
            gen = rows[thesis:]
            if not gen:
                continue
            feas = [row for row in gen if row["ref"].status == "optimal"]
            out += ["", f"### sampler {label}: {len(gen)} generated applications ({len(feas)} feasible by enumerate)",
                    "", f"| trials per study | objective reached | cost gap mean, max [%] (where comparable) | feasible found | feasible found "
                    f"within {LIMIT_S:g} s (wall / CPU) | time mean, p95, max [s] (wall) | time mean, p95, max [s] (CPU) |",
                    "|---|---|---|---|---|---|---|"]
            for b in budgets:
                res = {row["name"]: row["bb"][(smp, cont, b)] for row in gen}
                ok = sum(reached(row["ref"], res[row["name"]][0], order) for row in gen)
                ff = [row for row in feas if res[row["name"]][0].status in ("optimal", "feasible")]
                fast_w = sum(res[row["name"]][1] <= LIMIT_S for row in ff)
                fast_c = sum(res[row["name"]][2] <= LIMIT_S for row in ff)

                def spread(i):
                    ts = sorted(x[i] for x in res.values())
                    return f"{statistics.mean(ts):.2f}, {ts[int(0.95 * (len(ts) - 1))]:.2f}, {ts[-1]:.2f}"
                gaps = [gap(row["ref"], res[row["name"]][0], order) for row in gen]
                gaps = [g for g in gaps if g is not None]
                gap_cell = f"{statistics.mean(gaps):+.2f}, {max(gaps):+.2f} ({len(gaps)})" if gaps else "-"
                out.append(f"| {b} | {_pct(ok, len(gen))} | {gap_cell} | "
                           f"{_pct(len(ff), len(feas))} | {_pct(fast_w, len(feas))} / "
                           f"{_pct(fast_c, len(feas))} | {spread(1)} | {spread(2)} |")
            tw = sorted(row["t_ref"] for row in gen)
            tc = sorted(row["c_ref"] for row in gen)
            out.append(f"| enumerate | exact | 0 | {len(feas)} | | {statistics.mean(tw):.2f}, {tw[int(0.95 * (len(tw) - 1))]:.2f}, "
                       f"{tw[-1]:.2f} | {statistics.mean(tc):.2f}, {tc[int(0.95 * (len(tc) - 1))]:.2f}, {tc[-1]:.2f} |")
            b = budgets[-1]
            miss = [row for row in gen if not reached(row["ref"], row["bb"][(smp, cont, b)][0], order)
                    or (row in feas and row["bb"][(smp, cont, b)][1] > LIMIT_S)]
            if miss:
                out += ["", f"The rest at {b} trials (objective not reached, or feasible found after {LIMIT_S:g} s "
                        "wall):", "", "| application | enumerate | black-box | time [s] (wall / CPU) |", "|---|---|---|---|"]
                for row in miss:
                    r, t, c = row["bb"][(smp, cont, b)]
                    out.append(f"| {row['name']} | {describe(row['ref'], order)} | {describe(r, order)} | "
                               f"{t:.2f} / {c:.2f} |")
            out.append("")
    return "\n".join(out)


def reproducible(apps, objective, budget, seed) -> list:
    """Whether two runs with the same seed give the same design (the thesis and default cases)."""
    out = []
    for name, d in apps:
        a = solve(d, objective, "blackbox", n_trials=budget, seed=seed)
        b = solve(d, objective, "blackbox", n_trials=budget, seed=seed)
        out.append((name, a.parts == b.parts and a.status == b.status))
    return out


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--apps", type=int, default=200)
    p.add_argument("--budgets", default="25,50,100,200")
    p.add_argument("--samplers", default="tpe")
    p.add_argument("--objective", default="standard")
    p.add_argument("--grid", action="store_true", help="also search the exact solvers' grids only")
    p.add_argument("--seed", type=int, default=0)
    a = p.parse_args(argv)
    warnings.simplefilter("ignore")
    budgets = [int(x) for x in a.budgets.split(",")]
    samplers = a.samplers.split(",")
    modes = [True, False] if a.grid else [True]
    default = Path(__file__).resolve().parents[1] / "synth" / "data" / "default_case.yaml"
    apps = [("default case", load_input(default)), ("thesis case 1", load_input(case_path("case1"))),
            ("thesis case 1 as run", load_input(case_path("case1_as_run"))),
            ("thesis case 3", load_input(case_path("case3")))]
    thesis = len(apps)
    apps += [(f"generated {i}", d) for i, d in enumerate(generate(a.apps, seed=0))]
    t0 = time.perf_counter()
    rows, order = run(apps, a.objective, budgets, samplers, modes, a.seed)
    print(tables(rows, order, budgets, samplers, modes, thesis))
    rep = reproducible(apps[:thesis], a.objective, budgets[-1], a.seed)
    print("| case | same design from the same seed |\n|---|---|\n" + "\n".join(f"| {n} | {'yes' if ok else 'NO'} |"
                                                                          for n, ok in rep))
    print(f"\n{len(apps)} applications ({thesis} cases + {a.apps} generated, seed 0), objective {a.objective}, "
          f"black-box seed {a.seed}; total {time.perf_counter() - t0:.0f} s")


if __name__ == "__main__":
    main()
