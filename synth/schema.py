"""The design input: every field of the thesis's design input table, validated.

The fields are those of the thesis's Excel input table (Fig. 22-23, Tables 9
and 13), in its sections, with the key names used under ``inputs:`` in
``shared/cases/*.yaml`` (so a case file is itself a valid input file). A field
is declared once in :data:`FIELDS` with its unit, bounds, choices, section and
whether it is optional; the Excel template, the bulk portfolio reader and the
validator all read that one table.

The thesis's selectors are fields too:

* standard/custom: ``pivot_class_diameter_mm`` and ``loading_arm_mm`` may be
  omitted (``null``) to take the Table 2 standard value;
* defined/assumed: ``durability_test`` (``defined``: give peak-to-peak angle,
  frequency and duration; ``assumed``: give ``engine_type`` from
  ``catalogs/durability_tests.csv``) and ``damping_typology`` (``defined``:
  give ``damping_target_nm``; ``assumed``: ``only_radial`` or
  ``radial_and_axial``);
* automatic/manual: ``main_spring_mode`` and ``bolt_mode`` (``manual``
  verifies the given part, ``automatic`` searches the catalog).

Every problem found is reported at once, one :class:`~synth.errors.Problem`
per field (name, value, what is accepted), in an :class:`~synth.errors.InputError`.

>>> d = validate({"application_type": "dry", "engine_fuel": "diesel"}, partial=True)
>>> d.application_type, d.differential_angle_deg is None
('dry', True)
"""

from __future__ import annotations

import dataclasses
import difflib
import math
import re
import sys
from dataclasses import dataclass, field, fields as dc_fields, make_dataclass
from typing import Any

from synth import catalog
from synth.errors import InputError, Problem
from synth.io.limits import short
from synth.io.numbers import is_not_given, number_from_text, percentage
from synth.io.numbers import parse_number_list as _parse_number_list

__all__ = ["Field", "FIELDS", "SECTIONS", "OWNERS", "PART_FIELDS", "plausibility", "UNIT_SLIPS", "DesignInput", "validate", "field_by_name",
           "parse_number_list"]

INF = math.inf


@dataclass(frozen=True)
class Field:
    """Declaration of one design-input field.

    ``lo``/``hi`` are bounds; ``lo_open``/``hi_open`` make them strict.
    ``choices`` lists accepted strings (or names a catalog with ``catalog``).
    """

    name: str
    section: str
    unit: str = "-"
    kind: str = "float"  # float | int | str | list
    required: bool = True
    lo: float = -INF
    hi: float = INF
    lo_open: bool = False
    hi_open: bool = False
    choices: tuple[str, ...] = ()
    catalog: str | None = None
    default: Any = None
    label: str = ""
    aliases: tuple[str, ...] = ()
    #: the thesis's own words for the choices (Tables 9 and 13, Fig. 22-23, chapter "typologies"): word -> choice
    words: tuple[tuple[str, str], ...] = ()
    #: why the bounds are what they are (shown in docs/sections/input_gate.md)
    basis: str = ""
    #: who controls the value (:data:`OWNERS`): ``designer`` (the tensioner designer: space, parts, pin, housing,
    #: bolt, materials) or ``specification`` (the belt-drive or engine specification: stiffness, torque and
    #: damping targets, travels, safety-factor targets, the engine support); "" for application data
    owner: str = ""
    #: relaxation: +1 raising the value, -1 lowering it, relaxes the registry constraints that name the field in
    #: their ``relaxed_by`` (:attr:`synth.design.constraints.Constraint.relaxed_by`; 0: none)
    relax: int = 0
    #: a field that names a part or a class: the design-space ``(table, column)`` it selects
    #: (:func:`synth.design.space.pinned_space`; ``synth design --fix/--free``)
    pins: tuple[str, str] | tuple = ()
    #: the usual range ``(lo, hi)`` of the value (:func:`plausibility`); () none
    typical: tuple = ()

    def accepted(self) -> str:
        if self.choices:
            words = [w for w, c in self.words if _norm_word(w) != c]  # "Belt In Oil" is belt_in_oil: not listed
            return "one of " + ", ".join(self.choices) + (
                " (or the thesis's words: " + ", ".join(words) + ")" if words else "")
        if self.catalog:
            return "one of " + ", ".join(catalog.keys(self.catalog)) + f" (catalogs/{self.catalog}.csv)"
        if self.kind == "list":
            lo = f"[{self.lo:g}" if self.lo > 0 else "(0"
            bound = f" in {lo}, {self.hi:g}] {self.unit}" if math.isfinite(self.hi) else f" [{self.unit}]"
            return f"one or two positive numbers{bound}"
        lo = "(" if self.lo_open else "["
        hi = ")" if self.hi_open else "]"
        kind = "an integer" if self.kind == "int" else "a number"
        return f"{kind} in {lo}{self.lo:g}, {self.hi:g}{hi} {self.unit}".rstrip()


def _f(name, section, unit="-", **kw) -> Field:
    return Field(name=name, section=section, unit=unit, **kw)


POS = dict(lo=0.0, lo_open=True)
NONNEG = dict(lo=0.0)

FIELDS: tuple[Field, ...] = (
    # Application
    _f("application_type", "Application", choices=("dry", "belt_in_oil"), label="Application type (Dry / Belt In Oil)",
       aliases=("application",), words=(("Belt In Oil", "belt_in_oil"), ("BIO", "belt_in_oil"),
                                        ("lubricated", "belt_in_oil"), ("Dry", "dry"))),
    _f("engine_fuel", "Application", kind="str", choices=("gasoline", "diesel"), label="Engine fuel",
       words=(("Gasoline", "gasoline"), ("petrol", "gasoline"), ("Diesel", "diesel"))),
    _f("annual_volume", "Application", "1/year", kind="int", required=False, lo=1, hi=1e9,
       label="Annual volume (pieces a year; selects the price breaks; empty: constant cost_annual_volume_default)",
       basis="a count of pieces, at least one a year; 1e9 is far above any engine programme (a few tens of millions "
             "of engines a year worldwide)"),
    # Pulley
    _f("pulley_shell_type", "Pulley", kind="str", choices=("flat", "toothed"), label="Pulley shell type",
       words=(("Flat", "flat"), ("cylindrical", "flat"), ("Toothed", "toothed"))),
    _f("pulley_diameter_mm", "Pulley", "mm", lo=10.0, hi=200, label="Pulley diameter",
       basis="manufacturability floor: a pulley runs on a ball bearing pressed into it, and the smallest "
             "deep-groove ball bearing of ISO 15 that carries a belt hubload (6000: D = 26 mm) is far above 10 mm; "
             "the pulley must also clear the catalog's smallest bearing with its rim (cross-field rule) and the "
             "chosen one (registry constraint pulley_over_bearing). A 1e-320 mm pulley passed before"),
    _f("pulley_max_parallelism_eol_mm", "Pulley", "mm", required=False, lo=0.001, hi=5,
       label="Pulley max parallelism at EOL",
       basis="metrology floor: a parallelism tolerance is verified on a coordinate measuring machine whose "
             "resolution is about 1 um; a tighter limit cannot be checked"),
    # Tensioner geometrical data
    _f("belt_loading_type", "Tensioner geometrical data", kind="str",
       choices=("single_eccentric", "double_eccentric", "double_eccentric_crank_rod"), label="Belt loading type",
       words=(("Autosetting", "single_eccentric"), ("Single eccentric autosetting", "single_eccentric"),
              ("Single eccentric", "single_eccentric"), ("Double eccentric", "double_eccentric"),
              ("Double eccentric with crank/rod loading system", "double_eccentric_crank_rod"),
              ("Double eccentric crank/rod", "double_eccentric_crank_rod"), ("crank/rod", "double_eccentric_crank_rod"))),
    _f("working_arm_mm", "Tensioner geometrical data", "mm", lo=0.1, hi=20, label="Working arm length",
       basis="manufacturability floor: the arm is the eccentricity machined between the bearing seat and the pivot "
             "bore; 0.1 mm is about the positional tolerance of the two bores (the smallest thesis Table 2 arm is "
             "2.5 mm; a short arm self-locks, step 3, and fails as a design); a 5e-324 mm arm overflowed the "
             "hubload lever to infinity"),
    _f("loading_arm_mm", "Tensioner geometrical data", "mm", required=False, **NONNEG, hi=20,
       label="Loading arm length (empty: Table 2 standard)"),
    _f("differential_angle_deg", "Tensioner geometrical data", "deg", lo=0.1, hi=180, hi_open=True,
       label="Differential angle",
       basis="measurement floor: a drive layout states belt-span angles to a tenth of a degree; the thesis's "
             "cases use 85-95 deg, and an angle of 5e-324 deg made the hubload lever zero (an infinite hubload)"),
    _f("wrap_angle_deg", "Tensioner geometrical data", "deg", required=False, lo=0.1, hi=360, hi_open=True,
       label="Wrap angle", basis="measurement floor, as the differential angle"),
    _f("nominal_arm_angle_from_EHR_deg", "Tensioner geometrical data", "deg", required=False, lo=-360, hi=360,
       label="Nominal arm angle with respect to E.H.R."),
    # Belt
    _f("belt_width_mm", "Belt", "mm", lo=6.0, hi=100, label="Belt width",
       basis="physical minimum: the narrowest standard synchronous belt, ISO 5296 XL 025, is 6.4 mm wide "
             "(rounded down to 6); automotive camshaft belts are 15-30 mm (thesis cases 16 and 26 mm). A belt "
             "5e-324 mm wide passed before"),
    _f("middle_plane_belt_height_mm", "Belt", "mm", lo=1.0, hi=200, label="Middle plane belt height",
       basis="manufacturability floor: 1 mm, below any pulley half-width"),
    _f("middle_plane_belt_height_increment_worst_mm", "Belt", "mm", required=False, **NONNEG, hi=50,
       label="Middle plane belt height increment (worst case)"),
    # Lock-up pin
    _f("lockup_pin_position_radius_mm", "Lock-up pin", "mm", required=False, lo=1.0, hi=200,
       label="Lock-up pin position radius", basis="manufacturability floor: at least the smallest pin's diameter"),
    _f("lockup_pin_angular_position_deg", "Lock-up pin", "deg", required=False, lo=-360, hi=360,
       label="Lock-up pin angular position"),
    _f("lockup_pin_diameter_mm", "Lock-up pin", "mm", required=False, lo=1.0, hi=20, label="Lock-up pin diameter",
       basis="physical minimum: ISO 8734 dowel pins start at 1 mm"),
    # Space constraints
    _f("max_pivot_height_mm", "Space constraints", "mm", lo=1.0, hi=300, label="Max pivot height",
       basis="manufacturability floor: 1 mm, below any bushing or bearing width"),
    _f("max_axial_displacement_mm", "Space constraints", "mm", required=False, lo=1.0, hi=300,
       label="Max axial displacement (N/A: reverse layout, eq. (18))",
       basis="manufacturability floor: 1 mm, below any pulley width"),
    _f("min_belt_crankcase_clearance_mm", "Space constraints", "mm", required=False, **NONNEG, hi=50,
       label="Min belt-crankcase clearance, eq. (27); empty: constant reverse_layout_min_crankcase_clearance_mm",
       basis="eq. (27)'s clearance_min; 50 mm is more than any pulley offset of the thesis's cases (belt plane "
             "20-29.5 mm above the crankcase)"),
    # Pivot
    _f("pivot_class_diameter_mm", "Pivot", "mm", required=False, lo=8.0, hi=60,
       label="Pivot class diameter (empty: Table 2 standard)",
       basis="physical minimum: the pivot is a tube around the fixation bolt; the smallest catalog bolt (M6) needs "
             "a 6.2 mm hole and the pivot wall at least 1 mm a side (catalogs/constants_execution.csv "
             "bolt_hole_clearance_mm, pivot_min_wall_mm): 8.2 mm, rounded down to 8. Thesis Table 2 classes are "
             "17-22 mm and its cases use 16 and 20. A 1e-6 mm pivot made the flowchart's bushing-length search "
             "allocate 24 GB (candidates = max pivot height / pivot diameter)"),
    _f("pivot_bushing_radial_thickness_mm", "Pivot", "mm", required=False, **POS, hi=5,
       label="Pivot bushing radial thickness (supplier)"),
    # Durability test
    _f("durability_test", "Durability test", kind="str", required=False, choices=("defined", "assumed"),
       words=(("Defined", "defined"), ("Assumed", "assumed")),
       default="defined", label="Durability test (defined / assumed from engine type)"),
    _f("engine_type", "Durability test", kind="str", required=False, catalog="durability_tests",
       label="Engine type (when the durability test is assumed)"),
    _f("durability_theta_peak_to_peak_deg", "Durability test", "deg", required=False, **NONNEG, hi=90,
       label="Theta peak-to-peak"),
    _f("durability_frequency_hz", "Durability test", "Hz", required=False, **NONNEG, hi=1000, label="Frequency"),
    _f("durability_duration_h", "Durability test", "h", required=False, **NONNEG, hi=1e5, label="Duration"),
    # Tensioner specifications
    _f("calculated_torque_target_nm", "Tensioner specifications", "Nm", lo=0.01, hi=100,
       label="Calculated torque target",
       basis="measurement floor: 0.01 Nm, the resolution of a tensioner torque bench; the thesis's targets are "
             "1.5-2.5 Nm"),
    _f("damping_typology", "Tensioner specifications", kind="str", required=False,
       choices=("defined", "only_radial", "radial_and_axial"), default="defined",
       words=(("Defined", "defined"), ("Only radial", "only_radial"), ("Radial and Axial", "radial_and_axial"),
              ("Radial + Axial", "radial_and_axial")),
       label="Damping typology (defined: give the target; assumed: only radial / radial and axial)"),
    _f("damping_target_nm", "Tensioner specifications", "Nm", required=False, **NONNEG, hi=100, label="Damping target"),
    _f("damping_tolerance_nm", "Tensioner specifications", "Nm", required=False, **NONNEG, hi=100, label="Damping tolerance"),
    _f("damping_eol_limit_nm", "Tensioner specifications", "Nm", required=False, **NONNEG, hi=100,
       label="Damping end-of-life limit"),
    # Main spring
    _f("spring_stiffness_nm_per_deg", "Main spring", "Nm/deg", lo=1e-4, hi=10, label="Spring stiffness",
       basis="measurement floor: 1e-4 Nm/deg is 0.01 Nm (a torque bench's resolution) over 100 deg of travel; "
             "the thesis's springs are 0.016-0.02 Nm/deg"),
    _f("spring_torque_tolerance_pct", "Main spring", "%", required=False, **NONNEG, hi=50, label="Spring torque tolerance"),
    _f("arm_travel_nominal_to_installation_deg", "Main spring", "deg", required=False, **NONNEG, hi=180,
       label="Arm travel nominal -> installation (hot stop); empty: constant main_spring_dtheta_inst_nom_deg"),
    _f("arm_travel_nominal_to_free_deg", "Main spring", "deg", required=False, **NONNEG, hi=180,
       label="Arm travel nominal -> free arm (cold stop); empty: constant main_spring_dtheta_nom_free_arm_deg"),
    _f("main_spring_mode", "Main spring", kind="str", required=False, choices=("automatic", "manual"),
       words=(("Automatic", "automatic"), ("Manual", "manual")),
       default="automatic", label="Main spring (automatic: search the catalog / manual: verify)"),
    _f("main_spring_material", "Main spring", kind="str", required=False, catalog="spring_materials",
       label="Main spring material (manual)"),
    _f("main_spring_wire_section", "Main spring", kind="str", required=False, choices=("round", "rectangular"),
       label="Wire section (manual)", words=(("Round wire", "round"), ("Flat wire", "rectangular"), ("flat", "rectangular"),
                                             ("rectangular wire", "rectangular"))),
    _f("main_spring_wire_size_mm", "Main spring", "mm", kind="list", required=False, lo=0.05, hi=20,
       label="Wire size: [d] or [b, h] (manual)", basis="EN 10270-1 spring steel wire: 0.05-20 mm"),
    _f("main_spring_mean_body_diameter_mm", "Main spring", "mm", required=False, lo=1.0, hi=200,
       label="Mean body diameter (manual)", basis="manufacturability floor: a coil wound on a 1 mm mandrel"),
    # Bolt
    _f("tilting_safety_factor", "Bolt", required=False, lo=1.0, hi=20, label="Tilting safety factor (target)",
       basis="a safety factor below 1 designs the joint to tilt; the thesis's target is 3"),
    _f("sliding_safety_factor", "Bolt", required=False, lo=1.0, hi=20, label="Sliding safety factor (target)",
       basis="a safety factor below 1 designs the joint to slide; the thesis's target is 3"),
    _f("bolt_mode", "Bolt", kind="str", required=False, choices=("automatic", "manual"), default="automatic",
       words=(("Automatic", "automatic"), ("Manual", "manual")),
       label="Bolt (automatic: escalate format and class / manual: verify)"),
    _f("bolt_format", "Bolt", kind="str", required=False, catalog="bolts", label="Bolt format (manual)"),
    _f("bolt_property_class", "Bolt", kind="str", required=False, catalog="bolt_property_classes",
       label="Bolt property class (manual)"),
    # Fixation dimensional features
    _f("engine_support_internal_diameter_mm", "Fixation dimensional features", "mm", required=False, lo=1.0, hi=100,
       label="Engine support internal diameter", basis="manufacturability floor: a bolt hole of at least 1 mm"),
    _f("engine_support_external_diameter_mm", "Fixation dimensional features", "mm", required=False, lo=1.0, hi=200,
       label="Engine support external diameter", basis="manufacturability floor, as the internal diameter"),
    _f("contact_angle_deg", "Fixation dimensional features", "deg", required=False, lo=0.1, hi=360,
       label="Contact angle", basis="measurement floor, as the belt angles"),
    _f("bolt_head_contact_external_diameter_mm", "Fixation dimensional features", "mm", required=False, lo=1.0,
       hi=100, label="Bolt head contact external diameter", basis="manufacturability floor, as the support bore"),
    _f("number_of_active_threads", "Fixation dimensional features", required=False, lo=1.0, hi=50,
       label="Number of active threads", basis="physical minimum: a joint carries on at least one engaged thread"),
    # Support strengths
    _f("support_yield_strength_compression_mpa", "Support strengths", "MPa", required=False, lo=10.0, hi=5000,
       label="Support yield strength (compression)",
       basis="physical minimum: the softest structural metal, annealed pure aluminium (EN AW-1050A O), yields at "
             "about 20 MPa; 10 MPa is below every engine support material"),
    _f("support_yield_strength_traction_mpa", "Support strengths", "MPa", required=False, lo=10.0, hi=5000,
       label="Support yield strength (traction)", basis="physical minimum, as in compression"),
)

#: who controls an input (:attr:`Field.owner`), in the words the outputs use
OWNERS = {"designer": "the tensioner designer", "specification": "the belt-drive or engine specification"}

_D, _S = "designer", "specification"
#: the control attributes of the fields (:attr:`Field.owner`, ``relax``, ``pins``), declared here once
#: (the diagnosis's relaxation candidates, the fix/free options and the "ask for" lines all read them from the
#: fields); kept beside :data:`FIELDS` so that each entry reads as one line
_CONTROL = {
    # space, pin, bolt and housing: the tensioner designer's
    "max_pivot_height_mm": dict(owner=_D, relax=+1),
    "max_axial_displacement_mm": dict(owner=_D, relax=+1),
    "lockup_pin_position_radius_mm": dict(owner=_D, relax=+1),
    "bolt_head_contact_external_diameter_mm": dict(owner=_D, relax=+1),
    "number_of_active_threads": dict(owner=_D, relax=+1),
    # the parts and classes an input may name (the designer's choices; --fix/--free)
    "pivot_class_diameter_mm": dict(owner=_D, pins=("core", "pivot_class_diameter_mm")),
    "pivot_bushing_radial_thickness_mm": dict(owner=_D, pins=("core", "pivot_bushing_radial_thickness_mm")),
    "main_spring_material": dict(owner=_D, pins=("spring", "main_spring_material")),
    "main_spring_wire_section": dict(owner=_D, pins=("spring", "round_wire")),
    "main_spring_wire_size_mm": dict(owner=_D, pins=("spring", "main_spring_wire")),
    "main_spring_mean_body_diameter_mm": dict(owner=_D, pins=("spring", "main_spring_mean_body_diameter_mm")),
    "bolt_format": dict(owner=_D, pins=("bolt", "bolt_format")),
    "bolt_property_class": dict(owner=_D, pins=("bolt", "bolt_property_class")),
    # the belt-drive specification (ask for), the engine's support and the safety-factor targets
    "pulley_max_parallelism_eol_mm": dict(owner=_S, relax=+1),
    "damping_tolerance_nm": dict(owner=_S, relax=+1),
    "damping_eol_limit_nm": dict(owner=_S, relax=-1),
    "spring_torque_tolerance_pct": dict(owner=_S, relax=-1),
    "arm_travel_nominal_to_installation_deg": dict(owner=_S, relax=-1),
    "arm_travel_nominal_to_free_deg": dict(owner=_S, relax=-1),
    "spring_stiffness_nm_per_deg": dict(owner=_S, relax=+1),
    "middle_plane_belt_height_mm": dict(owner=_S, relax=+1),
    "tilting_safety_factor": dict(owner=_S, relax=-1),
    "sliding_safety_factor": dict(owner=_S, relax=-1),
    "engine_support_internal_diameter_mm": dict(owner=_S, relax=+1),
    "engine_support_external_diameter_mm": dict(owner=_S, relax=+1),
}
#: the usual range of a field (the thesis's case studies and input tables, Tables 9 and 13, and the generated
#: applications' engineering ranges, each widened about x2 each way): a value outside it is accepted, but when a
#: unit slip (:data:`UNIT_SLIPS`) brings it inside, the outputs say so (:func:`plausibility`)
_TYPICAL = {
    "pulley_diameter_mm": (40, 120), "working_arm_mm": (1.5, 10), "differential_angle_deg": (30, 150),
    "wrap_angle_deg": (20, 220), "belt_width_mm": (10, 45), "middle_plane_belt_height_mm": (10, 60),
    "lockup_pin_position_radius_mm": (10, 80), "max_pivot_height_mm": (15, 80),
    "max_axial_displacement_mm": (15, 90), "pivot_class_diameter_mm": (12, 30),
    "durability_theta_peak_to_peak_deg": (1, 40), "calculated_torque_target_nm": (0.5, 10),
    "damping_target_nm": (0.1, 5), "spring_stiffness_nm_per_deg": (0.005, 0.1),
    "arm_travel_nominal_to_installation_deg": (5, 90), "arm_travel_nominal_to_free_deg": (5, 90),
    "main_spring_mean_body_diameter_mm": (20, 70), "engine_support_internal_diameter_mm": (5, 20),
    "engine_support_external_diameter_mm": (15, 50), "bolt_head_contact_external_diameter_mm": (8, 30),
    "support_yield_strength_compression_mpa": (100, 1500), "support_yield_strength_traction_mpa": (100, 1500),
}
#: unit -> (factor, the unit the value looks like it was given in): ``value x factor`` is the value in the field's
#: unit had it been typed in the other one
UNIT_SLIPS = {"mm": ((1000.0, "m"),), "deg": ((180.0 / math.pi, "rad"),), "Nm/deg": ((math.pi / 180.0, "Nm/rad"),),
              "MPa": ((1000.0, "GPa"), (1e-6, "Pa")), "Nm": ((1e-3, "N mm"),)}
FIELDS = tuple(dataclasses.replace(f, **_CONTROL.get(f.name, {}), typical=_TYPICAL.get(f.name, ()))
               for f in FIELDS)
#: the fields that name a part or a class (``synth design --fix/--free``), in the schema's order
PART_FIELDS: tuple[str, ...] = tuple(f.name for f in FIELDS if f.pins)

SECTIONS: tuple[str, ...] = tuple(dict.fromkeys(f.section for f in FIELDS))
_BY_NAME = {f.name: f for f in FIELDS}
_ALIASES = {a: f.name for f in FIELDS for a in f.aliases}


def field_by_name(name: str) -> Field:
    """The :class:`Field` declared as ``name``."""
    return _BY_NAME[name]


DesignInput = make_dataclass(
    "DesignInput",
    [(f.name, Any, field(default=None)) for f in FIELDS],
    frozen=True,
    namespace={
        "__doc__": "A validated design input; attribute names are the field names of :data:`FIELDS`.",
        "as_dict": lambda self: {f.name: getattr(self, f.name) for f in dc_fields(self)},
        "missing": lambda self, *names: [n for n in names if getattr(self, n) is None],
    },
)
DesignInput.__module__ = __name__


def _norm_word(text: str) -> str:
    """A choice as typed, normalised: lower case, quotes dropped, spaces/hyphens/slashes as ``_``."""
    t = text.strip().lower()
    for q in "\"'“”‘’`":
        t = t.replace(q, "")
    t = re.sub(r"[\s\-/+]+", "_", t)
    return t.strip("_")


def _choice(f: Field, text: str) -> str | None:
    """The choice ``text`` means: a choice itself or one of the thesis's words for it (case, spaces free)."""
    norm = _norm_word(text)
    if norm in f.choices:
        return norm
    for word, choice in f.words:
        if _norm_word(word) == norm:
            return choice
    return None


def coerce(f: Field, value: Any, problems: list[Problem]) -> Any:
    """Convert ``value`` to the field's kind, appending a problem on failure.

    ``None`` and the "not given" words (``N/A``, ``n.a.``, ``-``, empty; see
    :data:`synth.io.numbers.NOT_GIVEN`) give None: the field is not given.
    """
    if is_not_given(value):
        return None
    shown = short(value)
    if f.kind == "list":
        items = parse_number_list(value)
        items = items if isinstance(items, (list, tuple)) else [items]
        out = []
        for v in items:
            x = _number(v)
            if x is None or x < f.lo or x <= 0 or x > f.hi:
                problems.append(Problem(f.name, shown, f.accepted()))
                return None
            out.append(x)
        if not out or len(out) > 2:
            problems.append(Problem(f.name, shown, f.accepted()))
            return None
        return out
    if f.choices or f.catalog or f.kind == "str":
        if isinstance(value, (dict, list, tuple, bool)):
            problems.append(Problem(f.name, shown, f.accepted()))
            return None
        text = str(value).strip()
        if f.choices:
            choice = _choice(f, text)
            if choice is None:
                problems.append(Problem(f.name, shown, f.accepted()))
            return choice
        if f.catalog and text not in catalog.keys(f.catalog):
            problems.append(Problem(f.name, shown, f.accepted()))
            return None
        return text
    number = percentage(value, "%") if f.unit == "%" else _number(value)  # "8 %", "8%" and 8 in a % field
    if number is None:
        problems.append(Problem(f.name, shown, f.accepted()))
        return None
    below = number <= f.lo if f.lo_open else number < f.lo
    above = number >= f.hi if f.hi_open else number > f.hi
    if below or above:
        problems.append(Problem(f.name, shown, f.accepted()))
        return None
    if f.kind == "int":
        if number != int(number):
            problems.append(Problem(f.name, shown, f.accepted()))
            return None
        return int(number)
    return number


def _number(value) -> float | None:
    """A finite float from a number or a cell's text (decimal comma; a percentage only in a field whose unit is
    ``%``: :func:`synth.io.numbers.percentage`), else None (never raises).

    A subnormal number (below 2.2e-308 in magnitude, not 0) is no physical value either: None.
    """
    if isinstance(value, bool) or value is None:
        return None
    if isinstance(value, str):
        number = number_from_text(value)
    else:
        try:
            number = float(value)
        except (TypeError, ValueError, OverflowError):  # a 400-digit integer overflows a float
            return None
    if number is None or not math.isfinite(number) or (number != 0.0 and abs(number) < sys.float_info.min):
        return None
    return number


def _require(d: dict, names: tuple[str, ...], why: str, problems: list[Problem]) -> None:
    for n in names:
        if d.get(n) is None:
            problems.append(Problem(n, None, f"a value ({why})"))


def consistency(d: dict, problems: list[Problem]) -> None:
    """Cross-field rules: one problem per inconsistent field."""
    def both(a, b):
        return d.get(a) is not None and d.get(b) is not None

    if both("engine_support_internal_diameter_mm", "engine_support_external_diameter_mm") and \
            d["engine_support_internal_diameter_mm"] >= d["engine_support_external_diameter_mm"]:
        problems.append(Problem("engine_support_external_diameter_mm", d["engine_support_external_diameter_mm"],
                                f"a diameter above engine_support_internal_diameter_mm = {d['engine_support_internal_diameter_mm']:g} mm"))
    if both("engine_support_internal_diameter_mm", "bolt_head_contact_external_diameter_mm") and \
            d["bolt_head_contact_external_diameter_mm"] <= d["engine_support_internal_diameter_mm"]:
        problems.append(Problem("bolt_head_contact_external_diameter_mm", d["bolt_head_contact_external_diameter_mm"],
                                f"a diameter above engine_support_internal_diameter_mm = {d['engine_support_internal_diameter_mm']:g} mm"))
    if both("middle_plane_belt_height_mm", "max_axial_displacement_mm") and \
            d["middle_plane_belt_height_mm"] >= d["max_axial_displacement_mm"]:
        problems.append(Problem("middle_plane_belt_height_mm", d["middle_plane_belt_height_mm"],
                                f"a height below max_axial_displacement_mm = {d['max_axial_displacement_mm']:g} mm"))
    if both("damping_eol_limit_nm", "damping_target_nm") and d["damping_eol_limit_nm"] > d["damping_target_nm"]:
        problems.append(Problem("damping_eol_limit_nm", d["damping_eol_limit_nm"],
                                f"a limit not above damping_target_nm = {d['damping_target_nm']:g} Nm"))
    if both("damping_tolerance_nm", "damping_target_nm") and d["damping_tolerance_nm"] >= d["damping_target_nm"] > 0:
        problems.append(Problem("damping_tolerance_nm", d["damping_tolerance_nm"],
                                f"a tolerance below damping_target_nm = {d['damping_target_nm']:g} Nm"))
    if d.get("belt_loading_type") == "single_eccentric" and (d.get("loading_arm_mm") or 0) > 0:
        problems.append(Problem("loading_arm_mm", d["loading_arm_mm"],
                                "0 or empty for a single-eccentric (autosetting) tensioner, which has no loading arm"))
    pin = ("lockup_pin_position_radius_mm", "lockup_pin_angular_position_deg", "lockup_pin_diameter_mm")
    given = [n for n in pin if d.get(n) is not None]
    if 0 < len(given) < len(pin):
        for n in pin:
            if d.get(n) is None:
                problems.append(Problem(n, None, "a value: the lock-up pin needs radius, angular position and diameter together"))
    limits = _catalog_limits()
    if d.get("pulley_diameter_mm") is not None and limits["pulley"] is not None:
        name, bore_d, floor = limits["pulley"]
        if d["pulley_diameter_mm"] < floor:
            problems.append(Problem("pulley_diameter_mm", d["pulley_diameter_mm"],
                                    f"a pulley larger than the smallest catalog bearing ({name}, "
                                    f"D = {bore_d:g} mm) with its rim: at least {floor:g} mm "
                                    "(constant pulley_min_wall_mm a side)"))
    if d.get("pivot_bushing_radial_thickness_mm") is not None:
        thick = limits["thicknesses"]
        if thick and not any(abs(d["pivot_bushing_radial_thickness_mm"] - t) < 1e-9 for t in thick):
            problems.append(Problem("pivot_bushing_radial_thickness_mm", d["pivot_bushing_radial_thickness_mm"],
                                    "a supplier thickness: one of " + ", ".join(f"{t:g}" for t in thick) + " mm"))


_CATALOG_LIMITS: dict = {}


def _catalog_limits() -> dict:
    """What the consistency rules read of the catalogs, derived once per catalog data (a portfolio validates
    every row with them: listing the catalog folder and copying two tables per row was most of its cost).

    ``pulley``: ``(designation, D [mm], smallest pulley diameter [mm])`` of the smallest catalog bearing with
    its rim (``pulley_min_wall_mm`` a side), None without a bearing catalog; ``thicknesses``: the sorted
    radial thicknesses of the pivot bushings (empty without that catalog). Keyed by the user folders and the
    parsed tables themselves (a cleared catalog cache parses new ones, and so derives again)."""
    dirs = tuple(catalog.user_dirs())
    hit = _CATALOG_LIMITS.get(dirs)
    if hit is not None:
        sources, out = hit
        if all(catalog.load_cached(n, dirs) is src for n, src in sources) \
                and out["wall"] == catalog.constant("pulley_min_wall_mm"):
            return out
    have = set(catalog.names())
    sources, out = [], {"pulley": None, "thicknesses": [], "wall": catalog.constant("pulley_min_wall_mm")}
    if "ball_bearings" in have:
        sources.append(("ball_bearings", catalog.load_cached("ball_bearings", dirs)))
        bearings = catalog.load("ball_bearings")
        i = int(bearings["D_mm"].astype(float).idxmin())
        out["pulley"] = (bearings.iloc[i, 0], float(bearings["D_mm"][i]), float(bearings["D_mm"][i]) + 2.0 * out["wall"])
    if "pivot_bushings" in have:
        sources.append(("pivot_bushings", catalog.load_cached("pivot_bushings", dirs)))
        out["thicknesses"] = sorted({float(t) for t in catalog.load("pivot_bushings")["radial_thickness_mm"]})
    _CATALOG_LIMITS[dirs] = (tuple(sources), out)
    return out


def validate(data: dict, partial: bool = False) -> "DesignInput":
    """Validate a mapping of design-input fields into a :class:`DesignInput`.

    ``partial=True`` skips the required-field and selector rules (used for
    templates and tests). Raises :class:`~synth.errors.InputError` listing
    every problem.
    """
    if not isinstance(data, dict):
        raise InputError(Problem("input", type(data).__name__, "a mapping of field names to values"))
    data = {k: v for k, v in data.items()}
    problems: list[Problem] = []
    out: dict[str, Any] = {}
    given_as: dict[str, str] = {}
    for key, value in data.items():
        key = str(key)
        name = _ALIASES.get(key, key)
        if name not in _BY_NAME:
            near = difflib.get_close_matches(key, list(_BY_NAME), n=1)
            hint = f" (did you mean {near[0]}?)" if near else ""
            problems.append(Problem(short(key), short(value), "a known design-input field" + hint))
            continue
        if name in given_as:
            problems.append(Problem(key, short(value), f"only one of {given_as[name]} and {key}: both name the field "
                                                       f"{name} (remove one)"))
            continue
        given_as[name] = key
        out[name] = coerce(_BY_NAME[name], value, problems)
    return finish(out, problems, partial)


_DEFAULTED = tuple(f for f in FIELDS if f.default is not None)
_REQUIRED = tuple(f for f in FIELDS if f.required)


def finish(out: dict, problems: list[Problem], partial: bool = False) -> "DesignInput":
    """The rules of :func:`validate` after each field's value is coerced (``out``: field name -> value, None
    where not given; ``problems`` so far): defaults, required fields, selectors, cross-field consistency. The
    column validator of portfolios (:func:`synth.bulk.portfolio.validate_table`) coerces whole columns, then
    calls this per row."""
    for f in _DEFAULTED:
        if out.get(f.name) is None:
            out[f.name] = f.default
    if not partial:
        flagged = {p.field for p in problems}
        for f in _REQUIRED:
            if out.get(f.name) is None and f.name not in flagged:
                problems.append(Problem(f.name, None, "a value (required); " + f.accepted()))
        if out.get("durability_test") == "assumed":
            _require(out, ("engine_type",), "durability_test is 'assumed'", problems)
        if out.get("damping_typology") in ("defined", "radial_and_axial") and out.get("damping_target_nm") is None \
                and not any(p.field == "damping_target_nm" for p in problems):
            problems.append(Problem("damping_target_nm", None,
                                    "a value (the axial damping group is sized on it), or set damping_typology to only_radial"))
        if out.get("main_spring_mode") == "manual":
            _require(out, ("main_spring_material", "main_spring_wire_section", "main_spring_wire_size_mm",
                           "main_spring_mean_body_diameter_mm"), "main_spring_mode is 'manual'", problems)
            sec, size = out.get("main_spring_wire_section"), out.get("main_spring_wire_size_mm")
            if sec and size and len(size) != (1 if sec == "round" else 2):
                problems.append(Problem("main_spring_wire_size_mm", size,
                                        "[d] for a round wire, [b, h] for a rectangular one"))
        if out.get("bolt_mode") == "manual":
            _require(out, ("bolt_format", "bolt_property_class"), "bolt_mode is 'manual'", problems)
    consistency(out, problems)
    if problems:
        raise InputError(problems)
    return DesignInput(**out)


def plausibility(d) -> list[str]:
    """Warnings for values that look typed in another unit (rad for deg, Nm/rad for Nm/deg, m for mm, GPa or Pa
    for MPa, N mm for Nm): outside the field's usual range, inside it once converted. Accepted, never refused.

    >>> plausibility(validate({"spring_stiffness_nm_per_deg": 0.94, "differential_angle_deg": 1.5708}, partial=True))[0]
    'differential_angle_deg = 1.571 deg is outside the usual 30-150 deg; as rad it would be 90 deg: check the unit'
    """
    out = []
    for f in FIELDS:
        v = getattr(d, f.name, None)
        if not f.typical or isinstance(v, (bool, str, list)) or v is None:
            continue
        lo, hi = f.typical
        if lo <= v <= hi:
            continue
        for factor, other in UNIT_SLIPS.get(f.unit, ()):
            if lo <= v * factor <= hi:
                out.append(f"{f.name} = {v:.4g} {f.unit} is outside the usual {lo:g}-{hi:g} {f.unit}; as {other} it "
                           f"would be {v * factor:.4g} {f.unit}: check the unit")
                break
    return out


def parse_number_list(value):
    """A list-valued cell (a wire size: ``2.3 x 2.3``, ``2,5 x 2,5``, ``[2.3, 2.3]``, a number) as a list of floats.

    Text that does not parse is returned as it is, for :func:`validate` to
    report with the field's name. Used by the Excel and portfolio readers
    (:func:`synth.io.numbers.parse_number_list`).

    >>> parse_number_list("2.3 x 2.3"), parse_number_list("3"), parse_number_list(2.5), parse_number_list("abc")
    ([2.3, 2.3], [3.0], [2.5], 'abc')
    """
    return _parse_number_list(value)
