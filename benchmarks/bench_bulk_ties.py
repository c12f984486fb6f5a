"""Benchmark of the bulk engine's margin tie-break (issue 34): on generated applications, how many bulk rows name
another design than ``synth design`` (its objective ``standard`` is ``standard,cost,margin``:
:func:`synth.optimise.objectives.with_margin_tiebreak`), how many rows the tie-break changes, and its time beside
the search's (process CPU seconds, one chunk).

    .venv/bin/python benchmarks/bench_bulk_ties.py [--n 2000] [--seed 0] [--fidelity screening] [--no-compare]

The comparison solves every application with the exact solver (about 0.5 s each): 2,000 rows take about 20
minutes of CPU. Prints markdown tables.
"""

from __future__ import annotations

import argparse
import math
import time

from synth.bulk import screen_applications
from synth.data.generated_applications import generate
from synth.design.evaluate import Settings
from synth.design.space import PART_KEYS
from synth.optimise import solve
from synth.optimise.batch import Batch
from synth.optimise.margin_ties import margin_ties
from synth.optimise.objectives import Objective, with_margin_tiebreak


def differences(row, r) -> list:
    """What differs between a bulk row and a synthesis result (empty: the same verdict, design and objectives)."""
    feasible = r.status == "optimal" and not r.failed()
    if bool(row["feasible"]) != feasible:
        return [("feasible", row["feasible"], r.status)]
    if not feasible:
        return []
    out = [(k, row[f"part_{k}"], r.parts.get(k)) for k in PART_KEYS if row[f"part_{k}"] != r.parts.get(k)]
    for col, key in (("objective_standard", "standard"), ("objective_cost_eur", "cost"), ("objective_margin", "margin")):
        if not math.isclose(float(row[col]), float(r.objectives[key]), rel_tol=1e-9, abs_tol=1e-9):
            out.append((col, row[col], r.objectives[key]))
    return out


def tie_times(apps, settings, objective: str = "standard") -> dict:
    """CPU seconds of one chunk's search (:meth:`Batch.optimum`) and of its tie-break, and the rows it changes."""
    w = Objective.parse(objective).additive_weights()
    Batch(apps[:8], settings).optimum_margin_ties(w)  # the kernels loaded
    t0 = time.process_time()
    b = Batch(apps, settings)
    found = b.optimum(w)
    t1 = time.process_time()
    tied = margin_ties(b, w, found)
    t2 = time.process_time()
    return {"search_s": t1 - t0, "tie_break_s": t2 - t1, "feasible": sum(f is not None for f in found),
            "changed": sum(a != b for a, b in zip(found, tied))}


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--n", type=int, default=2000)
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--fidelity", default="screening", choices=["screening", "full"])
    ap.add_argument("--no-compare", action="store_true", help="only the times, not the comparison with the solver")
    ap.add_argument("--every", type=int, default=100, help="print the count so far every this many rows")
    a = ap.parse_args(argv)
    apps = generate(a.n, seed=a.seed)
    settings = Settings(fidelity=a.fidelity)
    t = tie_times(apps, settings)
    print(f"| applications | feasible | rows the tie-break changes | search CPU s | tie-break CPU s | share |\n"
          f"|---:|---:|---:|---:|---:|---:|\n"
          f"| {a.n} | {t['feasible']} | {t['changed']} | {t['search_s']:.2f} | {t['tie_break_s']:.2f} | "
          f"{t['tie_break_s'] / t['search_s']:.1%} |", flush=True)
    if a.no_compare:
        return 0
    df = screen_applications(apps, objective="standard", settings=settings, diagnose=False)
    bad = {}
    for i, d in enumerate(apps):
        diff = differences(df.iloc[i], solve(d, with_margin_tiebreak("standard"), "enumerate", settings=settings,
                                             relax=False))
        if diff:
            bad[i] = diff
        if (i + 1) % a.every == 0:
            print(f"compared {i + 1} rows: {len(bad)} differ", flush=True)
    print(f"\n| applications (seed {a.seed}, {a.fidelity}) | feasible rows | rows differing from synth design |\n"
          f"|---:|---:|---:|\n| {a.n} | {int(df['feasible'].sum())} | {len(bad)} |")
    for i, diff in list(bad.items())[:20]:
        print(f"- row {i}: {diff}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
