"""Lexicographic and weighted objectives as stages of a selection model (shared by the model solvers)."""

from __future__ import annotations

import contextlib
import os
import sys
import time

from synth.design.evaluate import Settings
from synth.design.space import SUBSYSTEMS
from synth.optimise.product import evaluate
from synth.optimise.model_data import model_data
from synth.optimise.objectives import FALLBACK_WEIGHTS, Objective
from synth.optimise.answer import build_result
from synth.optimise.diagnose import diagnose

__all__ = ["staged", "solve_with", "solve_evaluated", "solver_output_to_stderr"]

_TOL = 1e-7


@contextlib.contextmanager
def solver_output_to_stderr():
    """What a solver prints goes to stderr for the span of the block: stdout carries synth's output only.

    Native libraries write to file descriptor 1 themselves (HiGHS prints its banner when cvxpy creates the
    solver, before any option could silence it), so the descriptor is redirected, not only ``sys.stdout``;
    where the process has no real descriptors (a notebook's streams) ``sys.stdout`` alone is.
    """
    sys.stdout.flush()
    try:
        out_fd, err_fd = 1, sys.stderr.fileno()
        saved = os.dup(out_fd)
    except (AttributeError, OSError, ValueError):
        with contextlib.redirect_stdout(sys.stderr):
            yield
        return
    try:
        os.dup2(err_fd, out_fd)
        with contextlib.redirect_stdout(sys.stderr):
            yield
    finally:
        with contextlib.suppress(OSError, ValueError):
            sys.stderr.flush()
        os.dup2(saved, out_fd)
        os.close(saved)


def staged(md, obj: Objective, run):
    """Run ``run(weights, margin_weight, with_margin, t_lb, add_ub) -> (core, opts, additive, t) | None``
    in the stages of ``obj``; returns the last stage's answer and the number of stages. What the solver prints
    goes to stderr (:func:`solver_output_to_stderr`): ``--json`` output stays one JSON object."""
    with solver_output_to_stderr():
        return _staged(md, obj, run)


def _staged(md, obj: Objective, run):
    if obj.weights:
        w = {k: v for k, v in obj.weights.items() if k != "margin"}
        mw = obj.weights.get("margin", 0.0)
        return run(w, mw, mw > 0, -1e6, 1e12), 1
    if not obj.uses_margin():
        return run(obj.additive_weights(), 0.0, False, -1e6, 1e12), 1
    i = obj.order.index("margin")
    pre, post = obj.order[:i], obj.order[i + 1:] or tuple(FALLBACK_WEIGHTS)
    stages = 0
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


def solve_evaluated(ev, objective, run_factory, *, presolve: bool = True):
    """``(core position, options)`` of the staged model solver on an existing evaluation, or None."""
    obj = objective if isinstance(objective, Objective) else Objective.parse(objective)
    md, cores, opts = model_data(ev, obj.weights or obj.additive_weights(), obj.uses_margin(), presolve=presolve)
    if md.n_cores == 0:
        return None
    ans, _ = staged(md, obj, run_factory(md))
    if ans is None:
        return None
    return int(cores[ans[0]]), {s: int(opts[s][ans[1][s]]) for s in SUBSYSTEMS}


def solve_with(d, objective, run_factory, *, solver: str, settings: Settings = Settings(), pin_inputs: bool = False,
               presolve: bool = True, relax: bool = True, run_status: dict | None = None, **_):
    """Evaluate, presolve, then run the staged model solver made by ``run_factory(md)``."""
    obj = objective if isinstance(objective, Objective) else Objective.parse(objective)
    t0 = time.perf_counter()
    ev = evaluate(d, settings, pin_inputs=pin_inputs)
    t_eval = time.perf_counter() - t0
    md, cores, opts = model_data(ev, obj.weights or obj.additive_weights(), obj.uses_margin(), presolve=presolve)
    stats = {"evaluation_time_s": t_eval, "cores": md.n_cores,
             "options": {s: int(len(opts[s])) for s in SUBSYSTEMS}}
    if md.n_cores == 0:
        stats["time_s"] = time.perf_counter() - t0
        return diagnose(d, solver=solver, objective=obj, stats=stats, relax=relax, settings=settings,
                        pin_inputs=pin_inputs)
    t1 = time.perf_counter()
    ans, n_stages = staged(md, obj, run_factory(md))
    stats.update(solve_time_s=time.perf_counter() - t1, stages=n_stages, time_s=time.perf_counter() - t0)
    if ans is None:
        return diagnose(d, solver=solver, objective=obj, stats=stats, relax=relax, settings=settings,
                        pin_inputs=pin_inputs)
    core = int(cores[ans[0]])
    options = {s: int(opts[s][ans[1][s]]) for s in SUBSYSTEMS}
    proved = (run_status or {}).get("proved", True)
    if not proved:
        stats["note"] = "time limit reached: the best design found so far, optimality not proved"
    return build_result(ev, core, options, status="optimal" if proved else "feasible", solver=solver, objective=obj,
                        stats=stats)
