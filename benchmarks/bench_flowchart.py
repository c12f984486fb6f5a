"""Time of one full flowchart run at each fidelity, and what the cheap form costs in accuracy.

Run: ``.venv/bin/python benchmarks/bench_flowchart.py`` (prints a markdown table).

* ``full``: Almen-Laszlo cone spring, plastic wear integrated with scipy's solve_ivp
  as the cone force falls with the growing gap;
* ``screening-only``: linear cone spring, closed-form wear (the screening model alone: what its error is);
* ``screening``: the same procedure judged by the full model (issue 19: a reported design's checks are the full
  model's), so its values are full fidelity's.
"""

from __future__ import annotations

import sys
import time

from synth import flowchart
from synth.io import documents

from synth.data import CASES_DIR as CASES


def time_run(d, settings, repeat=5):
    best = float("inf")
    for _ in range(repeat):
        t0 = time.perf_counter()
        r = flowchart.run(d, settings)
        best = min(best, time.perf_counter() - t0)
    return best, r


def main(cases=("case1_as_run", "case3")) -> None:
    print("| case | fidelity | time per run [ms] | EOL damping [Nm] | difference to full | verdict |")
    print("|---|---|---|---|---|---|")
    for name in cases:
        d = documents.load_input(CASES / f"{name}.yaml")
        ref = None
        for fid in ("full", "screening-only", "screening"):
            t, r = time_run(d, flowchart.Settings(fidelity=fid))
            eol = r.values.get("damping_eol_nm")
            ref = eol if fid == "full" else ref
            diff = "-" if eol is None or ref is None or fid == "full" else f"{100 * (eol - ref) / ref:+.1f} %"
            print(f"| {name} | {fid} | {1000 * t:.1f} | {'-' if eol is None else f'{eol:.3f}'} | {diff} | {r.verdict} |")


if __name__ == "__main__":
    main(tuple(sys.argv[1:]) or ("case1_as_run", "case3"))
