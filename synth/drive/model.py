"""The validated drive: its pulleys (in the belt's travel order), the automatic tensioner as the drive sees it, the
crank's orders of angular fluctuation and the duty cycle's points; a :class:`Drive` is what every analysis of
:mod:`synth.drive` reads and what :func:`synth.drive.inputs.validate` makes of a drive file (:meth:`Drive.to_dict`
writes one back).
"""

from __future__ import annotations

from dataclasses import asdict, dataclass, replace

from synth.drive import belt as belt_data
from synth.drive.positions import frame_of, loading_sense

__all__ = ["Pulley", "Tensioner", "Order", "DutyPoint", "Drive"]


@dataclass(frozen=True)
class Pulley:
    """A pulley of the drive (lengths mm, inertia kg m^2, torques N m); ``radius_mm`` is the pitch radius,
    ``effective_radius_mm`` the effective one (None: the pitch radius)."""

    name: str
    role: str
    x_mm: float
    y_mm: float
    radius_mm: float
    inertia_kg_m2: float | None
    load_torque_nm: float = 0.0
    damping_nm_s_per_rad: float = 0.0
    backside: bool = False
    torque_order: float = 0.0
    torque_amplitude_nm: float = 0.0
    torque_phase_deg: float = 0.0
    effective_radius_mm: float | None = None


@dataclass(frozen=True)
class Tensioner:
    """The automatic tensioner as the drive sees it: pivot, arm, inertia, spring, nominal torque, friction.

    ``arm_angle_deg`` and ``nominal_torque_nm`` are the nominal position, stated or derived (``nominal_from``:
    ``angle``, ``torque`` or ``belt``); ``preload_nm`` is the spring's torque at ``free_arm_angle_deg``.
    """

    pivot_x_mm: float
    pivot_y_mm: float
    arm_length_mm: float
    arm_angle_deg: float
    inertia_kg_m2: float | None
    stiffness_nm_per_deg: float
    nominal_torque_nm: float
    friction_torque_nm: float | None
    damping_nm_s_per_rad: float = 0.0
    free_arm_angle_deg: float | None = None
    preload_nm: float | None = None
    installation_angle_deg: float | None = None
    pulley_mass_kg: float = 0.0
    nominal_from: str = "angle"

    @property
    def arm_inertia_kg_m2(self) -> float | None:
        """The arm's inertia about the pivot with its pulley's mass [kg m^2]."""
        if self.inertia_kg_m2 is None:
            return None
        return self.inertia_kg_m2 + self.pulley_mass_kg * (self.arm_length_mm / 1000.0) ** 2


@dataclass(frozen=True)
class Order:
    """One order of the crank's angular fluctuation: ``A cos(n Omega t + phase)``."""

    order: float
    amplitude_deg: float
    phase_deg: float = 0.0


@dataclass(frozen=True)
class DutyPoint:
    """One point of a duty cycle: engine speed [rpm], share of time [%] and the pulleys' loads, as
    ``((name, kW), ...)`` and ``((name, N m), ...)``."""

    speed_rpm: float
    time_pct: float | None = None
    power_kw: tuple = ()
    torque_nm: tuple = ()


@dataclass(frozen=True)
class Drive:
    """A validated drive (hashable: it can sit in :class:`synth.design.evaluate.Settings`)."""

    name: str
    pulleys: tuple
    tensioner: Tensioner
    belt_stiffness_n: float
    belt_damping_n_s: float
    orders: tuple
    speed_min_rpm: float | None
    speed_max_rpm: float | None
    speeds: int = 50
    durability_speed_rpm: float | None = None
    belt_min_tension_n: float = 0.0
    belt_friction_coefficient: float | None = None
    harmonics: int = 24
    regularisation: float = 0.01
    tolerance: float = 0.05
    belt_ribs: int | None = None
    belt_length_mm: float | None = None
    belt_length_tolerance_mm: float = 0.0
    belt_wear_pct: float = 0.0
    belt_thermal_change_pct: float = 0.0
    belt_elongation_stiffness_per_rib_n: float = belt_data.ELONGATION_EA_PER_RIB_N
    belt_measuring_tension_per_rib_n: float = belt_data.MEASURING_TENSION_PER_RIB_N
    duty: tuple = ()
    belt_stiffness_per_rib_n: float | None = None   # given per rib (EA = ribs x it), or None: stiffness_n given

    @property
    def crank_index(self) -> int:
        return next(i for i, p in enumerate(self.pulleys) if p.role == "crank")

    @property
    def tensioner_index(self) -> int:
        return next(i for i, p in enumerate(self.pulleys) if p.role == "tensioner")

    @property
    def dynamic(self) -> bool:
        """The drive states an excitation: the arm's periodic response can be solved."""
        return bool(self.orders) or any(p.torque_amplitude_nm > 0 for p in self.pulleys)

    @property
    def loading_sense(self) -> float:
        """``+1`` when the belt pushes the arm counter-clockwise at its nominal angle."""
        return loading_sense(frame_of(self), self.tensioner.arm_angle_deg)

    def speeds_rpm(self):
        import numpy as np
        return np.linspace(self.speed_min_rpm, self.speed_max_rpm, self.speeds)

    def with_tensioner(self, **changes) -> "Drive":
        """A copy with some tensioner values changed (the synthesised design's). The nominal arm angle stays;
        a spring changed there moves the free-arm preload with it (``preload = M_nom - k rel``)."""
        ten = replace(self.tensioner, **changes, nominal_from="angle")
        if ten.free_arm_angle_deg is not None:
            rel = abs((ten.arm_angle_deg - ten.free_arm_angle_deg + 180.0) % 360.0 - 180.0)
            ten = replace(ten, preload_nm=ten.nominal_torque_nm - ten.stiffness_nm_per_deg * rel)
        return replace(self, tensioner=ten)

    def to_dict(self) -> dict:
        """The drive as a drive-file mapping (:func:`validate` reads it back)."""
        t = {k: v for k, v in asdict(self.tensioner).items() if v is not None and k != "nominal_from"}
        if self.tensioner.nominal_from != "angle":
            t.pop("arm_angle_deg")
        else:
            t.pop("preload_nm", None)
        if self.tensioner.nominal_from == "belt":
            t.pop("nominal_torque_nm")
        belt = ({"stiffness_n": self.belt_stiffness_n} if self.belt_stiffness_per_rib_n is None else
                {"stiffness_per_rib_n": self.belt_stiffness_per_rib_n})
        belt.update({"damping_n_s": self.belt_damping_n_s, "min_tension_n": self.belt_min_tension_n,
                     "length_tolerance_mm": self.belt_length_tolerance_mm, "wear_pct": self.belt_wear_pct,
                     "thermal_change_pct": self.belt_thermal_change_pct,
                     "elongation_stiffness_per_rib_n": self.belt_elongation_stiffness_per_rib_n,
                     "measuring_tension_per_rib_n": self.belt_measuring_tension_per_rib_n})
        for key, value in (("ribs", self.belt_ribs), ("length_mm", self.belt_length_mm),
                           ("friction_coefficient", self.belt_friction_coefficient)):
            if value is not None:
                belt[key] = value
        out = {"name": self.name, "belt": belt, "pulleys": [_pulley_dict(p) for p in self.pulleys], "tensioner": t,
               "solver": {"harmonics": self.harmonics, "regularisation": self.regularisation,
                          "tolerance": self.tolerance}}
        if self.orders:
            out["excitation"] = {"speed_min_rpm": self.speed_min_rpm, "speed_max_rpm": self.speed_max_rpm,
                                 "speeds": self.speeds, "orders": [asdict(o) for o in self.orders]}
            if self.durability_speed_rpm is not None:
                out["excitation"]["durability_speed_rpm"] = self.durability_speed_rpm
        if self.duty:
            out["duty"] = [{"speed_rpm": p.speed_rpm, **({"time_pct": p.time_pct} if p.time_pct is not None else {}),
                            **({"power_kw": dict(p.power_kw)} if p.power_kw else {}),
                            **({"torque_nm": dict(p.torque_nm)} if p.torque_nm else {})} for p in self.duty]
        return out


def _pulley_dict(p: Pulley) -> dict:
    out = {k: v for k, v in asdict(p).items() if v is not None}
    out["backside"] = "true" if p.backside else "false"
    if "effective_radius_mm" in out:
        out["effective_diameter_mm"] = 2.0 * out.pop("effective_radius_mm")
    if p.torque_amplitude_nm == 0:
        for k in ("torque_order", "torque_amplitude_nm", "torque_phase_deg"):
            out.pop(k)
    if p.role == "tensioner":
        out.pop("x_mm"), out.pop("y_mm")
    return out
