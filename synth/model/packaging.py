"""Step 7 of the thesis flowchart: packaging constraints, eq. (50)-(54).

The axial stack of a rotary tensioner, measured from the crankcase face:

* standard layout (belt far from the crankcase): support plate, spring housing,
  (damper pad with axial damping), arm support of the ball bearing, ball
  bearing centred on the belt middle plane, endcap spacer, endcap, calking;
* reverse layout: the bearing sits low and the spring housing above it.

Checks (normalised margins, >= 0 passes):

* belt plane feasibility against the maximum pivot height, eq. (50) (standard:
  ``mpbh <= mpbh_max``) or eq. (51) (reverse: ``mpbh >= mpbh_min``);
* the pulley top against the maximum axial displacement (thesis eq. 26, the same
  stack seen from the pulley): ``mpbh + w_pulley/2 <= max_axial_displacement``;
* the spring cavity, eq. (52)-(53), against a minimum height.

Eq. (52) as printed omits the damper pad: with axial damping its height is
subtracted too (the correction reproduces the spring housing heights of thesis
Tables 10 and 14, 14.8 and 8.8 mm).

Units: mm.

>>> r = packaging(29.5, 40.0, 42.0, 13.0, 55.0, 5.0, 20.0, axial_damping=True,
...               endcap_spacer_height_mm=1.5, damper_pad_height_mm=3.5)
>>> round(float(r["spring_housing_height_mm"]), 2), bool(r["passes"])
(14.8, True)
"""

from __future__ import annotations

import numpy as np

from synth import catalog
from synth.checks import Check, margin_lower, margin_upper
from synth.errors import InputError, Problem

__all__ = ["LAYOUTS", "max_belt_plane_height_mm", "min_belt_plane_height_mm", "spring_housing_height_mm",
           "spring_housing_inner_diameter_mm",
           "spring_housing_outer_diameter_mm", "packaging", "packaging_checks"]

LAYOUTS = ("standard", "reverse")


def _c(name: str) -> float:
    return catalog.constant(name)


def _check_layout(layout: str) -> None:
    if layout not in LAYOUTS:
        raise InputError(Problem("architecture layout", layout, " or ".join(LAYOUTS)))


def max_belt_plane_height_mm(max_pivot_height_mm, bearing_width_mm, endcap_spacer_height_mm=0.0):
    """Highest belt middle plane a standard layout can host, eq. (50) [mm].

    ``mpbh_max = h_pivot_max - w_bearing/2 - h_es - h_e - h_calking``
    (``h_es = 0`` without endcap spacer; ``h_e``, ``h_calking`` from
    ``constants_packaging.csv``).

    >>> float(max_belt_plane_height_mm(40.0, 13.0, 1.5))
    29.8
    """
    h, w, h_es = (np.asarray(x, dtype=float) for x in (max_pivot_height_mm, bearing_width_mm, endcap_spacer_height_mm))
    return h - w / 2.0 - h_es - _c("endcap_height_mm") - _c("calking_height_mm")


def min_belt_plane_height_mm(bearing_width_mm, endcap_spacer_height_mm=0.0):
    """Lowest belt middle plane a reverse layout can host, eq. (51) [mm].

    ``mpbh_min = w_bearing/2 + h_es + h_pivot_base``.

    >>> float(min_belt_plane_height_mm(13.0, 1.5))
    11.0
    """
    w, h_es = np.asarray(bearing_width_mm, dtype=float), np.asarray(endcap_spacer_height_mm, dtype=float)
    return w / 2.0 + h_es + _c("pivot_base_height_mm")


def spring_housing_height_mm(belt_plane_height_mm, bearing_width_mm, *, layout="standard", axial_damping=False,
                             damper_pad_height_mm=0.0, max_pivot_height_mm=None):
    """Spring cavity height, eq. (52) (standard) and eq. (53) (reverse) [mm].

    Standard: ``h = mpbh - w/2 - t_arm - t_supp_plate - t_spring_bush - gap_crank_plate - h_dp``;
    reverse: ``h = h_pivot_max - t_e - h_calking - t_spring_bush - mpbh - w/2 - t_arm - h_dp``,
    where ``h_dp`` (damper pad height) counts only with axial damping: the
    printed eq. (52)-(53) omit it (NOTES.md; Tables 10/14 need it).

    >>> float(spring_housing_height_mm(20.0, 13.0))
    8.8
    >>> round(float(spring_housing_height_mm(29.5, 13.0, axial_damping=True, damper_pad_height_mm=3.5)), 2)
    14.8
    """
    _check_layout(layout)
    mpbh, w = np.asarray(belt_plane_height_mm, dtype=float), np.asarray(bearing_width_mm, dtype=float)
    h_dp = np.where(np.asarray(axial_damping, dtype=bool), np.asarray(damper_pad_height_mm, dtype=float), 0.0)
    t_arm, t_sb = _c("arm_bearing_support_thickness_mm"), _c("spring_bushing_axial_thickness_mm")
    if layout == "standard":
        return mpbh - w / 2.0 - t_arm - _c("support_plate_thickness_mm") - t_sb \
            - _c("crankcase_support_plate_gap_mm") - h_dp
    if max_pivot_height_mm is None:
        raise InputError(Problem("max_pivot_height_mm", None, "a value (needed by eq. (53), reverse layout)"))
    h = np.asarray(max_pivot_height_mm, dtype=float)
    return h - _c("endcap_height_mm") - _c("calking_height_mm") - t_sb - mpbh - w / 2.0 - t_arm - h_dp


def spring_housing_outer_diameter_mm(bearing_outer_diameter_mm, working_arm_mm):
    """Spring housing external diameter, eq. (54): ``D_bearing_ext - 2 * l_arm`` [mm].

    >>> float(spring_housing_outer_diameter_mm(55.0, 5.0))
    45.0
    """
    return np.asarray(bearing_outer_diameter_mm, dtype=float) - 2.0 * np.asarray(working_arm_mm, dtype=float)


def spring_housing_inner_diameter_mm(pivot_class_diameter_mm):
    """Inner support of the main spring: pivot class envelope + 2 x spring-bushing wall [mm].

    The thesis gives no spring-bushing dimension; the wall is the illustrative
    constant ``spring_bushing_wall_mm`` (3 mm: case 1's production spring,
    Dm 36.8 mm, 2.3 x 2.3 wire, winds without touching). Flowchart and
    optimiser both read this one function.

    >>> float(spring_housing_inner_diameter_mm(16.0))
    22.0
    """
    return np.asarray(pivot_class_diameter_mm, dtype=float) + 2.0 * catalog.constant("spring_bushing_wall_mm")


def packaging(belt_plane_height_mm, max_pivot_height_mm, max_axial_displacement_mm, bearing_width_mm,
              bearing_outer_diameter_mm, working_arm_mm, pulley_width_mm, *, layout="standard", axial_damping=False,
              endcap_spacer_height_mm=0.0, damper_pad_height_mm=0.0, belt_height_increment_mm=0.0):
    """All of step 7 (vectorised): stack heights, checks, margins and corrections.

    ``belt_height_increment_mm`` (default 0, as the thesis tool: case 3 passes
    only with the nominal plane) shifts the belt plane for the pulley-top check.

    Returns ``mpbh_max_mm`` (standard) or ``mpbh_min_mm`` (reverse),
    ``spring_housing_height_mm``, ``spring_housing_outer_diameter_mm``,
    ``pulley_top_mm``, margins ``margin_belt_plane``, ``margin_axial_displacement``,
    ``margin_spring_cavity``, ``passes``, and suggested corrections (>= 0, mm):
    ``lower_belt_plane_by_mm`` / ``raise_belt_plane_by_mm`` (belt plane
    feasibility), ``raise_max_pivot_height_by_mm``, ``reduce_pulley_top_by_mm``,
    ``spring_cavity_shortfall_mm``.
    """
    _check_layout(layout)
    mpbh = np.asarray(belt_plane_height_mm, dtype=float)
    h_es = np.asarray(endcap_spacer_height_mm, dtype=float)
    h_spring = spring_housing_height_mm(mpbh, bearing_width_mm, layout=layout, axial_damping=axial_damping,
                                        damper_pad_height_mm=damper_pad_height_mm,
                                        max_pivot_height_mm=max_pivot_height_mm)
    top = mpbh + np.asarray(belt_height_increment_mm, dtype=float) + np.asarray(pulley_width_mm, dtype=float) / 2.0
    ax_max = np.asarray(max_axial_displacement_mm, dtype=float)
    h_min = _c("spring_cavity_min_height_mm")
    out = {"spring_housing_height_mm": h_spring,
           "spring_housing_outer_diameter_mm": spring_housing_outer_diameter_mm(bearing_outer_diameter_mm,
                                                                               working_arm_mm),
           "pulley_top_mm": top,
           "margin_axial_displacement": margin_upper(top, ax_max),
           "reduce_pulley_top_by_mm": np.maximum(top - ax_max, 0.0),
           "margin_spring_cavity": margin_lower(h_spring, h_min),
           "spring_cavity_shortfall_mm": np.maximum(h_min - h_spring, 0.0)}
    if layout == "standard":
        lim = max_belt_plane_height_mm(max_pivot_height_mm, bearing_width_mm, h_es)
        out.update(mpbh_max_mm=lim, margin_belt_plane=margin_upper(mpbh, lim),
                   lower_belt_plane_by_mm=np.maximum(mpbh - lim, 0.0),
                   raise_max_pivot_height_by_mm=np.maximum(mpbh - lim, 0.0))
    else:
        lim = min_belt_plane_height_mm(bearing_width_mm, h_es)
        out.update(mpbh_min_mm=lim, margin_belt_plane=margin_lower(mpbh, lim),
                   raise_belt_plane_by_mm=np.maximum(lim - mpbh, 0.0))
    shape = np.broadcast_shapes(*(np.shape(v) for v in out.values()))
    out = {k: np.broadcast_to(v, shape) for k, v in out.items()}
    out["passes"] = np.all([out[k] >= 0.0 for k in out if k.startswith("margin_")], axis=0)
    return out


def packaging_checks(result: dict, *, max_axial_displacement_mm: float, belt_plane_height_mm: float,
                     layout: str = "standard") -> list[Check]:
    """Report records (:class:`~synth.checks.Check`) of step 7 for one scalar design.

    >>> r = packaging(20.0, 34.0, 36.3, 13.0, 55.0, 4.0, 30.0)
    >>> [c.verdict for c in packaging_checks(r, max_axial_displacement_mm=36.3, belt_plane_height_mm=20.0)]
    ['pass', 'pass', 'pass']
    """
    _check_layout(layout)
    s = {k: float(np.asarray(v).ravel()[0]) for k, v in result.items()}
    if layout == "standard":
        plane = Check("belt middle plane vs max pivot height", 7, belt_plane_height_mm, s["mpbh_max_mm"], "<=", "mm",
                      "eq. (50)", f"lower the belt plane or raise the max pivot height by "
                                  f"{s['lower_belt_plane_by_mm']:.2f} mm" if s["lower_belt_plane_by_mm"] > 0 else "")
    else:
        plane = Check("belt middle plane vs reverse-layout minimum", 7, belt_plane_height_mm, s["mpbh_min_mm"], ">=",
                      "mm", "eq. (51)", f"raise the belt plane by {s['raise_belt_plane_by_mm']:.2f} mm"
                      if s["raise_belt_plane_by_mm"] > 0 else "")
    return [
        plane,
        Check("pulley top vs max axial displacement", 7, s["pulley_top_mm"], max_axial_displacement_mm, "<=", "mm",
              "eq. (26)/(50)", f"narrower pulley or lower belt plane by {s['reduce_pulley_top_by_mm']:.2f} mm"
              if s["reduce_pulley_top_by_mm"] > 0 else ""),
        Check("spring housing height", 7, s["spring_housing_height_mm"], _c("spring_cavity_min_height_mm"), ">=",
              "mm", "eq. (52)-(53), damper pad included",
              f"{s['spring_cavity_shortfall_mm']:.2f} mm more axial room (raise belt plane or thinner stack)"
              if s["spring_cavity_shortfall_mm"] > 0 else ""),
    ]
