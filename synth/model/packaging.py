"""Step 7 of the thesis flowchart: packaging constraints, eq. (50)-(54).

The axial stack of a rotary tensioner, measured from the crankcase face:

* standard layout (belt far from the crankcase): support plate, spring housing,
  (damper pad with axial damping), arm support of the ball bearing, ball
  bearing centred on the belt middle plane, endcap spacer, endcap, calking;
* reverse layout: the bearing sits low and the spring housing above it.

The limits this step gives (the constraints that compare them are in
:mod:`synth.design.constraints`):

* the belt plane limit from the maximum pivot height, eq. (50) (standard:
  ``mpbh <= mpbh_max``) or eq. (51) (reverse: ``mpbh >= mpbh_min``);
* the spring cavity height and diameters, eq. (52)-(54).

Eq. (52) as printed omits the damper pad: with axial damping its height is
subtracted too (the correction reproduces the spring housing heights of thesis
Tables 10 and 14, 14.8 and 8.8 mm).

Units: mm.

>>> round(float(spring_housing_height_mm(29.5, 13.0, axial_damping=True, damper_pad_height_mm=3.5)), 2)
14.8
"""

from __future__ import annotations

import numpy as np

from synth import catalog
from synth.errors import InputError, Problem

__all__ = ["LAYOUTS", "max_belt_plane_height_mm", "min_belt_plane_height_mm", "spring_housing_height_mm",
           "spring_housing_inner_diameter_mm",
           "spring_housing_outer_diameter_mm"]

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
