"""Step 8 of the thesis flowchart: the cone (disc) spring of the axial damping.

The cone spring presses the axial stack (damper pad, arm, endcap spacer) so
that the plastic elements rub on the arm: the axial damping is
:math:`D_{ax} = F_{ax}\\,\\mu_{plastic}\\,(R_{m,dp} + R_{m,es})` (thesis eq. (9)).
This module gives

* the disc-spring characteristic and stresses of Almen and Laszlo as
  standardised in DIN EN 16984:2017 (formerly DIN 2092:2006), thesis
  eq. (55)-(63): :func:`disc_spring_force_n`, :func:`disc_spring_rate_n_per_mm`,
  :func:`disc_spring_stresses_mpa`, with ``fidelity="screening"`` for the
  cheap linear (secant) characteristic and ``"full"`` for Almen-Laszlo;
* the axial force required by the damping split of step 3 (eq. (9) inverted),
  the force tolerance band the spring supplier must meet (thesis Fig. 68),
  the geometric limits (thesis Table 8 and step 8 text) and the checks of the
  supplier's optimal ranges (thesis Table 7);
* :func:`cone_spring`, the vectorised step: sizes a spring inside the limits
  and returns every value and normalised margin.

Units: lengths in mm, forces in N, torques in N m, stresses in MPa. The
elastic constants come from ``catalogs/constants_cone_spring.csv``.

>>> round(float(disc_spring_force_n(0.15, 8.0, 4.2, 0.4, 0.2)), 0)   # DIN 2093 A 8: 210 N
210.0
"""

from __future__ import annotations

import numpy as np

from synth import catalog
from synth.errors import InputError, Problem
from synth.model.damping import axial_damping_nm as eq9
from synth.model.damping import axial_force_required_n as eq9_inverse

__all__ = [
    "centred_cone_spring",
    "FIDELITIES",
    "disc_spring_factors",
    "disc_spring_k4",
    "disc_spring_force_n",
    "disc_spring_rate_n_per_mm",
    "disc_spring_stresses_mpa",
    "disc_spring_thickness_for_force_mm",
    "disc_spring_group",
    "force_tolerance_band_n",

    "axial_damping_nm",
    "required_axial_force_n",
    "axial_force_tolerance_band",
    "gap_force_shifts_n",
    "cone_spring_min_internal_diameter_mm",
    "cone_spring_max_external_diameter_mm",
    "table7_ratios",
    "cone_spring",
]

#: ``screening``: linear (secant) characteristic; ``full``: Almen-Laszlo.
FIDELITIES = ("screening", "full")


def _f(x):
    return np.asarray(x, dtype=float)


def _check_fidelity(fidelity: str) -> None:
    if fidelity not in FIDELITIES:
        raise InputError(Problem("fidelity", fidelity, " or ".join(FIDELITIES)))


def elastic_constants(youngs_modulus_mpa=None, poisson_ratio=None):
    """``(E, nu)`` of the cone spring's steel as arrays: the given values, else the catalog's constants."""
    e = catalog.constant("cone_spring_youngs_modulus_mpa") if youngs_modulus_mpa is None else youngs_modulus_mpa
    nu = catalog.constant("cone_spring_poisson_ratio") if poisson_ratio is None else poisson_ratio
    return _f(e), _f(nu)


def _require(cond, field, value, accepted):
    if not np.all(cond):
        bad = np.asarray(value)[~np.broadcast_to(cond, np.shape(value))] if np.ndim(value) else value
        raise InputError(Problem(field, np.ravel(bad)[:3].tolist() if np.ndim(bad) else float(bad), accepted))


def _validate_geometry(outer_diameter_mm, inner_diameter_mm, thickness_mm, cone_height_mm):
    de, di, t, h0 = _f(outer_diameter_mm), _f(inner_diameter_mm), _f(thickness_mm), _f(cone_height_mm)
    _require(di > 0, "inner_diameter_mm", di, "> 0")
    _require(de > di, "outer_diameter_mm", de, "> inner_diameter_mm (a disc spring is an annulus)")
    _require(t > 0, "thickness_mm", t, "> 0")
    _require(h0 >= 0, "cone_height_mm", h0, ">= 0")
    return de, di, t, h0


def disc_spring_factors(outer_diameter_mm, inner_diameter_mm) -> dict:
    """Factors K1, K2, K3 of a disc spring, thesis eq. (60), DIN EN 16984:2017 clause 5.

    .. math::
        \\delta = D_e/D_i,\\quad
        K_1 = \\frac{1}{\\pi}\\frac{((\\delta-1)/\\delta)^2}{(\\delta+1)/(\\delta-1) - 2/\\ln\\delta},\\quad
        K_2 = \\frac{6}{\\pi}\\frac{(\\delta-1)/\\ln\\delta - 1}{\\ln\\delta},\\quad
        K_3 = \\frac{3}{\\pi}\\frac{\\delta-1}{\\ln\\delta}

    Diameters in mm (``De > Di > 0``, else :class:`InputError`). Returns a dict
    ``delta``, ``k1``, ``k2``, ``k3`` (dimensionless) and ``d0_mm``, the
    diameter of the rotation centre, thesis eq. (58):
    :math:`D_0 = (D_e - D_i)/\\ln\\delta`.

    >>> k = disc_spring_factors(40.0, 20.4)
    >>> round(float(k["k1"]), 4), round(float(k["k2"]), 4), round(float(k["k3"]), 4)
    (0.6861, 1.2108, 1.3626)
    """
    de, di, _, _ = _validate_geometry(outer_diameter_mm, inner_diameter_mm, 1.0, 0.0)
    d = de / di
    ln = np.log(d)
    k1 = ((d - 1.0) / d) ** 2 / ((d + 1.0) / (d - 1.0) - 2.0 / ln) / np.pi
    k2 = 6.0 / np.pi * ((d - 1.0) / ln - 1.0) / ln
    k3 = 3.0 / np.pi * (d - 1.0) / ln
    return {"delta": d, "k1": k1, "k2": k2, "k3": k3, "d0_mm": (de - di) / ln}


def disc_spring_k4(thickness_mm, free_height_mm, reduced_thickness_mm=None):
    """Factor K4 of a disc spring with contact flats, thesis eq. (61)-(63), DIN EN 16984:2017.

    .. math::
        C_1 = \\frac{(t'/t)^2}{(\\tfrac14 l_0/t - t'/t + \\tfrac34)(\\tfrac58 l_0/t - t'/t + \\tfrac38)},\\quad
        C_2 = \\frac{C_1}{(t'/t)^3}\\left[\\tfrac{5}{32}(l_0/t - 1)^2 + 1\\right],\\quad
        K_4 = \\sqrt{-C_1/2 + \\sqrt{(C_1/2)^2 + C_2}}

    ``thickness_mm`` t, ``free_height_mm`` l0 and ``reduced_thickness_mm`` t'
    (contact-flat springs of DIN group 3; ``None`` or ``t' = t``: no flats,
    K4 = 1 exactly). A flat disc (``l0 = t``) without flats also gives 1.

    >>> float(disc_spring_k4(2.25, 3.15)), round(float(disc_spring_k4(8.0, 10.6, 7.5)), 4)
    (1.0, 1.0834)
    """
    t, l0 = _f(thickness_mm), _f(free_height_mm)
    if reduced_thickness_mm is None:
        return np.ones(np.broadcast(t, l0).shape)
    tr = _f(reduced_thickness_mm) / t
    r = l0 / t
    c1 = tr ** 2 / ((0.25 * r - tr + 0.75) * (0.625 * r - tr + 0.375))
    c2 = c1 / tr ** 3 * (5.0 / 32.0 * (r - 1.0) ** 2 + 1.0)
    return np.sqrt(-c1 / 2.0 + np.sqrt((c1 / 2.0) ** 2 + c2))


def _prep(outer_diameter_mm, inner_diameter_mm, thickness_mm, cone_height_mm, reduced_thickness_mm,
          youngs_modulus_mpa, poisson_ratio):
    """Effective t, h0, K4 and the stiffness scale 4E/(1-nu^2)/(K1 De^2) [MPa/mm^2]."""
    de, di, t, h0 = _validate_geometry(outer_diameter_mm, inner_diameter_mm, thickness_mm, cone_height_mm)
    k = disc_spring_factors(de, di)
    e, nu = elastic_constants(youngs_modulus_mpa, poisson_ratio)
    k4 = disc_spring_k4(t, h0 + t, reduced_thickness_mm)
    if reduced_thickness_mm is not None:  # DIN EN 16984: t -> t', h0 -> h0' = l0 - t'
        tr = _f(reduced_thickness_mm)
        h0 = h0 + t - tr
        t = tr
    scale = 4.0 * e / (1.0 - nu ** 2) / (k["k1"] * de ** 2)
    return t, h0, k4, scale, k


def disc_spring_force_n(deflection_mm, outer_diameter_mm, inner_diameter_mm, thickness_mm, cone_height_mm,
                        *, fidelity: str = "full", reduced_thickness_mm=None,
                        youngs_modulus_mpa=None, poisson_ratio=None):
    """Force of a single disc spring at deflection s [N], DIN EN 16984:2017 (Almen-Laszlo).

    ``full`` (Almen-Laszlo, DIN EN 16984 eq. for F):

    .. math::
        F = \\frac{4E}{1-\\mu^2}\\frac{t^4}{K_1 D_e^2}K_4^2\\frac{s}{t}
            \\left[K_4^2\\left(\\frac{h_0}{t}-\\frac{s}{t}\\right)\\left(\\frac{h_0}{t}-\\frac{s}{2t}\\right)+1\\right]

    ``screening``: the linear secant through the origin and the flat point
    :math:`F_c = F(s=h_0) = \\frac{4E}{1-\\mu^2}\\frac{t^3 h_0}{K_1 D_e^2}K_4^2`
    (thesis Fig. 53-54: the characteristics compared at equal :math:`F_c`), i.e.
    :math:`F = \\frac{4E}{1-\\mu^2}\\frac{t^3}{K_1 D_e^2}K_4^2\\, s`; exact for
    :math:`h_0/t \\to 0` and at s = 0 and s = h0.

    Lengths in mm, E in MPa (default from the catalog, 206 GPa; Poisson 0.3).
    The deflection is clipped to ``[0, h0]``: below 0 the spring has lifted off
    (F = 0), beyond h0 it is flat and bottomed (the force of the flat disc is
    returned; :func:`cone_spring` flags a stack that flattens it). Finite for
    every admissible geometry, including h0/t = sqrt(2) where the curve reaches
    s = h0 with a horizontal tangent.

    >>> round(float(disc_spring_force_n(0.675, 40.0, 20.4, 2.25, 0.9)), -1)   # DIN 2093 A 40: 6.5 kN
    6500.0
    >>> round(float(disc_spring_force_n(0.675, 40.0, 20.4, 2.25, 0.9, fidelity="screening")), -1)
    6340.0
    """
    _check_fidelity(fidelity)
    t, h0, k4, scale, _ = _prep(outer_diameter_mm, inner_diameter_mm, thickness_mm, cone_height_mm,
                                reduced_thickness_mm, youngs_modulus_mpa, poisson_ratio)
    s = np.clip(_f(deflection_mm), 0.0, h0)
    if fidelity == "screening":
        return scale * t ** 3 * k4 ** 2 * s
    x, z = s / t, h0 / t
    return scale * t ** 4 * k4 ** 2 * x * (k4 ** 2 * (z - x) * (z - 0.5 * x) + 1.0)


def disc_spring_rate_n_per_mm(deflection_mm, outer_diameter_mm, inner_diameter_mm, thickness_mm, cone_height_mm,
                              *, fidelity: str = "full", reduced_thickness_mm=None,
                              youngs_modulus_mpa=None, poisson_ratio=None):
    """Spring rate dF/ds of a single disc spring [N/mm], DIN EN 16984:2017.

    .. math::
        R = \\frac{4E}{1-\\mu^2}\\frac{t^3}{K_1 D_e^2}K_4^2
            \\left[K_4^2\\left(\\left(\\frac{h_0}{t}\\right)^2 - 3\\frac{h_0}{t}\\frac{s}{t}
            + \\frac32\\left(\\frac{s}{t}\\right)^2\\right) + 1\\right]

    (``screening``: the constant secant rate). Zero at s = h0 when
    h0/t = sqrt(2) (thesis step 8: horizontal tangent), negative beyond the force
    maximum of springs with h0/t > sqrt(2). Deflection clipped to [0, h0].

    >>> round(float(disc_spring_rate_n_per_mm(0.0, 30.0, 16.2, 1.0, 2 ** 0.5)), 1)   # 3 x the linear rate at s = 0
    4573.3
    >>> round(float(disc_spring_rate_n_per_mm(2 ** 0.5, 30.0, 16.2, 1.0, 2 ** 0.5)), 9)
    0.0
    """
    _check_fidelity(fidelity)
    t, h0, k4, scale, _ = _prep(outer_diameter_mm, inner_diameter_mm, thickness_mm, cone_height_mm,
                                reduced_thickness_mm, youngs_modulus_mpa, poisson_ratio)
    base = scale * t ** 3 * k4 ** 2
    if fidelity == "screening":
        return base * np.ones_like(_f(deflection_mm) * h0)
    s = np.clip(_f(deflection_mm), 0.0, h0)
    x, z = s / t, h0 / t
    return base * (k4 ** 2 * (z * z - 3.0 * z * x + 1.5 * x * x) + 1.0)


def disc_spring_stresses_mpa(deflection_mm, outer_diameter_mm, inner_diameter_mm, thickness_mm, cone_height_mm,
                             *, reduced_thickness_mm=None, youngs_modulus_mpa=None, poisson_ratio=None) -> dict:
    """Stresses of a disc spring at deflection s [MPa], thesis eq. (59), DIN EN 16984:2017.

    With :math:`A = \\frac{4E}{1-\\mu^2}\\frac{t^2}{K_1 D_e^2}K_4\\frac{s}{t}` and
    :math:`B = K_4 (h_0/t - s/(2t))`:

    * :math:`\\sigma_{OM} = -A\\,3/\\pi` (top, at the rotation diameter D0; eq. (59))
    * :math:`\\sigma_{I} = -A\\,(K_2 B + K_3)`, :math:`\\sigma_{II} = -A\\,(K_2 B - K_3)` (inner edge)
    * :math:`\\sigma_{III} = -\\frac{A}{\\delta}((K_2-2K_3)B - K_3)`,
      :math:`\\sigma_{IV} = -\\frac{A}{\\delta}((K_2-2K_3)B + K_3)` (outer edge)

    Negative is compression. Returns ``sigma_om_mpa``, ``sigma_i_mpa`` ...
    ``sigma_iv_mpa``. Deflection clipped to [0, h0].

    >>> st = disc_spring_stresses_mpa(0.15, 8.0, 4.2, 0.4, 0.2)   # DIN 2093 A 8
    >>> [int(round(float(st[k]), -1)) for k in ("sigma_om_mpa", "sigma_ii_mpa", "sigma_iii_mpa")]
    [-1200, 1220, 1190]
    """
    t, h0, k4, scale, k = _prep(outer_diameter_mm, inner_diameter_mm, thickness_mm, cone_height_mm,
                                reduced_thickness_mm, youngs_modulus_mpa, poisson_ratio)
    s = np.clip(_f(deflection_mm), 0.0, h0)
    a = scale * t ** 2 * k4 * s / t
    b = k4 * (h0 / t - 0.5 * s / t)
    k2, k3, d = k["k2"], k["k3"], k["delta"]
    return {
        "sigma_om_mpa": -a * 3.0 / np.pi,
        "sigma_i_mpa": -a * (k2 * b + k3),
        "sigma_ii_mpa": -a * (k2 * b - k3),
        "sigma_iii_mpa": -a / d * ((k2 - 2.0 * k3) * b - k3),
        "sigma_iv_mpa": -a / d * ((k2 - 2.0 * k3) * b + k3),
    }


def disc_spring_thickness_for_force_mm(force_n, outer_diameter_mm, inner_diameter_mm, aspect_ratio,
                                       deflection_ratio, *, fidelity: str = "full",
                                       youngs_modulus_mpa=None, poisson_ratio=None):
    """Thickness t giving force F at deflection s = phi*h0 with h0 = zeta*t [mm] (DIN EN 16984 inverted).

    With :math:`\\zeta = h_0/t` and :math:`\\varphi = s/h_0` fixed, the force law
    is :math:`F = \\frac{4E}{1-\\mu^2}\\frac{t^4}{K_1 D_e^2}\\,g` with
    :math:`g = \\varphi\\zeta[(\\zeta - \\varphi\\zeta)(\\zeta - \\varphi\\zeta/2) + 1]`
    (``screening``: :math:`g = \\varphi\\zeta`), so
    :math:`t = (F K_1 D_e^2 (1-\\mu^2) / (4 E g))^{1/4}`: a closed form, no
    iteration. ``force_n`` <= 0 gives t = 0 (no spring needed); a zero
    ``aspect_ratio`` or ``deflection_ratio`` raises :class:`InputError` (no
    force can be produced).

    >>> round(float(disc_spring_thickness_for_force_mm(6500.2, 40.0, 20.4, 0.4, 0.75)), 4)
    2.25
    """
    _check_fidelity(fidelity)
    zeta, phi = _f(aspect_ratio), _f(deflection_ratio)
    _require(zeta > 0, "aspect_ratio", zeta, "> 0 (h0/t)")
    _require((phi > 0) & (phi <= 1), "deflection_ratio", phi, "in (0, 1] (s/h0)")
    k = disc_spring_factors(outer_diameter_mm, inner_diameter_mm)
    e, nu = elastic_constants(youngs_modulus_mpa, poisson_ratio)
    x = phi * zeta
    g = x if fidelity == "screening" else x * ((zeta - x) * (zeta - 0.5 * x) + 1.0)
    scale = 4.0 * e / (1.0 - nu ** 2) / (k["k1"] * _f(outer_diameter_mm) ** 2)
    return (np.maximum(_f(force_n), 0.0) / (scale * g)) ** 0.25


_TOLERANCE_ROWS: dict = {}


def tolerance_rows():
    """The force-tolerance table as arrays, parsed once per catalog table (a user folder or a cleared catalog
    cache gives a new table, and so a new parse)."""
    dirs = tuple(catalog.user_dirs())
    src = catalog.load_cached("disc_spring_force_tolerances", dirs)
    hit = _TOLERANCE_ROWS.get(dirs)
    if hit is not None and hit[0] is src:
        return hit[1]
    tab = catalog.load("disc_spring_force_tolerances")
    truth = {"true": True, "false": False}
    lo, hi = tab["t_from_mm"].to_numpy(float), tab["t_to_mm"].to_numpy(float)
    inc_lo = tab["includes_t_from"].astype(str).str.strip().str.lower().map(truth).to_numpy(bool)
    inc_hi = tab["includes_t_to"].astype(str).str.strip().str.lower().map(truth).to_numpy(bool)
    _TOLERANCE_ROWS[dirs] = (src, (tab, lo, hi, inc_lo, inc_hi))
    return tab, lo, hi, inc_lo, inc_hi


def _tolerance_row_index(thickness_mm):
    """Row of ``disc_spring_force_tolerances.csv`` for each thickness; -1 outside every row."""
    t = _f(thickness_mm)
    _, lo, hi, inc_lo, inc_hi = tolerance_rows()
    idx = np.full(t.shape, -1)
    for i in range(len(lo)):  # four rows of the standard, not a loop over designs
        above = np.where(inc_lo[i], t >= lo[i], t > lo[i])
        below = np.where(inc_hi[i], t <= hi[i], t < hi[i])
        idx = np.where((idx < 0) & above & below, i, idx)
    return idx


def disc_spring_group(thickness_mm):
    """DIN EN 16983 (DIN 2093) group of a disc spring of thickness t [mm]: 1, 2 or 3.

    Group 1: t < 1.25 mm; group 2: 1.25 <= t <= 6 mm; group 3 (contact flats):
    6 < t <= 16 mm (``catalogs/disc_spring_force_tolerances.csv``). A thickness
    outside every group (t <= 0 or t > 16 mm) raises :class:`InputError`.

    >>> disc_spring_group([0.4, 1.25, 3.0, 6.0, 8.0]).tolist()
    [1, 2, 2, 2, 3]
    """
    t = _f(thickness_mm)
    idx = _tolerance_row_index(t)
    _require(idx >= 0, "thickness_mm", t, "0 < t <= 16 mm (DIN EN 16983 groups 1-3)")
    _require(t > 0, "thickness_mm", t, "> 0")
    tab = tolerance_rows()[0]
    return tab["group"].to_numpy(int)[idx]


def force_tolerance_band_n(force_n, thickness_mm) -> dict:
    """Manufacturing tolerance of a disc spring's force, DIN EN 16983 (DIN 2093) [N].

    The force at the test length :math:`l_0 - 0.75 h_0` may deviate from the
    nominal F by :math:`+\\delta_+ / -\\delta_-` of F, by thickness:
    +25/-7.5 % for t < 1.25 mm (group 1), +15/-7.5 % for 1.25 <= t <= 3 mm,
    +10/-5 % for 3 < t <= 6 mm (group 2), +/-5 % above 6 mm (group 3)
    (``catalogs/disc_spring_force_tolerances.csv``). The tolerance is specified
    at the test deflection; applying it at another deflection (as the cone
    spring's nominal gap) is synth's reading.

    Returns ``force_min_n`` = F (1 - delta-), ``force_max_n`` = F (1 + delta+),
    ``tol_plus_pct``, ``tol_minus_pct`` and ``group``.

    DIN 2093 A 8 (t = 0.4 mm, F = 210 N, group 1) and A 40 (t = 2.25 mm, 6500 N):

    >>> r = force_tolerance_band_n([210.0, 6500.0], [0.4, 2.25])
    >>> r["force_min_n"].round(2).tolist(), r["force_max_n"].round(2).tolist()
    ([194.25, 6012.5], [262.5, 7475.0])
    """
    f = _f(force_n)
    grp = disc_spring_group(thickness_mm)
    idx = _tolerance_row_index(thickness_mm)
    tab = tolerance_rows()[0]
    plus = tab["force_tol_plus_pct"].to_numpy(float)[idx]
    minus = tab["force_tol_minus_pct"].to_numpy(float)[idx]
    return {"force_min_n": f * (1.0 - minus / 100.0), "force_max_n": f * (1.0 + plus / 100.0),
            "tol_plus_pct": plus, "tol_minus_pct": minus, "group": grp}


def axial_damping_nm(axial_force_n, plastic_friction_coefficient, damper_pad_mean_radius_mm,
                     endcap_spacer_mean_radius_mm):
    """Axial damping torque, thesis eq. (9): :math:`D_{ax} = F_{ax}\\,\\mu\\,(R_{m,dp} + R_{m,es})` [N m].

    Radii in mm (converted to m). Negative forces (a lifted spring) give 0.

    >>> round(float(axial_damping_nm(508.95, 0.1294, 12.5, 13.5)), 3)
    1.712
    """
    return eq9(np.maximum(_f(axial_force_n), 0.0), plastic_friction_coefficient, damper_pad_mean_radius_mm,
               endcap_spacer_mean_radius_mm)


def required_axial_force_n(axial_damping_nm_, plastic_friction_coefficient, damper_pad_mean_radius_mm,
                           endcap_spacer_mean_radius_mm):
    """Cone-spring axial force that produces the axial damping, thesis eq. (9) inverted [N].

    :math:`F_{ax} = D_{ax} / (\\mu (R_{m,dp} + R_{m,es}))`; radii in mm, damping
    in N m. No axial damping (``D_ax <= 0``) needs no force (0). A friction
    coefficient or radius sum <= 0 raises :class:`InputError`.

    >>> round(float(required_axial_force_n(1.71, 0.13, 12.5, 13.5)), 1)
    505.9
    """
    mu = _f(plastic_friction_coefficient)
    r = _f(damper_pad_mean_radius_mm) + _f(endcap_spacer_mean_radius_mm)
    _require(mu > 0, "plastic_friction_coefficient", mu, "> 0")
    _require(r > 0, "damper_pad_mean_radius_mm + endcap_spacer_mean_radius_mm", r, "> 0")
    return eq9_inverse(np.maximum(_f(axial_damping_nm_), 0.0), mu, damper_pad_mean_radius_mm,
                       endcap_spacer_mean_radius_mm)


def gap_force_shifts_n(nominal_deflection_mm, gap_tolerance_mm, outer_diameter_mm, inner_diameter_mm,
                       thickness_mm, cone_height_mm, *, fidelity: str = "full", **kw) -> dict:
    """Force change of the spring when the gap is at its tolerance limits [N] (thesis step 8, Fig. 68).

    A gap smaller by the tolerance (maximum material) deflects the spring by
    ``s_n + dh``, a larger gap by ``s_n - dh``. ``full``: the exact differences
    along the Almen-Laszlo curve (asymmetric for a regressive spring);
    ``screening``: ``+/- rate * dh`` with the secant rate.

    Returns ``force_shift_min_gap_n`` = F(s_n + dh) - F(s_n) and
    ``force_shift_max_gap_n`` = F(s_n - dh) - F(s_n), plus
    ``deflection_max_mm`` = s_n + dh (must stay <= h0: the spring must not
    bottom).

    >>> r = gap_force_shifts_n(0.5, 0.2, 30.0, 16.2, 1.0, 0.5, fidelity="screening")
    >>> round(float(r["force_shift_min_gap_n"]), 1), round(float(r["force_shift_max_gap_n"]), 1)
    (304.9, -304.9)
    """
    s, dh = _f(nominal_deflection_mm), _f(gap_tolerance_mm)
    geo = (outer_diameter_mm, inner_diameter_mm, thickness_mm, cone_height_mm)
    if fidelity == "screening":
        rate = disc_spring_rate_n_per_mm(s, *geo, fidelity="screening", **kw)
        up, down = rate * dh, -rate * dh
    else:
        f0 = disc_spring_force_n(s, *geo, fidelity=fidelity, **kw)
        up = disc_spring_force_n(s + dh, *geo, fidelity=fidelity, **kw) - f0
        down = disc_spring_force_n(s - dh, *geo, fidelity=fidelity, **kw) - f0
    return {"force_shift_min_gap_n": up, "force_shift_max_gap_n": down, "deflection_max_mm": s + dh}


def axial_force_tolerance_band(damping_target_nm, damping_tolerance_nm, radial_damping_nm,
                               plastic_friction_coefficient, damper_pad_mean_radius_mm,
                               endcap_spacer_mean_radius_mm, force_shift_min_gap_n, force_shift_max_gap_n,
                               force_tolerance_plus=0.0, force_tolerance_minus=0.0) -> dict:
    """Cone-spring force tolerance at the nominal gap (thesis step 8, Fig. 68) and the room left in it [N].

    The damping must stay within ``target +/- tolerance`` for every gap height
    in the stack-up band (thesis step 8: the upper damping limit at maximum
    material, the lower at minimum material). The radial damping is fixed
    (step 3), so by eq. (9) the axial force must stay within

    .. math::
        F_{up} = \\frac{D_t + \\Delta D - D_{rad}}{\\mu (R_{dp} + R_{es})},\\quad
        F_{lo} = \\frac{\\max(D_t - \\Delta D - D_{rad}, 0)}{\\mu (R_{dp} + R_{es})}

    and, with :math:`\\Delta F_\\pm` the force shifts at the gap limits
    (:func:`gap_force_shifts_n`), the force at the nominal gap must lie in

    .. math::
        F_{max,tol} = F_{up} - \\max(\\Delta F_+, \\Delta F_-, 0),\\quad
        F_{min,tol} = F_{lo} - \\min(\\Delta F_+, \\Delta F_-, 0)

    A spring ordered at the nominal force :math:`F_n` (from the nominal axial
    damping ``D_t - D_rad``) is delivered within ``F_n (1 - d-) .. F_n (1 + d+)``
    (manufacturing tolerance, EN 16983 / DIN 2093); the room left is
    :math:`\\min(F_{max,tol} - F_n(1+d_+),\\ F_n(1-d_-) - F_{min,tol})`, >= 0 when every
    delivered spring keeps the damping in its band at every gap.

    Returns ``cone_spring_fax_max_tolerance_n``, ``cone_spring_fax_min_tolerance_n``,
    ``cone_spring_fax_nominal_n``, ``fax_damping_upper_n`` / ``fax_damping_lower_n``
    (:math:`F_{up}, F_{lo}`), ``band_n`` (:math:`F_{up} - F_{lo}`), ``band_room_n`` and ``gap_room_n``
    (the room for an exact spring, the gap tolerance alone).

    Thesis case 1 (D 2.00 +/- 0.30 N m, D_rad 0.2871 N m, R 12.5 + 13.5 mm,
    mu 0.1294, a spring rate of 95.2 N/mm over the worst-case 0.22 mm):

    >>> r = axial_force_tolerance_band(2.0, 0.3, 0.2871, 0.1294, 12.5, 13.5, 95.2 * 0.22, -95.2 * 0.22)
    >>> round(float(r["cone_spring_fax_max_tolerance_n"]), 1), round(float(r["cone_spring_fax_min_tolerance_n"]), 1)
    (577.3, 440.9)
    >>> round(float(r["band_room_n"]), 1)
    68.2
    """
    mu_r = _f(plastic_friction_coefficient) * (_f(damper_pad_mean_radius_mm) + _f(endcap_spacer_mean_radius_mm)) * 1e-3
    _require(mu_r > 0, "plastic_friction_coefficient * (R_dp + R_es)", mu_r, "> 0")
    target, tol, rad = _f(damping_target_nm), _f(damping_tolerance_nm), _f(radial_damping_nm)
    f_up = np.maximum(target + tol - rad, 0.0) / mu_r
    f_lo = np.maximum(target - tol - rad, 0.0) / mu_r
    f_nom = np.maximum(target - rad, 0.0) / mu_r
    up, down = _f(force_shift_min_gap_n), _f(force_shift_max_gap_n)
    f_max = f_up - np.maximum(np.maximum(up, down), 0.0)
    f_min = f_lo - np.minimum(np.minimum(up, down), 0.0)
    room = np.minimum(f_max - f_nom * (1.0 + _f(force_tolerance_plus)), f_nom * (1.0 - _f(force_tolerance_minus)) - f_min)
    gap_room = np.minimum(f_max - f_nom, f_nom - f_min)
    return {
        "cone_spring_fax_max_tolerance_n": f_max,
        "cone_spring_fax_min_tolerance_n": f_min,
        "cone_spring_fax_nominal_n": f_nom,
        "fax_damping_upper_n": f_up,
        "fax_damping_lower_n": f_lo,
        "band_n": f_up - f_lo,
        "band_room_n": room,
        "gap_room_n": gap_room,
    }


def cone_spring_min_internal_diameter_mm(pivot_diameter_mm) -> dict:
    """Smallest cone-spring inner diameter on the pivot guide, thesis Table 8 [mm].

    :math:`D_{i,min} = d_{pivot} + c(D_i)` with the diametral clearance ``c``
    of the class the resulting ``Di`` falls in (0.2 mm below 18 mm, 0.3 mm in
    [18, 22), 0.4 mm in [22, 28)). Table 8 ends at 28 mm (``table8_max_mm``):
    beyond it the last clearance is used and the design is flagged by the
    Table 8 constraint instead of extrapolated.

    Returns ``cone_spring_min_internal_diameter_mm``, ``pivot_clearance_mm`` and ``table8_max_mm``.

    >>> r = cone_spring_min_internal_diameter_mm([16.0, 17.75, 17.9, 21.7, 30.0])
    >>> r["cone_spring_min_internal_diameter_mm"].round(2).tolist(), float(r["table8_max_mm"])
    ([16.2, 17.95, 18.2, 22.1, 30.4], 28.0)
    """
    d = _f(pivot_diameter_mm)
    lo, hi, c = catalog.parsed("cone_spring_clearances", _clearance_rows)
    clearance = np.full(d.shape, c[-1])
    chosen = np.zeros(d.shape, dtype=bool)
    for lo_i, hi_i, c_i in zip(lo, hi, c):  # loop over the 3 table rows, not over designs
        cand = d + c_i
        hit = ~chosen & (cand >= lo_i) & (cand < hi_i)
        clearance = np.where(hit, c_i, clearance)
        chosen |= hit
    return {"cone_spring_min_internal_diameter_mm": d + clearance, "pivot_clearance_mm": clearance,
            "table8_max_mm": float(hi[-1])}


def _clearance_rows(tab) -> tuple:
    """``(di_min, di_max, clearance)`` arrays of thesis Table 8, by increasing ``di_min``."""
    tab = tab.sort_values("di_min_mm")
    return tuple(tab[k].to_numpy(float) for k in ("di_min_mm", "di_max_mm", "clearance_mm"))


def cone_spring_max_external_diameter_mm(damper_pad_outer_diameter_mm):
    """Largest cone-spring outer diameter bearing on the damper pad (thesis step 8 text) [mm].

    :math:`D_{e,max} = \\lfloor (D_{dp,out} - m) / g \\rfloor g`: 1 mm less than
    the damper-pad outer diameter (the text: the spring edge must bear on the
    pad even when flat), rounded down to the grid ``g`` = 1 mm, which is what
    thesis case 1 prints (pad 31.5 mm -> 30.0 mm). Both from
    ``constants_cone_spring.csv``.

    >>> cone_spring_max_external_diameter_mm([31.5, 34.5, 27.5]).tolist()
    [30.0, 33.0, 26.0]
    """
    m = catalog.constant("cone_spring_od_margin_mm")
    g = catalog.constant("cone_spring_od_round_down_mm")
    raw = _f(damper_pad_outer_diameter_mm) - m
    # a small relative guard so that e.g. 30.0 / 1.0 is not floored to 29 by rounding
    return np.floor(raw / g + 1e-9) * g


def table7_ratios(outer_diameter_mm, inner_diameter_mm, thickness_mm, cone_height_mm) -> dict:
    """The ratios of the supplier's optimal ranges, thesis Table 7 and eq. (55)-(57).

    ``diameter_ratio = De/Di`` (eq. (55)), ``aspect_ratio = h0/t`` (eq. (56)),
    ``thinness = De/t`` (eq. (57)); the ranges are in ``catalogs/cone_spring_ranges.csv``
    (advisory constraints of :mod:`synth.design.constraints`).

    >>> r = table7_ratios(30.0, 16.2, 0.75, 0.9)
    >>> round(float(r["diameter_ratio"]), 4), float(r["aspect_ratio"]), float(r["thinness"])
    (1.8519, 1.2, 40.0)
    """
    de, di, t, h0 = _f(outer_diameter_mm), _f(inner_diameter_mm), _f(thickness_mm), _f(cone_height_mm)
    with np.errstate(divide="ignore", invalid="ignore"):
        return {"diameter_ratio": de / di, "aspect_ratio": h0 / t, "thinness": de / t}


def cone_spring(axial_damping_nm_, damping_target_nm, damping_tolerance_nm, radial_damping_nm,
                plastic_friction_coefficient, damper_pad_mean_radius_mm, endcap_spacer_mean_radius_mm,
                outer_diameter_mm, inner_diameter_mm, gap_tolerance_mm, *, aspect_ratio, deflection_ratio,
                force_tolerance_plus=None, force_tolerance_minus=None, fidelity: str = "full",
                thickness_mm=None, deflection_offset_mm=0.0, force_factor=1.0) -> dict:
    """Step 8: size the cone spring of one variant and its force tolerance band (thesis eq. (9), (55)-(63), Fig. 68).

    1. nominal axial force from the axial damping of step 3 (eq. (9) inverted);
    2. the variant: outer and inner diameter (``De`` on the damper pad, ``Di``
       on the pivot, Table 8), ``aspect_ratio`` zeta = h0/t and
       ``deflection_ratio`` phi = s/h0 at the nominal gap;
    3. thickness in closed form for the nominal force at ``s = phi*h0``
       (:func:`disc_spring_thickness_for_force_mm`);
    4. the force shifts over the stack-up gap tolerance of step 6 along the
       characteristic (``fidelity``), the tolerance band and the room left in it
       for the manufacturing tolerance (``force_tolerance_plus/minus`` as
       fractions; by default DIN EN 16983's for the spring's thickness,
       :func:`force_tolerance_band_n`; NaN beyond its thickness groups);
    5. stresses at the maximum-material deflection.

    Inputs broadcast (one call, many designs; valid geometry: ``De > Di > 0``,
    ``zeta > 0``, ``0 < phi <= 1``, a positive nominal force). Forces N, lengths mm, torques N m.

    A made spring (``thickness_mm`` given, finite; a production-scatter sample of :mod:`synth.robust`): it is
    not sized, its thickness is the given one (``h0 = zeta t``, ``s_n = phi h0`` as designed); it sits at the
    deflection ``s_n + deflection_offset_mm`` (the realised gap stack: a smaller gap deflects it more) and
    gives ``force_factor`` times its characteristic's force there (its manufacturing scatter). The band is
    checked for that one realisation: ``cone_spring_gap_band_room_n`` and ``cone_spring_force_band_room_n``
    are ``min(F_up - F, F - F_lo)``, ``cone_spring_fax_nominal_n`` is the realised force ``F``,
    ``cone_spring_nominal_deflection_mm`` and ``cone_spring_max_deflection_mm`` the realised deflection.

    Returns the ``thesis_tool`` keys ``cone_spring_fax_max_tolerance_n``,
    ``cone_spring_fax_min_tolerance_n``, the spring's ``cone_spring_internal_diameter_mm`` and
    ``cone_spring_external_diameter_mm``, plus ``cone_spring_fax_nominal_n``,
    ``cone_spring_thickness_mm``, ``cone_spring_cone_height_mm``,
    ``cone_spring_free_height_mm``, ``cone_spring_nominal_deflection_mm``,
    ``cone_spring_max_deflection_mm`` (at maximum material),
    ``cone_spring_rate_n_per_mm`` (at the nominal deflection), the five stresses
    ``sigma_*_mpa`` at the maximum deflection (clipped at the flat position),
    ``cone_spring_fax_band_n``, ``cone_spring_force_band_room_n`` and the
    Table 7 ratios ``cone_spring_diameter_ratio``, ``cone_spring_aspect_ratio``,
    ``cone_spring_thinness``.

    >>> r = cone_spring(1.7129, 2.0, 0.3, 0.2871, 0.1294, 12.5, 13.5, 30.0, 16.2, 0.22,
    ...                 aspect_ratio=1.2, deflection_ratio=0.75)
    >>> round(float(r["cone_spring_fax_nominal_n"]), 1), round(float(r["cone_spring_thickness_mm"]), 3)
    (509.1, 0.742)
    """
    _check_fidelity(fidelity)
    zeta, phi = _f(aspect_ratio), _f(deflection_ratio)
    f_nom = required_axial_force_n(axial_damping_nm_, plastic_friction_coefficient,
                                   damper_pad_mean_radius_mm, endcap_spacer_mean_radius_mm)
    de, di = _f(outer_diameter_mm), _f(inner_diameter_mm)
    t = disc_spring_thickness_for_force_mm(f_nom, de, di, zeta, phi, fidelity=fidelity)
    made = None
    if thickness_mm is not None:  # a made spring: the given thickness where finite
        made = np.isfinite(_f(thickness_mm))
        t = np.where(made, _f(thickness_mm), t)
    h0 = zeta * t
    s_n = phi * h0
    dh = _f(gap_tolerance_mm)
    geo = (de, di, t, h0)
    if force_tolerance_plus is None or force_tolerance_minus is None:
        row = _tolerance_row_index(t)
        tab = tolerance_rows()[0]
        plus_pct = np.append(tab["force_tol_plus_pct"].to_numpy(float), np.nan)[row]
        minus_pct = np.append(tab["force_tol_minus_pct"].to_numpy(float), np.nan)[row]
        force_tolerance_plus = plus_pct / 100.0 if force_tolerance_plus is None else force_tolerance_plus
        force_tolerance_minus = minus_pct / 100.0 if force_tolerance_minus is None else force_tolerance_minus
    shifts = gap_force_shifts_n(s_n, dh, *geo, fidelity=fidelity)
    band = axial_force_tolerance_band(damping_target_nm, damping_tolerance_nm, radial_damping_nm,
                                      plastic_friction_coefficient, damper_pad_mean_radius_mm,
                                      endcap_spacer_mean_radius_mm, shifts["force_shift_min_gap_n"],
                                      shifts["force_shift_max_gap_n"], force_tolerance_plus, force_tolerance_minus)
    s_max = s_n + dh
    if made is not None:
        s_made = s_n + _f(deflection_offset_mm)
        with np.errstate(invalid="ignore"):
            f_made = disc_spring_force_n(s_made, *geo, fidelity=fidelity) * _f(force_factor)
        room_made = np.minimum(band["fax_damping_upper_n"] - f_made, f_made - band["fax_damping_lower_n"])
        for key, val in (("band_room_n", room_made), ("gap_room_n", room_made),
                         ("cone_spring_fax_max_tolerance_n", band["fax_damping_upper_n"]),
                         ("cone_spring_fax_min_tolerance_n", band["fax_damping_lower_n"])):
            band[key] = np.where(made, val, band[key])
        f_nom = np.where(made, f_made, f_nom)
        s_max = np.where(made, s_made, s_max)
        s_n = np.where(made, s_made, s_n)
    out = {
        "cone_spring_fax_max_tolerance_n": band["cone_spring_fax_max_tolerance_n"],
        "cone_spring_fax_min_tolerance_n": band["cone_spring_fax_min_tolerance_n"],
        "cone_spring_fax_nominal_n": f_nom,
        "cone_spring_fax_band_n": band["band_n"],
        "cone_spring_force_band_room_n": band["band_room_n"],
        "cone_spring_gap_band_room_n": band["gap_room_n"],
        "cone_spring_internal_diameter_mm": di,
        "cone_spring_external_diameter_mm": de,
        "cone_spring_thickness_mm": t,
        "cone_spring_cone_height_mm": h0,
        "cone_spring_free_height_mm": h0 + t,
        "cone_spring_nominal_deflection_mm": s_n,
        "cone_spring_max_deflection_mm": s_max,
        "cone_spring_rate_n_per_mm": disc_spring_rate_n_per_mm(s_n, *geo, fidelity=fidelity),
        "cone_spring_force_tolerance_plus": _f(force_tolerance_plus) + 0.0 * t,
        "cone_spring_force_tolerance_minus": _f(force_tolerance_minus) + 0.0 * t,
    }
    out.update(disc_spring_stresses_mpa(np.minimum(s_max, h0), *geo))
    out.update({f"cone_spring_{k}": v for k, v in table7_ratios(*geo).items()})
    shape = np.broadcast_shapes(*(np.shape(v) for v in out.values()))
    return {k: np.broadcast_to(_f(v), shape) for k, v in out.items()}


def centred_cone_spring(axial_damping_nm_, damping_target_nm, damping_tolerance_nm, radial_damping_nm,
                        plastic_friction_coefficient, damper_pad_mean_radius_mm, endcap_spacer_mean_radius_mm,
                        outer_diameter_mm, inner_diameter_mm, gap_tolerance_mm, *, aspect_ratio, deflection_ratio,
                        fidelity: str = "full", iterations: int = 3) -> dict:
    """Steps 6 and 8 as the thesis leaves them to the supplier: the cone spring's nominal height, and so its force,
    set to centre the delivered springs in the damping window (thesis step 6: the gap stack's nominal "is
    exploited by the cone spring supplier, in order to achieve the requested cone spring axial force"; step 8 and
    the conclusions: the height left to the supplier, its tolerance set by the gap tolerance and the damping window).

    :func:`cone_spring` sizes the spring for the force of the damping target and gives the band its force must
    keep at the nominal gap, ``[F_min,tol, F_max,tol]`` (the damping window less the force shift over the gap
    tolerance, Fig. 68). A spring ordered at the nominal ``F`` is delivered in ``[F (1 - d-), F (1 + d+)]``
    (DIN EN 16983: +25/-7.5 % below 1.25 mm): an asymmetric window. The nominal that centres the delivered range
    in the band is

    .. math:: F^* = \frac{F_{max,tol} + F_{min,tol}}{2 + d_+ - d_-}

    and the room left, ``min(F_max,tol - F* (1 + d+), F* (1 - d-) - F_min,tol)``, is the largest any nominal
    leaves. The spring is the variant's (its ``h0/t`` and ``s/h0``) thickness for ``F*`` (the supplier's free
    height ``(1 + h0/t) t``); the band and the DIN EN 16983 group follow the thickness, so ``F*`` is found by a
    fixed-point iteration (``iterations``; the group changes at most once).

    Returns :func:`cone_spring`'s keys for the centred spring, with ``cone_spring_fax_nominal_n`` = ``F*`` and
    ``cone_spring_force_band_room_n`` the centred room.

    Thesis case 1 (D 2.00 +/- 0.30 N m, the tool's spring variant): the band at the nominal gap is 498-555 N, narrower
    than the delivered range of any nominal (+25/-7.5 %); the target's 509.1 N overruns its top by 83 N, the centred
    484.6 N by 50 N on both sides:

    >>> args = (1.7129, 2.0, 0.3, 0.2871, 0.1294, 12.5, 13.5, 30.0, 16.2, 0.22)
    >>> c = centred_cone_spring(*args, aspect_ratio=1.2, deflection_ratio=0.75)
    >>> t = cone_spring(*args, aspect_ratio=1.2, deflection_ratio=0.75)
    >>> round(float(t["cone_spring_fax_nominal_n"]), 1), round(float(c["cone_spring_fax_nominal_n"]), 1)
    (509.1, 484.6)
    >>> round(float(t["cone_spring_force_band_room_n"]), 1), round(float(c["cone_spring_force_band_room_n"]), 1)
    (-82.7, -50.3)
    """
    mu_r = _f(plastic_friction_coefficient) * (_f(damper_pad_mean_radius_mm) + _f(endcap_spacer_mean_radius_mm)) * 1e-3
    rest = (damping_target_nm, damping_tolerance_nm, radial_damping_nm, plastic_friction_coefficient,
            damper_pad_mean_radius_mm, endcap_spacer_mean_radius_mm, outer_diameter_mm, inner_diameter_mm,
            gap_tolerance_mm)
    kw = dict(aspect_ratio=aspect_ratio, deflection_ratio=deflection_ratio, fidelity=fidelity)
    d_ax = _f(axial_damping_nm_)
    for _ in range(max(1, int(iterations))):
        cs = cone_spring(d_ax, *rest, **kw)
        p, m = cs["cone_spring_force_tolerance_plus"], cs["cone_spring_force_tolerance_minus"]
        f_star = (cs["cone_spring_fax_max_tolerance_n"] + cs["cone_spring_fax_min_tolerance_n"]) / (2.0 + p - m)
        d_ax = np.where(np.isfinite(f_star) & (f_star > 0), f_star * mu_r, d_ax)
    cs = dict(cone_spring(d_ax, *rest, **kw))
    p, m = cs["cone_spring_force_tolerance_plus"], cs["cone_spring_force_tolerance_minus"]
    f_max, f_min = cs["cone_spring_fax_max_tolerance_n"], cs["cone_spring_fax_min_tolerance_n"]
    f_star = (f_max + f_min) / (2.0 + p - m)
    cs["cone_spring_fax_nominal_n"] = f_star
    cs["cone_spring_force_band_room_n"] = np.minimum(f_max - f_star * (1.0 + p), f_star * (1.0 - m) - f_min)
    return cs

