"""Step 10: tilting, sliding and the fixation bolt (thesis eq. (94)-(111)).

The tensioner is clamped on the engine by one bolt. The bolt preload must keep
the pivot base in contact with the crankcase under the tilting moment of the
hubload (which acts at the belt middle-plane height) and must hold the
hubload by friction (sliding). The preload is carried by a bolt format and
property class, and the clamped parts are checked under the head (on the
head's own bearing face, or a washer's, within the support's seat) and in
the threads.

Units: forces in N, lengths in mm, torques in N*mm inside and N*m at the
public outputs (``_nm``), stresses in MPa (= N/mm^2), angles in degrees.

Where the printed thesis equations are wrong or ambiguous the physically
correct form is implemented and the thesis tool's convention is offered as a
keyword option; see ``docs/sections/bolted_joint.md``.

Two paths size and judge the joint (:func:`fixation` ``method``): ``"thesis"``
(the thesis tool's elastic stress check at exactly the required clamp force:
the reproduction path of the thesis cases) and ``"vdi2230"`` (VDI 2230 Part 1:
the made joint of a tightening method, its preload window ``[F_M,min,
alpha_A F_M,min]`` sized to the requirement, or the bolt's yield point for
yield- and angle-controlled tightening). Thread data: ``catalogs/bolts.csv``
(ISO 261/262/724, ISO 898-1 A_s), head forms ``catalogs/bolt_heads.csv``
(hex, flange, socket), washers ``catalogs/washers.csv`` (ISO 7089, ISO 7093-1),
classes ``catalogs/bolt_property_classes.csv`` (ISO 898-1), tightening methods
``catalogs/tightening_factors.csv``. This module computes the values of the
step-10 checks for a given bolt; which bolt passes is the registry's verdict and
the flowchart's (or an optimiser's) choice. The VDI 2230 equations are
:mod:`synth.model.vdi2230`.

Thesis case 1 as run (its 13 mm contact: a head bearing on at least 13 mm, e.g. a flange head on a 13 mm seat):

>>> hl = nominal_hubload_n(3.25, 5.0, 85.0)
>>> round(float(hl), 1)
652.5
>>> out = fixation(hl, 29.5, 2.0, 2.5, 2.5, 8.2, 22.9, 360.0, 400.0, 400.0,
...                application_type="belt_in_oil", number_of_active_threads=2.3,
...                bolt_head_contact_external_diameter_mm=13.0, head_type="flange",
...                bolt_format="M8x1.25", bolt_property_class="8.8")
>>> round(float(out["bolt_tightening_torque_nm"]), 2), round(float(out["bolt_under_head_stress_mpa"]), 1)
(19.64, 204.1)
"""

from __future__ import annotations

import numpy as np

from synth.catalog import constant, load
from synth.errors import CatalogError, InputError, Problem
from synth.model.input_guards import as_array as _arr, require as _require
from synth.model.vdi2230 import (DEFAULT_EMBEDDING_LOADING, DEFAULT_EMBEDDING_ROUGHNESS, DEFAULT_TIGHTENING_METHOD,
                                 HEAD_TYPES, assembly_torque_nm, bolt_resilience_mm_per_n,
                                 clamped_parts_resilience_mm_per_n, embedding_preload_loss_n, embedding_um,
                                 head_mean_diameter_mm, permissible_assembly_preload_n)
from synth.model import vdi2230 as _vdi
from synth import parts
from synth.model.damping import hubload_nominal_n
from synth import catalog as _catalog

__all__ = [
    "friction_coefficient", "nominal_hubload_n",
    "tilting_lever_mm", "pivot_base_contact_area_mm2", "pivot_base_bending_factor_per_mm3",
    "bolt_force_tilting_n", "bolt_force_sliding_n", "required_bolt_force_n",
    "tilting_safety_factor", "sliding_safety_factor", "pivot_base_pressure_mpa",
    "thread_torque_nmm", "under_head_torque_nmm", "tightening_torque_nm",
    "bolt_normal_stress_mpa", "bolt_torsion_stress_mpa", "von_mises_stress_mpa",
    "under_head_stress_mpa", "thread_area_mm2", "thread_bearing_stress_mpa",
    "min_head_contact_diameter_mm", "min_active_threads",
    "METHODS", "bolt_head", "bolt_candidates", "NO_WASHER", "washer_series", "washer_dimensions",
    "head_bearing_diameter_mm", "head_friction_diameter_mm", "fixation",
]

STEP = 10
_MIN_SECTOR_DEG = 1e-6  # numerical floor of the contact angle (a line contact), see the bending factor
ENVIRONMENTS = ("dry", "belt_in_oil")


# ----------------------------------------------------------------------------------------------
# catalog helpers
# ----------------------------------------------------------------------------------------------

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
    return parts.mu(str(interface).strip(), str(environment).strip())


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
    arm = _require("working_arm_mm", working_arm_mm)
    a = _require("differential_angle_deg", differential_angle_deg, low=0.0, high=180.0,
                 accepted="an angle in (0, 180) deg")
    if np.any(a >= 180.0):
        raise InputError(Problem("differential_angle_deg", 180.0, "an angle in (0, 180) deg"))
    return hubload_nominal_n(t, arm, a)


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
    diameter and the support internal diameter (or a washer's bore). A head
    (or washer) bearing no larger than the hole leaves no annulus: the
    pressure is infinite (the check fails). Case 3: 14500/(pi/4 (11^2 - 8.2^2)) = 343.4 MPa.

    >>> round(float(under_head_stress_mpa(14500.0, 11.0, 8.2)), 1), float(under_head_stress_mpa(14500.0, 8.0, 8.2))
    (343.4, inf)
    """
    dw = _require("bolt_head_contact_external_diameter_mm", head_contact_diameter_mm)
    dh = _require("engine_support_internal_diameter_mm", hole_diameter_mm, inclusive=True)
    ring = np.pi / 4.0 * (dw**2 - dh**2)
    with np.errstate(divide="ignore"):
        return np.where(ring > 0, _arr(bolt_force_n) / np.where(ring > 0, ring, 1.0), np.inf)


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
# catalogs: bolt formats, head forms and property classes, escalation order
# ----------------------------------------------------------------------------------------------

METHODS = ("thesis", "vdi2230")


def bolt_head(bolt_format: str, head_type: str = "hex"):
    """The ``catalogs/bolt_heads.csv`` row of a thread format in a head form (a pandas Series).

    Head forms: ``hex`` (ISO 4017, fine pitch ISO 8676), ``flange`` (ISO 4162 /
    ISO 15071), ``socket`` (ISO 4762 / ISO 12474). Columns ``dw_min_mm``
    (bearing-face diameter), ``head_outer_mm`` (s, dc or dk), ``head_height_mm``,
    ``product_standard`` (prices: :mod:`synth.cost`).

    >>> float(bolt_head("M8x1.25", "flange")["dw_min_mm"]), str(bolt_head("M8x1", "socket")["product_standard"])
    (14.9, 'ISO 12474')
    """
    if head_type not in HEAD_TYPES:
        raise InputError(Problem("head_type", head_type, "one of " + ", ".join(HEAD_TYPES)))
    heads = load("bolt_heads")
    hit = heads[(heads["bolt_format"] == str(bolt_format).strip()) & (heads["head_type"] == head_type)]
    if hit.empty:
        raise CatalogError(Problem("bolt_format", bolt_format, f"a format with a {head_type} head: "
                                   + ", ".join(heads.loc[heads["head_type"] == head_type, "bolt_format"])))
    return hit.iloc[0].copy()


_NUMERIC_BOLT_COLUMNS = ("d_mm", "pitch_mm", "d2_mm", "d3_mm", "D1_mm", "stress_area_mm2", "pivot_bore_min_mm")


def bolt_candidates(bolt_format: str | None = None, property_class: str | None = None, head_type: str = "hex"):
    """The (format, property class) pairs in the flowchart's escalation order, in one head form.

    Automatic mode (``None``): formats with an ``escalation_rank`` in
    ``bolts.csv`` (M8x1.25, M10x1.5, M12x1.75), and for each format the
    classes 8.8, 9.8, 10.9, 12.9 in rank order (thesis section 10: the class
    is raised first, the format when the strongest class yields). Classes not
    defined for the format's diameter (9.8 above 16 mm) are skipped. Naming a
    format or class restricts the list (manual verification). ``head_type``
    (``hex``, ``flange``, ``socket``) picks the head row of
    ``bolt_heads.csv``. Returns a list of dicts with the thread geometry, the
    head (``head_type``, ``dw_min_mm``, ``head_outer_mm``, ``head_height_mm``,
    ``head_product_standard``), ``rp02_mpa`` and ``rm_mpa`` (prices: :mod:`synth.cost`).

    >>> [(c["bolt_format"], c["bolt_property_class"]) for c in bolt_candidates()][:3]
    [('M8x1.25', '8.8'), ('M8x1.25', '9.8'), ('M8x1.25', '10.9')]
    >>> len(bolt_candidates("M10x1.25", "10.9")), bolt_candidates("M8x1.25", "8.8", "socket")[0]["dw_min_mm"]
    (1, 12.33)
    """
    key = (None if bolt_format is None else str(bolt_format).strip(),
           None if property_class is None else str(property_class).strip(), head_type)
    return [dict(c) for c in _candidates_memo(key, (bolt_format, property_class, head_type))]


_CANDIDATES: dict = {}


def _candidates_memo(key, args) -> tuple:
    """:func:`bolt_candidates` memoised per arguments and catalog tables (a user catalog folder, or a cleared
    catalog cache, gives new tables and so a new list). A named format and class is read from the table of every
    (format, class) of its head form, built in one pass; anything else (automatic mode, an unknown name: its
    error) by :func:`_bolt_candidates`."""
    dirs = tuple(_catalog.user_dirs())
    tables = tuple(_catalog.load_cached(n, dirs) for n in ("bolts", "bolt_property_classes", "bolt_heads"))
    hit = _CANDIDATES.get((key, dirs))
    if hit is not None and all(a is b for a, b in zip(hit[0], tables)):
        return hit[1]
    if len(_CANDIDATES) > 4096:
        _CANDIDATES.clear()
    fmt, cls, head = key
    out = None
    if fmt is not None and cls is not None and head in HEAD_TYPES:
        every = _CANDIDATES.get((("*", "*", head), dirs))
        if every is None or not all(a is b for a, b in zip(every[0], tables)):
            every = (tables, _every_candidate(head))
            _CANDIDATES[(("*", "*", head), dirs)] = every
        if (fmt, cls) in every[1]:
            out = (every[1][(fmt, cls)],)
    if out is None:
        out = tuple(_bolt_candidates(*args))
    _CANDIDATES[(key, dirs)] = (tables, out)
    return out


def _every_candidate(head_type) -> dict:
    """``{(format, class): candidate}`` of every defined pair in one head form (one pass over the catalogs)."""
    bolts, classes, heads = load("bolts"), load("bolt_property_classes"), load("bolt_heads")
    key_b, key_c = bolts.columns[0], classes.columns[0]
    head_of = {str(h["bolt_format"]).strip(): h for _, h in heads[heads["head_type"] == head_type].iterrows()}
    out = {}
    for _, b in bolts.iterrows():
        head = head_of.get(str(b[key_b]))
        if head is None:
            continue
        for _, c in classes.iterrows():
            cand = _candidate(b, c, head, head_type, key_b, key_c)
            if cand is not None:
                out[(cand["bolt_format"], cand["bolt_property_class"])] = cand
    return out


def _candidate(b, c, head, head_type, key_b, key_c) -> dict | None:
    """The candidate dict of one bolt row, class row and head row; None for a class not defined at the diameter."""
    if not np.isnan(float(c["d_max_mm"])) and float(b["d_mm"]) > float(c["d_max_mm"]):
        return None
    big = float(b["d_mm"]) > 16.0
    rp = float(c["rp02_min_d_gt16_mpa"] if big else c["rp02_min_mpa"])
    rm = float(c["rm_min_d_gt16_mpa"] if big else c["rm_min_mpa"])
    return {
        "bolt_format": str(b[key_b]), "bolt_property_class": str(c[key_c]),
        **{k: float(b[k]) for k in _NUMERIC_BOLT_COLUMNS},
        "head_type": head_type, "dw_min_mm": float(head["dw_min_mm"]),
        "head_outer_mm": float(head["head_outer_mm"]), "head_height_mm": float(head["head_height_mm"]),
        "head_product_standard": str(head["product_standard"]),
        "rp02_mpa": rp, "rm_mpa": rm,
    }


def _bolt_candidates(bolt_format, property_class, head_type):
    if head_type not in HEAD_TYPES:
        raise InputError(Problem("head_type", head_type, "one of " + ", ".join(HEAD_TYPES)))
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
        head = bolt_head(str(b[key_b]), head_type)
        for _, c in classes.iterrows():
            cand = _candidate(b, c, head, head_type, key_b, key_c)
            if cand is not None:
                out.append(cand)
    if not out:
        raise InputError(Problem("bolt_property_class", property_class,
                                 f"a class defined for {bolt_format} (ISO 898-1: 9.8 only up to 16 mm)"))
    return out


# ----------------------------------------------------------------------------------------------
# the head's bearing on the support: the screw's own head, a washer, the seat
# ----------------------------------------------------------------------------------------------

NO_WASHER = "none"


def washer_series() -> tuple:
    """The washer series of ``catalogs/washers.csv`` (its ``product_standard`` column), ``"none"`` first.

    >>> washer_series()
    ('none', 'ISO 7089', 'ISO 7093-1')
    """
    ws = load("washers")
    return (NO_WASHER, *dict.fromkeys(ws["product_standard"].astype(str).str.strip()))


def washer_dimensions(series, d_mm) -> dict:
    """``{"d1_mm", "d2_mm", "h_mm"}``: the bore, outer diameter and thickness of the ``series`` washer
    (``catalogs/washers.csv``) for each bolt diameter ``d_mm`` (arrays; ``"none"``: no washer, NaN
    diameters and 0 thickness). A series without a washer for a diameter is an error naming both.

    >>> w = washer_dimensions("ISO 7089", [8.0, 10.0])
    >>> w["d2_mm"].tolist(), w["h_mm"].tolist()
    ([16.0, 20.0], [1.6, 2.0])
    """
    d = np.atleast_1d(np.asarray(d_mm, dtype=float))
    series = str(series).strip()
    if series == NO_WASHER:
        return {"d1_mm": np.full(d.shape, np.nan), "d2_mm": np.full(d.shape, np.nan), "h_mm": np.zeros(d.shape)}
    ws = load("washers")
    rows = ws[ws["product_standard"].astype(str).str.strip() == series]
    if rows.empty:
        raise InputError(Problem("bolt_washer", series, "one of " + ", ".join(washer_series())))
    by_d = {float(r["d_mm"]): r for _, r in rows.iterrows()}
    out = {k: np.empty(d.shape) for k in ("d1_mm", "d2_mm", "h_mm")}
    for i, di in enumerate(d):
        r = by_d.get(float(di))
        if r is None:
            raise InputError(Problem("bolt_washer", series, f"a series with a washer for M{di:g} "
                                     f"(catalogs/washers.csv has {', '.join(f'M{x:g}' for x in sorted(by_d))})"))
        for k in out:
            out[k][i] = float(r[k])
    return out


def head_bearing_diameter_mm(head_dw_mm, washer_d2_mm=np.nan, washer_h_mm=0.0, seat_mm=None):
    """Outer diameter of the head's bearing on the support [mm]: the screw's own, a washer's, within the seat.

    Without a washer (``washer_d2_mm`` NaN) the head's bearing-face diameter
    ``dw`` (``bolt_heads.csv`` ``dw_min_mm``, ISO 4017 / 4162 / 4762). A
    washer under the head spreads the head's load at 45 deg through its
    thickness ``h``: it bears on ``min(d2, dw + 2 h)`` (a thin washer does
    not carry its whole face; synth assumption, the washer being hardened,
    300 HV, so that the head does not indent it). ``seat_mm`` (the
    application's ``bolt_head_contact_external_diameter_mm``, NaN or None:
    no seat) is the support's bearing face: the contact ends there.

    An ISO 4017 M6 head on the default 11 mm seat bears on its own 8.88 mm;
    an M8 flange head (14.9 mm) on it on the seat's 11 mm; an M8 hex head on
    an ISO 7089 washer (16 x 1.6 mm) with no seat on 11.63 + 3.2 = 14.83 mm:

    >>> [float(x) for x in head_bearing_diameter_mm([8.88, 14.9], seat_mm=11.0)]
    [8.88, 11.0]
    >>> round(float(head_bearing_diameter_mm(11.63, 16.0, 1.6)), 2)
    14.83
    """
    dw = _arr(head_dw_mm)
    d2 = _arr(washer_d2_mm)
    out = np.where(np.isfinite(d2), np.minimum(d2, dw + 2.0 * _arr(washer_h_mm)), dw)
    if seat_mm is not None:
        seat = _arr(seat_mm)
        out = np.where(np.isfinite(seat), np.minimum(out, seat), out)
    return out


def head_friction_diameter_mm(head_dw_mm, washer_d2_mm=np.nan, seat_mm=None):
    """Outer diameter of the face the head turns on while tightened [mm] (the under-head friction of eq. (101),
    VDI 2230 D_Km): the head's own face on a washer, or on the support within its seat.

    >>> float(head_friction_diameter_mm(11.63, seat_mm=11.0)), float(head_friction_diameter_mm(11.63, 16.0, 11.0))
    (11.0, 11.63)
    """
    dw = _arr(head_dw_mm)
    if seat_mm is None:
        return dw + 0.0 * np.nan_to_num(_arr(washer_d2_mm))
    seat = _arr(seat_mm)
    return np.where(np.isfinite(_arr(washer_d2_mm)) | ~np.isfinite(seat), dw, np.minimum(dw, seat))


# ----------------------------------------------------------------------------------------------
# the flowchart step
# ----------------------------------------------------------------------------------------------

def fixation(hubload_n, middle_plane_belt_height_mm, middle_plane_belt_height_increment_worst_mm,
             tilting_safety_factor_target, sliding_safety_factor_target,
             engine_support_internal_diameter_mm, engine_support_external_diameter_mm, contact_angle_deg,
             support_yield_strength_compression_mpa, support_yield_strength_traction_mpa, *,
             number_of_active_threads, application_type="dry",
             bolt_head_contact_external_diameter_mm=None, head_type="hex", washer=NO_WASHER,
             bolt_format=None, bolt_property_class=None,
             mu_crankcase=None, mu_thread=None, mu_head=None,
             contact_model="sector", torque_model="vdi", normal_stress_area="stress",
             torsion_diameter="minor", thread_area_model="triangle",
             method="thesis", tightening_method=DEFAULT_TIGHTENING_METHOD, alpha_a=None,
             embedding=False, clamp_length_mm=None,
             embedding_roughness=DEFAULT_EMBEDDING_ROUGHNESS, embedding_loading=DEFAULT_EMBEDDING_LOADING,
             clamped_interfaces=None, joint_type="tapped", clamped_parts_modulus_mpa=None,
             free_thread_length_mm=0.0, utilisation=None, candidates=None, clamp_force_n=None):
    """Step 10 of the flowchart: the joint of one named bolt, or of each of ``candidates`` (eq. (94)-(111)).

    Vectorised over designs: every numeric argument broadcasts. The clamp
    force the joint needs is ``F_req = max(F_tilting, F_sliding)`` for the
    safety targets (eq. (100)). This function computes the values of the
    registry's step-10 checks for the bolt it is given; choosing the bolt
    (the thesis's escalation: the first format and class that passes) is the
    caller's (:mod:`synth.flowchart`, the optimisers), from those checks.

    **The head's bearing diameter** on the support is the part's own: the
    head's ``dw_min`` (``bolt_heads.csv``, ``head_type``), or with a
    ``washer`` (``washers.csv`` series, ``"none"``: no washer) the washer's
    outer diameter as far as the head's load spreads through it
    (:func:`head_bearing_diameter_mm`). The application's
    ``bolt_head_contact_external_diameter_mm`` is a given seat: the support's
    bearing face ends there, so the contact is never larger
    (a head overhanging the seat bears on the seat).

    Two paths size and judge the joint (``method``):

    ``"thesis"`` (the reproduction path): the bolt is tightened to exactly
    ``F_req`` and judged by the elastic von Mises stress (eq. (103)-(107))
    against ``bolt_yield_utilisation_max * Rp0.2``; it reproduces the thesis
    cases (case 1 as run: M8x1.25 8.8, 19.64 N*m).

    ``"vdi2230"`` (the made joint of a tightening method, VDI 2230 Part 1):
    ``tightening_method`` (``catalogs/tightening_factors.csv``) tightens the
    joint into the window ``[F_M,min, F_M,max]``, ``F_M,max = alpha_A
    F_M,min`` (Table A8, the method's upper factor, or ``alpha_a``). A
    torque-controlled method sizes the window to the requirement:
    ``F_M,min = F_req`` (+ the embedding loss ``F_Z`` with ``embedding=True``,
    R4/R5: it needs ``clamp_length_mm``), and the bolt must carry the
    window's top: ``F_M,max <= F_M,zul`` (R7/2, plastic torsion, ``nu``).
    A yield- or angle-controlled method takes the bolt to its yield point:
    ``F_M,min`` is the bolt's own yield preload (R7/2 at ``nu = 1``) and the
    bolt is dimensioned for it (VDI 2230-1: ``alpha_A`` is the scatter of the
    lot's yield point; no ``F_M,zul`` check). The safety factors are those
    of the window's bottom (the smallest residual clamp force), the head,
    thread and pivot-base pressures and the bolt stresses those of its top
    (R10); ``bolt_axial_force_n`` is the window's mean and the tightening
    torque (R13/1) is set for it.

    ``clamp_force_n`` (broadcast like the designs, NaN where not given): a
    made joint, tightened to this preload (a production-scatter sample of
    :mod:`synth.robust`); every value then follows from it (the safety
    factors at it less the embedding loss, the pressures and stresses at
    it) and ``bolt_clamp_force_required_n`` stays ``F_req``.

    Friction coefficients default to ``friction_coefficients.csv`` for the
    ``application_type`` (``dry`` or ``belt_in_oil``).

    Options (thesis-tool conventions vs defaults): ``contact_model``
    (``sector``/``thesis``, see :func:`pivot_base_bending_factor_per_mm3`),
    ``torque_model`` (``vdi``/``helix``), ``normal_stress_area``
    (``stress`` = ISO 898-1 A_s / ``core`` = printed eq. (103)-(104)),
    ``torsion_diameter`` (``minor`` = eq. (105) / ``stress`` = VDI 2230),
    ``thread_area_model`` (see :func:`thread_area_mm2`); these apply to the
    thesis path. VDI-path options: ``embedding`` with ``clamp_length_mm``
    (the clamped length l_K), ``embedding_roughness``, ``embedding_loading``,
    ``clamped_interfaces``, ``joint_type``, ``clamped_parts_modulus_mpa``,
    ``free_thread_length_mm``, ``utilisation`` (``nu`` of R7, default 0.9).

    The bolt: ``bolt_format`` and ``bolt_property_class`` (one bolt), or
    ``candidates`` (a list of ``(bolt_format, bolt_property_class)`` pairs):
    every pair is evaluated and every returned array gains a trailing axis,
    one entry per pair (each entry equals the call naming that bolt).

    Returns a dict of arrays with the case keys ``bolt_tightening_torque_nm``,
    ``bolt_axial_force_n``, ``bolt_sigma_mpa``, ``bolt_tau_mpa``,
    ``bolt_sigma_eqv_mpa``, ``bolt_under_head_stress_mpa``,
    ``bolt_thread_stress_mpa``, ``bolt_format``, ``bolt_property_class``,
    ``pivot_base_contact_surface_mm2``, ``average_contact_pressure_mpa``,
    ``tilting_safety_factor``, ``sliding_safety_factor``; intermediates
    (``bolt_force_tilting_n``, ``bolt_force_sliding_n``, ``bolt_clamp_force_required_n``,
    ``tilting_moment_nmm``, ``pivot_base_max_pressure_mpa``,
    ``pivot_base_min_pressure_mpa``, ``bolt_utilisation``, ``bolt_rp02_mpa``,
    ``bolt_head_contact_diameter_mm`` (the bearing diameter on the support));
    column-G corrections (``min_head_contact_diameter_mm``, ``min_active_threads``,
    ``pivot_bore_min_mm``) -- the limits and verdicts are the registry's
    (:mod:`synth.design.constraints`); and for ``"vdi2230"`` also
    ``bolt_permissible_preload_n`` (F_M,zul; +inf for a yield-controlled
    method), ``bolt_required_preload_min_n`` (F_M,min), ``bolt_required_preload_max_n``
    (F_M,max), ``bolt_embedding_um`` (f_Z), ``bolt_embedding_loss_n`` (F_Z),
    ``bolt_residual_clamp_force_n`` (the smallest residual clamp force) and
    ``tightening_factor``.

    >>> r = fixation(462.5, 20.0, 2.0, 3.0, 3.0, 8.2, 28.0, 360.0, 400.0, 400.0, number_of_active_threads=2.6,
    ...              bolt_head_contact_external_diameter_mm=11.0, bolt_format="M8x1.25", bolt_property_class="8.8")
    >>> round(float(r["bolt_axial_force_n"])), round(float(r["tilting_safety_factor"]), 2)
    (13875, 5.18)
    >>> v = fixation(462.5, 20.0, 2.0, 3.0, 3.0, 8.2, 28.0, 360.0, 400.0, 400.0, method="vdi2230",
    ...              number_of_active_threads=2.6, head_type="flange", bolt_format="M8x1.25",
    ...              bolt_property_class="10.9")
    >>> round(float(v["bolt_required_preload_min_n"])), round(float(v["bolt_required_preload_max_n"]))
    (13875, 22200)
    >>> round(float(v["bolt_under_head_stress_mpa"]), 1), round(float(v["sliding_safety_factor"]), 2)
    (182.7, 3.0)
    """
    if method not in METHODS:
        raise InputError(Problem("method", method, "one of " + ", ".join(METHODS)))
    if application_type not in ENVIRONMENTS:
        raise InputError(Problem("application_type", application_type, "one of " + ", ".join(ENVIRONMENTS)))
    if head_type not in HEAD_TYPES:
        raise InputError(Problem("head_type", head_type, "one of " + ", ".join(HEAD_TYPES)))
    if normal_stress_area not in ("stress", "core"):
        raise InputError(Problem("normal_stress_area", normal_stress_area, "'stress' or 'core'"))
    if torsion_diameter not in ("minor", "stress"):
        raise InputError(Problem("torsion_diameter", torsion_diameter, "'minor' or 'stress'"))
    if method == "vdi2230" and embedding and clamp_length_mm is None:
        raise InputError(Problem("clamp_length_mm", None, "a clamped length > 0 mm (e.g. the pivot height) for the "
                                 "VDI 2230 embedding loss"))
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
    required = required_bolt_force_n(f_tilt, f_slide)
    made = None if clamp_force_n is None else _arr(clamp_force_n)
    area = pivot_base_contact_area_mm2(d_ext, d_int, contact_angle_deg)
    k = pivot_base_bending_factor_per_mm3(d_ext, d_int, contact_angle_deg, model=contact_model)
    moment = hl * lever

    # --- the bolts: one named, or candidates on a trailing axis (no choice among them here) --------------
    if candidates is not None:
        if bolt_format is not None or bolt_property_class is not None:
            raise InputError(Problem("candidates", "given with bolt_format/bolt_property_class",
                                     "either a list of (format, class) pairs or one format and class"))
        cands = [bolt_candidates(f, c, head_type)[0] for f, c in candidates]
        if not cands:
            raise InputError(Problem("candidates", "[]", "at least one (format, class) pair"))
    else:
        if bolt_format is None or bolt_property_class is None:
            raise InputError(Problem("bolt_format", bolt_format, "a bolt format and a property class (or a list of "
                                     "candidates): choosing the bolt is the flowchart's step, from the checks"))
        cands = bolt_candidates(bolt_format, bolt_property_class, head_type)
    col = {key: np.array([c[key] for c in cands], dtype=float) for key, v in cands[0].items() if isinstance(v, float)}
    names_f = np.array([c["bolt_format"] for c in cands])
    names_c = np.array([c["bolt_property_class"] for c in cands])
    wsh = washer_dimensions(washer, col["d_mm"])
    seat = None if bolt_head_contact_external_diameter_mm is None else \
        _arr(bolt_head_contact_external_diameter_mm)[..., None]
    if seat is not None and np.any(seat[..., 0] <= d_int):
        s_, d_ = np.broadcast_arrays(seat[..., 0], d_int)
        raise InputError(Problem("bolt_head_contact_external_diameter_mm", float(np.ravel(s_[s_ <= d_])[0]),
                                 "a seat diameter > the support internal diameter"))
    dw = head_bearing_diameter_mm(col["dw_min_mm"], wsh["d2_mm"], wsh["h_mm"], seat)   # on the support
    d_in = np.fmax(d_int[..., None], wsh["d1_mm"])                                  # its bore (a washer's)
    dk = head_friction_diameter_mm(col["dw_min_mm"], wsh["d2_mm"], seat)               # the turning face
    mu_gk = _arr(mu_g)[..., None]
    each = candidates is not None
    shape = np.broadcast_shapes(np.shape(required)[:], ()) + (len(cands),)

    def ex(a):  # a design array on the candidates' axis
        return np.asarray(a, dtype=float)[..., None]

    a_thr = thread_area_mm2(col["d_mm"], col["pitch_mm"], col["d2_mm"], col["d3_mm"], col["D1_mm"],
                            model=thread_area_model)
    vdi = {}
    if method == "thesis":
        force = ex(required) if made is None else np.where(np.isfinite(ex(made)), ex(made), ex(required))
        f_top = f_bottom = f_bolt = force
        t_thread = thread_torque_nmm(force, col["pitch_mm"], col["d2_mm"], mu_gk, model=torque_model)
        a_norm = col["stress_area_mm2"] if normal_stress_area == "stress" else np.pi / 4.0 * col["d3_mm"] ** 2
        d_tors = col["d3_mm"] if torsion_diameter == "minor" else (col["d2_mm"] + col["d3_mm"]) / 2.0
        sigma_s = bolt_normal_stress_mpa(force, a_norm)
        tau_s = bolt_torsion_stress_mpa(t_thread, d_tors)
        eqv_s = von_mises_stress_mpa(sigma_s, tau_s)
        torque = (t_thread + under_head_torque_nmm(force, dk, d_in, ex(mu_k))) / 1000.0
    else:
        tm = _vdi.tightening_method(tightening_method)
        yield_set = tm["preload_set_by"] == "yield"
        alpha = tm["alpha_a_max"] if alpha_a is None else float(_require(
            "alpha_a", alpha_a, low=1.0, inclusive=True, accepted="a tightening factor >= 1"))
        f_zul = permissible_assembly_preload_n(col["pitch_mm"], col["d2_mm"], col["d3_mm"], col["rp02_mpa"], mu_gk,
                                               utilisation=utilisation)
        f_z = np.zeros(shape)
        fz_um = 0.0
        if embedding:
            fz_um = embedding_um(embedding_roughness, embedding_loading, interfaces=clamped_interfaces,
                                 joint_type=joint_type)
            lk = ex(clamp_length_mm)
            d_s = bolt_resilience_mm_per_n(col["d_mm"], col["d3_mm"], lk, head_type=head_type, joint_type=joint_type,
                                           free_thread_length_mm=ex(free_thread_length_mm),
                                           internal_thread_modulus_mpa=clamped_parts_modulus_mpa)
            d_p = clamped_parts_resilience_mm_per_n(dw, d_in, ex(d_ext), lk, modulus_mpa=clamped_parts_modulus_mpa,
                                                    joint_type=joint_type)
            f_z = np.broadcast_to(embedding_preload_loss_n(fz_um, d_s, d_p), shape)
        if yield_set:  # the bolt's own yield preload (nu = 1, Rp0.2 min): the window's bottom
            f_min = np.broadcast_to(permissible_assembly_preload_n(col["pitch_mm"], col["d2_mm"], col["d3_mm"],
                                                                   col["rp02_mpa"], mu_gk, utilisation=1.0), shape)
            limit = np.full(shape, np.inf)
        else:
            f_min = np.broadcast_to(ex(required) + f_z, shape)
            limit = np.broadcast_to(f_zul, shape)
        f_max = alpha * f_min
        if made is None:
            f_bottom, f_top, f_bolt = f_min, f_max, (f_min + f_max) / 2.0
        else:
            mf = ex(made)
            f_bottom = np.where(np.isfinite(mf), mf, f_min)
            f_top = np.where(np.isfinite(mf), mf, f_max)
            f_bolt = np.where(np.isfinite(mf), mf, (f_min + f_max) / 2.0)
        d0 = (col["d2_mm"] + col["d3_mm"]) / 2.0
        thread_moment = f_top / 2.0 * (col["pitch_mm"] / np.pi + mu_gk * col["d2_mm"] /
                                       np.cos(np.radians(constant("thread_flank_half_angle_deg"))))
        sigma_s = f_top / (np.pi / 4.0 * d0**2)
        tau_s = 12.0 * thread_moment / (np.pi * d0**3)  # plastic torsion section pi d0^3/12 (VDI R7)
        eqv_s = von_mises_stress_mpa(sigma_s, tau_s)
        torque = assembly_torque_nm(f_bolt, col["pitch_mm"], col["d2_mm"], mu_gk, head_mean_diameter_mm(dk, d_in),
                                    ex(mu_k))
        f_bottom = f_bottom - f_z
        vdi = {"bolt_permissible_preload_n": limit, "bolt_required_preload_min_n": f_min,
               "bolt_required_preload_max_n": f_top, "bolt_embedding_um": np.full(shape, fz_um),
               "bolt_embedding_loss_n": f_z, "bolt_residual_clamp_force_n": f_bottom,
               "tightening_factor": np.full(shape, alpha)}
    sf_t = tilting_safety_factor(np.maximum(f_bottom, 0.0), ex(hl), ex(lever), ex(d_ext), ex(d_int),
                                 ex(contact_angle_deg), model=contact_model)
    sf_s = sliding_safety_factor(np.maximum(f_bottom, 0.0), ex(hl), ex(mu_cc))
    p_top = f_top / ex(area)
    out = {
        "bolt_tightening_torque_nm": torque,
        "bolt_axial_force_n": f_bolt,
        "bolt_sigma_mpa": sigma_s,
        "bolt_tau_mpa": tau_s,
        "bolt_sigma_eqv_mpa": eqv_s,
        "bolt_under_head_stress_mpa": under_head_stress_mpa(f_top, dw, d_in),
        "bolt_thread_stress_mpa": thread_bearing_stress_mpa(f_top, a_thr, ex(n_thr)),
        "bolt_format": names_f,
        "bolt_property_class": names_c,
        "pivot_base_contact_surface_mm2": ex(area),
        "average_contact_pressure_mpa": f_bolt / ex(area),
        "tilting_safety_factor": sf_t,
        "sliding_safety_factor": sf_s,
        "bolt_force_tilting_n": ex(f_tilt),
        "bolt_force_sliding_n": ex(f_slide),
        "bolt_clamp_force_required_n": ex(required),
        "tilting_moment_nmm": ex(moment),
        "pivot_base_max_pressure_mpa": p_top + ex(moment) * ex(k),
        "pivot_base_min_pressure_mpa": f_bottom / ex(area) - ex(moment) * ex(k),
        "bolt_rp02_mpa": col["rp02_mpa"],
        "bolt_utilisation": eqv_s / col["rp02_mpa"],
        "bolt_head_contact_diameter_mm": dw,
        "min_head_contact_diameter_mm": min_head_contact_diameter_mm(f_top, d_in, ex(s_comp)),
        "min_active_threads": min_active_threads(f_top, a_thr, ex(s_trac)),
        "pivot_bore_min_mm": col["pivot_bore_min_mm"],
        **vdi,
    }
    full = np.broadcast_shapes(*(np.shape(v) for v in out.values()), shape)
    out = {key: np.broadcast_to(v, full) for key, v in out.items()}
    if not each:
        out = {key: v[..., 0] for key, v in out.items()}
    return out
