"""The cost-against-margin Pareto front, exact, from the enumeration tables.

For each margin threshold ``tau`` (the distinct margins of the feasible
options, thinned to ``n_points`` quantiles), the cheapest design whose every
objective margin is at least ``tau`` (:func:`..solvers.enumerate.best_additive`);
the non-dominated (cost, margin) pairs form the front. Each point carries its
binding constraint.

>>> from synth.data.generated_applications import generate
>>> front = pareto_front(generate(2, seed=0)[1], n_points=8)
>>> len(front) >= 1, sorted(front[0])[:3]
(True, ['binding', 'cost_eur', 'inputs'])
"""

from __future__ import annotations

import numpy as np

from synth.design.evaluate import Settings
from synth.optimise.product import evaluate
from synth.optimise.answer import build_result
from synth.optimise.solvers.enumerate import margin_thresholds, best_additive, tables
from synth.design.constraints import words
from synth.io.outputs import write_figure

__all__ = ["pareto_front", "plot_front"]


def pareto_front(d, *, n_points: int = 40, settings: Settings = Settings()) -> list:
    """Points ``{cost_eur, margin, standard, binding, parts}`` of the front, by increasing cost.

    The margin is the design margin (input-only constraints, which no design changes, are not in it: their
    margins are in each point's ``inputs`` and the caller reports them apart).
    """
    ev = evaluate(d, settings)
    t = tables(ev, {"cost": 1.0})
    pts, seen = [], set()
    for tau in margin_thresholds(t, n_points):
        val, core, opts = best_additive(t, tau)
        if core is None:
            continue
        key = (core, tuple(opts.values()))
        if key in seen:
            continue
        seen.add(key)
        r = build_result(ev, core, opts, status="optimal", solver="enumerate", objective="cost|margin>=tau", stats={},
                         detail=False)
        b = r.binding(1)
        pts.append({"cost_eur": r.objectives["cost"], "margin": r.objectives["margin"], "standard": r.objectives["standard"],
                    "binding": b[0].id if b else "", "parts": r.parts,
                    "inputs": {c.id: c.margin for c in r.checks if not c.constraint.design and c.margin is not None}})
    pts.sort(key=lambda p: (p["cost_eur"], -p["margin"]))
    front, best = [], -np.inf
    for p in pts:
        if p["margin"] > best + 1e-12:
            front.append(p)
            best = p["margin"]
    return front


def plot_front(front: list, path, *, y: str = "margin", ylabel: str = "smallest margin [%]",
               title: str = "cost against margin: Pareto front", label=None) -> None:
    """Save the front (cost against ``y``; the margin, a fraction in the data, in percent) as a matplotlib step
    plot, each point labelled with ``label(point)`` (default its binding constraint in words)."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    label = label or (lambda p: words(p["binding"], 36))
    scale = 100.0 if y == "margin" else 1.0
    fig, ax = plt.subplots(figsize=(7, 4.5))
    c = [p["cost_eur"] for p in front]
    m = [scale * p[y] for p in front]
    ax.step(c, m, where="post", color="0.6")
    band = [p.get("cost_band_eur") for p in front]
    if all(band):  # the cost's 90 % band under the price bands (synth.cost.decision.band_of)
        ax.errorbar(c, m, xerr=[[x - b[0] for x, b in zip(c, band)], [b[1] - x for x, b in zip(c, band)]], fmt="none",
                    ecolor="C0", alpha=0.35, capsize=2, label="cost: 90 % band of the prices")
        ax.legend(fontsize=7, loc="lower right")
    ax.plot(c, m, "o", color="C0")
    for p, v in zip(front, m):
        ax.annotate(label(p), (p["cost_eur"], v), fontsize=6, xytext=(3, 3), textcoords="offset points")
    ax.set_xlabel("cost [EUR] (synth.cost: quoted, modelled and assumed prices)")
    ax.set_ylabel(ylabel)
    ax.set_title(title)
    ax.grid(True, alpha=0.3)
    fig.tight_layout()
    write_figure(fig, path, dpi=120)
