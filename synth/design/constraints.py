"""The constraint registry: every verdict synth gives is declared here, once.

A :class:`Constraint` holds everything every consumer needs: its id and
readable label, the thesis step and equation (or standard clause), the unit,
the evaluation group that computes its value and limit, the sense of the
comparison, the inputs it needs (so "not verified: <field> missing" is derived
here and nowhere else), the optional inputs whose documented default it may
use, where it applies, whether it depends on the design or on the inputs
only, whether it counts in the margin objective (input-only constraints
never do; ``objective_unless`` names a value that, where true, makes it a
constant of the design: the damping band is met exactly by the damping split
when the axial group is present) and whether it is advisory.

The margin of a constraint is computed by :func:`margin` from the value and
limit its group evaluates (:mod:`synth.design.evaluate`):

* ``<=``: ``(limit - value) / scale``; ``>=``: ``(value - limit) / scale``,
  with ``scale = |limit|`` (1 where the limit is 0) unless the entry names
  its own scale; ``margin >= 0`` passes and its size is the relative distance
  to the limit, whatever the unit.

The flowchart's checks, the optimiser's margins and formulations, the bulk
engine's columns, the diagnosis, the HTML and Excel outputs and the CAD
checks all list constraints from :data:`REGISTRY`; nothing else keeps a list.
Adding a constraint is one entry here plus the value and limit in its
group's function (see ``docs/sections/architecture.md``).

>>> REGISTRY["spring_yield"].label
'main spring stress at installation within the permissible bending stress'
>>> float(margin(REGISTRY["spring_yield"], 1500.0, 2000.0))
0.25
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

__all__ = ["words", "Constraint", "REGISTRY", "GROUPS", "REQUIREMENTS", "margin", "normalised_margin", "by_group", "FEAS_TOL"]

#: a margin above ``-FEAS_TOL`` passes (round-off of equal values)
FEAS_TOL = 1e-9

#: a limit smaller than this in magnitude (in its unit: mm, N, MPa, Nm...) normalises a margin as a zero limit
#: does (absolute); no physical limit of the registry is that small
SCALE_FLOOR = 1e-9

#: evaluation groups, in the thesis's order of the decomposition (see :mod:`synth.design.space`)
GROUPS = ("input", "core", "bushing", "axial", "spring", "bolt", "cad")

#: named requirements: name -> (the input fields, readable description). A requirement is met when every
#: field is given, except ``durability`` (also met by ``durability_test: assumed`` with an ``engine_type``).
# logical constraints (a part present or not, a supplier rated or not) have margin 0 or -1, and fits sized to
# their limit (a clearance hole on its bolt, a cone spring's bore on Table 8's clearance, a preload on its
# safety factor) have margin 0 by construction: they decide feasibility but do not count in the margin
# objective (objective=False), which would otherwise be 0 for every design
REQUIREMENTS = {
    "lockup_pin": (("lockup_pin_position_radius_mm", "lockup_pin_angular_position_deg", "lockup_pin_diameter_mm"),
                   "lock-up pin data"),
    "pin_geometry": (("wrap_angle_deg", "nominal_arm_angle_from_EHR_deg"), "wrap angle and nominal arm angle"),
    "durability": (("durability_theta_peak_to_peak_deg", "durability_frequency_hz", "durability_duration_h"),
                   "durability test (peak-to-peak angle, frequency and duration, or durability_test: assumed "
                   "with an engine_type)"),
    "damping_band": (("damping_target_nm", "damping_tolerance_nm"), "damping target and tolerance"),
    "fixation": (("tilting_safety_factor", "sliding_safety_factor", "engine_support_internal_diameter_mm",
                  "engine_support_external_diameter_mm", "contact_angle_deg", "support_yield_strength_compression_mpa",
                  "support_yield_strength_traction_mpa", "number_of_active_threads"), "fixation data"),
}


@dataclass(frozen=True)
class Constraint:
    """One constraint of the tensioner design (see the module docstring for the fields' use)."""

    id: str
    label: str
    step: int
    equation: str
    unit: str
    group: str
    value: str
    limit: str
    sense: str = "<="
    scale: str | None = None
    needs: tuple[str, ...] = ()
    assumes: tuple[str, ...] = ()
    applies: str | None = None
    design: bool = True
    objective: bool = True
    objective_unless: str | None = None
    advisory: bool = False
    correction: str = ""

    def __post_init__(self):
        if self.group not in GROUPS:
            raise ValueError(f"constraint {self.id}: group {self.group!r} not one of {GROUPS}")
        if self.sense not in ("<=", ">="):
            raise ValueError(f"constraint {self.id}: sense {self.sense!r} not '<=' or '>='")

    def requirement_fields(self) -> tuple[str, ...]:
        """Every input field this constraint needs (the named requirements expanded)."""
        out: list = []
        for n in self.needs:
            out += list(REQUIREMENTS[n][0]) if n in REQUIREMENTS else [n]
        return tuple(out)


def words(cid: str, width: int | None = None) -> str:
    """A constraint id in words (its label; ``width``: wrapped to lines of that many characters), for plots and
    tables people read; an id not in the registry stays as it is.

    >>> print(words("spring_yield", 40))
    main spring stress at installation within
    the permissible bending stress
    """
    import textwrap
    text = REGISTRY[cid].label if cid in REGISTRY else str(cid)
    return textwrap.fill(text, width) if width else text


def margin(c: Constraint, value, limit, scale=None) -> np.ndarray:
    """The normalised margin of constraint ``c`` (arrays broadcast); NaN where value or limit is NaN."""
    return normalised_margin(value, limit, c.sense, scale)


def normalised_margin(value, limit, sense: str, scale=None) -> np.ndarray:
    """``(limit - value) / scale`` for ``sense`` ``"<="``, ``(value - limit) / scale`` for ``">="`` (positive
    passes); ``scale`` defaults to ``|limit|``, 1 where it is 0 (the margin is then absolute), or below
    :data:`SCALE_FLOOR` (a limit of 1e-300 is a zero limit: dividing by it overflowed margins to infinity).

    >>> float(normalised_margin(8.0, 10.0, "<=")), float(normalised_margin(3.0, 0.0, ">="))
    (0.2, 3.0)
    >>> float(normalised_margin(1.0, 5e-324, "<="))
    -1.0
    """
    value = np.asarray(value, dtype=float)
    limit = np.asarray(limit, dtype=float)
    if scale is None:
        scale = np.abs(limit)
    scale = np.asarray(scale, dtype=float)
    scale = np.where(scale > SCALE_FLOOR, scale, 1.0)
    diff = limit - value if sense == "<=" else value - limit
    with np.errstate(invalid="ignore"):
        m = diff / scale
    # an infinite limit (no upper bound, e.g. the last Table 1 row) is an infinite margin, never NaN
    return np.where(np.isinf(limit) & np.isfinite(value), np.where(diff > 0, np.inf, -np.inf), m)


_LENGTHEN = "lengthen the bushing; at the longest that fits, a larger pivot diameter"
_AXIAL = ("axial damping group",)


def _c(*args, **kw) -> Constraint:
    return Constraint(*args, **kw)


_ENTRIES = (
    # --- inputs only (thesis step 0) ------------------------------------------------------------------------
    _c("pulley_axial_space", "pulley top within the maximum axial displacement", 0, "eq. (26)", "mm", "input",
       "pulley_top_mm", "max_axial_displacement_mm", "<=", needs=("max_axial_displacement_mm",),
       applies="layout_standard", design=False, objective=False,
       correction="max_axial_displacement_mm >= the pulley top, or a lower belt plane"),
    _c("pulley_crankcase_clearance", "pulley clear of the crankcase (reverse layout)", 0, "eq. (27)", "mm", "input",
       "pulley_bottom_mm", "min_belt_crankcase_clearance_mm", ">=", assumes=("min_belt_crankcase_clearance_mm",),
       applies="layout_reverse", design=False, objective=False, correction="a higher belt plane (middle_plane_belt_height_mm)"),
    _c("pin_within_pulley", "lock-up pin within the pulley outline", 0, "eq. (22)", "mm", "input",
       "pin_inner_radius_mm", "pulley_radius_mm", "<=", needs=("lockup_pin",), design=False, objective=False,
       correction="move the lock-up pin inwards (lockup_pin_position_radius_mm)"),
    _c("pin_clearance", "lock-up pin clearance to the pulley and the belt", 0, "eq. (23)-(25)", "mm", "input",
       "pin_clearance_mm", "pin_clearance_required_mm", ">=", needs=("lockup_pin", "pin_geometry"), design=False, objective=False,
       correction="move the lock-up pin out of the belt wrap or further from the belt span"),
    # --- core: bearing, pivot, damping, packaging (steps 1-3, 7) --------------------------------------------
    _c("bearing_load", "hubload within the bearing's Table 1 range", 1, "Table 1", "N", "core",
       "hubload_nominal_n", "bearing_max_hubload_n", "<=", correction="a larger bearing"),
    _c("pulley_over_bearing", "pulley larger than its bearing (a rim around the outer ring)", 1, "step 1, step 2",
       "mm", "core", "pulley_diameter_mm", "pulley_min_diameter_mm", ">=", objective=False,
       correction="a larger pulley (pulley_diameter_mm), or a smaller bearing"),
    _c("working_arm_table2", "working arm within Table 2 for the bearing", 2, "Table 2", "mm", "core",
       "working_arm_mm", "working_arm_max_table2_mm", "<=",
       correction="a bearing whose Table 2 covers the working arm, or a shorter working arm"),
    _c("loading_arm", "loading arm within Table 2", 2, "Table 2", "mm", "core",
       "loading_arm_mm", "loading_arm_max_mm", "<=", applies="has_loading_arm", objective_unless="loading_arm_defaulted",
       correction="a shorter loading arm (loading_arm_mm), or a bearing/working arm with a longer Table 2 limit"),
    _c("arm_wall", "arm wall on the eccentric side", 2, "step 2", "mm", "core",
       "arm_wall_mm", "arm_min_wall_mm", ">=", correction="a smaller pivot class, or a larger bearing"),
    _c("self_locking", "arm free to move (no self-locking)", 3, "eq. (12)", "-", "core",
       "lever_ratio", "lever_ratio_max", "<=",
       correction="a smaller pivot, a larger working arm, or a differential angle nearer 90 deg"),
    _c("damping_upper", "damping within the upper tolerance", 3, "eq. (10)-(11)", "Nm", "core",
       "damping_nm", "damping_upper_nm", "<=", needs=("damping_band",), objective_unless="axial_damping_present",
       correction="a smaller pivot diameter or a lower-friction bushing (radial damping above the target)"),
    _c("damping_lower", "damping within the lower tolerance", 3, "eq. (9)-(11)", "Nm", "core",
       "damping_nm", "damping_lower_nm", ">=", needs=("damping_band",), objective_unless="axial_damping_present",
       correction="an axial damping group (damping_typology: radial_and_axial)"),
    _c("spring_torque_positive", "spring torque at nominal positive", 3, "eq. (12)-(13)", "Nm", "core",
       "spring_torque_nominal_nm", "zero", ">=", correction="a lower damping target or a smaller pivot"),
    _c("axial_group_matches_split", "axial damping group present exactly when the damping split needs it", 3,
       "eq. (9)-(11)", "-", "core", "axial_group_present", "axial_damping_present", ">=",
       objective=False, correction="add a damper pad and endcap spacer (the split needs axial damping), or remove them"),
    _c("axial_group_not_superfluous", "no axial damping group where the damping split has none", 3,
       "eq. (9)-(11)", "-", "core", "axial_group_present", "axial_damping_present", "<=",
       objective=False, correction="remove the damper pad and endcap spacer: the radial damping meets the target"),
    _c("damper_pad_capacity", "damper pad class covers the axial damping", 3, "Table 3", "Nm", "core",
       "axial_damping_nm", "damper_pad_max_axial_damping_nm", "<=", applies="axial_group_present",
       correction="a larger damper pad class"),
    _c("cone_spring_annulus", "cone spring outer diameter (pad) above its inner diameter (pivot)", 8,
       "Table 8, step 8", "mm", "core", "cone_spring_max_external_diameter_mm", "cone_spring_min_internal_diameter_mm",
       ">=", applies="axial_group_present", correction="a damper pad with a larger outer diameter, or a smaller pivot"),
    _c("drive_belt_slack", "belt taut over the drive's speed sweep with the design's damping", 3,
       "drive periodic response (docs: drive)", "N", "core", "drive_min_span_tension_n", "drive_belt_min_tension_n",
       ">=", scale="drive_static_tension_n", applies="drive_given",
       correction="more damping or a higher calculated torque (a stiffer hold on the belt); or the drive's layout"),
    _c("drive_arm_lock", "tensioner arm free to swing at the durability speed (damping below the critical "
       "friction torque)", 3, "Zhu and Parker 2008 (docs: drive)", "Nm", "core", "damping_nm",
       "drive_critical_friction_nm", "<=", applies="drive_given",
       correction="less damping (a smaller axial damping group or pivot), or a drive that moves the arm more"),
    _c("spring_cavity", "spring cavity height", 7, "eq. (52)-(53)", "mm", "core",
       "spring_housing_height_mm", "spring_cavity_min_height_mm", ">=",
       correction="a higher maximum pivot height or a lower belt plane"),
    # --- bushing (step 4) ----------------------------------------------------------------------------------
    _c("bushing_rated", "bushing supplier rated for the application type", 4, "Table 5", "-", "bushing",
       "bushing_rated", "one", ">=", objective=False, correction="a supplier rated for the application type (Table 5)"),
    _c("bushing_p", "pivot bushing pressure", 4, "eq. (28), Table 5", "MPa", "bushing",
       "pivot_bushing_p_mpa", "pivot_bushing_p_max_mpa", "<=", needs=("durability",), applies="bushing_rated",
       correction=_LENGTHEN),
    _c("bushing_pv", "pivot bushing p*v", 4, "eq. (30), Table 5", "MPa m/s", "bushing",
       "pivot_bushing_pv_mpa_m_per_s", "pivot_bushing_pv_max_mpa_m_per_s", "<=", needs=("durability",),
       applies="bushing_rated", correction=_LENGTHEN),
    _c("bushing_pvt", "pivot bushing p*v*t", 4, "eq. (31), Table 5", "MPa m/s h", "bushing",
       "pivot_bushing_pvt_mpa_m_per_s_h", "pivot_bushing_pvt_max_mpa_m_per_s_h", "<=", needs=("durability",),
       applies="bushing_rated", correction=_LENGTHEN),
    _c("bushing_wear", "pivot bushing wear (most loaded end) within the sliding layer", 4, "eq. (32), (40)-(41)",
       "mm", "bushing", "pivot_bushing_wear_max_mm", "pivot_bushing_sliding_layer_mm", "<=", needs=("durability",),
       applies="bushing_rated", correction=_LENGTHEN),
    _c("bushing_parallelism", "pulley parallelism at end of life", 4, "eq. (42)", "mm", "bushing",
       "pivot_bushing_parallelism_mm", "pulley_max_parallelism_eol_mm", "<=",
       needs=("durability", "pulley_max_parallelism_eol_mm"), applies="bushing_rated",
       correction="centre the bushing on the belt plane or lengthen it"),
    _c("bushing_length", "pivot bushing length fits the pivot", 4, "eq. (33)-(34)", "mm", "bushing",
       "pivot_bushing_length_mm", "pivot_bushing_length_max_mm", "<=",
       correction="a shorter bushing, a higher maximum pivot height or a larger pivot diameter"),
    # --- axial damping group (steps 5, 6, 7, 8) ------------------------------------------------------------
    _c("axial_group_complete", "damper pad and endcap spacer both present or both absent", 3, "Tables 3-4", "-",
       "axial", "axial_group_mismatch", "zero", "<=", objective=False, correction="choose a damper pad and an endcap spacer together"),
    _c("endcap_spacer_capacity", "endcap spacer class covers the axial damping", 3, "Table 4", "Nm",
       "axial", "axial_damping_nm", "endcap_spacer_max_axial_damping_nm", "<=", applies="axial_group_present",
       correction="a larger endcap spacer class"),
    _c("belt_plane", "belt plane within the pivot stack", 7, "eq. (50)-(51)", "mm", "axial",
       "middle_plane_belt_height_mm", "belt_plane_limit_mm", "<=", applies="layout_standard",
       correction="a lower belt plane, a higher maximum pivot height or a thinner endcap spacer"),
    _c("belt_plane_reverse", "belt plane above the pivot stack (reverse layout)", 7, "eq. (50)-(51)", "mm", "axial",
       "middle_plane_belt_height_mm", "belt_plane_limit_mm", ">=", applies="layout_reverse",
       correction="a higher belt plane or a thinner endcap spacer"),
    _c("cone_force_band", "cone spring force keeps the damping in its band over the gap tolerance", 8,
       "eq. (9), Fig. 68", "N", "axial", "cone_spring_gap_band_room_n", "zero", ">=",
       scale="cone_spring_fax_band_n", needs=("damping_band",), applies="cone_spring_sized",
       correction="a flatter cone spring (higher h0/t, deflection nearer the flat point) or a wider damping tolerance"),
    _c("cone_force_manufacturing", "cone spring band also holds the standard manufacturing force tolerance "
       "(advisory)", 8, "DIN EN 16983 (DIN 2093) force tolerances", "N", "axial", "cone_spring_force_band_room_n",
       "zero", ">=", scale="cone_spring_fax_band_n", needs=("damping_band",), applies="cone_spring_sized",
       advisory=True, objective=False,
       correction="a tighter force tolerance agreed with the supplier (custom springs: case 1's real one is "
       "specified at +/-8.5 %), or a flatter spring"),
    _c("cone_not_flattened", "cone spring not flat at the maximum-material gap", 8, "DIN EN 16984; Table 6", "mm",
       "axial", "cone_spring_max_deflection_mm", "cone_spring_cone_height_mm", "<=", applies="cone_spring_sized",
       correction="a higher cone (h0) or a smaller nominal deflection"),
    _c("cone_sigma_om", "cone spring stress sigma_OM at the maximum deflection", 8, "eq. (59); DIN EN 16984", "MPa",
       "axial", "cone_spring_sigma_om_abs_mpa", "cone_spring_sigma_om_max_mpa", "<=", applies="cone_spring_sized",
       correction="a thicker, flatter cone spring"),
    _c("cone_table8_range", "cone spring inner diameter within Table 8", 8, "Table 8", "mm", "axial",
       "cone_spring_internal_diameter_mm", "cone_spring_table8_max_mm", "<=", applies="axial_group_present",
       correction="a smaller pivot diameter"),
    _c("cone_inner_clearance", "cone spring inner diameter clears the pivot (Table 8 clearance)", 8, "Table 8", "mm",
       "axial", "cone_spring_internal_diameter_mm", "cone_spring_min_internal_diameter_mm", ">=",
       applies="axial_group_present", objective=False, correction="a larger cone-spring inner diameter"),
    _c("cone_outer_on_pad", "cone spring outer diameter bears on the damper pad", 8, "step 8", "mm", "axial",
       "cone_spring_external_diameter_mm", "damper_pad_outer_diameter_mm", "<=",
       applies="axial_group_present", correction="a smaller cone-spring outer diameter or a larger damper pad"),
    *(_c(f"cone_{key}_{side}", f"cone spring {sym} {'at least' if side == 'min' else 'at most'} the Table 7 "
         f"{side}imum (supplier experience, advisory)", 8, f"{eq}, Table 7", "-", "axial", f"cone_spring_{key}",
         f"cone_spring_{key}_{side}", ">=" if side == "min" else "<=", applies="cone_spring_sized", advisory=True,
         objective=False, correction="the thesis's supplier range: a warning, the physical limits decide")
      for key, sym, eq in (("diameter_ratio", "De/Di", "eq. (55)"), ("aspect_ratio", "h0/t", "eq. (56)"),
                           ("thinness", "De/t", "eq. (57)")) for side in ("min", "max")),
    _c("damping_eol", "damping at end of life", 5, "eq. (9), (11), (43)-(49)", "Nm", "axial",
       "damping_eol_nm", "damping_eol_limit_nm", ">=", needs=("durability", "damping_eol_limit_nm"),
       applies="cone_spring_sized",
       correction="the next damper pad / endcap spacer class (larger contact surfaces, Tables 3-4)"),
    _c("damper_pad_wear", "damper pad wear", 5, "eq. (44)-(46)", "mm", "axial",
       "damper_pad_wear_mm", "damper_pad_wear_max_mm", "<=", needs=("durability",), applies="cone_spring_sized",
       correction="a damper pad class with a larger contact area"),
    _c("endcap_spacer_wear", "endcap spacer wear", 5, "eq. (47)-(49)", "mm", "axial",
       "endcap_spacer_wear_mm", "endcap_spacer_wear_max_mm", "<=", needs=("durability",),
       applies="cone_spring_sized", correction="an endcap spacer class with a larger contact area"),
    # --- main spring (step 9) ------------------------------------------------------------------------------
    _c("spring_yield", "main spring stress at installation within the permissible bending stress", 9,
       "eq. (69), (72)-(77); EN 13906-3", "MPa", "spring", "main_spring_sigma_inst_mpa",
       "main_spring_sigma_permissible_mpa", "<=",
       assumes=("arm_travel_nominal_to_installation_deg", "spring_torque_tolerance_pct"),
       correction="a larger wire, a stronger material or a larger mean diameter"),
    _c("spring_static_permissible", "main spring stress at installation within the spring makers' static rule "
       "(advisory)", 9, "EN 13906-3 practice: 0.75 Rm without curvature factor", "MPa", "spring",
       "main_spring_sigma_inst_uncorrected_mpa", "sigma_perm_static_limit_mpa", "<=",
       assumes=("arm_travel_nominal_to_installation_deg", "spring_torque_tolerance_pct"), advisory=True,
       objective=False, correction="the production springs of the thesis cases exceed it by 5-8 %: a warning "
       "(see docs: main spring); the installation check above decides"),
    _c("spring_material_section", "spring material supplied in the wire's section", 9, "EN 10270-1/-2/-3",
       "-", "spring", "main_spring_supplied_in_section", "one", ">=", objective=False,
       correction="a material made in this section (flat wire: the Si-Cr oil-tempered grades)"),
    _c("spring_fatigue", "main spring Smith-Goodman safety factor", 9, "figure 71", "-", "spring",
       "main_spring_safety_factor", "main_spring_min_safety_factor", ">=", needs=("durability",),
       assumes=("spring_torque_tolerance_pct",), correction="a larger wire or a stronger (valve-spring) grade"),
    _c("spring_outer_contact", "main spring outer diameter clear of the housing", 9, "eq. (81)-(84)", "mm", "spring",
       "main_spring_outer_diameter_max_mm", "spring_housing_outer_diameter_min_mm", "<=",
       assumes=("arm_travel_nominal_to_free_deg",), correction="a smaller mean diameter or a thinner wire"),
    _c("spring_inner_contact", "main spring inner diameter clear of its support", 9, "eq. (85)-(88)", "mm",
       "spring", "main_spring_inner_diameter_min_mm", "spring_housing_inner_diameter_max_mm", ">=",
       assumes=("arm_travel_nominal_to_installation_deg", "spring_torque_tolerance_pct"),
       correction="a larger mean diameter"),
    _c("spring_coil_gap", "main spring coil gap in the housing (worst condition)", 9, "eq. (89)-(93)", "mm",
       "spring", "main_spring_coil_gap_min_mm", "main_spring_min_coil_gap_mm", ">=", scale="main_spring_wire_b_mm",
       assumes=("arm_travel_nominal_to_installation_deg", "arm_travel_nominal_to_free_deg",
                "spring_torque_tolerance_pct"),
       correction="fewer coils (a larger mean diameter or wire), or a higher spring housing"),
    _c("spring_index_min", "main spring index at least the minimum", 9, "EN 13906-3", "-", "spring",
       "main_spring_index", "main_spring_index_min", ">=", correction="a larger mean diameter or a thinner wire"),
    _c("spring_index_max", "main spring index at most the maximum", 9, "EN 13906-3", "-", "spring",
       "main_spring_index", "main_spring_index_max", "<=", correction="a smaller mean diameter or a thicker wire"),
    # --- fixation (step 10) and the pivot wall around the bolt hole (step 2) -------------------------------
    _c("tilting", "tilting safety factor", 10, "eq. (94)-(97)", "-", "bolt",
       "tilting_safety_factor", "tilting_safety_factor_target", ">=", needs=("fixation",),
       assumes=("middle_plane_belt_height_increment_worst_mm",), objective=False,
       correction="a higher bolt preload or a larger support"),
    _c("sliding", "sliding safety factor", 10, "eq. (98)-(99)", "-", "bolt",
       "sliding_safety_factor", "sliding_safety_factor_target", ">=", needs=("fixation",), objective=False,
       correction="a higher bolt preload"),
    _c("bolt_yield", "bolt equivalent stress within the permissible utilisation", 10, "eq. (103)-(107)", "MPa", "bolt",
       "bolt_sigma_eqv_mpa", "bolt_sigma_permissible_mpa", "<=", needs=("fixation",),
       assumes=("middle_plane_belt_height_increment_worst_mm",), applies="bolt_method_thesis",
       correction="a larger bolt format or a higher property class"),
    _c("bolt_preload_vdi", "bolt maximum assembly preload within the permissible preload (VDI 2230)", 10,
       "VDI 2230-1 R5-R7", "N", "bolt", "bolt_required_preload_max_n", "bolt_permissible_preload_n", "<=",
       needs=("fixation",), assumes=("middle_plane_belt_height_increment_worst_mm",), applies="bolt_method_vdi",
       correction="a larger bolt format, a higher property class or a tighter tightening method"),
    _c("under_head", "under-head pressure within the support's compressive strength", 10, "eq. (108)-(109)", "MPa",
       "bolt", "bolt_under_head_stress_mpa", "support_yield_strength_compression_mpa", "<=", needs=("fixation",),
       assumes=("middle_plane_belt_height_increment_worst_mm",),
       correction="a larger bolt-head contact diameter (flange head or washer)"),
    _c("thread", "thread bearing stress within the support's strength", 10, "eq. (110)-(111)", "MPa", "bolt",
       "bolt_thread_stress_mpa", "support_yield_strength_traction_mpa", "<=", needs=("fixation",),
       assumes=("middle_plane_belt_height_increment_worst_mm",), correction="more active threads"),
    _c("pivot_bore", "support bore large enough for the bolt", 10, "step 2; section 10", "mm", "bolt",
       "engine_support_internal_diameter_mm", "pivot_bore_min_mm", ">=", needs=("fixation",), objective=False,
       correction="a smaller bolt format, or a larger support bore"),
    _c("pivot_base_pressure", "pivot base maximum contact pressure", 10, "eq. (96), Fig. 74", "MPa", "bolt",
       "pivot_base_max_pressure_mpa", "support_yield_strength_compression_mpa", "<=", needs=("fixation",),
       assumes=("middle_plane_belt_height_increment_worst_mm",),
       correction="a larger pivot base (engine_support_external_diameter_mm)"),
    _c("pivot_wall", "pivot wall around the bolt hole", 2, "step 2", "mm", "bolt",
       "pivot_wall_mm", "pivot_min_wall_mm", ">=", correction="a larger pivot diameter, a shorter loading arm or a "
       "smaller bolt"),
)

_CAD = (
    # --- step 11: the 3D model, measured on the built solids (synth.cad.verify) ----------------------------
    _c("cad_interference", "no interference between parts (3D model)", 11, "step 11 (Fig. 75-76)", "mm3", "cad",
       "cad_interference_mm3", "cad_interference_tolerance_mm3", "<=", scale="one", objective=False,
       correction="resize the two parts named in the note"),
    _c("cad_pivot_height", "pivot top within the maximum pivot height (3D model)", 11, "eq. (50), (53)", "mm", "cad",
       "cad_pivot_top_mm", "max_pivot_height_mm", "<=", objective=False),
    _c("cad_axial_space", "assembly within the maximum axial displacement (3D model)", 11, "eq. (26)", "mm", "cad",
       "cad_assembly_top_mm", "max_axial_displacement_mm", "<=", needs=("max_axial_displacement_mm",),
       objective=False),
    _c("cad_crankcase_face", "parts above the crankcase face (3D model)", 11, "eq. (27)", "mm", "cad",
       "cad_lowest_part_mm", "zero", ">=", objective=False),
    _c("cad_belt_plane", "pulley mid-plane on the belt plane (3D model)", 11, "eq. (50)-(53)", "mm", "cad",
       "cad_pulley_offset_mm", "cad_dimension_tolerance_mm", "<=", scale="one", objective=False),
    _c("cad_spring_diameter", "main spring within the housing diameter (3D model)", 11, "eq. (54), (81)-(82)", "mm",
       "cad", "cad_spring_diameter_mm", "spring_housing_outer_diameter_mm", "<=", objective=False,
       correction="a smaller mean body diameter or wire, or a larger housing"),
    _c("cad_spring_height", "main spring within the housing height (3D model)", 11, "eq. (52)-(53), (89)-(93)", "mm",
       "cad", "cad_spring_height_mm", "spring_housing_height_mm", "<=", objective=False,
       correction="fewer coils or a thinner wire, or a taller housing"),
    _c("cad_collar", "spring-bushing collar height not negative (3D model)", 11, "step 6 stack", "mm", "cad",
       "cad_collar_height_mm", "zero", ">=", objective=False,
       correction="a shorter pivot bushing or a taller spring housing"),
)

#: id -> :class:`Constraint`, in the thesis's step order within each group
REGISTRY: dict[str, Constraint] = {}
for _e in _ENTRIES + _CAD:
    if _e.id in REGISTRY:  # pragma: no cover - caught by the registry tests
        raise ValueError(f"constraint {_e.id} declared twice")
    REGISTRY[_e.id] = _e


def by_group(group: str) -> tuple[Constraint, ...]:
    """The constraints evaluated by ``group``, in registry order."""
    return tuple(c for c in REGISTRY.values() if c.group == group)
