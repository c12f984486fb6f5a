"""Bulk screening engine: one row per application, the same answer as ``solve(d, objective, "enumerate")``.

:func:`screen_applications` is the public entry point (the contract with the
bulk harness). It evaluates a chunk of applications together, on the
applications axis of the one evaluator (:mod:`synth.design.evaluate`): every
group function is called once per chunk with the rows of all applications,
never once per application. :func:`screen_applications_reference` loops over
:func:`synth.optimise.solve` and is the definition of the right answer that
the tests compare the fast path with.

Fast path, for additive objectives (``standard``, ``cost``, their orders and
weighted sums without the margin):

1. inputs and cores of every application (rows ``(application, core)``);
2. per feasible core, the cheapest feasible option of each subsystem, the
   options evaluated **in score order with early exit** (growing blocks; a
   stable order keeps the reference's lowest-index tie-break), the main spring
   once per distinct spring key;
3. per application the core with the smallest total score;
4. the chosen designs re-verified together through the registry's groups.

Objectives with the margin and infeasible applications (their nearest design
and diagnosis) take the per-application path.

Columns of the result (exactly, in this order): see :func:`columns`.
"""

from __future__ import annotations

import math
from typing import Sequence

import numpy as np
import pandas as pd

from synth import catalog
from synth.design import evaluate as E
from synth.design.applications import Applications
from synth.design.constraints import FEAS_TOL, REGISTRY
from synth.design.result import FAIL, PASS, WARNING
from synth.design.space import PART_KEYS, SUBSYSTEMS, core_rows, space
from synth.optimise.evaluate import core_scores, option_scores
from synth.optimise.solvers.enumerate import weights_vec

__all__ = ["columns", "constraint_ids", "screen_applications", "screen_applications_reference", "row_from_result"]


def constraint_ids() -> list:
    """The registry constraints a bulk row reports a margin for (every group but the 3D model's)."""
    return [cid for cid, c in REGISTRY.items() if c.group != "cad"]


def columns() -> list:
    """The result columns, in order (the contract with the harness).

    >>> cols = columns()
    >>> cols[:2], "part_ball_bearing" in cols, "margin_self_locking" in cols, cols[-1]
    (['feasible', 'status'], True, True, 'notes')
    """
    return (["feasible", "status", "verdict", "objective_standard", "objective_cost_eur", "objective_margin"]
            + [f"part_{k}" for k in PART_KEYS]
            + ["margin_min", "binding_constraint", "binding_margin"]
            + [f"margin_{n}" for n in constraint_ids()]
            + ["violated", "relaxation", "notes"])


def _num(v):
    return float(v) if v is not None else math.nan


def _g(x) -> str:
    return f"{float(x):.6g}"


def _fmt_relaxation(rel: dict) -> str:
    return ", ".join(f"{name} {_g(ch['from'])}->{_g(ch['to'])}" for name, ch in rel["inputs"].items())


def row_from_result(res, diagnose: bool = True) -> dict:
    """One result row (dict of :func:`columns`) from a :class:`~synth.design.result.Result`.

    ``binding_constraint`` is the design's most critical constraint: the
    smallest margin counted in the margin objective when feasible, the most
    violated constraint when infeasible; ``margin_min`` is the smallest margin
    of all evaluated (non-advisory) constraints. Constraints that are not
    verified or do not apply have no margin (NaN); ``notes`` says why.
    """
    feasible = res.status in ("optimal", "feasible") and not res.failed()
    m = res.margins
    row = {"feasible": bool(feasible), "status": "optimal" if feasible else "infeasible", "verdict": res.verdict,
           "objective_standard": _num(res.objectives.get("standard")),
           "objective_cost_eur": _num(res.objectives.get("cost")),
           "objective_margin": _num(res.objectives.get("margin"))}
    for k in PART_KEYS:
        row[f"part_{k}"] = res.parts.get(k)
    row["margin_min"] = float(min(m.values())) if m else math.inf
    failed = sorted(res.failed(), key=lambda c: c.margin)
    binds = failed[:1] if failed else res.binding(1)
    if binds:
        row["binding_constraint"], row["binding_margin"] = binds[0].id, float(binds[0].margin)
    else:
        row["binding_constraint"], row["binding_margin"] = "", math.inf
    every = {c.id: c.margin for c in res.checks if c.margin is not None and c.verdict in (PASS, FAIL, WARNING)}
    for n in constraint_ids():  # advisory constraints carry their margin, passing or warning
        row[f"margin_{n}"] = float(every[n]) if n in every else math.nan
    row["violated"] = ";".join(f"{c.id}:{c.margin:+.3f}" for c in failed) if not feasible else ""
    rel = (res.diagnosis or {}).get("relaxations") or []
    row["relaxation"] = _fmt_relaxation(rel[0]) if (rel and diagnose and not feasible) else ""
    notes = [str(n) for n in res.notes]
    nv = {}
    for c in res.not_verified():
        nv.setdefault(c.note.replace("not verified: ", ""), []).append(c.id)
    if nv:
        notes.append("not verified: " + "; ".join(f"{', '.join(ids)} ({why})" for why, ids in nv.items()))
    if res.assumptions():
        notes.append("assumed: " + "; ".join(a.replace(" assumed", "") for a in res.assumptions()))
    row["notes"] = "; ".join(dict.fromkeys(notes))
    return row


def error_row(exc: Exception) -> dict:
    """The row of an application that cannot be evaluated (its message in ``notes``)."""
    row = {c: math.nan for c in columns()}
    row.update({"feasible": False, "status": "infeasible", "verdict": "fail", "binding_constraint": "", "violated": "",
                "relaxation": "", "notes": f"not evaluated: {exc}".replace("\n", "; ")})
    row.update({f"part_{k}": None for k in PART_KEYS})
    return row


def frame(rows: list) -> pd.DataFrame:
    """The result DataFrame of ``rows`` (dicts of :func:`columns`), index 0..n-1, fixed dtypes."""
    df = pd.DataFrame(rows, columns=columns()) if rows else pd.DataFrame({c: pd.Series(dtype=object) for c in columns()})
    df["feasible"] = df["feasible"].astype(bool)
    for c in df.columns:
        if c.startswith(("objective_", "margin_")) or c == "binding_margin":
            df[c] = df[c].astype(float)
    return df.reset_index(drop=True)


def screen_applications_reference(apps: Sequence, *, objective: str = "standard", fidelity: str = "screening",
                                  diagnose: bool = True) -> pd.DataFrame:
    """Reference engine: ``solve(d, objective, "enumerate")`` per application (slow; the right answer)."""
    from synth.errors import InputError
    from synth.optimise import solve
    settings = E.Settings(fidelity=fidelity)
    rows = []
    for d in apps:
        try:
            rows.append(row_from_result(solve(d, objective, "enumerate", settings=settings, relax=diagnose), diagnose))
        except InputError as exc:
            rows.append(error_row(exc))
    return frame(rows)


# --------------------------------------------------------------------------------------------------------------
# the fast path
# --------------------------------------------------------------------------------------------------------------

def _first_feasible(n_rows: int, order: np.ndarray, ok_of, first: int, growth: int) -> np.ndarray:
    """Per row, the first option of ``order`` that ``ok_of(rows, options) -> bool`` accepts (-1: none).

    Options are tried in growing blocks; a row stops at its first feasible option, so the cheapest
    feasible option (in score order, ties by position) is found without evaluating the rest.
    """
    pick = np.full(n_rows, -1, dtype=np.int64)
    active = np.arange(n_rows)
    pos, block = 0, max(int(first), 1)
    while len(active) and pos < len(order):
        blk = order[pos:pos + block]
        rr, kk = (x.ravel() for x in np.meshgrid(active, np.arange(len(blk)), indexing="ij"))
        ok = ok_of(rr, blk[kk]).reshape(len(active), len(blk))
        has = ok.any(axis=1)
        pick[active[has]] = blk[np.argmax(ok[has], axis=1)]
        active = active[~has]
        pos += len(blk)
        block *= max(int(growth), 1)
    return pick


def _solve_chunk(inputs: list, weights: dict, settings: E.Settings) -> list:
    """``[(core row, {subsystem: option row}) or None]`` per application: the exact additive optimum."""
    sp = space()
    apps = Applications.of(inputs)
    n = len(apps)
    first, growth = int(catalog.constant("bulk_spring_first_block")), int(catalog.constant("bulk_spring_block_growth"))
    with np.errstate(over="ignore", divide="ignore", invalid="ignore"):
        ig = E.inputs(apps, np.arange(n))
        in_ok = ig.ok()
        per_app = [core_rows(sp, d) for d in inputs]
        a = np.concatenate([np.full(len(c), i, dtype=np.int64) for i, c in enumerate(per_app)])
        c = np.concatenate(per_app)
        keep = in_ok[a]
        a, c = a[keep], c[keep]
        cg = E.core(apps, a, sp.rows("core", c), settings)
        ok = cg.ok()
        rows = np.flatnonzero(ok)
        a_r, c_r = a[rows], c[rows]
        cv = {k: cg.values[k][rows] for k in ("pivot_class_standard_mm", "pivot_class_diameter_mm")}
        total = weights_vec(core_scores(sp, c_r, cv), weights)
        pick = {}
        # bushing: options of the core's supplier, in score order
        sc = weights_vec(option_scores(sp, "bushing"), weights)
        sup_opt = sp.tables["bushing"]["supplier_code"]
        bpick = np.full(len(rows), -1, dtype=np.int64)
        for s in np.unique(cg.values["supplier_code"][rows]):
            sel = np.flatnonzero(cg.values["supplier_code"][rows] == s)
            opts = np.flatnonzero(sup_opt == s)
            order = opts[np.argsort(sc[opts], kind="stable")]
            bpick[sel] = _first_feasible(len(sel), order, lambda rr, kk: E.bushing(
                apps, cg, rows[sel][rr], sp.rows("bushing", kk), settings).ok(), len(order), 1)
        pick["bushing"] = bpick
        # axial: the none option for cores without a pad, real options in score order for the others
        sc = weights_vec(option_scores(sp, "axial"), weights)
        real = sp.tables["axial"]["axial_group_present"]
        has_pad = cg.values["axial_group_present"][rows] > 0
        apick = np.full(len(rows), -1, dtype=np.int64)
        none = np.flatnonzero(~real)
        sel = np.flatnonzero(~has_pad)
        if len(sel):
            apick[sel] = _first_feasible(len(sel), none, lambda rr, kk: E.axial(
                apps, cg, rows[sel][rr], sp.rows("axial", kk), settings).ok(), 1, 1)
        sel = np.flatnonzero(has_pad)
        if len(sel):
            opts = np.flatnonzero(real)
            order = opts[np.argsort(sc[opts], kind="stable")]
            apick[sel] = _first_feasible(len(sel), order, lambda rr, kk: E.axial(
                apps, cg, rows[sel][rr], sp.rows("axial", kk), settings).ok(), first, growth)
        pick["axial"] = apick
        # bolt: step 10 per application and bolt (no core dependence), the pivot wall per core
        nb = sp.n("bolt")
        ua = np.unique(a_r)
        fa, fb = (x.ravel() for x in np.meshgrid(ua, np.arange(nb), indexing="ij"))
        fix = E.fixation_values(apps, fa, sp.rows("bolt", fb), settings)
        slot = {int(x): i for i, x in enumerate(ua)}
        sc = weights_vec(option_scores(sp, "bolt"), weights)
        order = np.argsort(sc, kind="stable")
        app_slot = np.array([slot[int(x)] for x in a_r], dtype=np.int64)

        def bolt_ok(rr, kk):
            idx = app_slot[rr] * nb + kk
            return E.bolt(apps, cg, rows[rr], sp.rows("bolt", kk), settings,
                          fixation={k: v[idx] for k, v in fix.items()}).ok()
        pick["bolt"] = _first_feasible(len(rows), order, bolt_ok, nb, 1)
        # main spring: once per distinct key, options in score order (the cost order does not depend on k)
        keys = E.spring_keys(cg, rows)
        stack = np.stack([keys["app"].astype(float)] + [keys[k] for k in (
            "spring_torque_nominal_nm", "spring_housing_height_mm", "spring_housing_outer_diameter_mm",
            "spring_housing_inner_diameter_mm")], axis=1)
        uniq, inv = np.unique(stack, axis=0, return_inverse=True)
        inv = np.asarray(inv).reshape(-1)
        ukeys = {"app": uniq[:, 0].astype(np.int64), "spring_torque_nominal_nm": uniq[:, 1],
                 "spring_housing_height_mm": uniq[:, 2], "spring_housing_outer_diameter_mm": uniq[:, 3],
                 "spring_housing_inner_diameter_mm": uniq[:, 4]}
        mbd = sp.tables["spring"]["main_spring_mean_body_diameter_mm"]
        sc = weights_vec(option_scores(sp, "spring", 1.0), weights)  # the order: the cost is (per-unit cost) / k
        spick_key = np.full(len(uniq), -1, dtype=np.int64)
        for ai in np.unique(ukeys["app"]):  # the searched diameters follow each application's housings
            ks = np.flatnonzero(ukeys["app"] == ai)
            lo = np.floor(ukeys["spring_housing_inner_diameter_mm"][ks].min()) - 1e-9
            hi = np.ceil(ukeys["spring_housing_outer_diameter_mm"][ks].max()) + 1e-9
            opts = np.flatnonzero((mbd >= lo) & (mbd <= hi))
            order = opts[np.argsort(sc[opts], kind="stable")]
            spick_key[ks] = _first_feasible(len(ks), order, lambda rr, kk: E.spring(
                apps, ukeys, ks[rr], sp.rows("spring", kk), settings).ok(), first, growth)
        pick["spring"] = spick_key[inv]
        k_app = apps.spring_stiffness_nm_per_deg[a_r]
        for s in SUBSYSTEMS:  # the same sums, in the same order, as synth.optimise.solvers.enumerate
            p = pick[s]
            pp = np.maximum(p, 0)
            if s == "spring":
                s_sc = weights_vec({"standard": sp.tables["spring"]["nonstandard"][pp],
                                    "cost": sp.spring_cost_eur(k_app, pp)}, weights)
            else:
                s_sc = weights_vec(option_scores(sp, s), weights)[pp]
            total = total + np.where(p >= 0, s_sc, np.inf)
    out: list = [None] * n
    for i in range(n):
        sel = np.flatnonzero((a_r == i) & np.isfinite(total))
        if not len(sel):
            continue
        j = sel[np.argmin(total[sel])]
        out[i] = (int(c_r[j]), {s: int(pick[s][j]) for s in SUBSYSTEMS})
    return out


def screen_applications(apps: Sequence, *, objective: str = "standard", fidelity: str = "screening",
                        diagnose: bool = True) -> pd.DataFrame:
    """One row per application of ``apps`` (validated ``DesignInput``), in the order given (index 0..n-1).

    ``objective`` as :func:`synth.optimise.solve` accepts it; ``fidelity``
    ``screening`` (closed-form wear, linear cone spring) or ``full``;
    ``diagnose=False`` skips the relaxation search of infeasible applications.
    Columns: :func:`columns`. The same answer as :func:`screen_applications_reference`.

    >>> from synth.data.generated_applications import generate
    >>> df = screen_applications(generate(2, seed=0), objective="cost")
    >>> list(df.index), df.loc[1, "status"]
    ([0, 1], 'optimal')
    """
    from synth.errors import InputError
    from synth.optimise import solve
    from synth.optimise.objectives import Objective
    from synth.optimise.result import build_result
    settings = E.Settings(fidelity=fidelity)
    obj = objective if isinstance(objective, Objective) else Objective.parse(objective)
    apps = list(apps)
    rows: list = [None] * len(apps)
    if obj.uses_margin():
        return screen_applications_reference(apps, objective=objective, fidelity=fidelity, diagnose=diagnose)
    w = obj.additive_weights() or {"cost": 1.0}
    chosen = _solve_chunk(apps, w, settings)
    from synth.design.verify import verify
    from synth.optimise.evaluate import design_scores
    from synth.optimise.result import design_margin, objective_name
    sp = space()
    for i, (d, ch) in enumerate(zip(apps, chosen)):
        try:
            if ch is None:
                res = solve(d, obj, "enumerate", settings=settings, relax=diagnose)
            else:
                core, opts = ch
                from synth.design.verify import parts_of_attributes
                attrs = {"core": sp.rows("core", [core]), **{s: sp.rows(s, [opts[s]]) for s in SUBSYSTEMS}}
                app1 = Applications.of([d])
                cg = E.core(app1, np.zeros(1, dtype=np.int64), attrs["core"], settings)
                parts = parts_of_attributes(attrs, {"core": cg})
                res = verify(d, parts, settings, status="optimal", solver="enumerate", detail=False)
                res.objective = objective_name(obj)
                res.objectives = {**design_scores(d, parts, settings), "margin": design_margin(res)}
            rows[i] = row_from_result(res, diagnose)
        except InputError as exc:
            rows[i] = error_row(exc)
    return frame(rows)
