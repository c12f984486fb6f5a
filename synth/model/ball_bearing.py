"""Step 1: ball bearing selection (thesis Table 1).

The bearing follows from the nominal hubload and the engine fuel: 6006 below
1000 N (gasoline) or 1200 N (diesel), 6007 above. Thresholds live in
``catalogs/bearing_selection.csv``, bearing data in ``catalogs/ball_bearings.csv``.

>>> select_bearing([652.5, 1100.0], "gasoline").tolist()
['6006', '6007']
>>> select_bearing(1100.0, "diesel").tolist()
['6006']
"""

from __future__ import annotations

import numpy as np

from synth import catalog
from synth.errors import InputError, Problem

__all__ = ["select_bearing", "max_hubload_n", "bearing_inner_diameter_mm", "basic_rating_life_h"]


def select_bearing(hubload_nominal_n, engine_fuel: str):
    """Bearing designation per Table 1 for each hubload (array of str).

    The first catalog row (in file order) whose ``max_hubload_nominal_n``
    exceeds the hubload is chosen; the last row has no upper bound.
    """
    rules = catalog.load("bearing_selection")
    rules = rules[rules["engine_fuel"] == engine_fuel]
    if rules.empty:
        raise InputError(Problem("engine_fuel", engine_fuel, "one of " + ", ".join(sorted(set(catalog.load("bearing_selection")["engine_fuel"])))))
    hl = np.atleast_1d(np.asarray(hubload_nominal_n, float))
    limits = rules["max_hubload_nominal_n"].astype(float).to_numpy()
    names = rules["designation"].astype(str).to_numpy()
    idx = np.searchsorted(limits, hl, side="right")  # limits ascending: first limit > hl
    return names[np.clip(idx, 0, len(names) - 1)]


def max_hubload_n(designation: str, engine_fuel: str):
    """The Table 1 upper hubload limit (N) of bearing ``designation``, or None where it has none.

    A bearing outside the engine fuel's Table 1 rows, and the last row (no
    upper bound), return None: there is no hubload limit to check.

    >>> max_hubload_n("6006", "gasoline"), max_hubload_n("6007", "gasoline")
    (1000.0, None)
    """
    rules = catalog.load("bearing_selection")
    hit = rules[(rules["engine_fuel"] == engine_fuel) & (rules["designation"].astype(str) == str(designation))]
    if hit.empty:
        return None
    lim = float(hit["max_hubload_nominal_n"].astype(float).iloc[0])
    return lim if np.isfinite(lim) else None


def bearing_inner_diameter_mm(designation):
    """Bore diameter ``d`` of each bearing designation, from ``ball_bearings.csv``.

    >>> bearing_inner_diameter_mm(["6006", "6007"]).tolist()
    [30.0, 35.0]
    """
    table = catalog.load("ball_bearings").set_index("designation")["d_mm"].astype(float)
    return np.array([table[str(d)] for d in np.atleast_1d(designation)])


def basic_rating_life_h(dynamic_load_rating_n, equivalent_load_n, speed_rpm):
    """Basic rating life of a ball bearing, ISO 281: ``L10h = (C/P)^3 * 1e6 / (60 n)`` [h].

    An informative output (the thesis selects by Table 1 only).

    >>> round(float(basic_rating_life_h(13800.0, 1380.0, 6000.0)))
    2778
    """
    c = np.asarray(dynamic_load_rating_n, float)
    p = np.maximum(np.asarray(equivalent_load_n, float), np.finfo(float).tiny)
    n = np.maximum(np.asarray(speed_rpm, float), np.finfo(float).tiny)
    return (c / p) ** 3 * 1e6 / (60.0 * n)
