"""The thesis's graphs of one design (Fig. 15-19, 39-45, 68, 71, 74), the drive's and the optimiser's: one function
``g_<graph id>(data, ax, verdict)`` per graph of :data:`synth.report.plots.CATALOG`, drawing on ``ax`` and returning
the plotted series (named 1-D arrays).

Every graph reads its numbers from the one evaluator, never from a second
physics path:

* the wear histories (damping decay, plastic wear, cone-spring force against
  time) are ``result.curves["plastic_wear"]``, kept by
  :func:`synth.design.verify.verify` / :func:`synth.flowchart.run` with
  ``time_points`` (the report re-verifies a result without them);
* the bushing wear and the pulley parallelism against time are
  :func:`synth.design.evaluate.bushing` evaluated at the design's own rows
  for a time axis (the durability duration as an array of applications);
* the cone-spring characteristic is :func:`synth.model.disc_spring.disc_spring_force_n`
  at the geometry the evaluator sized (``result.values``);
* the hysteresis and sensitivity sweeps, the Goodman diagram and the pivot
  base pressure call the physics function the evaluator calls, with the
  result's values and the design's catalog attributes
  (:meth:`synth.design.space.Space.design_attributes`), over a plotted axis.

A graph whose data the result lacks raises :class:`~synth.report.graph_data.Skip` with the reason.
"""

from __future__ import annotations

import math

import numpy as np

from synth.design import evaluate
from synth.design.result import PASS
from synth.drive.analysis import drive_model, drive_sweep, durability_point
from synth.model import bolted_joint, damping, disc_spring
from synth.report.figures import line_styles, plain
from synth.report.graph_data import COLOURS, Data, Skip, colour

#: points per swept curve
SWEEP_POINTS = 121
#: points of the time axes (as the report's verification keeps the wear history)
TIME_POINTS = 60


def _characterisation(dt: Data):
    try:
        half = dt.durability()[0] / 2.0 or 10.0
    except Skip:
        half = 10.0
    theta = np.linspace(-half, half, SWEEP_POINTS)
    ch = damping.characterisation(dt.need("spring_torque_nominal_nm"), dt.need("spring_stiffness_nm_per_deg"),
                             dt.get("axial_damping_nm", 0.0) or 0.0, dt.need("working_arm_mm"),
                             dt.need("differential_angle_deg"), dt.need("pivot_diameter_mm"),
                             dt.need("mu_pivot_bushing"), theta, dt.friction_circle)
    return theta, ch


def g_hysteresis_load(dt: Data, ax, verdict):
    theta, ch = _characterisation(dt)
    ax.plot(theta, ch["hubload_loading_n"], color=colour(verdict), label="loading")
    ax.plot(theta, ch["hubload_unloading_n"], color=COLOURS["other"], label="unloading")
    ax.fill_between(theta, ch["hubload_unloading_n"], ch["hubload_loading_n"], color=colour(verdict), alpha=0.1)
    ax.set(xlabel="arm rotation from nominal [deg]", ylabel="hubload [N]")
    return {"theta_deg": theta, "hubload_loading_n": ch["hubload_loading_n"],
            "hubload_unloading_n": ch["hubload_unloading_n"]}


def g_hysteresis_torque(dt: Data, ax, verdict):
    theta, ch = _characterisation(dt)
    ax.plot(theta, ch["torque_loading_nm"], color=colour(verdict), label="loading")
    ax.plot(theta, ch["torque_unloading_nm"], color=COLOURS["other"], label="unloading")
    ax.plot(theta, ch["calculated_torque_nm"], "--", color="black", lw=0.8, label="calculated torque")
    ax.fill_between(theta, ch["torque_unloading_nm"], ch["torque_loading_nm"], color=colour(verdict), alpha=0.1)
    ax.set(xlabel="arm rotation from nominal [deg]", ylabel="torque at the pulley [Nm]")
    return {"theta_deg": theta, "torque_loading_nm": ch["torque_loading_nm"],
            "torque_unloading_nm": ch["torque_unloading_nm"], "calculated_torque_nm": ch["calculated_torque_nm"]}


def _sensitivity(dt: Data, ax, parameter, values, xlabel, design: float):
    kw = dict(spring_torque_nominal_nm=dt.need("spring_torque_nominal_nm"),
              axial_damping_nm=dt.get("axial_damping_nm", 0.0) or 0.0, working_arm_mm=dt.need("working_arm_mm"),
              differential_angle_deg=dt.need("differential_angle_deg"), pivot_diameter_mm=dt.need("pivot_diameter_mm"),
              mu_pivot_bushing=dt.need("mu_pivot_bushing"), friction_circle=dt.friction_circle)
    if parameter == "mu_plastic":
        kw["mu_plastic"] = dt.mu_plastic()
    s = damping.sensitivity(parameter, values, **kw)
    ax.plot(values, s["calculated_torque_nm"], color=COLOURS["nominal"], label="calculated torque [Nm]")
    ax.plot(values, s["damping_nm"], color=COLOURS["other"], label="damping [Nm]")
    target, tol = dt.get("damping_target_nm"), dt.get("damping_tolerance_nm")
    if target is not None and tol is not None:
        ax.axhspan(target - tol, target + tol, color=COLOURS[PASS], alpha=0.12, label="damping target band")
    ax2 = ax.twinx()
    ax2.plot(values, s["asymmetry_ratio"], ":", color="black")
    ax2.set_ylabel("asymmetry ratio [-]")
    # the right axis's curve in the one legend (drawn on the left axis), and the design's own point on each curve
    ax.plot([], [], ":", color="black", label="asymmetry ratio (right axis)")
    ax.axvline(design, color=COLOURS["limit"], ls="-.", lw=0.8, label=f"design point ({plain(design)})")
    for key in ("calculated_torque_nm", "damping_nm"):
        ax.plot([design], [np.interp(design, values, s[key])], "o", color="black", ms=4)
    ax2.plot([design], [np.interp(design, values, s["asymmetry_ratio"])], "o", color="black", ms=4)
    ax.set(xlabel=xlabel, ylabel="torque [Nm]")
    return {"values": np.asarray(values, float), "calculated_torque_nm": s["calculated_torque_nm"],
            "damping_nm": s["damping_nm"], "asymmetry_ratio": np.asarray(s["asymmetry_ratio"], float)}


def g_sensitivity_differential_angle(dt: Data, ax, verdict):
    a = float(dt.need("differential_angle_deg"))
    values = np.linspace(max(a - 30.0, 5.0), min(a + 30.0, 175.0), SWEEP_POINTS)
    return _sensitivity(dt, ax, "differential_angle_deg", values, "differential angle [deg]", a)


def g_sensitivity_mu_pivot_bushing(dt: Data, ax, verdict):
    mu = float(dt.need("mu_pivot_bushing"))
    return _sensitivity(dt, ax, "mu_pivot_bushing", np.linspace(0.0, 2.0 * mu, SWEEP_POINTS),
                        "pivot bushing friction [-]", mu)


def g_sensitivity_mu_plastic(dt: Data, ax, verdict):
    dt.axial()
    mu = dt.mu_plastic()
    return _sensitivity(dt, ax, "mu_plastic", np.linspace(0.5 * mu, 1.5 * mu, SWEEP_POINTS),
                        "plastic friction coefficient [-]", mu)


def _bushing(dt: Data, time_points: int = TIME_POINTS) -> dict:
    if "bushing" in dt.cache:
        return dt.cache["bushing"]
    t_end = dt.durability()[2]
    attrs = dt.attributes()
    t = np.linspace(0.0, t_end, time_points)
    apps = dt.apps.subset(np.zeros(time_points, dtype=np.int64))
    apps.derived["duration_h"] = t
    rows = np.arange(time_points)
    rep = {tab: {k: np.repeat(np.asarray(v), time_points, axis=0) for k, v in attrs[tab].items()}
           for tab in ("core", "bushing")}
    cg = evaluate.core(apps, rows, rep["core"], dt.settings)
    g = evaluate.bushing(apps, cg, rows, rep["bushing"], dt.settings)
    if not bool(g.values["bushing_rated"][0]):
        raise Skip("the bushing supplier has no wear rating for this environment")
    out = {"time_h": t, **{k: np.asarray(v, float) for k, v in g.values.items() if k != "app"}}
    dt.cache["bushing"] = out
    return out


def g_bushing_wear(dt: Data, ax, verdict):
    b = _bushing(dt)
    t = b["time_h"]
    depth = float(b["pivot_bushing_sliding_layer_mm"][0])
    w_max = np.abs(b["pivot_bushing_wear_max_mm"])
    ax.plot(t, np.abs(b["pivot_bushing_wear_a_mm"]), color=COLOURS["other"], label="lower end (A)")
    ax.plot(t, np.abs(b["pivot_bushing_wear_b_mm"]), color=COLOURS["nominal"], label="upper end (B)")
    ax.plot(t, w_max, color=colour(verdict), lw=2, label="most loaded end")
    ax.axhline(depth, ls="--", color=COLOURS["limit"], label="sliding layer depth")
    ax.set(xlabel="time [h]", ylabel="wear [mm]")
    return {"time_h": t, "wear_a_mm": np.abs(b["pivot_bushing_wear_a_mm"]),
            "wear_b_mm": np.abs(b["pivot_bushing_wear_b_mm"]), "wear_max_mm": w_max,
            "limit_mm": np.full_like(t, depth)}


def g_pulley_parallelism(dt: Data, ax, verdict):
    b = _bushing(dt)
    t, par = b["time_h"], b["pivot_bushing_parallelism_mm"]
    par_max = float(b["pulley_max_parallelism_eol_mm"][0])
    ax.plot(t, par, color=colour(verdict), lw=2, label="pulley parallelism")
    series = {"time_h": t, "parallelism_mm": par}
    if math.isfinite(par_max):
        ax.axhline(par_max, ls="--", color=COLOURS["limit"], label="max parallelism at EOL")
        series["limit_mm"] = np.full_like(t, par_max)
    ax.set(xlabel="time [h]", ylabel="parallelism [mm]")
    return series


def g_damping_decay(dt: Data, ax, verdict):
    h = dt.plastic_history()
    t, dmp = h["time_h"], h["damping_nm"]
    eol = dt.get("damping_eol_limit_nm")
    ax.plot(t, dmp, color=colour(verdict), lw=2, label="damping")
    series = {"time_h": t, "damping_nm": dmp}
    if eol is not None:
        ax.axhline(eol, ls="--", color=COLOURS["limit"], label="end-of-life limit")
        series["limit_nm"] = np.full_like(t, eol)
    ax.set(xlabel="time [h]", ylabel="damping [Nm]")
    return series


def _characteristic(dt: Data):
    c = dt.cone()
    geo = (c["cone_spring_external_diameter_mm"], c["cone_spring_internal_diameter_mm"],
           c["cone_spring_thickness_mm"], c["cone_spring_cone_height_mm"])
    s = np.linspace(0.0, geo[3], SWEEP_POINTS)
    f = disc_spring.disc_spring_force_n(s, *geo, fidelity=dt.fidelity)
    s_n = c["cone_spring_nominal_deflection_mm"]
    f_n = float(disc_spring.disc_spring_force_n(s_n, *geo, fidelity=dt.fidelity))
    return c, geo, s, np.asarray(f, float), s_n, f_n


def g_cone_spring_characteristic(dt: Data, ax, verdict):
    c, geo, s, f, s_n, f_n = _characteristic(dt)
    ax.plot(s, f, color=colour(verdict), lw=2, label=f"De {geo[0]:.3g} / Di {geo[1]:.3g} / t {geo[2]:.3g} mm")
    ax.plot([s_n], [f_n], "o", color="black", label="nominal working point")
    series = {"deflection_mm": s, "force_n": f, "nominal_deflection_mm": np.array([s_n]),
              "nominal_force_n": np.array([f_n])}
    s_max = c["cone_spring_max_deflection_mm"]
    if math.isfinite(s_max):
        ax.axvline(s_max, ls="--", color=COLOURS["limit"], lw=0.8, label="maximum deflection (worst gap)")
        series["max_deflection_mm"] = np.array([s_max])
    ax.set(xlabel="deflection [mm]", ylabel="axial force [N]")
    return series


def g_plastic_wear(dt: Data, ax, verdict):
    h = dt.plastic_history()
    t, w = h["time_h"], h["plastic_wear_total_mm"]
    total = h["damper_pad_wear_eol_mm"] + h["endcap_spacer_wear_eol_mm"]
    share = h["damper_pad_wear_eol_mm"] / total if total > 0 else 0.5
    ax.plot(t, w, color=colour(verdict), lw=2, label="stack-up (total)")
    ax.plot(t, share * w, color=COLOURS["other"], label="damper pad")
    ax.plot(t, (1 - share) * w, ":", color=COLOURS["other"], label="endcap spacer")
    ax.set(xlabel="time [h]", ylabel="wear [mm]")
    return {"time_h": t, "plastic_wear_total_mm": w, "damper_pad_wear_mm": share * w,
            "endcap_spacer_wear_mm": (1 - share) * w}


def g_cone_spring_force_time(dt: Data, ax, verdict):
    h = dt.plastic_history()
    t, f = h["time_h"], h["cone_spring_force_n"]
    ax.plot(t, f, color=colour(verdict), lw=2, label="axial force (wear and relaxation)")
    ax.set(xlabel="time [h]", ylabel="cone spring axial force [N]")
    return {"time_h": t, "cone_spring_force_n": f}


def g_cone_spring_tolerance_band(dt: Data, ax, verdict):
    c, geo, s, f, s_n, f_n = _characteristic(dt)
    lo, hi = c["cone_spring_fax_min_tolerance_n"], c["cone_spring_fax_max_tolerance_n"]
    dh = c["cone_spring_gap_tolerance_mm"]
    col = colour(verdict)
    ax.plot(s, f, color=COLOURS["nominal"], label="characteristic")
    ax.axhspan(lo, hi, color=col, alpha=0.15, label="force tolerance at nominal gap")
    ax.axhline(lo, color=col, lw=1)
    ax.axhline(hi, color=col, lw=1)
    ax.axvspan(max(s_n - dh, 0.0), s_n + dh, color=COLOURS["other"], alpha=0.12, label="gap tolerance")
    ax.plot([s_n], [f_n], "o", color="black", label="nominal")
    ax.set(xlabel="deflection [mm]", ylabel="axial force [N]")
    return {"deflection_mm": s, "force_n": f, "fax_min_tolerance_n": np.array([lo]),
            "fax_max_tolerance_n": np.array([hi]), "deflection_band_mm": np.array([max(s_n - dh, 0.0), s_n + dh])}


def g_goodman(dt: Data, ax, verdict):
    smax, smin = (float(x) for x in dt.need("main_spring_sigma_a_max_mpa", "main_spring_sigma_a_min_mpa"))
    sf = float(dt.need("main_spring_safety_factor"))
    sp = dt.attributes()["spring"]
    rm, sy, sa0 = (float(np.asarray(sp[k]).reshape(-1)[0]) for k in ("Rm_mpa", "sigma_y_mpa", "sigma_A0_mpa"))
    sm = np.linspace(0.0, sy, SWEEP_POINTS)
    upper = np.minimum(sa0 + sm * (1.0 - sa0 / rm), sy)
    lower = 2.0 * sm - upper
    work_m = (smax + smin) / 2.0
    ax.plot(sm, upper, color=COLOURS["nominal"], lw=2, label="upper limit (Goodman, yield)")
    ax.plot(sm, lower, color=COLOURS["nominal"], lw=1)
    ax.plot(sm, sm, ":", color=COLOURS["other"], label="mean stress")
    ax.plot([work_m, work_m], [smin, smax], color=colour(verdict), lw=4, label="working range")
    ax.plot([0.0, work_m * sf], [0.0, smax * sf], "--", color=COLOURS["limit"], lw=0.8,
            label=f"safety factor {sf:.2f}")
    ax.set(xlabel="mean stress [MPa]", ylabel="stress [MPa]")
    return {"mean_stress_mpa": sm, "upper_limit_mpa": upper, "lower_limit_mpa": lower,
            "working_range_mpa": np.array([smin, smax]), "safety_factor": np.array([sf])}


def g_pivot_base_pressure(dt: Data, ax, verdict):
    force = float(dt.need("bolt_axial_force_n"))
    hl = float(dt.need("hubload_nominal_n"))
    h = float(dt.need("middle_plane_belt_height_mm"))
    inc = float(dt.apps.f["middle_plane_belt_height_increment_worst_mm"][0])
    d_ext, d_int = dt.need("engine_support_external_diameter_mm", "engine_support_internal_diameter_mm")
    theta = float(dt.need("contact_angle_deg"))
    n = SWEEP_POINTS
    ang = np.linspace(-180.0, 180.0, 2 * n + 1) if theta >= 360.0 else np.linspace(-theta / 2, theta / 2, n)
    nominal = bolted_joint.pivot_base_pressure_mpa(ang, force, hl * float(bolted_joint.tilting_lever_mm(h, 0.0)), d_ext, d_int, theta)
    worst = bolted_joint.pivot_base_pressure_mpa(ang, force, hl * float(bolted_joint.tilting_lever_mm(h, inc)), d_ext, d_int, theta)
    ax.plot(ang, nominal, color=COLOURS["nominal"], label="nominal")
    ax.plot(ang, worst, color=colour(verdict), lw=2, label="worst condition")
    ax.axhline(0.0, ls="--", color=COLOURS["limit"], label="lift-off (tilting)")
    ax.set(xlabel="contact angle from the hubload direction [deg]", ylabel="contact pressure [MPa]")
    return {"angle_deg": ang, "pressure_nominal_mpa": np.asarray(nominal, float),
            "pressure_worst_mpa": np.asarray(worst, float)}


def _drive_sweep(dt: Data):
    """The drive's sweep with the design's own damping (the registry's drive checks evaluate the same sweep)."""
    drive = dt.settings.drive
    if drive is None:
        raise Skip("the design was not run with a drive (synth design --drive)")
    damping = dt.get("damping_nm")
    if damping is None:
        raise Skip("the design has no damping value")
    return drive, drive_model(drive), drive_sweep(drive, float(damping)), float(damping)


def g_drive_arm_amplitude(dt: Data, ax, verdict):
    drive, _, sw, damping = _drive_sweep(dt)
    ax.plot(sw["speed_rpm"], sw["theta_pp_deg"], color=colour(verdict), label=f"damping {damping:.3g} Nm")
    if drive.durability_speed_rpm is not None:
        ax.axvline(drive.durability_speed_rpm, color=COLOURS["limit"], ls="--", lw=0.8, label="durability speed")
    ax.set(xlabel="engine speed [rpm]", ylabel="arm peak-to-peak angle [deg]")
    return {"speed_rpm": sw["speed_rpm"], "theta_pp_deg": sw["theta_pp_deg"]}


def g_drive_span_tension(dt: Data, ax, verdict):
    drive, model, sw, _ = _drive_sweep(dt)
    out = {"speed_rpm": sw["speed_rpm"]}
    for j, name in enumerate(model.span_names):
        line, = ax.plot(sw["speed_rpm"], sw["tension_max_n"][:, j], lw=1, label=name)
        ax.plot(sw["speed_rpm"], sw["tension_min_n"][:, j], lw=1, color=line.get_color(), ls=":")
        out[f"{name}_min_n"], out[f"{name}_max_n"] = sw["tension_min_n"][:, j], sw["tension_max_n"][:, j]
    ax.axhline(drive.belt_min_tension_n, color=colour(verdict), lw=1.5, label="slack limit")
    line_styles(ax, drive.durability_speed_rpm)
    ax.set(xlabel="engine speed [rpm]", ylabel="span tension, max (solid) and min (dotted) [N]")
    return out


def g_drive_hysteresis_loop(dt: Data, ax, verdict):
    drive, _, _, damping = _drive_sweep(dt)
    if drive.durability_speed_rpm is None:
        raise Skip("the drive gives no durability speed")
    p = durability_point(drive, damping)
    ang = np.degrees(p["psi_rad"])
    tq = drive.tensioner.nominal_torque_nm - drive.tensioner.stiffness_nm_per_deg * ang - p["friction_nm_t"]
    ax.plot(np.append(ang, ang[:1]), np.append(tq, tq[:1]), color=colour(verdict))
    ax.set(xlabel="arm angle from nominal (take-up positive) [deg]",
           ylabel="belt torque on the arm [Nm]", title=f"{p['speed_rpm']:g} rpm, theta_pp {p['theta_pp_deg']:.3g} deg")
    return {"angle_deg": ang, "torque_nm": tq}


def _rows(obj) -> list[dict]:
    if obj is None:
        return []
    if hasattr(obj, "to_dict"):
        return obj.to_dict(orient="records")
    if isinstance(obj, dict):
        return [obj]
    return list(obj)


def _numeric_columns(rows):
    cols = list(dict.fromkeys(k for r in rows for k in r))
    out = []
    for k in cols:
        try:
            arr = np.array([float(r.get(k)) for r in rows])
        except (TypeError, ValueError):
            continue
        if np.all(np.isfinite(arr)):
            out.append((k, arr))
    return out


def g_pareto(dt: Data, ax, verdict):
    rows = _rows(dt.extra.get("pareto"))
    num = _numeric_columns(rows)
    if len(rows) < 2 or len(num) < 2:
        raise Skip("no Pareto front given (--pareto FILE with two numeric objective columns)")
    (kx, x), (ky, y) = num[0], num[1]
    order = np.argsort(x)
    ax.plot(x[order], y[order], "o-", color=COLOURS["nominal"])
    ax.set(xlabel=kx, ylabel=ky)
    return {kx: x[order], ky: y[order]}


def g_solvers(dt: Data, ax, verdict):
    rows = _rows(dt.extra.get("solvers"))
    num = _numeric_columns(rows)
    if not rows or not num:
        raise Skip("no solver comparison given (--solvers FILE: a name column and numeric columns)")
    names = [str(r.get("solver", r.get("name", i))) for i, r in enumerate(rows)]
    k, vals = num[0]
    ax.bar(names, vals, color=COLOURS["nominal"])
    ax.set(ylabel=k)
    ax.tick_params(axis="x", rotation=30)
    return {k: vals}
