"""The thesis's graphs of one design, drawn with matplotlib (Agg) from the evaluator's data.

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

Each graph's verdict colour is the verdict of the result's own checks
(:data:`GRAPH_CHECKS`, registry ids): green pass, red fail, amber warning, and
the neutral blue where the check was not evaluated. A graph whose data the
result lacks (a step that does not apply, an input not given) is listed with
the reason, never drawn empty and never filled in by re-running a step's
selection.

Every :class:`Graph` carries its data (``series``: named 1-D arrays, the
plotted lines) and the PNG, so tests assert on the numbers and the report
embeds the picture.

>>> [g[0] for g in CATALOG][:3]
['hysteresis_load', 'hysteresis_torque', 'sensitivity_differential_angle']
>>> GRAPH_CHECKS["bushing_wear"]
('bushing_wear',)
"""

from __future__ import annotations

import io
import math
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from synth.design.constraints import REGISTRY
from synth.design.result import FAIL, PASS, WARNING
from synth.model import damping
from synth.design import evaluate
from synth.model import disc_spring
from synth.model import bolted_joint
from synth.drive.analysis import drive_model, drive_sweep
from synth.drive.analysis import durability_point
from synth.progress import progress
from synth.design.evaluate import Settings
from synth.schema import validate
from synth.design.applications import Applications
from synth.design.space import space

__all__ = ["Graph", "Skipped", "CATALOG", "GRAPH_CHECKS", "build_graphs", "graph_png", "COLOURS", "graph_verdict",
           "drive_figure", "pareto_figure", "ON_REQUEST"]

#: Thesis colours: verified green, failed red, advisory warning amber, nominal/reference blue, limit black.
COLOURS = {PASS: "#2e7d32", FAIL: "#c62828", WARNING: "#ef6c00", "nominal": "#1f5fbf", "limit": "black",
           "other": "#7f7f7f"}

#: graphs drawn only from a file the user gives (``synth report --pareto/--solvers``): without it nothing is missing,
#: so a review document does not list them as not drawn
ON_REQUEST = ("pareto", "solvers")

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
    ("drive_arm_amplitude", "Tensioner arm amplitude against engine speed", "drive"),
    ("drive_span_tension", "Span tensions against engine speed", "drive"),
    ("drive_hysteresis_loop", "Arm friction loop at the durability speed", "drive"),
    ("pareto", "Pareto front", "optimiser"),
    ("solvers", "Solver comparison", "optimiser"),
)
_TITLES = {i: (t, f) for i, t, f in CATALOG}

#: graph id -> the registry checks whose verdict colours the graph (the worst of them)
GRAPH_CHECKS: dict[str, tuple[str, ...]] = {
    "hysteresis_load": ("self_locking",),
    "hysteresis_torque": ("damping_upper", "damping_lower"),
    "bushing_wear": ("bushing_wear",),
    "pulley_parallelism": ("bushing_parallelism",),
    "damping_decay": ("damping_eol",),
    "cone_spring_characteristic": ("cone_not_flattened",),
    "plastic_wear": ("damper_pad_wear", "endcap_spacer_wear"),
    "cone_spring_force_time": ("damping_eol",),
    "cone_spring_tolerance_band": ("cone_force_band",),
    "goodman": ("spring_fatigue",),
    "pivot_base_pressure": ("tilting", "pivot_base_pressure"),
    "drive_arm_amplitude": ("drive_arm_lock",),
    "drive_span_tension": ("drive_belt_slack",),
    "drive_hysteresis_loop": ("drive_arm_lock",),
}
_UNKNOWN = sorted({c for ids in GRAPH_CHECKS.values() for c in ids} - set(REGISTRY))
if _UNKNOWN:  # pragma: no cover - a renamed registry id must not silently leave a graph uncoloured
    raise ImportError(f"synth.report.plots: GRAPH_CHECKS names checks the registry does not hold: {_UNKNOWN}")
_N = 121  # points per swept curve
_T = 60   # points of the time axes (as the report's verification keeps the wear history)


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


def graph_verdict(result, gid: str) -> str | None:
    """The verdict of graph ``gid``: the worst verdict of its :data:`GRAPH_CHECKS` among the result's checks.

    ``fail`` before ``warning`` before ``pass``; None when none of them was evaluated.

    >>> from synth.design.result import Check, Result
    >>> r = Result("verified", checks=[Check("tilting", 3.8, 3.5, 0.09, "pass"),
    ...                                Check("pivot_base_pressure", 500.0, 400.0, -0.25, "fail")])
    >>> graph_verdict(r, "pivot_base_pressure"), graph_verdict(r, "goodman")
    ('fail', None)
    """
    ids = GRAPH_CHECKS.get(gid, ())
    hits = {c.verdict for c in result.checks if c.id in ids}
    for v in (FAIL, WARNING, PASS):
        if v in hits:
            return v
    return None


def _colour(verdict) -> str:
    return COLOURS.get(verdict, COLOURS["nominal"])


# ------------------------------------------------------------------------------------------ data access
class _Data:
    """The result's values and parts, its application as arrays and its model settings."""

    def __init__(self, result, extra: dict | None):
        self.r, self.v = result, {**result.values, **result.parts}
        self.extra = extra or {}
        self._cache: dict = {}
        known = set(Settings.__dataclass_fields__)
        self.settings = Settings(**{k: v for k, v in (result.settings or {}).items() if k in known})
        # the model of the result's values: the judge's (full at fidelity screening)
        self.fidelity, self.friction_circle = self.settings.judge.model, self.settings.friction_circle
        self.d = None
        if isinstance(result.inputs, dict):
            self.d = validate({k: v for k, v in result.inputs.items() if v is not None})
        elif result.inputs is not None:
            self.d = result.inputs

    @property
    def apps(self):
        """The result's application as :class:`~synth.design.applications.Applications` (N = 1)."""
        if "apps" not in self._cache:
            if self.d is None:
                raise _Skip("the result carries no design input")
            self._cache["apps"] = Applications.of([self.d])
        return self._cache["apps"]

    def need(self, *keys):
        """Values of ``keys`` from the result (or the input); _Skip naming the first missing one."""
        out = []
        for k in keys:
            val = self.v.get(k)
            if val is None and self.d is not None and hasattr(self.d, k):
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
        """``(theta_pp_deg, frequency_hz, duration_h)`` of the evaluator's applications (given or assumed)."""
        a = self.apps
        th, fr, du = (float(x[0]) for x in (a.theta_pp_deg, a.frequency_hz, a.duration_h))
        if not all(math.isfinite(x) for x in (th, fr, du)):
            raise _Skip("durability test missing (peak-to-peak angle, frequency and duration, or an engine type)")
        return th, fr, du

    def axial(self) -> bool:
        if not self.v.get("axial_damping_present"):
            raise _Skip("no axial damping: the step does not apply")
        return True

    def attributes(self) -> dict:
        """The design's catalog attributes (one row per table), as the evaluator reads them."""
        if "attrs" not in self._cache:
            if not self.r.parts or any(v is None for v in self.r.parts.values()):
                raise _Skip("the result has no complete design (parts)")
            self._cache["attrs"] = space().design_attributes(self.r.parts)
        return self._cache["attrs"]

    def mu_plastic(self) -> float:
        """The plastic friction coefficient the evaluator uses for the application's environment."""
        return float(self.apps.mu_plastic[0])

    def cone(self) -> dict:
        """Cone spring geometry, nominal deflection and force band as the evaluator sized them."""
        self.axial()
        keys = ("cone_spring_external_diameter_mm", "cone_spring_internal_diameter_mm",
                "cone_spring_thickness_mm", "cone_spring_cone_height_mm", "cone_spring_nominal_deflection_mm",
                "cone_spring_fax_max_tolerance_n", "cone_spring_fax_min_tolerance_n", "cone_spring_gap_tolerance_mm")
        if not all(isinstance(self.v.get(k), (int, float)) and math.isfinite(self.v[k]) for k in keys):
            raise _Skip("the design has no sized cone spring")
        c = {k: float(self.v[k]) for k in keys}
        c["cone_spring_max_deflection_mm"] = float(self.v.get("cone_spring_max_deflection_mm") or math.nan)
        return c

    def plastic_history(self) -> dict:
        """The step 5 time histories kept by the evaluator (``result.curves["plastic_wear"]``)."""
        self.axial()
        c = (self.r.curves or {}).get("plastic_wear")
        want = ("time_h", "plastic_wear_total_mm", "cone_spring_force_n", "damping_nm")
        if not isinstance(c, dict) or not all(k in c for k in want):
            raise _Skip("the result keeps no wear history (the durability test is missing, or the result "
                        "was verified without time points)")
        h = {k: np.asarray(c[k], float).reshape(-1) for k in want}
        h["damper_pad_wear_eol_mm"] = float(self.need("damper_pad_wear_mm"))
        h["endcap_spacer_wear_eol_mm"] = float(self.need("endcap_spacer_wear_mm"))
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


# ------------------------------------------------------------------------------------------ graphs
def _characterisation(dt: _Data):
    try:
        half = dt.durability()[0] / 2.0 or 10.0
    except _Skip:
        half = 10.0
    theta = np.linspace(-half, half, _N)
    ch = damping.characterisation(dt.need("spring_torque_nominal_nm"), dt.need("spring_stiffness_nm_per_deg"),
                             dt.get("axial_damping_nm", 0.0) or 0.0, dt.need("working_arm_mm"),
                             dt.need("differential_angle_deg"), dt.need("pivot_diameter_mm"),
                             dt.need("mu_pivot_bushing"), theta, dt.friction_circle)
    return theta, ch


def g_hysteresis_load(dt: _Data, ax, verdict):
    theta, ch = _characterisation(dt)
    ax.plot(theta, ch["hubload_loading_n"], color=_colour(verdict), label="loading")
    ax.plot(theta, ch["hubload_unloading_n"], color=COLOURS["other"], label="unloading")
    ax.fill_between(theta, ch["hubload_unloading_n"], ch["hubload_loading_n"], color=_colour(verdict), alpha=0.1)
    ax.set(xlabel="arm rotation from nominal [deg]", ylabel="hubload [N]")
    return {"theta_deg": theta, "hubload_loading_n": ch["hubload_loading_n"],
            "hubload_unloading_n": ch["hubload_unloading_n"]}


def g_hysteresis_torque(dt: _Data, ax, verdict):
    theta, ch = _characterisation(dt)
    ax.plot(theta, ch["torque_loading_nm"], color=_colour(verdict), label="loading")
    ax.plot(theta, ch["torque_unloading_nm"], color=COLOURS["other"], label="unloading")
    ax.plot(theta, ch["calculated_torque_nm"], "--", color="black", lw=0.8, label="calculated torque")
    ax.fill_between(theta, ch["torque_unloading_nm"], ch["torque_loading_nm"], color=_colour(verdict), alpha=0.1)
    ax.set(xlabel="arm rotation from nominal [deg]", ylabel="torque at the pulley [Nm]")
    return {"theta_deg": theta, "torque_loading_nm": ch["torque_loading_nm"],
            "torque_unloading_nm": ch["torque_unloading_nm"], "calculated_torque_nm": ch["calculated_torque_nm"]}


def _sensitivity(dt: _Data, ax, parameter, values, xlabel, design: float):
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
    ax.axvline(design, color=COLOURS["limit"], ls="-.", lw=0.8, label=f"design point ({_plain(design)})")
    for key in ("calculated_torque_nm", "damping_nm"):
        ax.plot([design], [np.interp(design, values, s[key])], "o", color="black", ms=4)
    ax2.plot([design], [np.interp(design, values, s["asymmetry_ratio"])], "o", color="black", ms=4)
    ax.set(xlabel=xlabel, ylabel="torque [Nm]")
    return {"values": np.asarray(values, float), "calculated_torque_nm": s["calculated_torque_nm"],
            "damping_nm": s["damping_nm"], "asymmetry_ratio": np.asarray(s["asymmetry_ratio"], float)}


def g_sensitivity_differential_angle(dt: _Data, ax, verdict):
    a = float(dt.need("differential_angle_deg"))
    values = np.linspace(max(a - 30.0, 5.0), min(a + 30.0, 175.0), _N)
    return _sensitivity(dt, ax, "differential_angle_deg", values, "differential angle [deg]", a)


def g_sensitivity_mu_pivot_bushing(dt: _Data, ax, verdict):
    mu = float(dt.need("mu_pivot_bushing"))
    return _sensitivity(dt, ax, "mu_pivot_bushing", np.linspace(0.0, 2.0 * mu, _N), "pivot bushing friction [-]", mu)


def g_sensitivity_mu_plastic(dt: _Data, ax, verdict):
    dt.axial()
    mu = dt.mu_plastic()
    return _sensitivity(dt, ax, "mu_plastic", np.linspace(0.5 * mu, 1.5 * mu, _N), "plastic friction coefficient [-]",
                        mu)


def _bushing(dt: _Data, time_points: int = _T) -> dict:
    if "bushing" in dt._cache:
        return dt._cache["bushing"]
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
        raise _Skip("the bushing supplier has no wear rating for this environment")
    out = {"time_h": t, **{k: np.asarray(v, float) for k, v in g.values.items() if k != "app"}}
    dt._cache["bushing"] = out
    return out


def g_bushing_wear(dt: _Data, ax, verdict):
    b = _bushing(dt)
    t = b["time_h"]
    depth = float(b["pivot_bushing_sliding_layer_mm"][0])
    w_max = np.abs(b["pivot_bushing_wear_max_mm"])
    ax.plot(t, np.abs(b["pivot_bushing_wear_a_mm"]), color=COLOURS["other"], label="lower end (A)")
    ax.plot(t, np.abs(b["pivot_bushing_wear_b_mm"]), color=COLOURS["nominal"], label="upper end (B)")
    ax.plot(t, w_max, color=_colour(verdict), lw=2, label="most loaded end")
    ax.axhline(depth, ls="--", color=COLOURS["limit"], label="sliding layer depth")
    ax.set(xlabel="time [h]", ylabel="wear [mm]")
    return {"time_h": t, "wear_a_mm": np.abs(b["pivot_bushing_wear_a_mm"]),
            "wear_b_mm": np.abs(b["pivot_bushing_wear_b_mm"]), "wear_max_mm": w_max,
            "limit_mm": np.full_like(t, depth)}


def g_pulley_parallelism(dt: _Data, ax, verdict):
    b = _bushing(dt)
    t, par = b["time_h"], b["pivot_bushing_parallelism_mm"]
    par_max = float(b["pulley_max_parallelism_eol_mm"][0])
    ax.plot(t, par, color=_colour(verdict), lw=2, label="pulley parallelism")
    series = {"time_h": t, "parallelism_mm": par}
    if math.isfinite(par_max):
        ax.axhline(par_max, ls="--", color=COLOURS["limit"], label="max parallelism at EOL")
        series["limit_mm"] = np.full_like(t, par_max)
    ax.set(xlabel="time [h]", ylabel="parallelism [mm]")
    return series


def g_damping_decay(dt: _Data, ax, verdict):
    h = dt.plastic_history()
    t, dmp = h["time_h"], h["damping_nm"]
    eol = dt.get("damping_eol_limit_nm")
    ax.plot(t, dmp, color=_colour(verdict), lw=2, label="damping")
    series = {"time_h": t, "damping_nm": dmp}
    if eol is not None:
        ax.axhline(eol, ls="--", color=COLOURS["limit"], label="end-of-life limit")
        series["limit_nm"] = np.full_like(t, eol)
    ax.set(xlabel="time [h]", ylabel="damping [Nm]")
    return series


def _characteristic(dt: _Data):
    c = dt.cone()
    geo = (c["cone_spring_external_diameter_mm"], c["cone_spring_internal_diameter_mm"],
           c["cone_spring_thickness_mm"], c["cone_spring_cone_height_mm"])
    s = np.linspace(0.0, geo[3], _N)
    f = disc_spring.disc_spring_force_n(s, *geo, fidelity=dt.fidelity)
    s_n = c["cone_spring_nominal_deflection_mm"]
    f_n = float(disc_spring.disc_spring_force_n(s_n, *geo, fidelity=dt.fidelity))
    return c, geo, s, np.asarray(f, float), s_n, f_n


def g_cone_spring_characteristic(dt: _Data, ax, verdict):
    c, geo, s, f, s_n, f_n = _characteristic(dt)
    ax.plot(s, f, color=_colour(verdict), lw=2, label=f"De {geo[0]:.3g} / Di {geo[1]:.3g} / t {geo[2]:.3g} mm")
    ax.plot([s_n], [f_n], "o", color="black", label="nominal working point")
    series = {"deflection_mm": s, "force_n": f, "nominal_deflection_mm": np.array([s_n]),
              "nominal_force_n": np.array([f_n])}
    s_max = c["cone_spring_max_deflection_mm"]
    if math.isfinite(s_max):
        ax.axvline(s_max, ls="--", color=COLOURS["limit"], lw=0.8, label="maximum deflection (worst gap)")
        series["max_deflection_mm"] = np.array([s_max])
    ax.set(xlabel="deflection [mm]", ylabel="axial force [N]")
    return series


def g_plastic_wear(dt: _Data, ax, verdict):
    h = dt.plastic_history()
    t, w = h["time_h"], h["plastic_wear_total_mm"]
    total = h["damper_pad_wear_eol_mm"] + h["endcap_spacer_wear_eol_mm"]
    share = h["damper_pad_wear_eol_mm"] / total if total > 0 else 0.5
    ax.plot(t, w, color=_colour(verdict), lw=2, label="stack-up (total)")
    ax.plot(t, share * w, color=COLOURS["other"], label="damper pad")
    ax.plot(t, (1 - share) * w, ":", color=COLOURS["other"], label="endcap spacer")
    ax.set(xlabel="time [h]", ylabel="wear [mm]")
    return {"time_h": t, "plastic_wear_total_mm": w, "damper_pad_wear_mm": share * w,
            "endcap_spacer_wear_mm": (1 - share) * w}


def g_cone_spring_force_time(dt: _Data, ax, verdict):
    h = dt.plastic_history()
    t, f = h["time_h"], h["cone_spring_force_n"]
    ax.plot(t, f, color=_colour(verdict), lw=2, label="axial force (wear and relaxation)")
    ax.set(xlabel="time [h]", ylabel="cone spring axial force [N]")
    return {"time_h": t, "cone_spring_force_n": f}


def g_cone_spring_tolerance_band(dt: _Data, ax, verdict):
    c, geo, s, f, s_n, f_n = _characteristic(dt)
    lo, hi = c["cone_spring_fax_min_tolerance_n"], c["cone_spring_fax_max_tolerance_n"]
    dh = c["cone_spring_gap_tolerance_mm"]
    col = _colour(verdict)
    ax.plot(s, f, color=COLOURS["nominal"], label="characteristic")
    ax.axhspan(lo, hi, color=col, alpha=0.15, label="force tolerance at nominal gap")
    ax.axhline(lo, color=col, lw=1)
    ax.axhline(hi, color=col, lw=1)
    ax.axvspan(max(s_n - dh, 0.0), s_n + dh, color=COLOURS["other"], alpha=0.12, label="gap tolerance")
    ax.plot([s_n], [f_n], "o", color="black", label="nominal")
    ax.set(xlabel="deflection [mm]", ylabel="axial force [N]")
    return {"deflection_mm": s, "force_n": f, "fax_min_tolerance_n": np.array([lo]),
            "fax_max_tolerance_n": np.array([hi]), "deflection_band_mm": np.array([max(s_n - dh, 0.0), s_n + dh])}


def g_goodman(dt: _Data, ax, verdict):
    smax, smin = (float(x) for x in dt.need("main_spring_sigma_a_max_mpa", "main_spring_sigma_a_min_mpa"))
    sf = float(dt.need("main_spring_safety_factor"))
    sp = dt.attributes()["spring"]
    rm, sy, sa0 = (float(np.asarray(sp[k]).reshape(-1)[0]) for k in ("Rm_mpa", "sigma_y_mpa", "sigma_A0_mpa"))
    sm = np.linspace(0.0, sy, _N)
    upper = np.minimum(sa0 + sm * (1.0 - sa0 / rm), sy)
    lower = 2.0 * sm - upper
    work_m = (smax + smin) / 2.0
    ax.plot(sm, upper, color=COLOURS["nominal"], lw=2, label="upper limit (Goodman, yield)")
    ax.plot(sm, lower, color=COLOURS["nominal"], lw=1)
    ax.plot(sm, sm, ":", color=COLOURS["other"], label="mean stress")
    ax.plot([work_m, work_m], [smin, smax], color=_colour(verdict), lw=4, label="working range")
    ax.plot([0.0, work_m * sf], [0.0, smax * sf], "--", color=COLOURS["limit"], lw=0.8,
            label=f"safety factor {sf:.2f}")
    ax.set(xlabel="mean stress [MPa]", ylabel="stress [MPa]")
    return {"mean_stress_mpa": sm, "upper_limit_mpa": upper, "lower_limit_mpa": lower,
            "working_range_mpa": np.array([smin, smax]), "safety_factor": np.array([sf])}


def g_pivot_base_pressure(dt: _Data, ax, verdict):
    force = float(dt.need("bolt_axial_force_n"))
    hl = float(dt.need("hubload_nominal_n"))
    h = float(dt.need("middle_plane_belt_height_mm"))
    inc = float(dt.apps.f["middle_plane_belt_height_increment_worst_mm"][0])
    d_ext, d_int = dt.need("engine_support_external_diameter_mm", "engine_support_internal_diameter_mm")
    theta = float(dt.need("contact_angle_deg"))
    ang = np.linspace(-180.0, 180.0, 2 * _N + 1) if theta >= 360.0 else np.linspace(-theta / 2, theta / 2, _N)
    nominal = bolted_joint.pivot_base_pressure_mpa(ang, force, hl * float(bolted_joint.tilting_lever_mm(h, 0.0)), d_ext, d_int, theta)
    worst = bolted_joint.pivot_base_pressure_mpa(ang, force, hl * float(bolted_joint.tilting_lever_mm(h, inc)), d_ext, d_int, theta)
    ax.plot(ang, nominal, color=COLOURS["nominal"], label="nominal")
    ax.plot(ang, worst, color=_colour(verdict), lw=2, label="worst condition")
    ax.axhline(0.0, ls="--", color=COLOURS["limit"], label="lift-off (tilting)")
    ax.set(xlabel="contact angle from the hubload direction [deg]", ylabel="contact pressure [MPa]")
    return {"angle_deg": ang, "pressure_nominal_mpa": np.asarray(nominal, float),
            "pressure_worst_mpa": np.asarray(worst, float)}


def _drive_sweep(dt: _Data):
    """The drive's sweep with the design's own damping (the registry's drive checks evaluate the same sweep)."""
    drive = dt.settings.drive
    if drive is None:
        raise _Skip("the design was not run with a drive (synth design --drive)")
    damping = dt.get("damping_nm")
    if damping is None:
        raise _Skip("the design has no damping value")
    return drive, drive_model(drive), drive_sweep(drive, float(damping)), float(damping)


def g_drive_arm_amplitude(dt: _Data, ax, verdict):
    drive, _, sw, damping = _drive_sweep(dt)
    ax.plot(sw["speed_rpm"], sw["theta_pp_deg"], color=_colour(verdict), label=f"damping {damping:.3g} Nm")
    if drive.durability_speed_rpm is not None:
        ax.axvline(drive.durability_speed_rpm, color=COLOURS["limit"], ls="--", lw=0.8, label="durability speed")
    ax.set(xlabel="engine speed [rpm]", ylabel="arm peak-to-peak angle [deg]")
    return {"speed_rpm": sw["speed_rpm"], "theta_pp_deg": sw["theta_pp_deg"]}


def g_drive_span_tension(dt: _Data, ax, verdict):
    drive, model, sw, _ = _drive_sweep(dt)
    out = {"speed_rpm": sw["speed_rpm"]}
    for j, name in enumerate(model.span_names):
        line, = ax.plot(sw["speed_rpm"], sw["tension_max_n"][:, j], lw=1, label=name)
        ax.plot(sw["speed_rpm"], sw["tension_min_n"][:, j], lw=1, color=line.get_color(), ls=":")
        out[f"{name}_min_n"], out[f"{name}_max_n"] = sw["tension_min_n"][:, j], sw["tension_max_n"][:, j]
    ax.axhline(drive.belt_min_tension_n, color=_colour(verdict), lw=1.5, label="slack limit")
    _line_styles(ax, drive.durability_speed_rpm)
    ax.set(xlabel="engine speed [rpm]", ylabel="span tension, max (solid) and min (dotted) [N]")
    return out


def g_drive_hysteresis_loop(dt: _Data, ax, verdict):
    drive, _, _, damping = _drive_sweep(dt)
    if drive.durability_speed_rpm is None:
        raise _Skip("the drive gives no durability speed")
    p = durability_point(drive, damping)
    ang = np.degrees(p["psi_rad"])
    tq = drive.tensioner.nominal_torque_nm - drive.tensioner.stiffness_nm_per_deg * ang - p["friction_nm_t"]
    ax.plot(np.append(ang, ang[:1]), np.append(tq, tq[:1]), color=_colour(verdict))
    ax.set(xlabel="arm angle from nominal (take-up positive) [deg]",
           ylabel="belt torque on the arm [Nm]", title=f"{p['speed_rpm']:g} rpm, theta_pp {p['theta_pp_deg']:.3g} deg")
    return {"angle_deg": ang, "torque_nm": tq}


def _plain(x) -> str:
    from synth import formatting as fmt
    return fmt.number(x)


def _line_styles(ax, durability_speed_rpm=None) -> None:
    """What the span-tension plots' line styles mean, in the legend (each span keeps one colour: solid its largest
    tension over a revolution, dotted its smallest), and the durability speed marked."""
    ax.plot([], [], color="0.3", lw=1, label="solid: largest tension")
    ax.plot([], [], color="0.3", lw=1, ls=":", label="dotted: smallest tension")
    if durability_speed_rpm is not None:
        ax.axvline(durability_speed_rpm, color=COLOURS["limit"], ls="--", lw=0.8,
                   label=f"durability speed ({_plain(durability_speed_rpm)} rpm)")


def drive_figure(res: dict):
    """Arm amplitude and the lowest span tension against speed, from :func:`synth.drive.analysis.analyse`."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    sw = res["sweep"]
    fig, (a1, a2) = plt.subplots(2, 1, figsize=(7, 6), sharex=True)
    a1.plot(sw["speed_rpm"], sw["theta_pp_deg"], color=COLOURS["nominal"], label="arm peak-to-peak angle")
    a1.set(ylabel="arm peak-to-peak [deg]", title=res["name"])
    t_min, t_max = np.asarray(sw["tension_min_n"]), np.asarray(sw["tension_max_n"])
    for j, name in enumerate(res["spans"]):
        line, = a2.plot(sw["speed_rpm"], t_max[:, j], lw=1, label=name)
        a2.plot(sw["speed_rpm"], t_min[:, j], lw=1, ls=":", color=line.get_color())
    a2.axhline(res["slack"]["limit_n"], color=COLOURS["limit"], lw=1, label="slack limit")
    durability = (res.get("durability") or {}).get("speed_rpm")
    if durability is not None:
        a1.axvline(durability, color=COLOURS["limit"], ls="--", lw=0.8, label=f"durability speed ({_plain(durability)} rpm)")
    _line_styles(a2, durability)
    a2.set(xlabel="engine speed [rpm]", ylabel="span tension [N]")
    a1.legend(fontsize=7)
    a2.legend(fontsize=7)
    fig.tight_layout()
    return fig


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


def g_pareto(dt: _Data, ax, verdict):
    rows = _rows(dt.extra.get("pareto"))
    num = _numeric_columns(rows)
    if len(rows) < 2 or len(num) < 2:
        raise _Skip("no Pareto front given (--pareto FILE with two numeric objective columns)")
    (kx, x), (ky, y) = num[0], num[1]
    order = np.argsort(x)
    ax.plot(x[order], y[order], "o-", color=COLOURS["nominal"])
    ax.set(xlabel=kx, ylabel=ky)
    return {kx: x[order], ky: y[order]}


def g_solvers(dt: _Data, ax, verdict):
    rows = _rows(dt.extra.get("solvers"))
    num = _numeric_columns(rows)
    if not rows or not num:
        raise _Skip("no solver comparison given (--solvers FILE: a name column and numeric columns)")
    names = [str(r.get("solver", r.get("name", i))) for i, r in enumerate(rows)]
    k, vals = num[0]
    ax.bar(names, vals, color=COLOURS["nominal"])
    ax.set(ylabel=k)
    ax.tick_params(axis="x", rotation=30)
    return {k: vals}


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
    verdict = graph_verdict(dt.r, gid)
    try:
        series = _FUNCS[gid](dt, ax, verdict)
    except _Skip as why:
        import matplotlib.pyplot as plt
        plt.close(fig)
        return Skipped(gid, title, str(why))
    series = {k: np.atleast_1d(np.asarray(v, float)) for k, v in series.items()}
    if ax.get_legend_handles_labels()[0]:
        ax.legend(fontsize=8, loc="best")
    return Graph(gid, title, figure, series, verdict, png=_png(fig))


_CAD_TITLES = {"section": "3D model: section through the pivot axis", "exploded": "3D model: exploded view"}


def _cad_graphs(dt: _Data) -> list[Graph]:
    return cad_graphs(list(dt.extra.get("cad") or []) + list((dt.r.curves or {}).get("cad_images") or []))


def cad_graphs(paths) -> list[Graph]:
    """The 3D model's pictures (PNG paths: ``section.png``, ``exploded.png``) as graphs (Fig. 75-76)."""
    out = []
    for i, p in enumerate(paths):
        p = Path(p)
        if p.is_file() and p.suffix.lower() == ".png":
            title = _CAD_TITLES.get(p.stem, f"3D model: {p.stem}")
            out.append(Graph(f"cad_{i + 1}", title, "Fig. 75-76", {}, None, png=p.read_bytes()))
    return out


def build_graphs(result, extra: dict | None = None, *, show_progress: bool = True):
    """Every graph of :data:`CATALOG` that applies, and the skipped ones with the reason.

    ``extra``: ``{"pareto": rows, "solvers": rows, "cad": [png paths]}`` from
    other scenes. Returns ``(graphs, skipped)``.
    """
    dt = _Data(result, extra)
    graphs, skipped = [], []
    ids = [gid for gid, _, _ in CATALOG if not gid.startswith("drive_") or dt.settings.drive is not None]
    for gid in (progress(ids, "report graphs") if show_progress else ids):
        g = _draw(gid, dt)
        (skipped if isinstance(g, Skipped) else graphs).append(g)
    graphs.extend(_cad_graphs(dt))
    return graphs, skipped


def pareto_figure(front: list, path, *, y: str = "margin", ylabel: str = "smallest margin [%]",
                  title: str = "cost against margin: Pareto front", note=None) -> None:
    """Save a Pareto front (cost against ``y``; a margin, a fraction in the data, in percent) to ``path``: each
    point numbered, and under the plot one line per number saying which design it is
    (:func:`synth.formatting.design_label`), what it scores and ``note(point)`` (default: what binds), so no label
    is clipped and every point names its design."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import textwrap

    from synth import formatting as fmt
    from synth.design.constraints import words
    from synth.io.outputs import write_figure
    note = note or (lambda p: "binds: " + words(p["binding"]))
    scale = 100.0 if y == "margin" else 1.0
    lines = []
    for i, p in enumerate(front, start=1):
        score = fmt.percent(p[y]) if y == "margin" else f"{y} {fmt.number(p[y], 3)}"
        text = f"{i}: {fmt.number(p['cost_eur'])} EUR, {score}; {note(p)}; {fmt.design_label(p.get('parts') or {})}"
        lines += textwrap.wrap(text, 125, subsequent_indent="     ")
    fig = plt.figure(figsize=(8.5, 4.6 + 0.16 * len(lines)))
    height = 4.1 / (4.6 + 0.16 * len(lines))
    ax = fig.add_axes((0.1, 1.0 - height - 0.02, 0.86, height - 0.09))
    c = [p["cost_eur"] for p in front]
    m = [scale * p[y] for p in front]
    ax.step(c, m, where="post", color="0.6", label="front (cheapest design at each level)")
    ax.plot(c, m, "o", color=COLOURS["nominal"], label="design on the front (numbered below)")
    for i, (x, v) in enumerate(zip(c, m), start=1):
        ax.annotate(str(i), (x, v), fontsize=8, xytext=(4, 4), textcoords="offset points")
    ax.set_xlabel("cost [EUR] (catalog unit costs)")
    ax.set_ylabel(ylabel)
    ax.set_title(title)
    ax.grid(True, alpha=0.3)
    ax.margins(x=0.08, y=0.12)
    ax.legend(fontsize=7, loc="lower right")
    fig.text(0.02, 1.0 - height - 0.1, "\n".join(lines), fontsize=6.5, va="top", family="monospace")
    write_figure(fig, path, dpi=120)
