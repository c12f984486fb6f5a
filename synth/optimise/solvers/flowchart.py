"""The thesis flowchart as a baseline: one component at a time, the first that passes.

Greedy order of the thesis: bearing from Table 1, pivot class from the input
or Table 2, bushing supplier from the input wall thickness, the smallest
damper pad class that carries the axial damping, the shortest catalog
bushing length that passes, the smallest endcap spacer with the default cone
aspect ratio first, the cheapest feasible main spring (the automatic search
of step 9) and the bolt escalation of step 10 (format, then class). Each
choice is final: a later failure is not repaired (the thesis's flowchart
stops at the first design that passes, or at a failure).

>>> from synth.data.generated_applications import generate
>>> r = solve(generate(2, seed=0)[1])
>>> r.solver, r.status in ("baseline", "infeasible")
('flowchart', True)
"""

from __future__ import annotations

import time

import numpy as np

from synth import catalog
from synth.optimise.evaluate import evaluate
from synth.optimise.result import build_result
from synth.optimise.space import NONE, SUBSYSTEMS, build_space
from synth.model import ball_bearing as s1, pivot as s2, plain_bushing as s4, bolted_joint as s10

__all__ = ["solve"]


def _order(sp, s):
    t = sp.subsystems[s]
    if s == "bushing":
        return np.lexsort((t["bushing_length_mm"].to_numpy(),))
    if s == "axial":
        z0 = catalog.constant("cone_spring_default_aspect_ratio")
        return np.lexsort((np.abs(t["cone_aspect_ratio"].to_numpy() - z0), t["es_max_axial_damping_nm"].to_numpy()))
    if s == "spring":
        return np.argsort(t["cost_eur"].to_numpy(), kind="stable")
    ranks = {(c["bolt_format"], c["bolt_property_class"]): i for i, c in enumerate(s10.bolt_candidates())}
    return np.array(sorted(range(len(t)), key=lambda i: ranks.get((t["bolt_format"][i], t["bolt_property_class"][i]), 10**6 + i)))


def solve(d, objective="standard", *, fidelity: str = "screening", friction_circle: bool = True, **_):
    """The thesis flowchart's greedy design, verified like every solver's (status ``baseline`` or ``infeasible``)."""
    t0 = time.perf_counter()
    sp = build_space(d, fidelity=fidelity, friction_circle=friction_circle)
    hl = sp.fixed["hubload_nominal_n"]
    bearing = str(s1.select_bearing(hl, d.engine_fuel)[0])
    c = sp.cores
    try:
        std_class, _ = s2.standard_pivot_class(bearing, d.working_arm_mm)
    except Exception:
        std_class = float(c["pivot_class_mm"].iloc[0])
    pclass = float(d.pivot_class_diameter_mm) if d.pivot_class_diameter_mm is not None else std_class
    thick = d.pivot_bushing_radial_thickness_mm
    supplier = s4.supplier_for_thickness(thick) if thick is not None else \
        str(catalog.load("pivot_bushings").sort_values("radial_thickness_mm").iloc[-1]["supplier"])
    sel = (c["bearing"] == bearing) & np.isclose(c["pivot_class_mm"], pclass) & (c["supplier"] == supplier)
    ev = evaluate(sp, prune=False)
    rows = np.flatnonzero(sel.to_numpy())
    notes = [f"flowchart: bearing {bearing} (Table 1), pivot class {pclass:g} mm, supplier {supplier}"]
    if not len(rows):
        from synth.optimise.diagnose import diagnose
        return diagnose(d, sp, solver="flowchart", stats={"time_s": time.perf_counter() - t0}, relax=False)
    # damper pad: 'none' when there is no axial damping, else the smallest class that carries it
    cand = [r for r in rows if ev.core_available[r]]
    dp_order = sorted(cand, key=lambda r: (c["dp_max_axial_damping_nm"].iloc[r], c["damper_pad"].iloc[r] != NONE))
    feas_core = [r for r in dp_order if ev.core_feasible()[r]]
    core = feas_core[0] if feas_core else (dp_order[0] if dp_order else rows[0])
    options, ok = {}, bool(feas_core)
    for s in SUBSYSTEMS:
        sub = ev.subs[s]
        f = sub.feasible()[core]
        order = _order(sp, s)
        hit = [k for k in order if f[k]]
        options[s] = int(hit[0]) if hit else int(next((k for k in order if sub.available[core, k]), order[0]))
        ok &= bool(hit)
    stats = {"time_s": time.perf_counter() - t0}
    res = build_result(sp, core, options, status="baseline" if ok else "infeasible", solver="flowchart",
                       objective="greedy", stats=stats, notes=notes)
    if not ok:
        res.diagnosis = {"message": "the greedy flowchart stops at a failing step",
                         "violated": [k for k, m in res.margins.items() if m < -1e-9], "relaxations": []}
    return res
