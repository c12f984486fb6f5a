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
import json
import math
import re
from dataclasses import dataclass, field, fields as dc_fields, make_dataclass
from pathlib import Path
from typing import Any

from synth import catalog
from synth.errors import InputError, Problem

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

    def accepted(self) -> str:
        if self.choices:
            return "one of " + ", ".join(self.choices)
        if self.catalog:
            return "one of " + ", ".join(catalog.keys(self.catalog)) + f" (catalogs/{self.catalog}.csv)"
        if self.kind == "list":
            return f"a list of positive numbers [{self.unit}]"
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
       aliases=("application",)),
    _f("engine_fuel", "Application", kind="str", choices=("gasoline", "diesel"), label="Engine fuel"),
    # Pulley
    _f("pulley_shell_type", "Pulley", kind="str", choices=("flat", "toothed"), label="Pulley shell type"),
    _f("pulley_diameter_mm", "Pulley", "mm", **POS, hi=200, label="Pulley diameter"),
    _f("pulley_max_parallelism_eol_mm", "Pulley", "mm", required=False, **POS, hi=5, label="Pulley max parallelism at EOL"),
    # Tensioner geometrical data
    _f("belt_loading_type", "Tensioner geometrical data", kind="str",
       choices=("single_eccentric", "double_eccentric", "double_eccentric_crank_rod"), label="Belt loading type"),
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
    _f("max_axial_displacement_mm", "Space constraints", "mm", **POS, hi=300, label="Max axial displacement"),
    # Pivot
    _f("pivot_class_diameter_mm", "Pivot", "mm", required=False, **POS, hi=60,
       label="Pivot class diameter (empty: Table 2 standard)"),
    _f("pivot_bushing_radial_thickness_mm", "Pivot", "mm", required=False, **POS, hi=5,
       label="Pivot bushing radial thickness (supplier)"),
    # Durability test
    _f("durability_test", "Durability test", kind="str", required=False, choices=("defined", "assumed"),
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
       default="automatic", label="Main spring (automatic: search the catalog / manual: verify)"),
    _f("main_spring_material", "Main spring", kind="str", required=False, catalog="spring_materials",
       label="Main spring material (manual)"),
    _f("main_spring_wire_section", "Main spring", kind="str", required=False, choices=("round", "rectangular"),
       label="Wire section (manual)"),
    _f("main_spring_wire_size_mm", "Main spring", "mm", kind="list", required=False,
       label="Wire size: [d] or [b, h] (manual)"),
    _f("main_spring_mean_body_diameter_mm", "Main spring", "mm", required=False, **POS, hi=200,
       label="Mean body diameter (manual)"),
    # Bolt
    _f("tilting_safety_factor", "Bolt", required=False, **POS, hi=20, label="Tilting safety factor (target)"),
    _f("sliding_safety_factor", "Bolt", required=False, **POS, hi=20, label="Sliding safety factor (target)"),
    _f("bolt_mode", "Bolt", kind="str", required=False, choices=("automatic", "manual"), default="automatic",
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


def _coerce(f: Field, value: Any, problems: list[Problem]) -> Any:
    """Convert ``value`` to the field's kind, appending a problem on failure."""
    if value is None:
        return None
    if f.kind == "list":
        items = value if isinstance(value, (list, tuple)) else [value]
        try:
            out = [float(v) for v in items]
        except (TypeError, ValueError):
            problems.append(Problem(f.name, value, f.accepted()))
            return None
        if not out or any(not math.isfinite(v) or v <= 0 for v in out):
            problems.append(Problem(f.name, value, f.accepted()))
            return None
        return out
    if f.choices or f.catalog or f.kind == "str":
        text = str(value).strip()
        if f.choices:
            norm = text.lower().replace(" ", "_").replace("-", "_")
            if norm not in f.choices:
                problems.append(Problem(f.name, value, f.accepted()))
                return None
            return norm
        if f.catalog and text not in catalog.keys(f.catalog):
            problems.append(Problem(f.name, value, f.accepted()))
            return None
        return text
    if isinstance(value, bool):
        problems.append(Problem(f.name, value, f.accepted()))
        return None
    if isinstance(value, str):
        text = value.strip().rstrip("%").strip()
        try:
            value = float(text)
        except ValueError:
            problems.append(Problem(f.name, value, f.accepted()))
            return None
    try:
        number = float(value)
    except (TypeError, ValueError):
        problems.append(Problem(f.name, value, f.accepted()))
        return None
    if not math.isfinite(number):
        problems.append(Problem(f.name, value, f.accepted()))
        return None
    below = number <= f.lo if f.lo_open else number < f.lo
    above = number >= f.hi if f.hi_open else number > f.hi
    if below or above:
        problems.append(Problem(f.name, value, f.accepted()))
        return None
    if f.kind == "int":
        if number != int(number):
            problems.append(Problem(f.name, value, f.accepted()))
            return None
        return int(number)
    return number


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
    problems: list[Problem] = []
    out: dict[str, Any] = {}
    for key, value in data.items():
        name = _ALIASES.get(key, key)
        if name not in _BY_NAME:
            near = difflib.get_close_matches(str(key), list(_BY_NAME), n=1)
            hint = f" (did you mean {near[0]}?)" if near else ""
            problems.append(Problem(str(key), value, "a known design-input field" + hint))
            continue
        out[name] = _coerce(_BY_NAME[name], value, problems)
    for f in FIELDS:
        if out.get(f.name) is None and f.default is not None:
            out[f.name] = f.default
    if not partial:
        for f in FIELDS:
            if f.required and out.get(f.name) is None and not any(p.field == f.name for p in problems):
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
    """Read a YAML, TOML, JSON or Excel (.xlsx template) file into a dict (the ``inputs:`` block if any)."""
    p = Path(path)
    if p.suffix.lower() in (".xlsx", ".xlsm"):  # the Excel input template (synth template)
        from synth.excel.reader import read_workbook
        return read_workbook(p)
    if not p.is_file():
        raise InputError(Problem("input file", str(p), "an existing .yaml, .yml, .toml, .json or .xlsx file"))
    text = p.read_text(encoding="utf-8")
    suffix = p.suffix.lower()
    try:
        if suffix in (".yaml", ".yml"):
            import yaml
            data = yaml.safe_load(text)
        elif suffix == ".toml":
            import tomllib
            data = tomllib.loads(text)
        elif suffix == ".json":
            data = json.loads(text)
        else:
            raise InputError(Problem("input file", str(p), "a file ending in .yaml, .yml, .toml or .json"))
    except InputError:
        raise
    except Exception as exc:  # parser errors carry line numbers: keep them
        raise InputError(Problem("input file", str(p), f"valid {suffix[1:].upper()} ({exc})")) from None
    if not isinstance(data, dict):
        raise InputError(Problem("input file", str(p), "a mapping of field names to values"))
    if "inputs" in data:
        data = data["inputs"]
    return data or {}


def load_input(path: str | Path) -> "DesignInput":
    """Read and validate a design-input file (YAML, TOML or JSON; a case file works)."""
    return validate(read_mapping(path))


def parse_number_list(value):
    """A list-valued cell (a wire size: ``2.3 x 2.3``, ``2.3; 2.3``, ``[2.3, 2.3]``, a number) as a list of floats.

    Text that does not parse is returned as it is, for :func:`validate` to
    report with the field's name. Used by the Excel and portfolio readers.

    >>> parse_number_list("2.3 x 2.3"), parse_number_list("3"), parse_number_list(2.5), parse_number_list("abc")
    ([2.3, 2.3], [3.0], [2.5], 'abc')
    """
    import numpy as np
    if isinstance(value, (list, tuple, np.ndarray)):
        return [float(v) if isinstance(v, (int, float, np.number)) else v for v in value]
    if isinstance(value, (int, float, np.number)):
        return [float(value)]
    parts = [p for p in re.split(r"[x×X;,\s\[\]]+", str(value)) if p]
    try:
        return [float(p) for p in parts]
    except ValueError:
        return value
