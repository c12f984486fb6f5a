"""``synth bulk --capability``: each application's design re-selected for the production capability target.

A run whose configuration carries a capability target (:attr:`synth.design.settings.Settings.capability`, a
:class:`~synth.robust.settings.RobustSettings`: ``--capability``/``--ppm``, or the design rules' targets) gives
every application the design ``synth design --capability`` gives it: the best design of the objective whose
every targeted check meets the target, or, when none does, the nominal optimum with what prevents the target.
There is one mechanism, the design's own: :func:`synth.optimise.honour.solve_honouring` with ``robust=`` (the
robust synthesis, :func:`synth.robust.synthesis.robust_solve`), per application, under the run's one
:class:`~synth.design.settings.Settings` (also in a Dask worker: it travels with the chunk), at the model that judges a
design (``Settings.judge``: the bulk's default fidelity ``screening`` takes the full model for these rows, as ``synth
design`` does; before, the screening search chose another design of equal objective on 4 of 50 rows and another
robust search's answer on 1). The bulk leaves out
only the search of the one input or tolerance value that would allow a design (``explain=False``: the same
design; ``synth design`` on that application names it), and keeps the row's words on what prevents the target:
the checks that rejected the candidates, how often, their best Ppk and what drives their scatter
(:meth:`synth.robust.synthesis.SearchReport.why_none`).

One shortcut, exact: an application none of whose catalog designs passes every check with the made joint (the
design's tightening method and its VDI 2230 preload window, :func:`synth.robust.sampling.production`; checked for
the whole chunk at once by :func:`synth.optimise.batch.any_feasible`) has no candidate for the robust search, and
``synth design`` returns its nominal optimum: the bulk's nominal row (:func:`synth.bulk.engine.screen_applications`
without the target), with the robust search's words for why and, when that design passes nominally, its capability
as ``synth design`` reports it beside the design (:func:`synth.robust.synthesis.nominal_capability`: the smallest
Ppk, the failing checks, ...).

Columns (:data:`COLUMNS`, in every bulk result; empty without a target): ``capability_verdict`` (``PASS``: the
row's design meets the target; ``FAIL``: no catalog design does), its smallest Ppk and largest probability of
violation (upper 95 % end, ppm) over the targeted checks, the binding check (smallest Ppk), the failing checks,
and ``capability_why`` (what binds, or what prevents the target).
"""

from __future__ import annotations

import math

import numpy as np

from synth.design.space import fixed_fields
from synth.design.verdict import combine

__all__ = ["COLUMNS", "NUMBERS", "screen_robust", "capability_cells"]

#: the number columns among the capability columns (NaN when empty; the others are text, "" when empty)
NUMBERS = ("capability_min_ppk", "capability_max_ppm")
#: the capability columns of a bulk row (after the nominal ones; empty without a target)
COLUMNS = ("capability_verdict", *NUMBERS, "capability_binding",
           "capability_failing", "capability_why")


def capability_cells(res) -> dict:
    """The :data:`COLUMNS` of a robust synthesis's result ``res`` (:func:`synth.robust.synthesis.robust_solve`)."""
    return _cells(res.robust or {}, bool(res.stats.get("robust_found")), res.stats.get("robust_why", ""))


def _cells(rob: dict, found: bool, why: str) -> dict:
    """The :data:`COLUMNS` of a capability ``rob`` (:meth:`~synth.robust.capability.Capability.to_dict`, or empty:
    no design to judge), ``found``: whether the design meets the target, ``why``: what prevents it."""
    checks = [c for c in rob.get("checks", []) if c.get("target")]
    worst = min(checks, key=lambda c: math.inf if c.get("ppk") is None else c["ppk"], default=None)
    if found and worst is not None:
        why = f"binds: {worst['id']} Ppk {_g(worst.get('ppk'))}"
    prevented = (rob.get("prevented_by") or {}).get("text")
    return {"capability_verdict": "PASS" if found else "FAIL",
            "capability_min_ppk": _num(rob.get("min_ppk")),
            "capability_max_ppm": _num(rob.get("max_p_violation")) * 1e6,
            "capability_binding": worst["id"] if worst is not None else "",
            "capability_failing": " ".join(rob.get("failing", [])),
            "capability_why": "; ".join(x for x in (why, prevented) if x)}


def _num(v) -> float:
    return math.nan if v is None else float(v)


def _g(v) -> str:
    return "none" if v is None else f"{float(v):.3g}"


def _row(d, objective, settings, diagnose: bool, row_of) -> dict:
    from synth.optimise.honour import solve_honouring
    from synth.robust.synthesis import robust_for
    with np.errstate(all="ignore"):  # a check without scatter has no contributors (0/0): not the user's concern
        res = solve_honouring(d, objective, "enumerate", settings=settings, explain=False,
                              robust=robust_for(settings.capability))
    return {**row_of(res, diagnose), **capability_cells(res)}


def screen_robust(apps: list, objective, settings, diagnose: bool, nominal, row_of) -> list:
    """The rows (dicts of the bulk's columns) of ``apps`` under ``settings``'s capability target (see the module
    docstring); ``nominal(apps, settings)``: the bulk's nominal rows (a DataFrame) of ``apps`` without the target;
    ``row_of(result, diagnose)``: a result's row (:func:`synth.bulk.engine.row_from_result`).
    """
    from synth.optimise.batch import any_feasible
    from synth.robust.sampling import production
    from synth.design.space import PART_KEYS
    from synth.robust.synthesis import SearchReport, nominal_capability
    rs = settings.capability
    settings = settings.judge  # the robust synthesis's model (robust_solve): the shortcut's rows at it too
    rows: list = [None] * len(apps)
    # the shortcut applies where the robust search's space is the whole catalog (no part the input names)
    free = [i for i, d in enumerate(apps) if not fixed_fields(d, True)]
    made = any_feasible([apps[i] for i in free], production(settings)) if free else []
    none = [i for i, ok in zip(free, made) if not ok]
    if none:
        why = SearchReport().why_none(rs)  # no candidate: the robust search's own words
        df = nominal([apps[i] for i in none], settings.replace(capability=None))
        for i, row in zip(none, df.to_dict(orient="records")):
            notes = "; ".join(x for x in (row["notes"], why) if x)
            rob = {}
            if row["feasible"]:  # the nominal design's capability, as synth design reports it beside the design
                with np.errstate(all="ignore"):
                    rob = nominal_capability(apps[i], {k: row[f"part_{k}"] for k in PART_KEYS}, settings, rs)
            rows[i] = {**row, "verdict": combine(str(row["verdict"]), target_missed=True), "notes": notes,
                       **_cells(rob, False, why)}
    for i, d in enumerate(apps):
        if rows[i] is None:
            rows[i] = _row(d, objective, settings, diagnose, row_of)
    return rows
