"""Step 2: pivot diameter definition (thesis Table 2 and its rules).

* Table 2 gives, per bearing and working arm, the standard pivot class
  diameter and the maximum loading arm (``catalogs/pivot_classes.csv``).
* The class is for the 1 mm bushing; a thinner bushing enlarges the pivot by
  twice the thickness difference (0.5 mm bushing: +1 mm).
* The bolt hole is the bolt diameter + 0.2 mm (8.2 mm for M8, 10.2 mm for M10),
  eccentric by the loading arm on a double-eccentric tensioner.
* The arm keeps at least 1 mm of wall on the side of the eccentricity.

>>> standard_pivot_class("6006", 5.0)
(17.0, 3.5)
>>> float(pivot_diameter_mm(20.0, 0.5))
21.0
"""

from __future__ import annotations

import numpy as np

from synth import catalog
from synth.catalog import constant
from synth.errors import InputError, Problem

__all__ = [
    "table2_column", "standard_pivot_class", "pivot_diameter_mm", "bolt_hole_diameter_mm", "arm_wall_mm", "pivot_wall_mm",
    "max_pivot_class_for_wall_mm", "pivot_wall_values",
]


def table2_column(working_arms_mm, working_arm_mm):
    """Column of thesis Table 2 for a working arm, among a bearing's ascending ``working_arms_mm`` [index].

    "Given a tensioner working arm length, the standard value for the loading arm length (if present) and for the
    pivot class diameter correspond to the value that can be found in the same column." An arm between two
    columns takes the next larger arm's column (the smaller pivot class, which keeps the arm wall); the text
    leaves that case open. Returns ``(column, within)``: the column (clipped to the last) and whether the arm is
    within the table (not beyond its last column).

    >>> i, ok = table2_column([2.5, 3.0, 4.0, 5.0], [3.0, 3.5, 5.0, 5.5])
    >>> i.tolist(), ok.tolist()
    ([1, 2, 3, 3], [True, True, True, False])
    """
    arms = np.asarray(working_arms_mm, float)
    wa = np.asarray(working_arm_mm, float)
    return np.minimum(np.searchsorted(arms, wa - 1e-9), len(arms) - 1), wa <= arms[-1] + 1e-9


def standard_pivot_class(bearing: str, working_arm_mm: float) -> tuple[float, float]:
    """Table 2: ``(pivot class diameter, max loading arm)`` [mm] for a bearing and working arm.

    A working arm between two columns takes the column with the next larger
    arm (the smaller, conservative pivot class). A working arm beyond the
    table for that bearing is an input error naming the accepted range.
    """
    df = catalog.load("pivot_classes")
    df = df[df["bearing"].astype(str) == str(bearing)].sort_values("working_arm_mm")
    arms = df["working_arm_mm"].astype(float).to_numpy()
    if df.empty or not table2_column(arms, working_arm_mm)[1]:
        raise InputError(Problem("working_arm_mm", working_arm_mm,
                                 f"at most {arms[-1]:g} mm with bearing {bearing} (thesis Table 2)" if len(arms)
                                 else f"a bearing listed in catalogs/pivot_classes.csv (got {bearing})"))
    row = df.iloc[int(table2_column(arms, working_arm_mm)[0])]
    return float(row["pivot_class_diameter_mm"]), float(row["max_loading_arm_mm"])


def pivot_diameter_mm(pivot_class_diameter_mm, bushing_radial_thickness_mm):
    """Pivot diameter from its class and the bushing thickness.

    ``d_p = class + 2 (t_ref - t)`` with ``t_ref`` = 1 mm (constant
    ``pivot_reference_bushing_thickness_mm``): the bore in the arm stays that
    of the class whatever the supplier.

    >>> pivot_diameter_mm([16.0, 20.0], [1.0, 0.5]).tolist()
    [16.0, 21.0]
    """
    t_ref = constant("pivot_reference_bushing_thickness_mm")
    return np.asarray(pivot_class_diameter_mm, float) + 2.0 * (t_ref - np.asarray(bushing_radial_thickness_mm, float))


def bolt_hole_diameter_mm(bolt_nominal_diameter_mm):
    """Pivot bolt hole = bolt nominal diameter + clearance (0.2 mm, thesis step 2).

    >>> bolt_hole_diameter_mm([8.0, 10.0]).tolist()
    [8.2, 10.2]
    """
    return np.asarray(bolt_nominal_diameter_mm, float) + constant("bolt_hole_clearance_mm")


def arm_wall_mm(bearing_inner_diameter_mm, working_arm_mm, pivot_class_diameter_mm):
    """Thinnest arm wall, on the side of the eccentricity: ``d_b/2 - e_w - class/2``.

    The pivot class diameter is the bore envelope of the arm (see
    docs/model.md: this reading makes Table 2 and both case studies
    consistent with the 1 mm minimum; adding the bushing on top would make
    Table 2's own entries fail).

    >>> float(arm_wall_mm(30.0, 5.0, 16.0))
    2.0
    """
    return (np.asarray(bearing_inner_diameter_mm, float) - np.asarray(pivot_class_diameter_mm, float)) / 2.0 \
        - np.asarray(working_arm_mm, float)


def max_pivot_class_for_wall_mm(bearing_inner_diameter_mm, working_arm_mm):
    """Largest pivot class that keeps the minimum arm wall: ``d_b - 2 (e_w + wall_min)``.

    >>> float(max_pivot_class_for_wall_mm(30.0, 4.0))
    20.0
    """
    return np.asarray(bearing_inner_diameter_mm, float) - 2.0 * (np.asarray(working_arm_mm, float)
                                                                  + constant("arm_min_wall_mm"))


def pivot_wall_mm(pivot_diameter_mm_, loading_arm_mm, bolt_hole_diameter_mm_):
    """Thinnest pivot-tube wall around the (eccentric) bolt hole: ``d_p/2 - e_l - d_h/2``.

    >>> round(float(pivot_wall_mm(16.0, 2.5, 8.2)), 2)
    1.4
    """
    return np.asarray(pivot_diameter_mm_, float) / 2.0 - np.asarray(loading_arm_mm, float) \
        - np.asarray(bolt_hole_diameter_mm_, float) / 2.0


def pivot_wall_values(pivot_diameter_mm, loading_arm_mm, bolt_d_mm) -> dict:
    """The physics of constraint ``pivot_wall`` (step 2, judged with the bolt, group ``bolt``): the bolt hole
    ``d_h = d + 0.2 mm``, the pivot wall around it ``d_p/2 - e_l - d_h/2`` [mm] and its limit, the minimum wall
    (``pivot_min_wall_mm``, 1 mm: ``catalogs/constants_execution.csv``). Parameters are value keys of the
    group (the core's pivot diameter and loading arm, the bolt option's nominal diameter), arrays broadcast;
    valid for any pivot, arm and bolt size (a negative wall: the hole breaks out of the pivot).

    By hand: a 16 mm pivot, a 2.5 mm loading arm and an M8 bolt (8.2 mm hole, thesis step 2): 8 - 2.5 - 4.1 = 1.4 mm.

    >>> v = pivot_wall_values(16.0, 2.5, 8.0)
    >>> round(float(v["pivot_bolt_hole_diameter_mm"]), 2), round(float(v["pivot_wall_mm"]), 2), float(v["pivot_min_wall_mm"])
    (8.2, 1.4, 1.0)
    """
    hole = bolt_hole_diameter_mm(bolt_d_mm)
    wall = pivot_wall_mm(pivot_diameter_mm, loading_arm_mm, hole)
    shape = np.shape(wall)
    return {"pivot_bolt_hole_diameter_mm": np.broadcast_to(np.asarray(hole, dtype=float), shape),
            "pivot_wall_mm": np.asarray(wall, dtype=float),
            "pivot_min_wall_mm": np.full(shape, constant("pivot_min_wall_mm"))}
