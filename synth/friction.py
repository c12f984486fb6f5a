"""Friction coefficients by interface and environment (``catalogs/friction_coefficients.csv``).

>>> mu("pivot_bushing", "belt_in_oil") < mu("pivot_bushing", "dry")
True
"""

from __future__ import annotations

from synth import catalog
from synth.errors import CatalogError, Problem

__all__ = ["mu", "mu_row"]


def mu_row(interface: str, environment: str):
    """The catalog row (``mu``, ``source``...) for an interface in an environment."""
    df = catalog.load("friction_coefficients")
    hit = df[(df["interface"] == interface) & (df["environment"].isin([environment, "any"]))]
    if hit.empty:
        pairs = ", ".join(sorted(set(df["interface"] + "/" + df["environment"])))
        raise CatalogError(Problem("friction coefficient", f"{interface}/{environment}", "one of " + pairs))
    exact = hit[hit["environment"] == environment]
    return (exact if not exact.empty else hit).iloc[0]


def mu(interface: str, environment: str) -> float:
    """Friction coefficient of ``interface`` (e.g. ``pivot_bushing``) in ``environment`` (``dry``/``belt_in_oil``)."""
    return float(mu_row(interface, environment)["mu"])
