"""Generated applications spanning the design-input ranges (for benchmarks, solver agreement and bulk runs).

:func:`generate` draws ``n`` validated :class:`~synth.schema.DesignInput`
from a seeded random generator: two thesis families (belt-in-oil with
axial damping like case 1, dry with radial damping only like case 3) and,
within each, the application inputs drawn uniformly over engineering ranges
(working arm 2.5-5 mm, differential angle 70-110 deg, calculated torque
1.5-4 N m (2.5-3.5 with axial damping), damping target 25-40 % of it (45-60 % with axial damping), spring stiffness 0.012-0.04 N m/deg,
belt width 16-30 mm, belt plane 18-30 mm with the space constraints following
it, safety-factor targets 2-3.5...). Part choices (pivot class, bushing wall,
spring, bolt) are left to the optimiser. The same seed gives the same list.

>>> apps = generate(5, seed=1)
>>> len(apps), apps[0].application_type in ("dry", "belt_in_oil")
(5, True)
"""

from __future__ import annotations

import numpy as np

from synth.schema import validate

__all__ = ["generate", "RANGES"]

#: input -> (low, high) of the uniform draw
RANGES = {
    "working_arm_mm": (2.5, 5.0),
    "differential_angle_deg": (70.0, 110.0),
    "calculated_torque_target_nm": (1.5, 4.0),
    "calculated_torque_target_oil_nm": (2.5, 3.5),
    "damping_fraction": (0.45, 0.6),
    "damping_fraction_radial": (0.25, 0.4),
    "damping_tolerance_fraction": (0.3, 0.45),
    "spring_stiffness_nm_per_deg": (0.02, 0.045),
    "spring_torque_tolerance_pct": (3.0, 8.0),
    "belt_width_mm": (16.0, 30.0),
    "middle_plane_belt_height_mm": (24.0, 32.0),
    "pivot_height_allowance_mm": (10.0, 16.0),
    "axial_allowance_mm": (1.0, 6.0),
    "pulley_diameter_mm": (55.0, 75.0),
    "safety_factor": (2.0, 2.8),
    "engine_support_external_diameter_mm": (22.0, 30.0),
    "bolt_head_contact_external_diameter_mm": (13.0, 15.0),
    "durability_duration_h": (400.0, 1500.0),
}


def _u(rng, name):
    lo, hi = RANGES[name]
    return float(rng.uniform(lo, hi))


#: optional inputs :func:`generate` may leave out (``vary=True``), each with probability ``DROP``
OPTIONAL = ("pulley_max_parallelism_eol_mm", "loading_arm_mm", "middle_plane_belt_height_increment_worst_mm",
            "damping_tolerance_nm", "damping_eol_limit_nm", "spring_torque_tolerance_pct",
            "arm_travel_nominal_to_installation_deg", "arm_travel_nominal_to_free_deg",
            "contact_angle_deg", "bolt_head_contact_external_diameter_mm", "number_of_active_threads",
            "wrap_angle_deg", "lockup_pin")
DROP = 0.3


def _vary(raw: dict, rng) -> dict:
    """A variant of ``raw`` across the schema's choices: optional inputs left out, the travels, the lock-up pin,
    single eccentric, only radial damping, an assumed durability test, wide ranges."""
    raw = dict(raw)
    raw["arm_travel_nominal_to_installation_deg"] = float(rng.uniform(15.0, 70.0))
    raw["arm_travel_nominal_to_free_deg"] = float(rng.uniform(10.0, 45.0))
    raw.update(wrap_angle_deg=float(rng.uniform(40.0, 160.0)), nominal_arm_angle_from_EHR_deg=float(rng.uniform(-180, 180)),
               lockup_pin_position_radius_mm=float(rng.uniform(25.0, 50.0)),
               lockup_pin_angular_position_deg=float(rng.uniform(-180, 180)), lockup_pin_diameter_mm=4.0)
    for name in OPTIONAL:
        if rng.uniform() < DROP:
            if name == "lockup_pin":
                for k in ("lockup_pin_position_radius_mm", "lockup_pin_angular_position_deg", "lockup_pin_diameter_mm"):
                    raw.pop(k, None)
            elif name == "damping_eol_limit_nm" or name == "damping_tolerance_nm":
                raw.pop(name, None)
            else:
                raw.pop(name, None)
    r = rng.uniform()
    if r < 0.1:
        raw.update(belt_loading_type="single_eccentric")
        raw.pop("loading_arm_mm", None)
    if rng.uniform() < 0.15:
        raw["damping_typology"] = "only_radial"
    if rng.uniform() < 0.15:
        for k in ("durability_theta_peak_to_peak_deg", "durability_frequency_hz", "durability_duration_h"):
            raw.pop(k, None)
        if rng.uniform() < 0.5:
            raw.update(durability_test="assumed", engine_type=str(rng.choice(["gasoline", "diesel"])))
    if rng.uniform() < 0.1:
        raw["working_arm_mm"] = round(float(rng.uniform(2.0, 7.5)), 1)
    if rng.uniform() < 0.1:
        raw["differential_angle_deg"] = float(rng.uniform(20.0, 160.0))
    return raw


def generate(n: int = 50, seed: int = 0, *, vary: bool = False) -> list:
    """``n`` generated design inputs (validated), alternating the oil/axial and dry/radial families.

    ``vary=True`` also spreads the choices and leaves optional inputs out (:func:`_vary`): every optional
    input present and absent, for the tests that compare every path of the evaluator.
    """
    rng = np.random.default_rng(seed)
    out = []
    for i in range(n):
        oil = i % 2 == 0
        t_c = _u(rng, "calculated_torque_target_nm" if not oil else "calculated_torque_target_oil_nm")
        damping = t_c * _u(rng, "damping_fraction" if oil else "damping_fraction_radial")
        mpbh = _u(rng, "middle_plane_belt_height_mm")
        belt = _u(rng, "belt_width_mm")
        sf = _u(rng, "safety_factor")
        raw = {
            "application_type": "belt_in_oil" if oil else "dry",
            "engine_fuel": "gasoline" if rng.uniform() < 0.5 else "diesel",
            "pulley_shell_type": "toothed" if oil else "flat",
            "pulley_diameter_mm": _u(rng, "pulley_diameter_mm"),
            "pulley_max_parallelism_eol_mm": 0.3 if oil else 0.5,
            "belt_loading_type": "double_eccentric",
            "working_arm_mm": round(_u(rng, "working_arm_mm"), 1),
            "loading_arm_mm": 2.0,
            "differential_angle_deg": _u(rng, "differential_angle_deg"),
            "belt_width_mm": belt,
            "middle_plane_belt_height_mm": mpbh,
            "middle_plane_belt_height_increment_worst_mm": 2.0,
            "max_pivot_height_mm": mpbh + _u(rng, "pivot_height_allowance_mm"),
            "max_axial_displacement_mm": mpbh + (belt + 4.0) / 2 + _u(rng, "axial_allowance_mm"),
            "durability_theta_peak_to_peak_deg": 16.0,
            "durability_frequency_hz": 50.0,
            "durability_duration_h": _u(rng, "durability_duration_h"),
            "calculated_torque_target_nm": t_c,
            "damping_target_nm": damping,
            "damping_tolerance_nm": max(damping * _u(rng, "damping_tolerance_fraction"), 0.15),
            "damping_eol_limit_nm": 0.75 * damping,
            "spring_stiffness_nm_per_deg": _u(rng, "spring_stiffness_nm_per_deg"),
            "spring_torque_tolerance_pct": _u(rng, "spring_torque_tolerance_pct"),
            "tilting_safety_factor": sf,
            "sliding_safety_factor": sf,
            "engine_support_internal_diameter_mm": 8.2,
            "engine_support_external_diameter_mm": _u(rng, "engine_support_external_diameter_mm"),
            "contact_angle_deg": 360.0,
            "bolt_head_contact_external_diameter_mm": _u(rng, "bolt_head_contact_external_diameter_mm"),
            "number_of_active_threads": 2.6,
            "support_yield_strength_compression_mpa": 400.0,
            "support_yield_strength_traction_mpa": 400.0,
        }
        if vary:
            raw = _vary(raw, rng)
            if raw.get("damping_eol_limit_nm") is not None and raw.get("damping_target_nm") is not None:
                raw["damping_eol_limit_nm"] = min(raw["damping_eol_limit_nm"], raw["damping_target_nm"])
        out.append(validate(raw))
    return out
