"""What every graph of a design draws with: the result's data as the graphs read it, the colours and the figure.

:class:`Data` gives a graph the result's values and parts, its application as arrays, its model settings and the
data a step kept (the wear history, the cone spring, the catalog attributes), raising :class:`Skip` with the reason
when the result lacks what a graph needs; :func:`new_figure` and :func:`png_bytes` make and encode the figure
(matplotlib, Agg); :data:`COLOURS` are the thesis's verdict colours.

>>> colour("fail"), colour(None) == COLOURS["nominal"]
('#c62828', True)
"""

from __future__ import annotations

import io
import math

import numpy as np

from synth.design.applications import Applications
from synth.design.evaluate import Settings
from synth.design.result import FAIL, PASS, WARNING
from synth.design.space import space
from synth.schema import validate

__all__ = ["COLOURS", "colour", "Skip", "Data", "new_figure", "png_bytes"]

#: Thesis colours: verified green, failed red, advisory warning amber, nominal/reference blue, limit black.
COLOURS = {PASS: "#2e7d32", FAIL: "#c62828", WARNING: "#ef6c00", "nominal": "#1f5fbf", "limit": "black",
           "other": "#7f7f7f"}


class Skip(Exception):
    """A graph that does not apply or lacks data: the message says why."""


def colour(verdict) -> str:
    return COLOURS.get(verdict, COLOURS["nominal"])


# ------------------------------------------------------------------------------------------ data access
class Data:
    """The result's values and parts, its application as arrays and its model settings."""

    def __init__(self, result, extra: dict | None):
        self.r, self.v = result, {**result.values, **result.parts}
        self.extra = extra or {}
        self.cache: dict = {}
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
        if "apps" not in self.cache:
            if self.d is None:
                raise Skip("the result carries no design input")
            self.cache["apps"] = Applications.of([self.d])
        return self.cache["apps"]

    def need(self, *keys):
        """Values of ``keys`` from the result (or the input); Skip naming the first missing one."""
        out = []
        for k in keys:
            val = self.v.get(k)
            if val is None and self.d is not None and hasattr(self.d, k):
                val = getattr(self.d, k)
            if val is None or (isinstance(val, float) and not math.isfinite(val)):
                raise Skip(f"{k} missing")
            out.append(val)
        return out if len(out) > 1 else out[0]

    def get(self, k, default=None):
        try:
            return self.need(k)
        except Skip:
            return default

    def durability(self) -> tuple[float, float, float]:
        """``(theta_pp_deg, frequency_hz, duration_h)`` of the evaluator's applications (given or assumed)."""
        a = self.apps
        th, fr, du = (float(x[0]) for x in (a.theta_pp_deg, a.frequency_hz, a.duration_h))
        if not all(math.isfinite(x) for x in (th, fr, du)):
            raise Skip("durability test missing (peak-to-peak angle, frequency and duration, or an engine type)")
        return th, fr, du

    def axial(self) -> bool:
        if not self.v.get("axial_damping_present"):
            raise Skip("no axial damping: the step does not apply")
        return True

    def attributes(self) -> dict:
        """The design's catalog attributes (one row per table), as the evaluator reads them."""
        if "attrs" not in self.cache:
            if not self.r.parts or any(v is None for v in self.r.parts.values()):
                raise Skip("the result has no complete design (parts)")
            self.cache["attrs"] = space().design_attributes(self.r.parts)
        return self.cache["attrs"]

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
            raise Skip("the design has no sized cone spring")
        c = {k: float(self.v[k]) for k in keys}
        c["cone_spring_max_deflection_mm"] = float(self.v.get("cone_spring_max_deflection_mm") or math.nan)
        return c

    def plastic_history(self) -> dict:
        """The step 5 time histories kept by the evaluator (``result.curves["plastic_wear"]``)."""
        self.axial()
        c = (self.r.curves or {}).get("plastic_wear")
        want = ("time_h", "plastic_wear_total_mm", "cone_spring_force_n", "damping_nm")
        if not isinstance(c, dict) or not all(k in c for k in want):
            raise Skip("the result keeps no wear history (the durability test is missing, or the result "
                        "was verified without time points)")
        h = {k: np.asarray(c[k], float).reshape(-1) for k in want}
        h["damper_pad_wear_eol_mm"] = float(self.need("damper_pad_wear_mm"))
        h["endcap_spacer_wear_eol_mm"] = float(self.need("endcap_spacer_wear_mm"))
        return h


# ------------------------------------------------------------------------------------------ drawing helpers
def new_figure(title: str):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(6.4, 4.0), dpi=100)
    ax.set_title(title, fontsize=11)
    ax.grid(True, alpha=0.3)
    return fig, ax


def png_bytes(fig) -> bytes:
    import matplotlib.pyplot as plt
    buf = io.BytesIO()
    fig.tight_layout()
    fig.savefig(buf, format="png")
    plt.close(fig)
    return buf.getvalue()
