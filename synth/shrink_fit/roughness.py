"""Roughness parameters of the journal and hub bore (paper eq. 3-16).

All lengths in micrometres. The paper's subscripts: ``s`` the crankshaft
journal, ``h`` the toothed-pulley hub bore, ``eq`` the equivalent surface of
the pair (sums, eq. 7-13).

Equation corrections (see ``docs/sections/shrink_fit.md``):

* eq. (16) is printed ``Rv / (r**(1/v) * b)``; its own Table 1 (and eq. 3)
  need ``Rv / (r * b**(1/v))``, which is Kombalov's form. We implement the
  latter for single and equivalent surfaces.
* Table 1's single-surface Rp and Rv are the estimates ``Rp = 0.5 Rz`` and
  ``Rv = 1.2 Rp`` of sec. 3.4 (rounded); its derived values (b, v, r) use the
  unrounded estimates. :func:`surface` estimates Rp and Rv that way when they
  are not given, or always with ``rp_rv_from_rz=True``.
"""

from __future__ import annotations

import numpy as np

from synth.catalog import constant

__all__ = ["profile_v", "profile_b", "asperity_radius_um", "komalov_parameter",
           "surface", "equivalent_surface"]


def profile_v(rp_um, ra_um, t_m=0.5):
    """Bearing-curve exponent ``v = 2 t_m Rp / Ra - 1`` (paper eq. 4).

    Parameters: ``rp_um`` peak height Rp [um], ``ra_um`` Ra [um], ``t_m``
    relative reference length at the centre line [-]. Returns v [-].
    The journal of Table 1 (Rp = 2.36, Ra = 0.62) gives 2.81:

    >>> round(float(profile_v(2.36, 0.62)), 2)
    2.81
    """
    rp, ra, t = (np.asarray(x, dtype=float) for x in (rp_um, ra_um, t_m))
    return 2.0 * t * rp / ra - 1.0


def profile_b(rv_um, rp_um, v, t_m=0.5):
    """Bearing-curve constant ``b = t_m (Rv/Rp)**v`` (paper eq. 5 and 14).

    For the equivalent surface pass ``t_m = t_meq`` (eq. 12, the sum of both
    surfaces' t_m) and ``v = v_eq``. Journal of Table 1: 0.83.

    >>> round(float(profile_b(2.832, 2.36, 2.806)), 2)
    0.83
    """
    rv, rp, v, t = (np.asarray(x, dtype=float) for x in (rv_um, rp_um, v, t_m))
    return t * (rv / rp) ** v


def asperity_radius_um(ra_um, sm_um, rp_um):
    """Mean asperity radius ``r = 9 Ra^2 Sm^2 / (128 (5.5 Ra - Rp)^3)`` [um] (eq. 6, 15).

    Valid only while ``5.5 Ra > Rp`` (the input loader rejects other
    surfaces); outside that domain the radius is returned as ``inf`` (a flat
    surface: Komalov parameter 0), never NaN. Journal of Table 1: 143.18 um.

    >>> round(float(asperity_radius_um(0.62, 78.31, 2.36)), 2)
    143.18
    """
    ra, sm, rp = (np.asarray(x, dtype=float) for x in (ra_um, sm_um, rp_um))
    denom = 5.5 * ra - rp
    safe = np.where(denom > 0.0, denom, 1.0)
    return np.where(denom > 0.0, 9.0 * ra**2 * sm**2 / (128.0 * safe**3), np.inf)


def komalov_parameter(rv_um, r_um, b, v):
    """Kombalov ("Komalov") complex roughness parameter ``Rv / (r b**(1/v))`` [-] (eq. 3, 16 corrected).

    Journal of Table 1 (Rv 2.832, r 143.18, b 0.834, v 2.806): 0.021.

    >>> round(float(komalov_parameter(2.832, 143.18, 0.834, 2.806)), 4)
    0.0211
    """
    rv, r, b, v = (np.asarray(x, dtype=float) for x in (rv_um, r_um, b, v))
    return rv / (r * b ** (1.0 / v))


def surface(ra_um, rz_um, sm_um=None, rp_um=None, rv_um=None, t_m=None, rp_rv_from_rz=False, sm_over_ra=None):
    """Derived parameters of one surface (paper eq. 3-6).

    Missing ``sm_um`` is estimated as ``sm_over_ra`` (default: constant
    ``shrink_fit_sm_over_ra``, 1000) times Ra, missing ``rp_um`` as 0.5 Rz and
    ``rv_um`` as 1.2 Rp (sec. 3.4); ``rp_rv_from_rz=True`` uses the estimates
    even when Rp and Rv are given (what the paper's Table 1 did).

    Returns a dict with keys ``ra_um, rz_um, sm_um, rp_um, rv_um, t_m, v, b,
    asperity_radius_um, komalov``. New hub bore of Table 1:

    >>> s = surface(0.31, 2.33, 56.34, rp_rv_from_rz=True)
    >>> round(float(s["v"]), 2), round(float(s["b"]), 2), round(float(s["asperity_radius_um"]), 1)
    (2.76, 0.83, 136.2)
    """
    ra, rz = np.asarray(ra_um, dtype=float), np.asarray(rz_um, dtype=float)
    t = constant("shrink_fit_t_m") if t_m is None else t_m
    ratio = constant("shrink_fit_sm_over_ra") if sm_over_ra is None else sm_over_ra
    sm = ra * ratio if sm_um is None else np.asarray(sm_um, dtype=float)
    if rp_rv_from_rz or rp_um is None:
        rp = rz * constant("shrink_fit_rp_over_rz")
    else:
        rp = np.asarray(rp_um, dtype=float)
    if rp_rv_from_rz or rv_um is None:
        rv = rp * constant("shrink_fit_rv_over_rp")
    else:
        rv = np.asarray(rv_um, dtype=float)
    v = profile_v(rp, ra, t)
    b = profile_b(rv, rp, v, t)
    r = asperity_radius_um(ra, sm, rp)
    return {"ra_um": ra, "rz_um": rz, "sm_um": sm, "rp_um": rp, "rv_um": rv, "t_m": np.asarray(t, dtype=float),
            "v": v, "b": b, "asperity_radius_um": r, "komalov": komalov_parameter(rv, r, b, v)}


def equivalent_surface(journal: dict, hub: dict) -> dict:
    """Equivalent surface of the pair (paper eq. 7-16), from two :func:`surface` dicts.

    Ra, Rz, Sm, Rp, Rv, t_m and v add (eq. 7-13); b, r and the Komalov
    parameter follow from the sums (eq. 14-16, eq. 16 corrected). Same keys
    as :func:`surface`. Table 1, new pulley on the journal:

    >>> j = surface(0.62, 4.72, 78.31, rp_rv_from_rz=True)
    >>> e = equivalent_surface(j, surface(0.31, 2.33, 56.34, rp_rv_from_rz=True))
    >>> [round(float(e[k]), 3) for k in ("v", "b", "asperity_radius_um", "komalov")]
    [5.565, 2.758, 274.296, 0.013]
    """
    keys = ("ra_um", "rz_um", "sm_um", "rp_um", "rv_um", "t_m", "v")
    eq = {k: journal[k] + hub[k] for k in keys}
    eq["b"] = profile_b(eq["rv_um"], eq["rp_um"], eq["v"], eq["t_m"])
    eq["asperity_radius_um"] = asperity_radius_um(eq["ra_um"], eq["sm_um"], eq["rp_um"])
    eq["komalov"] = komalov_parameter(eq["rv_um"], eq["asperity_radius_um"], eq["b"], eq["v"])
    return eq
