"""The thesis's graphs of one design, drawn with matplotlib (Agg) from the physics functions.

Each graph is computed from the flowchart result: from ``result.curves`` when
the flowchart stored the curve under the graph's id, else from the physics
functions of :mod:`synth.model` with the values of ``result.values`` (and,
where a step's values are not in the result, the same physics the flowchart
would call). A graph that cannot be drawn (a step that does not apply, data
missing) is listed with the reason, never drawn empty.

Every :class:`Graph` carries its data (``series``: named 1-D arrays, the
plotted lines) and the PNG, so tests assert on the numbers and the report
embeds the picture. Colours follow the thesis: the curve compared with a
limit is green when verified, red when failed; the limit is dashed black.

Graph ids and thesis figures: :data:`CATALOG`.

>>> [g[0] for g in CATALOG][:3]
['hysteresis_load', 'hysteresis_torque', 'sensitivity_differential_angle']
"""

from __future__ import annotations

import io
import math
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from synth.design.result import FAIL, PASS

__all__ = ["Graph", "Skipped", "CATALOG", "build_graphs", "graph_png", "COLOURS"]

#: Thesis colours: verified green, failed red, nominal/reference blue, limit black.
COLOURS = {PASS: "#2e7d32", FAIL: "#c62828", "nominal": "#1f5fbf", "limit": "black", "other": "#7f7f7f"}

#: (id, title, thesis figure)
CATALOG: tuple[tuple[str, str, str], ...] = (
    ("hysteresis_load", "Hysteresis cycle in hubload", "Fig. 15"),
    ("hysteresis_torque", "Hysteresis cycle in torque", "Fig. 16"),
    ("sensitivity_differential_angle", "Sensitivity to the differential angle", "Fig. 17"),
    ("sensitivity_mu_pivot_bushing", "Sensitivity to the pivot-bushing friction", "Fig. 18"),
    ("sensitivity_mu_plastic", "Sensitivity to the plastic-element friction", "Fig. 19"),
    ("bushing_wear", "Pivot bushing wear against time", "Fig. 39"),
    ("pulley_parallelism", "Pulley parallelism against time", "Fig. 40"),
    ("damping_decay", "Damping decay over the durability test", "Fig. 42"),
    ("cone_spring_characteristic", "Cone spring characteristic", "Fig. 43"),
    ("plastic_wear", "Plastic friction elements wear against time", "Fig. 44"),
    ("cone_spring_force_time", "Cone spring axial force against time", "Fig. 45"),
    ("cone_spring_tolerance_band", "Cone spring force tolerance band", "Fig. 68"),
    ("goodman", "Smith-Goodman diagram of the main spring", "Fig. 71"),
    ("pivot_base_pressure", "Pivot base contact pressure against contact angle", "Fig. 74"),
    ("pareto", "Pareto front", "optimiser"),
    ("solvers", "Solver comparison", "optimiser"),
)
_TITLES = {i: (t, f) for i, t, f in CATALOG}
_N = 121  # points per curve


class _Skip(Exception):
    """A graph that does not apply or lacks data: the message says why."""


@dataclass
class Graph:
    """One drawn graph: id, title, thesis figure, data series, verdict and PNG bytes."""

    id: str
    title: str
    figure: str
    series: dict = field(default_factory=dict)
    verdict: str | None = None
    caption: str = ""
    png: bytes = b""


@dataclass
class Skipped:
    id: str
    title: str
    reason: str


# ------------------------------------------------------------------------------------------ data access
class _Data:
    """Values of the result with lazily computed fallbacks of the steps the result lacks."""

    def __init__(self, result, extra: dict | None):
        from synth.schema import validate
        self.r, self.v = result, {**result.values, **result.parts}
        self.d = validate(result.inputs) if isinstance(result.inputs, dict) else result.inputs
        self.extra = extra or {}
        self.fidelity = result.settings.get("fidelity", "full")
        self.friction_circle = result.settings.get("friction_circle", True)
        self._cache: dict = {}

    def need(self, *keys):
        """Values of ``keys`` from the result (or the input); _Skip naming the first missing one."""
        out = []
        for k in keys:
            val = self.v.get(k)
            if val is None and hasattr(self.d, k):
                val = getattr(self.d, k)
            if val is None or (isinstance(val, float) and not math.isfinite(val)):
                raise _Skip(f"{k} missing")
            out.append(val)
        return out if len(out) > 1 else out[0]

    def get(self, k, default=None):
        try:
            return self.need(k)
        except _Skip:
            return default

    def durability(self) -> tuple[float, float, float]:
        """``(theta_pp_deg, frequency_hz, duration_h)``: given, or from the engine type when assumed."""
        if getattr(self.d, "durability_test", None) == "assumed" and getattr(self.d, "engine_type", None):
            from synth import catalog
            row = catalog.row("durability_tests", self.d.engine_type, field="engine_type")
            return float(row["theta_peak_to_peak_deg"]), float(row["frequency_hz"]), float(row["duration_h"])
        return tuple(float(x) for x in self.need("durability_theta_peak_to_peak_deg", "durability_frequency_hz",
                                                 "durability_duration_h"))

    def axial(self) -> bool:
        if not self.v.get("axial_damping_present"):
            raise _Skip("no axial damping: the step does not apply")
        return True

    def curve(self, gid):
        """``result.curves[gid]`` as a dict of 1-D float arrays, or None."""
        c = (self.r.curves or {}).get(gid)
        if not isinstance(c, dict):
            return None
        try:
            out = {k: np.asarray(v, float).reshape(-1) for k, v in c.items() if np.size(v) > 1}
        except (TypeError, ValueError):
            return None
        return out if len(out) >= 2 else None

    # --- step 5/6/8 chain ---------------------------------------------------------------------
    def axial_group(self) -> dict:
        """Damper pad and endcap spacer data: from the result, else the Table 3-4 class of step 3."""
        if "group" in self._cache:
            return self._cache["group"]
        from synth import catalog
        from synth.model import damping as s3
        g = {}
        for part, table in (("damper_pad", "damper_pads"), ("endcap_spacer", "endcap_spacers")):
            keys = [f"{part}_contact_area_mm2", f"{part}_mean_radius_mm", f"{part}_axial_height_mm"]
            if part == "damper_pad":
                keys.append("damper_pad_outer_diameter_mm")
            if all(self.v.get(k) is not None for k in keys):
                g.update({k: float(self.v[k]) for k in keys})
                continue
            cls = str(s3.select_axial_group_class(self.need("axial_damping_nm"), table)[0])
            if not cls:
                raise _Skip(f"axial damping above every {table} class (Tables 3-4)")
            row = catalog.row(table, cls)
            g.update({k: float(row[k.replace(f"{part}_", "")]) for k in keys})
        self._cache["group"] = g
        return g

    def mu_plastic(self) -> float:
        val = self.v.get("plastic_friction_coefficient") or self.v.get("mu_plastic")
        if val is not None:
            return float(val)
        from synth.model import friction_wear as s5
        return float(s5.plastic_material(application_type=self.d.application_type)["plastic_friction_coefficient"])

    def cone(self) -> dict:
        """Cone spring geometry, nominal deflection and force band (result values, else step 8)."""
        if "cone" in self._cache:
            return self._cache["cone"]
        self.axial()
        from synth.model import stackup as s6, disc_spring as s8
        geo_keys = ("cone_spring_external_diameter_mm", "cone_spring_internal_diameter_mm",
                    "cone_spring_thickness_mm", "cone_spring_cone_height_mm", "cone_spring_nominal_deflection_mm",
                    "cone_spring_fax_max_tolerance_n", "cone_spring_fax_min_tolerance_n")
        gap = self.v.get("gap_tolerance_mm") or self.v.get("cone_spring_gap_tolerance_mm") or s6.gap_tolerance_mm()
        if not all(self.v.get(k) is not None for k in geo_keys):
            raise _Skip("the design has no sized cone spring")
        c = {k: float(self.v[k]) for k in geo_keys}
        c["gap_tolerance_mm"] = float(gap)
        self._cache["cone"] = c
        return c

    def plastic_history(self) -> dict:
        """Step 5 time histories (result curves, else :func:`friction_wear.plastic_wear`)."""
        if "plastic" in self._cache:
            return self._cache["plastic"]
        self.axial()
        stored = self.curve("plastic_wear")
        want = ("time_h", "plastic_wear_total_mm", "cone_spring_force_n", "damping_nm")
        if stored and all(k in stored for k in want):
            h = {k: stored[k] for k in want}
            w_dp, w_es = self.v.get("damper_pad_wear_mm"), self.v.get("endcap_spacer_wear_mm")
            if w_dp is None or w_es is None:  # split of the total: the step 5 physics below
                h.update({k: v for k, v in self._plastic_physics().items() if k.endswith("_eol_mm")})
            else:
                h["damper_pad_wear_eol_mm"], h["endcap_spacer_wear_eol_mm"] = float(w_dp), float(w_es)
            self._cache["plastic"] = h
            return h
        self._cache["plastic"] = self._plastic_physics()
        return self._cache["plastic"]

    def _plastic_physics(self) -> dict:
        from synth.model import friction_wear as s5
        c, g = self.cone(), self.axial_group()
        th, f, t = self.durability()
        r = s5.plastic_wear(c["cone_spring_nominal_deflection_mm"], c["cone_spring_external_diameter_mm"],
                            c["cone_spring_internal_diameter_mm"], c["cone_spring_thickness_mm"],
                            c["cone_spring_cone_height_mm"], g["damper_pad_contact_area_mm2"],
                            g["damper_pad_mean_radius_mm"], g["damper_pad_axial_height_mm"],
                            g["endcap_spacer_contact_area_mm2"], g["endcap_spacer_mean_radius_mm"],
                            g["endcap_spacer_axial_height_mm"], th, f, t, self.need("radial_damping_nm"),
                            application_type=self.d.application_type, fidelity=self.fidelity, time_points=_N,
                            plastic_friction_coefficient=self.mu_plastic())
        h = {k: np.asarray(v, float).reshape(-1) for k, v in r["history"].items()}
        h["damper_pad_wear_eol_mm"] = float(np.asarray(r["damper_pad_wear_mm"]).reshape(-1)[0])
        h["endcap_spacer_wear_eol_mm"] = float(np.asarray(r["endcap_spacer_wear_mm"]).reshape(-1)[0])
        return h


# ------------------------------------------------------------------------------------------ drawing helpers
def _fig(title: str):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(6.4, 4.0), dpi=100)
    ax.set_title(title, fontsize=11)
    ax.grid(True, alpha=0.3)
    return fig, ax


def _png(fig) -> bytes:
    import matplotlib.pyplot as plt
    buf = io.BytesIO()
    fig.tight_layout()
    fig.savefig(buf, format="png")
    plt.close(fig)
    return buf.getvalue()


def _verdict(ok) -> str:
    return PASS if bool(ok) else FAIL


def _check_verdict(result, *ids) -> str | None:
    """The worst verdict of the result's checks ``ids`` (registry ids)."""
    hits = [c.verdict for c in result.checks if c.id in ids]
    if FAIL in hits:
        return FAIL
    return PASS if PASS in hits else None


# ------------------------------------------------------------------------------------------ graphs
def _characterisation(dt: _Data):
    from synth.model import damping as s3
    try:
        half = dt.durability()[0] / 2.0 or 10.0
    except _Skip:
        half = 10.0
    theta = np.linspace(-half, half, _N)
    ch = s3.characterisation(dt.need("spring_torque_nominal_nm"), dt.need("spring_stiffness_nm_per_deg"),
                             dt.get("axial_damping_nm", 0.0) or 0.0, dt.need("working_arm_mm"),
                             dt.need("differential_angle_deg"), dt.need("pivot_diameter_mm"),
                             dt.need("mu_pivot_bushing"), theta, dt.friction_circle)
    return theta, ch


def g_hysteresis_load(dt: _Data, ax):
    theta, ch = _characterisation(dt)
    ax.plot(theta, ch["hubload_loading_n"], color=COLOURS["nominal"], label="loading")
    ax.plot(theta, ch["hubload_unloading_n"], color=COLOURS["other"], label="unloading")
    ax.fill_between(theta, ch["hubload_unloading_n"], ch["hubload_loading_n"], color=COLOURS["nominal"], alpha=0.1)
    ax.set(xlabel="arm rotation from nominal [deg]", ylabel="hubload [N]")
    return {"theta_deg": theta, "hubload_loading_n": ch["hubload_loading_n"],
            "hubload_unloading_n": ch["hubload_unloading_n"]}, None


def g_hysteresis_torque(dt: _Data, ax):
    theta, ch = _characterisation(dt)
    ax.plot(theta, ch["torque_loading_nm"], color=COLOURS["nominal"], label="loading")
    ax.plot(theta, ch["torque_unloading_nm"], color=COLOURS["other"], label="unloading")
    ax.plot(theta, ch["calculated_torque_nm"], "--", color="black", lw=0.8, label="calculated torque")
    ax.fill_between(theta, ch["torque_unloading_nm"], ch["torque_loading_nm"], color=COLOURS["nominal"], alpha=0.1)
    ax.set(xlabel="arm rotation from nominal [deg]", ylabel="torque at the pulley [Nm]")
    return {"theta_deg": theta, "torque_loading_nm": ch["torque_loading_nm"],
            "torque_unloading_nm": ch["torque_unloading_nm"], "calculated_torque_nm": ch["calculated_torque_nm"]}, None


def _sensitivity(dt: _Data, ax, parameter, values, xlabel):
    from synth.model import damping as s3
    kw = dict(spring_torque_nominal_nm=dt.need("spring_torque_nominal_nm"),
              axial_damping_nm=dt.get("axial_damping_nm", 0.0) or 0.0, working_arm_mm=dt.need("working_arm_mm"),
              differential_angle_deg=dt.need("differential_angle_deg"), pivot_diameter_mm=dt.need("pivot_diameter_mm"),
              mu_pivot_bushing=dt.need("mu_pivot_bushing"), friction_circle=dt.friction_circle)
    if parameter == "mu_plastic":
        kw["mu_plastic"] = dt.mu_plastic()
    s = s3.sensitivity(parameter, values, **kw)
    ax.plot(values, s["calculated_torque_nm"], color=COLOURS["nominal"], label="calculated torque [Nm]")
    ax.plot(values, s["damping_nm"], color=COLOURS["other"], label="damping [Nm]")
    target, tol = dt.get("damping_target_nm"), dt.get("damping_tolerance_nm")
    if target is not None and tol is not None:
        ax.axhspan(target - tol, target + tol, color=COLOURS[PASS], alpha=0.12, label="damping target band")
    ax2 = ax.twinx()
    ax2.plot(values, s["asymmetry_ratio"], ":", color="black", label="asymmetry ratio")
    ax2.set_ylabel("asymmetry ratio [-]")
    ax.set(xlabel=xlabel, ylabel="torque [Nm]")
    return {"values": np.asarray(values, float), "calculated_torque_nm": s["calculated_torque_nm"],
            "damping_nm": s["damping_nm"], "asymmetry_ratio": np.asarray(s["asymmetry_ratio"], float)}, None


def g_sensitivity_differential_angle(dt: _Data, ax):
    a = float(dt.need("differential_angle_deg"))
    values = np.linspace(max(a - 30.0, 5.0), min(a + 30.0, 175.0), _N)
    return _sensitivity(dt, ax, "differential_angle_deg", values, "differential angle [deg]")


def g_sensitivity_mu_pivot_bushing(dt: _Data, ax):
    mu = float(dt.need("mu_pivot_bushing"))
    return _sensitivity(dt, ax, "mu_pivot_bushing", np.linspace(0.0, 2.0 * mu, _N), "pivot bushing friction [-]")


def g_sensitivity_mu_plastic(dt: _Data, ax):
    dt.axial()
    mu = dt.mu_plastic()
    return _sensitivity(dt, ax, "mu_plastic", np.linspace(0.5 * mu, 1.5 * mu, _N), "plastic friction coefficient [-]")


def _bushing(dt: _Data):
    if "bushing" in dt._cache:
        return dt._cache["bushing"]
    from synth import parts as P
    from synth.model import plain_bushing as s4
    th, f, t_end = dt.durability()
    p = P.arrays()
    sup = p.bushing.code(dt.need("pivot_bushing_supplier"))
    env = P.env_code(dt.d.application_type)[0]
    length = dt.need("pivot_bushing_length_mm")
    par_max = dt.get("pulley_max_parallelism_eol_mm")
    t = np.linspace(0.0, float(t_end), _N)
    r = s4.evaluate_bushing(dt.need("hubload_nominal_n"), dt.need("pivot_diameter_mm"), length, th, f, t,
                            k_w_mm3_per_n_m=p.bushing_limits["k_w_mm3_per_n_m"][sup, env],
                            radial_clearance_mm=p.bushing.radial_clearance_mm[sup],
                            belt_plane_height_mm=dt.need("middle_plane_belt_height_mm"),
                            max_pivot_height_mm=dt.need("max_pivot_height_mm"),
                            axial_damping=bool(dt.v.get("axial_group_present")),
                            pulley_diameter_mm=dt.need("pulley_diameter_mm"),
                            fidelity="full" if dt.r.settings.get("bushing_running_in") else "screening")
    lim = {"sliding_layer_depth_mm": p.bushing.sliding_layer_depth_mm[sup]}
    dt._cache["bushing"] = (t, r, lim, par_max)
    return dt._cache["bushing"]


def g_bushing_wear(dt: _Data, ax):
    c = dt.curve("bushing_wear")
    if c:
        return _generic(ax, c, "time [h]", "wear [mm]"), None
    t, r, lim, _ = _bushing(dt)
    depth = float(lim["sliding_layer_depth_mm"])
    w_max = np.abs(np.asarray(r["wear_max_mm"], float))
    verdict = _check_verdict(dt.r, "bushing_wear") or _verdict(w_max[-1] <= depth)
    ax.plot(t, np.abs(r["wear_a_mm"]), color=COLOURS["other"], label="lower end (A)")
    ax.plot(t, np.abs(r["wear_b_mm"]), color=COLOURS["nominal"], label="upper end (B)")
    ax.plot(t, w_max, color=COLOURS[verdict], lw=2, label="most loaded end")
    ax.axhline(depth, ls="--", color=COLOURS["limit"], label="sliding layer depth")
    ax.set(xlabel="time [h]", ylabel="wear [mm]")
    return {"time_h": t, "wear_a_mm": np.abs(r["wear_a_mm"]), "wear_b_mm": np.abs(r["wear_b_mm"]),
            "wear_max_mm": w_max, "limit_mm": np.full_like(t, depth)}, verdict


def g_pulley_parallelism(dt: _Data, ax):
    c = dt.curve("pulley_parallelism")
    if c:
        return _generic(ax, c, "time [h]", "parallelism [mm]"), None
    t, r, _, par_max = _bushing(dt)
    par = np.asarray(r["parallelism_mm"], float)
    verdict = (_check_verdict(dt.r, "bushing_parallelism") or _verdict(par[-1] <= par_max)) if par_max else None
    ax.plot(t, par, color=COLOURS[verdict] if verdict else COLOURS["nominal"], lw=2, label="pulley parallelism")
    series = {"time_h": t, "parallelism_mm": par}
    if par_max:
        ax.axhline(par_max, ls="--", color=COLOURS["limit"], label="max parallelism at EOL")
        series["limit_mm"] = np.full_like(t, par_max)
    ax.set(xlabel="time [h]", ylabel="parallelism [mm]")
    return series, verdict


def g_damping_decay(dt: _Data, ax):
    h = dt.plastic_history()
    t, dmp = h["time_h"], h["damping_nm"]
    eol = dt.get("damping_eol_limit_nm")
    verdict = (_check_verdict(dt.r, "damping_eol") or _verdict(dmp[-1] >= eol)) if eol is not None else None
    ax.plot(t, dmp, color=COLOURS[verdict] if verdict else COLOURS["nominal"], lw=2, label="damping")
    series = {"time_h": t, "damping_nm": dmp}
    if eol is not None:
        ax.axhline(eol, ls="--", color=COLOURS["limit"], label="end-of-life limit")
        series["limit_nm"] = np.full_like(t, eol)
    ax.set(xlabel="time [h]", ylabel="damping [Nm]")
    return series, verdict


def _characteristic(dt: _Data):
    from synth.model import disc_spring as s8
    c = dt.cone()
    geo = (c["cone_spring_external_diameter_mm"], c["cone_spring_internal_diameter_mm"],
           c["cone_spring_thickness_mm"], c["cone_spring_cone_height_mm"])
    s = np.linspace(0.0, geo[3], _N)
    f = s8.disc_spring_force_n(s, *geo, fidelity=dt.fidelity)
    s_n = c["cone_spring_nominal_deflection_mm"]
    f_n = float(s8.disc_spring_force_n(s_n, *geo, fidelity=dt.fidelity))
    return c, geo, s, np.asarray(f, float), s_n, f_n


def g_cone_spring_characteristic(dt: _Data, ax):
    c = dt.curve("cone_spring_characteristic")
    if c:
        return _generic(ax, c, "deflection [mm]", "force [N]"), None
    c, geo, s, f, s_n, f_n = _characteristic(dt)
    ax.plot(s, f, color=COLOURS["nominal"], lw=2, label=f"De {geo[0]:g} / Di {geo[1]:g} / t {geo[2]:.3g} mm")
    ax.plot([s_n], [f_n], "o", color="black", label="nominal working point")
    ax.set(xlabel="deflection [mm]", ylabel="axial force [N]")
    return {"deflection_mm": s, "force_n": f, "nominal_deflection_mm": np.array([s_n]),
            "nominal_force_n": np.array([f_n])}, None


def g_plastic_wear(dt: _Data, ax):
    h = dt.plastic_history()
    t, w = h["time_h"], h["plastic_wear_total_mm"]
    total = h["damper_pad_wear_eol_mm"] + h["endcap_spacer_wear_eol_mm"]
    share = h["damper_pad_wear_eol_mm"] / total if total > 0 else 0.5
    verdict = _check_verdict(dt.r, "damper_pad_wear", "endcap_spacer_wear")
    ax.plot(t, w, color=COLOURS[verdict] if verdict else COLOURS["nominal"], lw=2, label="stack-up (total)")
    ax.plot(t, share * w, color=COLOURS["other"], label="damper pad")
    ax.plot(t, (1 - share) * w, ":", color=COLOURS["other"], label="endcap spacer")
    ax.set(xlabel="time [h]", ylabel="wear [mm]")
    return {"time_h": t, "plastic_wear_total_mm": w, "damper_pad_wear_mm": share * w,
            "endcap_spacer_wear_mm": (1 - share) * w}, verdict


def g_cone_spring_force_time(dt: _Data, ax):
    h = dt.plastic_history()
    t, f = h["time_h"], h["cone_spring_force_n"]
    verdict = _check_verdict(dt.r, "damping_eol")
    ax.plot(t, f, color=COLOURS[verdict] if verdict else COLOURS["nominal"], lw=2,
            label="axial force (wear and relaxation)")
    ax.set(xlabel="time [h]", ylabel="cone spring axial force [N]")
    return {"time_h": t, "cone_spring_force_n": f}, verdict


def g_cone_spring_tolerance_band(dt: _Data, ax):
    c, geo, s, f, s_n, f_n = _characteristic(dt)
    lo, hi = c["cone_spring_fax_min_tolerance_n"], c["cone_spring_fax_max_tolerance_n"]
    dh = c["gap_tolerance_mm"]
    verdict = _check_verdict(dt.r, "cone_force_band") or _verdict(lo <= f_n <= hi)
    ax.plot(s, f, color=COLOURS["nominal"], label="characteristic")
    ax.axhspan(lo, hi, color=COLOURS[verdict], alpha=0.15, label="force tolerance at nominal gap")
    ax.axhline(lo, color=COLOURS[verdict], lw=1)
    ax.axhline(hi, color=COLOURS[verdict], lw=1)
    ax.axvspan(max(s_n - dh, 0.0), s_n + dh, color=COLOURS["other"], alpha=0.12, label="gap tolerance")
    ax.plot([s_n], [f_n], "o", color="black", label="nominal")
    ax.set(xlabel="deflection [mm]", ylabel="axial force [N]")
    return {"deflection_mm": s, "force_n": f, "fax_min_tolerance_n": np.array([lo]),
            "fax_max_tolerance_n": np.array([hi]), "deflection_band_mm": np.array([max(s_n - dh, 0.0), s_n + dh])}, verdict


def g_goodman(dt: _Data, ax):
    c = dt.curve("goodman")
    if c:
        return _generic(ax, c, "mean stress [MPa]", "stress [MPa]"), None
    from synth.model import torsion_spring as s9
    smax, smin = (float(x) for x in dt.need("main_spring_sigma_a_max_mpa", "main_spring_sigma_a_min_mpa"))
    material = dt.need("main_spring_material")
    size = dt.need("main_spring_wire_size_mm")
    size = list(size) if isinstance(size, (list, tuple)) else [float(size)]
    round_wire = dt.get("main_spring_wire_section", "round") == "round" or len(size) == 1
    b, h = (size[0], size[0]) if len(size) == 1 else (size[0], size[1])
    p = s9.material_properties(material, b, h, round_wire)
    rm, sy, sa0 = (float(np.asarray(p[k]).reshape(-1)[0]) for k in ("Rm_mpa", "sigma_y_mpa", "sigma_A0_mpa"))
    sm = np.linspace(0.0, sy, _N)
    upper = np.minimum(sa0 + sm * (1.0 - sa0 / rm), sy)
    lower = 2.0 * sm - upper
    sf = float(s9.goodman_safety_factor(smax, smin, rm, sa0, sy))
    target = dt.get("main_spring_safety_factor_min")
    verdict = _check_verdict(dt.r, "spring_fatigue") or _verdict(sf >= float(target or 1.0))
    work_m = (smax + smin) / 2.0
    ax.plot(sm, upper, color=COLOURS["nominal"], lw=2, label="upper limit (Goodman, yield)")
    ax.plot(sm, lower, color=COLOURS["nominal"], lw=1)
    ax.plot(sm, sm, ":", color=COLOURS["other"], label="mean stress")
    ax.plot([work_m, work_m], [smin, smax], color=COLOURS[verdict], lw=4, label="working range")
    ax.plot([0.0, work_m * sf], [0.0, smax * sf], "--", color=COLOURS["limit"], lw=0.8,
            label=f"safety factor {sf:.2f}")
    ax.set(xlabel="mean stress [MPa]", ylabel="stress [MPa]")
    return {"mean_stress_mpa": sm, "upper_limit_mpa": upper, "lower_limit_mpa": lower,
            "working_range_mpa": np.array([smin, smax]), "safety_factor": np.array([sf])}, verdict


def g_pivot_base_pressure(dt: _Data, ax):
    from synth.model import bolted_joint as s10
    force = float(dt.need("bolt_axial_force_n"))
    hl = float(dt.need("hubload_nominal_n"))
    h = float(dt.need("middle_plane_belt_height_mm"))
    inc = float(dt.get("middle_plane_belt_height_increment_worst_mm", 0.0) or 0.0)
    d_ext, d_int = dt.need("engine_support_external_diameter_mm", "engine_support_internal_diameter_mm")
    theta = float(dt.get("contact_angle_deg", 360.0) or 360.0)
    ang = np.linspace(-180.0, 180.0, 2 * _N + 1) if theta >= 360.0 else np.linspace(-theta / 2, theta / 2, _N)
    nominal = s10.pivot_base_pressure_mpa(ang, force, hl * float(s10.tilting_lever_mm(h, 0.0)), d_ext, d_int, theta)
    worst = s10.pivot_base_pressure_mpa(ang, force, hl * float(s10.tilting_lever_mm(h, inc)), d_ext, d_int, theta)
    verdict = _check_verdict(dt.r, "tilting") or _verdict(np.min(worst) > 0.0)
    ax.plot(ang, nominal, color=COLOURS["nominal"], label="nominal")
    ax.plot(ang, worst, color=COLOURS[verdict], lw=2, label="worst condition")
    ax.axhline(0.0, ls="--", color=COLOURS["limit"], label="lift-off (tilting)")
    ax.set(xlabel="contact angle from the hubload direction [deg]", ylabel="contact pressure [MPa]")
    return {"angle_deg": ang, "pressure_nominal_mpa": np.asarray(nominal, float),
            "pressure_worst_mpa": np.asarray(worst, float)}, verdict


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


def g_pareto(dt: _Data, ax):
    rows = _rows(dt.extra.get("pareto"))
    num = _numeric_columns(rows)
    if len(rows) < 2 or len(num) < 2:
        raise _Skip("no Pareto front given (--pareto FILE with two numeric objective columns)")
    (kx, x), (ky, y) = num[0], num[1]
    order = np.argsort(x)
    ax.plot(x[order], y[order], "o-", color=COLOURS["nominal"])
    ax.set(xlabel=kx, ylabel=ky)
    return {kx: x[order], ky: y[order]}, None


def g_solvers(dt: _Data, ax):
    rows = _rows(dt.extra.get("solvers"))
    num = _numeric_columns(rows)
    if not rows or not num:
        raise _Skip("no solver comparison given (--solvers FILE: a name column and numeric columns)")
    names = [str(r.get("solver", r.get("name", i))) for i, r in enumerate(rows)]
    k, vals = num[0]
    ax.bar(names, vals, color=COLOURS["nominal"])
    ax.set(ylabel=k)
    ax.tick_params(axis="x", rotation=30)
    return {k: vals}, None


def _generic(ax, curve: dict, xlabel: str, ylabel: str) -> dict:
    """Plot a curve stored by the flowchart: first array as x, the others as y."""
    keys = list(curve)
    x = curve[keys[0]]
    for k in keys[1:]:
        if curve[k].shape == x.shape:
            ax.plot(x, curve[k], label=k)
    ax.set(xlabel=keys[0] or xlabel, ylabel=ylabel)
    return curve


_FUNCS = {gid: globals()[f"g_{gid}"] for gid, _, _ in CATALOG}


def graph_png(graph_id: str, result, extra: dict | None = None) -> Graph:
    """Draw one graph; raises ``LookupError`` with the reason when it does not apply."""
    dt = _Data(result, extra)
    g = _draw(graph_id, dt)
    if isinstance(g, Skipped):
        raise LookupError(f"{graph_id}: {g.reason}")
    return g


def _draw(gid: str, dt: _Data):
    title, figure = _TITLES[gid]
    fig, ax = _fig(f"{title} ({figure})")
    try:
        series, verdict = _FUNCS[gid](dt, ax)
    except _Skip as why:
        import matplotlib.pyplot as plt
        plt.close(fig)
        return Skipped(gid, title, str(why))
    series = {k: np.atleast_1d(np.asarray(v, float)) for k, v in series.items()}
    if ax.get_legend_handles_labels()[0]:
        ax.legend(fontsize=8, loc="best")
    return Graph(gid, title, figure, series, verdict, png=_png(fig))


def _cad_graphs(dt: _Data) -> list[Graph]:
    paths = list(dt.extra.get("cad") or []) + list((dt.r.curves or {}).get("cad_images") or [])
    out = []
    for i, p in enumerate(paths):
        p = Path(p)
        if p.is_file() and p.suffix.lower() == ".png":
            out.append(Graph(f"cad_{i + 1}", f"CAD model: {p.stem}", "Fig. 75-76", {}, None, png=p.read_bytes()))
    return out


def build_graphs(result, extra: dict | None = None, *, show_progress: bool = True):
    """Every graph of :data:`CATALOG` that applies, and the skipped ones with the reason.

    ``extra``: ``{"pareto": rows, "solvers": rows, "cad": [png paths]}`` from
    other scenes. Returns ``(graphs, skipped)``.
    """
    from synth.report.progress import progress
    dt = _Data(result, extra)
    graphs, skipped = [], []
    ids = [gid for gid, _, _ in CATALOG]
    for gid in (progress(ids, "report graphs") if show_progress else ids):
        g = _draw(gid, dt)
        (skipped if isinstance(g, Skipped) else graphs).append(g)
    graphs.extend(_cad_graphs(dt))
    return graphs, skipped
