"""Infeasible inputs: the nearest design, what it violates by how much, and the smallest input relaxation.

* The **nearest design** maximises the smallest normalised margin over the
  whole catalog product (every core evaluated, nothing pruned): the design
  that misses the requirements by the least.
* Its **violated constraints** are listed with their margins (a margin of
  -0.35 on a stress means the stress is 35 % above its limit).
* **Relaxations**: for every input that can relax a violated constraint
  (:data:`RELAXABLE`), the smallest change that makes the application
  feasible, found by bisection on that one input (each probe is one
  exhaustive feasibility check). A missing entry means that input alone
  cannot make the design feasible within its range.

>>> from synth.schema import load_input

>>> from synth.data import case_path
>>> r = diagnose(load_input(case_path("case1")), relax=False)
>>> r.status, len(r.diagnosis["violated"]) > 0
('infeasible', True)
"""

from __future__ import annotations

import dataclasses
import time

import numpy as np

from synth.errors import InputError
from synth.optimise.evaluate import CONSTRAINTS, FEAS_TOL, evaluate
from synth.optimise.space import SUBSYSTEMS, build_space
from synth.schema import field_by_name

__all__ = ["RELAXABLE", "nearest_design", "is_feasible", "relaxations", "diagnose"]

#: input field -> (direction: +1 raise / -1 lower, the constraints it relaxes)
RELAXABLE = {
    "max_pivot_height_mm": (+1, ("belt_plane", "bushing_length", "bushing_p", "bushing_pv", "bushing_pvt",
                                 "bushing_wear", "bushing_parallelism", "spring_cavity", "spring_coil_gap")),
    "max_axial_displacement_mm": (+1, ("axial_displacement",)),
    "pulley_max_parallelism_eol_mm": (+1, ("bushing_parallelism",)),
    "damping_tolerance_nm": (+1, ("damping_upper", "damping_lower", "cone_force_band")),
    "damping_eol_limit_nm": (-1, ("damping_eol",)),
    "spring_torque_tolerance_pct": (-1, ("spring_yield", "spring_fatigue")),
    "tilting_safety_factor": (-1, ("bolt_yield", "under_head", "thread", "pivot_base_pressure")),
    "sliding_safety_factor": (-1, ("bolt_yield", "under_head", "thread", "pivot_base_pressure")),
    "bolt_head_contact_external_diameter_mm": (+1, ("under_head",)),
    "number_of_active_threads": (+1, ("thread",)),
    "engine_support_internal_diameter_mm": (+1, ("pivot_bore",)),
    "engine_support_external_diameter_mm": (+1, ("pivot_base_pressure", "bolt_yield", "under_head", "thread")),
    "middle_plane_belt_height_mm": (+1, ("spring_coil_gap", "spring_cavity")),
    "spring_stiffness_nm_per_deg": (+1, ("spring_coil_gap",)),
}


def is_feasible(d, *, fidelity: str = "screening", friction_circle: bool = True) -> bool:
    """Whether any design of the catalog product meets every constraint for input ``d``."""
    from synth.optimise.solvers.enumerate import max_margin, tables
    try:
        sp = build_space(d, fidelity=fidelity, friction_circle=friction_circle)
    except InputError:
        return False
    ev = evaluate(sp)
    return bool(len(ev.rows)) and max_margin(tables(ev, {"cost": 1.0})) > -np.inf


def nearest_design(sp):
    """``(core, options, min_margin)`` of the design with the largest smallest margin (all constraints)."""
    ev = evaluate(sp, prune=False)
    core_m = np.where(ev.core_available, np.min(ev.core_margin_array, axis=1) if ev.core_margin_array.shape[1]
                      else np.inf, -np.inf)
    best_k = {}
    for s in SUBSYSTEMS:
        sub = ev.subs[s]
        m = np.where(sub.available, sub.min_margin(), -np.inf)
        best_k[s] = np.argmax(m, axis=1)
        core_m = np.minimum(core_m, m[np.arange(len(m)), best_k[s]])
    r = int(np.argmax(core_m))
    return r, {s: int(best_k[s][r]) for s in SUBSYSTEMS}, float(core_m[r])


def _probe_default(d, changes: dict, fidelity):
    try:
        return is_feasible(dataclasses.replace(d, **changes), fidelity=fidelity)
    except InputError:
        return False


def _far(d, name, sign):
    cur = getattr(d, name)
    f = field_by_name(name)
    if sign > 0:
        return min(2.0 * cur, f.hi) if np.isfinite(f.hi) else 2.0 * cur
    far = max(0.25 * cur, f.lo if np.isfinite(f.lo) else 0.0)
    return f.lo + 1e-3 * abs(cur) if f.lo_open and far <= f.lo else far


def relaxations(d, violated: list, *, fidelity: str = "screening", steps: int = 7, probe=None) -> list:
    """Smallest input changes that make ``d`` feasible, for the inputs that relax ``violated``.

    First each input alone (bisection between its value and a far value:
    x2 or /4 within the schema's range); when no single input suffices, all
    the relevant inputs together, moved by a common fraction of their range
    (one entry with ``"inputs"``). ``probe(d, changes, fidelity) -> bool``
    replaces the feasibility check (the bulk engine passes a faster one with the same answers).
    """
    _probe = probe or _probe_default
    out = []
    cands = {n: sign for n, (sign, rel) in RELAXABLE.items() if getattr(d, n) is not None and set(rel) & set(violated)}
    for name, sign in cands.items():
        cur, far = getattr(d, name), _far(d, name, sign)
        if not _probe(d, {name: far}, fidelity):
            continue
        good, bad = far, cur
        for _ in range(steps):
            mid = 0.5 * (good + bad)
            if _probe(d, {name: mid}, fidelity):
                good = mid
            else:
                bad = mid
        out.append({"inputs": {name: {"from": cur, "to": round(float(good), 4)}},
                    "relative_change": round(abs(good - cur) / max(abs(cur), 1e-9), 4),
                    "relaxes": sorted(set(RELAXABLE[name][1]) & set(violated))})
    if not out and len(cands) > 1:
        far = {n: _far(d, n, s) for n, s in cands.items()}

        def at(lam):
            return {n: getattr(d, n) + lam * (far[n] - getattr(d, n)) for n in cands}
        if _probe(d, at(1.0), fidelity):
            good, bad = 1.0, 0.0
            for _ in range(steps):
                mid = 0.5 * (good + bad)
                good, bad = (mid, bad) if _probe(d, at(mid), fidelity) else (good, mid)
            out.append({"inputs": {n: {"from": getattr(d, n), "to": round(float(v), 4)} for n, v in at(good).items()},
                        "relative_change": round(good, 4), "relaxes": sorted(set(violated))})
    return sorted(out, key=lambda r: r["relative_change"])


def diagnose(d, sp=None, *, solver: str = "enumerate", objective=None, stats: dict | None = None,
             relax: bool = True):
    """A :class:`~synth.optimise.result.DesignResult` with ``status="infeasible"`` and its ``diagnosis``."""
    from synth.optimise.result import build_result
    t0 = time.perf_counter()
    sp = sp or build_space(d)
    core, options, m0 = nearest_design(sp)
    res = build_result(sp, core, options, status="infeasible", solver=solver,
                       objective=_objname(objective), stats=stats or {})
    violated = {k: m for k, m in res.margins.items() if m < -FEAS_TOL}
    res.binding = [{"constraint": k, "label": CONSTRAINTS[k][1], "step": CONSTRAINTS[k][0],
                    "equation": CONSTRAINTS[k][2], "margin": m} for k, m in sorted(violated.items(), key=lambda kv: kv[1])]
    res.diagnosis = {
        "message": "no design of the catalog product meets every constraint; the nearest design is shown",
        "violated": res.binding,
        "relaxations": relaxations(d, list(violated), fidelity=sp.fidelity) if relax else [],
    }
    res.stats["diagnosis_time_s"] = time.perf_counter() - t0
    return res


def _objname(objective) -> str:
    if objective is None:
        return "standard,cost"
    if getattr(objective, "weights", None):
        return ",".join(f"{k}={v:g}" for k, v in objective.weights.items())
    return ",".join(getattr(objective, "order", (str(objective),)))
