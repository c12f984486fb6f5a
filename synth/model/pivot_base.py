"""Step 10: the pivot base on the crankcase under the hubload: tilting and sliding (thesis eq. (94)-(100)), the
clamp force they need and the pressure under the base.

Units as in :mod:`synth.model.bolted_joint` (forces in N, lengths in mm, moments in N*mm, pressures in MPa, angles
in degrees); the bolt that carries the clamp force is :func:`synth.model.bolted_joint.fixation`'s.
"""

from __future__ import annotations

import numpy as np

from synth.errors import InputError, Problem
from synth.model.input_guards import as_array as _arr, require as _require

__all__ = ["tilting_lever_mm", "pivot_base_contact_area_mm2", "pivot_base_bending_factor_per_mm3",
           "bolt_force_tilting_n", "bolt_force_sliding_n", "required_bolt_force_n", "tilting_safety_factor",
           "sliding_safety_factor", "pivot_base_pressure_mpa"]

_MIN_SECTOR_DEG = 1e-6  # numerical floor of the contact angle (a line contact), see the bending factor


def tilting_lever_mm(middle_plane_belt_height_mm, middle_plane_belt_height_increment_worst_mm=0.0):
    """Lever of the hubload about the pivot base, eq. (95): ``h_mid + dh_worst`` [mm].

    The worst-case increment of the belt middle-plane height is added so that
    the requirement holds in the extreme position (thesis text after eq. (95)).

    >>> float(tilting_lever_mm(29.5, 2.0))
    31.5
    """
    return _arr(middle_plane_belt_height_mm) + _arr(middle_plane_belt_height_increment_worst_mm)


def pivot_base_contact_area_mm2(d_ext_mm, d_int_mm, contact_angle_deg=360.0):
    """Contact area of the pivot base on the crankcase, eq. (97) [mm^2].

    Annulus between the engine-support internal and external diameters,
    reduced to the contact sector: ``A = theta/360 * pi/4 * (D^2 - d^2)``.

    >>> round(float(pivot_base_contact_area_mm2(22.9, 8.2)), 2)
    359.06
    >>> round(float(pivot_base_contact_area_mm2(28.0, 8.2, 180.0)), 2)
    281.47
    """
    D, d, th = _geometry(d_ext_mm, d_int_mm, contact_angle_deg)
    return th / 360.0 * np.pi / 4.0 * (D**2 - d**2)


def _geometry(d_ext_mm, d_int_mm, contact_angle_deg):
    d = _require("engine_support_internal_diameter_mm", d_int_mm, inclusive=True)
    D = _require("engine_support_external_diameter_mm", d_ext_mm)
    if np.any(D <= d):
        D, d = np.broadcast_arrays(D, d)
        i = np.flatnonzero(np.ravel(D <= d))[0]
        raise InputError(Problem("engine_support_external_diameter_mm", float(np.ravel(D)[i]),
                                 f"a diameter > the internal diameter ({float(np.ravel(d)[i]):g} mm)"))
    th = _require("contact_angle_deg", contact_angle_deg, high=360.0, accepted="an angle in (0, 360] deg")
    return D, d, th


def _one_minus_sinc_term(t):
    """``t - sin(t)`` without cancellation for small ``t`` (series below 1e-2 rad)."""
    small = t < 1e-2
    ts = np.where(small, t, 0.0)
    series = ts**3 / 6.0 - ts**5 / 120.0 + ts**7 / 5040.0
    return np.where(small, series, t - np.sin(t))


def _sector(D, d, th):
    """Annular sector of angle ``th`` [deg] symmetric about +x: radii, half angle [rad], area,
    centroid ``x_c`` and principal centroidal second moments ``I_xx`` (of y), ``I_yy`` (of x - x_c).

    ``A = a (ro^2 - ri^2)``, ``x_c = 2/3 sin(a)/a (ro^3 - ri^3)/(ro^2 - ri^2)``,
    ``I_xx = (ro^4 - ri^4)/8 (t - sin t)``, ``I_yy = (ro^4 - ri^4)/8 (t + sin t) - A x_c^2`` (t = 2a).
    """
    ro, ri = D / 2.0, d / 2.0
    t = np.radians(th)
    a = t / 2.0
    area = a * (ro**2 - ri**2)
    xc = 2.0 / 3.0 * np.sinc(a / np.pi) * (ro**3 - ri**3) / (ro**2 - ri**2)  # sinc = sin(a)/a
    xc = np.where(np.isclose(th, 360.0), 0.0, xc)
    i4 = (ro**4 - ri**4) / 8.0
    ixx = i4 * _one_minus_sinc_term(t)
    # Iyy about the centroid stays positive (inertia of a radial line); guard round-off only
    iyy = np.maximum(i4 * (t + np.sin(t)) - area * xc**2, i4 * t * 1e-12)
    return ro, ri, a, area, xc, ixx, iyy


def pivot_base_bending_factor_per_mm3(d_ext_mm, d_int_mm, contact_angle_deg=360.0, *, model="sector"):
    """Worst-fibre bending stress per unit tilting moment of the pivot base [1/mm^3].

    ``sigma_b,max = M_tilt * k`` (MPa with M in N*mm). For a full annulus
    (eq. (96)) ``k = (D/2) / I`` with ``I = pi (D^4 - d^4) / 64``.

    ``model="sector"`` (default, physics): a partial contact is an annular
    sector of angle ``theta``; with a linear (rigid-body) pressure field about
    its principal centroidal axes and the hubload in the worst direction,
    ``k = max over the sector of sqrt((y/I_xx)^2 + ((x - x_c)/I_yy)^2)``
    (closed-form A, centroid and I of the sector; the maximum lies on the
    outer arc, where it is found in closed form, or at the inner corners). ``model="thesis"``: eq. (96) as
    printed, the full-annulus value scaled by ``360/theta`` (read from the
    scrambled fraction; equal to the sector model at 360 deg).

    Near ``theta = 0`` the factor grows like ``1/theta^2`` (finite for
    ``theta > 0``; angles below 1e-6 deg are evaluated at 1e-6 deg, a line
    contact, to keep the sector inertia representable); ``theta <= 0`` or
    ``> 360`` raises InputError.

    >>> round(float(pivot_base_bending_factor_per_mm3(22.9, 8.2)) * 1e4, 4)
    8.6237
    >>> k180 = pivot_base_bending_factor_per_mm3(22.9, 8.2, 180.0)
    >>> bool(k180 > pivot_base_bending_factor_per_mm3(22.9, 8.2, 360.0))
    True
    """
    D, d, th = _geometry(d_ext_mm, d_int_mm, contact_angle_deg)
    th = np.maximum(th, _MIN_SECTOR_DEG)
    if D.size > 64 and d.size == D.size and th.size == D.size and (D == D.flat[0]).all() and \
            (d == d.flat[0]).all() and (th == th.flat[0]).all():
        # one support repeated (the samples of one design, synth.robust): computed once, broadcast
        one = pivot_base_bending_factor_per_mm3(D.flat[0], d.flat[0], th.flat[0], model=model)
        return np.broadcast_to(one, D.shape)
    full = 32.0 * D / (np.pi * (D**4 - d**4))
    if model == "thesis":
        return full * 360.0 / th
    if model != "sector":
        raise InputError(Problem("model", model, "'sector' or 'thesis'"))
    ro, ri, a, area, xc, ixx, iyy = _sector(D, d, th)
    # on the outer arc g = (r sin(phi)/Ixx)^2 + ((r cos(phi) - xc)/Iyy)^2 is a quadratic in
    # c = cos(phi) on [cos(a), 1]: its maximum is at an end or at the vertex (closed form)
    q2 = ro**2 * (1.0 / iyy**2 - 1.0 / ixx**2)
    q1 = -2.0 * ro * xc / iyy**2
    q0 = ro**2 / ixx**2 + xc**2 / iyy**2

    def g(c):
        return q0 + q1 * c + q2 * c**2

    lo_c = np.cos(a)
    vertex = np.clip(-q1 / (2.0 * np.where(q2 < 0, q2, -1.0)), lo_c, 1.0)
    outer = np.maximum(np.maximum(g(lo_c), g(np.ones_like(lo_c))), np.where(q2 < 0, g(vertex), 0.0))
    corner = (ri * np.sin(a) / ixx) ** 2 + ((ri * np.cos(a) - xc) / iyy) ** 2
    k = np.sqrt(np.maximum(outer, corner))
    return np.where(np.isclose(th, 360.0), full, k)


def bolt_force_tilting_n(hubload_n, safety_factor, lever_mm, d_ext_mm, d_int_mm, contact_angle_deg=360.0,
                         *, model="sector"):
    """Minimum bolt force against tilting, eq. (94)-(97) [N].

    ``HL_t = HL * SF_t`` (94), ``M_t = HL_t * lever`` (95), the average contact
    pressure must equal the worst-fibre bending stress so that the minimum
    pressure just reaches zero: ``sigma_avg = M_t * k`` (96) and
    ``F_t = sigma_avg * A`` (97).

    Case 3 (HL 462.5 N, SF 3, lever 22 mm, support 8.2/28 mm):
    M_t = 462.5*3*22 = 30525 N*mm; k = 32*28/(pi*(28^4-8.2^4)) = 4.6745e-4 /mm^3;
    sigma_avg = 14.269 MPa; A = 562.94 mm^2; F_t = 8033 N.

    >>> round(float(bolt_force_tilting_n(462.5, 3.0, 22.0, 28.0, 8.2)))
    8033
    """
    hl = _require("hubload_n", hubload_n, inclusive=True)
    sf = _require("tilting_safety_factor", safety_factor, inclusive=True)
    lever = _require("tilting lever (middle plane belt height + increment) [mm]", lever_mm, inclusive=True)
    k = pivot_base_bending_factor_per_mm3(d_ext_mm, d_int_mm, contact_angle_deg, model=model)
    area = pivot_base_contact_area_mm2(d_ext_mm, d_int_mm, contact_angle_deg)
    return hl * sf * lever * k * area


def bolt_force_sliding_n(hubload_n, safety_factor, mu_crankcase):
    """Minimum bolt force against sliding, eq. (98)-(99): ``F_s = HL * SF_s / f`` [N].

    >>> round(float(bolt_force_sliding_n(462.5, 3.0, 0.10)), 1)
    13875.0
    """
    hl = _require("hubload_n", hubload_n, inclusive=True)
    sf = _require("sliding_safety_factor", safety_factor, inclusive=True)
    mu = _require("pivot base-crankcase friction coefficient", mu_crankcase)
    return hl * sf / mu


def required_bolt_force_n(force_tilting_n, force_sliding_n):
    """Bolt axial force that meets both targets, eq. (100): ``max(F_t, F_s)`` [N].

    >>> float(required_bolt_force_n(8033.0, 13875.0))
    13875.0
    """
    return np.maximum(_arr(force_tilting_n), _arr(force_sliding_n))


def tilting_safety_factor(bolt_force_n, hubload_n, lever_mm, d_ext_mm, d_int_mm, contact_angle_deg=360.0,
                          *, model="sector"):
    """Tilting safety factor reached by a bolt force (eq. (94)-(97) solved for SF) [-].

    ``SF_t = (F/A) / (HL * lever * k)``: average pressure over the bending
    stress amplitude at the nominal hubload. A zero hubload or lever gives
    ``inf`` (nothing tilts), never NaN.

    Case 1 as run: F 16312 N on 359.06 mm^2 = 45.43 MPa; HL*lever*k =
    652.5*31.5*8.6237e-4 = 17.725 MPa; SF = 2.563.

    >>> round(float(tilting_safety_factor(16312.5, 652.5, 31.5, 22.9, 8.2)), 3)
    2.563
    """
    f = _require("bolt_axial_force_n", bolt_force_n, inclusive=True)
    hl = _require("hubload_n", hubload_n, inclusive=True)
    lever = _require("tilting lever [mm]", lever_mm, inclusive=True)
    k = pivot_base_bending_factor_per_mm3(d_ext_mm, d_int_mm, contact_angle_deg, model=model)
    area = pivot_base_contact_area_mm2(d_ext_mm, d_int_mm, contact_angle_deg)
    demand = hl * lever * k
    with np.errstate(divide="ignore"):
        return np.where(demand > 0, f / area / np.where(demand > 0, demand, 1.0), np.inf)


def sliding_safety_factor(bolt_force_n, hubload_n, mu_crankcase):
    """Sliding safety factor reached by a bolt force, eq. (99) solved for SF: ``f*F/HL`` [-].

    >>> round(float(sliding_safety_factor(14500.0, 483.33, 0.10)), 2)
    3.0
    """
    f = _require("bolt_axial_force_n", bolt_force_n, inclusive=True)
    hl = _require("hubload_n", hubload_n, inclusive=True)
    mu = _require("pivot base-crankcase friction coefficient", mu_crankcase)
    return np.where(hl > 0, mu * f / np.where(hl > 0, hl, 1.0), np.inf)


def pivot_base_pressure_mpa(angle_deg, bolt_force_n, tilting_moment_nmm, d_ext_mm, d_int_mm,
                            contact_angle_deg=360.0, hubload_direction_deg=0.0):
    """Contact pressure on the outer edge of the pivot base vs polar angle (Fig. 74) [MPa].

    Linear (rigid-body) pressure field: ``p = F/A + M ((x - x_c) cos(psi)/I_yy
    + y sin(psi)/I_xx)`` with ``psi`` the hubload direction; for a full
    annulus this is the thesis's sinusoid ``p = sigma_avg + M (D/2)/I *
    cos(angle - psi)``, maximum on the hubload side. Angles are measured from
    the bisector of the contact sector; outside the sector the pressure is 0.
    Negative values mean lift-off (tilting): they are returned, not clipped.
    ``angle_deg`` broadcasts against the design arrays (add a trailing axis to
    plot a curve per design).

    >>> p = pivot_base_pressure_mpa([0.0, 90.0, 180.0], 14500.0, 462.5 * 22.0, 28.0, 8.2)
    >>> [round(float(v), 2) for v in p]
    [30.51, 25.76, 21.0]
    """
    D, d, th = _geometry(d_ext_mm, d_int_mm, contact_angle_deg)
    th = np.maximum(th, _MIN_SECTOR_DEG)
    f = _arr(bolt_force_n)
    m = _arr(tilting_moment_nmm)
    psi = np.radians(_arr(hubload_direction_deg))
    ang = np.radians(_arr(angle_deg))
    ro, ri, a, area, xc, ixx, iyy = _sector(D, d, th)
    full = np.isclose(th, 360.0)
    x = ro * np.cos(ang) - xc
    y = ro * np.sin(ang)
    p = f / area + m * (x * np.cos(psi) / iyy + y * np.sin(psi) / ixx)
    wrapped = np.abs((np.degrees(ang) + 180.0) % 360.0 - 180.0)
    inside = full | (wrapped <= th / 2.0 + 1e-9)
    return np.where(inside, p, 0.0)
