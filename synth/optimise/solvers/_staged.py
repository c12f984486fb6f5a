"""Lexicographic and weighted objectives as stages of a selection model (shared by the model solvers)."""

from __future__ import annotations

import time

from synth.optimise.evaluate import evaluate
from synth.optimise.formulations.data import model_data
from synth.optimise.objectives import Objective
from synth.optimise.result import build_result
from synth.optimise.space import SUBSYSTEMS, build_space

__all__ = ["staged", "solve_with"]

_TOL = 1e-7


def staged(md, obj: Objective, run):
    """Run ``run(weights, margin_weight, with_margin, t_lb, add_ub) -> (core, opts, additive, t) | None``
    in the stages of ``obj``; returns the last stage's answer and the number of stages."""
    if obj.weights:
        w = {k: v for k, v in obj.weights.items() if k != "margin"}
        mw = obj.weights.get("margin", 0.0)
        return run(w, mw, mw > 0, -1e6, 1e12), 1
    if not obj.uses_margin():
        return run(obj.additive_weights(), 0.0, False, -1e6, 1e12), 1
    i = obj.order.index("margin")
    pre, post = obj.order[:i], obj.order[i + 1:] or ("cost",)
    t_lb, stages = -1e6, 0
    if pre:
        pw = Objective(order=pre).additive_weights()
        r = run(pw, 0.0, False, -1e6, 1e12)
        stages += 1
        if r is None:
            return None, stages
        r = run(pw, 0.0, True, -1e6, r[2] + _TOL * max(1.0, abs(r[2])))
        stages += 1
        return r, stages
    r = run({}, 0.0, True, -1e6, 1e12)
    stages += 1
    if r is None:
        return None, stages
    r = run(Objective(order=post).additive_weights(), 0.0, False, r[3] - _TOL, 1e12)
    return r, stages + 1


def solve_with(d, objective, run_factory, *, solver: str, fidelity: str = "screening", pin_inputs: bool = False,
               friction_circle: bool = True, presolve: bool = True, relax: bool = True):
    """Build space, evaluate, presolve, then run the staged model solver made by ``run_factory(md)``."""
    obj = objective if isinstance(objective, Objective) else Objective.parse(objective)
    t0 = time.perf_counter()
    sp = build_space(d, fidelity=fidelity, friction_circle=friction_circle, pin_inputs=pin_inputs)
    ev = evaluate(sp)
    t_eval = time.perf_counter() - t0
    md = model_data(ev, obj.weights or obj.additive_weights(), obj.uses_margin(), presolve=presolve)
    stats = {"evaluation_time_s": t_eval, "cores": md.n_cores,
             "options": {s: int(len(md.opts[s])) for s in SUBSYSTEMS}, "options_before_presolve": md.sizes_before}
    if md.n_cores == 0:
        from synth.optimise.diagnose import diagnose
        stats["time_s"] = time.perf_counter() - t0
        return diagnose(d, sp, solver=solver, objective=obj, stats=stats, relax=relax)
    t1 = time.perf_counter()
    ans, n_stages = staged(md, obj, run_factory(md))
    stats.update(solve_time_s=time.perf_counter() - t1, stages=n_stages, time_s=time.perf_counter() - t0)
    if ans is None:
        from synth.optimise.diagnose import diagnose
        return diagnose(d, sp, solver=solver, objective=obj, stats=stats, relax=relax)
    c, opts = ans[0], ans[1]
    core = int(md.cores[c])
    options = {s: int(md.opts[s][opts[s]]) for s in SUBSYSTEMS}
    from synth.optimise.solvers.enumerate import _name
    return build_result(sp, core, options, status="optimal", solver=solver, objective=_name(obj), stats=stats)


def solve_evaluated(sp, ev, objective, run_factory, *, presolve: bool = True):
    """``(core, options)`` (indices into ``sp``) of the staged model solver on an existing evaluation, or None."""
    obj = objective if isinstance(objective, Objective) else Objective.parse(objective)
    md = model_data(ev, obj.weights or obj.additive_weights(), obj.uses_margin(), presolve=presolve)
    if md.n_cores == 0:
        return None
    ans, _ = staged(md, obj, run_factory(md))
    if ans is None:
        return None
    return int(md.cores[ans[0]]), {s: int(md.opts[s][ans[1][s]]) for s in SUBSYSTEMS}
