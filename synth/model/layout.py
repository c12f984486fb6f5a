"""Step 0: tensioner execution selection (thesis eq. (17)-(27)).

Layout (standard or reverse) from the belt offset, pulley width from the belt,
lock-up pin position checks and the axial displacement check. All functions
are vectorised; angles in degrees, lengths in millimetres.

>>> bool(is_standard_layout(29.5, 42.0))
True
>>> float(pulley_width_mm(16.0))
20.0
"""

from __future__ import annotations

import numpy as np

from synth.catalog import constant

__all__ = [
    "layout_of", "is_standard_layout", "pulley_width_mm", "hubload_angle_from_ehr_deg", "belt_contact_centre_deg",
    "wrap_limits_deg", "pin_angular_zone", "pin_clearance_mm",
]


def layout_of(middle_plane_belt_height_mm, max_axial_displacement_mm):
    """The layout eq. (17)-(18) choose, NaN-aware: ``"standard"``, ``"reverse"`` (or ``"unknown"``).

    * both given: standard if ``h_mid >= h_max / 2`` (eq. (17); equality is
      standard, as the thesis says), else reverse (eq. (18));
    * max axial displacement not given (NaN or None: the thesis writes N/A in
      the input table of a reverse-layout tensioner): **reverse**. With no
      upper limit on the axial space, eq. (17) reads ``h_mid >= inf/2``, which
      is false, so eq. (18) holds; and the space check of a reverse layout is
      eq. (27) (belt-crankcase clearance), which needs no maximum height,
      while the standard layout's eq. (26) cannot be checked without it;
    * middle plane belt height not given: ``"unknown"`` (the schema requires
      it, so a validated input never gives this).

    Vectorised: arrays give an array of strings.

    >>> layout_of(29.5, 42.0), layout_of(10.0, 42.0), layout_of(21.0, 42.0), layout_of(16.0, float("nan"))
    ('standard', 'reverse', 'standard', 'reverse')
    >>> layout_of([29.5, 16.0, float("nan")], [42.0, None, 42.0]).tolist()
    ['standard', 'reverse', 'unknown']
    """
    h = np.asarray(middle_plane_belt_height_mm, dtype=float)
    h_max = np.asarray(np.where(np.equal(max_axial_displacement_mm, None), np.nan, max_axial_displacement_mm), dtype=float)
    standard = np.isfinite(h_max) & (h >= h_max / 2.0)
    out = np.where(np.isnan(h), "unknown", np.where(standard, "standard", "reverse"))
    return out.item() if out.ndim == 0 else out


def is_standard_layout(middle_plane_belt_height_mm, max_height_mm):
    """Standard layout if ``h_mid >= h_max / 2`` (eq. (17)), else reverse (eq. (18)).

    ``max_height_mm`` is the maximum axial height available for the pulley
    (the input ``max_axial_displacement_mm``; see docs/model.md).

    >>> is_standard_layout([29.5, 10.0], 42.0).tolist()
    [True, False]
    """
    return np.asarray(middle_plane_belt_height_mm, float) >= np.asarray(max_height_mm, float) / 2.0


def pulley_width_mm(belt_width_mm):
    """Pulley width = belt width + margin (constant ``pulley_width_margin_mm``, 4 mm).

    The thesis prints the width without its rule; belt 16 -> pulley 20 (case 1)
    and belt 26 -> pulley 30 (case 3) give a 4 mm margin (2 mm a side).

    >>> float(pulley_width_mm(26.0))
    30.0
    """
    return np.asarray(belt_width_mm, float) + constant("pulley_width_margin_mm")


def hubload_angle_from_ehr_deg(differential_angle_deg, nominal_arm_angle_deg):
    """Angle between the hubload and the engine horizontal reference, eq. (19).

    ``HL_EHR = 360 - (alpha + gamma)``, wrapped to [0, 360).

    >>> round(float(hubload_angle_from_ehr_deg(85.0, 136.7)), 1)
    138.3
    """
    a = np.asarray(differential_angle_deg, float) + np.asarray(nominal_arm_angle_deg, float)
    return np.mod(360.0 - a, 360.0)


def belt_contact_centre_deg(hubload_angle_deg):
    """Direction of the middle of the belt-pulley contact arc: opposite the hubload.

    The hubload of eq. (19) is the force of the belt on the pulley; it points
    from the contact arc through the pulley centre, so the arc is centred at
    ``HL_EHR + 180``. (Eq. (20)-(21) print the arc centred on ``HL_EHR``; with
    that reading case 1's production lock-up pin would sit in the middle of
    the belt wrap. See docs/model.md.)

    >>> round(float(belt_contact_centre_deg(138.3)), 1)
    318.3
    """
    return np.mod(np.asarray(hubload_angle_deg, float) + 180.0, 360.0)


def wrap_limits_deg(hubload_angle_deg, wrap_angle_deg):
    """Upper and lower belt-pulley contact limits, eq. (20)-(21): ``centre +/- wrap/2``.

    ``centre`` is :func:`belt_contact_centre_deg` of the hubload angle.

    >>> [round(float(x), 1) for x in wrap_limits_deg(138.3, 69.2)]
    [352.9, 283.7]
    """
    centre = belt_contact_centre_deg(hubload_angle_deg)
    beta = np.asarray(wrap_angle_deg, float) / 2.0
    return centre + beta, centre - beta


def pin_angular_zone(pin_angle_deg, theta_plus_deg, theta_minus_deg):
    """Where the pin lies relative to the wrap: +1 beyond theta+, -1 before theta-, 0 within.

    Angles are compared on the circle (the offset from the arc centre wrapped
    to (-180, 180]).

    >>> pin_angular_zone([127.0, 180.0, 90.0], 172.9, 103.7).tolist()
    [0, 1, -1]
    """
    tp, tm = np.asarray(theta_plus_deg, float), np.asarray(theta_minus_deg, float)
    centre, half = (tp + tm) / 2.0, (tp - tm) / 2.0
    off = np.mod(np.asarray(pin_angle_deg, float) - centre + 180.0, 360.0) - 180.0
    return np.where(off > half, 1, np.where(off < -half, -1, 0))


def pin_clearance_mm(pin_radius_mm, pin_angle_deg, pin_diameter_mm, pulley_diameter_mm,
                     theta_plus_deg, theta_minus_deg):
    """Lock-up pin clearance to the pulley and belt and what it must reach, eq. (23)-(25) [mm].

    * within the wrap (eq. (23)): the pin's inner edge ``R_pin - d_pin/2`` must reach
      ``D_pulley/2 + c_pulley`` (5 mm);
    * beyond theta+ or before theta- (eq. (24)-(25)): the pin keeps ``c_belt`` (2 mm)
      from the belt span, the line tangent to the pulley at the contact limit.
      The distance from the pin centre to that line, on the pulley side, is
      ``R - R_pin cos(phi - theta_lim)``; it must be at least ``d_pin/2 + c_belt``.

    Returns ``(clearance_mm, required_mm)``.

    >>> c, r = pin_clearance_mm(45.0, 138.3, 4.0, 66.0, 172.9, 103.7)
    >>> round(float(c), 3), float(r), round(float((c - r) / r), 3)
    (43.0, 38.0, 0.132)
    """
    r_pin = np.asarray(pin_radius_mm, float)
    phi = np.asarray(pin_angle_deg, float)
    d_pin = np.asarray(pin_diameter_mm, float)
    r = np.asarray(pulley_diameter_mm, float) / 2.0
    zone = pin_angular_zone(phi, theta_plus_deg, theta_minus_deg)
    theta_lim = np.where(zone > 0, theta_plus_deg, theta_minus_deg)
    dist = r - r_pin * np.cos(np.radians(phi - theta_lim))
    clearance = np.where(zone == 0, r_pin - d_pin / 2.0, dist)
    required = np.where(zone == 0, r + constant("lockup_pin_pulley_clearance_mm"),
                        d_pin / 2.0 + constant("lockup_pin_belt_clearance_mm"))
    return clearance, required
