"""Step 6 of the thesis flowchart: axial stack-up of the cone-spring gap.

The cone spring sits in a gap whose height is the pivot height minus the
endcap spacer, the arm hub and the damper pad heights (thesis step 6). Each
height carries the fixed tolerance of thesis Table 6 (``catalogs/
stackup_tolerances.csv``); the gap tolerance is their worst-case sum
(thesis: +/-0.22 mm) or, as a less pessimistic alternative, their root sum
of squares (RSS, statistical stack-up of independent normal deviations with
equal process capability).

>>> r = gap_stackup(40.0, 1.5, 30.0, 3.5)
>>> float(r["gap_height_nominal_mm"]), r["gap_tolerance_worst_case_mm"]
(5.0, 0.22)
"""

from __future__ import annotations

import numpy as np

from synth import catalog
from synth.errors import InputError, Problem

__all__ = ["component_tolerances_mm", "gap_tolerance_mm", "gap_stackup", "STACKUP_METHODS"]

#: Ways of combining the component tolerances.
STACKUP_METHODS = ("worst_case", "rss")

_COMPONENTS = ("pivot", "endcap_spacer", "arm", "damper_pad")


def component_tolerances_mm() -> dict[str, float]:
    """Symmetric tolerances of the gap-height chain, thesis Table 6 [mm].

    >>> component_tolerances_mm()["pivot"]
    0.07
    """
    return dict(catalog.parsed("stackup_tolerances", _component_tolerances))


def _component_tolerances(df) -> tuple:
    """``((component, tolerance), ...)`` of the table (parsed once per table: the evaluator asks for the gap
    tolerance at every axial evaluation)."""
    tol = dict(zip(df["component"], df["tolerance_mm"].astype(float)))
    return tuple((c, float(tol[c])) for c in _COMPONENTS)


def gap_tolerance_mm(method: str = "worst_case", tolerances_mm: dict | None = None) -> float:
    """Tolerance of the cone-spring gap height from thesis Table 6 [mm].

    ``worst_case``: :math:`T = \\sum_i T_i` (thesis Table 6, "Overall +/-0.22");
    ``rss``: :math:`T = \\sqrt{\\sum_i T_i^2}` (statistical stack-up).
    ``tolerances_mm`` overrides single components (e.g. a tighter pivot).

    >>> gap_tolerance_mm("worst_case"), round(gap_tolerance_mm("rss"), 4)
    (0.22, 0.1114)
    """
    tol = component_tolerances_mm()
    if tolerances_mm:
        unknown = set(tolerances_mm) - set(tol)
        if unknown:
            raise InputError(Problem("tolerances_mm", sorted(unknown, key=str), "keys among " + ", ".join(_COMPONENTS)))
        tol.update({k: float(v) for k, v in tolerances_mm.items()})
    t = np.array(list(tol.values()), dtype=float)
    if method == "worst_case":
        return float(round(t.sum(), 12))
    if method == "rss":
        return float(np.sqrt(np.sum(t * t)))
    raise InputError(Problem("stackup_method", method, " or ".join(STACKUP_METHODS)))


def gap_stackup(pivot_height_mm, endcap_spacer_height_mm, arm_height_mm, damper_pad_height_mm,
                *, method: str = "worst_case", tolerances_mm: dict | None = None) -> dict:
    """Nominal cone-spring gap height and its tolerance band (thesis step 6).

    :math:`h_{gap} = h_{pivot} - h_{es} - h_{arm} - h_{dp}` (thesis step 6 text),
    tolerance from :func:`gap_tolerance_mm` (thesis Table 6).

    Parameters are heights in mm (numpy arrays broadcast). ``pivot_height_mm``
    is the height available between the pivot base and its head on the axis of
    the stack (the thesis's "pivot height").

    Returns a dict: ``gap_height_nominal_mm``, ``gap_height_min_mm`` (maximum
    material), ``gap_height_max_mm`` (minimum material),
    ``gap_tolerance_worst_case_mm``, ``gap_tolerance_rss_mm``,
    ``gap_tolerance_mm`` (the one of ``method``, used downstream) and
    ``margin_gap_positive`` (``>= 0`` when even the maximum-material gap is
    open: a negative gap means the stack does not fit).

    >>> r = gap_stackup([40.0, 40.0], 1.5, 30.0, [3.5, 8.5], method="rss")
    >>> r["gap_height_min_mm"].round(3).tolist(), r["margin_gap_positive"].round(3).tolist()
    ([4.889, -0.111], [43.901, -1.0])
    """
    h = (np.asarray(pivot_height_mm, dtype=float) - np.asarray(endcap_spacer_height_mm, dtype=float)
         - np.asarray(arm_height_mm, dtype=float) - np.asarray(damper_pad_height_mm, dtype=float))
    wc = gap_tolerance_mm("worst_case", tolerances_mm)
    rss = gap_tolerance_mm("rss", tolerances_mm)
    tol = gap_tolerance_mm(method, tolerances_mm)
    h_min = h - tol
    # margin of h_min >= 0: the limit is zero, so it is normalised by the tolerance
    # (the natural length scale of the stack) instead of by |limit|
    return {
        "gap_height_nominal_mm": h,
        "gap_height_min_mm": h_min,
        "gap_height_max_mm": h + tol,
        "gap_tolerance_worst_case_mm": wc,
        "gap_tolerance_rss_mm": rss,
        "gap_tolerance_mm": tol,
        "margin_gap_positive": h_min / tol,
    }
