"""Contact pressure of the interference fit and its loss by smoothing (paper eq. 17-19).

Diameters in mm, interference (diametral, as ISO 286 gives it) in mm,
roughness in um, pressure and strength in MPa.

Pressure rules (a named, documented choice; see ``docs/sections/shrink_fit.md``):

* ``"lame"`` (default): thick-walled cylinders of one material, diametral
  interference ``U``: ``p = E U (1 - QA^2)(1 - QI^2) / (2 d (1 - QA^2 QI^2))``
  with ``QA = d / d_zo`` and ``QI = d_ww / d``.
* ``"paper_eq17"``: eq. (17) as the paper applies it, the same expression
  without the 1/2, i.e. the diametral interference used where the formula
  needs the radial one. It reproduces the paper's Table 2 and doubles the
  pressure.

Smoothing rules (eq. 18): ``"din7190_2001"`` ``G = 0.8 (Rz_s + Rz_h)`` per
displacement (default, the paper's rule) and ``"din7190_2017"``
``G = 0.4 (Rz_s + Rz_h)`` (DIN 7190-1:2017).
"""

from __future__ import annotations

import numpy as np

from synth.catalog import constant

__all__ = ["PRESSURE_RULES", "SMOOTHING_RULES", "smoothing_factor", "lame_factor_per_mm",
           "contact_pressure_mpa", "smoothing_mm", "total_smoothing_mm",
           "hub_yield_pressure_mpa", "journal_yield_pressure_mpa"]

#: pressure rule -> factor applied to ``E * U * lame_factor_per_mm``
PRESSURE_RULES = {"lame": 0.5, "paper_eq17": 1.0}

#: smoothing rule -> name of its factor in ``catalogs/constants_shrink_fit.csv``
SMOOTHING_RULES = {
    "din7190_2001": "shrink_fit_smoothing_factor_din7190_2001",
    "din7190_2017": "shrink_fit_smoothing_factor_din7190_2017",
}


def smoothing_factor(rule: str = "din7190_2001") -> float:
    """Smoothing factor of ``rule`` (0.8 for DIN 7190:2001, 0.4 for DIN 7190-1:2017; eq. 18).

    >>> smoothing_factor("din7190_2017")
    0.4
    """
    return constant(SMOOTHING_RULES[rule])


def lame_factor_per_mm(journal_outer_diameter_mm, journal_inner_diameter_mm, hub_outer_diameter_mm):
    """Geometry factor of eq. (17): ``(d^2 - d_ww^2)(d_zo^2 - d^2) / (d^3 (d_zo^2 - d_ww^2))`` [1/mm].

    Equal to ``(1 - QA^2)(1 - QI^2) / (d (1 - QA^2 QI^2))``. The paper's
    journal (30 mm, bore 12 mm, hub 35 mm): 0.0084181 1/mm.

    >>> round(float(lame_factor_per_mm(30, 12, 35)), 7)
    0.0084181
    """
    d, di, do = (np.asarray(x, dtype=float) for x in
                 (journal_outer_diameter_mm, journal_inner_diameter_mm, hub_outer_diameter_mm))
    return (d**2 - di**2) * (do**2 - d**2) / (d**3 * (do**2 - di**2))


def contact_pressure_mpa(interference_mm, journal_outer_diameter_mm, journal_inner_diameter_mm,
                         hub_outer_diameter_mm, young_modulus_mpa, smoothing_mm=0.0, rule="lame"):
    """Contact pressure [MPa] of the fit (paper eq. 17, with smoothing eq. 19).

    ``interference_mm`` is the diametral interference U; ``smoothing_mm``
    the total smoothing ``sum G_i`` subtracted from it (eq. 19). A
    non-positive effective interference gives 0 MPa (the joint is loose),
    never a negative pressure. ``rule`` is ``"lame"`` (physically correct,
    default) or ``"paper_eq17"`` (twice that: the paper's Table 2).

    Paper, 30H7/u6, worn surfaces (G = 0.011704 mm), U = 0.027 mm: Table 2
    prints 27.04 MPa with eq. (17) as applied; Lame gives half.

    >>> round(float(contact_pressure_mpa(0.027, 30, 12, 35, 210000, 0.011704, "paper_eq17")), 2)
    27.04
    >>> round(float(contact_pressure_mpa(0.027, 30, 12, 35, 210000, 0.011704)), 2)
    13.52
    """
    u = np.asarray(interference_mm, dtype=float) - np.asarray(smoothing_mm, dtype=float)
    factor = PRESSURE_RULES[rule]
    geo = lame_factor_per_mm(journal_outer_diameter_mm, journal_inner_diameter_mm, hub_outer_diameter_mm)
    return factor * np.asarray(young_modulus_mpa, dtype=float) * np.clip(u, 0.0, None) * geo


def smoothing_mm(rz_journal_um, rz_hub_um, rule="din7190_2001"):
    """Smoothing of one displacement ``G_i = c (Rz_s + Rz_h)`` [mm] (paper eq. 18).

    ``c`` = 0.8 (DIN 7190:2001, the paper) or 0.4 (DIN 7190-1:2017). First
    displacement of the paper (initial journal Rz 4.8 um, new bore 2.33 um):

    >>> round(float(smoothing_mm(4.8, 2.33)), 6)
    0.005704
    """
    rz = np.asarray(rz_journal_um, dtype=float) + np.asarray(rz_hub_um, dtype=float)
    return smoothing_factor(rule) * rz * 1e-3


def total_smoothing_mm(displacements, rz_journal_initial_um, rz_hub_new_um, rz_journal_um, rz_hub_worn_um,
                       rule="din7190_2001"):
    """Total smoothing ``sum_{i=1..n} G_i`` [mm] after ``n`` displacements (paper eq. 18-19).

    A displacement is one sliding of the bore along the journal: pulling the
    pulley off, or pressing it back on (the first, thermal shrink fit slides
    nothing, as in the paper). The first displacement cuts the initial
    surfaces (journal ``rz_journal_initial_um``, new bore ``rz_hub_new_um``),
    each later one the worn surfaces (``rz_journal_um``, ``rz_hub_worn_um``).
    The paper's i = 2: 0.8 (4.8 + 2.33) + 0.8 (4.72 + 2.78) = 11.704 um
    (Table 2 prints 0.0117 mm).

    >>> round(float(total_smoothing_mm(2, 4.8, 2.33, 4.72, 2.78)), 6)
    0.011704
    >>> total_smoothing_mm([0, 1], 4.8, 2.33, 4.72, 2.78).round(6).tolist()
    [0.0, 0.005704]
    """
    n = np.clip(np.asarray(displacements, dtype=float), 0.0, None)
    first = smoothing_mm(rz_journal_initial_um, rz_hub_new_um, rule)
    later = smoothing_mm(rz_journal_um, rz_hub_worn_um, rule)
    return np.where(n >= 1.0, first + np.clip(n - 1.0, 0.0, None) * later, 0.0)


def hub_yield_pressure_mpa(journal_outer_diameter_mm, hub_outer_diameter_mm, yield_strength_mpa):
    """Contact pressure [MPa] at which the hub bore starts to yield (Lame, von Mises, plane stress).

    At the bore ``sigma_t = p (1 + QA^2)/(1 - QA^2)``, ``sigma_r = -p``, so
    ``sigma_vM = p sqrt(3 + QA^4) / (1 - QA^2)`` and the limit is
    ``Re (1 - QA^2) / sqrt(3 + QA^4)`` (DIN 7190-1 uses the close
    ``Re (1 - QA^2)/sqrt(3)``). Hub 35 mm on 30 mm, Re 1100 MPa:

    >>> round(float(hub_yield_pressure_mpa(30, 35, 1100)), 1)
    155.1
    """
    qa = np.asarray(journal_outer_diameter_mm, dtype=float) / np.asarray(hub_outer_diameter_mm, dtype=float)
    return np.asarray(yield_strength_mpa, dtype=float) * (1.0 - qa**2) / np.sqrt(3.0 + qa**4)


def journal_yield_pressure_mpa(journal_outer_diameter_mm, journal_inner_diameter_mm, yield_strength_mpa):
    """Contact pressure [MPa] at which the journal starts to yield (Lame, von Mises, plane stress).

    Hollow journal: at its bore ``sigma_r = 0``, ``sigma_t = -2p/(1 - QI^2)``,
    limit ``Re (1 - QI^2)/2``. Solid journal (``d_ww = 0``): uniform
    ``sigma_r = sigma_t = -p``, limit ``Re``. The paper's journal (30/12 mm),
    Re 520 MPa:

    >>> round(float(journal_yield_pressure_mpa(30, 12, 520)), 1)
    218.4
    >>> float(journal_yield_pressure_mpa(30, 0, 520))
    520.0
    """
    d = np.asarray(journal_outer_diameter_mm, dtype=float)
    di = np.asarray(journal_inner_diameter_mm, dtype=float)
    re = np.asarray(yield_strength_mpa, dtype=float)
    qi = di / d
    return np.where(di > 0.0, re * (1.0 - qi**2) / 2.0, re)
