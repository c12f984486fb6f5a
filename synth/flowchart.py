"""The thesis design flowchart (steps 0-10), run in the thesis's order.

:func:`run` walks the steps with the thesis's iterations (lengthen the
bushing, enlarge the damper-pad class, escalate bolt format and class, search
the spring catalog in automatic mode). Each step reads the physics functions of
:mod:`synth.model` (the same ones the optimisers use) and adds

* values to ``result.values`` (flat dict; the keys of the case files'
  ``thesis_tool:`` block, same names and units, plus more);
* :class:`~synth.checks.Check` records to ``result.checks`` (verdict, margin,
  suggested correction, or "not verified: <field> missing");
* notes (decisions, skipped steps) to ``result.notes``.

Steps a case does not need are not run (no axial damping: no cone spring, no
plastic wear, no stack-up).

>>> from synth.scenes.demo import default_input
>>> r = run(default_input())
>>> r.values["architecture"], r.values["ball_bearing"]
('rotary_standard', '6006')
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any, Callable

import numpy as np

from synth import catalog
from synth.checks import FAIL, NOT_VERIFIED, PASS, Check
from synth.friction import mu as friction_mu
from synth.model import layout as s0, ball_bearing as s1, pivot as s2, damping as s3
from synth.model import plain_bushing as s4, friction_wear as s5, stackup as s6
from synth.model import packaging as s7, disc_spring as s8, torsion_spring as s9
from synth.model import bolted_joint as s10

__all__ = ["Settings", "FlowchartResult", "run", "STEP_NAMES"]

STEP_NAMES = {
    0: "Execution selection", 1: "Ball bearing", 2: "Pivot diameter", 3: "Damping", 4: "Pivot bushing",
    5: "Plastic element wear", 6: "Axial stack-up", 7: "Packaging", 8: "Cone spring", 9: "Main spring",
    10: "Tilting, sliding and bolt",
}


@dataclass(frozen=True)
class Settings:
    """Model settings (speed against accuracy, and conventions).

    * ``fidelity``: ``"full"`` (time-integrated wear, Almen-Laszlo cone spring)
      or ``"screening"`` (closed-form wear, linear cone spring).
    * ``friction_circle``: radial friction on ``r_p sin(atan(mu))`` (physics,
      default) or on ``r_p mu`` (the thesis tool's tables).
    * ``bushing_length_scheme``: ``"thesis"`` (the thesis tool's trial lengths,
      multiples of half the pivot diameter, then the next catalog length is
      reported as the part to buy) or ``"catalog"`` (the shortest catalog
      length that passes).
    * ``bushing_running_in``: integrate the running-in of the pivot clearance
      in the bushing wear (an extension with illustrative constants; off by
      default, the thesis's closed-form wear eq. (32) is used).
    """

    fidelity: str = "full"
    friction_circle: bool = True
    bushing_length_scheme: str = "thesis"
    bushing_running_in: bool = False

    def __post_init__(self):
        if self.fidelity not in ("full", "screening"):
            from synth.errors import InputError, Problem
            raise InputError(Problem("fidelity", self.fidelity, "one of full, screening"))


@dataclass
class FlowchartResult:
    """Outcome of one flowchart run."""

    inputs: Any
    settings: Settings
    values: dict = field(default_factory=dict)
    checks: list = field(default_factory=list)
    notes: list = field(default_factory=list)
    steps_run: list = field(default_factory=list)
    curves: dict = field(default_factory=dict)

    @property
    def verdict(self) -> str:
        """``fail`` if any check fails, else ``pass`` (not-verified checks are listed, not failed)."""
        return FAIL if any(c.verdict == FAIL for c in self.checks) else PASS

    def failed(self) -> list:
        return [c for c in self.checks if c.verdict == FAIL]

    @property
    def parts(self) -> dict | None:
        """The catalog choices of this run as the optimiser names them (:data:`PART_KEYS`), or None.

        None when the flowchart stopped before choosing every part (self-locking,
        no Table 2 class, a step not run). ``run(d, parts=result.parts)``
        re-verifies the same design.
        """
        v = self.values
        need = ("ball_bearing", "pivot_class_diameter_mm", "pivot_bushing_supplier", "pivot_bushing_length_mm",
                "main_spring_material", "main_spring_wire_section", "main_spring_mean_body_diameter_mm",
                "bolt_format", "bolt_property_class")
        if any(v.get(k) is None for k in need):
            return None
        axial = bool(v.get("axial_damping_present"))
        if axial and v.get("damper_pad_class") is None:
            return None
        return {"bearing": v["ball_bearing"], "pivot_class_mm": float(v["pivot_class_diameter_mm"]),
                "supplier": v["pivot_bushing_supplier"], "damper_pad": v["damper_pad_class"] if axial else "none",
                "bushing_length_mm": float(v["pivot_bushing_length_mm"]),
                "endcap_spacer": v["endcap_spacer_class"] if axial else "none",
                "cone_aspect_ratio": float(v.get("cone_aspect_ratio", 0.0)) if axial else 0.0,
                "spring_material": v["main_spring_material"],
                "spring_wire": _wire_designation(v["main_spring_wire_section"], v["main_spring_wire_size_mm"]),
                "spring_mbd_mm": float(v["main_spring_mean_body_diameter_mm"]),
                "bolt_format": v["bolt_format"], "bolt_property_class": v["bolt_property_class"]}

    def not_verified(self) -> list:
        return [c for c in self.checks if c.verdict == NOT_VERIFIED]

    def check(self, name: str) -> Check:
        for c in self.checks:
            if c.name == name:
                return c
        raise KeyError(name)

    def to_dict(self) -> dict:
        return {
            **{k: _plain(v) for k, v in self.values.items()},
            "verdict": self.verdict,
            "checks": [{k: _plain(v) for k, v in c.as_dict().items()} for c in self.checks],
            "notes": list(self.notes),
            "steps_run": list(self.steps_run),
            "settings": {"fidelity": self.settings.fidelity, "friction_circle": self.settings.friction_circle},
        }


def _plain(v):
    """JSON-friendly scalars: numpy to Python, non-finite floats to None."""
    if isinstance(v, np.ndarray):
        v = v.tolist() if v.ndim else v.item()
    if isinstance(v, (np.generic,)):
        v = v.item()
    if isinstance(v, list):
        return [_plain(x) for x in v]
    if isinstance(v, float) and not math.isfinite(v):
        return None
    return v


class _Ctx:
    """Mutable state of one run: the input, settings, and the growing result."""

    def __init__(self, d, settings: Settings):
        self.d, self.s = d, settings
        self.r = FlowchartResult(d, settings)
        self.v = self.r.values
        self.parts = None

    def check(self, name, step, value, limit, kind="<=", unit="", equation="", correction="", note=""):
        c = Check(name, step, None if value is None else float(value), None if limit is None else float(limit),
                  kind=kind, unit=unit, equation=equation, correction=correction, note=note)
        self.r.checks.append(c)
        return c

    def skip(self, name, step, missing, equation=""):
        self.r.checks.append(Check.skipped(name, step, missing, equation=equation))

    def note(self, text):
        self.r.notes.append(text)


def _f(x) -> float:
    return float(np.asarray(x, float).reshape(-1)[0])


# --- step 0 -------------------------------------------------------------------------------------

def _step0(c: _Ctx):
    d, v = c.d, c.v
    h_max = d.max_axial_displacement_mm
    standard = bool(s0.is_standard_layout(d.middle_plane_belt_height_mm, h_max))
    v["architecture"] = "rotary_standard" if standard else "rotary_reverse"
    v["pulley_type"] = d.pulley_shell_type
    v["pulley_width_mm"] = _f(s0.pulley_width_mm(d.belt_width_mm))
    w = v["pulley_width_mm"]
    if standard:
        c.check("pulley top within max axial displacement", 0, d.middle_plane_belt_height_mm + w / 2, h_max, "<=",
                "mm", "eq. (26)", correction=f"max_axial_displacement_mm >= {d.middle_plane_belt_height_mm + w / 2:.1f}")
    else:
        from synth.catalog import constant
        clr = constant("reverse_layout_min_crankcase_clearance_mm")
        c.check("pulley clear of crankcase (reverse)", 0, d.middle_plane_belt_height_mm - w / 2, clr, ">=", "mm",
                "eq. (27)", correction=f"middle_plane_belt_height_mm >= {clr + w / 2:.1f}")
    pin = ("lockup_pin_position_radius_mm", "lockup_pin_angular_position_deg", "lockup_pin_diameter_mm")
    missing = d.missing(*pin)
    if missing:
        c.skip("lock-up pin within pulley outline", 0, missing[0], "eq. (22)")
        c.skip("lock-up pin clearance to pulley and belt", 0, missing[0], "eq. (23)-(25)")
        return
    r_pin, phi, d_pin = (getattr(d, n) for n in pin)
    inner = r_pin - d_pin / 2
    c.check("lock-up pin within pulley outline", 0, inner, d.pulley_diameter_mm / 2, "<=", "mm", "eq. (22)")
    geo = d.missing("wrap_angle_deg", "nominal_arm_angle_from_EHR_deg")
    if geo:
        c.skip("lock-up pin clearance to pulley and belt", 0, geo[0], "eq. (23)-(25)")
        return
    hl_ehr = _f(s0.hubload_angle_from_ehr_deg(d.differential_angle_deg, d.nominal_arm_angle_from_EHR_deg))
    tp, tm = (_f(x) for x in s0.wrap_limits_deg(hl_ehr, d.wrap_angle_deg))
    v["hubload_angle_from_EHR_deg"], v["wrap_upper_limit_deg"], v["wrap_lower_limit_deg"] = hl_ehr, tp, tm
    zone = int(s0.pin_angular_zone(phi, tp, tm)[()])
    margin = _f(s0.pin_clearance_margin(r_pin, phi, d_pin, d.pulley_diameter_mm, tp, tm))
    from synth.catalog import constant
    if zone == 0:
        need = d.pulley_diameter_mm / 2 + constant("lockup_pin_pulley_clearance_mm")
        c.check("lock-up pin clearance to pulley and belt", 0, inner, need, ">=", "mm", "eq. (23)",
                correction=f"move the pin outside the wrap ({tm:.1f}..{tp:.1f} deg) or to a radius >= {need + d_pin / 2:.1f} mm",
                note="pin within the belt wrap angle")
    else:
        need = d_pin / 2 + constant("lockup_pin_belt_clearance_mm")
        c.check("lock-up pin clearance to pulley and belt", 0, need * (1 + margin), need, ">=", "mm",
                "eq. (24)" if zone > 0 else "eq. (25)", note="distance from the belt span")


# --- step 1 -------------------------------------------------------------------------------------

def _step1(c: _Ctx):
    d, v = c.d, c.v
    v["hubload_nominal_n"] = _f(s3.hubload_nominal_n(d.calculated_torque_target_nm, d.working_arm_mm,
                                                     d.differential_angle_deg))
    if c.parts:
        v["ball_bearing"] = str(c.parts["bearing"])
        limit = s1.max_hubload_n(v["ball_bearing"], d.engine_fuel)
        if limit is not None:
            c.check("hubload within the bearing's Table 1 range", 1, v["hubload_nominal_n"], limit, "<=", "N", "Table 1",
                    correction="a larger bearing")
    else:
        v["ball_bearing"] = str(s1.select_bearing(v["hubload_nominal_n"], d.engine_fuel)[0])
    v["bearing_inner_diameter_mm"] = _f(s1.bearing_inner_diameter_mm(v["ball_bearing"]))
    b = catalog.row("ball_bearings", v["ball_bearing"])
    v["bearing_outer_diameter_mm"], v["bearing_width_mm"] = float(b["D_mm"]), float(b["B_mm"])


# --- step 2 -------------------------------------------------------------------------------------

def _default_bushing_thickness_mm() -> float:
    df = catalog.load("pivot_bushings")
    return float(df["radial_thickness_mm"].astype(float).max())


def _step2(c: _Ctx):
    d, v = c.d, c.v
    bearing = v["ball_bearing"]
    from synth.errors import InputError
    try:
        std_class, max_la = s2.standard_pivot_class(bearing, d.working_arm_mm)
    except InputError as exc:
        arms = catalog.load("pivot_classes")
        arm_max = float(arms[arms["bearing"].astype(str) == bearing]["working_arm_mm"].max())
        c.check(f"working arm within Table 2 for bearing {bearing}", 2, d.working_arm_mm, arm_max, "<=", "mm", "Table 2",
                correction=f"working_arm_mm <= {arm_max:g}, or a lower hubload (bearing chosen by Table 1)",
                note=str(exc.problems[0]))
        c.note("step 2 has no pivot class for this bearing and working arm; later steps are not run")
        return False
    v["pivot_class_standard_mm"], v["loading_arm_max_mm"] = std_class, max_la
    if d.pivot_class_diameter_mm is None:
        pivot_class = std_class
        c.note(f"pivot class: Table 2 standard {std_class:g} mm (bearing {bearing}, working arm {d.working_arm_mm:g} mm)")
    else:
        pivot_class = d.pivot_class_diameter_mm
        if pivot_class > std_class:
            c.note(f"pivot class {pivot_class:g} mm is custom and above Table 2's standard {std_class:g} mm; "
                   "the arm-wall check decides")
    v["pivot_class_diameter_mm"] = pivot_class
    if d.belt_loading_type == "single_eccentric":
        loading_arm = 0.0
    else:
        loading_arm = max_la if d.loading_arm_mm is None else d.loading_arm_mm
        c.check("loading arm within Table 2", 2, loading_arm, max_la, "<=", "mm", "Table 2",
                correction=f"loading_arm_mm <= {max_la:g}")
    v["loading_arm_mm"] = loading_arm
    t_b = d.pivot_bushing_radial_thickness_mm
    if t_b is None:
        t_b = _default_bushing_thickness_mm()
        c.note(f"pivot bushing radial thickness not given: {t_b:g} mm assumed")
    v["pivot_bushing_radial_thickness_mm"] = t_b
    v["pivot_diameter_mm"] = _f(s2.pivot_diameter_mm(pivot_class, t_b))
    wall = _f(s2.arm_wall_mm(v["bearing_inner_diameter_mm"], d.working_arm_mm, pivot_class))
    from synth.catalog import constant
    c.check("arm wall on the eccentric side", 2, wall, constant("arm_min_wall_mm"), ">=", "mm", "step 2",
            correction=f"pivot_class_diameter_mm <= {_f(s2.max_pivot_class_for_wall_mm(v['bearing_inner_diameter_mm'], d.working_arm_mm)):g}")


# --- step 3 -------------------------------------------------------------------------------------

def _step3(c: _Ctx):
    d, v, s = c.d, c.v, c.s
    mu_pb = friction_mu("pivot_bushing", d.application_type)
    v["mu_pivot_bushing"] = mu_pb
    rho = _f(s3.lever_ratio(v["pivot_diameter_mm"], mu_pb, d.working_arm_mm, d.differential_angle_deg,
                            s.friction_circle))
    v["lever_ratio"] = rho
    lock = c.check("arm free to move (no self-locking)", 3, rho, 1.0, "<=", "-", "eq. (12)",
                   correction="a smaller pivot, a larger working arm, or a differential angle nearer 90 deg")
    if lock.verdict == FAIL:
        c.note("the arm self-locks: the friction circle exceeds the lever; later steps are not run")
        return False
    target = d.damping_target_nm if d.damping_target_nm is not None else 0.0
    axial_allowed = d.damping_typology != "only_radial"
    split = s3.damping_split(d.calculated_torque_target_nm, target, rho, axial_allowed)
    for k in ("radial_damping_nm", "axial_damping_nm", "spring_torque_nominal_nm", "damping_nm"):
        v[k] = _f(split[k])
    v["axial_damping_present"] = bool(np.asarray(split["axial_damping_present"]).reshape(-1)[0])
    if not v["axial_damping_present"]:
        v["axial_damping_nm"] = None
    if d.damping_target_nm is not None and d.damping_tolerance_nm is not None:
        tol = d.damping_tolerance_nm
        c.check("damping within upper tolerance", 3, v["damping_nm"], d.damping_target_nm + tol, "<=", "Nm",
                "eq. (10)-(11)", correction="a smaller pivot diameter or a lower-friction bushing (radial damping above target)")
        c.check("damping within lower tolerance", 3, v["damping_nm"], d.damping_target_nm - tol, ">=", "Nm",
                "eq. (9)-(11)", correction="damping_typology radial_and_axial (add the axial damping group)")
    elif d.damping_tolerance_nm is None:
        c.skip("damping within tolerance", 3, "damping_tolerance_nm", "eq. (11)")
    c.check("spring torque positive", 3, v["spring_torque_nominal_nm"], 0.0, ">=", "Nm", "eq. (12)-(13)")
    ch = s3.characterisation(v["spring_torque_nominal_nm"], d.spring_stiffness_nm_per_deg, v["axial_damping_nm"] or 0.0,
                             d.working_arm_mm, d.differential_angle_deg, v["pivot_diameter_mm"], mu_pb,
                             np.array([0.0]), s.friction_circle)
    v["hubload_loading_n"] = _f(ch["hubload_loading_n"])
    v["hubload_unloading_n"] = _f(ch["hubload_unloading_n"])
    v["asymmetry_ratio"] = _f(ch["asymmetry_ratio"])
    return True


# --- durability test (defined or assumed) -----------------------------------------------------

def _durability(c: _Ctx):
    """``(theta_pp_deg, frequency_hz, duration_h)`` or None (then the wear checks are not verified)."""
    d = c.d
    if d.durability_test == "assumed":
        row = catalog.row("durability_tests", d.engine_type, field="engine_type")
        out = (float(row["theta_peak_to_peak_deg"]), float(row["frequency_hz"]), float(row["duration_h"]))
        c.note(f"durability test assumed for engine type {d.engine_type}: {out[0]:g} deg p-p, {out[1]:g} Hz, "
               f"{out[2]:g} h ({row['source']})")
        return out
    names = ("durability_theta_peak_to_peak_deg", "durability_frequency_hz", "durability_duration_h")
    missing = d.missing(*names)
    if missing:
        return missing[0]
    return tuple(float(getattr(d, n)) for n in names)


# --- step 4 -------------------------------------------------------------------------------------

def _step4(c: _Ctx):
    d, v, s = c.d, c.v, c.s
    dur = _durability(c)
    c.durability = dur
    if isinstance(dur, str):
        for name in ("pivot bushing pressure", "pivot bushing p*v", "pivot bushing p*v*t",
                     "pivot bushing wear (most loaded end) vs sliding layer", "pulley parallelism at end of life"):
            c.skip(name, 4, dur, "eq. (28)-(42)")
        c.note(f"step 4 not run: {dur} missing (the bushing length needs the durability test)")
        return
    par_max = d.pulley_max_parallelism_eol_mm
    if c.parts:
        supplier = str(c.parts["supplier"])
        r = dict(s4.evaluate_bushing(
            v["hubload_nominal_n"], v["pivot_diameter_mm"], float(c.parts["bushing_length_mm"]), *dur, supplier=supplier,
            environment=d.application_type, belt_plane_height_mm=d.middle_plane_belt_height_mm,
            max_pivot_height_mm=d.max_pivot_height_mm, axial_damping=v["axial_damping_present"],
            pulley_diameter_mm=d.pulley_diameter_mm, parallelism_max_mm=par_max if par_max is not None else 1e9,
            fidelity="full" if s.bushing_running_in else "screening"))
        r.update(length_mm=float(c.parts["bushing_length_mm"]), length_catalog_mm=float(c.parts["bushing_length_mm"]),
                 found=r["passes"])
    else:
        supplier = s4.supplier_for_thickness(v["pivot_bushing_radial_thickness_mm"])
        r = s4.select_bushing_length(
            v["hubload_nominal_n"], v["pivot_diameter_mm"], *dur, supplier=supplier, environment=d.application_type,
            belt_plane_height_mm=d.middle_plane_belt_height_mm, max_pivot_height_mm=d.max_pivot_height_mm,
            axial_damping=v["axial_damping_present"], pulley_diameter_mm=d.pulley_diameter_mm,
            parallelism_max_mm=par_max if par_max is not None else 1e9, scheme=s.bushing_length_scheme,
            fidelity="full" if s.bushing_running_in else "screening")
    v["pivot_bushing_supplier"] = supplier
    v["pivot_bushing_length_mm"] = _f(r["length_mm"])
    v["pivot_bushing_length_catalog_mm"] = _f(r["length_catalog_mm"])
    for k in ("p_mpa", "v_m_per_s", "pv_mpa_m_per_s", "pvt_mpa_m_per_s_h", "wear_max_mm", "parallelism_mm"):
        v[f"pivot_bushing_{k}"] = _f(r[k])
    checks = s4.bushing_checks({**r, "length_mm": r["length_mm"]}, supplier=supplier, environment=d.application_type,
                               parallelism_max_mm=par_max if par_max is not None else 1e9)
    for ch in checks:
        if ch.name.startswith("pulley parallelism") and par_max is None:
            c.skip(ch.name, 4, "pulley_max_parallelism_eol_mm", ch.equation)
        else:
            c.r.checks.append(ch)
    if not bool(np.asarray(r["found"]).reshape(-1)[0]):
        c.note("no bushing length passes every step 4 check: the thesis's next move is a larger pivot diameter")
    if v["pivot_bushing_length_catalog_mm"] != v["pivot_bushing_length_mm"]:
        c.note(f"pivot bushing: {v['pivot_bushing_length_mm']:g} mm required; the next catalog length of supplier "
               f"{supplier} is {v['pivot_bushing_length_catalog_mm']:g} mm")


# --- steps 5, 6, 8: the axial damping group ---------------------------------------------------

def _step5(c: _Ctx):
    """Steps 6 (gap tolerance), 8 (cone spring) and 5 (plastic wear), iterating on the pad class.

    The damper pad and endcap spacer classes start from the damping each
    element carries (half the axial damping: each friction face gives
    ``F mu R_i``); if the end-of-life damping fails, both move to the next
    class (larger contact surfaces), as the thesis's step 5 loop does.
    """
    d, v, s = c.d, c.v, c.s
    if not v["axial_damping_present"]:
        c.note("no axial damping: steps 5 (plastic wear), 6 (stack-up) and 8 (cone spring) are not needed")
        return "skipped"
    pads, spacers = catalog.load("damper_pads"), catalog.load("endcap_spacers")
    share = v["axial_damping_nm"] / 2.0
    start = int(np.searchsorted(pads["max_axial_damping_nm"].astype(float).to_numpy(), share, side="left"))
    aspect = None
    if c.parts:  # fixed parts: one pad/spacer pair, the given cone-spring aspect ratio, no class loop
        if str(c.parts.get("damper_pad")) == "none" or str(c.parts.get("endcap_spacer")) == "none":
            c.check("axial damping group in the parts", 3, 0.0, 1.0, ">=", "-", "eq. (9)-(11)",
                    correction="choose a damper pad and an endcap spacer class (the damping split needs axial damping)")
            return
        pads = pads[pads["class"].astype(str) == str(c.parts["damper_pad"])].reset_index(drop=True)
        sp_row = spacers[spacers["class"].astype(str) == str(c.parts["endcap_spacer"])]
        spacers = sp_row.reset_index(drop=True)
        aspect = float(c.parts["cone_aspect_ratio"])
        for name, row, cls in (("damper pad", pads, "damper_pad"), ("endcap spacer", spacers, "endcap_spacer")):
            c.check(f"{name} class carries the axial damping", 3, share, float(row["max_axial_damping_nm"].iloc[0]),
                    "<=", "Nm", "Tables 3-4", correction=f"a larger {name} class")
        start = 0
    if start >= len(pads):
        c.check("axial damping within the plastic-element classes", 5, share, float(pads["max_axial_damping_nm"].max()),
                "<=", "Nm", "Tables 3-4", correction="a larger pivot (more radial damping) or a lower damping target")
        return
    mu_pl = s5.plastic_material(application_type=d.application_type)["plastic_friction_coefficient"]
    v["mu_plastic"] = float(mu_pl)
    gap_tol = float(s6.gap_tolerance_mm("worst_case"))
    v["cone_spring_gap_tolerance_mm"] = gap_tol
    c.r.steps_run.append(6)
    dur = getattr(c, "durability", None)
    tol = d.damping_tolerance_nm if d.damping_tolerance_nm is not None else 0.0
    if d.damping_tolerance_nm is None:
        c.note("damping_tolerance_nm missing: cone-spring force band computed for a zero damping tolerance")
    for i in range(start, len(pads)):
        pad, sp = pads.iloc[i], spacers.iloc[i]
        cone = s8.cone_spring(v["axial_damping_nm"], d.damping_target_nm, tol, v["radial_damping_nm"], mu_pl,
                              float(pad["mean_radius_mm"]), float(sp["mean_radius_mm"]), float(pad["outer_diameter_mm"]),
                              v["pivot_diameter_mm"], gap_tol, aspect_ratio=aspect, fidelity=s.fidelity)
        wear = None
        if dur is not None and not isinstance(dur, str) and d.damping_eol_limit_nm is not None:
            wear = s5.plastic_wear(
                cone["cone_spring_nominal_deflection_mm"], cone["cone_spring_max_external_diameter_mm"],
                cone["cone_spring_min_internal_diameter_mm"], cone["cone_spring_thickness_mm"],
                cone["cone_spring_cone_height_mm"], float(pad["contact_area_mm2"]), float(pad["mean_radius_mm"]),
                float(pad["axial_height_mm"]), float(sp["contact_area_mm2"]), float(sp["mean_radius_mm"]),
                float(sp["axial_height_mm"]), *dur, v["radial_damping_nm"], d.damping_eol_limit_nm,
                application_type=d.application_type, fidelity=s.fidelity, time_points=60)
            if float(np.asarray(wear["margins"]["damping_eol"]).reshape(-1)[0]) < 0 and i + 1 < len(pads):
                c.note(f"plastic elements {pad['class']}/{sp['class']}: end-of-life damping "
                       f"{_f(wear['damping_eol_nm']):.3f} Nm below the limit; next class")
                continue
        break
    v["damper_pad_class"], v["endcap_spacer_class"] = str(pad["class"]), str(sp["class"])
    for key, col in (("contact_area_mm2", "contact_area_mm2"), ("mean_radius_mm", "mean_radius_mm"),
                     ("axial_height_mm", "axial_height_mm")):
        v[f"damper_pad_{key}"] = float(pad[col])
        v[f"endcap_spacer_{key}"] = float(sp[col])
    v["damper_pad_outer_diameter_mm"] = float(pad["outer_diameter_mm"])
    for k in ("cone_spring_fax_max_tolerance_n", "cone_spring_fax_min_tolerance_n", "cone_spring_fax_nominal_n",
              "cone_spring_min_internal_diameter_mm", "cone_spring_max_external_diameter_mm",
              "cone_spring_thickness_mm", "cone_spring_cone_height_mm", "cone_spring_nominal_deflection_mm",
              "cone_spring_rate_n_per_mm"):
        v[k] = _f(cone[k])
    v["cone_spring_sigma_om_mpa"] = _f(cone["sigma_om_mpa"])
    v["cone_aspect_ratio"] = float(catalog.constant("cone_spring_default_aspect_ratio") if aspect is None else aspect)
    c.r.steps_run.append(8)
    c.r.checks.extend(s8.cone_spring_checks(cone))
    if wear is None:
        missing = dur if isinstance(dur, str) else "damping_eol_limit_nm"
        c.skip("end-of-life damping", 5, missing, "eq. (43)-(49)")
        return
    for k in ("damping_eol_nm", "axial_damping_eol_nm", "cone_spring_force_eol_n", "damper_pad_wear_mm",
              "endcap_spacer_wear_mm", "plastic_wear_total_mm"):
        v[k] = _f(wear[k])
    c.r.curves["plastic_wear"] = {k: np.asarray(val).reshape(-1).tolist() for k, val in wear["history"].items()} \
        if isinstance(wear.get("history"), dict) else {}
    c.r.checks.extend(s5.plastic_wear_checks(wear, d.damping_eol_limit_nm, float(pad["axial_height_mm"]),
                                             float(sp["axial_height_mm"])))


# --- step 7 -------------------------------------------------------------------------------------

def _step7(c: _Ctx):
    d, v = c.d, c.v
    layout = "standard" if v["architecture"] == "rotary_standard" else "reverse"
    r = s7.packaging(d.middle_plane_belt_height_mm, d.max_pivot_height_mm, d.max_axial_displacement_mm,
                     v["bearing_width_mm"], v["bearing_outer_diameter_mm"], d.working_arm_mm, v["pulley_width_mm"],
                     layout=layout, axial_damping=v["axial_damping_present"],
                     endcap_spacer_height_mm=v.get("endcap_spacer_axial_height_mm") or 0.0,
                     damper_pad_height_mm=v.get("damper_pad_axial_height_mm") or 0.0)
    v["spring_housing_height_mm"] = _f(r["spring_housing_height_mm"])
    v["spring_housing_outer_diameter_mm"] = _f(r["spring_housing_outer_diameter_mm"])
    for ch in s7.packaging_checks(r, max_axial_displacement_mm=d.max_axial_displacement_mm,
                                  belt_plane_height_mm=d.middle_plane_belt_height_mm, layout=layout):
        if ch.name.startswith("pulley top"):  # eq. (26) is checked once, in step 0
            continue
        c.r.checks.append(ch)


# --- step 10 ------------------------------------------------------------------------------------

_FIXATION_INPUTS = ("tilting_safety_factor", "sliding_safety_factor", "engine_support_internal_diameter_mm",
                    "engine_support_external_diameter_mm", "support_yield_strength_compression_mpa",
                    "support_yield_strength_traction_mpa", "number_of_active_threads")


def _step10(c: _Ctx):
    d, v = c.d, c.v
    missing = d.missing(*_FIXATION_INPUTS)
    if missing:
        for name in ("tilting safety factor", "sliding safety factor", "bolt equivalent stress vs yield",
                     "under-head pressure vs support", "thread bearing stress vs support"):
            c.skip(name, 10, missing[0], "eq. (94)-(111)")
        c.note(f"step 10 not run: {missing[0]} missing")
        return
    manual = d.bolt_mode == "manual"
    r = s10.fixation(
        v["hubload_nominal_n"], d.middle_plane_belt_height_mm, d.middle_plane_belt_height_increment_worst_mm or 0.0,
        d.tilting_safety_factor, d.sliding_safety_factor, d.engine_support_internal_diameter_mm,
        d.engine_support_external_diameter_mm, d.contact_angle_deg or 360.0,
        d.support_yield_strength_compression_mpa, d.support_yield_strength_traction_mpa,
        number_of_active_threads=d.number_of_active_threads, application_type=d.application_type,
        bolt_head_contact_external_diameter_mm=d.bolt_head_contact_external_diameter_mm,
        bolt_format=d.bolt_format if manual else None, bolt_property_class=d.bolt_property_class if manual else None)
    if d.middle_plane_belt_height_increment_worst_mm is None:
        c.note("middle_plane_belt_height_increment_worst_mm missing: tilting lever without the worst-case increment")
    if d.contact_angle_deg is None:
        c.note("contact_angle_deg missing: full 360 deg contact of the pivot base assumed")
    for k in ("bolt_tightening_torque_nm", "bolt_axial_force_n", "bolt_sigma_mpa", "bolt_tau_mpa",
              "bolt_sigma_eqv_mpa", "bolt_under_head_stress_mpa", "bolt_thread_stress_mpa",
              "pivot_base_contact_surface_mm2", "average_contact_pressure_mpa", "tilting_safety_factor",
              "sliding_safety_factor", "pivot_base_max_pressure_mpa", "bolt_utilisation", "min_head_contact_diameter_mm",
              "min_active_threads", "pivot_bore_min_mm"):
        v[k] = _f(r[k])
    v["bolt_format"] = str(np.asarray(r["bolt_format"]).reshape(-1)[0])
    v["bolt_property_class"] = str(np.asarray(r["bolt_property_class"]).reshape(-1)[0])
    c.r.checks.extend(s10.fixation_checks(
        r, tilting_safety_factor_target=d.tilting_safety_factor, sliding_safety_factor_target=d.sliding_safety_factor,
        engine_support_internal_diameter_mm=d.engine_support_internal_diameter_mm,
        support_yield_strength_compression_mpa=d.support_yield_strength_compression_mpa,
        support_yield_strength_traction_mpa=d.support_yield_strength_traction_mpa))
    # step 2's bolt hole, now that the bolt is known: the pivot wall around the eccentric hole
    bolt = catalog.row("bolts", v["bolt_format"])
    hole = _f(s2.bolt_hole_diameter_mm(float(bolt["d_mm"])))
    v["pivot_bolt_hole_diameter_mm"] = hole
    from synth.catalog import constant
    wall_min = constant("pivot_min_wall_mm")
    need = 2 * (v["loading_arm_mm"] + hole / 2 + wall_min)
    c.check("pivot wall around the bolt hole", 2, _f(s2.pivot_wall_mm(v["pivot_diameter_mm"], v["loading_arm_mm"], hole)),
            wall_min, ">=", "mm", "step 2", correction=f"a pivot diameter >= {need:.1f} mm for the {hole:g} mm bolt hole "
            f"({v['bolt_format']}), or a shorter loading arm")


# --- step 9 -------------------------------------------------------------------------------------

def _spring_inputs(c: _Ctx) -> dict:
    d, v = c.d, c.v
    from synth.catalog import constant
    if d.arm_travel_nominal_to_installation_deg is None:
        c.note(f"arm_travel_nominal_to_installation_deg missing: {constant('main_spring_dtheta_inst_nom_deg'):g} deg "
               "assumed (constant main_spring_dtheta_inst_nom_deg) for the installation stress")
    return dict(stiffness_nm_per_deg=d.spring_stiffness_nm_per_deg, spring_torque_nominal_nm=v["spring_torque_nominal_nm"],
                torque_tolerance_pct=d.spring_torque_tolerance_pct or 0.0,
                theta_pp_deg=c.durability[0] if isinstance(getattr(c, "durability", None), tuple) else 0.0,
                housing_height_mm=v["spring_housing_height_mm"],
                dtheta_inst_nom_deg=d.arm_travel_nominal_to_installation_deg,
                dtheta_nom_free_arm_deg=d.arm_travel_nominal_to_free_deg)


def _wire_designation(section: str, size_mm: list) -> str:
    """The ``spring_wires.csv`` designation of a section and size; an unknown size lists the catalog's."""
    from synth.errors import InputError, Problem
    df = catalog.load("spring_wires")
    df = df[df["section"].str.strip() == section]
    b, h = (size_mm[0], size_mm[0]) if section == "round" else (size_mm[0], size_mm[1])
    hit = df[(abs(df["b_mm"].astype(float) - b) < 1e-6) & (abs(df["h_mm"].astype(float) - h) < 1e-6)]
    if hit.empty:
        sizes = ", ".join(f"[{r.b_mm:g}]" if section == "round" else f"[{r.b_mm:g}, {r.h_mm:g}]" for r in df.itertuples())
        raise InputError(Problem("main_spring_wire_size_mm", size_mm, f"a {section} wire of catalogs/spring_wires.csv: {sizes}"))
    return str(hit.iloc[0]["designation"])


def _step9(c: _Ctx):
    d, v = c.d, c.v
    from synth.catalog import constant
    if d.spring_torque_tolerance_pct is None:
        c.note("spring_torque_tolerance_pct missing: spring stresses at the nominal torque without tolerance")
    if not isinstance(getattr(c, "durability", None), tuple):
        c.note("durability test missing: spring stresses without the working oscillation")
    kw = _spring_inputs(c)
    d_out = v["spring_housing_outer_diameter_mm"]
    d_in = _f(s7.spring_housing_inner_diameter_mm(v["pivot_class_diameter_mm"]))
    v["spring_support_inner_diameter_mm"] = d_in
    if d.main_spring_mode == "manual":
        size = d.main_spring_wire_size_mm
        wire = _wire_designation(d.main_spring_wire_section, size)
        r = s9.main_spring_from_catalog(d.main_spring_material, wire, d.main_spring_mean_body_diameter_mm,
                                        housing_outer_diameter_mm=d_out, housing_inner_diameter_mm=d_in, **kw)
    else:
        table = s9.search_main_spring(housing_outer_diameter_mm=d_out, housing_inner_diameter_mm=d_in,
                                      only_feasible=False, **kw)
        n_ok = int(table["feasible"].sum())
        if not n_ok:  # nearest design: the largest smallest margin
            margins = table[[k for k in table.columns if k.startswith("margin_")]].min(axis=1)
            table = table.iloc[np.argsort(-margins.to_numpy(), kind="stable")]
        picked = table.iloc[0].to_dict()
        c.note(f"main spring (automatic): {n_ok} feasible of {len(table)} catalog springs; "
               f"the cheapest feasible is chosen" if n_ok else
               f"main spring (automatic): none of {len(table)} catalog springs passes; the one with the largest "
               "smallest margin is reported")
        r = s9.main_spring_from_catalog(picked["main_spring_material"], picked["main_spring_wire"],
                                        picked["main_spring_mean_body_diameter_mm"],
                                        housing_outer_diameter_mm=d_out, housing_inner_diameter_mm=d_in, **kw)
    for k in ("main_spring_safety_factor", "main_spring_sigma_a_max_mpa", "main_spring_sigma_a_min_mpa",
              "main_spring_sigma_inst_mpa", "main_spring_active_coils_free", "main_spring_mean_body_diameter_mm",
              "hooks_angle_free_state_deg", "hooks_angle_nominal_deg"):
        v[k] = _f(r[k])
    v["main_spring_material"] = str(r["main_spring_material"])
    v["main_spring_working_condition"] = "winding"
    v["main_spring_wire_section"] = str(r["main_spring_wire_section"])
    w = s9.wire_properties(str(r["main_spring_wire"]))
    v["main_spring_wire_size_mm"] = [float(w["h_mm"])] if w["round_wire"] else [float(w["b_mm"]), float(w["h_mm"])]
    v["main_spring_cost_eur"] = _f(r["cost_eur"])
    c.r.checks.extend(s9.main_spring_checks(r))


STEPS: dict[int, Callable[[_Ctx], Any]] = {0: _step0, 1: _step1, 2: _step2, 3: _step3, 4: _step4, 5: _step5,
                                           7: _step7, 9: _step9, 10: _step10}


def _with_parts(d, parts: dict):
    """The input ``d`` with the catalog choices of ``parts`` written into its own fields.

    Pivot class and bushing wall (from the supplier), main spring and bolt
    (manual modes) are input fields already; the bearing, bushing length,
    damper pad, endcap spacer and cone-spring aspect ratio are read from
    ``parts`` by the steps themselves.
    """
    from synth.errors import InputError, Problem
    from synth.schema import validate
    missing = [k for k in PART_KEYS if k not in parts]
    if missing:
        raise InputError(Problem("parts", sorted(parts), "a dict with the keys " + ", ".join(PART_KEYS)))
    thickness = float(catalog.row("pivot_bushings", parts["supplier"], field="parts.supplier")["radial_thickness_mm"])
    w = s9.wire_properties(str(parts["spring_wire"]))
    data = {k: val for k, val in vars(d).items()}
    data.update(pivot_class_diameter_mm=float(parts["pivot_class_mm"]),
                pivot_bushing_radial_thickness_mm=thickness,
                main_spring_mode="manual", main_spring_material=str(parts["spring_material"]),
                main_spring_wire_section="round" if w["round_wire"] else "rectangular",
                main_spring_wire_size_mm=[float(w["h_mm"])] if w["round_wire"] else [float(w["b_mm"]), float(w["h_mm"])],
                main_spring_mean_body_diameter_mm=float(parts["spring_mbd_mm"]),
                bolt_mode="manual", bolt_format=str(parts["bolt_format"]),
                bolt_property_class=str(parts["bolt_property_class"]))
    return validate(data)


#: the part keys of a fixed-parts run (the optimiser's :data:`synth.optimise.result.PART_KEYS`)
PART_KEYS = ("bearing", "pivot_class_mm", "supplier", "damper_pad", "bushing_length_mm", "endcap_spacer",
             "cone_aspect_ratio", "spring_material", "spring_wire", "spring_mbd_mm", "bolt_format", "bolt_property_class")


def run(design_input, settings: Settings | None = None, parts: dict | None = None) -> FlowchartResult:
    """Run the flowchart on a validated :class:`~synth.schema.DesignInput`.

    ``parts`` (optional) fixes every catalog choice (the keys of
    :data:`PART_KEYS`, as an optimiser's result reports them): the flowchart
    then verifies that design instead of selecting one, with the same steps,
    checks and report values (no class loops, no escalation, no search).
    """
    if parts:
        design_input = _with_parts(design_input, parts)
    c = _Ctx(design_input, settings or Settings())
    c.parts = dict(parts) if parts else None
    if parts:
        c.note("fixed-parts verification: every catalog choice is given; the flowchart checks it and selects nothing")
    for n in sorted(STEPS):
        c.r.steps_run.append(n)
        outcome = STEPS[n](c)
        if outcome == "skipped":
            c.r.steps_run.remove(n)
        if outcome is False:
            break
    return c.r
