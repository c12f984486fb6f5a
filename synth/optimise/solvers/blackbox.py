"""Black-box search with optuna: TPE for one objective, NSGA-II for several; anytime.

Each trial picks one row of every table (core and subsystem options) and
evaluates that one design with the chosen fidelity (default ``full``: the
time-integrated plastic wear and the Almen-Laszlo cone spring), so the model
may be as costly as the physics allows and the space as large as the
catalogs grow. Constraints reach optuna as ``-margin <= 0`` (constrained TPE /
NSGA-II); the best feasible trial is returned with ``status="feasible"``
(no optimality proof).

>>> from synth.data.generated_applications import generate
>>> from synth.design.evaluate import Settings
>>> r = solve(generate(2, seed=0)[1], "cost", n_trials=20, settings=Settings(fidelity="screening"), seed=1)
>>> r.solver
'blackbox'
"""

from __future__ import annotations

import time

import numpy as np

from synth.design.evaluate import Settings
from synth.design.space import SUBSYSTEMS
from synth.optimise.evaluate import Evaluation, evaluate, evaluate_choice
from synth.optimise.objectives import Objective
from synth.optimise.result import build_result

__all__ = ["solve", "front"]


def _space(d, settings, pin_inputs=False) -> Evaluation:
    """The application's space (no subsystem evaluated: the trials evaluate one design each), with the parts the
    input names kept (``pin_inputs``, :func:`synth.design.space.space_for`)."""
    return evaluate(d, settings, subsystems=False, pin_inputs=pin_inputs)


def _values(ev: Evaluation, core: int, opts: dict, margin: float) -> dict:
    return ev.objective_values(core, opts, margin)


def solve(d, objective="standard", *, n_trials: int = 200, settings: Settings = Settings(), seed: int = 0,
          time_limit_s: float | None = None, pin_inputs=False, **_):
    """Best feasible design found by optuna in ``n_trials`` trials (or ``time_limit_s`` seconds, at least one trial)."""
    import optuna
    optuna.logging.set_verbosity(optuna.logging.WARNING)
    obj = objective if isinstance(objective, Objective) else Objective.parse(objective)
    t0 = time.perf_counter()
    ev = _space(d, settings, pin_inputs)
    multi = False  # one scalar objective (lexicographic orders are scalarised); see front() for NSGA-II
    cache = {}

    def objective_fn(trial):
        core = trial.suggest_int("core", 0, len(ev.cores) - 1)
        opts = {s: trial.suggest_int(s, 0, ev.space.n(s) - 1) for s in SUBSYSTEMS}
        key = (core, tuple(opts.values()))
        if key not in cache:
            cache[key] = evaluate_choice(ev, core, opts)
        worst, marg = cache[key]
        trial.set_user_attr("constraints", [float(np.clip(-worst, -1e6, 1e6))])
        trial.set_constraint("worst_margin", float(np.clip(-worst, -1e6, 1e6)))  # feasible when <= 0
        vals = _values(ev, core, opts, float(np.clip(marg, -1e6, 1e6)))
        trial.set_user_attr("values", vals)
        return obj.score(vals) if not obj.uses_margin() or obj.weights else -vals["margin"] * 1e4 + vals["cost"]

    sampler = optuna.samplers.TPESampler(seed=seed) if not multi else optuna.samplers.NSGAIISampler(seed=seed)
    study = optuna.create_study(direction="minimize", sampler=sampler)
    try:  # start from the thesis flowchart's greedy design: the search is then never worse than it
        from synth.optimise.solvers import flowchart
        base = flowchart.solve(d, settings=settings)
        row = _row_of(ev, base.parts)
        if row is not None:
            study.enqueue_trial(row)
    except Exception:  # the baseline is a hint only
        pass
    study.optimize(objective_fn, n_trials=max(int(n_trials), 1), timeout=time_limit_s)
    if not any(t.value is not None for t in study.trials):  # nothing completed (a time limit below one trial)
        study.optimize(objective_fn, n_trials=1)
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
    return build_result(ev, core, options, status=status, solver="blackbox", objective=obj, stats=stats)


def _row_of(ev: Evaluation, parts: dict):
    """Trial parameters (positions and option rows) of a design given by its parts, or None (off the grids)."""
    from synth.design.space import PART_KEYS_BY_TABLE
    sp = ev.space
    out = {}
    for table in ("core",) + SUBSYSTEMS:
        t = sp.tables[table]
        hit = np.ones(sp.n(table), bool)
        for k in PART_KEYS_BY_TABLE[table]:
            if k not in t:
                continue
            col = t[k]
            hit &= (col == str(parts[k])) if col.dtype == object else np.isclose(col, float(parts[k]))
        if table == "bushing":
            hit &= t["pivot_bushing_supplier"] == str(parts["pivot_bushing_supplier"])
        if table == "core":
            hit = hit[ev.cores]
        if not hit.any():
            return None
        out["core" if table == "core" else table] = int(np.flatnonzero(hit)[0])
    return out


def front(d, *, n_trials: int = 300, settings: Settings = Settings(), seed: int = 0, population: int = 30) -> list:
    """Cost-against-margin front by NSGA-II (two objectives): the non-dominated feasible trials.

    Returns ``[{"cost_eur", "margin", "parts"}]`` by increasing cost (anytime, no proof; the exact
    front is :func:`synth.optimise.pareto.pareto_front`).
    """
    import optuna
    optuna.logging.set_verbosity(optuna.logging.WARNING)
    ev = _space(d, settings)

    def fn(trial):
        core = trial.suggest_int("core", 0, len(ev.cores) - 1)
        opts = {s: trial.suggest_int(s, 0, ev.space.n(s) - 1) for s in SUBSYSTEMS}
        worst, marg = evaluate_choice(ev, core, opts)
        trial.set_constraint("worst_margin", float(np.clip(-worst, -1e6, 1e6)))
        return _values(ev, core, opts, 0.0)["cost"], float(np.clip(marg, -1e6, 1e6))

    study = optuna.create_study(directions=["minimize", "maximize"],
                                sampler=optuna.samplers.NSGAIISampler(seed=seed, population_size=population))
    study.optimize(fn, n_trials=n_trials)
    pts = []
    for t in study.best_trials:
        if t.system_attrs.get("constraints", [0])[0] > 0:
            continue
        pts.append({"cost_eur": t.values[0], "margin": t.values[1],
                    "parts": ev.parts(t.params["core"], {s: t.params[s] for s in SUBSYSTEMS})})
    return sorted(pts, key=lambda p: p["cost_eur"])
