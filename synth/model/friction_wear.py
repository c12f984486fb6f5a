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
* ``fidelity="full"``: ``scipy.integrate.solve_ivp`` of the two wear depths of
  every design at once along the Almen-Laszlo characteristic
  (:func:`synth.model.disc_spring.disc_spring_force_n`), with the
  relaxation acting on the force during the test.

Units: lengths mm, areas mm^2, forces N, torques N m, pressures MPa, speeds
m/s, times h, wear constants mm^3/(N m).

>>> round(float(sliding_speed_m_per_s(16.0, 12.5, 50.0)), 4)
0.3491
"""

from __future__ import annotations

import numpy as np
from scipy.integrate import solve_ivp

from synth import catalog
from synth.checks import Check, margin_lower, margin_upper
from synth.errors import InputError, Problem
from synth.model.disc_spring import (_broadcast_all, axial_damping_nm, disc_spring_force_n,
                                              disc_spring_rate_n_per_mm)

__all__ = [
    "FIDELITIES",
    "APPLICATION_TYPES",
    "plastic_material",
    "sliding_speed_m_per_s",
    "contact_pressure_mpa",
    "relaxation_factor",
    "plastic_wear",
    "plastic_wear_checks",
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


def plastic_wear(initial_deflection_mm, outer_diameter_mm, inner_diameter_mm, thickness_mm, cone_height_mm,
                 damper_pad_contact_area_mm2, damper_pad_mean_radius_mm, damper_pad_axial_height_mm,
                 endcap_spacer_contact_area_mm2, endcap_spacer_mean_radius_mm, endcap_spacer_axial_height_mm,
                 durability_theta_peak_to_peak_deg, durability_frequency_hz, durability_duration_h,
                 radial_damping_nm, damping_eol_limit_nm, *,
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
    ``radial_damping_nm`` (step 3) and ``damping_eol_limit_nm`` (input).
    ``material``/``application_type`` select ``k_wear`` and ``mu`` from
    ``catalogs/plastic_wear.csv`` unless given explicitly. A zero duration gives
    zero wear.

    Returns ``damper_pad_wear_mm``, ``endcap_spacer_wear_mm``,
    ``plastic_wear_total_mm``, ``cone_spring_force_initial_n``,
    ``cone_spring_force_eol_n``, ``cone_spring_deflection_eol_mm``,
    ``damper_pad_pressure_initial_mpa``, ``endcap_spacer_pressure_initial_mpa``,
    ``damper_pad_sliding_speed_m_per_s``, ``endcap_spacer_sliding_speed_m_per_s``,
    ``axial_damping_initial_nm``, ``axial_damping_eol_nm``, ``damping_initial_nm``,
    ``damping_eol_nm``, and ``margins``: ``damping_eol`` (EOL damping >= limit),
    ``damper_pad_wear`` and ``endcap_spacer_wear`` (wear <= allowed fraction
    of the element height, ``plastic_max_wear_fraction``). With
    ``time_points > 0`` also ``history``: ``time_h``, ``plastic_wear_total_mm``,
    ``cone_spring_force_n``, ``damping_nm`` arrays of shape ``(time_points,) +
    design shape`` (thesis Fig. 42-45).

    >>> r = plastic_wear(0.668, 30.0, 16.2, 0.742, 0.890, 460, 12.5, 3.5, 490, 13.5, 1.5,
    ...                  16, 50, 1200, 0.287, 1.5, fidelity="screening")
    >>> round(float(r["plastic_wear_total_mm"]), 3), round(float(r["damping_eol_nm"]), 2)
    (0.294, 1.52)
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
    shape = np.broadcast(s0, f0, c_dp, c_es, duration, _f(radial_damping_nm), _f(damping_eol_limit_nm),
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
        n = int(np.prod(shape)) if shape else 1
        flat = [np.ravel(x) for x in (s0, c_dp, c_es, t_end_s)]
        s0_f, cdp_f, ces_f, te_f = flat
        geo_f = tuple(np.ravel(g) for g in geo_b)

        def force(tau_, w_tot):
            rho = relaxation_factor(tau_ * te_f / 3600.0, relaxation_pct, relaxation_time_h)
            return rho * disc_spring_force_n(s0_f - w_tot, *geo_f, **kwg)

        def rhs(tau_, y):
            f = force(tau_, y[:n] + y[n:])
            return np.concatenate((te_f * cdp_f * f, te_f * ces_f * f))

        sol = solve_ivp(rhs, (0.0, 1.0), np.zeros(2 * n), method="RK45", t_eval=tau if n_t > 0 else [1.0],
                        rtol=catalog.constant("plastic_wear_ode_rtol"),
                        atol=catalog.constant("plastic_wear_ode_atol_mm"))
        if not sol.success:  # pragma: no cover - RK45 on a bounded, Lipschitz right-hand side
            raise RuntimeError(f"plastic wear integration failed: {sol.message}")
        y_end = sol.y[:, -1]
        w_dp_f, w_es_f = y_end[:n], y_end[n:]
        w = (w_dp_f + w_es_f).reshape(shape)
        split_dp = w_dp_f.reshape(shape)
        f_eol = force(1.0, w_dp_f + w_es_f).reshape(shape)
        if n_t > 0:
            w_hist = (sol.y[:n] + sol.y[n:]).T.reshape((n_t,) + shape)
            f_hist = np.stack([force(tt, sol.y[:n, i] + sol.y[n:, i]) for i, tt in enumerate(sol.t)]).reshape((n_t,) + shape)

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
        "margins": {
            "damping_eol": margin_lower(dax_eol + d_rad, damping_eol_limit_nm),
            "damper_pad_wear": margin_upper(w_dp, frac * h_dp),
            "endcap_spacer_wear": margin_upper(w_es, frac * h_es),
        },
    }
    out = _broadcast_all(out)
    if n_t > 0:
        out["history"] = {
            "time_h": tau.reshape((-1,) + (1,) * len(shape)) * t_end_h,
            "plastic_wear_total_mm": w_hist,
            "cone_spring_force_n": f_hist,
            "damping_nm": axial_damping_nm(f_hist, mu, r_dp, r_es) + d_rad,
        }
    return out


def plastic_wear_checks(result: dict, damping_eol_limit_nm, damper_pad_axial_height_mm,
                        endcap_spacer_axial_height_mm, index=()) -> list[Check]:
    """:class:`synth.checks.Check` records of one design of :func:`plastic_wear` (step 5).

    >>> r = plastic_wear(0.668, 30.0, 16.2, 0.742, 0.890, 460, 12.5, 3.5, 490, 13.5, 1.5,
    ...                  16, 50, 1200, 0.287, 1.5, fidelity="screening")
    >>> [c.verdict for c in plastic_wear_checks(r, 1.5, 3.5, 1.5)]
    ['pass', 'pass', 'pass']
    """
    def v(key):
        return float(np.asarray(result[key])[index])

    def s(x):
        return float(np.broadcast_to(np.asarray(x, dtype=float), np.shape(result["plastic_wear_total_mm"]))[index])

    frac = catalog.constant("plastic_max_wear_fraction")
    return [
        Check("end-of-life damping", 5, v("damping_eol_nm"), s(damping_eol_limit_nm), ">=", "N m",
              "eq. (9), (11), (43)-(49)",
              correction="the next damper pad / endcap spacer class (larger contact surfaces, Tables 3-4)",
              note=f"axial {v('axial_damping_eol_nm'):.3g} N m at EOL"),
        Check("damper pad wear", 5, v("damper_pad_wear_mm"), frac * s(damper_pad_axial_height_mm), "<=", "mm",
              "eq. (44)-(46)", note=f"limit = {frac:g} x axial height (illustrative)"),
        Check("endcap spacer wear", 5, v("endcap_spacer_wear_mm"), frac * s(endcap_spacer_axial_height_mm), "<=", "mm",
              "eq. (47)-(49)", note=f"limit = {frac:g} x axial height (illustrative)"),
    ]
