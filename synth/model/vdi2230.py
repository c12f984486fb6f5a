"""VDI 2230 Part 1 (2015) path of the fixation bolt (thesis step 10, ``method="vdi2230"`` of
:func:`synth.model.bolted_joint.fixation`): ISO thread geometry, permissible assembly preload, tightening factor,
embedding loss and the resiliences of bolt and clamped parts (R1, R4-R7, R13; section 5.1).

Units: forces in N, lengths in mm, torques in N*mm inside and N*m at the public outputs (``_nm``), stresses in MPa,
resiliences in mm/N, embedding in um. Constants: ``catalogs/constants_fixation.csv`` and the VDI tables in
``catalogs/`` (each with its source); see ``docs/sections/bolted_joint.md``.
"""

from __future__ import annotations

import numpy as np

from synth.catalog import constant, load, parsed
from synth.errors import InputError, Problem
from synth.model.input_guards import as_array as _arr, require as _require

__all__ = [
    "iso724_diameters_mm", "stress_area_mm2", "permissible_assembly_preload_n", "elastic_permissible_preload_n",
    "assembly_torque_nm", "head_mean_diameter_mm", "tightening_factor_from_scatter", "tightening_factor",
    "tightening_method", "preload_scatter", "PRELOAD_SET_BY",
    "embedding_um", "bolt_resilience_mm_per_n", "clamped_parts_resilience_mm_per_n", "embedding_preload_loss_n",
    "DEFAULT_TIGHTENING_METHOD", "DEFAULT_EMBEDDING_ROUGHNESS", "DEFAULT_EMBEDDING_LOADING", "JOINT_TYPES",
    "HEAD_TYPES",
]


def iso724_diameters_mm(d_mm, pitch_mm):
    """Basic pitch, minor and nut-minor diameters of an ISO metric thread, ISO 724 [mm].

    From the ISO 68-1 basic profile (fundamental triangle height
    ``H = sqrt(3)/2 P``): ``d2 = d - 3/4 H = d - 0.649519 P``,
    ``d3 = d - 17/12 H = d - 1.226869 P`` (minor diameter of the bolt thread
    with the root radius of ISO 898-1), ``D1 = d - 5/4 H = d - 1.082532 P``.
    Valid for any d > 0, P > 0 (ISO 261 pairs P with d).

    >>> [round(float(v), 3) for v in iso724_diameters_mm(8.0, 1.25)]
    [7.188, 6.466, 6.647]
    """
    d = _require("d_mm", d_mm)
    p = _require("pitch_mm", pitch_mm)
    h = np.sqrt(3.0) / 2.0 * p
    return d - 0.75 * h, d - 17.0 / 12.0 * h, d - 1.25 * h


def stress_area_mm2(d2_mm, d3_mm):
    """Nominal stress area of a bolt thread, ISO 898-1: ``A_s = pi/4 ((d2 + d3)/2)^2`` [mm^2].

    ISO 898-1:2013 tabulates it to three significant figures (M8: 36.6 mm^2).

    >>> round(float(stress_area_mm2(7.188, 6.466)), 2)
    36.61
    """
    return np.pi / 4.0 * ((_arr(d2_mm) + _arr(d3_mm)) / 2.0) ** 2


def _utilisation(utilisation):
    return constant("vdi_utilisation_nu") if utilisation is None else _require(
        "utilisation", utilisation, high=1.0, accepted="a yield utilisation in (0, 1]")


def permissible_assembly_preload_n(pitch_mm, d2_mm, d3_mm, rp02_mpa, mu_thread, *, utilisation=None, d0_mm=None):
    """Permissible assembly preload ``F_M,zul``, VDI 2230 Part 1 (2015) step R7, eq. (R7/2) [N].

    ``F_M,zul = A0 nu Rp0.2min / sqrt(1 + 3 [3/2 d2/d0 (P/(pi d2) + 1.155 mu_G,min)]^2)``:
    the preload at which the von Mises stress of tension plus thread-torque
    torsion reaches ``nu Rp0.2``, with the torsion taken on a *plastic*
    section (``W_p = pi d0^3/12``, factor 3/2 instead of the elastic 2).
    ``d0``: diameter of the smallest cross-section, ``d_S = (d2 + d3)/2`` for
    shank bolts with a full thread or a shank of at least d (the default),
    ``A0 = pi/4 d0^2`` (= ISO 898-1 ``A_s``); pass ``d0_mm`` for a reduced
    shank. ``nu`` defaults to the constant ``vdi_utilisation_nu`` (0.9, the
    basis of VDI 2230 Tables A1-A4); ``1.155 = 1/cos 30``. Units: N, mm, MPa.
    Valid for ISO metric threads, mu_G >= 0, 0 < nu <= 1.

    VDI 2230 Table A2 (as reprinted by Bossard/Mastik, see
    tests/validation): M8x1, 8.8, mu_G 0.10: 20.7 kN.

    >>> round(float(permissible_assembly_preload_n(1.0, 7.350, 6.773, 640.0, 0.10)) / 1e3, 1)
    20.7
    """
    p = _require("pitch_mm", pitch_mm)
    d2 = _require("d2_mm", d2_mm)
    d3 = _require("d3_mm", d3_mm)
    rp = _require("rp02_mpa", rp02_mpa)
    mu = _require("thread friction coefficient", mu_thread, inclusive=True)
    nu = _utilisation(utilisation)
    d0 = (d2 + d3) / 2.0 if d0_mm is None else _require("d0_mm", d0_mm)
    a0 = np.pi / 4.0 * d0**2
    k = 1.5 * d2 / d0 * (p / (np.pi * d2) + mu / np.cos(np.radians(constant("thread_flank_half_angle_deg"))))
    return a0 * nu * rp / np.sqrt(1.0 + 3.0 * k**2)


def elastic_permissible_preload_n(pitch_mm, d2_mm, d3_mm, stress_area, rp02_mpa, mu_thread, *, utilisation=None,
                                  torsion_diameter="minor"):
    """The preload at which the thesis's elastic stress form reaches ``nu Rp0.2`` [N].

    Eq. (103)-(107) solved for the force: ``sigma = F/A_s``,
    ``tau = 16 T_G/(pi d^3)`` with ``T_G = F/2 (P/pi + mu d2/cos 30)``
    (:func:`thread_torque_nmm`), ``sqrt(sigma^2 + 3 tau^2) = nu Rp0.2``, so
    ``F = nu Rp0.2 / sqrt(1/A_s^2 + 3 c^2)``, ``c = 8 (P/pi + mu d2/cos 30)/(pi d^3)``.
    ``d = d3`` (``torsion_diameter="minor"``, eq. (105)) or ``(d2+d3)/2``
    (``"stress"``). It is the thesis-form counterpart of
    :func:`permissible_assembly_preload_n` (elastic torsion on d3 instead of
    plastic torsion on d0): M8x1.25 8.8, mu 0.14, nu 0.9: 15.43 kN vs 18.13 kN.

    >>> round(float(elastic_permissible_preload_n(1.25, 7.188, 6.466, 36.6, 640.0, 0.14)) / 1e3, 2)
    15.43
    """
    if torsion_diameter not in ("minor", "stress"):
        raise InputError(Problem("torsion_diameter", torsion_diameter, "'minor' or 'stress'"))
    p, d2, d3 = _arr(pitch_mm), _arr(d2_mm), _arr(d3_mm)
    a_s = _require("bolt stress area [mm2]", stress_area)
    rp = _require("rp02_mpa", rp02_mpa)
    mu = _require("thread friction coefficient", mu_thread, inclusive=True)
    d = d3 if torsion_diameter == "minor" else (d2 + d3) / 2.0
    cb = np.cos(np.radians(constant("thread_flank_half_angle_deg")))
    c = 8.0 * (p / np.pi + mu * d2 / cb) / (np.pi * d**3)
    return _utilisation(utilisation) * rp / np.sqrt(1.0 / a_s**2 + 3.0 * c**2)


def assembly_torque_nm(preload_n, pitch_mm, d2_mm, mu_thread, head_mean_diameter_mm, mu_head):
    """Tightening torque, VDI 2230 Part 1 (2015) eq. (R13/1) as printed [N*m].

    ``M_A = F_M (0.16 P + 0.58 d2 mu_G + D_Km/2 mu_K)`` with the rounded
    coefficients of the guideline (``0.16 ~ 1/(2 pi)``, ``0.58 ~ 1/(2 cos 30)``;
    :func:`tightening_torque_nm` is the unrounded form, 0.3 % different).
    ``D_Km`` is the mean friction diameter under the head,
    ``(d_w + d_h)/2`` (:func:`head_mean_diameter_mm`). VDI 2230 Table A2 (via
    Bossard): M8x1, 8.8, mu 0.10, F 20.7 kN, D_Km (11.63 + 9)/2: 22.8 N*m.

    >>> round(float(assembly_torque_nm(20.7e3, 1.0, 7.350, 0.10, head_mean_diameter_mm(11.63, 9.0), 0.10)), 1)
    22.8
    """
    f = _arr(preload_n)
    p, d2 = _arr(pitch_mm), _arr(d2_mm)
    mu_g = _require("thread friction coefficient", mu_thread, inclusive=True)
    mu_k = _require("under-head friction coefficient", mu_head, inclusive=True)
    return f * (0.16 * p + 0.58 * d2 * mu_g + _arr(head_mean_diameter_mm) / 2.0 * mu_k) / 1000.0


def head_mean_diameter_mm(head_contact_diameter_mm, hole_diameter_mm):
    """Mean friction diameter under the bolt head ``D_Km = (d_w + d_h)/2`` (VDI 2230 Part 1, R13) [mm].

    >>> float(head_mean_diameter_mm(11.63, 9.0))
    10.315
    """
    return (_arr(head_contact_diameter_mm) + _arr(hole_diameter_mm)) / 2.0


def tightening_factor_from_scatter(scatter):
    """Tightening factor ``alpha_A = F_M,max/F_M,min = (1 + s)/(1 - s)`` for a preload scatter ``+/- s`` (VDI 2230, R1) [-].

    ``s`` is the relative scatter about the mean preload (0.23 for +/-23 %).

    >>> round(float(tightening_factor_from_scatter(0.23)), 2)
    1.6
    """
    s = _require("preload scatter", scatter, inclusive=True, high=0.99, accepted="a relative scatter in [0, 0.99]")
    return (1.0 + s) / (1.0 - s)


DEFAULT_TIGHTENING_METHOD = "torque_wrench_tested"  # engine assembly: torque set by tests on the real joint
DEFAULT_EMBEDDING_ROUGHNESS = "rz_10_40"            # machined faces, 10 <= Rz < 40 um
DEFAULT_EMBEDDING_LOADING = "transverse"             # the hubload loads the joint in shear
HEAD_TYPES = ("hex", "flange", "socket")             # head forms (catalogs/bolt_heads.csv)
PRELOAD_SET_BY = ("torque", "yield")                 # what sets the preload of a tightening method
JOINT_TYPES = ("tapped", "through")                  # VDI ESV (tapped thread) / DSV (through bolt and nut)


def tightening_method(method: str = DEFAULT_TIGHTENING_METHOD) -> dict:
    """The ``catalogs/tightening_factors.csv`` row of a tightening method, as plain values.

    Keys ``alpha_a_min``, ``alpha_a_max`` (VDI 2230-1 Table A8 tightening factor
    ``alpha_A = F_M,max/F_M,min``), ``preload_set_by`` (``"torque"``: the
    torque sets the preload, sized to ``F_M,min`` and bounded by the bolt's
    permissible preload; ``"yield"``: yield- and angle-controlled tightening
    take the bolt to its yield point, the preload is the bolt's own and the
    bolt is dimensioned for ``F_M,min``), ``design_option`` (offered to the
    design space); its assembly cost is the price book's (:mod:`synth.cost`).

    >>> r = tightening_method("yield_controlled")
    >>> r["alpha_a_max"], r["preload_set_by"], r["design_option"]
    (1.4, 'yield', True)
    """
    rows, every = parsed("tightening_factors", _tightening_rows)  # read once per loaded table (a hot path)
    r = rows.get(str(method).strip())
    if r is None:
        raise InputError(Problem("tightening_method", method, "one of " + ", ".join(every)))
    set_by = r["preload_set_by"]
    if set_by not in PRELOAD_SET_BY:
        raise InputError(Problem(f"catalog tightening_factors.csv, row {method}, column preload_set_by", set_by,
                                 " or ".join(PRELOAD_SET_BY)))
    return {"tightening_method": str(method).strip(), **r}


def _tightening_rows(df) -> tuple:
    """``({method: its row's values}, [every method as written])`` of ``tightening_factors.csv`` (the first row of
    a method wins)."""
    rows: dict = {}
    for _, r in df.iterrows():
        rows.setdefault(str(r["tightening_method"]).strip(), {
            "alpha_a_min": float(r["alpha_a_min"]), "alpha_a_max": float(r["alpha_a_max"]),
            "preload_set_by": str(r["preload_set_by"]).strip(),
            "design_option": str(r["design_option"]).strip().lower() in ("true", "1", "yes")})
    return rows, [str(x) for x in df["tightening_method"]]


def tightening_factor(method: str = DEFAULT_TIGHTENING_METHOD, bound: str = "max") -> float:
    """Tightening factor ``alpha_A`` of a tightening method (VDI 2230-1 Table A8), from
    ``catalogs/tightening_factors.csv`` [-].

    ``bound="max"`` (default, the conservative end) or ``"min"`` of the
    method's range. Default method: torque-controlled tightening with the
    torque found by tests on the original joint (alpha_A 1.4-1.6), as on an
    engine assembly line.

    >>> round(tightening_factor(), 2), round(tightening_factor("torque_wrench_tested", "min"), 2)
    (1.6, 1.4)
    """
    if bound not in ("min", "max"):
        raise InputError(Problem("bound", bound, "'min' or 'max'"))
    return tightening_method(method)[f"alpha_a_{bound}"]


def preload_scatter(alpha_a):
    """The relative preload scatter ``s = (alpha_A - 1)/(alpha_A + 1)`` about the mean of the window
    ``[F_M,min, alpha_A F_M,min]`` (the inverse of :func:`tightening_factor_from_scatter`) [-].

    >>> round(float(preload_scatter(1.6)), 4)
    0.2308
    """
    a = _require("alpha_a", alpha_a, low=1.0, inclusive=True, accepted="a tightening factor >= 1")
    return (a - 1.0) / (a + 1.0)


def embedding_um(roughness_class: str = DEFAULT_EMBEDDING_ROUGHNESS, loading: str = DEFAULT_EMBEDDING_LOADING, *,
                 interfaces=None, joint_type: str = "tapped"):
    """Total amount of embedding ``f_Z`` of a joint, VDI 2230 Part 1 Table 5.4/1 guide values [um].

    ``f_Z = f_thread + f_head + (f_nut if through bolt) + n_interfaces f_interface``
    with the per-surface values of ``catalogs/embedding_amounts.csv`` for the
    surface roughness class (``rz_lt_10``, ``rz_10_40``, ``rz_40_160``) and the
    loading (``axial`` or ``transverse``). ``interfaces`` counts the inner
    interfaces of the clamped stack (default: constant ``vdi_clamped_interfaces``,
    the pivot base on the crankcase); a tapped joint (``joint_type="tapped"``,
    VDI "ESV") has one thread and one head face, a through bolt one more (nut) face.

    >>> float(embedding_um("rz_10_40", "transverse", interfaces=1))
    10.0
    """
    if joint_type not in JOINT_TYPES:
        raise InputError(Problem("joint_type", joint_type, "one of " + ", ".join(JOINT_TYPES)))
    df = load("embedding_amounts")
    hit = df[(df["roughness_class"] == str(roughness_class).strip()) & (df["loading"] == str(loading).strip())]
    if hit.empty:
        if str(roughness_class).strip() not in set(df["roughness_class"]):
            raise InputError(Problem("embedding roughness class", roughness_class,
                                     "one of " + ", ".join(sorted(set(df["roughness_class"])))))
        raise InputError(Problem("embedding loading", loading, "one of " + ", ".join(sorted(set(df["loading"])))))
    r = hit.iloc[0]
    n = constant("vdi_clamped_interfaces") if interfaces is None else _require(
        "clamped_interfaces", interfaces, inclusive=True, accepted="a number of inner interfaces >= 0")
    faces = 2.0 if joint_type == "through" else 1.0
    return float(r["thread_um"]) + faces * float(r["head_or_nut_um"]) + n * float(r["interface_um"])


def bolt_resilience_mm_per_n(d_mm, d3_mm, clamp_length_mm, *, head_type="hex", joint_type="tapped",
                             free_thread_length_mm=0.0, modulus_mpa=None, internal_thread_modulus_mpa=None):
    """Axial elastic resilience of the bolt ``delta_S``, VDI 2230 Part 1 section 5.1.1.1 [mm/N].

    ``delta_S = delta_SK + delta_shank + delta_Gew + delta_G + delta_M``,
    eq. (5.1/3): head ``l_SK/(E_S A_N)`` with ``l_SK = 0.5 d`` (hexagon and
    flange heads, 5.1/14) or ``0.4 d`` (socket heads, 5.1/15); plain shank of
    diameter d over ``l_K - l_Gew``; free loaded thread ``l_Gew/(E_S A_d3)``
    (5.1/12); engaged thread ``0.5 d/(E_S A_d3)`` (5.1/5-6); nut
    ``0.4 d/(E_S A_N)`` (through bolt, 5.1/10) or tapped region
    ``0.33 d/(E_BI A_N)`` (tapped joint, 5.1/11). ``A_N = pi d^2/4``,
    ``A_d3 = pi d3^2/4``. Default: the clamped length is spanned by the plain
    shank (``free_thread_length_mm=0``; the stiffer bolt, so the larger
    embedding loss); moduli default to the constants ``bolt_modulus_mpa`` and
    ``clamped_parts_modulus_mpa`` (the crankcase thread). Valid for
    ``l_K >= l_Gew >= 0``.

    M8, d3 6.466, l_K 40 mm, hex head, tapped in aluminium (E 70000),
    steel bolt (E 210000): (4 + 40)/(E 50.27) + 4/(E 32.84) +
    2.64/(70000 50.27) = 4.168e-6 + 0.580e-6 + 0.750e-6 = 5.498e-6 mm/N.

    >>> round(float(bolt_resilience_mm_per_n(8.0, 6.466, 40.0, modulus_mpa=210000.0,
    ...                                      internal_thread_modulus_mpa=70000.0)) * 1e6, 3)
    5.498
    """
    if head_type not in HEAD_TYPES:
        raise InputError(Problem("head_type", head_type, "one of " + ", ".join(HEAD_TYPES)))
    if joint_type not in JOINT_TYPES:
        raise InputError(Problem("joint_type", joint_type, "one of " + ", ".join(JOINT_TYPES)))
    d = _require("d_mm", d_mm)
    d3 = _require("d3_mm", d3_mm)
    lk = _require("clamp_length_mm", clamp_length_mm, accepted="a clamped length > 0 mm")
    lgew = _require("free_thread_length_mm", free_thread_length_mm, inclusive=True)
    if np.any(lgew > lk):
        raise InputError(Problem("free_thread_length_mm", float(np.max(lgew)), "a length <= the clamped length"))
    e_s = constant("bolt_modulus_mpa") if modulus_mpa is None else _require("bolt modulus [MPa]", modulus_mpa)
    if joint_type == "through":
        e_m, l_m = e_s, 0.4 * d
    else:
        e_m = constant("clamped_parts_modulus_mpa") if internal_thread_modulus_mpa is None else _require(
            "internal thread modulus [MPa]", internal_thread_modulus_mpa)
        l_m = 0.33 * d
    a_n = np.pi / 4.0 * d**2
    a_d3 = np.pi / 4.0 * d3**2
    l_sk = (0.4 if head_type == "socket" else 0.5) * d
    return (l_sk + (lk - lgew)) / (e_s * a_n) + (lgew + 0.5 * d) / (e_s * a_d3) + l_m / (e_m * a_n)


def clamped_parts_resilience_mm_per_n(head_contact_diameter_mm, hole_diameter_mm, outer_diameter_mm, clamp_length_mm,
                                      *, modulus_mpa=None, joint_type="tapped"):
    """Elastic resilience of concentrically clamped parts ``delta_P``, VDI 2230 Part 1 section 5.1.2.1 [mm/N].

    Substitute deformation cone from the head bearing diameter ``d_W`` with
    ``tan(phi) = 0.348 + 0.013 ln(beta_L) + 0.193 ln(y)`` (tapped joint, ESV,
    5.1/26) or ``0.362 + 0.032 ln(beta_L/2) + 0.153 ln(y)`` (through bolt,
    DSV, 5.1/27), ``beta_L = l_K/d_W``, ``y = D_A/d_W``; limiting diameter
    ``D_A,Gr = d_W + w l_K tan(phi)`` (5.1/23, w = 2 tapped, 1 through).
    ``D_A >= D_A,Gr``: cone only (5.1/24)
    ``delta_P = 2 ln[(d_W + d_h)(D_A,Gr - d_h)/((d_W - d_h)(D_A,Gr + d_h))]/(w E_P pi d_h tan(phi))``;
    ``d_W < D_A < D_A,Gr``: cone plus sleeve (5.1/25); ``D_A <= d_W``: a
    sleeve ``l_K/(E_P pi/4 (D_A^2 - d_h^2))``. ``d_h``: hole diameter
    (here the engine-support internal diameter), ``D_A``: outer diameter
    of the clamped part (the support external diameter). E_P defaults to
    the constant ``clamped_parts_modulus_mpa``. Valid for
    ``d_W > d_h``, ``D_A > d_h``, ``l_K > 0``.

    Case 1 support (d_W 13, d_h 8.2, D_A 22.9, l_K 40, aluminium 70000 MPa),
    tapped: tan(phi) = 0.348 + 0.013 ln(3.077) + 0.193 ln(1.762) = 0.4719,
    D_A,Gr = 50.75 > D_A, so cone plus sleeve: (0.1902 + 0.2582)/(70000 pi)
    = 2.039e-6 mm/N (a 40 mm aluminium sleeve of 359 mm^2 alone gives 1.59e-6).

    >>> round(float(clamped_parts_resilience_mm_per_n(13.0, 8.2, 22.9, 40.0, modulus_mpa=70000.0)) * 1e6, 3)
    2.039
    """
    if joint_type not in JOINT_TYPES:
        raise InputError(Problem("joint_type", joint_type, "one of " + ", ".join(JOINT_TYPES)))
    dw = _require("bolt_head_contact_external_diameter_mm", head_contact_diameter_mm)
    dh = _require("engine_support_internal_diameter_mm", hole_diameter_mm)
    da = _require("engine_support_external_diameter_mm", outer_diameter_mm)
    lk = _require("clamp_length_mm", clamp_length_mm, accepted="a clamped length > 0 mm")
    ep = constant("clamped_parts_modulus_mpa") if modulus_mpa is None else _require("clamped parts modulus [MPa]",
                                                                                     modulus_mpa)
    dw, dh, da, lk, ep = np.broadcast_arrays(dw, dh, da, lk, ep)
    if np.any(dw <= dh):
        raise InputError(Problem("bolt_head_contact_external_diameter_mm", float(np.ravel(dw[dw <= dh])[0]),
                                 "a diameter > the support internal diameter"))
    if np.any(da <= dh):
        raise InputError(Problem("engine_support_external_diameter_mm", float(np.ravel(da[da <= dh])[0]),
                                 "a diameter > the support internal diameter"))
    w = 2.0 if joint_type == "tapped" else 1.0
    beta, y = lk / dw, np.maximum(da, dw) / dw
    tan_phi = (0.348 + 0.013 * np.log(beta) + 0.193 * np.log(y)) if joint_type == "tapped" else \
        (0.362 + 0.032 * np.log(beta / 2.0) + 0.153 * np.log(y))
    tan_phi = np.maximum(tan_phi, 1e-3)  # the fits stay > 0.1 for any real joint; guard absurd l_K/d_W only
    da_gr = dw + w * lk * tan_phi
    with np.errstate(divide="ignore", invalid="ignore"):
        cone = 2.0 * np.log((dw + dh) * (da_gr - dh) / ((dw - dh) * (da_gr + dh))) / (w * ep * np.pi * dh * tan_phi)
        da_c = np.clip(da, dw * (1 + 1e-12), None)
        cone_sleeve = (2.0 / (w * dh * tan_phi) * np.log((dw + dh) * (da_c - dh) / ((dw - dh) * (da_c + dh)))
                       + 4.0 / (da_c**2 - dh**2) * (lk - (da_c - dw) / (w * tan_phi))) / (ep * np.pi)
    sleeve = lk / (ep * np.pi / 4.0 * (da**2 - dh**2))
    return np.where(da >= da_gr, cone, np.where(da > dw, cone_sleeve, sleeve))


def embedding_preload_loss_n(embedding_um_, bolt_resilience, clamped_resilience):
    """Preload lost to embedding ``F_Z = f_Z/(delta_S + delta_P)``, VDI 2230 Part 1 eq. (R4/1) [N].

    ``f_Z`` in um (converted to mm), resiliences in mm/N.

    >>> round(float(embedding_preload_loss_n(10.0, 5.498e-6, 2.039e-6)))
    1327
    """
    fz = _require("embedding [um]", embedding_um_, inclusive=True)
    return fz * 1e-3 / (_require("bolt resilience", bolt_resilience) + _require("clamped parts resilience",
                                                                                clamped_resilience))
