"""Geometric verification of the exported model: the thesis's "visual check of the packaging" made automatic.

:func:`verify_model` measures the built solids (never the result values they
came from) and returns :class:`synth.checks.Check` records of step 11, so a
failed check is reported like any other failed constraint:

* ``interference <a>/<b>``: intersection volume of two parts (BRep boolean
  common; pairs whose bounding boxes do not overlap are skipped) must not
  exceed ``cad_interference_tolerance_mm3``; parts designed to touch share a
  face and have no volume in common;
* ``pivot top within max pivot height`` (eq. 50/53): pivot bounding box top
  <= ``max_pivot_height_mm``;
* ``assembly within max axial displacement`` (eq. 26): every part but the
  bolt <= ``max_axial_displacement_mm``;
* ``parts above the crankcase face`` (eq. 27): every part but the pivot and
  the bolt >= 0;
* ``pulley mid-plane on the belt plane``: |pulley mid-plane - belt plane|
  <= ``cad_dimension_tolerance_mm``;
* ``main spring within housing diameter`` (eq. 81-82, 54) and ``main spring
  within housing height`` (eq. 89-93, 52): the swept spring's extents against
  the housing cavity;
* ``spring-bushing collar height`` (step 6 stack): the room left between the
  housing floor and the cone spring / arm hub is not negative.

>>> from synth.cad.assembly import build
>>> from synth.cad.dimensions import geometry_from, _example_values, _example_inputs
>>> g = geometry_from(_example_values(), inputs=_example_inputs())     # case 1 with the thesis's 41 mm spring
>>> [c.verdict for c in verify_model(build(g), interference=False)][:2]
['pass', 'pass']
>>> c = verify_model(build(g.replace(spring_mean_diameter_mm=46.0)), interference=False)[4]
>>> c.name, c.verdict, round(c.value, 2)     # 46 + 2.3 mm wire in a 45 mm housing
('main spring within housing diameter', 'fail', 48.3)
"""

from __future__ import annotations

import itertools

from synth import catalog
from synth.cad.assembly import TensionerModel
from synth.cad.parts import stack
from synth.checks import FAIL, Check

__all__ = ["verify_model", "interference_volumes", "failed"]

STEP = 11


def _overlap(a, b, tol: float = 1e-6) -> bool:
    return not (a.xmax < b.xmin + tol or b.xmax < a.xmin + tol or a.ymax < b.ymin + tol or b.ymax < a.ymin + tol
                or a.zmax < b.zmin + tol or b.zmax < a.zmin + tol)


def interference_volumes(model: TensionerModel) -> dict:
    """``{(a, b): intersection volume mm3}`` for every pair of parts whose bounding boxes overlap."""
    boxes = {n: s.BoundingBox() for n, s in model.parts.items()}
    out = {}
    for a, b in itertools.combinations(model.parts, 2):
        if not _overlap(boxes[a], boxes[b]):
            continue
        common = model.parts[a].intersect(model.parts[b])
        out[(a, b)] = abs(float(common.Volume())) if common.Solids() else 0.0
    return out


def verify_model(model: TensionerModel, *, interference: bool = True) -> list[Check]:
    """All step-11 checks of ``model`` (see the module docstring)."""
    g, p = model.geometry, model.parts
    checks: list[Check] = []
    tol_v = catalog.constant("cad_interference_tolerance_mm3")
    tol = catalog.constant("cad_dimension_tolerance_mm")
    if interference:
        vols = interference_volumes(model)
        worst = max(vols.values(), default=0.0)
        checks.append(Check("no interference between parts", STEP, worst, tol_v, "<=", "mm3", "step 11 (Fig. 75-76)",
                            note=f"{len(vols)} overlapping bounding boxes of {len(p) * (len(p) - 1) // 2} pairs"))
        for (a, b), v in sorted(vols.items()):
            if v > tol_v:
                checks.append(Check(f"interference {a}/{b}", STEP, v, tol_v, "<=", "mm3", "step 11",
                                    correction=f"resize {a} or {b}: they share {v:.1f} mm3"))
    bb = {n: s.BoundingBox() for n, s in p.items()}
    checks.append(Check("pivot top within max pivot height", STEP, bb["pivot"].zmax, g.max_pivot_height_mm, "<=", "mm",
                        "eq. (50)" if g.layout == "standard" else "eq. (53)"))
    top = max(b.zmax for n, b in bb.items() if n != "fixation_bolt")
    checks.append(Check("assembly within max axial displacement", STEP, top, g.max_axial_displacement_mm, "<=", "mm",
                        "eq. (26)", note="fixation bolt head excluded"))
    low = min(b.zmin for n, b in bb.items() if n not in ("fixation_bolt", "pivot"))
    checks.append(Check("parts above the crankcase face", STEP, low, 0.0, ">=", "mm", "eq. (27)"))
    mid = 0.5 * (bb["pulley"].zmin + bb["pulley"].zmax)
    checks.append(Check("pulley mid-plane on the belt plane", STEP, abs(mid - g.belt_plane_height_mm), tol, "<=", "mm",
                        "eq. (50)-(53)", note=f"pulley mid-plane {mid:.3f} mm, belt plane {g.belt_plane_height_mm:.3f} mm"))
    sp = bb["main_spring"]
    d_out = max(sp.xlen, sp.ylen)
    checks.append(Check("main spring within housing diameter", STEP, d_out, g.spring_housing_outer_diameter_mm, "<=", "mm",
                        "eq. (54), (81)-(82)", correction="smaller mean body diameter or wire, or a larger housing"))
    checks.append(Check("main spring within housing height", STEP, sp.zlen, g.spring_housing_height_mm, "<=", "mm",
                        "eq. (52)-(53), (89)-(93)", correction="fewer coils or a thinner wire, or a taller housing"))
    s = stack(g)
    checks.append(Check("spring-bushing collar height", STEP, s.collar_top_u - s.flange_top_u, 0.0, ">=", "mm",
                        "step 6 stack", correction="a shorter pivot bushing or a taller spring housing"))
    return checks


def failed(checks: list[Check]) -> list[Check]:
    return [c for c in checks if c.verdict == FAIL]
