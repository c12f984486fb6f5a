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
when the axial group is present), whether it is advisory, the inputs whose change in their declared direction
relaxes it (``relaxed_by``: the diagnosis's candidates, :mod:`synth.optimise.diagnose`) and, for a
check whose value or limit its group does not compute yet, the physics function that does (``physics``).
Every field is a keyword: an entry reads as what it declares.

The margin of a constraint is computed by :func:`margin` from the value and
limit its group evaluates (:mod:`synth.design.evaluate`):

* ``<=``: ``(limit - value) / scale``; ``>=``: ``(value - limit) / scale``,
  with ``scale = |limit|`` (1 where the limit is 0) unless the entry names
  its own scale; ``margin >= 0`` passes and its size is the relative distance
  to the limit, whatever the unit.

The flowchart's checks, the optimiser's margins and formulations, the bulk
engine's columns, the diagnosis, the HTML and Excel outputs and the CAD
checks all list constraints from :data:`REGISTRY`; nothing else keeps a list.
Adding a constraint is one entry here and one physics function: the entry's
``physics`` (a function of :mod:`synth.model` whose parameters name the
values it reads, by key: the group's values, its option's columns, its core's
values, the application's fields) returns the value and the limit, which
:func:`synth.design.evaluate.finish` adds to the group's values (see
``docs/sections/architecture.md``). :func:`register` adds entries at run time
(a plug-in, a test).

>>> REGISTRY["spring_yield"].label
'main spring stress at installation within the permissible bending stress'
>>> float(margin(REGISTRY["spring_yield"], 1500.0, 2000.0))
0.25
"""

from __future__ import annotations

import contextlib
import inspect
from dataclasses import dataclass
from typing import Callable

import numpy as np

from synth.model import pivot

__all__ = ["words", "Constraint", "REGISTRY", "GROUPS", "EVALUATED_GROUPS", "TENSIONER_GROUPS", "REQUIREMENTS", "margin", "normalised_margin", "by_group",
           "FEAS_TOL", "register", "unregister", "registered", "version", "physics_inputs"]

#: a margin above ``-FEAS_TOL`` passes (round-off of equal values)
FEAS_TOL = 1e-9

#: a limit smaller than this in magnitude (in its unit: mm, N, MPa, Nm...) normalises a margin as a zero limit
#: does (absolute); no physical limit of the registry is that small
SCALE_FLOOR = 1e-9

#: the groups the tensioner's evaluator computes for a design (:mod:`synth.design.evaluate`: the flowchart, the
#: optimisers, the bulk engine, the platform), in the thesis's order of the decomposition (:mod:`synth.design.space`)
EVALUATED_GROUPS = ("input", "core", "bushing", "axial", "spring", "bolt")
#: the tensioner's groups: the evaluator's and its 3D model's (``cad``: measured on the built solids, step 11)
TENSIONER_GROUPS = (*EVALUATED_GROUPS, "cad")
#: every group: the tensioner's and the crankshaft pulley's shrink fit (``shrink_fit``: its own scene,
#: :mod:`synth.shrink_fit.analysis`, never a tensioner design's check)
GROUPS = (*TENSIONER_GROUPS, "shrink_fit")

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


@dataclass(frozen=True, kw_only=True)
class Constraint:
    """One constraint of the tensioner design (see the module docstring for the fields' use; keywords only)."""

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
    #: targeted by the production capability (:mod:`synth.robust`) even where the margin objective leaves it out:
    #: a check sized to its limit nominally (a safety factor the preload is sized to) is judged at its made scatter
    capability: bool = False
    advisory: bool = False
    correction: str = ""
    #: input fields whose change in their declared direction (:attr:`synth.schema.Field.relax`) can relax this
    #: constraint: the diagnosis's relaxation candidates (:func:`synth.optimise.diagnose.relaxable`)
    relaxed_by: tuple[str, ...] = ()
    #: ``physics(**values) -> {key: array}``: computes this check's value and limit (and what else it names) from
    #: the values its parameters name (:func:`physics_inputs`); None: the group's function computes them
    physics: Callable | None = None

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

    def counts_in_objective(self, values: dict, rows=None):
        """Where this check counts in the margin objective: an objective, non-advisory check, except where its
        ``objective_unless`` value is positive (the design meets it by construction; NaN or 0: it counts), for the
        rows of ``values`` (or ``rows`` of them). The one rule of the margin objective: the assessment
        (:mod:`synth.design.assessment`) applies it for every consumer.

        >>> c = REGISTRY["damping_upper"]
        >>> c.counts_in_objective({"axial_damping_present": np.array([0.0, 1.0, np.nan])}).tolist()
        [True, False, True]
        >>> REGISTRY["spring_index_min"].counts_in_objective({})
        True
        """
        if self.advisory or not self.objective:
            return False
        if self.objective_unless is None or self.objective_unless not in values:
            return True
        v = np.asarray(values[self.objective_unless], dtype=float)
        return ~((v if rows is None else v[rows]) > 0)

    def reads(self) -> tuple[str, ...]:
        """The value keys its margin reads: value, limit, scale, where it applies, when it leaves the objective
        and its physics function's parameters."""
        keys = (self.value, self.limit, self.scale, self.applies, self.objective_unless)
        return tuple(dict.fromkeys([k for k in keys if k] + list(physics_inputs(self))))


def physics_inputs(c: Constraint) -> tuple[str, ...]:
    """The value keys the physics function of ``c`` reads (its parameter names; () without one).

    >>> def wall_mm(pivot_diameter_mm, bolt_d_mm): ...
    >>> physics_inputs(Constraint(id="x", label="x", step=2, equation="", unit="mm", group="bolt", value="a",
    ...                           limit="b", physics=wall_mm))
    ('pivot_diameter_mm', 'bolt_d_mm')
    """
    if c.physics is None:
        return ()
    return tuple(p.name for p in inspect.signature(c.physics).parameters.values()
                 if p.kind in (p.POSITIONAL_OR_KEYWORD, p.KEYWORD_ONLY))


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
    big = scale > SCALE_FLOOR
    if not big.all():  # (the evaluator's hot path: most limits need no floor, and then no copy is made)
        scale = np.where(big, scale, 1.0)
    diff = limit - value if sense == "<=" else value - limit
    with np.errstate(invalid="ignore"):
        m = np.asarray(diff / scale)
    # an infinite limit (no upper bound, e.g. the last Table 1 row) is an infinite margin, never NaN
    unbounded = np.isinf(limit)
    if unbounded.any():
        return np.where(unbounded & np.isfinite(value), np.where(diff > 0, np.inf, -np.inf), m)
    return m


_LENGTHEN = "lengthen the bushing; at the longest that fits, a larger pivot diameter"


_ENTRIES = (
    # --- inputs only (thesis step 0) ------------------------------------------------------------------------
    Constraint(id="pulley_axial_space", label="pulley top within the maximum axial displacement", step=0,
               equation="eq. (26)", unit="mm", group="input", value="pulley_top_mm",
               limit="max_axial_displacement_mm", sense="<=", needs=("max_axial_displacement_mm",),
               applies="layout_standard", design=False, objective=False,
               correction="max_axial_displacement_mm >= the pulley top, or a lower belt plane",
               relaxed_by=("max_axial_displacement_mm",)),
    Constraint(id="pulley_crankcase_clearance", label="pulley clear of the crankcase (reverse layout)", step=0,
               equation="eq. (27)", unit="mm", group="input", value="pulley_bottom_mm",
               limit="min_belt_crankcase_clearance_mm", sense=">=", assumes=("min_belt_crankcase_clearance_mm",),
               applies="layout_reverse", design=False, objective=False,
               correction="a higher belt plane (middle_plane_belt_height_mm)"),
    Constraint(id="pin_within_pulley", label="lock-up pin within the pulley outline", step=0, equation="eq. (22)",
               unit="mm", group="input", value="pin_inner_radius_mm", limit="pulley_radius_mm", sense="<=",
               needs=("lockup_pin",), design=False, objective=False,
               correction="move the lock-up pin inwards (lockup_pin_position_radius_mm)"),
    Constraint(id="pin_clearance", label="lock-up pin clearance to the pulley and the belt", step=0,
               equation="eq. (23)-(25)", unit="mm", group="input", value="pin_clearance_mm",
               limit="pin_clearance_required_mm", sense=">=", needs=("lockup_pin", "pin_geometry"), design=False,
               objective=False, correction="move the lock-up pin out of the belt wrap or further from the belt span",
               relaxed_by=("lockup_pin_position_radius_mm",)),
    # --- core: bearing, pivot, damping, packaging (steps 1-3, 7) --------------------------------------------
    Constraint(id="bearing_load", label="hubload within the bearing's Table 1 range", step=1, equation="Table 1",
               unit="N", group="core", value="hubload_nominal_n", limit="bearing_max_hubload_n", sense="<=",
               correction="a larger bearing"),
    Constraint(id="pulley_over_bearing", label="pulley larger than its bearing (a rim around the outer ring)", step=1,
               equation="step 1, step 2", unit="mm", group="core", value="pulley_diameter_mm",
               limit="pulley_min_diameter_mm", sense=">=", objective=False,
               correction="a larger pulley (pulley_diameter_mm), or a smaller bearing"),
    Constraint(id="working_arm_table2", label="working arm within Table 2 for the bearing", step=2,
               equation="Table 2", unit="mm", group="core", value="working_arm_mm", limit="working_arm_max_table2_mm",
               sense="<=", correction="a bearing whose Table 2 covers the working arm, or a shorter working arm"),
    Constraint(id="loading_arm", label="loading arm within Table 2", step=2, equation="Table 2", unit="mm",
               group="core", value="loading_arm_mm", limit="loading_arm_max_mm", sense="<=",
               applies="has_loading_arm", objective_unless="loading_arm_defaulted",
               correction="a shorter loading arm (loading_arm_mm), or a bearing/working arm with a longer Table 2 limit"),
    Constraint(id="arm_wall", label="arm wall on the eccentric side", step=2, equation="step 2", unit="mm",
               group="core", value="arm_wall_mm", limit="arm_min_wall_mm", sense=">=",
               correction="a smaller pivot class, or a larger bearing"),
    Constraint(id="self_locking", label="arm free to move (no self-locking)", step=3, equation="eq. (12)", unit="-",
               group="core", value="lever_ratio", limit="lever_ratio_max", sense="<=",
               correction="a smaller pivot, a larger working arm, or a differential angle nearer 90 deg"),
    Constraint(id="damping_upper", label="damping within the upper tolerance", step=3, equation="eq. (10)-(11)",
               unit="Nm", group="core", value="damping_nm", limit="damping_upper_nm", sense="<=",
               needs=("damping_band",), objective_unless="axial_damping_present",
               correction="a smaller pivot diameter or a lower-friction bushing (radial damping above the target)",
               relaxed_by=("damping_tolerance_nm",)),
    Constraint(id="damping_lower", label="damping within the lower tolerance", step=3, equation="eq. (9)-(11)",
               unit="Nm", group="core", value="damping_nm", limit="damping_lower_nm", sense=">=",
               needs=("damping_band",), objective_unless="axial_damping_present",
               correction="an axial damping group (damping_typology: radial_and_axial)",
               relaxed_by=("damping_tolerance_nm",)),
    Constraint(id="spring_torque_positive", label="spring torque at nominal positive", step=3,
               equation="eq. (12)-(13)", unit="Nm", group="core", value="spring_torque_nominal_nm", limit="zero",
               sense=">=", correction="a lower damping target or a smaller pivot"),
    Constraint(id="axial_group_matches_split",
               label="axial damping group present exactly when the damping split needs it", step=3,
               equation="eq. (9)-(11)", unit="-", group="core", value="axial_group_present",
               limit="axial_damping_present", sense=">=", objective=False,
               correction="add a damper pad and endcap spacer (the split needs axial damping), or remove them"),
    Constraint(id="axial_group_not_superfluous", label="no axial damping group where the damping split has none",
               step=3, equation="eq. (9)-(11)", unit="-", group="core", value="axial_group_present",
               limit="axial_damping_present", sense="<=", objective=False,
               correction="remove the damper pad and endcap spacer: the radial damping meets the target"),
    Constraint(id="damper_pad_capacity", label="damper pad class covers the axial damping", step=3,
               equation="Table 3", unit="Nm", group="core", value="axial_damping_nm",
               limit="damper_pad_max_axial_damping_nm", sense="<=", applies="axial_group_present",
               correction="a larger damper pad class"),
    Constraint(id="cone_spring_annulus", label="cone spring outer diameter (pad) above its inner diameter (pivot)",
               step=8, equation="Table 8, step 8", unit="mm", group="core",
               value="cone_spring_max_external_diameter_mm", limit="cone_spring_min_internal_diameter_mm", sense=">=",
               applies="axial_group_present",
               correction="a damper pad with a larger outer diameter, or a smaller pivot"),
    Constraint(id="drive_belt_slack", label="belt taut over the drive's speed sweep with the design's damping",
               step=3, equation="drive periodic response (docs: drive)", unit="N", group="core",
               value="drive_min_span_tension_n", limit="drive_belt_min_tension_n", sense=">=",
               scale="drive_static_tension_n", applies="drive_given",
               correction="more damping or a higher calculated torque (a stiffer hold on the belt); or the drive's layout"),
    Constraint(id="drive_arm_lock",
               label="tensioner arm free to swing at the durability speed (damping below the critical "
               "friction torque)", step=3, equation="Zhu and Parker 2008 (docs: drive)", unit="Nm", group="core",
               value="damping_nm", limit="drive_critical_friction_nm", sense="<=", applies="drive_given",
               correction="less damping (a smaller axial damping group or pivot), or a drive that moves the arm more"),
    Constraint(id="spring_cavity", label="spring cavity height", step=7, equation="eq. (52)-(53)", unit="mm",
               group="core", value="spring_housing_height_mm", limit="spring_cavity_min_height_mm", sense=">=",
               correction="a higher maximum pivot height or a lower belt plane",
               relaxed_by=("middle_plane_belt_height_mm", "max_pivot_height_mm")),
    # --- bushing (step 4) ----------------------------------------------------------------------------------
    Constraint(id="bushing_rated", label="bushing supplier rated for the application type", step=4,
               equation="Table 5", unit="-", group="bushing", value="bushing_rated", limit="one", sense=">=",
               objective=False, correction="a supplier rated for the application type (Table 5)"),
    Constraint(id="bushing_p", label="pivot bushing pressure", step=4, equation="eq. (28), Table 5", unit="MPa",
               group="bushing", value="pivot_bushing_p_mpa", limit="pivot_bushing_p_max_mpa", sense="<=",
               needs=("durability",), applies="bushing_rated", correction=_LENGTHEN,
               relaxed_by=("max_pivot_height_mm",)),
    Constraint(id="bushing_pv", label="pivot bushing p*v", step=4, equation="eq. (30), Table 5", unit="MPa m/s",
               group="bushing", value="pivot_bushing_pv_mpa_m_per_s", limit="pivot_bushing_pv_max_mpa_m_per_s",
               sense="<=", needs=("durability",), applies="bushing_rated", correction=_LENGTHEN,
               relaxed_by=("max_pivot_height_mm",)),
    Constraint(id="bushing_pvt", label="pivot bushing p*v*t", step=4, equation="eq. (31), Table 5", unit="MPa m/s h",
               group="bushing", value="pivot_bushing_pvt_mpa_m_per_s_h", limit="pivot_bushing_pvt_max_mpa_m_per_s_h",
               sense="<=", needs=("durability",), applies="bushing_rated", correction=_LENGTHEN,
               relaxed_by=("max_pivot_height_mm",)),
    Constraint(id="bushing_wear", label="pivot bushing wear (most loaded end) within the sliding layer", step=4,
               equation="eq. (32), (40)-(41)", unit="mm", group="bushing", value="pivot_bushing_wear_max_mm",
               limit="pivot_bushing_sliding_layer_mm", sense="<=", needs=("durability",), applies="bushing_rated",
               correction=_LENGTHEN,
               relaxed_by=("max_pivot_height_mm",)),
    Constraint(id="bushing_parallelism", label="pulley parallelism at end of life", step=4, equation="eq. (42)",
               unit="mm", group="bushing", value="pivot_bushing_parallelism_mm",
               limit="pulley_max_parallelism_eol_mm", sense="<=",
               needs=("durability", "pulley_max_parallelism_eol_mm"), applies="bushing_rated",
               correction="centre the bushing on the belt plane or lengthen it",
               relaxed_by=("pulley_max_parallelism_eol_mm", "max_pivot_height_mm")),
    Constraint(id="bushing_length", label="pivot bushing length fits the pivot", step=4, equation="eq. (33)-(34)",
               unit="mm", group="bushing", value="pivot_bushing_length_mm", limit="pivot_bushing_length_max_mm",
               sense="<=", correction="a shorter bushing, a higher maximum pivot height or a larger pivot diameter",
               relaxed_by=("max_pivot_height_mm",)),
    # --- axial damping group (steps 5, 6, 7, 8) ------------------------------------------------------------
    Constraint(id="axial_group_complete", label="damper pad and endcap spacer both present or both absent", step=3,
               equation="Tables 3-4", unit="-", group="axial", value="axial_group_mismatch", limit="zero", sense="<=",
               objective=False, correction="choose a damper pad and an endcap spacer together"),
    Constraint(id="endcap_spacer_capacity", label="endcap spacer class covers the axial damping", step=3,
               equation="Table 4", unit="Nm", group="axial", value="axial_damping_nm",
               limit="endcap_spacer_max_axial_damping_nm", sense="<=", applies="axial_group_present",
               correction="a larger endcap spacer class"),
    Constraint(id="belt_plane", label="belt plane within the pivot stack", step=7, equation="eq. (50)-(51)",
               unit="mm", group="axial", value="middle_plane_belt_height_mm", limit="belt_plane_limit_mm", sense="<=",
               applies="layout_standard",
               correction="a lower belt plane, a higher maximum pivot height or a thinner endcap spacer",
               relaxed_by=("max_pivot_height_mm",)),
    Constraint(id="belt_plane_reverse", label="belt plane above the pivot stack (reverse layout)", step=7,
               equation="eq. (50)-(51)", unit="mm", group="axial", value="middle_plane_belt_height_mm",
               limit="belt_plane_limit_mm", sense=">=", applies="layout_reverse",
               correction="a higher belt plane or a thinner endcap spacer"),
    Constraint(id="cone_force_band", label="cone spring force keeps the damping in its band over the gap tolerance",
               step=8, equation="eq. (9), Fig. 68", unit="N", group="axial", value="cone_spring_gap_band_room_n",
               limit="zero", sense=">=", scale="cone_spring_fax_band_n", needs=("damping_band",),
               applies="cone_spring_sized",
               correction="a flatter cone spring (higher h0/t, deflection nearer the flat point) or a wider damping tolerance",
               relaxed_by=("damping_tolerance_nm",)),
    Constraint(id="cone_force_manufacturing",
               label="cone spring band also holds the standard manufacturing force tolerance "
               "(advisory)", step=8, equation="DIN EN 16983 (DIN 2093) force tolerances", unit="N", group="axial",
               value="cone_spring_force_band_room_n", limit="zero", sense=">=", scale="cone_spring_fax_band_n",
               needs=("damping_band",), applies="cone_spring_sized", advisory=True, objective=False,
               correction="a tighter force tolerance agreed with the supplier (custom springs: case 1's real one is "
               "specified at +/-8.5 %), or a flatter spring"),
    Constraint(id="cone_not_flattened", label="cone spring not flat at the maximum-material gap", step=8,
               equation="DIN EN 16984; Table 6", unit="mm", group="axial", value="cone_spring_max_deflection_mm",
               limit="cone_spring_cone_height_mm", sense="<=", applies="cone_spring_sized",
               correction="a higher cone (h0) or a smaller nominal deflection"),
    Constraint(id="cone_sigma_om", label="cone spring stress sigma_OM at the maximum deflection", step=8,
               equation="eq. (59); DIN EN 16984", unit="MPa", group="axial", value="cone_spring_sigma_om_abs_mpa",
               limit="cone_spring_sigma_om_max_mpa", sense="<=", applies="cone_spring_sized",
               correction="a thicker, flatter cone spring"),
    Constraint(id="cone_table8_range", label="cone spring inner diameter within Table 8", step=8, equation="Table 8",
               unit="mm", group="axial", value="cone_spring_internal_diameter_mm", limit="cone_spring_table8_max_mm",
               sense="<=", applies="axial_group_present", correction="a smaller pivot diameter"),
    Constraint(id="cone_inner_clearance", label="cone spring inner diameter clears the pivot (Table 8 clearance)",
               step=8, equation="Table 8", unit="mm", group="axial", value="cone_spring_internal_diameter_mm",
               limit="cone_spring_min_internal_diameter_mm", sense=">=", applies="axial_group_present",
               objective=False, correction="a larger cone-spring inner diameter"),
    Constraint(id="cone_outer_on_pad", label="cone spring outer diameter bears on the damper pad", step=8,
               equation="step 8", unit="mm", group="axial", value="cone_spring_external_diameter_mm",
               limit="damper_pad_outer_diameter_mm", sense="<=", applies="axial_group_present",
               correction="a smaller cone-spring outer diameter or a larger damper pad"),
    *(Constraint(id=f"cone_{key}_{side}",
                 label=f"cone spring {sym} {'at least' if side == 'min' else 'at most'} the Table 7 "
                 f"{side}imum (supplier experience, advisory)", step=8, equation=f"{eq}, Table 7", unit="-",
                 group="axial", value=f"cone_spring_{key}", limit=f"cone_spring_{key}_{side}",
                 sense=">=" if side == "min" else "<=", applies="cone_spring_sized", advisory=True, objective=False,
                 correction="the thesis's supplier range: a warning, the physical limits decide")
      for key, sym, eq in (("diameter_ratio", "De/Di", "eq. (55)"), ("aspect_ratio", "h0/t", "eq. (56)"),
                           ("thinness", "De/t", "eq. (57)")) for side in ("min", "max")),
    Constraint(id="damping_eol", label="damping at end of life", step=5, equation="eq. (9), (11), (43)-(49)",
               unit="Nm", group="axial", value="damping_eol_nm", limit="damping_eol_limit_nm", sense=">=",
               needs=("durability", "damping_eol_limit_nm"), applies="cone_spring_sized",
               correction="the next damper pad / endcap spacer class (larger contact surfaces, Tables 3-4)",
               relaxed_by=("damping_eol_limit_nm",)),
    Constraint(id="damper_pad_wear", label="damper pad wear", step=5, equation="eq. (44)-(46)", unit="mm",
               group="axial", value="damper_pad_wear_mm", limit="damper_pad_wear_max_mm", sense="<=",
               needs=("durability",), applies="cone_spring_sized",
               correction="a damper pad class with a larger contact area"),
    Constraint(id="endcap_spacer_wear", label="endcap spacer wear", step=5, equation="eq. (47)-(49)", unit="mm",
               group="axial", value="endcap_spacer_wear_mm", limit="endcap_spacer_wear_max_mm", sense="<=",
               needs=("durability",), applies="cone_spring_sized",
               correction="an endcap spacer class with a larger contact area"),
    # --- main spring (step 9) ------------------------------------------------------------------------------
    Constraint(id="spring_yield", label="main spring stress at installation within the permissible bending stress",
               step=9, equation="eq. (69), (72)-(77); EN 13906-3", unit="MPa", group="spring",
               value="main_spring_sigma_inst_mpa", limit="main_spring_sigma_permissible_mpa", sense="<=",
               assumes=("arm_travel_nominal_to_installation_deg", "spring_torque_tolerance_pct"),
               correction="a larger wire, a stronger material or a larger mean diameter",
               relaxed_by=("spring_torque_tolerance_pct", "arm_travel_nominal_to_installation_deg")),
    Constraint(id="spring_static_permissible",
               label="main spring stress at installation within the spring makers' static rule "
               "(advisory)", step=9, equation="EN 13906-3 practice: 0.75 Rm without curvature factor", unit="MPa",
               group="spring", value="main_spring_sigma_inst_uncorrected_mpa", limit="sigma_perm_static_limit_mpa",
               sense="<=", assumes=("arm_travel_nominal_to_installation_deg", "spring_torque_tolerance_pct"),
               advisory=True, objective=False,
               correction="the production springs of the thesis cases exceed it by 5-8 %: a warning "
               "(see docs: main spring); the installation check above decides"),
    Constraint(id="spring_material_section", label="spring material supplied in the wire's section", step=9,
               equation="EN 10270-1/-2/-3", unit="-", group="spring", value="main_spring_supplied_in_section",
               limit="one", sense=">=", objective=False,
               correction="a material made in this section (flat wire: the Si-Cr oil-tempered grades)"),
    Constraint(id="spring_fatigue", label="main spring Smith-Goodman safety factor", step=9, equation="figure 71",
               unit="-", group="spring", value="main_spring_safety_factor", limit="main_spring_min_safety_factor",
               sense=">=", needs=("durability",), assumes=("spring_torque_tolerance_pct",),
               correction="a larger wire or a stronger (valve-spring) grade",
               relaxed_by=("spring_torque_tolerance_pct",)),
    Constraint(id="spring_outer_contact", label="main spring outer diameter clear of the housing", step=9,
               equation="eq. (81)-(84)", unit="mm", group="spring", value="main_spring_outer_diameter_max_mm",
               limit="spring_housing_outer_diameter_min_mm", sense="<=", assumes=("arm_travel_nominal_to_free_deg",),
               correction="a smaller mean diameter or a thinner wire",
               relaxed_by=("arm_travel_nominal_to_free_deg",)),
    Constraint(id="spring_inner_contact", label="main spring inner diameter clear of its support", step=9,
               equation="eq. (85)-(88)", unit="mm", group="spring", value="main_spring_inner_diameter_min_mm",
               limit="spring_housing_inner_diameter_max_mm", sense=">=",
               assumes=("arm_travel_nominal_to_installation_deg", "spring_torque_tolerance_pct"),
               correction="a larger mean diameter",
               relaxed_by=("spring_torque_tolerance_pct", "arm_travel_nominal_to_installation_deg")),
    Constraint(id="spring_coil_gap", label="main spring coil gap in the housing (worst condition)", step=9,
               equation="eq. (89)-(93)", unit="mm", group="spring", value="main_spring_coil_gap_worst_mm",
               limit="main_spring_min_coil_gap_mm", sense=">=", scale="main_spring_wire_b_mm",
               assumes=("arm_travel_nominal_to_installation_deg", "arm_travel_nominal_to_free_deg",
               "spring_torque_tolerance_pct"),
               correction="fewer coils (a larger mean diameter or wire), or a higher spring housing",
               relaxed_by=("middle_plane_belt_height_mm", "max_pivot_height_mm", "spring_stiffness_nm_per_deg",
                           "spring_torque_tolerance_pct", "arm_travel_nominal_to_installation_deg",
                           "arm_travel_nominal_to_free_deg")),
    Constraint(id="spring_index_min", label="main spring index at least the minimum", step=9, equation="EN 13906-3",
               unit="-", group="spring", value="main_spring_index", limit="main_spring_index_min", sense=">=",
               correction="a larger mean diameter or a thinner wire"),
    Constraint(id="spring_index_max", label="main spring index at most the maximum", step=9, equation="EN 13906-3",
               unit="-", group="spring", value="main_spring_index", limit="main_spring_index_max", sense="<=",
               correction="a smaller mean diameter or a thicker wire"),
    # --- fixation (step 10) and the pivot wall around the bolt hole (step 2) -------------------------------
    Constraint(id="tilting", label="tilting safety factor", step=10, equation="eq. (94)-(97)", unit="-", group="bolt",
               value="tilting_safety_factor", limit="tilting_safety_factor_target", sense=">=", needs=("fixation",),
               assumes=("middle_plane_belt_height_increment_worst_mm",), objective=False, capability=True,
               correction="a higher bolt preload or a larger support"),
    Constraint(id="sliding", label="sliding safety factor", step=10, equation="eq. (98)-(99)", unit="-", group="bolt",
               value="sliding_safety_factor", limit="sliding_safety_factor_target", sense=">=", needs=("fixation",),
               objective=False, capability=True, correction="a higher bolt preload"),
    Constraint(id="bolt_yield", label="bolt equivalent stress within the permissible utilisation", step=10,
               equation="eq. (103)-(107)", unit="MPa", group="bolt", value="bolt_sigma_eqv_mpa",
               limit="bolt_sigma_permissible_mpa", sense="<=", needs=("fixation",),
               assumes=("middle_plane_belt_height_increment_worst_mm",), applies="bolt_method_thesis",
               correction="a larger bolt format or a higher property class",
               relaxed_by=("tilting_safety_factor", "sliding_safety_factor", "engine_support_external_diameter_mm")),
    Constraint(id="bolt_preload_vdi", label="bolt maximum assembly preload within the permissible preload (VDI 2230)",
               step=10, equation="VDI 2230-1 R5-R7", unit="N", group="bolt", value="bolt_required_preload_max_n",
               limit="bolt_permissible_preload_n", sense="<=", needs=("fixation",),
               assumes=("middle_plane_belt_height_increment_worst_mm",), applies="bolt_method_vdi",
               correction="a larger bolt format, a higher property class or a tighter tightening method"),
    Constraint(id="under_head", label="under-head pressure within the support's compressive strength", step=10,
               equation="eq. (108)-(109)", unit="MPa", group="bolt", value="bolt_under_head_stress_mpa",
               limit="support_yield_strength_compression_mpa", sense="<=", needs=("fixation",),
               assumes=("middle_plane_belt_height_increment_worst_mm",),
               correction="a larger bolt-head contact diameter (flange head or washer)",
               relaxed_by=("tilting_safety_factor", "sliding_safety_factor", "engine_support_external_diameter_mm",
                           "bolt_head_contact_external_diameter_mm")),
    Constraint(id="thread", label="thread bearing stress within the support's strength", step=10,
               equation="eq. (110)-(111)", unit="MPa", group="bolt", value="bolt_thread_stress_mpa",
               limit="support_yield_strength_traction_mpa", sense="<=", needs=("fixation",),
               assumes=("middle_plane_belt_height_increment_worst_mm",), correction="more active threads",
               relaxed_by=("tilting_safety_factor", "sliding_safety_factor", "engine_support_external_diameter_mm",
                           "number_of_active_threads")),
    Constraint(id="pivot_bore", label="support bore large enough for the bolt", step=10,
               equation="step 2; section 10", unit="mm", group="bolt", value="engine_support_internal_diameter_mm",
               limit="pivot_bore_min_mm", sense=">=", needs=("fixation",), objective=False,
               correction="a smaller bolt format, or a larger support bore",
               relaxed_by=("engine_support_internal_diameter_mm",)),
    Constraint(id="pivot_base_pressure", label="pivot base maximum contact pressure", step=10,
               equation="eq. (96), Fig. 74", unit="MPa", group="bolt", value="pivot_base_max_pressure_mpa",
               limit="support_yield_strength_compression_mpa", sense="<=", needs=("fixation",),
               assumes=("middle_plane_belt_height_increment_worst_mm",),
               correction="a larger pivot base (engine_support_external_diameter_mm)",
               relaxed_by=("tilting_safety_factor", "sliding_safety_factor", "engine_support_external_diameter_mm")),
    # step 2's wall around the bolt hole depends on the bolt's diameter: judged when the bolt is chosen; the one
    # bolt check that reads the core (its physics' parameters), so the bulk engine evaluates it per core and
    # bolt diameter, the others per application and bolt (synth.optimise.batch)
    Constraint(id="pivot_wall", label="pivot wall around the bolt hole", step=2, equation="step 2", unit="mm",
               group="bolt", value="pivot_wall_mm", limit="pivot_min_wall_mm", sense=">=",
               physics=pivot.pivot_wall_values,
               correction="a larger pivot diameter, a shorter loading arm or a smaller bolt"),
)

_CAD = (
    # --- step 11: the 3D model, measured on the built solids (synth.cad.verify) ----------------------------
    Constraint(id="cad_interference", label="no interference between parts (3D model)", step=11,
               equation="step 11 (Fig. 75-76)", unit="mm3", group="cad", value="cad_interference_mm3",
               limit="cad_interference_tolerance_mm3", sense="<=", scale="one", objective=False,
               correction="resize the two parts named in the note"),
    Constraint(id="cad_pivot_height", label="pivot top within the maximum pivot height (3D model)", step=11,
               equation="eq. (50), (53)", unit="mm", group="cad", value="cad_pivot_top_mm",
               limit="max_pivot_height_mm", sense="<=", objective=False),
    Constraint(id="cad_axial_space", label="assembly within the maximum axial displacement (3D model)", step=11,
               equation="eq. (26)", unit="mm", group="cad", value="cad_assembly_top_mm",
               limit="max_axial_displacement_mm", sense="<=", needs=("max_axial_displacement_mm",), objective=False),
    Constraint(id="cad_crankcase_face", label="parts above the crankcase face (3D model)", step=11,
               equation="eq. (27)", unit="mm", group="cad", value="cad_lowest_part_mm", limit="zero", sense=">=",
               objective=False),
    Constraint(id="cad_belt_plane", label="pulley mid-plane on the belt plane (3D model)", step=11,
               equation="eq. (50)-(53)", unit="mm", group="cad", value="cad_pulley_offset_mm",
               limit="cad_dimension_tolerance_mm", sense="<=", scale="one", objective=False),
    Constraint(id="cad_spring_diameter", label="main spring within the housing diameter (3D model)", step=11,
               equation="eq. (54), (81)-(82)", unit="mm", group="cad", value="cad_spring_diameter_mm",
               limit="spring_housing_outer_diameter_mm", sense="<=", objective=False,
               correction="a smaller mean body diameter or wire, or a larger housing"),
    Constraint(id="cad_spring_height", label="main spring within the housing height (3D model)", step=11,
               equation="eq. (52)-(53), (89)-(93)", unit="mm", group="cad", value="cad_spring_height_mm",
               limit="spring_housing_height_mm", sense="<=", objective=False,
               correction="fewer coils or a thinner wire, or a taller housing"),
    Constraint(id="cad_collar", label="spring-bushing collar height not negative (3D model)", step=11,
               equation="step 6 stack", unit="mm", group="cad", value="cad_collar_height_mm", limit="zero",
               sense=">=", objective=False, correction="a shorter pivot bushing or a taller spring housing"),
    Constraint(id="cad_solids", label="every part built as a valid solid (3D model)", step=11,
               equation="step 11 (Fig. 75-76)", unit="parts", group="cad", value="cad_unbuilt_parts", limit="zero",
               sense="<=", objective=False, correction="resize the parts the note names (their geometry is the "
                                                       "design's: the design's own checks say which input binds)"),
)

_SHRINK_FIT = (
    # --- the crankshaft pulley's shrink fit (its own scene: Siczek et al. 2025, synth.shrink_fit) -----------
    # values and limits computed by synth.shrink_fit.analysis.analyse; step 0: not a step of the thesis
    Constraint(id="shrink_fit_slip_new", label="shrink fit: no slip, new joint, minimum interference", step=0,
               equation="paper eq. (1) sec. 3.3, eq. (17)", unit="Nm", group="shrink_fit",
               value="torque_new_min_nm", limit="slip_torque_required_nm", sense=">=",
               correction="a tighter fit (larger minimum interference) or a longer bore"),
    Constraint(id="shrink_fit_slip_worn",
               label="shrink fit: no slip after the case's displacements, minimum interference", step=0,
               equation="paper eq. (1) sec. 3.3, eq. (19)", unit="Nm", group="shrink_fit",
               value="torque_worn_min_nm", limit="slip_torque_required_nm", sense=">=",
               correction="fewer displacements (re-assemblies), smoother surfaces or a tighter fit"),
    Constraint(id="shrink_fit_hub_elastic", label="shrink fit: hub bore stays elastic at maximum interference",
               step=0, equation="Lame + von Mises", unit="MPa", group="shrink_fit", value="pressure_peak_mpa",
               limit="hub_yield_pressure_mpa", sense="<=",
               correction="a looser fit (smaller maximum interference), a larger hub or a stronger hub material"),
    Constraint(id="shrink_fit_journal_elastic", label="shrink fit: journal stays elastic at maximum interference",
               step=0, equation="Lame + von Mises", unit="MPa", group="shrink_fit", value="pressure_peak_mpa",
               limit="journal_yield_pressure_mpa", sense="<=",
               correction="a looser fit (smaller maximum interference), a smaller bore in the journal or a "
               "stronger journal material"),
)

#: id -> :class:`Constraint`, in the thesis's step order within each group (entries added by :func:`register` last)
REGISTRY: dict[str, Constraint] = {}
_VERSION = [0]
_BY_GROUP: dict = {}


def version() -> int:
    """A number that changes whenever the registry does (what a consumer caches from it is keyed on it)."""
    return _VERSION[0]


def register(*constraints: Constraint) -> None:
    """Add constraints to the registry (a plug-in's checks, a test's): every consumer lists them from then on. An id
    already declared is refused."""
    for c in constraints:
        if not isinstance(c, Constraint):
            raise TypeError(f"register: {c!r} is not a Constraint")
        if c.id in REGISTRY:
            raise ValueError(f"constraint {c.id} declared twice")
    for c in constraints:
        REGISTRY[c.id] = c
    _VERSION[0] += 1
    _BY_GROUP.clear()


def unregister(*ids: str) -> None:
    """Remove the constraints ``ids`` (added by :func:`register`)."""
    for cid in ids:
        REGISTRY.pop(cid)
    _VERSION[0] += 1
    _BY_GROUP.clear()


@contextlib.contextmanager
def registered(*constraints: Constraint):
    """The registry with ``constraints`` added for the duration of a ``with`` block."""
    register(*constraints)
    try:
        yield constraints
    finally:
        unregister(*(c.id for c in constraints))


def by_group(group: str) -> tuple[Constraint, ...]:
    """The constraints evaluated by ``group``, in registry order."""
    hit = _BY_GROUP.get(group)
    if hit is None:
        hit = _BY_GROUP[group] = tuple(c for c in REGISTRY.values() if c.group == group)
    return hit


register(*_ENTRIES, *_CAD, *_SHRINK_FIT)
