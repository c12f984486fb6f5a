"""ISO 286 fits of the hole-basis system: ``30H7/u6`` to its interference range.

Data: ``catalogs/iso286_it_grades.csv`` (standard tolerance grades IT5-IT8)
and ``catalogs/iso286_shaft_deviations.csv`` (fundamental deviations of the
shafts f, g, h, js, k, m, n, p, r, s, t, u, v, x), both ISO 286-1/-2:2010,
nominal sizes over 6 up to 50 mm. Holes: H only (EI = 0, ES = IT).

Interference is positive when the shaft is larger than the hole:
``U_max = es - EI``, ``U_min = ei - ES`` (negative: the fit may be loose).

>>> f = fit_limits("30H7/u6")
>>> f["interference_min_mm"], f["interference_max_mm"]
(0.027, 0.061)
"""

from __future__ import annotations

import re

from synth.catalog import load
from synth.errors import CatalogError, Problem

__all__ = ["parse_fit", "fit_limits", "shaft_letters", "candidate_fits"]

_FIT = re.compile(r"^\s*(?:[Øø⌀]\s*)?(\d+(?:\.\d+)?)\s*([A-Za-z]+)(\d+)\s*/\s*([a-z]+)(\d+)\s*$")


def _grades() -> list[int]:
    return sorted(int(c[2:-3]) for c in load("iso286_it_grades").columns if c.startswith("IT"))


def parse_fit(designation: str, field: str = "fit") -> tuple[float, str, int, str, int]:
    """Split ``"30H7/u6"`` into ``(30.0, "H", 7, "u", 6)``; a malformed one raises InputError.

    >>> parse_fit("Ø30 H7/u6")
    (30.0, 'H', 7, 'u', 6)
    """
    m = _FIT.match(str(designation))
    if not m:
        raise CatalogError(Problem(field, designation, "an ISO 286 hole-basis fit such as '30H7/u6'"))
    d, hole, hg, shaft, sg = m.groups()
    return float(d), hole, int(hg), shaft, int(sg)


def shaft_letters() -> list[str]:
    """Shaft fundamental-deviation letters in the catalog, loosest first."""
    order = ["f", "g", "h", "js", "k", "m", "n", "p", "r", "s", "t", "u", "v", "x"]
    have = set(load("iso286_shaft_deviations")["letter"])
    return [x for x in order if x in have] + sorted(have - set(order))


def _it_um(d_mm: float, grade: int, field: str) -> float:
    it = load("iso286_it_grades")
    hit = it[(it["over_mm"] < d_mm) & (d_mm <= it["up_to_mm"])]
    if hit.empty:
        lo, hi = it["over_mm"].min(), it["up_to_mm"].max()
        raise CatalogError(Problem(field, d_mm, f"a nominal diameter over {lo:g} up to {hi:g} mm"))
    col = f"IT{grade}_um"
    if col not in it.columns:
        raise CatalogError(Problem(field, f"IT{grade}", "tolerance grade IT" + ", IT".join(map(str, _grades()))))
    return float(hit.iloc[0][col])


def fit_limits(designation: str, field: str = "fit") -> dict:
    """Limit deviations and interference range of an ISO 286 hole-basis fit.

    Returns a dict: ``designation, diameter_mm, hole_upper_mm, hole_lower_mm,
    shaft_upper_mm, shaft_lower_mm, interference_min_mm,
    interference_max_mm`` (deviations from the nominal size, mm). Unknown or
    unsupported fits raise :class:`synth.errors.CatalogError` listing what is
    accepted.

    >>> fit_limits("20H7/k6")["interference_min_mm"]
    -0.019
    """
    d, hole, hg, letter, sg = parse_fit(designation, field)
    if hole != "H":
        raise CatalogError(Problem(field, designation, "a hole-basis fit (hole H), e.g. '30H7/u6'"))
    it_hole, it_shaft = _it_um(d, hg, field), _it_um(d, sg, field)
    dev = load("iso286_shaft_deviations")
    rows = dev[(dev["letter"] == letter) & (dev["over_mm"] < d) & (d <= dev["up_to_mm"])]
    if rows.empty:
        ok = sorted(set(dev[(dev["over_mm"] < d) & (d <= dev["up_to_mm"])]["letter"]),
                    key=shaft_letters().index)
        raise CatalogError(Problem(field, designation,
                                   f"shaft letter one of {', '.join(ok) or '(none)'} for {d:g} mm"))
    r = rows.iloc[0]
    value = float(r["value_um"])
    if letter == "js":
        es, ei = it_shaft / 2.0, -it_shaft / 2.0
    elif r["deviation"] == "es":
        es, ei = value, value - it_shaft
    else:
        ei = value if not (letter == "k" and sg > 7) else 0.0
        es = ei + it_shaft
    ES, EI = it_hole, 0.0
    return {"designation": f"{d:g}H{hg}/{letter}{sg}", "diameter_mm": d,
            "hole_upper_mm": round(ES * 1e-3, 6), "hole_lower_mm": round(EI * 1e-3, 6),
            "shaft_upper_mm": round(es * 1e-3, 6), "shaft_lower_mm": round(ei * 1e-3, 6),
            "interference_min_mm": round((ei - ES) * 1e-3, 6), "interference_max_mm": round((es - EI) * 1e-3, 6)}


def candidate_fits(diameter_mm: float, hole_grade: int = 7, shaft_grade: int = 6,
                   letters: tuple[str, ...] = ("k", "m", "n", "p", "r", "s", "t", "u", "v", "x")) -> list[str]:
    """Fit designations ``H<hole_grade>/<letter><shaft_grade>`` the catalog has for ``diameter_mm``.

    >>> candidate_fits(30)
    ['30H7/k6', '30H7/m6', '30H7/n6', '30H7/p6', '30H7/r6', '30H7/s6', '30H7/t6', '30H7/u6', '30H7/v6', '30H7/x6']
    >>> candidate_fits(12)[-2:]
    ['12H7/u6', '12H7/x6']
    """
    dev = load("iso286_shaft_deviations")
    have = set(dev[(dev["over_mm"] < diameter_mm) & (diameter_mm <= dev["up_to_mm"])]["letter"])
    return [f"{diameter_mm:g}H{hole_grade}/{x}{shaft_grade}" for x in letters if x in have]
