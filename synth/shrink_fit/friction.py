"""Friction coefficient of the journal / hub-bore contact (paper eq. 1, 2, 16b, Fig. 3).

Pressures in MPa, hardness as the Brinell number HB (the paper divides the
pressure in MPa by the HB number: Table 2's ``p_s/HB`` = 47.73/245 = 0.195),
penetration depth in um.

* elastic contact, eq. (1): ``mu = k sqrt(dK) (p_c/HB)**0.25``;
* plastic-saturated contact, eq. (2):
  ``mu = 0.1 tau0/HB_a + beta + 0.9 sqrt(dK) (p_c/HB)**0.5``;
* saturation when ``p_c/HB`` exceeds 0.0625 (sec. 4.2).

HB is the hardness of the softer surface (the paper's definition). The
paper's Table 3 used the harder hub (388 HB) for the adhesion term
``0.1 tau0/HB_a`` and the journal (245 HB) for the rest; ``HB_a`` is
therefore a separate argument (see ``docs/sections/shrink_fit.md``).
"""

from __future__ import annotations

import numpy as np

from synth.catalog import constant, load

__all__ = ["FRICTION_MODELS", "penetration_depth_um", "k_fit", "k_coefficient", "k_extrapolated",
           "mu_elastic", "mu_plastic", "plastic_saturated", "friction_coefficient"]

FRICTION_MODELS = ("regime", "elastic", "plastic")


def penetration_depth_um(ra_eq_um, pressure_mpa, hardness_hb):
    """Penetration depth ``h = 3.4 Ra_eq (p_c/HB)**(1/3)`` [um] (paper eq. 16, the second one).

    Negative pressures are treated as 0. Table 3, new surfaces at 47.73 MPa:
    0.00183 mm.

    >>> round(float(penetration_depth_um(0.93, 47.73, 245)), 3)
    1.833
    """
    p = np.clip(np.asarray(pressure_mpa, dtype=float), 0.0, None)
    return 3.4 * np.asarray(ra_eq_um, dtype=float) * np.cbrt(p / np.asarray(hardness_hb, dtype=float))


def k_fit() -> tuple[float, float, float, float]:
    """Straight line ``k = a + b h`` through ``catalogs/shrink_fit_k_vs_h.csv`` (paper Fig. 3).

    Returns ``(a, b_per_um, h_min_um, h_max_um)``; the points are the paper's
    Table 3 pairs (k read from its Fig. 3, after [54]), the fit reproduces them
    to 0.1 %.

    >>> a, b, lo, hi = k_fit()
    >>> round(a, 3), round(b, 3), lo, hi
    (1.159, -0.132, 1.647, 2.433)
    """
    df = load("shrink_fit_k_vs_h")
    h, k = df["penetration_depth_um"].to_numpy(float), df["k"].to_numpy(float)
    b, a = np.polyfit(h, k, 1)
    return float(a), float(b), float(h.min()), float(h.max())


def k_coefficient(penetration_depth_um):
    """Coefficient k [-] of eq. (1) as a function of penetration depth [um] (paper Fig. 3).

    Linear fit of :func:`k_fit`, extrapolated linearly outside the fitted
    range (see :func:`k_extrapolated`) and clipped at 0 (never negative).

    >>> round(float(k_coefficient(1.833)), 3)
    0.917
    """
    a, b, _, _ = k_fit()
    return np.clip(a + b * np.asarray(penetration_depth_um, dtype=float), 0.0, None)


def k_extrapolated(penetration_depth_um):
    """True where the depth lies outside the range of the Fig. 3 points (k extrapolated).

    >>> k_extrapolated([1.0, 2.0]).tolist()
    [True, False]
    """
    _, _, lo, hi = k_fit()
    h = np.asarray(penetration_depth_um, dtype=float)
    return (h < lo - 1e-3) | (h > hi + 1e-3)  # points are given to 0.001 um


def mu_elastic(k, komalov, pressure_mpa, hardness_hb):
    """Friction coefficient for elastic contact ``k sqrt(dK) (p_c/HB)**0.25`` [-] (paper eq. 1, after [54]).

    Table 3, new surfaces, 47.73 MPa (k 0.916, dK 0.01285): 0.069.

    >>> round(float(mu_elastic(0.916, 0.01285, 47.73, 245)), 3)
    0.069
    """
    p = np.clip(np.asarray(pressure_mpa, dtype=float), 0.0, None)
    return np.asarray(k, dtype=float) * np.sqrt(komalov) * (p / np.asarray(hardness_hb, dtype=float)) ** 0.25


def mu_plastic(komalov, pressure_mpa, hardness_hb, tau0_mpa=None, beta=None, adhesion_hardness_hb=None):
    """Friction coefficient for plastic-saturated contact [-] (paper eq. 2, after [31]).

    ``0.1 tau0/HB_a + beta + 0.9 sqrt(dK) (p_c/HB)**0.5`` with ``HB_a =
    adhesion_hardness_hb`` (default: ``hardness_hb``, the softer surface).
    ``tau0_mpa`` and ``beta`` default to the catalog constants (1256 MPa,
    0.072). Table 3, new surfaces, 47.73 MPa, adhesion term on the 388 HB hub
    as the paper did: 0.441.

    >>> round(float(mu_plastic(0.01285, 47.73, 245, adhesion_hardness_hb=388)), 3)
    0.441
    >>> round(float(mu_plastic(0.01285, 47.73, 245)), 3)
    0.63
    """
    tau0 = constant("shrink_fit_tau0_mpa") if tau0_mpa is None else tau0_mpa
    beta = constant("shrink_fit_beta") if beta is None else beta
    hb = np.asarray(hardness_hb, dtype=float)
    hba = hb if adhesion_hardness_hb is None else np.asarray(adhesion_hardness_hb, dtype=float)
    p = np.clip(np.asarray(pressure_mpa, dtype=float), 0.0, None)
    return 0.1 * np.asarray(tau0, dtype=float) / hba + beta + 0.9 * np.sqrt(komalov) * np.sqrt(p / hb)


def plastic_saturated(pressure_mpa, hardness_hb):
    """True where ``p_c/HB`` exceeds the saturation limit 0.0625 (paper sec. 4.2).

    >>> plastic_saturated([10.0, 47.73], 245).tolist()
    [False, True]
    """
    ratio = np.asarray(pressure_mpa, dtype=float) / np.asarray(hardness_hb, dtype=float)
    return ratio > constant("shrink_fit_plastic_saturation_p_over_hb")


def friction_coefficient(ra_eq_um, komalov, pressure_mpa, hardness_hb, model="regime",
                         tau0_mpa=None, beta=None, adhesion_hardness_hb=None) -> dict:
    """Penetration depth, k and both friction coefficients, and the one ``model`` selects.

    ``model``: ``"regime"`` (eq. 2 where the contact is plastic-saturated,
    eq. 1 elsewhere; the paper's reading), ``"elastic"`` (eq. 1 always, the
    cautious choice) or ``"plastic"`` (eq. 2 always). Returns a dict with
    keys ``penetration_depth_um, k, k_extrapolated, mu_eq1, mu_eq2,
    saturated, mu``.

    >>> r = friction_coefficient(0.93, 0.01285, 47.73, 245, adhesion_hardness_hb=388)
    >>> round(float(r["mu_eq1"]), 3), round(float(r["mu"]), 3)
    (0.069, 0.441)
    """
    if model not in FRICTION_MODELS:
        raise ValueError(f"friction model {model!r}: expected one of {FRICTION_MODELS}")
    h = penetration_depth_um(ra_eq_um, pressure_mpa, hardness_hb)
    k = k_coefficient(h)
    mu1 = mu_elastic(k, komalov, pressure_mpa, hardness_hb)
    mu2 = mu_plastic(komalov, pressure_mpa, hardness_hb, tau0_mpa, beta, adhesion_hardness_hb)
    sat = plastic_saturated(pressure_mpa, hardness_hb)
    mu = {"regime": np.where(sat, mu2, mu1), "elastic": mu1, "plastic": mu2}[model]
    return {"penetration_depth_um": h, "k": k, "k_extrapolated": k_extrapolated(h), "mu_eq1": mu1,
            "mu_eq2": mu2, "saturated": sat, "mu": mu}
