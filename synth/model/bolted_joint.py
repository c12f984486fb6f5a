"""Step 10: tilting, sliding and the fixation bolt (thesis eq. (94)-(111)).

The tensioner is clamped on the engine by one bolt. The bolt preload must keep
the pivot base in contact with the crankcase under the tilting moment of the
hubload (which acts at the belt middle-plane height) and must hold the
hubload by friction (sliding). The preload is then carried by a bolt format
and property class (the smallest that does not yield), and the clamped parts
are checked under the head and in the threads.

Units: forces in N, lengths in mm, torques in N*mm inside and N*m at the
public outputs (``_nm``), stresses in MPa (= N/mm^2), angles in degrees.

Where the printed thesis equations are wrong or ambiguous the physically
correct form is implemented and the thesis tool's convention is offered as a
keyword option; see ``docs/sections/bolted_joint.md``.

>>> hl = nominal_hubload_n(3.25, 5.0, 85.0)
>>> round(float(hl), 1)
652.5
>>> out = fixation(hl, 29.5, 2.0, 2.5, 2.5, 8.2, 22.9, 360.0, 400.0, 400.0,
...                application_type="belt_in_oil", number_of_active_threads=2.3,
...                bolt_head_contact_external_diameter_mm=13.0)
>>> str(out["bolt_format"]), str(out["bolt_property_class"]), round(float(out["bolt_tightening_torque_nm"]), 2)
('M8x1.25', '8.8', 19.64)
"""

from __future__ import annotations

import numpy as np

from synth.catalog import constant, load
from synth.checks import Check, margin_lower, margin_upper
from synth.errors import CatalogError, InputError, Problem

__all__ = [
    "friction_coefficient", "nominal_hubload_n",
    "tilting_lever_mm", "pivot_base_contact_area_mm2", "pivot_base_bending_factor_per_mm3",
    "bolt_force_tilting_n", "bolt_force_sliding_n", "required_bolt_force_n",
    "tilting_safety_factor", "sliding_safety_factor", "pivot_base_pressure_mpa",
    "thread_torque_nmm", "under_head_torque_nmm", "tightening_torque_nm",
    "bolt_normal_stress_mpa", "bolt_torsion_stress_mpa", "von_mises_stress_mpa",
    "under_head_stress_mpa", "thread_area_mm2", "thread_bearing_stress_mpa",
    "min_head_contact_diameter_mm", "min_active_threads",
    "bolt_candidates", "fixation", "fixation_checks",
]

STEP = 10
_MIN_SECTOR_DEG = 1e-6  # numerical floor of the contact angle (a line contact), see the bending factor
ENVIRONMENTS = ("dry", "belt_in_oil")


# ----------------------------------------------------------------------------------------------
# input guards and catalog helpers
# ----------------------------------------------------------------------------------------------

def _arr(x):
    return np.asarray(x, dtype=float)


def _require(name, x, *, low=0.0, inclusive=False, high=None, accepted=None):
    """Raise InputError if any element of ``x`` is outside (low, high] (NaN fails)."""
    a = _arr(x)
    ok = (a >= low) if inclusive else (a > low)
    if high is not None:
        ok &= a <= high
    ok &= np.isfinite(a)
    if not np.all(ok):
        bad = a[~ok] if a.ndim else a
        value = float(np.ravel(bad)[0])
        if accepted is None:
            accepted = f"a finite number {'>=' if inclusive else '>'} {low:g}" + (
                f" and <= {high:g}" if high is not None else "")
        raise InputError(Problem(name, value, accepted))
    return a


def friction_coefficient(interface: str, environment: str) -> float:
    """Friction coefficient of an ``interface`` in an ``environment``.

    Reads ``catalogs/friction_coefficients.csv`` (columns
    ``interface,environment,mu,source,note``). Interfaces: ``thread``,
    ``under_head``, ``pivot_bushing``, ``pivot_base_crankcase``; environments:
    ``dry`` and ``belt_in_oil`` (the case files' ``application_type``).
    Values are those that reproduce thesis cases 1 and 3 (cases/NOTES.md).

    >>> friction_coefficient("pivot_base_crankcase", "dry")
    0.1
    >>> friction_coefficient("under_head", "belt_in_oil")
    0.08
    """
    df = load("friction_coefficients")
    hit = df[(df["interface"] == str(interface).strip()) & (df["environment"] == str(environment).strip())]
    if hit.empty:
        if str(interface).strip() not in set(df["interface"]):
            raise CatalogError(Problem("friction interface", interface, "one of " + ", ".join(sorted(set(df["interface"])))))
        envs = df.loc[df["interface"] == str(interface).strip(), "environment"]
        raise CatalogError(Problem("application_type", environment, "one of " + ", ".join(sorted(set(envs)))))
    return float(hit.iloc[0]["mu"])


def nominal_hubload_n(calculated_torque_nm, working_arm_mm, differential_angle_deg):
    """Nominal hubload from the calculated-torque target, eq. (7) corrected.

    ``HL = T_calc / (l_arm * sin(alpha))`` [N], torque in N*m, working arm in
    mm. The printed eq. (7) has ``cos(alpha)``; the lever of the hubload about
    the pivot is ``l_arm * sin(alpha)`` as in eq. (12)-(13) (with cos, case 3 at
    alpha = 90 deg would divide by zero). This is the hubload the thesis tool
    uses elsewhere (cases/NOTES.md). ``alpha`` must lie in (0, 180) deg.

    >>> round(float(nominal_hubload_n(1.85, 4.0, 90.0)), 1)
    462.5
    """
    t = _require("calculated_torque_target_nm", calculated_torque_nm)
    l = _require("working_arm_mm", working_arm_mm)
    a = _require("differential_angle_deg", differential_angle_deg, low=0.0, high=180.0,
                 accepted="an angle in (0, 180) deg")
    if np.any(a >= 180.0):
        raise InputError(Problem("differential_angle_deg", 180.0, "an angle in (0, 180) deg"))
    from synth.model.damping import hubload_nominal_n  # one implementation of eq. (7)
    return hubload_nominal_n(t, l, a)


# ----------------------------------------------------------------------------------------------
# tilting and sliding, eq. (94)-(100)
# ----------------------------------------------------------------------------------------------

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


# ----------------------------------------------------------------------------------------------
# bolt, eq. (101)-(111)
# ----------------------------------------------------------------------------------------------

def thread_torque_nmm(bolt_force_n, pitch_mm, d2_mm, mu_thread, *, model="vdi"):
    """Thread torque during tightening, eq. (106) corrected [N*mm].

    ``model="vdi"`` (default): ``T_G = F/2 (P/pi + mu d2 / cos(beta))``, the
    linearised form of eq. (101)/(106) and of VDI 2230-1
    (``M_A = F (0.16 P + 0.58 d2 mu_G + D_Km/2 mu_K)``; 0.58 = 1/(2 cos 30)).
    The printed eq. (101) multiplies by ``cos(beta)``; the flank friction acts
    on the inclined flank so it is divided (the case tables confirm).
    ``model="helix"``: the exact helix form ``F d2/2 tan(phi + rho')`` with
    ``tan(phi) = P/(pi d2)``, ``tan(rho') = mu/cos(beta)`` (about 1 % higher).
    ``d2`` is the pitch diameter ``d - 0.6495 P`` (eq. (102), ISO 724).

    M8x1.25, F 14500 N, mu 0.14: P/pi = 0.3979, 0.14*7.188/0.8660 = 1.1620,
    T = 7250 * 1.5599 = 11309 N*mm.

    >>> round(float(thread_torque_nmm(14500.0, 1.25, 7.188, 0.14)))
    11309
    """
    f = _arr(bolt_force_n)
    p = _arr(pitch_mm)
    d2 = _arr(d2_mm)
    mu = _require("thread friction coefficient", mu_thread, inclusive=True)
    cb = np.cos(np.radians(constant("thread_flank_half_angle_deg")))
    if model == "vdi":
        return f / 2.0 * (p / np.pi + mu * d2 / cb)
    if model == "helix":
        return f * d2 / 2.0 * np.tan(np.arctan(p / (np.pi * d2)) + np.arctan(mu / cb))
    raise InputError(Problem("torque_model", model, "'vdi' or 'helix'"))


def under_head_torque_nmm(bolt_force_n, head_contact_diameter_mm, hole_diameter_mm, mu_head):
    """Under-head friction torque, eq. (101) last term [N*mm].

    ``T_K = F mu_K D_Km / 2`` with the mean bearing diameter
    ``D_Km = (d_w + d_h)/2`` (VDI 2230-1): bolt-head contact diameter and the
    support hole.

    >>> round(float(under_head_torque_nmm(14500.0, 11.0, 8.2, 0.16)))
    11136
    """
    f = _arr(bolt_force_n)
    mu = _require("under-head friction coefficient", mu_head, inclusive=True)
    dkm = (_arr(head_contact_diameter_mm) + _arr(hole_diameter_mm)) / 2.0
    return f * mu * dkm / 2.0


def tightening_torque_nm(bolt_force_n, pitch_mm, d2_mm, mu_thread, head_contact_diameter_mm, hole_diameter_mm,
                         mu_head, *, model="vdi"):
    """Bolt tightening torque, eq. (101) corrected (VDI 2230-1 form) [N*m].

    Thread torque (:func:`thread_torque_nmm`) plus under-head torque
    (:func:`under_head_torque_nmm`). Case 3: 11309 + 11136 N*mm = 22.44 N*m
    (thesis tool 22.60, mu_K 0.162).

    >>> round(float(tightening_torque_nm(14500.0, 1.25, 7.188, 0.14, 11.0, 8.2, 0.16)), 2)
    22.45
    """
    tg = thread_torque_nmm(bolt_force_n, pitch_mm, d2_mm, mu_thread, model=model)
    tk = under_head_torque_nmm(bolt_force_n, head_contact_diameter_mm, hole_diameter_mm, mu_head)
    return (tg + tk) / 1000.0


def bolt_normal_stress_mpa(bolt_force_n, area_mm2):
    """Bolt normal stress, eq. (103) corrected: ``F / A_s`` [MPa].

    The default area is the ISO 898-1 stress area ``A_s = pi/4 ((d2+d3)/2)^2``
    (catalog ``stress_area_mm2``); eq. (103)-(104) print the core area
    ``pi d3^2/4`` but the case tables follow A_s (cases/NOTES.md). Case 3:
    14500/36.6 = 396.2 MPa (tool 394.67).

    >>> round(float(bolt_normal_stress_mpa(14500.0, 36.6)), 1)
    396.2
    """
    return _arr(bolt_force_n) / _require("bolt stress area [mm2]", area_mm2)


def bolt_torsion_stress_mpa(thread_torque_nmm_, diameter_mm):
    """Bolt torsion stress, eq. (105): ``16 T_G / (pi d^3)`` [MPa].

    ``d`` is the minor diameter ``d3`` as in the thesis (conservative); VDI
    2230-1 uses the stress diameter ``(d2+d3)/2`` (``torsion_diameter="stress"``
    in :func:`fixation`). Case 3: 16*11309/(pi*6.466^3) = 213.0 MPa (tool 214.05).

    >>> round(float(bolt_torsion_stress_mpa(11309.0, 6.466)), 1)
    213.0
    """
    d = _require("bolt torsion diameter [mm]", diameter_mm)
    return 16.0 * _arr(thread_torque_nmm_) / (np.pi * d**3)


def von_mises_stress_mpa(sigma_mpa, tau_mpa):
    """Von Mises equivalent stress, eq. (107): ``sqrt(sigma^2 + 3 tau^2)`` [MPa].

    >>> round(float(von_mises_stress_mpa(442.74, 239.94)), 2)
    607.23
    """
    s, t = _arr(sigma_mpa), _arr(tau_mpa)
    return np.sqrt(s**2 + 3.0 * t**2)


def under_head_stress_mpa(bolt_force_n, head_contact_diameter_mm, hole_diameter_mm):
    """Bearing stress under the bolt head, eq. (108)-(109) [MPa].

    ``F / (pi/4 (d_w^2 - d_int^2))``: annulus between the bolt-head contact
    diameter and the support internal diameter. A head not larger than the
    hole raises InputError. Case 3: 14500/(pi/4 (11^2 - 8.2^2)) = 343.4 MPa.

    >>> round(float(under_head_stress_mpa(14500.0, 11.0, 8.2)), 1)
    343.4
    """
    dw = _require("bolt_head_contact_external_diameter_mm", head_contact_diameter_mm)
    dh = _require("engine_support_internal_diameter_mm", hole_diameter_mm, inclusive=True)
    if np.any(dw <= dh):
        raise InputError(Problem("bolt_head_contact_external_diameter_mm", float(np.ravel(np.broadcast_to(dw, np.broadcast(dw, dh).shape)[dw <= dh])[0]),
                                 "a diameter > the support internal diameter"))
    return _arr(bolt_force_n) / (np.pi / 4.0 * (dw**2 - dh**2))


def thread_area_mm2(d_mm, pitch_mm, d2_mm, d3_mm, D1_mm, *, model="triangle"):
    """Bearing area of one engaged thread turn, eq. (111) corrected [mm^2].

    ``model="triangle"`` (default; what the thesis tables follow, NOTES.md):
    ``pi d2 P cos(30 deg)`` (the flank height of the fundamental triangle
    ``H = 0.866 P`` projected on the pitch cylinder). ``"engagement"``: the
    ISO 68-1 basic-profile engagement ``pi d2 H1`` with ``H1 = (d - D1)/2 =
    0.5413 P`` (classical thread bearing pressure, larger stress).
    ``"printed"``: eq. (111) as printed, ``pi (d^2 - d3^2)/4``.

    >>> round(float(thread_area_mm2(8.0, 1.25, 7.188, 6.466, 6.647)), 2)
    24.45
    """
    d, p, d2, d3, D1 = (_arr(v) for v in (d_mm, pitch_mm, d2_mm, d3_mm, D1_mm))
    if model == "triangle":
        return np.pi * d2 * p * np.cos(np.radians(constant("thread_flank_half_angle_deg")))
    if model == "engagement":
        return np.pi * d2 * (d - D1) / 2.0
    if model == "printed":
        return np.pi / 4.0 * (d**2 - d3**2)
    raise InputError(Problem("thread_area_model", model, "'triangle', 'engagement' or 'printed'"))


def thread_bearing_stress_mpa(bolt_force_n, area_per_thread_mm2, number_of_active_threads):
    """Average thread bearing stress, eq. (110): ``F / (A_thread n)`` [MPa].

    Case 3: 14500 / (24.445 * 2.6) = 228.1 MPa (tool 228.14).

    >>> round(float(thread_bearing_stress_mpa(14500.0, 24.445, 2.6)), 1)
    228.1
    """
    n = _require("number_of_active_threads", number_of_active_threads)
    return _arr(bolt_force_n) / (_require("thread area [mm2]", area_per_thread_mm2) * n)


def min_head_contact_diameter_mm(bolt_force_n, hole_diameter_mm, allowable_pressure_mpa):
    """Column-G correction: smallest bolt-head contact diameter, eq. (108)-(109) inverted [mm].

    ``d_w,min = sqrt(4 F / (pi sigma_allow) + d_int^2)``. Case 3:
    sqrt(4*14500/(pi*400) + 8.2^2) = sqrt(46.15 + 67.24) = 10.65 mm.

    >>> round(float(min_head_contact_diameter_mm(14500.0, 8.2, 400.0)), 2)
    10.65
    """
    s = _require("support_yield_strength_compression_mpa", allowable_pressure_mpa)
    return np.sqrt(4.0 * _arr(bolt_force_n) / (np.pi * s) + _arr(hole_diameter_mm) ** 2)


def min_active_threads(bolt_force_n, area_per_thread_mm2, allowable_stress_mpa):
    """Column-G correction: smallest number of active threads, eq. (110) inverted [-].

    ``n_min = F / (A_thread sigma_allow)``. Case 3: 14500/(24.445*400) = 1.48.

    >>> round(float(min_active_threads(14500.0, 24.445, 400.0)), 2)
    1.48
    """
    s = _require("support_yield_strength_traction_mpa", allowable_stress_mpa)
    return _arr(bolt_force_n) / (_require("thread area [mm2]", area_per_thread_mm2) * s)


# ----------------------------------------------------------------------------------------------
# catalogs: bolt formats and property classes, escalation order
# ----------------------------------------------------------------------------------------------

def bolt_candidates(bolt_format: str | None = None, property_class: str | None = None):
    """The (format, property class) pairs in the flowchart's escalation order.

    Automatic mode (``None``): formats with an ``escalation_rank`` in
    ``bolts.csv`` (M8x1.25, M10x1.5, M12x1.75), and for each format the
    classes 8.8, 9.8, 10.9, 12.9 in rank order (thesis section 10: the class
    is raised first, the format when the strongest class yields). Classes not
    defined for the format's diameter (9.8 above 16 mm) are skipped. Naming a
    format or class restricts the list (manual verification). Returns a list
    of dicts with the bolt geometry and ``rp02_mpa``, ``rm_mpa``.

    >>> [(c["bolt_format"], c["bolt_property_class"]) for c in bolt_candidates()][:3]
    [('M8x1.25', '8.8'), ('M8x1.25', '9.8'), ('M8x1.25', '10.9')]
    >>> len(bolt_candidates("M10x1.25", "10.9"))
    1
    """
    bolts = load("bolts")
    classes = load("bolt_property_classes")
    key_b, key_c = bolts.columns[0], classes.columns[0]
    if bolt_format is None:
        bolts = bolts[bolts["escalation_rank"].notna()].sort_values("escalation_rank")
    else:
        hit = bolts[bolts[key_b] == str(bolt_format).strip()]
        if hit.empty:
            raise CatalogError(Problem("bolt_format", bolt_format, "one of " + ", ".join(load("bolts")[key_b])))
        bolts = hit
    if property_class is None:
        classes = classes.sort_values("escalation_rank")
    else:
        hit = classes[classes[key_c] == str(property_class).strip()]
        if hit.empty:
            raise CatalogError(Problem("bolt_property_class", property_class,
                                       "one of " + ", ".join(load("bolt_property_classes")[key_c])))
        classes = hit
    out = []
    for _, b in bolts.iterrows():
        big = float(b["d_mm"]) > 16.0
        for _, c in classes.iterrows():
            if not np.isnan(float(c["d_max_mm"])) and float(b["d_mm"]) > float(c["d_max_mm"]):
                continue
            rp = float(c["rp02_min_d_gt16_mpa"] if big else c["rp02_min_mpa"])
            rm = float(c["rm_min_d_gt16_mpa"] if big else c["rm_min_mpa"])
            out.append({
                "bolt_format": str(b[key_b]), "bolt_property_class": str(c[key_c]),
                **{k: float(b[k]) for k in ("d_mm", "pitch_mm", "d2_mm", "d3_mm", "D1_mm", "stress_area_mm2",
                                            "dw_min_hex_mm", "dw_min_flange_mm", "pivot_bore_min_mm",
                                            "unit_cost_eur")},
                "rp02_mpa": rp, "rm_mpa": rm, "unit_cost_factor": float(c["unit_cost_factor"]),
            })
    if not out:
        raise InputError(Problem("bolt_property_class", property_class,
                                 f"a class defined for {bolt_format} (ISO 898-1: 9.8 only up to 16 mm)"))
    return out


# ----------------------------------------------------------------------------------------------
# the flowchart step
# ----------------------------------------------------------------------------------------------

def fixation(hubload_n, middle_plane_belt_height_mm, middle_plane_belt_height_increment_worst_mm,
             tilting_safety_factor_target, sliding_safety_factor_target,
             engine_support_internal_diameter_mm, engine_support_external_diameter_mm, contact_angle_deg,
             support_yield_strength_compression_mpa, support_yield_strength_traction_mpa, *,
             number_of_active_threads, application_type="dry",
             bolt_head_contact_external_diameter_mm=None, head_type="hex",
             bolt_format=None, bolt_property_class=None,
             mu_crankcase=None, mu_thread=None, mu_head=None,
             contact_model="sector", torque_model="vdi", normal_stress_area="stress",
             torsion_diameter="minor", thread_area_model="triangle"):
    """Step 10 of the flowchart: bolt preload, bolt choice and all checks (eq. (94)-(111)).

    Vectorised over designs: every numeric argument broadcasts. The bolt force
    is ``max(F_tilting, F_sliding)`` for the safety targets (eq. (100)); the
    bolt is the first (format, class) of :func:`bolt_candidates` whose von
    Mises stress stays within ``bolt_yield_utilisation_max * Rp0.2``
    (the largest if none does; its margin is then negative).

    Friction coefficients default to ``friction_coefficients.csv`` for the
    ``application_type`` (``dry`` or ``belt_in_oil``). The bolt-head contact
    diameter defaults to the catalog ``dw_min`` of the chosen format
    (``head_type`` ``hex`` ISO 4017 or ``flange`` ISO 4162).

    Options (thesis-tool conventions vs defaults): ``contact_model``
    (``sector``/``thesis``, see :func:`pivot_base_bending_factor_per_mm3`),
    ``torque_model`` (``vdi``/``helix``), ``normal_stress_area``
    (``stress`` = ISO 898-1 A_s / ``core`` = printed eq. (103)-(104)),
    ``torsion_diameter`` (``minor`` = eq. (105) / ``stress`` = VDI 2230),
    ``thread_area_model`` (see :func:`thread_area_mm2`).

    Returns a dict of arrays with the case keys ``bolt_tightening_torque_nm``,
    ``bolt_axial_force_n``, ``bolt_sigma_mpa``, ``bolt_tau_mpa``,
    ``bolt_sigma_eqv_mpa``, ``bolt_under_head_stress_mpa``,
    ``bolt_thread_stress_mpa``, ``bolt_format``, ``bolt_property_class``,
    ``pivot_base_contact_surface_mm2``, ``average_contact_pressure_mpa``,
    ``tilting_safety_factor``, ``sliding_safety_factor``; intermediates
    (``bolt_force_tilting_n``, ``bolt_force_sliding_n``, ``tilting_moment_nmm``,
    ``pivot_base_max_pressure_mpa``, ``pivot_base_min_pressure_mpa``,
    ``bolt_utilisation``, ``bolt_rp02_mpa``); column-G corrections
    (``min_head_contact_diameter_mm``, ``min_active_threads``,
    ``pivot_bore_min_mm``); and margins (>= 0 passes) ``margin_tilting``,
    ``margin_sliding``, ``margin_bolt_yield``, ``margin_under_head``,
    ``margin_thread``, ``margin_pivot_bore``, ``margin_pivot_base_pressure``.

    >>> r = fixation(462.5, 20.0, 2.0, 3.0, 3.0, 8.2, 28.0, 360.0, 400.0, 400.0,
    ...              number_of_active_threads=2.6, bolt_head_contact_external_diameter_mm=11.0)
    >>> round(float(r["bolt_axial_force_n"])), round(float(r["tilting_safety_factor"]), 2)
    (13875, 5.18)
    """
    if application_type not in ENVIRONMENTS:
        raise InputError(Problem("application_type", application_type, "one of " + ", ".join(ENVIRONMENTS)))
    if head_type not in ("hex", "flange"):
        raise InputError(Problem("head_type", head_type, "'hex' or 'flange'"))
    if normal_stress_area not in ("stress", "core"):
        raise InputError(Problem("normal_stress_area", normal_stress_area, "'stress' or 'core'"))
    if torsion_diameter not in ("minor", "stress"):
        raise InputError(Problem("torsion_diameter", torsion_diameter, "'minor' or 'stress'"))
    mu_cc = friction_coefficient("pivot_base_crankcase", application_type) if mu_crankcase is None else mu_crankcase
    mu_g = friction_coefficient("thread", application_type) if mu_thread is None else mu_thread
    mu_k = friction_coefficient("under_head", application_type) if mu_head is None else mu_head

    hl = _require("hubload_n", hubload_n, inclusive=True)
    lever = tilting_lever_mm(middle_plane_belt_height_mm, middle_plane_belt_height_increment_worst_mm)
    d_int = _arr(engine_support_internal_diameter_mm)
    d_ext = _arr(engine_support_external_diameter_mm)
    s_comp = _require("support_yield_strength_compression_mpa", support_yield_strength_compression_mpa)
    s_trac = _require("support_yield_strength_traction_mpa", support_yield_strength_traction_mpa)
    n_thr = _require("number_of_active_threads", number_of_active_threads)

    f_tilt = bolt_force_tilting_n(hl, tilting_safety_factor_target, lever, d_ext, d_int, contact_angle_deg,
                                  model=contact_model)
    f_slide = bolt_force_sliding_n(hl, sliding_safety_factor_target, mu_cc)
    force = required_bolt_force_n(f_tilt, f_slide)
    area = pivot_base_contact_area_mm2(d_ext, d_int, contact_angle_deg)
    k = pivot_base_bending_factor_per_mm3(d_ext, d_int, contact_angle_deg, model=contact_model)
    moment = hl * lever
    p_avg = force / area
    sf_t = tilting_safety_factor(force, hl, lever, d_ext, d_int, contact_angle_deg, model=contact_model)
    sf_s = sliding_safety_factor(force, hl, mu_cc)

    # --- bolt escalation: candidates on a trailing axis --------------------------------------
    cands = bolt_candidates(bolt_format, bolt_property_class)
    col = {key: np.array([c[key] for c in cands]) for key in cands[0] if key not in ("bolt_format", "bolt_property_class")}
    names_f = np.array([c["bolt_format"] for c in cands])
    names_c = np.array([c["bolt_property_class"] for c in cands])
    fk = force[..., None]
    t_thread = thread_torque_nmm(fk, col["pitch_mm"], col["d2_mm"], _arr(mu_g)[..., None], model=torque_model)
    a_norm = col["stress_area_mm2"] if normal_stress_area == "stress" else np.pi / 4.0 * col["d3_mm"] ** 2
    d_tors = col["d3_mm"] if torsion_diameter == "minor" else (col["d2_mm"] + col["d3_mm"]) / 2.0
    sigma = bolt_normal_stress_mpa(fk, a_norm)
    tau = bolt_torsion_stress_mpa(t_thread, d_tors)
    eqv = von_mises_stress_mpa(sigma, tau)
    limit = constant("bolt_yield_utilisation_max") * col["rp02_mpa"]
    passes = eqv <= limit
    idx = np.where(passes.any(axis=-1), passes.argmax(axis=-1), len(cands) - 1)

    def pick(a):
        a = np.broadcast_to(a, eqv.shape)
        return np.take_along_axis(a, idx[..., None], axis=-1)[..., 0]

    sel = {key: col[key][idx] for key in col}
    sigma_s, tau_s, eqv_s, t_thread_s = pick(sigma), pick(tau), pick(eqv), pick(t_thread)
    if bolt_head_contact_external_diameter_mm is None:
        dw = sel["dw_min_hex_mm"] if head_type == "hex" else sel["dw_min_flange_mm"]
    else:
        dw = _arr(bolt_head_contact_external_diameter_mm)
    t_head = under_head_torque_nmm(force, dw, d_int, mu_k)
    torque = (t_thread_s + t_head) / 1000.0
    s_head = under_head_stress_mpa(force, dw, d_int)
    a_thr = thread_area_mm2(sel["d_mm"], sel["pitch_mm"], sel["d2_mm"], sel["d3_mm"], sel["D1_mm"],
                            model=thread_area_model)
    s_thr = thread_bearing_stress_mpa(force, a_thr, n_thr)
    p_max = p_avg + moment * k

    out = {
        "bolt_tightening_torque_nm": torque,
        "bolt_axial_force_n": force,
        "bolt_sigma_mpa": sigma_s,
        "bolt_tau_mpa": tau_s,
        "bolt_sigma_eqv_mpa": eqv_s,
        "bolt_under_head_stress_mpa": s_head,
        "bolt_thread_stress_mpa": s_thr,
        "bolt_format": names_f[idx],
        "bolt_property_class": names_c[idx],
        "pivot_base_contact_surface_mm2": area,
        "average_contact_pressure_mpa": p_avg,
        "tilting_safety_factor": sf_t,
        "sliding_safety_factor": sf_s,
        "bolt_force_tilting_n": f_tilt,
        "bolt_force_sliding_n": f_slide,
        "tilting_moment_nmm": moment,
        "pivot_base_max_pressure_mpa": p_max,
        "pivot_base_min_pressure_mpa": p_avg - moment * k,
        "bolt_rp02_mpa": sel["rp02_mpa"],
        "bolt_utilisation": eqv_s / sel["rp02_mpa"],
        "bolt_unit_cost_eur": sel["unit_cost_eur"] * sel["unit_cost_factor"],
        "min_head_contact_diameter_mm": min_head_contact_diameter_mm(force, d_int, s_comp),
        "min_active_threads": min_active_threads(force, a_thr, s_trac),
        "pivot_bore_min_mm": sel["pivot_bore_min_mm"],
        "margin_tilting": margin_lower(sf_t, tilting_safety_factor_target),
        "margin_sliding": margin_lower(sf_s, sliding_safety_factor_target),
        "margin_bolt_yield": margin_upper(eqv_s, constant("bolt_yield_utilisation_max") * sel["rp02_mpa"]),
        "margin_under_head": margin_upper(s_head, s_comp),
        "margin_thread": margin_upper(s_thr, s_trac),
        "margin_pivot_bore": margin_lower(d_int, sel["pivot_bore_min_mm"]),
        "margin_pivot_base_pressure": margin_upper(p_max, s_comp),
    }
    return out


_CHECKS = [
    # name, value key, limit key or input, kind, unit, equation, correction key
    ("tilting safety factor", "tilting_safety_factor", "tilting_target", ">=", "-", "eq. (94)-(97)", None),
    ("sliding safety factor", "sliding_safety_factor", "sliding_target", ">=", "-", "eq. (98)-(99)", None),
    ("bolt von Mises stress", "bolt_sigma_eqv_mpa", "bolt_limit", "<=", "MPa", "eq. (103)-(107)", None),
    ("under-head stress", "bolt_under_head_stress_mpa", "s_comp", "<=", "MPa", "eq. (108)-(109)",
     "min_head_contact_diameter_mm"),
    ("thread bearing stress", "bolt_thread_stress_mpa", "s_trac", "<=", "MPa", "eq. (110)-(111)", "min_active_threads"),
    ("pivot bore for the bolt", "support_bore", "pivot_bore_min_mm", ">=", "mm", "thesis step 2 / section 10",
     "pivot_bore_min_mm"),
    ("pivot base max contact pressure", "pivot_base_max_pressure_mpa", "s_comp", "<=", "MPa", "eq. (96), Fig. 74", None),
]


def fixation_checks(result: dict, *, tilting_safety_factor_target, sliding_safety_factor_target,
                    engine_support_internal_diameter_mm, support_yield_strength_compression_mpa,
                    support_yield_strength_traction_mpa, index=()) -> list[Check]:
    """Report records (:class:`synth.checks.Check`) of one design of a :func:`fixation` result.

    ``index`` selects the design in vectorised results (``()`` for scalars).
    Failing checks carry the thesis's column-G correction in ``correction``.

    >>> r = fixation(462.5, 20.0, 2.0, 3.0, 3.0, 8.2, 28.0, 360.0, 400.0, 400.0,
    ...              number_of_active_threads=2.6, bolt_head_contact_external_diameter_mm=11.0)
    >>> [c.verdict for c in fixation_checks(r, tilting_safety_factor_target=3.0, sliding_safety_factor_target=3.0,
    ...   engine_support_internal_diameter_mm=8.2, support_yield_strength_compression_mpa=400.0,
    ...   support_yield_strength_traction_mpa=400.0)]
    ['pass', 'pass', 'pass', 'pass', 'pass', 'pass', 'pass']
    """
    def get(key):
        return float(np.asarray(result[key])[index])
    extra = {
        "tilting_target": float(np.asarray(tilting_safety_factor_target, float)[index] if np.ndim(tilting_safety_factor_target) else tilting_safety_factor_target),
        "sliding_target": float(np.asarray(sliding_safety_factor_target, float)[index] if np.ndim(sliding_safety_factor_target) else sliding_safety_factor_target),
        "s_comp": float(np.broadcast_to(support_yield_strength_compression_mpa, np.shape(result["bolt_axial_force_n"]))[index]),
        "s_trac": float(np.broadcast_to(support_yield_strength_traction_mpa, np.shape(result["bolt_axial_force_n"]))[index]),
        "support_bore": float(np.broadcast_to(engine_support_internal_diameter_mm, np.shape(result["bolt_axial_force_n"]))[index]),
        "bolt_limit": constant("bolt_yield_utilisation_max") * get("bolt_rp02_mpa"),
    }
    fmt = str(np.asarray(result["bolt_format"])[index])
    cls = str(np.asarray(result["bolt_property_class"])[index])
    checks = []
    for name, vkey, lkey, kind, unit, eq, corr in _CHECKS:
        value = extra[vkey] if vkey in extra else get(vkey)
        limit = extra[lkey] if lkey in extra else get(lkey)
        c = Check(name, STEP, value, limit, kind=kind, unit=unit, equation=eq)
        if c.verdict == "fail" and corr is not None:
            c.correction = {
                "min_head_contact_diameter_mm": f"bolt-head contact diameter >= {get(corr):.1f} mm",
                "min_active_threads": f"at least {get(corr):.1f} active threads",
                "pivot_bore_min_mm": f"{fmt} needs a pivot/support bore of at least {get(corr):.1f} mm",
            }[corr]
        if name == "bolt von Mises stress":
            c.note = f"{fmt} class {cls}"
            if c.verdict == "fail":
                c.correction = "no catalog format/class passes: larger format or lower preload"
        checks.append(c)
    return checks
