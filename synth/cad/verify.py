"""Geometric verification of the exported model: the thesis's "visual check of the packaging" made automatic.

:func:`verify_model` measures the built solids (never the result values they
came from) and returns the registry's step-11 checks (the ``cad`` group of
:mod:`synth.design.constraints`), so a failed geometric check is reported like
any other failed constraint:

* ``cad_interference``: the largest intersection volume of two parts (BRep
  boolean common; pairs whose bounding boxes do not overlap are skipped) must
  not exceed ``cad_interference_tolerance_mm3``; the note names the pairs;
* ``cad_pivot_height`` (eq. 50/53): pivot bounding box top <= ``max_pivot_height_mm``;
* ``cad_axial_space`` (eq. 26): every part but the bolt <= ``max_axial_displacement_mm``;
* ``cad_crankcase_face`` (eq. 27): every part but the pivot and the bolt >= 0;
* ``cad_belt_plane``: |pulley mid-plane - belt plane| <= ``cad_dimension_tolerance_mm``;
* ``cad_spring_diameter`` (eq. 81-82, 54) and ``cad_spring_height`` (eq. 89-93, 52):
  the swept spring's extents against the housing cavity;
* ``cad_collar`` (step 6 stack): the room between the housing floor and the
  cone spring / arm hub is not negative;
* ``cad_solids``: every part was built as a valid solid; a part the CAD kernel
  could not make (a sweep that fails, a wire wider than its coil: see
  :func:`synth.cad.assembly.build`) fails it, its note names the part and why,
  and a check measured on that part is not verified.

>>> from synth.cad.assembly import build
>>> from synth.cad.dimensions import geometry_from, _example_values, _example_inputs
>>> g = geometry_from(_example_values(), inputs=_example_inputs())     # case 1 with the thesis's 41 mm spring
>>> [c.verdict for c in verify_model(build(g), interference=False)][:3]
['not verified', 'pass', 'pass']
>>> c = [c for c in verify_model(build(g.replace(spring_mean_diameter_mm=46.0)), interference=False)
...      if c.id == "cad_spring_diameter"][0]
>>> c.verdict, round(c.value, 2)     # 46 + 2.3 mm wire in a 45 mm housing
('fail', 48.3)
"""

from __future__ import annotations

import itertools

from synth import catalog
from synth.cad.assembly import TensionerModel
from synth.cad.solids import stack
from synth.design.result import FAIL, NOT_VERIFIED, Check, checks_of
from synth.design.evaluate import finish

__all__ = ["verify_model", "interference_volumes", "failed"]


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


#: check -> the parts its value is measured on (None: every part but those named by :data:`_BUT`)
_MEASURED_ON = {"cad_pivot_height": ("pivot",), "cad_belt_plane": ("pulley",), "cad_spring_diameter": ("main_spring",),
                "cad_spring_height": ("main_spring",), "cad_axial_space": None, "cad_crankcase_face": None,
                "cad_interference": None}
_BUT = {"cad_axial_space": ("fixation_bolt",), "cad_crankcase_face": ("fixation_bolt", "pivot"),
        "cad_interference": ()}


def verify_model(model: TensionerModel, *, interference: bool = True, rules=None) -> list[Check]:
    """The step-11 checks of ``model`` (see the module docstring), as registry :class:`Check` records, under the
    design ``rules`` of the result it was built from (:class:`synth.design.rules.Rules` or their mapping)."""
    from synth.design.rules import Rules
    import numpy as np

    g, p = model.geometry, model.parts
    unbuilt = dict(getattr(model, "unbuilt", {}) or {})
    bb = {n: s.BoundingBox() for n, s in p.items()}
    nan = float("nan")

    def box(name: str, attr: str) -> float:
        return getattr(bb[name], attr) if name in bb else nan

    st = stack(g)
    v = {
        "cad_interference_mm3": np.nan, "cad_interference_tolerance_mm3": catalog.constant("cad_interference_tolerance_mm3"),
        "cad_pivot_top_mm": box("pivot", "zmax"), "max_pivot_height_mm": g.max_pivot_height_mm,
        "cad_assembly_top_mm": max((b.zmax for n, b in bb.items() if n != "fixation_bolt"), default=nan),
        "max_axial_displacement_mm": np.nan if g.max_axial_displacement_mm is None else g.max_axial_displacement_mm,
        "cad_lowest_part_mm": min((b.zmin for n, b in bb.items() if n not in ("fixation_bolt", "pivot")), default=nan),
        "cad_pulley_offset_mm": abs(0.5 * (box("pulley", "zmin") + box("pulley", "zmax")) - g.belt_plane_height_mm),
        "cad_dimension_tolerance_mm": catalog.constant("cad_dimension_tolerance_mm"),
        "cad_spring_diameter_mm": max(box("main_spring", "xlen"), box("main_spring", "ylen")),
        "spring_housing_outer_diameter_mm": g.spring_housing_outer_diameter_mm,
        "cad_spring_height_mm": box("main_spring", "zlen"), "spring_housing_height_mm": g.spring_housing_height_mm,
        "cad_collar_height_mm": st.collar_top_u - st.flange_top_u,
        "cad_unbuilt_parts": float(len(unbuilt)),
    }
    note = ""
    if interference:
        vols = interference_volumes(model)
        v["cad_interference_mm3"] = max(vols.values(), default=0.0)
        bad = [f"{a}/{b} {vol:.1f} mm3" for (a, b), vol in sorted(vols.items())
               if vol > v["cad_interference_tolerance_mm3"]]
        note = (f"{len(vols)} overlapping bounding boxes of {len(p) * (len(p) - 1) // 2} pairs"
                + (("; interfering: " + ", ".join(bad)) if bad else ""))
    group = finish("cad", {k: np.atleast_1d(np.asarray(x, dtype=float)) for k, x in v.items()}, None, np.zeros(1, int),
                   rules=Rules.from_mapping(rules or None))
    checks = [c for c in checks_of({"cad": group}, None) if c.verdict != "not applicable" or c.id != "cad_interference"]
    for c in checks:
        if c.id == "cad_interference":
            c.note = note if interference else "not verified: interference not computed (--no-interference)"
            if not interference:
                c.verdict, c.value, c.margin = "not verified", None, None
        if c.id == "cad_solids" and unbuilt:
            c.note = "not built: " + "; ".join(f"{n}: {why}" for n, why in unbuilt.items())
        elif c.id in _MEASURED_ON and unbuilt:
            on = _MEASURED_ON[c.id] or tuple(n for n in list(p) + list(unbuilt) if n not in _BUT[c.id])
            missing = [n for n in on if n in unbuilt]
            if missing:
                c.verdict, c.value, c.margin = NOT_VERIFIED, None, None
                c.note = f"not verified: {', '.join(missing)} not built (see cad_solids)"
    return checks


def failed(checks: list[Check]) -> list[Check]:
    return [c for c in checks if c.verdict == FAIL]
