"""Applications as arrays: the inputs of N validated design inputs, with the applications axis.

:class:`Applications` turns a list of :class:`~synth.schema.DesignInput` into
one float array per numeric field (NaN where not given), integer codes for
the categorical fields, the documented defaults of the optional inputs that
have one (:data:`DEFAULTS`, with a mask of where they were assumed), the
quantities that follow from the inputs alone (hubload, layout, pulley width,
durability test, friction) and a mask per named requirement of
:data:`synth.design.constraints.REQUIREMENTS`. Every consumer (flowchart,
optimiser, bulk) builds its applications here, so every optional input
reaches every consumer the same way. One application is ``N = 1``.

>>> from synth.data import case_path
>>> from synth.io.documents import load_input
>>> a = Applications.of([load_input(case_path("case1_as_run"))])
>>> round(float(a.hubload_nominal_n[0]), 1), bool(a.layout_standard[0]), bool(a.met("durability")[0])
(652.5, True, True)
>>> a.assumed_note("arm_travel_nominal_to_installation_deg", 0)
'arm_travel_nominal_to_installation_deg = 50 deg assumed (constant main_spring_dtheta_inst_nom_deg)'
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from synth import catalog, parts
from synth.design.constraints import REQUIREMENTS
from synth.model import damping, layout
from synth.schema import FIELDS
from synth.errors import InputError, Problem

__all__ = ["Applications", "DEFAULTS", "NUMERIC_FIELDS"]

#: optional input -> the named constant that is its documented default (used, and said so, when not given)
DEFAULTS = {
    "arm_travel_nominal_to_installation_deg": "main_spring_dtheta_inst_nom_deg",
    "arm_travel_nominal_to_free_deg": "main_spring_dtheta_nom_free_arm_deg",
    "spring_torque_tolerance_pct": "main_spring_torque_tolerance_default_pct",
    "middle_plane_belt_height_increment_worst_mm": "belt_height_increment_default_mm",
    "min_belt_crankcase_clearance_mm": "reverse_layout_min_crankcase_clearance_mm",
}

#: durability input -> its value after the assumed test (engine type) is applied
_DURABILITY = {"durability_theta_peak_to_peak_deg": "theta_pp_deg", "durability_frequency_hz": "frequency_hz",
               "durability_duration_h": "duration_h"}

NUMERIC_FIELDS = tuple(f.name for f in FIELDS if f.kind in ("float", "int") and not f.choices and not f.catalog) + tuple(
    n for n in DEFAULTS if n not in {f.name for f in FIELDS})


def _units() -> dict:
    return {f.name: f.unit for f in FIELDS}


@dataclass
class Applications:
    """N applications as arrays (see the module docstring). Attribute access reads a numeric field's array."""

    inputs: list
    f: dict                     # numeric field -> (n,) float, NaN where not given (defaults applied)
    given: dict                 # numeric field -> (n,) bool: the user gave it
    env: np.ndarray             # (n,) application type codes (parts.ENVIRONMENTS)
    fuel: np.ndarray            # (n,) engine fuel codes (parts.FUELS)
    derived: dict = field(default_factory=dict)

    @classmethod
    def of(cls, inputs) -> "Applications":
        """The applications of a list of validated design inputs."""
        inputs = list(inputs)
        f, given = {}, {}
        for name in NUMERIC_FIELDS:
            raw = [getattr(d, name, None) for d in inputs]
            given[name] = np.array([v is not None for v in raw], dtype=bool)
            f[name] = np.array([np.nan if v is None else float(v) for v in raw], dtype=float)
            if name in DEFAULTS:
                f[name] = np.where(given[name], f[name], catalog.constant(DEFAULTS[name]))
        env = parts.env_code([d.application_type for d in inputs]) if inputs else np.zeros(0, np.int64)
        fuel = parts.fuel_code([d.engine_fuel for d in inputs]) if inputs else np.zeros(0, np.int64)
        a = cls(inputs, f, given, env, fuel)
        a._derive()
        return a

    def __len__(self) -> int:
        return len(self.inputs)

    def __getattr__(self, item):
        f = self.__dict__.get("f", {})
        if item in f:
            return f[item]
        d = self.__dict__.get("derived", {})
        if item in d:
            return d[item]
        raise AttributeError(item)

    def text(self, name: str) -> np.ndarray:
        """A categorical field as an object array (None where not given)."""
        return np.array([getattr(d, name, None) for d in self.inputs], dtype=object)

    def subset(self, idx) -> "Applications":
        """The applications ``idx`` (an index array) as a new :class:`Applications`."""
        idx = np.asarray(idx, dtype=np.int64)
        inputs = self.inputs * len(idx) if len(self.inputs) == 1 else [self.inputs[i] for i in idx]
        a = Applications(inputs, {k: v[idx] for k, v in self.f.items()},
                         {k: v[idx] for k, v in self.given.items()}, self.env[idx], self.fuel[idx])
        a.derived = {k: v[idx] for k, v in self.derived.items()}
        return a

    def with_fields(self, rows, **fields) -> "Applications":
        """The applications ``rows`` (an index array) with numeric fields replaced by arrays over the rows, and
        what follows from the inputs alone re-derived (hubload, layout, pulley width): a production-scatter
        sample (:mod:`synth.robust`) is one application per sample row.

        >>> from synth.data import case_path
        >>> from synth.io.documents import load_input
        >>> a = Applications.of([load_input(case_path("case3"))]).with_fields([0, 0], working_arm_mm=[4.0, 8.0])
        >>> a.hubload_nominal_n.round(1).tolist()
        [462.5, 231.2]
        """
        a = self.subset(rows)
        n = len(a)
        for k, v in fields.items():
            if k not in a.f:
                raise InputError(Problem("field", k, "a numeric input field"))
            a.f[k] = np.broadcast_to(np.asarray(v, dtype=float), (n,)).copy()
        a._derive_numeric()
        return a

    def _derive_numeric(self) -> None:
        """The quantities that follow from the numeric fields alone."""
        f, d = self.f, self.derived
        d["hubload_nominal_n"] = damping.hubload_nominal_n(f["calculated_torque_target_nm"], f["working_arm_mm"],
                                                      f["differential_angle_deg"])
        # eq. (17)-(18); with no axial limit (N/A) the layout is reverse (synth.model.layout.layout_of)
        d["layout_standard"] = np.atleast_1d(layout.layout_of(f["middle_plane_belt_height_mm"],
                                                          f["max_axial_displacement_mm"]) == "standard")
        d["layout_reverse"] = ~d["layout_standard"]
        d["pulley_width_mm"] = layout.pulley_width_mm(f["belt_width_mm"])

    def _derive(self) -> None:
        f, p = self.f, parts.arrays()
        n = len(self.inputs)
        d = self.derived
        self._derive_numeric()
        d["mu_pivot_bushing"] = parts.mu("pivot_bushing", self.env) if n else np.zeros(0)
        # the fixation's interfaces (eq. (99), (101)): per application, so that a production-scatter sample
        # (synth.robust) can give each row its own friction
        for key, interface in (("mu_crankcase", "pivot_base_crankcase"), ("mu_thread", "thread"),
                               ("mu_head", "under_head")):
            d[key] = np.asarray(parts.mu(interface, self.env), dtype=float) if n else np.zeros(0)
        d["mu_plastic"] = p.plastic["mu"][self.env]
        d["k_wear_plastic_mm3_per_n_m"] = p.plastic["k_wear_mm3_per_n_m"][self.env]
        typ = self.text("damping_typology")
        d["axial_allowed"] = np.array([t != "only_radial" for t in typ], dtype=bool)
        d["damping_target_or_zero_nm"] = np.where(self.given["damping_target_nm"], f["damping_target_nm"], 0.0)
        d["single_eccentric"] = np.array([t == "single_eccentric" for t in self.text("belt_loading_type")], bool)
        # the durability test: given, or assumed from the engine type
        th, fr, du = (f[k].copy() for k in ("durability_theta_peak_to_peak_deg", "durability_frequency_hz",
                                              "durability_duration_h"))
        for i, dd in enumerate(self.inputs):
            if getattr(dd, "durability_test", None) == "assumed" and getattr(dd, "engine_type", None):
                r = p.durability.code(dd.engine_type, "engine_type")
                th[i], fr[i], du[i] = (p.durability.cols[k][r] for k in ("theta_peak_to_peak_deg", "frequency_hz",
                                                                          "duration_h"))
        d["theta_pp_deg"], d["frequency_hz"], d["duration_h"] = th, fr, du
        d["durability_given"] = np.isfinite(th) & np.isfinite(fr) & np.isfinite(du)

    def met(self, requirement: str) -> np.ndarray:
        """``(n,)`` bool: the requirement (a named one of REQUIREMENTS, or an input field) is given."""
        if requirement == "durability":
            return self.derived["durability_given"]
        names = REQUIREMENTS[requirement][0] if requirement in REQUIREMENTS else (requirement,)
        ok = np.ones(len(self), dtype=bool)
        for n in names:
            ok &= self.given[n] if n in self.given else np.array([getattr(d, n, None) is not None for d in self.inputs])
        return ok

    def missing_note(self, requirement: str, i: int = 0) -> str:
        """``"not verified: <field>, <field> missing (<what>)"``: the input fields of a requirement that
        application ``i`` left out, with the readable name of the requirement (REQUIREMENTS).

        >>> from synth.data import case_path
        >>> from synth.io.documents import load_input
        >>> import dataclasses
        >>> d = dataclasses.replace(load_input(case_path("case1_as_run")), tilting_safety_factor=None)
        >>> Applications.of([d]).missing_note("fixation")
        'not verified: tilting_safety_factor missing (fixation data)'
        """
        if requirement not in REQUIREMENTS:
            return f"not verified: {requirement} missing"
        names, what = REQUIREMENTS[requirement]
        left_out = [n for n in names if not (self.given[n][i] if n in self.given
                                             else getattr(self.inputs[i], n, None) is not None)]
        if requirement == "durability":
            left_out = [n for n in left_out if not np.isfinite(self.derived[_DURABILITY[n]][i])]
        return f"not verified: {', '.join(left_out) or requirement} missing ({what})"

    def assumed(self, name: str) -> np.ndarray:
        """``(n,)`` bool: the optional input ``name`` was not given and its documented default is used."""
        return ~self.given[name] if name in DEFAULTS else np.zeros(len(self), dtype=bool)

    def assumed_note(self, name: str, i: int) -> str:
        """``"<field> = <value> <unit> assumed (constant <name>)"`` for application ``i``."""
        unit = _units().get(name, "")
        return f"{name} = {self.f[name][i]:g} {unit} assumed (constant {DEFAULTS[name]})".replace("  ", " ")
