"""The drive input's fields, each declared once (:class:`synth.schema.Field`: section, unit, bounds with their basis,
default, label): the validator (:func:`synth.drive.inputs.validate`), the workbook reader and the docs read this
one table; and the count bounds of its lists.
"""

from __future__ import annotations

import math

from synth.drive import belt as belt_data
from synth.schema import Field

__all__ = ["FIELDS", "ROLES", "MAX_PULLEYS", "MAX_DUTY_POINTS", "MAX_ORDERS"]

INF = math.inf
ROLES = ("crank", "driven", "idler", "tensioner")
#: count bounds of the lists (each entry is a row of small dense algebra; see docs/sections/drive.md, "Bounds")
MAX_PULLEYS = 40
MAX_DUTY_POINTS = 200
MAX_ORDERS = 20

_COORD = dict(lo=-2000.0, hi=2000.0, basis="an engine front is well within 2 m")
_RADIUS = dict(lo=1.0, hi=500.0, basis="the smallest pulley of any belt drive is several mm; 1 mm is a floor "
                                       "(a subnormal radius made the span matrix singular)")
_INERTIA = dict(lo=1e-9, hi=10.0, basis="1e-9 kg m2 is a 2 mm steel disc; 10 kg m2 is beyond a truck's flywheel "
                                        "(a subnormal inertia made the mass matrix singular)")
_POWER = dict(lo=-500.0, hi=500.0, basis="an accessory or a belt starter-generator draws or gives well under 500 kW")


def _f(name, section, unit="-", **kw) -> Field:
    return Field(name=name, section=section, unit=unit, **kw)


#: every field of a drive input; ``section`` is the mapping it sits in (``pulleys``, ``orders``, ``duty``: one per
#: row; ``loads``: the values of a duty point's ``power_kw`` and ``torque_nm`` mappings)
FIELDS: tuple[Field, ...] = (
    _f("name", "drive", kind="str", required=False, default="drive", label="Drive name"),
    _f("stiffness_n", "belt", "N", required=False, lo=1000.0, hi=1e7,
       label="Belt stiffness EA per unit strain (span: EA/L); empty: ribs x stiffness_per_rib_n",
       basis="automotive timing and poly-V belts: EA 1e4-5e5 N; 1e7 is twenty times the stiffest, 1000 N a floor "
             "below any belt"),
    _f("ribs", "belt", kind="int", required=False, lo=1, hi=60, label="Ribs of a poly-V belt (PK: 3-12)",
       basis="automotive PK belts have 3 to 12 ribs; 60 is beyond any industrial PL belt"),
    _f("stiffness_per_rib_n", "belt", "N", required=False, lo=100.0, hi=1e6, default=belt_data.EA_PER_RIB_N,
       label="EA per rib of the spans in the rotational model (modes, response)",
       basis="default fitted on a drive report's first mode (synth.drive.belt.EA_PER_RIB_N); the reports imply "
             "7.6-13.5 kN"),
    _f("elongation_stiffness_per_rib_n", "belt", "N", required=False, lo=100.0, hi=1e6,
       default=belt_data.ELONGATION_EA_PER_RIB_N,
       label="Quasi-static EA per rib: the belt's elongation from its measuring tension (required belt length)",
       basis="default: fourteen drive reports' required-length column (synth.drive.belt.ELONGATION_EA_PER_RIB_N)"),
    _f("measuring_tension_per_rib_n", "belt", "N", required=False, lo=0.0, hi=1000.0,
       default=belt_data.MEASURING_TENSION_PER_RIB_N,
       label="Tension per rib and strand at which the belt's length is measured"),
    _f("length_mm", "belt", "mm", required=False, lo=100.0, hi=20000.0, label="Belt effective length (as measured)",
       basis="automotive belts are 600-3000 mm; 20 m is beyond any conveyor-free drive"),
    _f("length_tolerance_mm", "belt", "mm", required=False, lo=0.0, hi=200.0, default=0.0,
       label="Belt length tolerance (+/-)"),
    _f("wear_pct", "belt", "%", required=False, lo=0.0, hi=10.0, default=0.0,
       label="Belt elongation at replacement (wear), % of the longest belt"),
    _f("thermal_change_pct", "belt", "%", required=False, lo=-5.0, hi=5.0, default=0.0,
       label="Belt length change when hot, % (signed; widens the shortest or the longest belt)"),
    _f("damping_n_s", "belt", "N s", required=False, lo=0.0, hi=1e4, default=0.0,
       label="Belt damping c' per unit strain (span: c'/L)"),
    _f("min_tension_n", "belt", "N", required=False, lo=0.0, hi=1e4, default=0.0,
       label="Lowest effective span tension before the belt counts as slack"),
    _f("friction_coefficient", "belt", required=False, lo=0.01, hi=3.0,
       label="Belt-pulley friction coefficient (poly-V: effective; empty: no slip margin, a toothed belt)"),
    _f("pivot_x_mm", "tensioner", "mm", **_COORD, label="Tensioner pivot x"),
    _f("pivot_y_mm", "tensioner", "mm", **_COORD, label="Tensioner pivot y"),
    _f("arm_length_mm", "tensioner", "mm", lo=0.1, hi=300, label="Arm length (pivot to pulley centre)",
       basis="0.1 mm: the positional tolerance of an eccentric's two bores (the design input's floor); "
             "accessory-drive arms reach about 100 mm"),
    _f("arm_angle_deg", "tensioner", "deg", required=False, lo=-360, hi=360,
       label="Nominal arm angle (counter-clockwise from +x); empty: from free_arm_angle_deg and preload_nm"),
    _f("free_arm_angle_deg", "tensioner", "deg", required=False, lo=-360, hi=360,
       label="Free-arm angle: the arm on its stop without a belt (counter-clockwise from +x)"),
    _f("preload_nm", "tensioner", "Nm", required=False, lo=0.0, hi=500,
       label="Spring torque at the free arm (preload); the nominal angle follows"),
    _f("installation_angle_deg", "tensioner", "deg", required=False, lo=-360, hi=360,
       label="Installation (load) stop: the arm turned back to fit the belt (counter-clockwise from +x)"),
    _f("inertia_kg_m2", "tensioner", "kg m2", required=False, **_INERTIA,
       label="Arm inertia about the pivot (with its pulley unless pulley_mass_kg is given)"),
    _f("pulley_mass_kg", "tensioner", "kg", required=False, lo=0.0, hi=100.0, default=0.0,
       label="Tensioner pulley mass (adds m l^2 to the arm's inertia)"),
    _f("stiffness_nm_per_deg", "tensioner", "Nm/deg", lo=1e-4, hi=50, label="Spring rate",
       basis="1e-4 Nm/deg: the design input's floor (a torque bench's resolution over 100 deg); accessory-drive "
             "springs are about 0.5 Nm/deg"),
    _f("nominal_torque_nm", "tensioner", "Nm", required=False, lo=0.01, hi=500,
       label="Spring torque at nominal (calculated torque; a report's spring mean load); empty: from the belt length",
       basis="0.01 Nm: a torque bench's resolution (the design input's floor)"),
    _f("friction_torque_nm", "tensioner", "Nm", required=False, lo=0.0, hi=100,
       label="Friction torque (the damping; needed for the periodic response)"),
    _f("damping_nm_s_per_rad", "tensioner", "Nm s/rad", required=False, lo=0.0, hi=100, default=0.0,
       label="Viscous damping of the arm"),
    _f("name", "pulleys", kind="str", label="Pulley name"),
    _f("role", "pulleys", kind="str", required=False, choices=ROLES, default="driven",
       label="crank (drives), driven, idler or tensioner (its centre follows the arm)"),
    _f("x_mm", "pulleys", "mm", required=False, **_COORD, label="Centre x (not for the tensioner)"),
    _f("y_mm", "pulleys", "mm", required=False, **_COORD, label="Centre y (not for the tensioner)"),
    _f("radius_mm", "pulleys", "mm", required=False, **_RADIUS, label="Pitch radius (or pitch_diameter_mm)"),
    _f("pitch_diameter_mm", "pulleys", "mm", required=False, lo=2.0, hi=1000.0,
       label="Pitch diameter (the belt's cord line; or radius_mm)"),
    _f("effective_diameter_mm", "pulleys", "mm", required=False, lo=2.0, hi=1000.0,
       label="Effective diameter (belt length is measured on it; empty: the pitch diameter)"),
    _f("inertia_kg_m2", "pulleys", "kg m2", required=False, **_INERTIA,
       label="Inertia with what it drives (the crank's: for the free system's modes)"),
    _f("load_torque_nm", "pulleys", "Nm", required=False, lo=-1000, hi=1000, default=0.0,
       label="Mean load torque (driven pulleys)"),
    _f("damping_nm_s_per_rad", "pulleys", "Nm s/rad", required=False, lo=0.0, hi=100, default=0.0,
       label="Viscous damping of the pulley's shaft"),
    _f("torque_order", "pulleys", required=False, lo=0.5, hi=50,
       label="Order of the load torque's fluctuation (a camshaft of 4 cylinders: 2), a multiple of 0.5"),
    _f("torque_amplitude_nm", "pulleys", "Nm", required=False, lo=0.0, hi=1000, default=0.0,
       label="Amplitude of the load torque's fluctuation"),
    _f("torque_phase_deg", "pulleys", "deg", required=False, lo=-360, hi=360, default=0.0,
       label="Phase of the load torque's fluctuation"),
    _f("backside", "pulleys", kind="str", required=False, choices=("true", "false"), default="false",
       label="The belt's back on the pulley (outside the loop; a report's flat 'back' contact)"),
    _f("speed_rpm", "duty", "rpm", lo=1.0, hi=20000, label="Engine speed of the duty point"),
    _f("time_pct", "duty", "%", required=False, lo=0.0, hi=100.0, label="Share of the duty cycle's time"),
    _f("power_kw", "loads", "kW", **_POWER, label="A pulley's power at the duty point (name: kW; the crank's follows)"),
    _f("torque_nm", "loads", "Nm", lo=-5000.0, hi=5000.0, label="A pulley's torque at the duty point (name: N m)"),
    _f("speed_min_rpm", "excitation", "rpm", lo=1.0, hi=20000, label="Lowest engine speed of the sweep"),
    _f("speed_max_rpm", "excitation", "rpm", lo=1.0, hi=20000, label="Highest engine speed of the sweep"),
    _f("speeds", "excitation", kind="int", required=False, lo=2, hi=60, default=50, label="Speeds in the sweep",
       basis="60 speeds at the largest harmonics run in about a minute with the tolerance check (docs: drive, "
             "Bounds)"),
    _f("durability_speed_rpm", "excitation", "rpm", required=False, lo=1.0, hi=20000,
       label="Engine speed of the durability test (theta_pp and f are taken there)"),
    _f("irregularity", "excitation", required=False, lo=1e-4, hi=2.0,
       label="Kinematic irregularity delta (thesis eq. (3)) of the firing order; instead of orders"),
    _f("firing_order", "excitation", required=False, lo=0.5, hi=50, label="Order of the irregularity (4 cylinders: 2)"),
    _f("order", "orders", lo=0.5, hi=50, label="Order (a multiple of 0.5)"),
    _f("amplitude_deg", "orders", "deg", lo=0.0, hi=30, label="Crank angle amplitude of the order"),
    _f("phase_deg", "orders", "deg", required=False, lo=-360, hi=360, default=0.0, label="Phase"),
    _f("harmonics", "solver", kind="int", required=False, lo=4, hi=32, default=24,
       label="Harmonics of the base frequency in the harmonic balance",
       basis="the tolerance check solves again at twice the harmonics: 64 harmonics cost 0.6 s a speed, 128 "
             "cost 5 s (docs: drive, Bounds); 400 ran for minutes"),
    _f("regularisation", "solver", required=False, lo=1e-3, hi=0.5, default=0.01,
       label="Friction regularisation eps / peak arm speed without friction",
       basis="1e-3: the tolerance check halves it; below, the regularised Coulomb law is too stiff for the "
             "harmonic balance's time samples"),
    _f("tolerance", "solver", required=False, lo=1e-4, hi=0.5, default=0.05,
       label="Largest relative move of the answer when the regularisation is halved and the harmonics doubled"),
)
