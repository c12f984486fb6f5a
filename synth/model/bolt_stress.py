"""Step 10: the bolt's own torques and stresses (thesis eq. (101)-(111)): thread and under-head torques, the
tightening torque, the normal, torsion and von Mises stresses, the pressures under the head and in the threads and
the smallest head and thread engagement that carry a force.

Units as in :mod:`synth.model.bolted_joint` (forces in N, lengths in mm, torques in N*mm inside and N*m at the
public outputs, stresses in MPa).
"""

from __future__ import annotations

import numpy as np

from synth.catalog import constant
from synth.errors import InputError, Problem
from synth.model.input_guards import as_array as _arr, require as _require

__all__ = ["thread_torque_nmm", "under_head_torque_nmm", "tightening_torque_nm", "bolt_normal_stress_mpa",
           "bolt_torsion_stress_mpa", "von_mises_stress_mpa", "under_head_stress_mpa", "thread_area_mm2",
           "thread_bearing_stress_mpa", "min_head_contact_diameter_mm", "min_active_threads"]


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
