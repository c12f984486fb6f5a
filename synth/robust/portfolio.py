"""Capability of many designs at once (``synth bulk --capability``): K designs x N samples in one evaluator call.

Each design of a chunk gets the same N standard-normal points (one scrambled
Sobol sample over every quantity of the tolerance catalog, as for one design:
:func:`synth.robust.capability.capability`), turned into its own deviations by
its own bands (:func:`synth.robust.tolerances.resolve`); a quantity not in play
for a design deviates by 0 there. The K x N rows go through
:func:`synth.robust.sampling.perturb` and the one evaluator in one call; the
statistics are the single design's (:mod:`synth.robust.stats`: P(violation)
with its Clopper-Pearson interval, the target method's Ppk), per design and per
targeted check, vectorised; the joint is the made one (VDI 2230,
:func:`synth.robust.sampling.production`). The importance
sampling of small probabilities is not run here: a ppm target below what the
samples resolve is judged on the Monte Carlo's upper bound, and the columns
say so (``capability_method``).

>>> from synth.scenes.demo import default_input
>>> from synth.optimise import solve
>>> d = default_input()
>>> rows = portfolio_capability([d, d], [solve(d, "standard,cost,margin").parts, None],
...                             rs=RobustSettings(samples=256))
>>> rows[0]["capability_meets"], rows[1]["capability_meets"]
(False, None)
"""

from __future__ import annotations

import numpy as np

from synth.design import evaluate
from synth.design.applications import Applications
from synth.design.assessment import assess, passes
from synth.design.constraints import EVALUATED_GROUPS, REGISTRY
from synth.design.space import space
from synth.design.verify import evaluate_design
from synth.robust import stats
from synth.robust.sampling import Base, centred_cone, context, perturb, production, sobol_u
from synth.robust.settings import RobustSettings
from synth.robust.tolerances import resolve, tolerances
from synth import catalog

__all__ = ["portfolio_capability", "COLUMNS", "BULK_SAMPLES"]

#: Monte Carlo samples per application in the bulk (2^10): the capability of the bulk's chosen design
BULK_SAMPLES = 1024
#: the result columns of :func:`portfolio_capability`
COLUMNS = ("capability_meets", "capability_min_ppk", "capability_max_ppm", "capability_failing",
           "capability_binding", "capability_method")


def _chunk(inputs: list, parts: list, settings: evaluate.Settings, rs: RobustSettings, table: dict) -> list:
    settings = production(settings)
    k = len(inputs)
    sp = space()
    per = [sp.design_attributes(p) for p in parts]
    attrs = {t: {c: np.concatenate([np.asarray(a[t][c]) for a in per]) for c in per[0][t]} for t in per[0]}
    apps = Applications.of(inputs)
    with np.errstate(all="ignore"):
        groups = evaluate_design(apps, attrs, settings, detail=False)
    names = tuple(table)
    q = len(names)
    lo, hi = np.zeros((k, q)), np.zeros((k, q))
    kind = np.array([0 if table[n].kind == "normal" else 1 for n in names])
    for i in range(k):
        sc = resolve(context(apps, attrs, groups, settings, i), table)
        lo[i, sc.columns], hi[i, sc.columns] = sc.lo, sc.hi
    n = rs.samples
    u = sobol_u(n, q, rs.seed)
    rows = np.repeat(np.arange(k), n)
    from scipy.special import ndtr
    uu = np.tile(u, (k, 1))
    low, high = lo[rows], hi[rows]
    x = np.where(kind[None, :] == 0, (low + high) / 2.0 + (high - low) / 6.0 * uu, low + (high - low) * ndtr(uu))
    dev = {name: x[:, j] for j, name in enumerate(names) if (hi[:, j] > lo[:, j]).any()}
    base = Base(inputs, {}, settings, apps, attrs, groups, None, (), cone=centred_cone(apps, attrs, groups, settings))
    a_s, at_s = perturb(base, dev or {"_n": np.zeros(len(rows))}, rows)
    with np.errstate(all="ignore"):
        gs = evaluate_design(a_s, at_s, settings, detail=False)
    out = [{"ppk": np.inf, "p_hi": 0.0, "failing": [], "binding": "", "binding_ppk": np.inf} for _ in range(k)]
    judged = assess(groups)  # the checks each design's capability targets: evaluated ones only
    targeted = judged.targeted & judged.evaluated
    for j, cid in enumerate(judged.columns.ids):
        c = REGISTRY[cid]
        if c.group not in EVALUATED_GROUPS:
            continue
        on = targeted[:, j]
        if not on.any():
            continue
        m = np.asarray(gs[c.group].margins[cid], dtype=float).reshape(k, n)
        fails = (~passes(m)).sum(axis=1)
        ppk = stats.ppk_percentile(m) if rs.method == "percentile" else stats.ppk_moment(m)
        p_hi = stats.clopper_pearson(fails, n)[1]
        for i in np.flatnonzero(on):
            o = out[i]
            if ppk[i] < o["binding_ppk"]:
                o["binding"], o["binding_ppk"] = cid, float(ppk[i])
            o["ppk"] = min(o["ppk"], float(ppk[i]))
            o["p_hi"] = max(o["p_hi"], float(p_hi[i]))
            if (rs.capability is not None and ppk[i] < rs.capability) or (rs.ppm is not None and p_hi[i] > rs.ppm * 1e-6):
                o["failing"].append(cid)
    return out


def _run(args):
    """A process pool's task: one chunk (the catalogs of the parent: its user folders are passed along)."""
    dirs, inputs, parts, settings, rs = args
    if dirs:
        catalog.set_user_dirs(*dirs)
    return _chunk(inputs, parts, settings, rs, tolerances())


def portfolio_capability(inputs: list, parts: list, *, settings: evaluate.Settings = evaluate.Settings(),
                         rs: RobustSettings = RobustSettings(samples=BULK_SAMPLES), chunk: int = 64,
                         table: dict | None = None, workers: int = 1) -> list:
    """One dict of :data:`COLUMNS` per design (``parts[i]`` of ``inputs[i]``; None: no design, the columns empty):
    whether it meets ``rs``'s target on every targeted check, its smallest Ppk, its largest probability of
    violation (upper 95 % end, in ppm), the failing checks and the one of smallest Ppk. ``workers > 1``: the
    chunks in that many processes (the same numbers: every chunk's samples are the same seeded points)."""
    table = tolerances() if table is None else table
    out = [dict.fromkeys(COLUMNS) for _ in inputs]
    todo = [i for i, p in enumerate(parts) if p]
    chunks = [todo[s:s + max(1, int(chunk))] for s in range(0, len(todo), max(1, int(chunk)))]
    if workers > 1 and len(chunks) > 1:
        from concurrent.futures import ProcessPoolExecutor
        dirs = [str(d) for d in catalog.user_dirs()]  # the folders in use here (a `using` block too)
        with ProcessPoolExecutor(max_workers=int(workers)) as pool:
            results = list(pool.map(_run, [(dirs, [inputs[i] for i in idx], [parts[i] for i in idx], settings, rs)
                                           for idx in chunks]))
    else:
        results = [_chunk([inputs[i] for i in idx], [parts[i] for i in idx], settings, rs, table) for idx in chunks]
    for idx, res in zip(chunks, results):
        for i, r in zip(idx, res):
            out[i] = {"capability_meets": not r["failing"], "capability_min_ppk": r["ppk"],
                      "capability_max_ppm": r["p_hi"] * 1e6, "capability_failing": " ".join(r["failing"]),
                      "capability_binding": r["binding"],
                      "capability_method": f"monte carlo, {rs.samples} samples, {rs.method} index (upper 95 % "
                                           "ends; bounded outputs judged by the same index)"}
    return out
