"""The drive input: every field declared once, read through the input gate, validated into a :class:`Drive`.

A drive file (YAML, TOML, JSON, or a workbook sheet named ``Drive``) has the
sections ``belt``, ``tensioner``, ``pulleys`` (a list in the belt's travel
order), ``excitation`` (speeds and the crank's orders, or the thesis's
irregularity, eq. (3)) and an optional ``solver``. Each field is declared in
:data:`FIELDS` (a :class:`synth.schema.Field`: unit, bounds, default, why);
the validator, the workbook reader and the docs read that one table. Every
problem is reported at once, naming the field as written
(``pulleys[2].radius_mm``) or the workbook cell (``Drive!B7``).

Workbook layout (sheet ``Drive``): column A the field (``belt.stiffness_n``),
column B its value; a row ``pulleys`` (and ``orders``) in column A starts a
table whose next row holds the column names (``name``, ``role``,
``radius_mm``...), one row per pulley until an empty row.

>>> d = example_drive()
>>> d.name, [p.name for p in d.pulleys], d.tensioner.arm_length_mm
('example timing drive (illustrative)', ['CRK', 'TEN', 'CAM', 'IDL', 'WP'], 4.0)
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass, replace
from pathlib import Path

from synth.errors import InputError, Problem
from synth.io.limits import short
from synth.io.numbers import is_not_given, number_from_text
from synth.schema import Field
from synth.drive.statics import static_state
from synth.io.files import existing_file, suffix_of
from synth.io.structured import read_document
from synth.io.workbook import read_sheet, column_letter

__all__ = ["FIELDS", "ROLES", "Pulley", "Tensioner", "Order", "Drive", "validate", "load_drive", "example_drive",
           "EXAMPLE_PATH", "DRIVE_SUFFIXES", "drive_from_mapping"]

INF = math.inf
ROLES = ("crank", "driven", "idler", "tensioner")
DRIVE_SUFFIXES = (".yaml", ".yml", ".toml", ".json", ".xlsx", ".xlsm", ".ods")
EXAMPLE_PATH = Path(__file__).resolve().parents[1] / "data" / "drives" / "example_timing_drive.yaml"

_POS = dict(lo=0.0, lo_open=True)
_COORD = dict(lo=-2000.0, hi=2000.0, basis="an engine front is well within 2 m")


def _f(name, section, unit="-", **kw) -> Field:
    return Field(name=name, section=section, unit=unit, **kw)


#: every field of a drive input; ``section`` is the mapping it sits in (``pulleys`` and ``orders``: one per row)
FIELDS: tuple[Field, ...] = (
    _f("name", "drive", kind="str", required=False, default="drive", label="Drive name"),
    _f("stiffness_n", "belt", "N", **_POS, hi=1e7, label="Belt stiffness EA per unit strain (span: EA/L)",
       basis="automotive timing and poly-V belts: EA 1e4-5e5 N; 1e7 is twenty times the stiffest"),
    _f("damping_n_s", "belt", "N s", required=False, lo=0.0, hi=1e4, default=0.0,
       label="Belt damping c' per unit strain (span: c'/L)"),
    _f("min_tension_n", "belt", "N", required=False, lo=0.0, hi=1e4, default=0.0,
       label="Lowest effective span tension before the belt counts as slack"),
    _f("friction_coefficient", "belt", required=False, **_POS, hi=3.0,
       label="Belt-pulley friction coefficient (poly-V: effective; empty: no slip margin, a toothed belt)"),
    _f("pivot_x_mm", "tensioner", "mm", **_COORD, label="Tensioner pivot x"),
    _f("pivot_y_mm", "tensioner", "mm", **_COORD, label="Tensioner pivot y"),
    _f("arm_length_mm", "tensioner", "mm", **_POS, hi=200, label="Arm length (the working arm)"),
    _f("arm_angle_deg", "tensioner", "deg", lo=-360, hi=360, label="Nominal arm angle (counter-clockwise from +x)"),
    _f("inertia_kg_m2", "tensioner", "kg m2", **_POS, hi=1.0, label="Arm and pulley inertia about the pivot"),
    _f("stiffness_nm_per_deg", "tensioner", "Nm/deg", **_POS, hi=10, label="Spring stiffness",
       basis="the design input's spring_stiffness_nm_per_deg bound"),
    _f("nominal_torque_nm", "tensioner", "Nm", **_POS, hi=100, label="Arm torque at nominal (calculated torque)"),
    _f("friction_torque_nm", "tensioner", "Nm", lo=0.0, hi=100, label="Friction torque (the damping)"),
    _f("damping_nm_s_per_rad", "tensioner", "Nm s/rad", required=False, lo=0.0, hi=100, default=0.0,
       label="Viscous damping of the arm"),
    _f("name", "pulleys", kind="str", label="Pulley name"),
    _f("role", "pulleys", kind="str", required=False, choices=ROLES, default="driven",
       label="crank (drives), driven, idler or tensioner (its centre follows the arm)"),
    _f("x_mm", "pulleys", "mm", required=False, **_COORD, label="Centre x (not for the tensioner)"),
    _f("y_mm", "pulleys", "mm", required=False, **_COORD, label="Centre y (not for the tensioner)"),
    _f("radius_mm", "pulleys", "mm", **_POS, hi=500, label="Pitch radius"),
    _f("inertia_kg_m2", "pulleys", "kg m2", required=False, **_POS, hi=10.0,
       label="Inertia with what it drives (not for the crank)"),
    _f("load_torque_nm", "pulleys", "Nm", required=False, lo=-1000, hi=1000, default=0.0,
       label="Mean load torque (driven pulleys)"),
    _f("damping_nm_s_per_rad", "pulleys", "Nm s/rad", required=False, lo=0.0, hi=100, default=0.0,
       label="Viscous damping of the pulley's shaft"),
    _f("torque_order", "pulleys", required=False, **_POS, hi=50,
       label="Order of the load torque's fluctuation (a camshaft of 4 cylinders: 2), a multiple of 0.5"),
    _f("torque_amplitude_nm", "pulleys", "Nm", required=False, lo=0.0, hi=1000, default=0.0,
       label="Amplitude of the load torque's fluctuation"),
    _f("torque_phase_deg", "pulleys", "deg", required=False, lo=-360, hi=360, default=0.0,
       label="Phase of the load torque's fluctuation"),
    _f("backside", "pulleys", kind="str", required=False, choices=("true", "false"), default="false",
       label="The belt's back on the pulley (outside the loop)"),
    _f("speed_min_rpm", "excitation", "rpm", **_POS, hi=20000, label="Lowest engine speed of the sweep"),
    _f("speed_max_rpm", "excitation", "rpm", **_POS, hi=20000, label="Highest engine speed of the sweep"),
    _f("speeds", "excitation", kind="int", required=False, lo=2, hi=1000, default=50, label="Speeds in the sweep"),
    _f("durability_speed_rpm", "excitation", "rpm", required=False, **_POS, hi=20000,
       label="Engine speed of the durability test (theta_pp and f are taken there)"),
    _f("irregularity", "excitation", required=False, **_POS, hi=2.0,
       label="Kinematic irregularity delta (thesis eq. (3)) of the firing order; instead of orders"),
    _f("firing_order", "excitation", required=False, **_POS, hi=50, label="Order of the irregularity (4 cylinders: 2)"),
    _f("order", "orders", **_POS, hi=50, label="Order (a multiple of 0.5)"),
    _f("amplitude_deg", "orders", "deg", lo=0.0, hi=30, label="Crank angle amplitude of the order"),
    _f("phase_deg", "orders", "deg", required=False, lo=-360, hi=360, default=0.0, label="Phase"),
    _f("harmonics", "solver", kind="int", required=False, lo=4, hi=400, default=24,
       label="Harmonics of the base frequency in the harmonic balance"),
    _f("regularisation", "solver", required=False, **_POS, hi=0.5, default=0.01,
       label="Friction regularisation eps / peak arm speed without friction"),
    _f("tolerance", "solver", required=False, **_POS, hi=0.5, default=0.05,
       label="Largest relative move of the answer when the regularisation is halved and the harmonics doubled"),
)

_SECTIONS = ("belt", "tensioner", "pulleys", "excitation", "solver")
_BY = {(f.section, f.name): f for f in FIELDS}


@dataclass(frozen=True)
class Pulley:
    """A pulley of the drive (lengths mm, inertia kg m^2, torques N m)."""

    name: str
    role: str
    x_mm: float
    y_mm: float
    radius_mm: float
    inertia_kg_m2: float
    load_torque_nm: float = 0.0
    damping_nm_s_per_rad: float = 0.0
    backside: bool = False
    torque_order: float = 0.0
    torque_amplitude_nm: float = 0.0
    torque_phase_deg: float = 0.0


@dataclass(frozen=True)
class Tensioner:
    """The automatic tensioner as the drive sees it: pivot, arm, inertia, spring, nominal torque, friction."""

    pivot_x_mm: float
    pivot_y_mm: float
    arm_length_mm: float
    arm_angle_deg: float
    inertia_kg_m2: float
    stiffness_nm_per_deg: float
    nominal_torque_nm: float
    friction_torque_nm: float
    damping_nm_s_per_rad: float = 0.0


@dataclass(frozen=True)
class Order:
    """One order of the crank's angular fluctuation: ``A cos(n Omega t + phase)``."""

    order: float
    amplitude_deg: float
    phase_deg: float = 0.0


@dataclass(frozen=True)
class Drive:
    """A validated drive (hashable: it can sit in :class:`synth.design.evaluate.Settings`)."""

    name: str
    pulleys: tuple
    tensioner: Tensioner
    belt_stiffness_n: float
    belt_damping_n_s: float
    orders: tuple
    speed_min_rpm: float
    speed_max_rpm: float
    speeds: int = 50
    durability_speed_rpm: float | None = None
    belt_min_tension_n: float = 0.0
    belt_friction_coefficient: float | None = None
    harmonics: int = 24
    regularisation: float = 0.01
    tolerance: float = 0.05

    @property
    def crank_index(self) -> int:
        return next(i for i, p in enumerate(self.pulleys) if p.role == "crank")

    @property
    def tensioner_index(self) -> int:
        return next(i for i, p in enumerate(self.pulleys) if p.role == "tensioner")

    def speeds_rpm(self):
        import numpy as np
        return np.linspace(self.speed_min_rpm, self.speed_max_rpm, self.speeds)

    def with_tensioner(self, **changes) -> "Drive":
        """A copy with some tensioner values changed (the synthesised design's)."""
        return replace(self, tensioner=replace(self.tensioner, **changes))

    def to_dict(self) -> dict:
        """The drive as a drive-file mapping (:func:`validate` reads it back)."""
        t = asdict(self.tensioner)
        out = {"name": self.name,
               "belt": {"stiffness_n": self.belt_stiffness_n, "damping_n_s": self.belt_damping_n_s,
                        "min_tension_n": self.belt_min_tension_n},
               "pulleys": [_pulley_dict(p) for p in self.pulleys],
               "tensioner": t,
               "excitation": {"speed_min_rpm": self.speed_min_rpm, "speed_max_rpm": self.speed_max_rpm,
                              "speeds": self.speeds, "orders": [asdict(o) for o in self.orders]},
               "solver": {"harmonics": self.harmonics, "regularisation": self.regularisation,
                          "tolerance": self.tolerance}}
        if self.durability_speed_rpm is not None:
            out["excitation"]["durability_speed_rpm"] = self.durability_speed_rpm
        if self.belt_friction_coefficient is not None:
            out["belt"]["friction_coefficient"] = self.belt_friction_coefficient
        return out


def _pulley_dict(p: Pulley) -> dict:
    out = {**asdict(p), "backside": "true" if p.backside else "false"}
    if p.torque_amplitude_nm == 0:
        for k in ("torque_order", "torque_amplitude_nm", "torque_phase_deg"):
            out.pop(k)
    if p.role == "crank" and p.inertia_kg_m2 == 0:
        out.pop("inertia_kg_m2")
    if p.role == "tensioner":
        out.pop("x_mm"), out.pop("y_mm")
    return out


def _value(f: Field, raw, where: str, problems: list):
    """One field's value (the default when not given), or a Problem naming ``where``."""
    if raw is None or is_not_given(raw):
        if f.required and f.default is None:
            problems.append(Problem(where, None, "a value (required); " + f.accepted()))
        return f.default
    if f.choices:
        text = str(raw).strip().lower() if not isinstance(raw, (dict, list)) else None
        if isinstance(raw, bool):
            text = "true" if raw else "false"
        if text not in f.choices:
            problems.append(Problem(where, short(raw), f.accepted()))
            return None
        return text
    if f.kind == "str":
        if isinstance(raw, (dict, list, bool)):
            problems.append(Problem(where, short(raw), "a text"))
            return None
        return str(raw).strip()
    x = number_from_text(raw) if isinstance(raw, str) else (
        None if isinstance(raw, bool) or not isinstance(raw, (int, float)) else float(raw))
    if x is None or not math.isfinite(x):
        problems.append(Problem(where, short(raw), f.accepted()))
        return None
    below = x <= f.lo if f.lo_open else x < f.lo
    above = x >= f.hi if f.hi_open else x > f.hi
    if below or above or (f.kind == "int" and x != int(x)):
        problems.append(Problem(where, short(raw), f.accepted() + (f" ({f.basis})" if f.basis and above else "")))
        return None
    return int(x) if f.kind == "int" else x


def _section(data: dict, section: str, prefix: str, problems: list, skip=()) -> dict:
    """The declared fields of ``section`` read from mapping ``data`` (unknown keys are problems)."""
    if not isinstance(data, dict):
        problems.append(Problem(prefix.rstrip(".") or section, short(data), "a mapping of field names to values"))
        return {}
    known = {f.name: f for f in FIELDS if f.section == section}
    out = {}
    for k in data:
        if str(k) not in known and str(k) not in skip:
            problems.append(Problem(f"{prefix}{short(k)}", short(data[k]),
                                    "one of the keys " + ", ".join(list(known) + list(skip))))
    for name, f in known.items():
        out[name] = _value(f, data.get(name), f"{prefix}{name}", problems)
    return out


def validate(data) -> Drive:
    """Validate a drive mapping (the parsed file) into a :class:`Drive`; every problem at once.

    >>> try:
    ...     validate({"belt": {"stiffness_n": -1}})
    ... except InputError as exc:
    ...     print(exc.problems[0])
    belt.stiffness_n: got -1; accepted: a number in (0, 1e+07] N
    """
    if not isinstance(data, dict):
        raise InputError(Problem("drive file", type(data).__name__, "a mapping with belt, tensioner, pulleys, "
                                                                     "excitation (and solver)"))
    problems: list[Problem] = []
    for k in data:
        if k not in _SECTIONS and k != "name":
            problems.append(Problem(short(k), "a section", "one of the sections name, " + ", ".join(_SECTIONS)))
    name = _value(_BY[("drive", "name")], data.get("name"), "name", problems)
    belt = _section(data.get("belt"), "belt", "belt.", problems)
    ten = _section(data.get("tensioner"), "tensioner", "tensioner.", problems)
    exc = _section(data.get("excitation"), "excitation", "excitation.", problems, skip=("orders",))
    solver = _section(data.get("solver") or {}, "solver", "solver.", problems)
    raw_pulleys = data.get("pulleys")
    pulleys = []
    if not isinstance(raw_pulleys, list) or len(raw_pulleys) < 3:
        problems.append(Problem("pulleys", short(raw_pulleys), "a list of at least three pulleys (crank, tensioner "
                                                               "and one more) in the belt's travel order"))
        raw_pulleys = raw_pulleys if isinstance(raw_pulleys, list) else []
    for i, rp in enumerate(raw_pulleys):
        v = _section(rp, "pulleys", f"pulleys[{i}].", problems)
        if not v:
            continue
        where = f"pulleys[{i}]"
        role = v.get("role") or "driven"
        if role != "tensioner":
            for key in ("x_mm", "y_mm"):
                if v.get(key) is None and not any(p.field == f"{where}.{key}" for p in problems):
                    problems.append(Problem(f"{where}.{key}", None, "a value (every pulley but the tensioner has a "
                                                                    "fixed centre)"))
        if role != "crank" and v.get("inertia_kg_m2") is None and not any(
                p.field == f"{where}.inertia_kg_m2" for p in problems):
            problems.append(Problem(f"{where}.inertia_kg_m2", None, "a value (every pulley but the crank, whose "
                                                                    "motion is given, has an inertia)"))
        for key in ("load_torque_nm", "torque_amplitude_nm"):
            if role in ("idler", "tensioner", "crank") and (v.get(key) or 0.0) != 0.0:
                problems.append(Problem(f"{where}.{key}", v[key], f"0 for a {role} pulley"))
        if (v.get("torque_amplitude_nm") or 0.0) > 0:
            o = v.get("torque_order")
            if o is None or abs(2 * o - round(2 * o)) > 1e-9:
                problems.append(Problem(f"{where}.torque_order", o, "a multiple of 0.5 (the order of the load "
                                                                    "torque's fluctuation)"))
        pulleys.append(Pulley(name=v.get("name") or f"P{i + 1}", role=role, x_mm=v.get("x_mm") or 0.0,
                              y_mm=v.get("y_mm") or 0.0, radius_mm=v.get("radius_mm") or 1.0,
                              inertia_kg_m2=v.get("inertia_kg_m2") or 0.0, load_torque_nm=v.get("load_torque_nm") or 0.0,
                              damping_nm_s_per_rad=v.get("damping_nm_s_per_rad") or 0.0,
                              backside=v.get("backside") == "true", torque_order=v.get("torque_order") or 0.0,
                              torque_amplitude_nm=v.get("torque_amplitude_nm") or 0.0,
                              torque_phase_deg=v.get("torque_phase_deg") or 0.0))
    if raw_pulleys:
        for role in ("crank", "tensioner"):
            n = sum(p.role == role for p in pulleys)
            if n != 1:
                problems.append(Problem("pulleys", f"{n} pulleys with role {role}", f"exactly one {role} pulley"))
        names = [p.name for p in pulleys]
        dup = sorted({n for n in names if names.count(n) > 1})
        if dup:
            problems.append(Problem("pulleys", ", ".join(dup), "distinct pulley names"))
    orders = []
    raw_orders = (data.get("excitation") or {}).get("orders") if isinstance(data.get("excitation"), dict) else None
    if raw_orders is not None:
        if not isinstance(raw_orders, list) or not raw_orders:
            problems.append(Problem("excitation.orders", short(raw_orders), "a list of {order, amplitude_deg, phase_deg}"))
        else:
            for i, ro in enumerate(raw_orders):
                v = _section(ro, "orders", f"excitation.orders[{i}].", problems)
                if v and v.get("order") is not None and abs(2 * v["order"] - round(2 * v["order"])) > 1e-9:
                    problems.append(Problem(f"excitation.orders[{i}].order", v["order"],
                                            "a multiple of 0.5 (a four-stroke cycle is two revolutions)"))
                elif v and None not in (v.get("order"), v.get("amplitude_deg")):
                    orders.append(Order(v["order"], v["amplitude_deg"], v.get("phase_deg") or 0.0))
    if exc.get("irregularity") is not None:
        if raw_orders is not None:
            problems.append(Problem("excitation.irregularity", exc["irregularity"], "either orders or irregularity"))
        elif exc.get("firing_order") is None:
            problems.append(Problem("excitation.firing_order", None, "the order of the irregularity (4 cylinders: 2)"))
        else:
            n = exc["firing_order"]
            # eq. (3): delta = (w_max - w_min) / w_mean = 2 n A for theta_c = A cos(n Omega t)
            orders.append(Order(n, math.degrees(exc["irregularity"] / (2.0 * n)), 0.0))
    elif raw_orders is None and data.get("excitation") is not None:
        problems.append(Problem("excitation.orders", None, "the crank's orders, or irregularity with firing_order"))
    if None not in (exc.get("speed_min_rpm"), exc.get("speed_max_rpm")) and exc["speed_min_rpm"] >= exc["speed_max_rpm"]:
        problems.append(Problem("excitation.speed_max_rpm", exc["speed_max_rpm"],
                                f"a speed above speed_min_rpm = {exc['speed_min_rpm']:g} rpm"))
    if problems:
        raise InputError(problems)
    drive = Drive(name=name or "drive", pulleys=tuple(pulleys), tensioner=Tensioner(**ten),
                  belt_stiffness_n=belt["stiffness_n"], belt_damping_n_s=belt["damping_n_s"], orders=tuple(orders),
                  speed_min_rpm=exc["speed_min_rpm"], speed_max_rpm=exc["speed_max_rpm"], speeds=exc["speeds"],
                  durability_speed_rpm=exc.get("durability_speed_rpm"), belt_min_tension_n=belt["min_tension_n"],
                  belt_friction_coefficient=belt.get("friction_coefficient"), harmonics=solver["harmonics"],
                  regularisation=solver["regularisation"], tolerance=solver["tolerance"])
    static_state(drive)  # a belt path that cannot exist is an input error now, not later
    return drive


def load_drive(path) -> Drive:
    """Read and validate a drive file: YAML, TOML, JSON (through :func:`synth.io.structured.read_document`) or
    the ``Drive`` sheet of a workbook (:func:`synth.io.workbook.read_sheet`)."""
    accepted = "an existing drive file: .yaml, .yml, .toml, .json, or a workbook (.xlsx, .ods) with a Drive sheet"
    suffix = suffix_of(path)
    if suffix not in DRIVE_SUFFIXES:
        existing_file(path, "--drive", accepted)
        raise InputError(Problem("--drive", str(path), accepted + " (by its extension)"))
    if suffix in (".xlsx", ".xlsm", ".ods"):
        return _from_sheet(path)
    data = read_document(path, "--drive", accepted=accepted)
    if data is None:
        raise InputError(Problem("--drive", str(path), "a drive mapping (the file is empty)"))
    if isinstance(data, dict):
        data.setdefault("name", Path(path).stem)
    return validate(data)


def _from_sheet(path) -> Drive:
    """The ``Drive`` sheet as a drive mapping; problems name the sheet and cell."""
    ws = read_sheet(path, "--drive", "Drive")
    data: dict = {"name": Path(path).stem}
    cell_of: dict[str, str] = {}
    rows = sorted({int("".join(ch for ch in a if ch.isdigit())) for a in ws.cells})
    i = 0
    while i < len(rows):
        r = rows[i]
        key = ws.value(f"A{r}")
        key = str(key).strip() if key is not None else ""
        if key in ("pulleys", "orders"):
            header_row = r + 1
            cols = []
            c = 2 if ws.value(f"A{header_row}") is None else 1
            while ws.value(f"{column_letter(c)}{header_row}") is not None:
                cols.append((column_letter(c), str(ws.value(f"{column_letter(c)}{header_row}")).strip()))
                c += 1
            items, rr = [], header_row + 1
            while any(ws.value(f"{col}{rr}") is not None for col, _ in cols):
                items.append({name: ws.value(f"{col}{rr}") for col, name in cols})
                for col, name in cols:
                    cell_of[f"{'excitation.' if key == 'orders' else ''}{key}[{len(items) - 1}].{name}"] = f"{col}{rr}"
                rr += 1
            if key == "orders":
                data.setdefault("excitation", {})["orders"] = items
            else:
                data["pulleys"] = items
            i = next((k for k, x in enumerate(rows) if x >= rr), len(rows))
            continue
        if key and "." in key:
            section, field = key.split(".", 1)
            data.setdefault(section, {})[field] = ws.value(f"B{r}")
            cell_of[key] = f"B{r}"
        elif key == "name":
            data["name"] = ws.value(f"B{r}")
        i += 1
    try:
        return validate(data)
    except InputError as exc:
        raise InputError([Problem(f"{p.field} ({ws.title}!{cell_of[p.field]})" if p.field in cell_of else
                                  f"{p.field} (sheet {ws.title})", p.value, p.accepted) for p in exc.problems]) from None


def example_drive() -> Drive:
    """The shipped illustrative timing drive (``synth/data/drives/example_timing_drive.yaml``)."""
    return load_drive(EXAMPLE_PATH)


def drive_from_mapping(data) -> Drive:
    """A :class:`Drive` from a drive-file mapping or from ``dataclasses.asdict`` of one (a saved result's
    settings); a :class:`Drive` is returned as it is."""
    if isinstance(data, Drive) or data is None:
        return data
    if isinstance(data, dict) and "belt_stiffness_n" in data:
        d = dict(data)
        d["pulleys"] = tuple(Pulley(**p) for p in d["pulleys"])
        d["tensioner"] = Tensioner(**d["tensioner"])
        d["orders"] = tuple(Order(**o) for o in d["orders"])
        return Drive(**d)
    return validate(data)
