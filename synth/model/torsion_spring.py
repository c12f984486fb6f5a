"""Step 9 of the thesis flowchart: the main torsion (leg) spring, eq. (64)-(93).

The main spring is a cylindrical helical torsion spring of round or
rectangular (flat/square) wire, loaded in winding (the usual case: presetting
leaves the outer fibre in compression) or unwinding. This module gives

* stiffness and active coils (eq. 64-65), working angles and torques
  (eq. 66-71), bending stresses with the curvature correction
  (eq. 72-77), coils and mean diameter in each condition (eq. 78-80),
  radial contact with the housing (eq. 81-88), coil gap (eq. 89-93),
  the Smith-Goodman safety factor (figure 71) and the angle between the
  hooks (the spring-housing height of eq. 52 and diameter of eq. 54 are step
  7's, re-exported here from :mod:`synth.model.packaging`);
* :func:`main_spring_design`, the whole step for arrays of designs (the
  design space evaluates every material x wire x mean diameter at once).

Units: lengths in mm, torques in N m, stiffness in N m/deg, stresses in MPa,
angles in degrees. A wire is described by ``b_mm`` (side parallel to the
spring axis), ``h_mm`` (radial side) and ``round_wire`` (True: ``b = h = d``).

Corrections to the printed equations are listed in
``docs/sections/torsion_spring.md``.

>>> p = material_properties("VDSiCr", 2.3, 2.3, True)
>>> r = main_spring_design(E_mpa=p["E_mpa"], Rm_mpa=p["Rm_mpa"], sigma_y_mpa=p["sigma_y_mpa"],
...     sigma_A0_mpa=p["sigma_A0_mpa"], b_mm=2.3, h_mm=2.3, round_wire=True, mbd_mm=44.0,
...     stiffness_nm_per_deg=0.0164, spring_torque_nominal_nm=1.56, torque_tolerance_pct=8, theta_pp_deg=16,
...     housing_height_mm=8.8, housing_outer_diameter_mm=46.0, housing_inner_diameter_mm=28.0,
...     torque_tolerance_side=-1, dtheta_inst_nom_deg=28.6)
>>> round(float(r["main_spring_active_coils_free"]), 2), round(float(r["hooks_angle_free_state_deg"]), 1)
(2.18, 295.7)
"""

from __future__ import annotations

import numpy as np

from synth import catalog
from synth.errors import InputError, Problem
from synth.model.packaging import spring_housing_height_mm, spring_housing_outer_diameter_mm  # noqa: F401  (re-exported: eq. 52, 54 live in step 7)
from synth import parts

__all__ = [
    "second_moment_mm4", "section_modulus_mm3", "equivalent_diameter_mm", "spring_index",
    "curvature_factor", "stiffness_nm_per_deg", "active_coils", "working_angles_deg", "torque_nm",
    "bending_stress_mpa", "coils_at_angle", "mean_diameter_at_coils_mm", "outer_diameter_max_mm",
    "inner_diameter_min_mm", "coil_gap_mm", "block_length_mm", "hooks_angle_deg",
    "goodman_safety_factor", "spring_housing_height_mm", "spring_housing_outer_diameter_mm",
    "rm_lookup_diameter_mm", "material_strength_mpa", "permissible_static_bending_stress_mpa", "material_properties",
    "material_wire_sections", "wire_properties", "main_spring_design", "MAIN_SPRING_CONSTANTS", "main_spring_constants",
]

#: the named constants (``catalogs/constants_main_spring.csv``) step 9 reads, by the role they play
MAIN_SPRING_CONSTANTS = (
    "main_spring_index_floor", "main_spring_dtheta_inst_nom_deg", "main_spring_dtheta_nom_free_arm_deg",
    "main_spring_mbd_tol_mm", "main_spring_min_safety_factor", "main_spring_min_coil_gap_mm",
    "main_spring_index_min", "main_spring_index_max", "spring_housing_outer_tol_mm", "spring_housing_inner_tol_mm",
)


def main_spring_constants() -> dict:
    """The catalog constants :func:`main_spring_design` reads, ``{name: value}`` (one read of each).

    Compiled callers (:mod:`synth.kernels.main_spring`) read them here once
    and pass them in as scalars, so both paths use the same values.

    >>> c = main_spring_constants()
    >>> c["main_spring_index_min"], c["main_spring_index_max"], c["main_spring_min_safety_factor"]
    (4.0, 20.0, 1.2)
    """
    return {name: catalog.constant(name) for name in MAIN_SPRING_CONSTANTS}


def _f(x):
    return np.asarray(x, dtype=float)


# --------------------------------------------------------------------------- section


def second_moment_mm4(b_mm, h_mm, round_wire):
    """Second moment of area of the wire about the bending axis [mm^4].

    Round: ``pi d^4/64`` (eq. 64 rewritten); rectangular: ``b h^3/12`` with
    ``h`` the radial side (eq. 65).

    >>> round(float(second_moment_mm4(2.0, 2.0, True)), 4), round(float(second_moment_mm4(3.0, 2.0, False)), 4)
    (0.7854, 2.0)
    """
    b, h = _f(b_mm), _f(h_mm)
    return np.where(round_wire, np.pi * h**4 / 64.0, b * h**3 / 12.0)


def section_modulus_mm3(b_mm, h_mm, round_wire):
    """Bending section modulus of the wire [mm^3]: ``pi d^3/32`` (eq. 73), ``b h^2/6`` (eq. 76).

    >>> round(float(section_modulus_mm3(2.3, 2.3, False)), 4)
    2.0278
    """
    b, h = _f(b_mm), _f(h_mm)
    return np.where(round_wire, np.pi * h**3 / 32.0, b * h**2 / 6.0)


def equivalent_diameter_mm(b_mm, h_mm, round_wire):
    """Diameter of the round wire with the same section modulus [mm], eq. (77) corrected.

    The printed eq. (77) reads ``(16/3 b h^2)^(1/3)``; equal section moduli
    ``pi d^3/32 = b h^2/6`` give ``d = (16 b h^2 / (3 pi))^(1/3)`` (pi missing in
    print, NOTES.md). Round wire returns its diameter.

    >>> round(float(equivalent_diameter_mm(2.3, 2.3, False)), 4)
    2.7437
    """
    b, h = _f(b_mm), _f(h_mm)
    return np.where(round_wire, h, np.cbrt(16.0 * b * h**2 / (3.0 * np.pi)))


def spring_index(mbd_mm, b_mm, h_mm, round_wire):
    """Spring index ``c = mbd / d`` (eq. 75) or ``mbd / d_eq`` (eq. 77) [-].

    >>> round(float(spring_index(44.0, 2.3, 2.3, True)), 3)
    19.13
    """
    return _f(mbd_mm) / equivalent_diameter_mm(b_mm, h_mm, round_wire)


def curvature_factor(c, fibre="inner"):
    """Curvature (Wahl-type) stress correction of a torsion spring, eq. (74) [-].

    ``inner`` (as printed, eq. 74): ``(4c^2 - c - 1) / (4c(c - 1))``;
    ``outer``: ``(4c^2 + c - 1) / (4c(c + 1))`` (Shigley; EN 13906-3 uses the
    inner-fibre factor q). ``c`` is clipped to ``main_spring_index_floor`` so an
    index near 1 gives a large finite factor, never a division by zero; the
    index check of :func:`main_spring_design` then fails.

    >>> round(float(curvature_factor(10.0)), 4), round(float(curvature_factor(10.0, "outer")), 4)
    (1.0806, 0.9295)
    """
    if fibre not in ("inner", "outer"):
        raise InputError(Problem("fibre", fibre, "'inner' or 'outer'"))
    c = np.maximum(_f(c), catalog.constant("main_spring_index_floor"))
    if fibre == "inner":
        return (4 * c**2 - c - 1) / (4 * c * (c - 1))
    return (4 * c**2 + c - 1) / (4 * c * (c + 1))


# --------------------------------------------------------------------------- stiffness, angles, stress


def stiffness_nm_per_deg(E_mpa, I_mm4, mbd_mm, n_a):
    """Angular stiffness of a torsion spring [N m/deg], eq. (64)/(65) solved for k_t.

    ``k = E I / (180 mbd n_a)`` in N mm/deg (from ``k = E I/(pi D n)`` per
    radian), divided by 1000. The product ``mbd_i n_i`` is constant (eq. 80),
    so the stiffness does not change with winding.

    >>> round(float(stiffness_nm_per_deg(206000, np.pi * 2.3**4 / 64, 44.0, 2.1786)), 4)
    0.0164
    """
    n = np.maximum(_f(n_a), 1e-9)
    return _f(E_mpa) * _f(I_mm4) / (180.0 * _f(mbd_mm) * n) / 1000.0


def active_coils(E_mpa, I_mm4, mbd_mm, stiffness_nm_per_deg):
    """Active coils in the free state for a target stiffness, eq. (64)/(65) [-].

    ``n_a = E I / (180 k_t mbd)`` with ``k_t`` in N mm/deg; for round wire this
    is the printed ``E d^4 pi / (180 * 64 k_t mbd)``, for rectangular wire
    ``E b h^3 / (180 * 12 k_t mbd)``.

    Hand check (case 3, round 2.3 mm, E = 206 GPa, mbd 44 mm, 0.0164 N m/deg):
    ``206000 * 1.3737 / (180 * 16.4 * 44) = 2.1786``.

    >>> round(float(active_coils(206000, np.pi * 2.3**4 / 64, 44.0, 0.0164)), 4)
    2.1786
    """
    k = np.maximum(_f(stiffness_nm_per_deg) * 1000.0, 1e-12)
    return _f(E_mpa) * _f(I_mm4) / (180.0 * k * _f(mbd_mm))


def working_angles_deg(spring_torque_nominal_nm, torque_tolerance_pct, stiffness_nm_per_deg, theta_pp_deg,
                       dtheta_inst_nom_deg, dtheta_nom_free_arm_deg, torque_tolerance_side=1.0):
    """Angles between the hooks in the working conditions, eq. (66)-(70) [deg].

    ``theta_nom = T_nom (1 + s tol/100) / k_t`` (eq. 66 prints ``s = +1``, the
    upper tolerance, the worst case for stress; ``s = -1`` gives the lower
    one), ``theta_nom+- = theta_nom +- theta_pp/2`` (67-68),
    ``theta_inst = theta_nom + dtheta_inst_nom`` (69),
    ``theta_free_arm = theta_nom - dtheta_nom_free_arm`` (70, clipped at 0).

    Returns a dict with keys ``theta_nom``, ``theta_plus``, ``theta_minus``,
    ``theta_inst``, ``theta_free_arm``, ``theta_free_state`` (0).

    >>> a = working_angles_deg(3.07, 4, 0.018, 16, 50, 30)
    >>> round(float(a["theta_nom"]), 2), round(float(a["theta_plus"]), 2), round(float(a["theta_inst"]), 2)
    (177.38, 185.38, 227.38)
    """
    k = np.maximum(_f(stiffness_nm_per_deg), 1e-12)
    t_nom = _f(spring_torque_nominal_nm) * (1.0 + _f(torque_tolerance_side) * _f(torque_tolerance_pct) / 100.0)
    th = t_nom / k
    half = _f(theta_pp_deg) / 2.0
    return {
        "theta_free_state": np.zeros_like(th),
        "theta_free_arm": np.maximum(th - _f(dtheta_nom_free_arm_deg), 0.0),
        "theta_minus": np.maximum(th - half, 0.0),
        "theta_nom": th,
        "theta_plus": th + half,
        "theta_inst": th + _f(dtheta_inst_nom_deg),
    }


def torque_nm(theta_deg, stiffness_nm_per_deg):
    """Spring torque at a hook angle, eq. (71): ``T_i = k_t theta_i`` [N m].

    >>> round(float(torque_nm(185.38, 0.018)), 4)
    3.3368
    """
    return _f(theta_deg) * _f(stiffness_nm_per_deg)


def bending_stress_mpa(torque_nm, mbd_mm, b_mm, h_mm, round_wire, fibre="inner"):
    """Corrected bending stress in the wire, eq. (73)-(77) [MPa].

    ``sigma = k_f M / Z`` with ``Z = pi d^3/32`` (round, eq. 73) or ``b h^2/6``
    (rectangular, eq. 76), ``k_f`` from :func:`curvature_factor` at the index of
    eq. (75)/(77) with the free-state mean diameter (as printed).

    Hand check (round 2.3 mm, mbd 44, 1 N m): ``Z = pi 2.3^3/32 = 1.19446``,
    ``c = 19.130``, ``k_f = 1.04065``, ``sigma = 1.04065 * 1000 / 1.19446 = 871.2``.

    >>> round(float(bending_stress_mpa(1.0, 44.0, 2.3, 2.3, True)), 1)
    871.2
    """
    c = spring_index(mbd_mm, b_mm, h_mm, round_wire)
    return curvature_factor(c, fibre) * _f(torque_nm) * 1000.0 / section_modulus_mm3(b_mm, h_mm, round_wire)


def coils_at_angle(n_a, theta_deg, winding=True):
    """Active coils at a hook angle: ``n_a + theta/360`` winding (78), ``n_a - theta/360`` unwinding (79).

    Unwinding is clipped at a tiny positive number (a spring cannot unwind
    past zero coils; the design is then infeasible anyway).

    >>> round(float(coils_at_angle(2.18, 90.0)), 3), round(float(coils_at_angle(2.18, 90.0, False)), 3)
    (2.43, 1.93)
    """
    sign = np.where(winding, 1.0, -1.0)
    return np.maximum(_f(n_a) + sign * _f(theta_deg) / 360.0, 1e-6)


def mean_diameter_at_coils_mm(mbd_mm, n_a, n_i):
    """Mean body diameter with ``n_i`` coils, eq. (80): ``mbd_i = mbd n_a / n_i`` [mm].

    (The wire length ``pi mbd n`` is conserved.)

    >>> round(float(mean_diameter_at_coils_mm(44.0, 2.0, 2.5)), 2)
    35.2
    """
    return _f(mbd_mm) * _f(n_a) / np.maximum(_f(n_i), 1e-9)


def outer_diameter_max_mm(mbd_i_mm, mbd_tol_mm, h_mm, h_tol_mm):
    """Largest outer diameter of the spring, eq. (83)/(84) [mm]: ``mbd_i + mbd_tol + (h + h_tol)``.

    ``h`` is the radial side (the diameter for round wire).

    >>> round(float(outer_diameter_max_mm(41.0, 0.4, 2.3, 0.03)), 2)
    43.73
    """
    return _f(mbd_i_mm) + _f(mbd_tol_mm) + _f(h_mm) + _f(h_tol_mm)


def inner_diameter_min_mm(mbd_i_mm, mbd_tol_mm, h_mm, h_tol_mm):
    """Smallest inner diameter of the spring, eq. (87)/(88) [mm]: ``mbd_i - mbd_tol - (h + h_tol)``.

    >>> round(float(inner_diameter_min_mm(35.0, 0.4, 2.3, 0.03)), 2)
    32.27
    """
    return _f(mbd_i_mm) - _f(mbd_tol_mm) - _f(h_mm) - _f(h_tol_mm)


def coil_gap_mm(housing_height_mm, b_mm, n_i):
    """Gap between coils in the housing, eq. (90)-(93) [mm].

    ``p_i = (H - b) / n_i`` and ``g_i = p_i - b`` where ``b`` is the AXIAL side
    of the wire (the diameter for round wire). Eq. (91)/(93) print the radial
    side ``h``; the axial gap depends on the axial side (same for square wire).

    Hand check: ``(8.8 - 2.3) / 2.5 - 2.3 = 0.3``.

    >>> round(float(coil_gap_mm(8.8, 2.3, 2.5)), 3)
    0.3
    """
    return (_f(housing_height_mm) - _f(b_mm)) / np.maximum(_f(n_i), 1e-9) - _f(b_mm)


def block_length_mm(b_mm, n_i, b_tol_mm=0.0):
    """Axial length of the coil body with touching coils: ``(n_i + 1)(b + b_tol)`` [mm].

    It is the smallest housing height with a zero gap in eq. (89)-(93).

    >>> round(float(block_length_mm(2.3, 2.5)), 2)
    8.05
    """
    return (_f(n_i) + 1.0) * (_f(b_mm) + _f(b_tol_mm))


def hooks_angle_deg(n_i):
    """Angle between the hooks with ``n_i`` coils: ``360 (ceil(n_i) - n_i)`` [deg].

    The thesis does not spell the convention out; this one reproduces the
    printed free-state values (NOTES.md). Winding by ``theta`` adds
    ``theta/360`` coils (eq. 78) so the angle falls by ``theta`` (mod 360).

    >>> round(float(hooks_angle_deg(2.179)), 2), round(float(hooks_angle_deg(4.0)), 1)
    (295.56, 0.0)
    """
    n = _f(n_i)
    return 360.0 * (np.ceil(n) - n)


def goodman_safety_factor(sigma_max_mpa, sigma_min_mpa, Rm_mpa, sigma_A0_mpa, sigma_y_mpa):
    """Smith-Goodman safety factor along the ray from the origin (thesis figure 71) [-].

    Smith diagram: x = mean stress, y = upper stress. The limit line is the
    Goodman line ``sigma_max = sigma_A0 + sigma_m (1 - sigma_A0/Rm)``, capped by
    the yield line ``sigma_max = sigma_y``. Scaling the working point
    ``(sigma_m, sigma_max)`` until it meets the limit gives
    ``SF = min(1 / (sigma_a/sigma_A0 + sigma_m/Rm), sigma_y/sigma_max)``.
    A load-free point returns +inf (no finite limit), never NaN.

    Hand check (sigma 1338/1114, Rm 2004, sigma_A0 701.4, sigma_y 1763.5):
    Goodman ``1/(112/701.4 + 1226/2004) = 1.297``, yield ``1763.5/1338 = 1.318``.

    >>> round(float(goodman_safety_factor(1338, 1114, 2004, 701.4, 1763.5)), 3)
    1.297
    """
    smax, smin = _f(sigma_max_mpa), _f(sigma_min_mpa)
    sa = np.abs(smax - smin) / 2.0
    sm = (smax + smin) / 2.0
    denom = sa / _f(sigma_A0_mpa) + np.maximum(sm, 0.0) / _f(Rm_mpa)
    with np.errstate(divide="ignore"):
        sf_g = np.where(denom > 0, 1.0 / np.where(denom > 0, denom, 1.0), np.inf)
        peak = np.maximum(np.abs(smax), np.abs(smin))
        sf_y = np.where(peak > 0, _f(sigma_y_mpa) / np.where(peak > 0, peak, 1.0), np.inf)
    return np.minimum(sf_g, sf_y)


# --------------------------------------------------------------------------- catalogs


def rm_lookup_diameter_mm(b_mm, h_mm, round_wire):
    """Wire diameter used to read the tensile strength table [mm].

    Round: ``d``. Rectangular (flat or square): the round wire of equal area
    ``sqrt(4 b h / pi)``. EN 10270-1/-2/-3 specify round wire only (EN 10270-1:
    "wire of circular cross-section"; EN 13906-3 covers springs "made from
    round wire and bar"), so no standard gives Rm for profiled wire; flat wire
    is cold-rolled from a round wire of (about) the same area and suppliers
    quote it by their own sheets. Reading the table at the equal-area
    diameter is synth's rule (a larger diameter than the thickness ``h``, so a
    lower Rm: on the safe side of the rolled wire's work hardening).

    >>> round(float(rm_lookup_diameter_mm(2.3, 2.3, False)), 3)
    2.595
    """
    b, h = _f(b_mm), _f(h_mm)
    return np.where(round_wire, h, np.sqrt(4.0 * b * h / np.pi))


def material_strength_mpa(material, d_mm, which="min"):
    """Tensile strength Rm of ``material`` at wire diameter ``d_mm`` [MPa].

    A step lookup in ``catalogs/spring_material_strength.csv``: every row
    holds the range ``d_over_mm < d <= d_mm`` of the standard's table (EN
    10270-1 Table 3: a size between two listed sizes takes the next larger
    size's values; EN 10270-2 Table 3 and EN 10270-3 list ranges) or of a
    supplier sheet. A diameter below the first row takes the first row (wire
    strength falls with diameter, so this is on the safe side); above the
    last row it takes the last row. ``which``: ``"min"`` (design value) or
    ``"max"``.

    EN 10270-2 Table 3, VDSiCr, 2.0 < d <= 2.5 mm: 1960-2060 MPa.

    >>> float(material_strength_mpa("VDSiCr", 2.3)), float(material_strength_mpa("VDSiCr", 2.3, "max"))
    (1960.0, 2060.0)
    >>> material_strength_mpa("VDSiCr", [2.0, 2.0001, 2.595]).tolist()
    [2010.0, 1960.0, 1910.0]
    """
    if which not in ("min", "max"):
        raise InputError(Problem("which", which, "'min' or 'max'"))
    p = parts.arrays()
    if str(material).strip() not in p.spring_strength:
        raise InputError(Problem("main_spring_material", material,
                                 "a grade of catalogs/spring_material_strength.csv: " + ", ".join(p.spring_strength)))
    upper, rm_min, rm_max = p.spring_strength[str(material).strip()]
    values = rm_min if which == "min" else rm_max
    d = _f(d_mm)
    # first row whose upper bound is >= d (d_over < d <= d_mm, the standard's table rows); gaps take the next row
    idx = np.clip(np.searchsorted(upper, d - 1e-9, side="left"), 0, len(upper) - 1)
    return values[idx]


def permissible_static_bending_stress_mpa(Rm_mpa, fraction, winding=True, unwinding_factor=None):
    """Permissible bending stress of a statically loaded torsion spring [MPa].

    .. math:: \\sigma_{zul} = f\\, R_m \\quad (\\times\\, k_{unw} \\text{ when loaded unwinding})

    to be compared with the bending stress *without* the curvature factor
    (static springs are checked without stress correction: Autodesk Inventor's
    EN 13906-3 torsion spring generator, "for springs under static load no
    correction is made"). ``fraction`` f = 0.75 for cold-formed spring wire and
    k_unw = 0.8 ("20 % lower when the spring is loaded in the opening sense"):
    aabag.de, permissible bending stresses of statically or rarely loaded leg
    springs. The values are the materials' ``sigma_perm_static_fraction``
    (``spring_materials.csv``) and ``main_spring_unwinding_static_factor``
    (``constants_main_spring.csv``).

    >>> float(permissible_static_bending_stress_mpa(1960.0, 0.75))
    1470.0
    >>> float(permissible_static_bending_stress_mpa(1960.0, 0.75, winding=False))
    1176.0
    """
    k = catalog.constant("main_spring_unwinding_static_factor") if unwinding_factor is None else unwinding_factor
    return _f(fraction) * _f(Rm_mpa) * np.where(np.asarray(winding, dtype=bool), 1.0, _f(k))


def material_properties(material, b_mm, h_mm, round_wire):
    """Elastic and strength data of a spring material for given wires.

    Returns a dict: ``E_mpa``, ``G_mpa``, ``density_kg_m3``, ``Rm_mpa`` (minimum
    of the standard at :func:`rm_lookup_diameter_mm`), ``sigma_y_mpa``
    (``sigma_y_bend_fraction * Rm``, the limit of the curvature-corrected
    installation stress, illustrative), ``sigma_A0_mpa``
    (``sigma_A0_fraction * Rm``, illustrative), ``sigma_perm_static_mpa``
    (``sigma_perm_static_fraction * Rm``, the static permissible stress of
    :func:`permissible_static_bending_stress_mpa` for winding); prices: :mod:`synth.cost`.

    >>> p = material_properties("VDSiCr", 2.3, 2.3, True)
    >>> float(p["E_mpa"]), float(p["Rm_mpa"]), round(float(p["sigma_y_mpa"]), 1), float(p["sigma_perm_static_mpa"])
    (206000.0, 1960.0, 1724.8, 1470.0)
    """
    mat = parts.arrays().spring_material
    i = mat.code(material, "main_spring_material")
    rm = material_strength_mpa(material, rm_lookup_diameter_mm(b_mm, h_mm, round_wire))
    return {
        "E_mpa": np.full_like(rm, mat.E_mpa[i]),
        "G_mpa": np.full_like(rm, mat.G_mpa[i]),
        "density_kg_m3": np.full_like(rm, mat.density_kg_m3[i]),
        "Rm_mpa": rm,
        "sigma_y_mpa": mat.sigma_y_bend_fraction[i] * rm,
        "sigma_A0_mpa": mat.sigma_A0_fraction[i] * rm,
        "sigma_perm_static_mpa": mat.sigma_perm_static_fraction[i] * rm,
    }


def wire_properties(wire):
    """One wire of ``catalogs/spring_wires.csv`` as a dict (``b_mm``, ``h_mm``, tolerances, ``round_wire``...).

    >>> w = wire_properties("F2.30x2.30")
    >>> w["round_wire"], w["b_mm"], w["h_tol_mm"]
    (False, 2.3, 0.03)
    """
    r = catalog.row("spring_wires", wire, field="main_spring_wire")
    return {"wire": str(r["designation"]), "round_wire": str(r["section"]).strip() == "round",
            "b_mm": float(r["b_mm"]), "h_mm": float(r["h_mm"]), "b_tol_mm": float(r["b_tol_mm"]),
            "h_tol_mm": float(r["h_tol_mm"])}


def material_wire_sections(material) -> set:
    """Wire sections a spring material is supplied in (``wire_sections`` of ``spring_materials.csv``).

    EN 10270-1/-2/-3 specify round wire; the catalog's flat/square wires are
    cold-rolled oil-tempered Si-Cr wire, so only the Si-Cr oil-tempered grades
    pair with them.

    >>> sorted(material_wire_sections("VDSiCr")), sorted(material_wire_sections("DH"))
    (['rectangular', 'round'], ['round'])
    """
    r = catalog.row("spring_materials", material, field="main_spring_material")
    return set(str(r["wire_sections"]).split())


# --------------------------------------------------------------------------- the step


def main_spring_design(*, E_mpa, Rm_mpa, sigma_y_mpa, sigma_A0_mpa, b_mm, h_mm, round_wire, mbd_mm,
                       stiffness_nm_per_deg, spring_torque_nominal_nm, torque_tolerance_pct, theta_pp_deg,
                       housing_height_mm, housing_outer_diameter_mm, housing_inner_diameter_mm,
                       b_tol_mm=0.0, h_tol_mm=0.0, dtheta_inst_nom_deg=None, dtheta_nom_free_arm_deg=None,
                       winding=True, torque_tolerance_side=1.0, fibre="inner", mbd_tol_mm=None,
                       housing_outer_tol_mm=None, housing_inner_tol_mm=None, sigma_perm_static_mpa=None):
    """Step 9 for arrays of designs (all arguments broadcast): stiffness to stresses, diameters and coil gap.

    Inputs from upstream steps: ``spring_torque_nominal_nm`` (step 3),
    ``stiffness_nm_per_deg``, ``torque_tolerance_pct``, ``theta_pp_deg`` (design
    input), ``housing_height_mm`` (eq. 52, :func:`spring_housing_height_mm`),
    ``housing_outer_diameter_mm`` (eq. 54), ``housing_inner_diameter_mm`` (spring
    bushing upper outer diameter), ``dtheta_inst_nom_deg`` /
    ``dtheta_nom_free_arm_deg`` (tensioner working range; defaults from
    ``constants_main_spring.csv``).

    Returns a dict of arrays: the case keys ``main_spring_active_coils_free``,
    ``main_spring_mean_body_diameter_mm``, ``main_spring_sigma_a_max_mpa``,
    ``main_spring_sigma_a_min_mpa``, ``main_spring_sigma_inst_mpa``,
    ``main_spring_safety_factor``, ``spring_housing_height_mm``,
    ``hooks_angle_free_state_deg``, ``hooks_angle_nominal_deg``; the angles
    ``theta_*_deg``, torques ``torque_*_nm``, coils ``coils_*``, diameters
    ``mbd_*_mm``, ``outer_diameter_max_mm``, ``inner_diameter_min_mm``,
    ``coil_gap_worst_mm``, ``block_length_max_mm``, ``spring_index``,
    ``curvature_factor``, and the limits they are checked against
    (:mod:`synth.design.constraints`): ``sigma_y_limit_mpa`` (installation),
    ``housing_outer_diameter_min_mm`` (eq. 82) and ``housing_inner_diameter_max_mm`` (eq. 86).

    With ``sigma_perm_static_mpa`` (the material's static permissible stress
    for winding, :func:`material_properties`) the result also carries the
    static check in the form spring makers apply it (an advisory constraint of
    the registry, ``spring_static_permissible``):
    ``main_spring_sigma_inst_uncorrected_mpa`` (installation stress without
    the curvature factor) and ``sigma_perm_static_limit_mpa`` (x 0.8 when
    unwinding); see :func:`permissible_static_bending_stress_mpa`.

    >>> r = main_spring_design(E_mpa=206000, Rm_mpa=2004, sigma_y_mpa=1763.5, sigma_A0_mpa=701.4,
    ...     b_mm=2.3, h_mm=2.3, round_wire=True, mbd_mm=44, stiffness_nm_per_deg=0.0164,
    ...     spring_torque_nominal_nm=1.56, torque_tolerance_pct=8, theta_pp_deg=16,
    ...     housing_height_mm=8.8, housing_outer_diameter_mm=46.0, housing_inner_diameter_mm=28.0,
    ...     dtheta_inst_nom_deg=28.6, torque_tolerance_side=-1)
    >>> round(float(r["main_spring_sigma_a_max_mpa"])), round(float(r["main_spring_sigma_inst_mpa"]))
    (1365, 1659)
    """
    k = _f(stiffness_nm_per_deg)
    mbd = _f(mbd_mm)
    cst = main_spring_constants()
    if dtheta_inst_nom_deg is None:
        dtheta_inst_nom_deg = cst["main_spring_dtheta_inst_nom_deg"]
    if dtheta_nom_free_arm_deg is None:
        dtheta_nom_free_arm_deg = cst["main_spring_dtheta_nom_free_arm_deg"]
    mbd_tol = cst["main_spring_mbd_tol_mm"] if mbd_tol_mm is None else mbd_tol_mm
    winding = np.asarray(winding, dtype=bool)

    inertia = second_moment_mm4(b_mm, h_mm, round_wire)
    n_a = active_coils(E_mpa, inertia, mbd, k)                                   # eq. 64-65
    ang = working_angles_deg(spring_torque_nominal_nm, torque_tolerance_pct, k, theta_pp_deg,
                             dtheta_inst_nom_deg, dtheta_nom_free_arm_deg, torque_tolerance_side)  # eq. 66-70
    out = {f"{name}_deg": val for name, val in ang.items()}
    sig, coils, dia = {}, {}, {}
    c = spring_index(mbd, b_mm, h_mm, round_wire)
    kf, z = curvature_factor(c, fibre), section_modulus_mm3(b_mm, h_mm, round_wire)  # once: they depend on the wire
    for state in ("free_arm", "minus", "nom", "plus", "inst", "free_state"):
        th = ang[f"theta_{state}"]
        out[f"torque_{state}_nm"] = torque_nm(th, k)                                # eq. 71
        sig[state] = kf * _f(out[f"torque_{state}_nm"]) * 1000.0 / z               # eq. 73-77, bending_stress_mpa
        coils[state] = coils_at_angle(n_a, th, winding)                             # eq. 78-79
        dia[state] = mean_diameter_at_coils_mm(mbd, n_a, coils[state])             # eq. 80
        out[f"sigma_{state}_mpa"] = sig[state]
        out[f"coils_{state}"] = coils[state]
        out[f"mbd_{state}_mm"] = dia[state]
    sf = goodman_safety_factor(sig["plus"], sig["minus"], Rm_mpa, sigma_A0_mpa, sigma_y_mpa)

    # radial contacts (eq. 81-88): winding -> largest diameter in the free state (assembly),
    # smallest at installation; unwinding the other way round.
    mbd_big = np.where(winding, dia["free_state"], dia["inst"])
    mbd_small = np.where(winding, dia["inst"], dia["free_state"])
    d_out = outer_diameter_max_mm(mbd_big, mbd_tol, h_mm, h_tol_mm)
    d_in = inner_diameter_min_mm(mbd_small, mbd_tol, h_mm, h_tol_mm)
    # axial (eq. 89-93): the worst condition in the housing has the most coils
    n_worst = np.maximum(np.maximum(coils["inst"], coils["free_arm"]), coils["nom"])
    gap = coil_gap_mm(housing_height_mm, _f(b_mm) + _f(b_tol_mm), n_worst)

    out.update({
        "main_spring_active_coils_free": n_a,
        "main_spring_mean_body_diameter_mm": mbd + 0.0 * n_a,
        "main_spring_sigma_a_max_mpa": sig["plus"],
        "main_spring_sigma_a_min_mpa": sig["minus"],
        "main_spring_sigma_inst_mpa": sig["inst"],
        "main_spring_safety_factor": sf,
        "spring_housing_height_mm": _f(housing_height_mm) + 0.0 * n_a,
        "hooks_angle_free_state_deg": hooks_angle_deg(n_a),
        "hooks_angle_nominal_deg": hooks_angle_deg(coils["nom"]),
        "spring_index": c,
        "curvature_factor": kf,
        "outer_diameter_max_mm": d_out,
        "inner_diameter_min_mm": d_in,
        "coil_gap_worst_mm": gap,
        "block_length_max_mm": block_length_mm(b_mm, n_worst, b_tol_mm),
        "stiffness_nm_per_deg": k + 0.0 * n_a,
        "sigma_y_limit_mpa": _f(sigma_y_mpa) + 0.0 * n_a,
    })
    tol_out = cst["spring_housing_outer_tol_mm"] if housing_outer_tol_mm is None else housing_outer_tol_mm
    tol_in = cst["spring_housing_inner_tol_mm"] if housing_inner_tol_mm is None else housing_inner_tol_mm
    out["housing_outer_diameter_min_mm"] = _f(housing_outer_diameter_mm) - _f(tol_out)          # eq. 82
    # eq. 85 corrected: the spring's inner diameter must stay ABOVE the support's (eq. 86 limit)
    out["housing_inner_diameter_max_mm"] = _f(housing_inner_diameter_mm) + _f(tol_in)
    if sigma_perm_static_mpa is not None:  # the spring makers' static rule (EN 13906-3 practice), see below
        out["main_spring_sigma_inst_uncorrected_mpa"] = sig["inst"] / out["curvature_factor"]
        out["sigma_perm_static_limit_mpa"] = permissible_static_bending_stress_mpa(sigma_perm_static_mpa, 1.0,
                                                                                  winding) + 0.0 * n_a
    return out
