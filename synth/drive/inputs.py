"""The drive input: every field declared once, read through the input gate, validated into a :class:`Drive`.

A drive file (YAML, TOML, JSON, or a workbook sheet named ``Drive``) has the
sections ``belt``, ``tensioner``, ``pulleys`` (a list in the belt's travel
order), and the optional ``duty`` (a list of duty points: engine speed, share
of time, each pulley's power or torque), ``excitation`` (speeds and the
crank's orders, or the thesis's irregularity, eq. (3): the arm's periodic
response) and ``solver``. Each field is declared in :data:`FIELDS` (a
:class:`synth.schema.Field`: unit, bounds, default, why); the validator, the
workbook reader and the docs read that one table. Every problem is reported
at once, naming the field as written (``pulleys[2].radius_mm``) or the
workbook cell (``Drive!B7``).

A drive-design report states a drive the way this input reads it: pulleys
with their pitch and effective diameters and the side the belt wraps
(``backside``), the belt's ribs, length, tolerance, wear and thermal change,
the tensioner as pivot, arm and spring (free-arm angle, preload, rate, the
nominal torque or "spring mean load", the installation stop), and the
accessories' power per engine speed. The tensioner's nominal arm angle is
then derived (:func:`synth.drive.positions.nominal_angle_deg`); it can also be
stated (``arm_angle_deg``), as for the synthesised tensioner.

Workbook layout (sheet ``Drive``): column A the field (``belt.stiffness_n``),
column B its value; a row ``pulleys``, ``orders`` or ``duty`` in column A
starts a table whose next row holds the column names (``name``, ``role``,
``radius_mm``...; a duty point's loads as ``power_kw.ALT``, ``torque_nm.A_C``),
one row per entry until an empty row.

>>> d = example_drive()
>>> d.name, [p.name for p in d.pulleys], d.tensioner.arm_length_mm
('example timing drive (illustrative)', ['CRK', 'TEN', 'CAM', 'IDL', 'WP'], 4.0)
"""

from __future__ import annotations

import math
import sys
from pathlib import Path

from synth.errors import InputError, Problem
from synth.io.limits import short
from synth.io.numbers import is_not_given, number_from_text
from synth.schema import Field
from synth.drive import belt as belt_data
from synth.drive.positions import nominal_angle_deg
from synth.drive.model import Drive, DutyPoint, Order, Pulley, Tensioner
from synth.drive.fields import FIELDS, MAX_DUTY_POINTS, MAX_ORDERS, MAX_PULLEYS, ROLES
from synth.drive.statics import static_state
from synth.io.files import existing_file, suffix_of
from synth.io.structured import read_document
from synth.io.workbook import read_sheet, column_letter

__all__ = ["FIELDS", "ROLES", "Pulley", "Tensioner", "Order", "DutyPoint", "Drive", "validate", "load_drive",
           "example_drive", "EXAMPLE_PATH", "DRIVE_SUFFIXES", "drive_from_mapping", "MAX_PULLEYS", "MAX_DUTY_POINTS",
           "MAX_ORDERS"]

DRIVE_SUFFIXES = (".yaml", ".yml", ".toml", ".json", ".xlsx", ".xlsm", ".ods")
EXAMPLE_PATH = Path(__file__).resolve().parents[1] / "data" / "drives" / "example_timing_drive.yaml"

_SECTIONS = ("belt", "tensioner", "pulleys", "duty", "excitation", "solver")
_BY = {(f.section, f.name): f for f in FIELDS}


def _number(raw) -> float | None:
    """A finite float from a number or a text (decimal comma, ``%``), else None (never raises)."""
    if isinstance(raw, bool):
        return None
    if isinstance(raw, str):
        return number_from_text(raw)
    if not isinstance(raw, (int, float)):
        return None
    try:
        x = float(raw)
    except OverflowError:  # an integer of hundreds of digits
        return None
    return x if math.isfinite(x) else None


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
    x = _number(raw)
    if x is None:
        problems.append(Problem(where, short(raw), f.accepted()))
        return None
    if x != 0.0 and abs(x) < sys.float_info.min:
        problems.append(Problem(where, short(raw), f.accepted() + " (a subnormal number is no physical value)"))
        return None
    below = x <= f.lo if f.lo_open else x < f.lo
    above = x >= f.hi if f.hi_open else x > f.hi
    if below or above or (f.kind == "int" and x != int(x)):
        problems.append(Problem(where, short(raw), f.accepted() + (f" ({f.basis})" if f.basis and (above or below) else "")))
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
    belt.stiffness_n: got -1; accepted: a number in [1000, 1e+07] N (automotive timing and poly-V belts:
    EA 1e4-5e5 N; 1e7 is twenty times the stiffest, 1000 N a floor below any belt)
    """
    if not isinstance(data, dict):
        raise InputError(Problem("drive file", type(data).__name__, "a mapping with belt, tensioner, pulleys "
                                                                     "(and duty, excitation, solver)"))
    problems: list[Problem] = []
    for k in data:
        if k not in _SECTIONS and k != "name":
            problems.append(Problem(short(k), "a section", "one of the sections name, " + ", ".join(_SECTIONS)))
    name = _value(_BY[("drive", "name")], data.get("name"), "name", problems)
    belt = _section(data.get("belt"), "belt", "belt.", problems)
    ten = _section(data.get("tensioner"), "tensioner", "tensioner.", problems)
    given_exc = data.get("excitation") is not None
    exc = _section(data.get("excitation"), "excitation", "excitation.", problems, skip=("orders",)) \
        if given_exc else {}
    solver = _section(data.get("solver") or {}, "solver", "solver.", problems)
    pulleys = _pulleys(data.get("pulleys"), problems)
    orders = _orders(data.get("excitation"), exc, problems) if given_exc else []
    duty = _duty(data.get("duty"), [p.name for p in pulleys], problems)
    stiffness_n = _belt_stiffness(belt, problems)
    dynamic = bool(orders) or any(p.torque_amplitude_nm > 0 for p in pulleys)
    _nominal_problems(ten, belt, problems)
    if dynamic:
        _dynamic_problems(pulleys, ten, exc, problems)
    if problems:
        raise InputError(problems)
    nominal_from = "angle" if ten.get("arm_angle_deg") is not None else (
        "torque" if ten.get("nominal_torque_nm") is not None else "belt")
    if nominal_from != "angle":
        belt_given = {**belt, "ribs": belt.get("ribs")}
        ten.update(nominal_angle_deg(tuple(pulleys), ten, belt_given))
        ten.pop("sense")
    elif ten.get("free_arm_angle_deg") is not None:
        rel = abs((ten["arm_angle_deg"] - ten["free_arm_angle_deg"] + 180.0) % 360.0 - 180.0)
        ten["preload_nm"] = ten["nominal_torque_nm"] - ten["stiffness_nm_per_deg"] * rel
    drive = Drive(name=name or "drive", pulleys=tuple(pulleys), tensioner=Tensioner(**ten, nominal_from=nominal_from),
                  belt_stiffness_n=stiffness_n, belt_damping_n_s=belt["damping_n_s"], orders=tuple(orders),
                  speed_min_rpm=exc.get("speed_min_rpm"), speed_max_rpm=exc.get("speed_max_rpm"),
                  speeds=exc.get("speeds") or 50, durability_speed_rpm=exc.get("durability_speed_rpm"),
                  belt_min_tension_n=belt["min_tension_n"], belt_friction_coefficient=belt.get("friction_coefficient"),
                  harmonics=solver["harmonics"], regularisation=solver["regularisation"], tolerance=solver["tolerance"],
                  belt_ribs=belt.get("ribs"), belt_length_mm=belt.get("length_mm"),
                  belt_length_tolerance_mm=belt["length_tolerance_mm"], belt_wear_pct=belt["wear_pct"],
                  belt_thermal_change_pct=belt["thermal_change_pct"],
                  belt_elongation_stiffness_per_rib_n=belt["elongation_stiffness_per_rib_n"],
                  belt_measuring_tension_per_rib_n=belt["measuring_tension_per_rib_n"], duty=tuple(duty),
                  belt_stiffness_per_rib_n=None if belt.get("stiffness_n") is not None else belt["stiffness_per_rib_n"])
    static_state(drive)  # a belt path that cannot exist is an input error now, not later
    _stop_problems(drive)
    return drive


def _pulleys(raw_pulleys, problems: list) -> list:
    pulleys = []
    if not isinstance(raw_pulleys, list) or not 3 <= len(raw_pulleys) <= MAX_PULLEYS:
        problems.append(Problem("pulleys", short(raw_pulleys) if not isinstance(raw_pulleys, list)
                                else f"{len(raw_pulleys)} pulleys",
                                f"a list of 3 to {MAX_PULLEYS} pulleys (crank, tensioner and one more) in the belt's "
                                "travel order"))
        raw_pulleys = raw_pulleys if isinstance(raw_pulleys, list) and len(raw_pulleys) <= MAX_PULLEYS else []
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
        radius = v.get("radius_mm")
        if (radius is None) == (v.get("pitch_diameter_mm") is None):
            if not any(p.field in (f"{where}.radius_mm", f"{where}.pitch_diameter_mm") for p in problems):
                problems.append(Problem(f"{where}.radius_mm", radius, "either radius_mm or pitch_diameter_mm (the "
                                                                      "pitch line's size, once)"))
        elif radius is None:
            radius = v["pitch_diameter_mm"] / 2.0
        for key in ("load_torque_nm", "torque_amplitude_nm"):
            if role in ("idler", "tensioner", "crank") and (v.get(key) or 0.0) != 0.0:
                problems.append(Problem(f"{where}.{key}", v[key], f"0 for a {role} pulley"))
        if (v.get("torque_amplitude_nm") or 0.0) > 0:
            o = v.get("torque_order")
            if o is None or abs(2 * o - round(2 * o)) > 1e-9:
                problems.append(Problem(f"{where}.torque_order", o, "a multiple of 0.5 (the order of the load "
                                                                    "torque's fluctuation)"))
        eff = v.get("effective_diameter_mm")
        pulleys.append(Pulley(name=v.get("name") or f"P{i + 1}", role=role, x_mm=v.get("x_mm") or 0.0,
                              y_mm=v.get("y_mm") or 0.0, radius_mm=radius or 1.0,
                              inertia_kg_m2=v.get("inertia_kg_m2"), load_torque_nm=v.get("load_torque_nm") or 0.0,
                              damping_nm_s_per_rad=v.get("damping_nm_s_per_rad") or 0.0,
                              backside=v.get("backside") == "true", torque_order=v.get("torque_order") or 0.0,
                              torque_amplitude_nm=v.get("torque_amplitude_nm") or 0.0,
                              torque_phase_deg=v.get("torque_phase_deg") or 0.0,
                              effective_radius_mm=None if eff is None else eff / 2.0))
    if raw_pulleys:
        for role in ("crank", "tensioner"):
            n = sum(p.role == role for p in pulleys)
            if n != 1:
                problems.append(Problem("pulleys", f"{n} pulleys with role {role}", f"exactly one {role} pulley"))
        names = [p.name for p in pulleys]
        dup = sorted({n for n in names if names.count(n) > 1})
        if dup:
            problems.append(Problem("pulleys", ", ".join(dup), "distinct pulley names"))
    return pulleys


def _orders(raw_exc, exc: dict, problems: list) -> list:
    orders = []
    raw_orders = raw_exc.get("orders") if isinstance(raw_exc, dict) else None
    if raw_orders is not None:
        if not isinstance(raw_orders, list) or not 1 <= len(raw_orders) <= MAX_ORDERS:
            problems.append(Problem("excitation.orders", short(raw_orders),
                                    f"a list of 1 to {MAX_ORDERS} {{order, amplitude_deg, phase_deg}}"))
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
    elif raw_orders is None:
        problems.append(Problem("excitation.orders", None, "the crank's orders, or irregularity with firing_order"))
    if None not in (exc.get("speed_min_rpm"), exc.get("speed_max_rpm")) and exc["speed_min_rpm"] >= exc["speed_max_rpm"]:
        problems.append(Problem("excitation.speed_max_rpm", exc["speed_max_rpm"],
                                f"a speed above speed_min_rpm = {exc['speed_min_rpm']:g} rpm"))
    return orders


def _duty(raw, names: list, problems: list) -> list:
    """The duty points; a workbook's flattened ``power_kw.ALT`` columns are read as the ``power_kw`` mapping."""
    if raw is None:
        return []
    if not isinstance(raw, list) or not 1 <= len(raw) <= MAX_DUTY_POINTS:
        problems.append(Problem("duty", short(raw) if not isinstance(raw, list) else f"{len(raw)} points",
                                f"a list of 1 to {MAX_DUTY_POINTS} duty points {{speed_rpm, time_pct, power_kw: "
                                "{pulley: kW}, torque_nm: {pulley: N m}}"))
        return []
    out = []
    for i, row in enumerate(raw):
        where = f"duty[{i}]"
        if not isinstance(row, dict):
            problems.append(Problem(where, short(row), "a mapping of speed_rpm, time_pct, power_kw, torque_nm"))
            continue
        row = dict(row)
        loads = {}
        for kind in ("power_kw", "torque_nm"):
            mapping = row.pop(kind, None)
            flat = {str(k).split(".", 1)[1]: row.pop(k) for k in list(row) if str(k).startswith(kind + ".")}
            if mapping is not None and not isinstance(mapping, dict):
                problems.append(Problem(f"{where}.{kind}", short(mapping), "a mapping of pulley names to values"))
                mapping = {}
            items = {**(mapping or {}), **{k: v for k, v in flat.items() if not is_not_given(v)}}
            values = []
            for key, value in items.items():
                if str(key) not in names:
                    problems.append(Problem(f"{where}.{kind}.{short(key)}", short(value),
                                            "a pulley name: " + ", ".join(names)))
                    continue
                x = _value(_BY[("loads", kind)], value, f"{where}.{kind}.{key}", problems)
                if x is not None:
                    values.append((str(key), x))
            loads[kind] = tuple(values)
        v = _section(row, "duty", f"{where}.", problems)
        if v and v.get("speed_rpm") is not None:
            out.append(DutyPoint(v["speed_rpm"], v.get("time_pct"), loads["power_kw"], loads["torque_nm"]))
    return out


def _belt_stiffness(belt: dict, problems: list) -> float | None:
    if belt.get("stiffness_n") is not None:
        return belt["stiffness_n"]
    if belt.get("ribs") is not None:
        return belt["ribs"] * belt["stiffness_per_rib_n"]
    problems.append(Problem("belt.stiffness_n", None, "a value, or belt.ribs (EA = ribs x stiffness_per_rib_n, "
                                                      f"default {belt_data.EA_PER_RIB_N:g} N per rib)"))
    return None


def _nominal_problems(ten: dict, belt: dict, problems: list) -> None:
    """The nominal position is stated once: the arm angle, or the free arm with its preload (and the nominal
    torque, or the belt's length and ribs)."""
    angle, free, pre, torque = (ten.get(k) for k in ("arm_angle_deg", "free_arm_angle_deg", "preload_nm",
                                                     "nominal_torque_nm"))
    if angle is not None and pre is not None:
        problems.append(Problem("tensioner.preload_nm", pre, "either arm_angle_deg or preload_nm (the nominal arm "
                                                             "angle or the spring's torque at the free arm: one "
                                                             "follows from the other)"))
    elif angle is not None:
        if torque is None:
            problems.append(Problem("tensioner.nominal_torque_nm", None, "a value (the spring's torque at the "
                                                                         "nominal arm angle)"))
    elif pre is not None or free is not None:
        if free is None or pre is None:
            problems.append(Problem("tensioner.free_arm_angle_deg" if free is None else "tensioner.preload_nm",
                                    None, "a value: free_arm_angle_deg and preload_nm state the spring together"))
        elif torque is None and (belt.get("length_mm") is None or belt.get("ribs") is None):
            problems.append(Problem("tensioner.nominal_torque_nm", None, "a value, or belt.length_mm with belt.ribs "
                                                                         "(the nominal angle then follows from the "
                                                                         "belt's length)"))
    else:
        problems.append(Problem("tensioner.arm_angle_deg", None, "the nominal arm angle, or free_arm_angle_deg with "
                                                                 "preload_nm"))


def _dynamic_problems(pulleys, ten: dict, exc: dict, problems: list) -> None:
    """The periodic response needs every inertia, the arm's friction and the sweep's speeds."""
    for i, p in enumerate(pulleys):
        if p.role != "crank" and p.inertia_kg_m2 is None and not any(
                q.field == f"pulleys[{i}].inertia_kg_m2" for q in problems):
            problems.append(Problem(f"pulleys[{i}].inertia_kg_m2", None, "a value (the excitation's response needs "
                                                                         "every pulley's inertia but the crank's)"))
    for key in ("inertia_kg_m2", "friction_torque_nm"):
        if ten.get(key) is None and not any(q.field == f"tensioner.{key}" for q in problems):
            problems.append(Problem(f"tensioner.{key}", None, "a value (the excitation's response needs it)"))
    for key in ("speed_min_rpm", "speed_max_rpm"):
        if exc.get(key) is None and not any(p.field == f"excitation.{key}" for p in problems):
            problems.append(Problem(f"excitation.{key}", None, "a value (the sweep's speeds)"))


def _stop_problems(drive) -> None:
    """The stops on the right sides: the free arm before the nominal position, the installation stop past it."""
    ten = drive.tensioner
    s = drive.loading_sense
    problems = []
    for key, sign, what in (("free_arm_angle_deg", -1.0, "before"), ("installation_angle_deg", 1.0, "past")):
        a = getattr(ten, key)
        if a is not None and sign * s * ((a - ten.arm_angle_deg + 180.0) % 360.0 - 180.0) < 0:
            problems.append(Problem(f"tensioner.{key}", a, f"an angle {what} the nominal arm angle "
                                    f"({ten.arm_angle_deg:.2f} deg) in the belt's loading sense "
                                    f"({'counter-clockwise' if s > 0 else 'clockwise'}): the belt pushes the arm "
                                    "from the free arm towards the installation stop"))
    if problems:
        raise InputError(problems)


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
    if ws.title != "Drive":
        raise InputError(Problem("--drive", str(path), "a workbook with a sheet named 'Drive' (this one has the sheets "
                                 + ", ".join(repr(n) for n in ws.sheetnames)[:300]
                                 + ("; a design input's workbook is read by synth design, not as a drive"
                                    if "Input" in ws.sheetnames else "") + ")"))
    data: dict = {"name": Path(path).stem}
    cell_of: dict[str, str] = {}
    rows = sorted({int("".join(ch for ch in a if ch.isdigit())) for a in ws.cells})
    i = 0
    while i < len(rows):
        r = rows[i]
        key = ws.value(f"A{r}")
        key = str(key).strip() if key is not None else ""
        if key in ("pulleys", "orders", "duty"):
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
                data[key] = items
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
        d["duty"] = tuple(DutyPoint(p["speed_rpm"], p.get("time_pct"),
                                    tuple((str(a), float(b)) for a, b in p.get("power_kw") or ()),
                                    tuple((str(a), float(b)) for a, b in p.get("torque_nm") or ()))
                          for p in d.get("duty") or ())
        return Drive(**d)
    return validate(data)
