"""One drive analysed: statics, modes, the speed sweep, the durability point, slack and lock, the tolerance check.

:func:`analyse` is what ``synth drive`` prints; :func:`durability_point` gives
the thesis's durability inputs (theta_pp and f, "from the system
calculation") and :func:`tensioner_checks` the values of the registry's
``drive_belt_slack`` and ``drive_arm_lock`` constraints for the friction
torques of many designs (one sweep per distinct friction, remembered).
"""

from __future__ import annotations

from functools import lru_cache

import numpy as np

from synth.drive.belt import EA_PER_RIB_RANGE_N
from synth.drive.modes import linear_drive, natural_frequencies, system_modes
from synth.drive.positions import duty_table, positions, travels
from synth.drive.response import speed_response, sweep
from synth.drive.statics import static_state
from synth.errors import InputError, Problem
from synth.threads import limits

__all__ = ["analyse", "durability_point", "tensioner_checks", "require_durability_speed", "states_positions"]


def require_durability_speed(drive) -> float:
    """The drive's durability speed, or an input error saying why it is needed."""
    if drive.durability_speed_rpm is None:
        raise InputError(Problem("excitation.durability_speed_rpm", None,
                                 "a value: the durability test's engine speed (theta_pp and f are taken there)"))
    return float(drive.durability_speed_rpm)


@lru_cache(maxsize=64)
def drive_model(drive):
    """The drive's linear model (:func:`linear_drive`), built once per drive."""
    return linear_drive(drive)


@lru_cache(maxsize=256)
def drive_sweep(drive, friction_nm: float):
    """The response over the drive's speeds at the damping friction ``friction_nm`` (:func:`sweep`), once per pair."""
    return sweep(drive_model(drive), drive, friction_nm, drive.speeds_rpm())


@limits("small")  # small dense solves: one BLAS thread (synth.threads)
def durability_point(drive, friction_nm: float | None = None) -> dict:
    """theta_pp [deg] and f [Hz] of the arm at the durability speed (the drive's friction unless given).

    >>> from synth.drive.inputs import example_drive
    >>> p = durability_point(example_drive())
    >>> round(p["frequency_hz"], 1), p["locked"]
    (50.0, False)
    """
    speed = require_durability_speed(drive)
    fr = drive.tensioner.friction_torque_nm if friction_nm is None else float(friction_nm)
    r = speed_response(drive_model(drive), drive, speed, fr, harmonics=drive.harmonics, eps_rel=drive.regularisation)
    return {"speed_rpm": speed, "theta_pp_deg": r["theta_pp_deg"], "frequency_hz": r["arm_frequency_hz"],
            "locked": r["locked"], "critical_friction_nm": r["critical_friction_nm"], "friction_nm": fr,
            "psi_rad": r["psi_rad"], "friction_nm_t": r["friction_nm_t"], "omega_b": r["omega_b"],
            "tension_min_n": r["tension_min_n"], "tension_max_n": r["tension_max_n"]}


@limits("small")
def tensioner_checks(drive, friction_nm) -> dict:
    """Per friction torque (array, N m): the lowest effective span tension over the sweep [N], and the drive's
    critical friction at the durability speed, its slack limit and static tensioner tension (for the margins).
    NaN friction gives NaN."""
    fr = np.atleast_1d(np.asarray(friction_nm, dtype=float))
    out = np.full(fr.shape, np.nan)
    for v in np.unique(fr[np.isfinite(fr)]):
        out[fr == v] = float(drive_sweep(drive, float(v))["tension_min_n"].min())
    point = durability_point(drive, 0.0)
    return {"min_span_tension_n": out, "critical_friction_nm": point["critical_friction_nm"],
            "belt_min_tension_n": drive.belt_min_tension_n,
            "static_tension_n": float(drive_model(drive).static["tensioner_tension_n"])}


@limits("small")
def analyse(drive, *, check: bool = True) -> dict:
    """Everything ``synth drive`` reports, as plain data (numbers, lists): the static state; the tensioner's
    positions and the duty table when the drive states them (a report's tables); the modes when every inertia is
    given (the free system's when the crank's is, and how they move over the EA range); the periodic response when
    the drive states an excitation."""
    s = static_state(drive)
    out = {
        "name": drive.name,
        "spans": [f"{p.name}-{drive.pulleys[(i + 1) % len(drive.pulleys)].name}" for i, p in enumerate(drive.pulleys)],
        "pulleys": [p.name for p in drive.pulleys],
        "static": {"tension_n": s["tension_n"].tolist(), "span_length_mm": s["span_length_mm"].tolist(),
                   "hub_load_n": s["hub_load_n"].tolist(), "wrap_deg": s["wrap_deg"].tolist(),
                   "load_torque_nm": s["load_torque_nm"].tolist(),
                   "tensioner_tension_n": s["tensioner_tension_n"], "take_up_mm_per_rad": s["take_up_mm_per_rad"],
                   "differential_angle_deg": s["differential_angle_deg"]},
        "friction_nm": drive.tensioner.friction_torque_nm,
    }
    problems = []
    if states_positions(drive):
        out["positions"] = _plain(positions(drive))
        out["travels"] = travels(drive, out["positions"])
        problems += [f"{r['position']}: {r['beyond_mm']:.2f} mm beyond the {r.get('stop', '')} stop"
                     for r in out["positions"]["rows"] if not r["found"]]
    if drive.duty:
        out["duty"] = _plain(duty_table(drive))
        low = float(np.min(out["duty"]["tension_n"]))
        if low < drive.belt_min_tension_n:
            problems.append(f"a span's tension {low:.1f} N below the belt's {drive.belt_min_tension_n:g} N")
    if _has_inertias(drive):
        model = drive_model(drive)
        free = natural_frequencies(model)
        held = natural_frequencies(model, arm_locked=True)
        out["modes"] = {"arm_free_hz": free["frequency_hz"].tolist(), "arm_locked_hz": held["frequency_hz"].tolist(),
                        "dofs": list(free["dofs"]), "shapes": np.asarray(free["modes"]).T.tolist()}
        if drive.pulleys[drive.crank_index].inertia_kg_m2 is not None:
            out["modes"]["system"] = _system(drive)
    if drive.dynamic:
        out.update(_response(drive, check))
        if out["slack"]["slack"] or out.get("durability", {}).get("locked", False) or \
                not out["solver"].get("within_tolerance", True):
            problems.append("the periodic response: " + ", ".join(
                w for w, bad in (("the belt goes slack", out["slack"]["slack"]),
                                 ("the arm locks", out.get("durability", {}).get("locked", False)),
                                 ("outside its tolerance", not out["solver"].get("within_tolerance", True))) if bad))
    bad = out.get("sweep", {}).get("unconverged_rpm", []) + out.get("solver", {}).get("check_unconverged_rpm", [])
    if bad:
        problems.append("the periodic response did not converge at " + ", ".join(f"{s:.0f}" for s in bad)
                        + " rpm (the arm near lock; a larger solver.regularisation eases it): its values there "
                          "are approximate")
    out["problems"] = problems
    return out


def states_positions(drive) -> bool:
    """The drive states what a report's tensioner table needs: a stop or the belt's length variation."""
    t = drive.tensioner
    return (t.free_arm_angle_deg is not None or t.installation_angle_deg is not None
            or drive.belt_length_tolerance_mm > 0 or drive.belt_wear_pct > 0 or drive.belt_thermal_change_pct != 0)


def _has_inertias(drive) -> bool:
    return drive.tensioner.inertia_kg_m2 is not None and all(
        p.inertia_kg_m2 is not None for i, p in enumerate(drive.pulleys) if i != drive.crank_index)


def _system(drive) -> dict:
    """The free system's first modes with the drive's EA and, for a belt of ribs, at the ends of the EA range."""
    f = system_modes(drive)["frequency_hz"]
    out = {"frequency_hz": f.tolist()}
    if drive.belt_ribs:
        lo, hi = EA_PER_RIB_RANGE_N
        out["ea_per_rib_n"] = drive.belt_stiffness_n / drive.belt_ribs
        out["range"] = {"ea_per_rib_n": [lo, hi],
                        "frequency_hz": [system_modes(drive, lo)["frequency_hz"].tolist(),
                                         system_modes(drive, hi)["frequency_hz"].tolist()]}
    return out


def _plain(data):
    """numpy to lists and floats (the JSON output)."""
    if isinstance(data, dict):
        return {k: _plain(v) for k, v in data.items()}
    if isinstance(data, (list, tuple)):
        return [_plain(v) for v in data]
    if isinstance(data, np.ndarray):
        return data.tolist()
    if isinstance(data, np.generic):
        return data.item()
    return data


def _response(drive, check: bool) -> dict:
    """The periodic response over the speed sweep, the slack and lock verdicts, the durability point."""
    model = drive_model(drive)
    sw = sweep(model, drive, drive.tensioner.friction_torque_nm, drive.speeds_rpm(), check=check)
    t_min = sw["tension_min_n"]
    i_slack = int(np.argmin(t_min.min(axis=1)))
    slack = bool(t_min.min() < drive.belt_min_tension_n)
    out = {
        "sweep": {"speed_rpm": sw["speed_rpm"].tolist(), "theta_pp_deg": sw["theta_pp_deg"].tolist(),
                  "arm_frequency_hz": sw["arm_frequency_hz"].tolist(),
                  "tension_min_n": sw["tension_min_n"].tolist(), "tension_max_n": sw["tension_max_n"].tolist(),
                  "critical_friction_nm": sw["critical_friction_nm"].tolist(), "locked": sw["locked"].tolist(),
                  "converged": bool(sw["converged"].all()),
                  "unconverged_rpm": sw["speed_rpm"][~sw["converged"]].tolist()},
        "slack": {"slack": slack, "min_tension_n": float(t_min.min()), "at_speed_rpm": float(sw["speed_rpm"][i_slack]),
                  "span": model.span_names[int(np.argmin(t_min[i_slack]))], "limit_n": drive.belt_min_tension_n},
        "solver": {"harmonics": sw["harmonics"], "regularisation": sw["regularisation"], "tolerance": drive.tolerance},
    }
    if check:
        out["solver"].update(change=sw["change"], within_tolerance=sw["within_tolerance"],
                             check_unconverged_rpm=sw["check_unconverged_rpm"].tolist())
    if drive.belt_friction_coefficient is not None:
        out["slip"] = _slip_margins(drive, model, sw)
    if drive.durability_speed_rpm is not None:
        p = durability_point(drive)
        out["durability"] = {k: p[k] for k in ("speed_rpm", "theta_pp_deg", "frequency_hz", "locked",
                                               "critical_friction_nm", "friction_nm")}
        out["durability"]["loop"] = {"angle_deg": np.degrees(p["psi_rad"]).tolist(),
                                     "friction_torque_nm": p["friction_nm_t"].tolist()}
    return out


def _slip_margins(drive, model, sw) -> dict:
    """Euler-Eytelwein per pulley with a load: ``1 - ln(T_tight / T_slack) / (mu wrap)`` at each speed's extremes
    (the tight side's largest over the slack side's lowest tension: a conservative pairing)."""
    mu = drive.belt_friction_coefficient
    wrap = np.radians(model.static["wrap_deg"])
    n = len(drive.pulleys)
    out = {}
    for i, p in enumerate(drive.pulleys):
        if p.role in ("idler", "tensioner"):
            continue
        t_in_min, t_out_min = sw["tension_min_n"][:, (i - 1) % n], sw["tension_min_n"][:, i]
        t_in_max, t_out_max = sw["tension_max_n"][:, (i - 1) % n], sw["tension_max_n"][:, i]
        tight = np.maximum(t_in_max, t_out_max)
        loose = np.minimum(t_in_min, t_out_min)
        with np.errstate(divide="ignore", invalid="ignore"):
            m = 1.0 - np.log(tight / loose) / (mu * wrap[i])
        out[p.name] = np.where(loose > 0, m, -np.inf).tolist()
    return out
