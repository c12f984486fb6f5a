"""Step 5 of the thesis flowchart: wear of the plastic friction elements.

The cone spring presses the damper pad and the endcap spacer against the arm;
their rubbing gives the axial damping :math:`D_{ax} = F_{ax}\\,\\mu\\,(R_{m,dp} +
R_{m,es})` (thesis eq. (9)). Over the durability test both plastics wear
(Archard/Reye: wear depth rate = k p v), the gap of the cone spring grows by
the total wear (eq. (43)), the spring relaxes along its characteristic and
sets (relaxation), the force falls, and with it the pressure, the wear rate
and the axial damping (thesis eq. (43)-(49), Fig. 41-46).

* ``fidelity="screening"``: the characteristic linearised at the initial
  deflection (tangent) and solved in closed form,
  :math:`w(t) = F_0/R\\,(1 - e^{-aRt})`; relaxation applied to the end-of-life
  force only (wear computed at the unrelaxed force: an upper bound).
* ``fidelity="full"``: the exact solution along the Almen-Laszlo
  characteristic (:func:`synth.model.disc_spring.disc_spring_force_n`) with
  the relaxation acting on the force during the test. The wear law
  :math:`dw/dt = c\\,\\rho(t)\\,F(s_0 - w)` separates:
  :math:`\\int_{s}^{s_0} du/F(u) = c \\int_0^t \\rho`, and for a disc without
  contact flats :math:`F(u) = u\\,q(u)` with a quadratic ``q``, so the left side
  has a closed form (:func:`wear_integral`); the deflection ``s`` at any time
  is its root (``scipy.optimize.elementwise.find_root``, element by element:
  each design's result does not depend on the others evaluated with it).

Units: lengths mm, areas mm^2, forces N, torques N m, pressures MPa, speeds
m/s, times h, wear constants mm^3/(N m).

>>> round(float(sliding_speed_m_per_s(16.0, 12.5, 50.0)), 4)
0.3491
"""

from __future__ import annotations

import numpy as np

from synth import catalog
from synth.errors import InputError, Problem
from synth.model.disc_spring import (elastic_constants, axial_damping_nm, disc_spring_factors,
                                     disc_spring_force_n, disc_spring_rate_n_per_mm)

__all__ = [
    "FIDELITIES",
    "APPLICATION_TYPES",
    "plastic_material",
    "sliding_speed_m_per_s",
    "contact_pressure_mpa",
    "relaxation_factor",
    "relaxation_integral_h",
    "wear_integral",
    "plastic_wear",
]

FIDELITIES = ("screening", "full")
APPLICATION_TYPES = ("belt_in_oil", "dry")

_EPS = np.finfo(float).eps


def _f(x):
    return np.asarray(x, dtype=float)


def plastic_material(material: str = "PPA_CF10_AR10_PTFE", application_type: str = "belt_in_oil") -> dict:
    """Wear constant and friction coefficient of a plastic friction element (``catalogs/plastic_wear.csv``).

    Returns ``k_wear_mm3_per_n_m`` (specific wear rate of the Archard/Reye
    law, thesis eq. (44) ``kw_plastic``) and ``plastic_friction_coefficient``
    (thesis eq. (9) ``phi_plastic``) for ``application_type`` ``belt_in_oil``
    or ``dry``. Unknown names raise :class:`synth.errors.InputError` listing the
    valid ones.

    >>> m = plastic_material()
    >>> m["k_wear_mm3_per_n_m"], m["plastic_friction_coefficient"]
    (1e-07, 0.129)
    """
    if application_type not in APPLICATION_TYPES:
        raise InputError(Problem("application_type", application_type, " or ".join(APPLICATION_TYPES)))
    r = catalog.row("plastic_wear", material, field="plastic_material")
    suffix = "belt_in_oil" if application_type == "belt_in_oil" else "dry"
    return {"k_wear_mm3_per_n_m": float(r[f"k_wear_{suffix}_mm3_per_n_m"]),
            "plastic_friction_coefficient": float(r[f"mu_{suffix}"])}


def sliding_speed_m_per_s(theta_peak_to_peak_deg, mean_radius_mm, frequency_hz):
    """Mean sliding speed of a plastic element, thesis eq. (46) and (49) [m/s].

    :math:`v = 2\\,\\theta_{pp}\\,\\pi\\,R_m\\,f / 180`: the arc ``2 theta_pp``
    swept per oscillation cycle at the mean radius, times the frequency.
    ``theta_peak_to_peak_deg`` in degrees, ``mean_radius_mm`` in mm.

    >>> round(float(sliding_speed_m_per_s(16.0, 13.5, 50.0)), 4)
    0.377
    """
    return 2.0 * _f(theta_peak_to_peak_deg) * np.pi * _f(mean_radius_mm) * 1e-3 * _f(frequency_hz) / 180.0


def contact_pressure_mpa(axial_force_n, contact_area_mm2):
    """Mean contact pressure of a plastic element, thesis eq. (45) and (48) corrected [MPa].

    :math:`p = F_{ax}/A_c` (the thesis prints :math:`A_c/F_{ax}`, dimensionally
    an inverse pressure; see NOTES.md and docs). Negative forces give 0; the
    area must be positive (:class:`InputError`).

    >>> round(float(contact_pressure_mpa(509.0, 460.0)), 4)
    1.1065
    """
    a = _f(contact_area_mm2)
    if not np.all(a > 0):
        raise InputError(Problem("contact_area_mm2", np.ravel(a[a <= 0] if a.ndim else a)[:3].tolist(), "> 0"))
    return np.maximum(_f(axial_force_n), 0.0) / a


def relaxation_factor(time_h, relaxation_pct=None, relaxation_time_h=None):
    """Share of the cone-spring force left after setting (relaxation), thesis step 5 [-].

    The thesis tool takes the setting loss as "x % of axial force lost in y
    hours"; we let it grow linearly to ``relaxation_pct`` at
    ``relaxation_time_h`` and stay there:
    :math:`\\rho(t) = 1 - \\frac{x}{100}\\min(t/y, 1)` (``y = 0``: immediate).
    Defaults (5 % in 100 h, the thesis's simulation values) from
    ``constants_plastic_wear.csv``.

    >>> relaxation_factor([0.0, 50.0, 100.0, 1200.0]).round(4).tolist()
    [1.0, 0.975, 0.95, 0.95]
    """
    x = catalog.constant("cone_spring_relaxation_pct") if relaxation_pct is None else relaxation_pct
    y = catalog.constant("cone_spring_relaxation_time_h") if relaxation_time_h is None else relaxation_time_h
    t, x, y = _f(time_h), _f(x), _f(y)
    frac = np.where(y > 0, np.minimum(t / np.where(y > 0, y, 1.0), 1.0), 1.0)
    frac = np.where(t > 0, frac, 0.0)  # nothing is lost before the test starts
    return 1.0 - x / 100.0 * frac


def relaxation_integral_h(time_h, relaxation_pct=None, relaxation_time_h=None):
    """Time integral of :func:`relaxation_factor` from 0 to ``time_h`` [h].

    :math:`R(t) = t - \\frac{x}{100}\\,(t^2/(2y))` for ``t <= y``, else
    :math:`t - \\frac{x}{100}(t - y/2)`; ``y = 0``: :math:`t (1 - x/100)`.

    >>> relaxation_integral_h([0.0, 100.0, 1200.0]).round(3).tolist()
    [0.0, 97.5, 1142.5]
    """
    x = catalog.constant("cone_spring_relaxation_pct") if relaxation_pct is None else relaxation_pct
    y = catalog.constant("cone_spring_relaxation_time_h") if relaxation_time_h is None else relaxation_time_h
    t, x, y = np.maximum(_f(time_h), 0.0), _f(x) / 100.0, _f(y)
    y_safe = np.where(y > 0, y, 1.0)
    lost = np.where(y > 0, np.where(t <= y, t * t / (2.0 * y_safe), t - y / 2.0), t)
    return t - x * lost


def wear_integral(deflection_mm, outer_diameter_mm, inner_diameter_mm, thickness_mm, cone_height_mm,
                  youngs_modulus_mpa=None, poisson_ratio=None):
    """Antiderivative :math:`\\Phi(u) = \\int du / F(u)` of the Almen-Laszlo force (no contact flats) [mm/N].

    :math:`F(u) = u\\,q(u)`, :math:`q = \\alpha + \\beta u + \\gamma u^2` with
    :math:`\\alpha = S t^3 (z^2+1)`, :math:`\\beta = -\\tfrac32 S t^2 z`, :math:`\\gamma = \\tfrac12 S t`,
    :math:`z = h_0/t`, :math:`S = 4E/((1-\\mu^2) K_1 D_e^2)` (DIN EN 16984), so

    .. math::
        \\Phi(u) = \\frac{\\ln u}{\\alpha} - \\frac{\\ln q(u)}{2\\alpha}
                 - \\frac{\\beta}{\\alpha\\sqrt{\\Delta}}\\arctan\\frac{2\\gamma u + \\beta}{\\sqrt{\\Delta}},
        \\quad \\Delta = 4\\alpha\\gamma - \\beta^2 = S^2 t^4 (2 - z^2/4) > 0 \\ (z < 2\\sqrt 2).

    ``deflection_mm`` may be given as ``(log_mm,)`` -- see :func:`plastic_wear`.
    Check against a numerical quadrature of 1/F between 0.2 and 0.6 mm:

    >>> from scipy.integrate import quad
    >>> geo = (30.0, 16.2, 0.742, 0.890)
    >>> ref = quad(lambda u: 1.0 / float(disc_spring_force_n(u, *geo)), 0.2, 0.6)[0]
    >>> bool(abs(float(wear_integral(0.6, *geo) - wear_integral(0.2, *geo)) / ref - 1.0) < 1e-10)
    True
    """
    return _wear_phi(np.log(_f(deflection_mm)), _f(deflection_mm), *_wear_coefficients(
        outer_diameter_mm, inner_diameter_mm, thickness_mm, cone_height_mm, youngs_modulus_mpa, poisson_ratio))


def _wear_coefficients(outer_diameter_mm, inner_diameter_mm, thickness_mm, cone_height_mm, e=None, nu=None):
    e, nu = elastic_constants(e, nu)
    k1 = disc_spring_factors(outer_diameter_mm, inner_diameter_mm)["k1"]
    t, z = _f(thickness_mm), _f(cone_height_mm) / _f(thickness_mm)
    s = 4.0 * e / (1.0 - nu ** 2) / (k1 * _f(outer_diameter_mm) ** 2)
    alpha, beta, gamma = s * t ** 3 * (z * z + 1.0), -1.5 * s * t * t * z, 0.5 * s * t
    return alpha, beta, gamma, np.sqrt(4.0 * alpha * gamma - beta * beta)


def _wear_phi(log_u, u, alpha, beta, gamma, root):
    q = alpha + beta * u + gamma * u * u
    return log_u / alpha - np.log(q) / (2.0 * alpha) - beta / (alpha * root) * np.arctan((2.0 * gamma * u + beta) / root)


def _deflection_after(s0, target, coef):
    """Deflection ``s`` with ``Phi(s0) - Phi(s) = target`` (>= 0), solved for ``v = ln(s0/s)`` in a proven bracket.

    ``1/(u q(u)) >= 1/(u q_max)`` on ``(0, s0]`` (``q`` convex: its maximum is at an end), so
    ``v = target * q_max`` already reaches the target: the root lies in ``[0, target * q_max]``.
    A tiny target (``v`` below ``sqrt(eps)``, e.g. a wear coefficient near zero) is below the round-off of
    ``Phi(s0) - Phi(s)``: there ``v = target q(s0)`` (first order, ``dPhi/dv = 1/q``; relative error ~ v).
    """
    from scipy.optimize.elementwise import find_root
    alpha, beta, gamma, root = coef
    q_max = np.maximum(alpha, alpha + beta * s0 + gamma * s0 * s0)
    phi0 = _wear_phi(np.log(s0), s0, *coef)

    def f(v, s0_, phi0_, target_, a, b, g, r):
        u = s0_ * np.exp(-v)
        return phi0_ - _wear_phi(np.log(s0_) - v, u, a, b, g, r) - target_

    hi = np.maximum(target * q_max, 0.0) * (1.0 + 1e-9) + 1e-300
    res = find_root(f, (np.zeros_like(hi), hi), args=(s0, phi0, target, alpha, beta, gamma, root),
                    tolerances={"xatol": 0.0, "xrtol": 4 * np.finfo(float).eps})
    v_first_order = target * (alpha + beta * s0 + gamma * s0 * s0)
    v = np.where(v_first_order < np.sqrt(np.finfo(float).eps), v_first_order, res.x)
    return np.where(target > 0, s0 * np.exp(-v), s0)


def plastic_wear(initial_deflection_mm, outer_diameter_mm, inner_diameter_mm, thickness_mm, cone_height_mm,
                 damper_pad_contact_area_mm2, damper_pad_mean_radius_mm, damper_pad_axial_height_mm,
                 endcap_spacer_contact_area_mm2, endcap_spacer_mean_radius_mm, endcap_spacer_axial_height_mm,
                 durability_theta_peak_to_peak_deg, durability_frequency_hz, durability_duration_h,
                 radial_damping_nm, *,
                 material: str = "PPA_CF10_AR10_PTFE", application_type: str = "belt_in_oil",
                 k_wear_mm3_per_n_m=None, plastic_friction_coefficient=None,
                 relaxation_pct=None, relaxation_time_h=None,
                 fidelity: str = "full", time_points: int = 0) -> dict:
    """Wear of damper pad and endcap spacer over the durability test and end-of-life damping, eq. (43)-(49).

    .. math::
        \\frac{dw_{dp}}{dt} = k_w \\frac{F_{ax}}{A_{dp}} v_{dp},\\quad
        \\frac{dw_{es}}{dt} = k_w \\frac{F_{ax}}{A_{es}} v_{es},\\quad
        w_{pfe} = w_{dp} + w_{es}\\ \\text{(eq. (43))},\\quad
        F_{ax}(t) = \\rho(t)\\,F(s_0 - w_{pfe})

    (eq. (44)-(49) with the pressure corrected to force over area; ``F`` the
    cone-spring characteristic, ``s0`` its deflection at new, ``rho`` the
    relaxation of :func:`relaxation_factor`). The gap grows by the total wear,
    so the deflection falls; a spring that lifts off (``s <= 0``) exerts no
    force. End-of-life damping ``D = D_ax + D_rad`` with ``D_ax`` from eq. (9)
    and the radial damping of step 3 held constant (thesis step 5 text).

    Parameters (numpy arrays broadcast to one shape of designs):
    cone-spring geometry (``outer/inner_diameter_mm``, ``thickness_mm``,
    ``cone_height_mm``: step 8's outputs) and its deflection at new;
    the plastic elements (Tables 3-4: contact area, mean radius, axial height);
    the durability test (peak-to-peak angle, frequency, duration);
    ``radial_damping_nm`` (step 3).
    ``material``/``application_type`` select ``k_wear`` and ``mu`` from
    ``catalogs/plastic_wear.csv`` unless given explicitly. A zero duration gives
    zero wear.

    Returns ``damper_pad_wear_mm``, ``endcap_spacer_wear_mm``,
    ``plastic_wear_total_mm``, ``cone_spring_force_initial_n``,
    ``cone_spring_force_eol_n``, ``cone_spring_deflection_eol_mm``,
    ``damper_pad_pressure_initial_mpa``, ``endcap_spacer_pressure_initial_mpa``,
    ``damper_pad_sliding_speed_m_per_s``, ``endcap_spacer_sliding_speed_m_per_s``,
    ``axial_damping_initial_nm``, ``axial_damping_eol_nm``, ``damping_initial_nm``,
    ``damping_eol_nm``, and the wear limits ``damper_pad_wear_max_mm`` and
    ``endcap_spacer_wear_max_mm`` (the allowed fraction of the element height,
    ``plastic_max_wear_fraction``). With
    ``time_points > 0`` also ``history``: ``time_h``, ``plastic_wear_total_mm``,
    ``cone_spring_force_n``, ``damping_nm`` arrays of shape ``(time_points,) +
    design shape`` (thesis Fig. 42-45).

    >>> r = plastic_wear(0.668, 30.0, 16.2, 0.742, 0.890, 460, 12.5, 3.5, 490, 13.5, 1.5,
    ...                  16, 50, 1200, 0.287, fidelity="screening")
    >>> round(float(r["plastic_wear_total_mm"]), 3), round(float(r["damping_eol_nm"]), 2)
    (0.294, 1.52)
    >>> f = plastic_wear(0.668, 30.0, 16.2, 0.742, 0.890, 460, 12.5, 3.5, 490, 13.5, 1.5, 16, 50, 1200, 0.287)
    >>> round(float(f["plastic_wear_total_mm"]), 3), round(float(f["damping_eol_nm"]), 3)
    (0.287, 1.533)
    """
    if fidelity not in FIDELITIES:
        raise InputError(Problem("fidelity", fidelity, " or ".join(FIDELITIES)))
    mat = plastic_material(material, application_type)
    kw = _f(mat["k_wear_mm3_per_n_m"] if k_wear_mm3_per_n_m is None else k_wear_mm3_per_n_m)
    mu = _f(mat["plastic_friction_coefficient"] if plastic_friction_coefficient is None
            else plastic_friction_coefficient)
    if not np.all(kw >= 0):
        raise InputError(Problem("k_wear_mm3_per_n_m", np.ravel(kw).tolist()[:3], ">= 0"))
    duration = _f(durability_duration_h)
    if not np.all(duration >= 0):
        raise InputError(Problem("durability_duration_h", np.ravel(duration).tolist()[:3], ">= 0"))
    e = catalog.constant("cone_spring_youngs_modulus_mpa")
    nu = catalog.constant("cone_spring_poisson_ratio")
    geo = (outer_diameter_mm, inner_diameter_mm, thickness_mm, cone_height_mm)
    kwg = {"youngs_modulus_mpa": e, "poisson_ratio": nu}

    v_dp = sliding_speed_m_per_s(durability_theta_peak_to_peak_deg, damper_pad_mean_radius_mm, durability_frequency_hz)
    v_es = sliding_speed_m_per_s(durability_theta_peak_to_peak_deg, endcap_spacer_mean_radius_mm, durability_frequency_hz)
    a_dp, a_es = _f(damper_pad_contact_area_mm2), _f(endcap_spacer_contact_area_mm2)
    contact_pressure_mpa(0.0, a_dp), contact_pressure_mpa(0.0, a_es)  # validate areas
    # wear depth per newton and second [mm/(N s)]: k [mm^3/(N m)] * v [m/s] / A [mm^2]
    c_dp, c_es = kw * v_dp / a_dp, kw * v_es / a_es
    s0 = _f(initial_deflection_mm)
    f0 = disc_spring_force_n(s0, *geo, **kwg)
    shape = np.broadcast(s0, f0, c_dp, c_es, duration, _f(radial_damping_nm),
                         *(np.asarray(g) for g in geo)).shape
    s0, f0, c_dp, c_es, t_end_h = (np.broadcast_to(x, shape).astype(float) for x in (s0, f0, c_dp, c_es, duration))
    geo_b = tuple(np.broadcast_to(_f(g), shape) for g in geo)
    rho_end = relaxation_factor(t_end_h, relaxation_pct, relaxation_time_h)
    t_end_s = t_end_h * 3600.0
    n_t = int(time_points)
    tau = np.linspace(0.0, 1.0, n_t) if n_t > 0 else None

    if fidelity == "screening":
        def wear_total(tt_s, rate):
            x = (c_dp + c_es) * rate * tt_s
            xs = np.where(x > _EPS, x, 1.0)
            phi = np.where(x > _EPS, -np.expm1(-xs) / xs, 1.0 - 0.5 * x)  # (1 - e^-x)/x, -> 1 at x -> 0
            return f0 * (c_dp + c_es) * tt_s * phi

        # tangent at new (>= 0), then a few fixed-point passes of the secant of the
        # characteristic over the wear range found with the previous rate
        rate = np.maximum(disc_spring_rate_n_per_mm(s0, *geo_b, **kwg), 0.0)
        w = wear_total(t_end_s, rate)
        for _ in range(int(catalog.constant("plastic_wear_secant_passes"))):
            drop = f0 - disc_spring_force_n(s0 - w, *geo_b, **kwg)
            rate = np.maximum(np.where(w > _EPS, drop / np.where(w > _EPS, w, 1.0), rate), 0.0)
            w = wear_total(t_end_s, rate)
        f_eol_raw = np.maximum(f0 - rate * w, 0.0)
        f_eol = rho_end * f_eol_raw
        if n_t > 0:
            t_s = tau.reshape((-1,) + (1,) * len(shape)) * t_end_s
            w_hist = wear_total(t_s, rate)
            f_hist = relaxation_factor(t_s / 3600.0, relaxation_pct, relaxation_time_h) * np.maximum(f0 - rate * w_hist, 0.0)
    else:
        coef = _wear_coefficients(*geo_b, e, nu)
        rate_c = c_dp + c_es  # mm/(N s): dw/dt = rate_c rho(t) F(s0 - w)
        target_end = rate_c * 3600.0 * relaxation_integral_h(t_end_h, relaxation_pct, relaxation_time_h)
        live = s0 > 0
        s0_safe = np.where(live, s0, 1.0)
        s_end = np.where(live, _deflection_after(s0_safe, np.where(live, target_end, 0.0), coef), 0.0)
        w = s0 - s_end
        split_dp = np.where(rate_c > 0, c_dp / np.where(rate_c > 0, rate_c, 1.0), 0.5) * w
        f_eol = rho_end * disc_spring_force_n(s_end, *geo_b, **kwg)
        if n_t > 0:
            t_h = tau.reshape((-1,) + (1,) * len(shape)) * t_end_h
            target_t = rate_c * 3600.0 * relaxation_integral_h(t_h, relaxation_pct, relaxation_time_h)
            s_t = np.where(live, _deflection_after(np.broadcast_to(s0_safe, target_t.shape),
                                                   np.where(live, target_t, 0.0),
                                                   tuple(np.broadcast_to(c, target_t.shape) for c in coef)), 0.0)
            w_hist = s0 - s_t
            f_hist = relaxation_factor(t_h, relaxation_pct, relaxation_time_h) * disc_spring_force_n(s_t, *geo_b, **kwg)

    share_dp = np.where(c_dp + c_es > 0, c_dp / np.where(c_dp + c_es > 0, c_dp + c_es, 1.0), 0.5)
    w_dp = share_dp * w if fidelity == "screening" else split_dp
    w_es = w - w_dp
    r_dp, r_es = damper_pad_mean_radius_mm, endcap_spacer_mean_radius_mm
    d_rad = _f(radial_damping_nm)
    dax0 = axial_damping_nm(f0, mu, r_dp, r_es)
    dax_eol = axial_damping_nm(f_eol, mu, r_dp, r_es)
    frac = catalog.constant("plastic_max_wear_fraction")
    h_dp, h_es = _f(damper_pad_axial_height_mm), _f(endcap_spacer_axial_height_mm)
    out = {
        "damper_pad_wear_mm": w_dp,
        "endcap_spacer_wear_mm": w_es,
        "plastic_wear_total_mm": w,
        "cone_spring_force_initial_n": f0,
        "cone_spring_force_eol_n": f_eol,
        "cone_spring_deflection_eol_mm": s0 - w,
        "damper_pad_pressure_initial_mpa": contact_pressure_mpa(f0, a_dp),
        "endcap_spacer_pressure_initial_mpa": contact_pressure_mpa(f0, a_es),
        "damper_pad_sliding_speed_m_per_s": v_dp,
        "endcap_spacer_sliding_speed_m_per_s": v_es,
        "axial_damping_initial_nm": dax0,
        "axial_damping_eol_nm": dax_eol,
        "damping_initial_nm": dax0 + d_rad,
        "damping_eol_nm": dax_eol + d_rad,
        "damper_pad_wear_max_mm": frac * h_dp,
        "endcap_spacer_wear_max_mm": frac * h_es,
    }
    shape_all = np.broadcast_shapes(*(np.shape(v) for v in out.values()))
    out = {k: np.broadcast_to(_f(v), shape_all).copy() for k, v in out.items()}
    if n_t > 0:
        out["history"] = {
            "time_h": tau.reshape((-1,) + (1,) * len(shape)) * t_end_h,
            "plastic_wear_total_mm": w_hist,
            "cone_spring_force_n": f_hist,
            "damping_nm": axial_damping_nm(f_hist, mu, r_dp, r_es) + d_rad,
        }
    return out
