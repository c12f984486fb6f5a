"""Black-box search with optuna: TPE for one objective, NSGA-II for several; anytime.

Each trial picks one row of every table (core and subsystem options) and
evaluates that one design with the chosen fidelity (default ``full``: the
time-integrated plastic wear and the Almen-Laszlo cone spring), so the model
may be as costly as the physics allows and the space as large as the
catalogs grow. Constraints reach optuna as ``-margin <= 0`` (constrained TPE /
NSGA-II); the best feasible trial is returned with ``status="feasible"``
(no optimality proof).

>>> from synth.data.generated_applications import generate
>>> r = solve(generate(2, seed=0)[1], "cost", n_trials=20, fidelity="screening", seed=1)
>>> r.solver
'blackbox'
"""

from __future__ import annotations

import time

import numpy as np

from synth.optimise.evaluate import evaluate
from synth.optimise.objectives import Objective
from synth.optimise.result import build_result, design_margin
from synth.optimise.space import SUBSYSTEMS, DesignSpace, build_space

__all__ = ["solve", "front", "evaluate_one"]


def _pick(sp: DesignSpace, core: int, options: dict) -> DesignSpace:
    return DesignSpace(sp.inputs, sp.fidelity, sp.friction_circle, sp.fixed, sp.cores.iloc[[core]].reset_index(drop=True),
                       {s: sp.subsystems[s].iloc[[options[s]]].reset_index(drop=True) for s in SUBSYSTEMS}, [])


def evaluate_one(sp: DesignSpace, core: int, options: dict) -> dict:
    """Margins (name -> value, ``-inf`` if the combination is not available) of one design."""
    ev = evaluate(_pick(sp, core, options), prune=False)
    m = {n: float(ev.core_margin_array[0, j]) for j, n in enumerate(ev.core_names)}
    avail = bool(ev.core_available[0])
    for s, sub in ev.subs.items():
        avail &= bool(sub.available[0, 0])
        m.update({n: float(sub.margins[0, 0, j]) for j, n in enumerate(sub.names)})
    m["_available"] = 0.0 if avail else -np.inf
    m["_axial"] = float(bool(ev.core_values["axial_damping_present"][0]))
    return m


def solve(d, objective="standard", *, n_trials: int = 200, fidelity: str = "full", seed: int = 0,
          timeout_s: float | None = None, friction_circle: bool = True, **_):
    """Best feasible design found by optuna in ``n_trials`` trials (or ``timeout_s``)."""
    import optuna
    optuna.logging.set_verbosity(optuna.logging.WARNING)
    obj = objective if isinstance(objective, Objective) else Objective.parse(objective)
    t0 = time.perf_counter()
    sp = build_space(d, fidelity=fidelity, friction_circle=friction_circle)
    names = obj.order if not obj.weights else tuple(obj.weights)
    multi = False  # one scalar objective (lexicographic orders are scalarised); see front() for NSGA-II
    cache = {}

    def objective_fn(trial):
        core = trial.suggest_int("core", 0, sp.n_cores - 1)
        opts = {s: trial.suggest_int(s, 0, len(sp.subsystems[s]) - 1) for s in SUBSYSTEMS}
        key = (core, tuple(opts.values()))
        if key not in cache:
            cache[key] = evaluate_one(sp, core, opts)
        m = cache[key]
        ax = bool(m.pop("_axial", 0.0)) if "_axial" in m else False
        margins = {k: v for k, v in m.items() if not k.startswith("_")}
        worst = min(min(margins.values()), m.get("_available", 0.0))
        trial.set_user_attr("constraints", [float(np.clip(-worst, -1e6, 1e6))])
        trial.set_constraint("worst_margin", float(np.clip(-worst, -1e6, 1e6)))  # feasible when <= 0
        cost = float(sp.cores["cost_eur"].iloc[core]) + sum(float(sp.subsystems[s]["cost_eur"].iloc[opts[s]]) for s in SUBSYSTEMS)
        std = float(sp.cores["nonstandard"].iloc[core]) + sum(float(sp.subsystems[s]["nonstandard"].iloc[opts[s]]) for s in SUBSYSTEMS)
        marg = design_margin(margins, ax)
        vals = {"cost": cost, "standard": std, "margin": float(np.clip(marg, -1e6, 1e6))}
        trial.set_user_attr("values", vals)
        return obj.score(vals) if not obj.uses_margin() or obj.weights else -vals["margin"] * 1e4 + vals["cost"]

    sampler = optuna.samplers.TPESampler(seed=seed) if not multi else optuna.samplers.NSGAIISampler(seed=seed)
    study = optuna.create_study(direction="minimize", sampler=sampler)
    try:  # start from the thesis flowchart's greedy design: the search is then never worse than it
        from synth.optimise.solvers import flowchart
        base = flowchart.solve(d, fidelity="screening")
        row = _row_of(sp, base.parts)
        if row is not None:
            study.enqueue_trial(row)
    except Exception:  # the baseline is a hint only
        pass
    study.optimize(objective_fn, n_trials=n_trials, timeout=timeout_s)
    feas = [t for t in study.trials if t.value is not None and t.user_attrs.get("constraints", [1])[0] <= 0]
    stats = {"time_s": time.perf_counter() - t0, "trials": len(study.trials), "feasible_trials": len(feas),
             "designs_evaluated": len(cache)}
    status = "feasible"
    if not feas:  # no proof of infeasibility: report the least-violating trial
        feas = [t for t in study.trials if t.value is not None]
        status = "infeasible"
        stats["note"] = f"no feasible design found in {len(study.trials)} trials (not a proof: run enumerate)"
        best = min(feas, key=lambda t: t.user_attrs["constraints"][0])
    else:
        best = min(feas, key=lambda t: t.value)
    core = best.params["core"]
    options = {s: best.params[s] for s in SUBSYSTEMS}
    from synth.optimise.solvers.enumerate import _name
    return build_result(sp, core, options, status=status, solver="blackbox", objective=_name(obj), stats=stats)


def _row_of(sp: DesignSpace, parts: dict):
    """Trial parameters (row indices) of a design given by its parts, or None."""
    out = {}
    cores = sp.cores
    hit = np.ones(len(cores), bool)
    for col in ("bearing", "pivot_class_mm", "supplier", "damper_pad"):
        hit &= cores[col].astype(str).to_numpy() == str(parts[col])
    if not hit.any():
        return None
    out["core"] = int(np.flatnonzero(hit)[0])
    from synth.optimise.space import PART_COLUMNS
    for s in SUBSYSTEMS:
        t = sp.subsystems[s]
        h = np.ones(len(t), bool)
        for col in PART_COLUMNS[s]:
            h &= t[col].astype(str).to_numpy() == str(parts[col])
        if not h.any():
            return None
        out[s] = int(np.flatnonzero(h)[0])
    return out


def front(d, *, n_trials: int = 300, fidelity: str = "full", seed: int = 0, population: int = 30) -> list:
    """Cost-against-margin front by NSGA-II (two objectives): the non-dominated feasible trials.

    Returns ``[{"cost_eur", "margin", "parts"}]`` by increasing cost (anytime, no proof; the exact
    front is :func:`synth.optimise.pareto.pareto_front`).
    """
    import optuna
    optuna.logging.set_verbosity(optuna.logging.WARNING)
    sp = build_space(d, fidelity=fidelity)

    def fn(trial):
        core = trial.suggest_int("core", 0, sp.n_cores - 1)
        opts = {s: trial.suggest_int(s, 0, len(sp.subsystems[s]) - 1) for s in SUBSYSTEMS}
        m = evaluate_one(sp, core, opts)
        ax = bool(m.pop("_axial"))
        avail = m.pop("_available")
        worst = min(min(m.values()), avail)
        trial.set_constraint("worst_margin", float(np.clip(-worst, -1e6, 1e6)))
        cost = float(sp.cores["cost_eur"].iloc[core]) + sum(float(sp.subsystems[s]["cost_eur"].iloc[opts[s]]) for s in SUBSYSTEMS)
        return cost, float(np.clip(design_margin(m, ax), -1e6, 1e6))

    study = optuna.create_study(directions=["minimize", "maximize"],
                                sampler=optuna.samplers.NSGAIISampler(seed=seed, population_size=population))
    study.optimize(fn, n_trials=n_trials)
    from synth.optimise.result import parts_of
    pts = []
    for t in study.best_trials:
        if t.system_attrs.get("constraints", [0])[0] > 0:
            continue
        pts.append({"cost_eur": t.values[0], "margin": t.values[1],
                    "parts": parts_of(sp, t.params["core"], {s: t.params[s] for s in SUBSYSTEMS})})
    return sorted(pts, key=lambda p: p["cost_eur"])
