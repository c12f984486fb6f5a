"""The speed-accuracy table of the fidelities (issue 19): time, verdict agreement and design validity.

    .venv/bin/python benchmarks/bench_fidelity.py [--n 10000] [--seed 0] [--chunk 1280] [--objective standard]

One portfolio of generated applications (``synth.data.generated_applications.generate(n, seed)``, the
applications of ``synth portfolio-sample``) through the bulk engine (``screen_applications``, no diagnosis, in
chunks as ``synth bulk`` cuts them) at each fidelity, the three runs side by side in one process (the machine is
shared: compare the ratios, not the absolute times). Full fidelity is the reference: for every other fidelity,

* verdict agreement: the share of applications with the full-fidelity verdict (feasible or not);
* feasible designs valid at full fidelity: of the designs it reports feasible, the share the full model passes
  (each verified through ``synth.design.verify.evaluate_design`` at full fidelity, all at once); the count of
  those that fail, by the constraint they fail;
* the same design as full fidelity's optimum, and how much worse the objective is where it is not.
"""

from __future__ import annotations

import argparse
import collections
import time

import numpy as np

from synth.bulk.engine import screen_applications
from synth.data.generated_applications import generate
from synth.design import evaluate
from synth.design.applications import Applications
from synth.design.constraints import FEAS_TOL
from synth.design.space import PART_KEYS, space
from synth.design.verify import evaluate_design


def run(apps, fidelity, objective, chunk):
    import pandas as pd
    t0 = time.perf_counter()
    parts = [screen_applications(apps[a:a + chunk], objective=objective, fidelity=fidelity, diagnose=False)
             for a in range(0, len(apps), chunk)]
    return pd.concat(parts, ignore_index=True), time.perf_counter() - t0


def failures_at_full(df, apps, chunk: int = 2000) -> collections.Counter:
    """Per constraint, the reported-feasible designs of ``df`` the full model rejects (``"designs"``: all of them)."""
    out: collections.Counter = collections.Counter()
    sp = space()
    idx = np.flatnonzero(df["feasible"].to_numpy())
    for a in range(0, len(idx), chunk):
        sel = idx[a:a + chunk]
        one = [sp.design_attributes({k: df.at[i, f"part_{k}"] for k in PART_KEYS}) for i in sel]
        attrs = {t: {k: np.concatenate([np.asarray(x[t][k]) for x in one]) for k in one[0][t]} for t in one[0]}
        with np.errstate(all="ignore"):
            groups = evaluate_design(Applications.of([apps[i] for i in sel]), attrs, evaluate.Settings(fidelity="full"),
                                     detail=False)
        bad = np.zeros(len(sel), dtype=bool)
        for g in groups.values():
            ok = g.ok()
            bad |= ~ok
            for cid, m in g.margins.items():
                from synth.design.constraints import REGISTRY
                if not REGISTRY[cid].advisory:
                    out[cid] += int((m < -FEAS_TOL).sum())
        out["designs"] += int(bad.sum())
    return out


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--n", type=int, default=10_000)
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--chunk", type=int, default=1280)
    ap.add_argument("--objective", default="standard")
    args = ap.parse_args(argv)
    apps = generate(args.n, seed=args.seed)
    screen_applications(apps[:20], diagnose=False)  # the process's first call (kernels, design space) apart
    fids = ("full", "screening", "screening-only")
    res = {f: run(apps, f, args.objective, args.chunk) for f in fids}
    full, t_full = res["full"]
    parts = [f"part_{k}" for k in PART_KEYS]
    print(f"## Speed and accuracy of the fidelities ({args.n} generated applications, seed {args.seed}, objective "
          f"{args.objective}, no diagnosis, chunks of {args.chunk}; full fidelity is the reference)\n")
    print("| fidelity | seconds | apps/s | x full | feasible | verdict = full's | reported feasible, valid at full "
          "| failing at full | design = full's optimum | worse objective (where it differs) |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    fails = {}
    for f in fids:
        df, dt = res[f]
        feas = df["feasible"].to_numpy()
        agree = float((feas == full["feasible"].to_numpy()).mean())
        fail = failures_at_full(df, apps)
        fails[f] = fail
        n_feas = int(feas.sum())
        valid = 1.0 - fail["designs"] / max(n_feas, 1)
        both = feas & full["feasible"].to_numpy()
        same = (df.loc[both, parts].astype(str).to_numpy() == full.loc[both, parts].astype(str).to_numpy()).all(axis=1)
        obj = "objective_standard" if args.objective == "standard" else "objective_cost_eur"
        worse = (df.loc[both, obj].to_numpy() - full.loc[both, obj].to_numpy())[~same]
        print(f"| {f} | {dt:.1f} | {args.n / dt:.0f} | {t_full / dt:.2f} | {n_feas} | {agree:.4f} | {valid:.4f} "
              f"| {fail['designs']} | {same.mean():.4f} | {int((worse > 1e-9).sum())} designs, mean "
              f"+{worse[worse > 1e-9].mean() if (worse > 1e-9).any() else 0.0:.3g} {obj.split('_', 1)[1]} |")
    print()
    for f in fids:
        top = ", ".join(f"{k} {v}" for k, v in fails[f].most_common() if k != "designs" and v)
        print(f"- {f}: designs reported feasible that fail at full fidelity: {fails[f]['designs']}"
              + (f" (checks failed: {top})" if top else ""))
    return 0 if fails["screening"]["designs"] == 0 and fails["full"]["designs"] == 0 else 1


if __name__ == "__main__":
    raise SystemExit(main())
