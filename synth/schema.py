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

import difflib
import math
import re
from dataclasses import dataclass, field, fields as dc_fields, make_dataclass
from pathlib import Path
from typing import Any

from synth import catalog
from synth.errors import InputError, Problem
from synth.io.limits import short
from synth.io.numbers import is_not_given, number_from_text
from synth.io.numbers import parse_number_list as _parse_number_list

__all__ = ["Field", "FIELDS", "SECTIONS", "DesignInput", "validate", "load_input", "read_mapping", "field_by_name",
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

    def accepted(self) -> str:
        if self.choices:
            words = [w for w, c in self.words if _norm_word(w) != c]  # "Belt In Oil" is belt_in_oil: not listed
            return "one of " + ", ".join(self.choices) + (
                " (or the thesis's words: " + ", ".join(words) + ")" if words else "")
        if self.catalog:
            return "one of " + ", ".join(catalog.keys(self.catalog)) + f" (catalogs/{self.catalog}.csv)"
        if self.kind == "list":
            bound = f" in (0, {self.hi:g}] {self.unit}" if math.isfinite(self.hi) else f" [{self.unit}]"
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
    # Pulley
    _f("pulley_shell_type", "Pulley", kind="str", choices=("flat", "toothed"), label="Pulley shell type",
       words=(("Flat", "flat"), ("cylindrical", "flat"), ("Toothed", "toothed"))),
    _f("pulley_diameter_mm", "Pulley", "mm", **POS, hi=200, label="Pulley diameter"),
    _f("pulley_max_parallelism_eol_mm", "Pulley", "mm", required=False, **POS, hi=5, label="Pulley max parallelism at EOL"),
    # Tensioner geometrical data
    _f("belt_loading_type", "Tensioner geometrical data", kind="str",
       choices=("single_eccentric", "double_eccentric", "double_eccentric_crank_rod"), label="Belt loading type",
       words=(("Autosetting", "single_eccentric"), ("Single eccentric autosetting", "single_eccentric"),
              ("Single eccentric", "single_eccentric"), ("Double eccentric", "double_eccentric"),
              ("Double eccentric with crank/rod loading system", "double_eccentric_crank_rod"),
              ("Double eccentric crank/rod", "double_eccentric_crank_rod"), ("crank/rod", "double_eccentric_crank_rod"))),
    _f("working_arm_mm", "Tensioner geometrical data", "mm", **POS, hi=20, label="Working arm length"),
    _f("loading_arm_mm", "Tensioner geometrical data", "mm", required=False, **NONNEG, hi=20,
       label="Loading arm length (empty: Table 2 standard)"),
    _f("differential_angle_deg", "Tensioner geometrical data", "deg", lo=0, hi=180, lo_open=True, hi_open=True,
       label="Differential angle"),
    _f("wrap_angle_deg", "Tensioner geometrical data", "deg", required=False, lo=0, hi=360, lo_open=True, hi_open=True,
       label="Wrap angle"),
    _f("nominal_arm_angle_from_EHR_deg", "Tensioner geometrical data", "deg", required=False, lo=-360, hi=360,
       label="Nominal arm angle with respect to E.H.R."),
    # Belt
    _f("belt_width_mm", "Belt", "mm", **POS, hi=100, label="Belt width"),
    _f("middle_plane_belt_height_mm", "Belt", "mm", **POS, hi=200, label="Middle plane belt height"),
    _f("middle_plane_belt_height_increment_worst_mm", "Belt", "mm", required=False, **NONNEG, hi=50,
       label="Middle plane belt height increment (worst case)"),
    # Lock-up pin
    _f("lockup_pin_position_radius_mm", "Lock-up pin", "mm", required=False, **POS, hi=200, label="Lock-up pin position radius"),
    _f("lockup_pin_angular_position_deg", "Lock-up pin", "deg", required=False, lo=-360, hi=360,
       label="Lock-up pin angular position"),
    _f("lockup_pin_diameter_mm", "Lock-up pin", "mm", required=False, **POS, hi=20, label="Lock-up pin diameter"),
    # Space constraints
    _f("max_pivot_height_mm", "Space constraints", "mm", **POS, hi=300, label="Max pivot height"),
    _f("max_axial_displacement_mm", "Space constraints", "mm", required=False, **POS, hi=300,
       label="Max axial displacement (N/A: reverse layout, eq. (18))"),
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
    _f("calculated_torque_target_nm", "Tensioner specifications", "Nm", **POS, hi=100, label="Calculated torque target"),
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
    _f("spring_stiffness_nm_per_deg", "Main spring", "Nm/deg", **POS, hi=10, label="Spring stiffness"),
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
    _f("main_spring_wire_size_mm", "Main spring", "mm", kind="list", required=False, **POS, hi=20,
       label="Wire size: [d] or [b, h] (manual)"),  # EN 10270-1 wire: 0.05-20 mm
    _f("main_spring_mean_body_diameter_mm", "Main spring", "mm", required=False, **POS, hi=200,
       label="Mean body diameter (manual)"),
    # Bolt
    _f("tilting_safety_factor", "Bolt", required=False, **POS, hi=20, label="Tilting safety factor (target)"),
    _f("sliding_safety_factor", "Bolt", required=False, **POS, hi=20, label="Sliding safety factor (target)"),
    _f("bolt_mode", "Bolt", kind="str", required=False, choices=("automatic", "manual"), default="automatic",
       words=(("Automatic", "automatic"), ("Manual", "manual")),
       label="Bolt (automatic: escalate format and class / manual: verify)"),
    _f("bolt_format", "Bolt", kind="str", required=False, catalog="bolts", label="Bolt format (manual)"),
    _f("bolt_property_class", "Bolt", kind="str", required=False, catalog="bolt_property_classes",
       label="Bolt property class (manual)"),
    # Fixation dimensional features
    _f("engine_support_internal_diameter_mm", "Fixation dimensional features", "mm", required=False, **POS, hi=100,
       label="Engine support internal diameter"),
    _f("engine_support_external_diameter_mm", "Fixation dimensional features", "mm", required=False, **POS, hi=200,
       label="Engine support external diameter"),
    _f("contact_angle_deg", "Fixation dimensional features", "deg", required=False, lo=0, hi=360, lo_open=True,
       label="Contact angle"),
    _f("bolt_head_contact_external_diameter_mm", "Fixation dimensional features", "mm", required=False, **POS, hi=100,
       label="Bolt head contact external diameter"),
    _f("number_of_active_threads", "Fixation dimensional features", required=False, **POS, hi=50,
       label="Number of active threads"),
    # Support strengths
    _f("support_yield_strength_compression_mpa", "Support strengths", "MPa", required=False, **POS, hi=5000,
       label="Support yield strength (compression)"),
    _f("support_yield_strength_traction_mpa", "Support strengths", "MPa", required=False, **POS, hi=5000,
       label="Support yield strength (traction)"),
)

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


def _coerce(f: Field, value: Any, problems: list[Problem]) -> Any:
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
            if x is None or x <= 0 or x > f.hi:
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
    number = _number(value)
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
    """A finite float from a number or a cell's text (decimal comma, ``%``), else None (never raises)."""
    if isinstance(value, bool) or value is None:
        return None
    if isinstance(value, str):
        return number_from_text(value)
    try:
        number = float(value)
    except (TypeError, ValueError, OverflowError):  # a 400-digit integer overflows a float
        return None
    return number if math.isfinite(number) else None


def _require(d: dict, names: tuple[str, ...], why: str, problems: list[Problem]) -> None:
    for n in names:
        if d.get(n) is None:
            problems.append(Problem(n, None, f"a value ({why})"))


def _consistency(d: dict, problems: list[Problem]) -> None:
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
    if d.get("pivot_bushing_radial_thickness_mm") is not None:
        thick = sorted({float(t) for t in catalog.load("pivot_bushings")["radial_thickness_mm"]}) \
            if "pivot_bushings" in catalog.names() else []
        if thick and not any(abs(d["pivot_bushing_radial_thickness_mm"] - t) < 1e-9 for t in thick):
            problems.append(Problem("pivot_bushing_radial_thickness_mm", d["pivot_bushing_radial_thickness_mm"],
                                    "a supplier thickness: one of " + ", ".join(f"{t:g}" for t in thick) + " mm"))


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
        out[name] = _coerce(_BY_NAME[name], value, problems)
    return _finish(out, problems, partial)


_DEFAULTED = tuple(f for f in FIELDS if f.default is not None)
_REQUIRED = tuple(f for f in FIELDS if f.required)


def _finish(out: dict, problems: list[Problem], partial: bool = False) -> "DesignInput":
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
    _consistency(out, problems)
    if problems:
        raise InputError(problems)
    return DesignInput(**out)


def read_mapping(path: str | Path) -> dict:
    """Read a design input (YAML, TOML, JSON, the .xlsx template or a LibreOffice .ods) into a dict.

    The file goes through the input gate (:func:`synth.io.documents.read_design_mapping`):
    size, encoding, YAML aliases, nesting, huge and non-finite numbers are
    checked before anything is built; a case file's ``inputs:`` block is read.
    """
    from synth.io.documents import read_design_mapping
    return read_design_mapping(path)


def load_input(path: str | Path) -> "DesignInput":
    """Read and validate a design-input file (YAML, TOML or JSON; a case file works)."""
    return validate(read_mapping(path))


def parse_number_list(value):
    """A list-valued cell (a wire size: ``2.3 x 2.3``, ``2,5 x 2,5``, ``[2.3, 2.3]``, a number) as a list of floats.

    Text that does not parse is returned as it is, for :func:`validate` to
    report with the field's name. Used by the Excel and portfolio readers
    (:func:`synth.io.numbers.parse_number_list`).

    >>> parse_number_list("2.3 x 2.3"), parse_number_list("3"), parse_number_list(2.5), parse_number_list("abc")
    ([2.3, 2.3], [3.0], [2.5], 'abc')
    """
    return _parse_number_list(value)
