"""Step 3: damping split and the tensioner characterisation (thesis eq. (7)-(16)).

The tensioner is a lever of length ``l = e_w sin(alpha)`` (working arm times
the sine of the differential angle) loaded by the hubload and held by the
spring torque ``M_s``. Friction adds the axial damping ``D_ax`` (cone spring on
the plastic elements, eq. (9)) and the radial damping of the pivot bushing,
which acts on the friction circle ``r_p sin(atan(mu))`` (eq. (10)). With the
corrected eq. (12)-(13) the torques at the pulley in loading and unloading are

    T_max = (M_s + D_ax) / (1 - rho),   T_min = (M_s - D_ax) / (1 + rho),
    rho   = r_p sin(atan(mu_pb)) / (e_w sin(alpha)),

and the characterisation outputs are the calculated torque
``T_c = (T_max + T_min)/2`` and the damping ``D = (T_max - T_min)/2``.
Setting these to their targets gives the design split used by the thesis
tool (NOTES.md): ``D_rad = T_c rho``, ``D_ax = D - T_c rho``,
``M_s = T_c - D rho`` (with axial damping) or ``T_c (1 - rho^2)`` (without).

``rho >= 1`` means the arm self-locks: the friction circle is larger than the
lever (the registry's ``self_locking`` constraint).

Lengths in mm, torques in Nm, forces in N, angles in degrees.

>>> round(float(hubload_nominal_n(1.85, 4.0, 90.0)), 1)
462.5
>>> s = damping_split(3.25, 2.0, lever_ratio(16.0, 0.055, 5.0, 85.0, friction_circle=False))
>>> [round(float(s[k]), 2) for k in ("radial_damping_nm", "axial_damping_nm", "spring_torque_nominal_nm")]
[0.29, 1.71, 3.07]
"""

from __future__ import annotations

import numpy as np


__all__ = [
    "friction_circle_factor", "lever_mm", "hubload_nominal_n", "lever_ratio",
    "damping_split", "made_tensioner", "hubload_loading_n", "hubload_unloading_n", "asymmetry_ratio", "characterisation",
    "sensitivity", "axial_damping_nm", "axial_force_required_n", "axial_group_class",
]


def friction_circle_factor(mu, friction_circle: bool = True):
    """Radius factor of the friction circle: ``sin(atan(mu))`` (eq. (10), corrected).

    The printed ``sin(phi_pb)`` of a friction coefficient is read as the sine of
    the friction angle. ``friction_circle=False`` uses ``mu`` itself, as the
    thesis tool's tables do (the two differ by ~mu^3/2: 1.1 % at mu = 0.15).

    >>> round(float(friction_circle_factor(0.15)), 5), float(friction_circle_factor(0.15, False))
    (0.14834, 0.15)
    """
    mu = np.asarray(mu, float)
    return np.sin(np.arctan(mu)) if friction_circle else mu


def lever_mm(working_arm_mm, differential_angle_deg):
    """Lever of the hubload about the pivot: ``e_w sin(alpha)`` [mm] (eq. (7), corrected).

    Eq. (7) prints ``cos(alpha)``; eq. (12)-(13) use ``sin``, and with ``cos``
    case 3 (alpha = 90 deg) would divide by zero.

    >>> round(float(lever_mm(5.0, 85.0)), 4)
    4.981
    """
    return np.asarray(working_arm_mm, float) * np.sin(np.radians(np.asarray(differential_angle_deg, float)))


def hubload_nominal_n(calculated_torque_nm, working_arm_mm, differential_angle_deg):
    """Nominal hubload from the calculated torque, eq. (7): ``HL = T_c / (e_w sin(alpha))`` [N].

    >>> round(float(hubload_nominal_n(3.25, 5.0, 85.0)), 1)
    652.5
    """
    return 1000.0 * np.asarray(calculated_torque_nm, float) / lever_mm(working_arm_mm, differential_angle_deg)


def lever_ratio(pivot_diameter_mm, mu_pivot_bushing, working_arm_mm, differential_angle_deg,
                friction_circle: bool = True):
    """``rho = r_p sin(atan(mu)) / (e_w sin(alpha))``: friction circle over lever (eq. (12)-(13)).

    >>> round(float(lever_ratio(21.0, 0.15, 4.0, 90.0, friction_circle=False)), 5)
    0.39375
    """
    r_p = np.asarray(pivot_diameter_mm, float) / 2.0
    return r_p * friction_circle_factor(mu_pivot_bushing, friction_circle) / lever_mm(working_arm_mm,
                                                                                        differential_angle_deg)


def damping_split(calculated_torque_target_nm, damping_target_nm, rho, axial_allowed=True):
    """Split the damping target into radial and axial parts (eq. (9)-(13), step 3).

    Returns a dict of arrays: ``radial_damping_nm`` (``T_c rho``),
    ``axial_damping_nm`` (``D - T_c rho``, 0 where not positive or not
    allowed), ``axial_damping_present`` (bool), ``spring_torque_nominal_nm``
    (``T_c - D rho`` with axial damping, ``T_c (1 - rho^2)`` without) and
    ``damping_nm`` (the damping the design really gives:
    ``D`` with axial damping, ``T_c rho`` without).

    >>> s = damping_split(1.85, 0.45, 0.39375)
    >>> round(float(s["spring_torque_nominal_nm"]), 2), bool(s["axial_damping_present"])
    (1.56, False)
    """
    t = np.asarray(calculated_torque_target_nm, float)
    d = np.asarray(damping_target_nm, float)
    rho = np.asarray(rho, float)
    d_rad = t * rho
    d_ax_raw = d - d_rad
    present = (d_ax_raw > 0) & np.asarray(axial_allowed, bool)
    d_ax = np.where(present, d_ax_raw, 0.0)
    m_s = np.where(present, t - d * rho, t * (1.0 - rho ** 2))
    return {
        "radial_damping_nm": d_rad,
        "axial_damping_nm": d_ax,
        "axial_damping_present": present,
        "spring_torque_nominal_nm": m_s,
        "damping_nm": np.where(present, d, d_rad),
    }



def made_tensioner(spring_torque_nm, axial_damping_nm, rho):
    """The characterisation of a made tensioner at its nominal position, eq. (12)-(13) forward [Nm].

    A made spring gives its own torque ``M_s`` (the spring maker holds the
    torque of eq. (66) within its tolerance), the axial group its ``D_ax`` and
    the pivot bushing its friction circle ``rho`` (eq. (12)-(13)): the torques
    at the pulley in loading and unloading are ``(M_s + D_ax)/(1 - rho)`` and
    ``(M_s - D_ax)/(1 + rho)``, so

    ``T_c = (M_s + D_ax rho)/(1 - rho^2)``, ``D = (D_ax + M_s rho)/(1 - rho^2)``.

    :func:`damping_split` is this relation solved for the design (``M_s``
    from the targets): a made tensioner at its design's values gives the
    targets back. Returns ``calculated_torque_nm``, ``damping_nm`` and
    ``radial_damping_nm`` (``D - D_ax``). ``0 <= rho < 1``.

    Case 3's production tensioner (spring torque 1.60 N m, 21 mm pivot, 4 mm arm; its specification: 0.45 +/-
    0.20 N m): with the thesis tool's mu 0.15 it would damp 0.746 N m, above its window; with 0.10 it damps 0.451:

    >>> [round(float(made_tensioner(1.60, 0.0, lever_ratio(21.0, mu, 4.0, 90.0, friction_circle=False))["damping_nm"]),
    ...        3) for mu in (0.15, 0.10)]
    [0.746, 0.451]
    """
    m_s = np.asarray(spring_torque_nm, float)
    d_ax = np.asarray(axial_damping_nm, float)
    rho = np.asarray(rho, float)
    den = 1.0 - rho ** 2
    t_c = (m_s + d_ax * rho) / den
    d = (d_ax + m_s * rho) / den
    return {"calculated_torque_nm": t_c, "damping_nm": d, "radial_damping_nm": d - d_ax}


def hubload_loading_n(spring_torque_nm, axial_damping_nm, working_arm_mm, differential_angle_deg,
                      pivot_diameter_mm, mu_pivot_bushing, friction_circle: bool = True):
    """Hubload in loading, eq. (12) corrected: ``(M_s + D_ax) / (e_w sin(alpha) - r_p sin(atan(mu)))`` [N].

    Where the denominator is not positive the arm self-locks: the result is
    ``inf``.

    >>> round(float(hubload_loading_n(1.563, 0.0, 4.0, 90.0, 21.0, 0.15, False)), 1)
    644.5
    """
    num = np.asarray(spring_torque_nm, float) + np.asarray(axial_damping_nm, float)
    den = lever_mm(working_arm_mm, differential_angle_deg) - np.asarray(pivot_diameter_mm, float) / 2.0 \
        * friction_circle_factor(mu_pivot_bushing, friction_circle)
    safe = np.where(den > 0, den, 1.0)
    return np.where(den > 0, 1000.0 * num / safe, np.inf)


def hubload_unloading_n(spring_torque_nm, axial_damping_nm, working_arm_mm, differential_angle_deg,
                        pivot_diameter_mm, mu_pivot_bushing, friction_circle: bool = True):
    """Hubload in unloading, eq. (13) corrected: ``(M_s - D_ax) / (e_w sin(alpha) + r_p sin(atan(mu)))`` [N].

    Clipped at 0 N: a damping above the spring torque leaves the arm on its
    stop rather than pulling the belt.

    >>> round(float(hubload_unloading_n(1.563, 0.0, 4.0, 90.0, 21.0, 0.15, False)), 1)
    280.3
    """
    num = np.asarray(spring_torque_nm, float) - np.asarray(axial_damping_nm, float)
    den = lever_mm(working_arm_mm, differential_angle_deg) + np.asarray(pivot_diameter_mm, float) / 2.0 \
        * friction_circle_factor(mu_pivot_bushing, friction_circle)
    return np.maximum(1000.0 * num / den, 0.0)


def asymmetry_ratio(axial_damping_nm, hubload_loading_n_, hubload_unloading_n_, pivot_diameter_mm,
                    mu_pivot_bushing, friction_circle: bool = True):
    """Damping asymmetry ratio ``D_h / D_l``, eq. (14)-(16).

    ``D_h = D_ax + HL_max r_p f``, ``D_l = D_ax + HL_min r_p f`` with
    ``f = sin(atan(mu))``. Equals 1 for purely axial damping; grows with the
    radial share. Returns 1 where both are zero (no friction at all).

    >>> round(float(asymmetry_ratio(0.0, 644.5, 280.4, 21.0, 0.15, False)), 3)
    2.299
    """
    rf = np.asarray(pivot_diameter_mm, float) / 2000.0 * friction_circle_factor(mu_pivot_bushing, friction_circle)
    d_ax = np.asarray(axial_damping_nm, float)
    d_h = d_ax + np.asarray(hubload_loading_n_, float) * rf
    d_l = d_ax + np.asarray(hubload_unloading_n_, float) * rf
    return np.where(d_l > 0, d_h / np.where(d_l > 0, d_l, 1.0), np.where(d_h > 0, np.inf, 1.0))


def characterisation(spring_torque_nominal_nm, spring_stiffness_nm_per_deg, axial_damping_nm, working_arm_mm,
                     differential_angle_deg, pivot_diameter_mm, mu_pivot_bushing, theta_deg,
                     friction_circle: bool = True, alpha_follows_arm: bool = True):
    """Static characterisation (hysteresis cycle, Fig. 15-16) over arm positions ``theta_deg``.

    ``theta_deg`` is the arm rotation from nominal, positive in the loading
    direction. The spring torque follows eq. (8), ``M_s = T_nom + k_t theta``;
    with ``alpha_follows_arm`` the differential angle changes with the arm,
    ``alpha = alpha_nom + theta`` (the hubload direction is fixed by the belt
    spans), otherwise it is held at nominal.

    Returns a dict of arrays over theta: ``spring_torque_nm``,
    ``hubload_loading_n``, ``hubload_unloading_n``, ``torque_loading_nm``,
    ``torque_unloading_nm`` (hubload times lever), ``calculated_torque_nm``,
    ``damping_nm``, ``asymmetry_ratio``, ``differential_angle_deg``.

    >>> c = characterisation(1.563, 0.0164, 0.0, 4.0, 90.0, 21.0, 0.15, [0.0], friction_circle=False)
    >>> round(float(c["calculated_torque_nm"][0]), 3), round(float(c["damping_nm"][0]), 3)
    (1.85, 0.728)
    """
    theta = np.asarray(theta_deg, float)
    m_s = np.asarray(spring_torque_nominal_nm, float) + np.asarray(spring_stiffness_nm_per_deg, float) * theta
    alpha = np.asarray(differential_angle_deg, float) + (theta if alpha_follows_arm else 0.0)
    alpha = np.clip(alpha, 1e-6, 180.0 - 1e-6)
    args = (working_arm_mm, alpha, pivot_diameter_mm, mu_pivot_bushing, friction_circle)
    hl_max = hubload_loading_n(m_s, axial_damping_nm, *args)
    hl_min = hubload_unloading_n(m_s, axial_damping_nm, *args)
    lev = lever_mm(working_arm_mm, alpha) / 1000.0
    t_max, t_min = hl_max * lev, hl_min * lev
    return {
        "theta_deg": theta,
        "differential_angle_deg": alpha,
        "spring_torque_nm": m_s,
        "hubload_loading_n": hl_max,
        "hubload_unloading_n": hl_min,
        "torque_loading_nm": t_max,
        "torque_unloading_nm": t_min,
        "calculated_torque_nm": (t_max + t_min) / 2.0,
        "damping_nm": (t_max - t_min) / 2.0,
        "asymmetry_ratio": asymmetry_ratio(axial_damping_nm, hl_max, hl_min, pivot_diameter_mm, mu_pivot_bushing,
                                           friction_circle),
    }


def sensitivity(parameter: str, values, *, spring_torque_nominal_nm, axial_damping_nm, working_arm_mm,
                differential_angle_deg, pivot_diameter_mm, mu_pivot_bushing, mu_plastic=None,
                friction_circle: bool = True):
    """Sensitivity of calculated torque, damping and asymmetry to one parameter (Fig. 17-19).

    ``parameter`` is ``differential_angle_deg`` (Fig. 17), ``mu_pivot_bushing``
    (Fig. 18) or ``mu_plastic`` (Fig. 19: the axial damping scales with the
    plastic friction coefficient, eq. (9), from its nominal ``mu_plastic``).
    The design (spring torque, cone-spring force) is held fixed.

    >>> s = sensitivity("mu_pivot_bushing", [0.0, 0.15], spring_torque_nominal_nm=1.563, axial_damping_nm=0.0,
    ...                 working_arm_mm=4.0, differential_angle_deg=90.0, pivot_diameter_mm=21.0,
    ...                 mu_pivot_bushing=0.15, friction_circle=False)
    >>> [round(float(x), 3) for x in s["damping_nm"]]
    [0.0, 0.728]
    """
    values = np.asarray(values, float)
    kw = dict(alpha=differential_angle_deg, mu_pb=mu_pivot_bushing, d_ax=axial_damping_nm)
    if parameter == "differential_angle_deg":
        kw["alpha"] = values
    elif parameter == "mu_pivot_bushing":
        kw["mu_pb"] = values
    elif parameter == "mu_plastic":
        if not mu_plastic:
            raise ValueError("mu_plastic sensitivity needs the nominal mu_plastic")
        kw["d_ax"] = np.asarray(axial_damping_nm, float) * values / mu_plastic
    else:
        raise ValueError(f"parameter: got {parameter!r}; accepted: differential_angle_deg, mu_pivot_bushing, mu_plastic")
    c = characterisation(spring_torque_nominal_nm, 0.0, kw["d_ax"], working_arm_mm, kw["alpha"], pivot_diameter_mm,
                         kw["mu_pb"], np.zeros_like(values), friction_circle, alpha_follows_arm=False)
    c["values"] = values
    return c


def axial_damping_nm(axial_force_n, mu_plastic, damper_pad_mean_radius_mm, endcap_spacer_mean_radius_mm):
    """Axial damping, eq. (9): ``D_ax = F_ax mu (R_dp + R_es)`` [Nm].

    >>> round(float(axial_damping_nm(500.0, 0.13, 12.5, 13.5)), 3)
    1.69
    """
    r = (np.asarray(damper_pad_mean_radius_mm, float) + np.asarray(endcap_spacer_mean_radius_mm, float)) / 1000.0
    return np.asarray(axial_force_n, float) * np.asarray(mu_plastic, float) * r


def axial_force_required_n(axial_damping_nm_, mu_plastic, damper_pad_mean_radius_mm, endcap_spacer_mean_radius_mm):
    """Cone-spring force giving the axial damping, eq. (9) inverted [N].

    >>> round(float(axial_force_required_n(1.69, 0.13, 12.5, 13.5)), 1)
    500.0
    """
    r = (np.asarray(damper_pad_mean_radius_mm, float) + np.asarray(endcap_spacer_mean_radius_mm, float)) / 1000.0
    return np.asarray(axial_damping_nm_, float) / (np.asarray(mu_plastic, float) * r)


def axial_group_class(axial_damping_nm_, class_max_axial_damping_nm):
    """Row of thesis Table 3 (damper pad) or Table 4 (endcap spacer) for an axial damping (step 3) [index].

    Both tables are entered with the axial damping ``D_ax`` of eq. (9), the
    friction torque of both faces together ("Damper pad dimensions as a
    function of the axial damping", rows ``DAX < 0.7``, ``0.7 < DAX < 1.10``,
    ``1.10 < DAX < 2.00`` Nm), not with a share of it. The row is the first
    whose upper bound ``class_max_axial_damping_nm`` (the catalog's
    ``max_axial_damping_nm``, in any row order) is not below ``D_ax``: the
    printed open intervals leave their bounds to neither row, synth gives a
    bound to the lower row, as the registry's capacity checks
    (``D_ax <= class max``) do.

    Returns ``(row, within)``: the catalog row (above every bound: the row of
    the largest bound) and whether ``D_ax`` is within the table (False above
    every bound, where that row's capacity check fails).

    >>> i, ok = axial_group_class([0.5, 0.7, 0.71, 1.71, 2.5], [0.70, 1.10, 2.00])
    >>> i.tolist(), ok.tolist()
    ([0, 0, 1, 2, 2], [True, True, True, True, False])
    """
    caps = np.asarray(class_max_axial_damping_nm, float)
    order = np.argsort(caps, kind="stable")
    k = np.searchsorted(caps[order], np.asarray(axial_damping_nm_, float), side="left")
    return order[np.minimum(k, len(caps) - 1)], k < len(caps)
