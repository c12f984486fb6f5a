"""Bulk screening engine: one row per application, the same answer as ``solve(d, objective, "enumerate")``.

:func:`screen_applications` is the public entry point (the contract with the
bulk harness); :func:`screen_applications_reference` loops over
:func:`synth.optimise.solve` one application at a time and is kept for
cross-checking.

Columns of the result (exactly, in this order): see :func:`columns`.
"""

from __future__ import annotations

import math
from typing import Sequence

import numpy as np
import pandas as pd

from synth.optimise.evaluate import CONSTRAINTS, FEAS_TOL
from synth.optimise.result import PART_KEYS

__all__ = ["columns", "screen_applications", "screen_applications_reference", "row_from_result", "absent_note"]

_AXIAL_GROUP = ("damper_pad_capacity", "cone_spring_annulus", "endcap_spacer_capacity", "cone_force_band",
                "cone_diameter_ratio", "cone_aspect_ratio", "cone_thinness", "cone_not_flattened", "cone_sigma_om",
                "cone_table8_range", "damping_eol", "damper_pad_wear", "endcap_spacer_wear")
_DURABILITY_GROUP = ("bushing_p", "bushing_pv", "bushing_pvt", "bushing_wear", "bushing_length", "bushing_parallelism",
                     "damping_eol", "damper_pad_wear", "endcap_spacer_wear")
_BOLT_GROUP = ("tilting", "sliding", "bolt_yield", "under_head", "thread", "pivot_bore", "pivot_base_pressure")


def _reasons(d, parts: dict) -> list:
    """``[(constraint names, why)]``: the reasons, in order, why constraints of ``d`` may not be evaluated."""
    from synth.optimise.evaluate import _FIX_FIELDS
    from synth.optimise.space import durability_of
    out = []
    if d.missing("lockup_pin_position_radius_mm", "lockup_pin_angular_position_deg", "lockup_pin_diameter_mm"):
        out.append((("pin_within_pulley", "pin_clearance"), "lock-up pin data not given"))
    elif d.missing("wrap_angle_deg", "nominal_arm_angle_from_EHR_deg"):
        out.append((("pin_clearance",), "wrap angle or nominal arm angle not given"))
    if d.belt_loading_type == "single_eccentric":
        out.append((("loading_arm",), "single eccentric loading (no loading arm)"))
    if d.damping_target_nm is None or d.damping_tolerance_nm is None:
        out.append((("damping_upper", "damping_lower", "cone_force_band"), "damping target or tolerance not given"))
    if durability_of(d) is None:
        out.append((_DURABILITY_GROUP, "durability test not given"))
    if not d.pulley_max_parallelism_eol_mm:
        out.append((("bushing_parallelism",), "pulley parallelism limit not given"))
    if d.damping_eol_limit_nm is None:
        out.append((("damping_eol",), "end-of-life damping limit not given"))
    if d.damping_typology == "only_radial":
        out.append((_AXIAL_GROUP, "only radial damping"))
    elif parts.get("damper_pad") in (None, "none"):
        out.append((_AXIAL_GROUP, "the design has no axial damping group"))
    if d.missing(*_FIX_FIELDS):
        out.append((_BOLT_GROUP, "fixation data not given"))
    return out


def columns() -> list:
    """The result columns, in order (the contract with the harness).

    >>> cols = columns()
    >>> cols[:2], "part_bearing" in cols, "margin_self_locking" in cols, cols[-1]
    (['feasible', 'status'], True, True, 'notes')
    """
    return (["feasible", "status", "objective_standard", "objective_cost_eur", "objective_margin"]
            + [f"part_{k}" for k in PART_KEYS]
            + ["margin_min", "binding_constraint", "binding_margin"]
            + [f"margin_{n}" for n in CONSTRAINTS]
            + ["violated", "relaxation", "notes"])


def _num(v):
    return float(v) if v is not None else math.nan


def _fmt_relaxation(rel: dict) -> str:
    return ", ".join(f"{name} {_g(ch['from'])}->{_g(ch['to'])}" for name, ch in rel["inputs"].items())


def _g(x) -> str:
    return f"{float(x):.6g}"


def absent_note(d, parts: dict, margins) -> str:
    """``"not evaluated: a, b (why); c (why)"`` for the constraints of :data:`CONSTRAINTS` not in ``margins``."""
    left = [n for n in CONSTRAINTS if n not in margins]
    if not left:
        return ""
    out = []
    for names, why in _reasons(d, parts):
        hit = [n for n in left if n in names]
        if hit:
            out.append(", ".join(hit) + f" ({why})")
            left = [n for n in left if n not in hit]
    if left:
        out.append(", ".join(left) + " (not applicable)")
    return "not evaluated: " + "; ".join(out)


def row_from_result(res, d, diagnose: bool = True) -> dict:
    """One result row (dict of :func:`columns`) from a :class:`~synth.optimise.result.DesignResult`.

    ``binding_constraint`` is the design's most critical constraint: the
    first of ``res.binding`` (the smallest counted margin when feasible, the
    most violated constraint when infeasible); ``margin_min`` is the smallest
    margin of all evaluated constraints.
    """
    feasible = res.status in ("optimal", "feasible")
    m = res.margins
    row = {"feasible": bool(feasible), "status": "optimal" if feasible else "infeasible",
           "objective_standard": _num(res.objectives.get("standard")),
           "objective_cost_eur": _num(res.objectives.get("cost")),
           "objective_margin": _num(res.objectives.get("margin"))}
    for k in PART_KEYS:
        row[f"part_{k}"] = res.parts.get(k)
    row["margin_min"] = float(min(m.values())) if m else math.inf
    if res.binding:
        row["binding_constraint"], row["binding_margin"] = res.binding[0]["constraint"], float(res.binding[0]["margin"])
    elif m:
        k = min(m, key=m.get)
        row["binding_constraint"], row["binding_margin"] = k, float(m[k])
    else:
        row["binding_constraint"], row["binding_margin"] = "", math.inf
    for n in CONSTRAINTS:
        row[f"margin_{n}"] = float(m[n]) if n in m else math.nan
    viol = sorted(((k, v) for k, v in m.items() if v < -FEAS_TOL), key=lambda kv: kv[1])
    row["violated"] = ";".join(f"{k}:{v:+.3f}" for k, v in viol) if not feasible else ""
    rel = (res.diagnosis or {}).get("relaxations") or []
    row["relaxation"] = _fmt_relaxation(rel[0]) if (rel and diagnose and not feasible) else ""
    notes = [str(n) for n in res.notes]
    absent = absent_note(d, res.parts, m)
    if absent:
        notes.append(absent)
    row["notes"] = "; ".join(dict.fromkeys(notes))
    return row


def error_row(exc: Exception) -> dict:
    """The row of an application the design space cannot be built for (e.g. a working arm beyond Table 2)."""
    row = {c: math.nan for c in columns()}
    row.update({"feasible": False, "status": "infeasible", "binding_constraint": "", "violated": "", "relaxation": "",
                "notes": f"no design space: {exc}".replace("\n", "; ")})
    row.update({f"part_{k}": None for k in PART_KEYS})
    return row


def screen_applications_reference(apps: Sequence, *, objective: str = "standard", fidelity: str = "screening",
                                  diagnose: bool = True) -> pd.DataFrame:
    """Reference engine: ``solve(d, objective, "enumerate", fidelity=...)`` per application.

    Slow (0.3-5 s per application) but the definition of the right answer.
    """
    from synth.errors import InputError
    from synth.optimise import solve
    rows = []
    for d in apps:
        try:
            rows.append(row_from_result(solve(d, objective, "enumerate", fidelity=fidelity, relax=diagnose), d, diagnose))
        except InputError as exc:
            rows.append(error_row(exc))
    return frame(rows)


def frame(rows: list) -> pd.DataFrame:
    """The result DataFrame of ``rows`` (dicts of :func:`columns`), index 0..n-1, fixed dtypes."""
    df = pd.DataFrame(rows, columns=columns()) if rows else _empty()
    df["feasible"] = df["feasible"].astype(bool)
    for c in df.columns:
        if c.startswith(("objective_", "margin_")) or c == "binding_margin":
            df[c] = df[c].astype(float)
    return df.reset_index(drop=True)


def _empty() -> pd.DataFrame:
    return pd.DataFrame({c: pd.Series(dtype=object) for c in columns()})


def screen_applications(apps: Sequence, *, objective: str = "standard", fidelity: str = "screening",
                        diagnose: bool = True) -> pd.DataFrame:
    """One row per application of ``apps`` (validated ``DesignInput``), in the order given (index 0..n-1).

    ``objective`` as :func:`synth.optimise.solve` accepts it; ``fidelity``
    ``screening`` (closed-form plastic wear) or ``full`` (time-integrated);
    ``diagnose=False`` skips the relaxation search of infeasible applications.
    Columns: :func:`columns`. The same answer as
    :func:`screen_applications_reference`, faster (see ``engine_fast``).

    >>> from synth.data.generated_applications import generate
    >>> df = screen_applications(generate(2, seed=0), objective="cost")
    >>> list(df.index), df.loc[1, "status"]
    ([0, 1], 'optimal')
    """
    from synth.bulk.engine_fast import screen_fast
    return screen_fast(apps, objective=objective, fidelity=fidelity, diagnose=diagnose)
