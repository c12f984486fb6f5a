"""Benchmark of the catalog solvers; prints a markdown table.

    .venv/bin/python benchmarks/bench_solvers.py [--apps 50] [--blackbox-apps 8] [--trials 60]

For thesis cases 1 and 3 and generated applications (synth.data.generated_applications): each solver's
time, objective and gap to the enumeration optimum (objective: cost, then standardisation); how much the
thesis flowchart's greedy design loses against the optimum; candidates per second of enumerate.
"""

from __future__ import annotations

import argparse
import statistics
import sys
import time
import warnings
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from synth.data.generated_applications import generate  # noqa: E402
from synth.optimise import solve  # noqa: E402
from synth.data import case_path
from synth.io.documents import load_input  # noqa: E402

SOLVERS = ["enumerate", "milp-highs", "minlp", "milp-cvxpy", "blackbox", "flowchart"]


def run(apps, n_blackbox, trials):
    rows = {s: [] for s in SOLVERS}
    loss = []
    for i, (name, d) in enumerate(apps):
        ref = None
        for s in SOLVERS:
            if s == "blackbox" and i >= n_blackbox:
                continue
            kw = {"n_trials": trials, "fidelity": "screening"} if s == "blackbox" else ({} if s == "flowchart" else {"relax": False})
            t0 = time.perf_counter()
            r = solve(d, "cost", s, **kw)
            dt = time.perf_counter() - t0
            ok = r.status in ("optimal", "feasible", "baseline")
            val = r.objectives["cost"] if ok else None
            if s == "enumerate":
                ref = val
                rows[s].append((name, dt, val, 0.0 if ok else None, r.stats))
                std_opt = solve(d, "standard", "enumerate", relax=False).objectives["standard"] if ok else None
            else:
                gap = None if (val is None or ref is None) else (val - ref) / ref
                rows[s].append((name, dt, val, gap, r.stats))
            if s == "flowchart":
                loss.append((name, ref, val, std_opt, r.objectives["standard"] if ok else None))
    return rows, loss


def table(rows, loss, n_apps):
    out = ["| solver | applications | solved (feasible) | mean time [s] | max time [s] | max gap to optimum | optimum matched |",
           "|---|---|---|---|---|---|---|"]
    for s, rs in rows.items():
        if not rs:
            continue
        solved = sum(r[2] is not None for r in rs)
        gaps = [r[3] for r in rs if r[3] is not None]
        matched = sum(abs(g) < 1e-9 for g in gaps)
        out.append(f"| {s} | {len(rs)} | {solved} | {statistics.mean(r[1] for r in rs):.2f} | {max(r[1] for r in rs):.2f} | "
                   f"{(max(gaps) * 100 if gaps else float('nan')):+.2f} % | {matched} of {len(gaps)} |")
    out += ["", "| case | enumerate cost [EUR] | milp-highs | minlp | milp-cvxpy | flowchart |", "|---|---|---|---|---|---|"]
    for i, (name, *_rest) in enumerate(rows["enumerate"][:2]):
        vals = []
        for s in ("enumerate", "milp-highs", "minlp", "milp-cvxpy", "flowchart"):
            v = rows[s][i][2]
            vals.append("infeasible" if v is None else f"{v:.4f}")
        out.append(f"| {name} | " + " | ".join(vals) + " |")
    both = [x for x in loss if x[1] is not None and x[2] is not None]
    greedy_fail = sum(1 for x in loss if x[1] is not None and x[2] is None)
    out += ["", "| thesis flowchart against the optimum | value |", "|---|---|",
            f"| applications with a feasible optimum | {sum(1 for x in loss if x[1] is not None)} |",
            f"| greedy flowchart fails where an optimum exists | {greedy_fail} |"]
    if both:
        out.append(f"| mean extra cost of the greedy design | {statistics.mean((x[2] - x[1]) / x[1] for x in both) * 100:+.1f} % |")
        out.append(f"| mean extra non-standard parts (vs the standardisation optimum) | "
                   f"{statistics.mean(x[4] - x[3] for x in both):+.2f} |")
    st = [r[4] for r in rows["enumerate"] if "candidates_per_s" in r[4]]
    if st:
        out += ["", "| enumerate throughput | median |", "|---|---|",
                f"| whole-tensioner candidates covered per second (decomposed, exact) | {statistics.median(s['candidates_per_s'] for s in st):.3g} |",
                f"| physics evaluations (core + subsystem entries) per second of solve time | "
                f"{statistics.median(s['physics_evaluations'] / s.get('evaluation_time_s', s['time_s']) for s in st):.3g} |",
                f"| catalog product size (median) | {statistics.median(s['candidates'] for s in st):.3g} |"]
    return "\n".join(out)


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--apps", type=int, default=50)
    p.add_argument("--blackbox-apps", type=int, default=8)
    p.add_argument("--trials", type=int, default=60)
    a = p.parse_args(argv)
    warnings.simplefilter("ignore")
    apps = [("thesis case 1", load_input(case_path("case1"))),
            ("thesis case 3", load_input(case_path("case3")))]
    apps += [(f"generated {i}", d) for i, d in enumerate(generate(a.apps, seed=0))]
    t0 = time.perf_counter()
    rows, loss = run(apps, a.blackbox_apps, a.trials)
    print(table(rows, loss, len(apps)))
    print(f"\n{len(apps)} applications (cases 1 and 3 + {a.apps} generated, seed 0), objective cost; "
          f"blackbox on the first {a.blackbox_apps} with {a.trials} trials; total {time.perf_counter() - t0:.0f} s")


if __name__ == "__main__":
    main()
