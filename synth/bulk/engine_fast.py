"""The fast bulk engine: ``solve(d, objective, "enumerate")`` per application, same answer, far less work.

Exactness first: every margin comes from the same calls of
:mod:`synth.optimise.evaluate` (hence :mod:`synth.model`) on the same
arrays as the reference; what changes is how much of the catalog product is
evaluated and how often the application-independent work is repeated.

1. **Shared tables.** The spaces of one chunk share the tables that do not
   depend on the application (``build_space(..., cache=)``: bushing, axial,
   bolt tables; core table per working arm / fuel / typology; the spring
   material x wire x diameter product).
2. **Bolts over the applications axis.** Step 10 depends on the application
   and the bolt row only (not on the core), so it runs once per bolt row for
   all applications of the chunk (arrays over applications,
   :func:`synth.optimise.evaluate.bolt_fixation`), not once per row and
   application.
3. **Branch and bound on the main springs** (additive objectives: standard,
   cost, their orders and weighted sums without the margin). The best design
   is ``min over cores (core + best bushing + best axial + best spring +
   best bolt)``; the three cheap subsystems are evaluated exactly for every
   core that passes its own constraints. The springs (thousands of options)
   are evaluated in increasing score order, in growing blocks, per distinct
   spring key (torque, housing height and diameters): the first feasible
   option in that order is the key's best (a stable sort keeps the
   reference's lowest-index tie-break), and a key is dropped once
   ``lower bound of its cores + score of the next unevaluated option`` exceeds
   the best complete design found (scores are non-negative sums, so the bound
   is valid). Objectives with the margin use the full evaluation.
4. **Nearest design** (infeasible applications): the max-min margin over all
   cores, with the spring subsystem evaluated in decreasing order of the
   cores' upper bound (their margin without springs) and stopped when the
   next bound is below the best value found.
5. **Feasibility probes** of the relaxation bisection stop at the first
   complete feasible design and evaluate the springs only for cores whose
   other subsystems can be completed.
6. **Catalog constants** are a dict lookup (``synth.catalog`` caches the
   merged constants files; before that cache one lookup cost 2.3 ms and an
   application needs hundreds).

At ``full`` fidelity the plastic-wear ODE integrates a whole batch with shared
adaptive steps, so the axial subsystem is always evaluated on exactly the
reference's batch (every core passing its own constraints, or every core for
the nearest design) and the chosen design is re-evaluated alone, as
:func:`synth.optimise.result.verify` does.
"""

from __future__ import annotations

import dataclasses
import types

import numpy as np

from synth import catalog
from synth.errors import InputError
from synth.optimise import diagnose as _diag
from synth.optimise import evaluate as E
from synth.optimise.evaluate import CONSTRAINTS, FEAS_TOL
from synth.optimise.objectives import Objective
from synth.optimise.result import DesignResult, binding_of, design_margin, objective_values, parts_of
from synth.optimise.space import build_space

__all__ = ["screen_fast", "solve_fast", "bolt_fixations"]

_FIX_ARRAYS = ("middle_plane_belt_height_mm", "tilting_safety_factor", "sliding_safety_factor",
               "engine_support_internal_diameter_mm", "engine_support_external_diameter_mm", "contact_angle_deg",
               "support_yield_strength_compression_mpa", "support_yield_strength_traction_mpa", "number_of_active_threads")


def bolt_fixations(apps: list, hubloads: list, bolt_rows: list) -> list:
    """Step 10 for every application x bolt row, one call per bolt row over the applications axis.

    Returns, per application, ``{(format, class): {key: value}}`` as
    :func:`synth.optimise.evaluate.bolt_fixation` gives it (None when the
    application lacks fixation data). Applications are grouped by
    environment and by whether the head diameter is given (the function's
    string and optional arguments).
    """
    out: list = [None] * len(apps)
    groups: dict = {}
    for i, d in enumerate(apps):
        if d is not None and not d.missing(*E._FIX_FIELDS):
            groups.setdefault((d.application_type, d.bolt_head_contact_external_diameter_mm is None), []).append(i)
    for (env, no_head), idx in groups.items():
        g = [apps[i] for i in idx]
        ns = types.SimpleNamespace(**{k: np.array([float(getattr(d, k)) for d in g]) for k in _FIX_ARRAYS})
        ns.middle_plane_belt_height_increment_worst_mm = np.array(
            [0.0 if d.middle_plane_belt_height_increment_worst_mm is None else float(d.middle_plane_belt_height_increment_worst_mm)
             for d in g])
        ns.application_type = env
        ns.bolt_head_contact_external_diameter_mm = None if no_head else np.array(
            [float(d.bolt_head_contact_external_diameter_mm) for d in g])
        hl = np.array([hubloads[i] for i in idx], float)
        for i in idx:
            out[i] = {}
        for fmt, cls in bolt_rows:
            r = E.bolt_fixation(ns, hl, fmt, cls)
            for j, i in enumerate(idx):
                out[i][(fmt, cls)] = {k: float(np.broadcast_to(v, (len(idx),))[j]) for k, v in r.items()}
    return out


# ------------------------------------------------------------------------------------------------
# evaluation pieces
# ------------------------------------------------------------------------------------------------

def _core(sp):
    names, arr, avail, cv = E._core(sp)
    if "cone_spring_annulus" in names:
        cv["cone_spring_annulus_ok"] = arr[:, names.index("cone_spring_annulus")] > 0
    else:
        cv["cone_spring_annulus_ok"] = np.zeros(len(arr), bool)
    ok = avail & np.all(arr >= -FEAS_TOL, axis=1) if arr.shape[1] else avail
    return names, arr, avail, cv, ok


def _weights_vec(table, weights: dict) -> np.ndarray:
    out = np.zeros(len(table))
    for k, w in weights.items():
        out += w * table["nonstandard" if k == "standard" else "cost_eur"].to_numpy(float)
    return out


def _spring_feasible(sp, uniq, options) -> np.ndarray:
    _, m, _ = E.spring_margins(sp, uniq, options)
    return np.all(m >= -FEAS_TOL, axis=2) if m.shape[2] else np.ones(m.shape[:2], bool)


def _optimum_additive(sp, weights: dict, cv, ok):
    """Exact optimum of an additive objective: ``(core, options)`` or None (see the module docstring, 3.)."""
    rows = np.flatnonzero(ok)
    if not len(rows):
        return None
    cv["row"] = rows
    idx = np.arange(len(rows))
    core_score = _weights_vec(sp.cores, weights)[rows]
    best, pick = {}, {}
    for s in ("bushing", "axial", "bolt"):
        sub = E._SUB_FUNCS[s](sp, cv, rows, False)
        sc = np.where(sub.feasible(), _weights_vec(sp.subsystems[s], weights)[None, :], np.inf)
        k = np.argmin(sc, axis=1) if sc.shape[1] else np.zeros(len(sc), int)
        best[s] = sc[idx, k] if sc.shape[1] else np.full(len(rows), np.inf)
        pick[s] = k
    partial = core_score + best["bushing"] + best["axial"] + best["bolt"]
    uniq, inv = np.unique(E.spring_keys(cv, rows), axis=0, return_inverse=True)
    inv = np.asarray(inv).reshape(-1)
    lb_key = np.full(len(uniq), np.inf)
    np.minimum.at(lb_key, inv, partial)
    s_score = _weights_vec(sp.subsystems["spring"], weights)
    order = np.argsort(s_score, kind="stable")
    sp_best = np.full(len(uniq), np.inf)
    sp_pick = np.zeros(len(uniq), int)
    active = np.isfinite(lb_key)
    pos, block, best_total = 0, int(catalog.constant("bulk_spring_first_block")), np.inf
    while active.any() and pos < len(order):
        blk = order[pos:pos + block]
        ua = np.flatnonzero(active)
        feas = _spring_feasible(sp, uniq[ua], blk)
        has = feas.any(axis=1)
        first = np.argmax(feas, axis=1)
        hit = ua[has]
        sp_pick[hit] = blk[first[has]]
        sp_best[hit] = s_score[sp_pick[hit]]
        active[hit] = False
        best_total = min(best_total, float(np.min(partial + sp_best[inv])))
        pos += len(blk)
        block *= int(catalog.constant("bulk_spring_block_growth"))
        if pos < len(order) and np.isfinite(best_total):
            slack = 1e-9 * max(1.0, abs(best_total))
            active &= ~(lb_key + s_score[order[pos]] > best_total + slack)
    total = core_score + best["bushing"]
    total = total + best["axial"]
    total = total + sp_best[inv]
    total = total + best["bolt"]
    if not np.isfinite(total).any():
        return None
    r = int(np.argmin(total))
    return int(rows[r]), {"bushing": int(pick["bushing"][r]), "axial": int(pick["axial"][r]),
                          "spring": int(sp_pick[inv[r]]), "bolt": int(pick["bolt"][r])}


def _optimum_full(sp, obj, ev=None):
    from synth.optimise.solvers.enumerate import solve_space
    core, options, _ = solve_space(sp, obj, ev or E.evaluate(sp))
    return None if core is None else (core, options)


def _nearest(sp, arr, avail, cv):
    """The nearest design (max-min margin over all cores), as :func:`synth.optimise.diagnose.nearest_design`."""
    n = len(arr)
    rows = np.arange(n)
    cv["row"] = rows
    core_m = np.where(avail, np.min(arr, axis=1) if arr.shape[1] else np.inf, -np.inf)
    best_k = {}
    for s in ("bushing", "axial", "bolt"):
        sub = E._SUB_FUNCS[s](sp, cv, rows, False)
        m = np.where(sub.available, sub.min_margin(), -np.inf)
        best_k[s] = np.argmax(m, axis=1)
        core_m = np.minimum(core_m, m[rows, best_k[s]])
    uniq, inv = np.unique(E.spring_keys(cv, rows), axis=0, return_inverse=True)
    inv = np.asarray(inv).reshape(-1)
    kmax = np.zeros(len(uniq), int)
    mmax = np.full(len(uniq), np.nan)

    def eval_keys(keys):
        keys = [k for k in dict.fromkeys(keys) if np.isnan(mmax[k])]
        if keys:
            _, m, _ = E.spring_margins(sp, uniq[keys])
            m = np.min(m, axis=2) if m.shape[2] else np.full(m.shape[:2], np.inf)
            kmax[keys] = np.argmax(m, axis=1)
            mmax[keys] = m[np.arange(len(keys)), kmax[keys]]

    val = np.full(n, -np.inf)
    order = np.argsort(-core_m, kind="stable")
    best = -np.inf
    step = int(catalog.constant("bulk_nearest_key_batch"))
    for start in range(0, n, step):
        batch = order[start:start + step]
        batch = batch[core_m[batch] >= best]
        if not len(batch):
            break
        eval_keys(inv[batch].tolist())
        val[batch] = np.minimum(core_m[batch], mmax[inv[batch]])
        best = max(best, float(np.max(val)))
    r = int(np.argmax(val))
    eval_keys([inv[r]])
    return r, {"bushing": int(best_k["bushing"][r]), "axial": int(best_k["axial"][r]),
               "spring": int(kmax[inv[r]]), "bolt": int(best_k["bolt"][r])}


def _feasible(sp) -> bool:
    """Whether some design of ``sp`` meets every constraint (as :func:`synth.optimise.diagnose.is_feasible`)."""
    _, _, _, cv, ok = _core(sp)
    rows = np.flatnonzero(ok)
    if not len(rows):
        return False
    cv["row"] = rows
    good = np.ones(len(rows), bool)
    for s in ("bushing", "bolt"):
        good &= E._SUB_FUNCS[s](sp, cv, rows, False).feasible().any(axis=1)
    if sp.fidelity == "full":  # the ODE batch must be the reference's
        good &= E._SUB_FUNCS["axial"](sp, cv, rows, False).feasible().any(axis=1)
    elif good.any():
        sel = np.flatnonzero(good)
        good[sel] = E._SUB_FUNCS["axial"](sp, cv, rows[sel], False).feasible().any(axis=1)
    if not good.any():
        return False
    uniq = np.unique(E.spring_keys(cv, rows[good]), axis=0)
    nk = len(sp.subsystems["spring"])
    pos, block = 0, int(catalog.constant("bulk_spring_first_block"))
    while pos < nk:
        blk = np.arange(pos, min(pos + block, nk))
        if _spring_feasible(sp, uniq, blk).any():
            return True
        pos += len(blk)
        block *= int(catalog.constant("bulk_spring_block_growth"))
    return False


def _verified_margins(sp, parts: dict):
    """Margins and availability of one design evaluated alone (as :func:`synth.optimise.result.verify`)."""
    rsp = sp.restrict(parts)
    sizes = [rsp.n_cores] + [len(t) for t in rsp.subsystems.values()]
    if min(sizes) != 1:
        raise ValueError(f"parts do not name exactly one design: {sizes} rows match")
    ev = E.evaluate(rsp, prune=False)
    margins = {n: float(ev.core_margin_array[0, j]) for j, n in enumerate(ev.core_names)}
    available = bool(ev.core_available[0])
    for sub in ev.subs.values():
        available &= bool(sub.available[0, 0])
        margins.update({n: float(sub.margins[0, 0, j]) for j, n in enumerate(sub.names)})
    ax = bool(np.asarray(ev.core_values["axial_damping_present"]).reshape(-1)[0])
    return margins, available, ax


def _objective_name(obj: Objective) -> str:
    if obj.weights:
        return ",".join(f"{k}={v:g}" for k, v in obj.weights.items())
    return ",".join(obj.order)


def solve_fast(d, sp, obj: Objective, *, relax: bool = True, probe_cache: dict | None = None,
               bolt: dict | None = None) -> DesignResult:
    """The result of ``solve(d, obj, "enumerate", fidelity=sp.fidelity, relax=relax)`` for the space ``sp`` of ``d``.

    Same status, parts, margins, binding, objectives, notes and relaxations;
    no derived values and no solver statistics (the bulk row does not use them).
    """
    with np.errstate(over="ignore", divide="ignore", invalid="ignore"):
        _, arr, avail, cv, ok = _core(sp)
        if obj.uses_margin():
            found = _optimum_full(sp, obj)
        else:
            w = obj.additive_weights()
            found = _optimum_additive(sp, w if w else {"cost": 1.0}, cv, ok)
        status = "optimal" if found else "infeasible"
        if found:
            core, options = found
        else:
            _, arr, avail, cv, ok = _core(sp)
            core, options = _nearest(sp, arr, avail, cv)
        parts = parts_of(sp, core, options)
        margins, available, ax = _verified_margins(sp, parts)
    margin = design_margin(margins, ax)
    res = DesignResult(status=status, solver="enumerate", objective=_objective_name(obj), parts=parts,
                       margins=margins, binding=binding_of(margins, ax),
                       objectives=objective_values(sp, core, options, margin), notes=list(sp.notes))
    failed = {k: m for k, m in margins.items() if m < -FEAS_TOL}
    if not (available and not failed):
        res.notes.append("verification failed: " + ", ".join(f"{k} {m:+.3g}" for k, m in failed.items()))
    if status == "infeasible":
        res.binding = [{"constraint": k, "label": CONSTRAINTS[k][1], "step": CONSTRAINTS[k][0],
                        "equation": CONSTRAINTS[k][2], "margin": m} for k, m in sorted(failed.items(), key=lambda kv: kv[1])]
        probe = _prober(probe_cache if probe_cache is not None else {}, bolt)
        res.diagnosis = {
            "message": "no design of the catalog product meets every constraint; the nearest design is shown",
            "violated": res.binding,
            "relaxations": _diag.relaxations(d, list(failed), fidelity=sp.fidelity, probe=probe) if relax else [],
        }
    return res


def _prober(cache: dict, bolt: dict | None):
    """A feasibility probe for :func:`synth.optimise.diagnose.relaxations`, equal to its default one."""
    fix = set(E._FIX_FIELDS) | {"middle_plane_belt_height_mm", "middle_plane_belt_height_increment_worst_mm",
                                "bolt_head_contact_external_diameter_mm", "application_type"}

    def probe(d, changes: dict, fidelity):
        try:
            d1 = dataclasses.replace(d, **changes)
            sp = build_space(d1, fidelity=fidelity, cache=cache)
            if bolt is not None and not (set(changes) & fix):
                sp.fixed["bolt_fixation"] = bolt
            with np.errstate(over="ignore", divide="ignore", invalid="ignore"):
                return _feasible(sp)
        except InputError:
            return False
    return probe


def screen_fast(apps, *, objective: str = "standard", fidelity: str = "screening", diagnose: bool = True):
    """The bulk result of ``apps`` (see :func:`synth.bulk.engine.screen_applications`)."""
    from synth.bulk.engine import error_row, frame, row_from_result
    obj = objective if isinstance(objective, Objective) else Objective.parse(objective)
    cache: dict = {}
    spaces = []
    for d in apps:
        try:
            spaces.append(build_space(d, fidelity=fidelity, cache=cache))
        except InputError as exc:
            spaces.append(exc)
    ok = [i for i, sp in enumerate(spaces) if not isinstance(sp, Exception)]
    bolts: list = [None] * len(apps)
    if ok:
        t = spaces[ok[0]].subsystems["bolt"]
        pre = bolt_fixations([apps[i] for i in ok], [spaces[i].fixed["hubload_nominal_n"] for i in ok],
                             list(zip(t["bolt_format"], t["bolt_property_class"])))
        for i, b in zip(ok, pre):
            bolts[i] = b
    rows = []
    for i, (d, sp) in enumerate(zip(apps, spaces)):
        if isinstance(sp, Exception):
            rows.append(error_row(sp))
            continue
        if bolts[i] is not None:
            sp.fixed["bolt_fixation"] = bolts[i]
        res = solve_fast(d, sp, obj, relax=diagnose, probe_cache=cache, bolt=bolts[i])
        rows.append(row_from_result(res, d, diagnose))
    return frame(rows)
