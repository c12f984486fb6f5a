"""One adapter from a synthesis result to the plain dimensions the CAD model needs.

:func:`geometry_from` accepts a :class:`synth.design.result.Result` (of any
scene) or its JSON (``--json`` of ``synth flowchart`` or ``synth design``),
and returns a frozen
:class:`TensionerGeometry` of plain floats and strings, units in the names.
Every dimension is *read* from the result (or from the catalog row the result
names, or from the step-7 stack constants the physics itself reads); nothing
of the physics is recomputed here.

The only derived quantities are geometric identities of an annulus:
the bore of a damper pad from its outer diameter and mean radius
(``d_i = 4 R_m - D_o``), and both diameters of an endcap spacer from its mean
radius and contact area (``D_o - d_i = 2 A / (2 pi R_m)``), because the thesis
Tables 3-4 give those two numbers and not the diameters.

>>> g = geometry_from(_example_values(), inputs=_example_inputs())
>>> g.layout, g.pulley_type, g.axial_damping, g.wire_section
('standard', 'toothed', True, 'rectangular')
>>> round(g.damper_pad_inner_diameter_mm, 2), round(g.cone_spring_installed_height_mm, 3)
(18.5, 0.965)
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass
from pathlib import Path

from synth import catalog
from synth.errors import InputError, Problem
from synth.design.result import Result
from synth.io.saved_results import load_result
from synth.io.documents import load_input

__all__ = ["TensionerGeometry", "geometry_from"]


@dataclass(frozen=True)
class TensionerGeometry:
    """Everything the parametric assembly reads (mm, counts, names).

    ``layout`` is ``standard`` (eq. 17: pulley above the spring housing) or
    ``reverse`` (eq. 18: pulley below it). ``status`` is the result's status
    (optimal, baseline...), ``verdict`` its verdict (pass, incomplete, fail); an infeasible nearest design is
    still exported.
    """

    name: str
    status: str
    feasible: bool
    layout: str
    pulley_type: str
    axial_damping: bool
    wire_section: str
    eccentric: str
    # inputs (application)
    belt_plane_height_mm: float
    max_pivot_height_mm: float
    max_axial_displacement_mm: float | None
    pulley_diameter_mm: float
    working_arm_mm: float
    # result
    pulley_width_mm: float
    loading_arm_mm: float
    bearing_designation: str
    bearing_inner_diameter_mm: float
    bearing_outer_diameter_mm: float
    bearing_width_mm: float
    bearing_ball_count: int
    bearing_ball_diameter_mm: float
    pivot_diameter_mm: float
    pivot_bushing_radial_thickness_mm: float
    pivot_bushing_length_mm: float
    spring_housing_height_mm: float
    spring_housing_outer_diameter_mm: float
    spring_support_inner_diameter_mm: float
    spring_wire_axial_mm: float
    spring_wire_radial_mm: float
    spring_mean_diameter_mm: float
    spring_active_coils: float
    bolt_format: str
    bolt_diameter_mm: float
    bolt_hole_diameter_mm: float
    bolt_head_diameter_mm: float
    damper_pad_outer_diameter_mm: float = 0.0
    damper_pad_inner_diameter_mm: float = 0.0
    damper_pad_axial_height_mm: float = 0.0
    endcap_spacer_outer_diameter_mm: float = 0.0
    endcap_spacer_inner_diameter_mm: float = 0.0
    endcap_spacer_axial_height_mm: float = 0.0
    cone_spring_outer_diameter_mm: float = 0.0
    cone_spring_inner_diameter_mm: float = 0.0
    cone_spring_thickness_mm: float = 0.0
    cone_spring_installed_height_mm: float = 0.0
    # step-7 stack constants (catalogs/constants_packaging.csv, read as the physics reads them)
    crankcase_gap_mm: float = 0.5
    support_plate_thickness_mm: float = 2.0
    spring_bushing_axial_thickness_mm: float = 0.7
    arm_bearing_support_thickness_mm: float = 1.5
    endcap_height_mm: float = 1.2
    calking_height_mm: float = 1.0
    pivot_base_height_mm: float = 3.0
    verdict: str = ""                # the result's verdict (pass, incomplete, fail): the STEP header

    def replace(self, **changes) -> "TensionerGeometry":
        """A copy with some fields changed (for what-if and test geometries)."""
        return dataclasses.replace(self, **changes)

    def as_dict(self) -> dict:
        return dataclasses.asdict(self)


_STACK = {"crankcase_gap_mm": "crankcase_support_plate_gap_mm", "support_plate_thickness_mm": "support_plate_thickness_mm",
          "spring_bushing_axial_thickness_mm": "spring_bushing_axial_thickness_mm",
          "arm_bearing_support_thickness_mm": "arm_bearing_support_thickness_mm",
          "endcap_height_mm": "endcap_height_mm", "calking_height_mm": "calking_height_mm",
          "pivot_base_height_mm": "pivot_base_height_mm"}

_INPUT_KEYS = ("middle_plane_belt_height_mm", "max_pivot_height_mm", "pulley_diameter_mm", "working_arm_mm",
               "belt_loading_type", "pulley_shell_type")


def _split(result) -> tuple[dict, dict | None, str, bool, str, str]:
    """``(parts and values, inputs, status, feasible, name, verdict)`` of a result, its JSON dict or its JSON
    path."""
    if isinstance(result, (str, Path)):
        result = load_result(result)  # the input gate's reader: size, encoding, shape
    if isinstance(result, dict):
        result = Result.from_dict(result)
    if not isinstance(result, Result):
        raise InputError(Problem("result", type(result).__name__, "a synth result or the JSON of --json"))
    values = {**result.values, **result.parts}
    return (values, result.inputs, result.status, result.feasible, f"{result.solver or 'design'}-{result.status}",
            result.verdict)


def _inputs_dict(inputs) -> dict | None:
    if inputs is None:
        return None
    if isinstance(inputs, (str, Path)):
        inputs = load_input(inputs)
    if dataclasses.is_dataclass(inputs):
        return dataclasses.asdict(inputs)
    return dict(inputs)


def _num(values: dict, key: str, missing: list, default=None) -> float:
    v = values.get(key, default)
    if v is None or (isinstance(v, float) and not math.isfinite(v)):
        if default is None:
            missing.append(key)
            return float("nan")
        v = default
    return float(v)


def geometry_from(result, inputs=None, *, name: str | None = None) -> TensionerGeometry:
    """The :class:`TensionerGeometry` of a result (object, JSON dict or JSON path).

    ``inputs`` (a DesignInput, a dict of its fields, or an input file) is needed
    only when the result does not carry its inputs (the flowchart JSON).
    A missing dimension raises :class:`~synth.errors.InputError` naming it.
    """
    values, ins, status, feasible, label, verdict = _split(result)
    ins = _inputs_dict(inputs) or _inputs_dict(ins)
    if ins is None:
        where = f" ({Path(result).name})" if isinstance(result, (str, Path)) else ""
        raise InputError(Problem(f"inputs{where}", None, "the design input (pass --input INPUT.yaml: this result "
                                                         "does not carry it)"))
    missing: list = [k for k in _INPUT_KEYS if ins.get(k) is None]
    if missing:
        raise InputError([Problem(f"inputs.{k}", None, "a value (needed by the CAD model)") for k in missing])
    v = values
    miss: list = []
    # the parts the design has: its axial group (damper pad, endcap spacer, cone spring) when present, whatever the
    # damping split asks for (a nearest design may lack the group the split needs: that check fails, the model
    # still draws what the design is; a 20 mm working arm's result was refused for lacking the pad's dimensions)
    present = v.get("axial_group_present")
    axial = bool(present) if present is not None else bool(v.get("axial_damping_present"))
    section = str(v.get("main_spring_wire_section") or "")
    size = v.get("main_spring_wire_size_mm")
    if isinstance(size, (int, float)):
        size = [float(size)]
    if section not in ("round", "rectangular") or not size:
        miss.append("main_spring_wire_section/main_spring_wire_size_mm")
        size = [float("nan")]
    # wire b (axial) x h (radial), as the coil-gap check of eq. (89)-(93) reads b
    b_ax = float(size[0])
    h_rad = float(size[1]) if section == "rectangular" and len(size) > 1 else b_ax
    bearing = str(v.get("ball_bearing") or "")
    try:
        brow = catalog.row("ball_bearings", bearing, "ball_bearing")
        balls, ball_d = int(brow["ball_count"]), float(brow["ball_diameter_mm"])
    except InputError:
        miss.append("ball_bearing")
        balls, ball_d = 0, float("nan")
    bolt = str(v.get("bolt_format") or "")
    try:
        bolt_row = catalog.row("bolts", bolt, "bolt_format")
        bolt_d, head_cat = float(bolt_row["d_mm"]), float(catalog.row("bolt_heads", f"{bolt} hex")["dw_min_mm"])
    except InputError:
        miss.append("bolt_format")
        bolt_d, head_cat = float("nan"), float("nan")
    head = ins.get("bolt_head_contact_external_diameter_mm") or head_cat
    inner_key = "spring_support_inner_diameter_mm" if v.get("spring_support_inner_diameter_mm") is not None \
        else "spring_housing_inner_diameter_mm"
    arch = str(v.get("architecture") or "")
    if arch not in ("rotary_standard", "rotary_reverse"):
        miss.append("architecture")
    kw = dict(
        name=name or label, status=status, feasible=bool(feasible), verdict=verdict,
        layout="reverse" if arch == "rotary_reverse" else "standard",
        pulley_type=str(v.get("pulley_type") or ins.get("pulley_shell_type")),
        axial_damping=axial, wire_section=section, eccentric=str(ins["belt_loading_type"]),
        belt_plane_height_mm=float(ins["middle_plane_belt_height_mm"]),
        max_pivot_height_mm=float(ins["max_pivot_height_mm"]),
        max_axial_displacement_mm=None if ins.get("max_axial_displacement_mm") is None
        else float(ins["max_axial_displacement_mm"]),
        pulley_diameter_mm=float(ins["pulley_diameter_mm"]), working_arm_mm=float(ins["working_arm_mm"]),
        pulley_width_mm=_num(v, "pulley_width_mm", miss),
        loading_arm_mm=_num(v, "loading_arm_mm", miss, default=0.0),
        bearing_designation=bearing,
        bearing_inner_diameter_mm=_num(v, "bearing_inner_diameter_mm", miss),
        bearing_outer_diameter_mm=_num(v, "bearing_outer_diameter_mm", miss),
        bearing_width_mm=_num(v, "bearing_width_mm", miss),
        bearing_ball_count=balls, bearing_ball_diameter_mm=ball_d,
        pivot_diameter_mm=_num(v, "pivot_diameter_mm", miss),
        pivot_bushing_radial_thickness_mm=_num(v, "pivot_bushing_radial_thickness_mm", miss),
        spring_housing_height_mm=_num(v, "spring_housing_height_mm", miss),
        spring_housing_outer_diameter_mm=_num(v, "spring_housing_outer_diameter_mm", miss),
        spring_support_inner_diameter_mm=_num(v, inner_key, miss),
        spring_wire_axial_mm=b_ax, spring_wire_radial_mm=h_rad,
        spring_mean_diameter_mm=_num(v, "main_spring_mean_body_diameter_mm", miss),
        spring_active_coils=_num(v, "main_spring_active_coils_free", miss),
        bolt_format=bolt, bolt_diameter_mm=bolt_d,
        bolt_hole_diameter_mm=_num(v, "pivot_bolt_hole_diameter_mm", miss),
        bolt_head_diameter_mm=float(head),
    )
    if kw["pulley_diameter_mm"] <= kw["bearing_outer_diameter_mm"]:  # registry check pulley_over_bearing fails
        raise InputError(Problem("inputs.pulley_diameter_mm", kw["pulley_diameter_mm"],
                                 f"a pulley larger than its bearing ({bearing}, D = {kw['bearing_outer_diameter_mm']:g} "
                                 "mm): a pulley inside its own bearing has no 3D model"))
    # bushing length: the catalog part when the flowchart names one, else the length searched by the optimiser;
    # with no durability test the result has none, and the bushing spans the bearing seat (arm plate + bearing)
    blen = v.get("pivot_bushing_length_mm")
    kw["pivot_bushing_length_mm"] = float(blen) if blen else kw["bearing_width_mm"] + catalog.constant(
        "arm_bearing_support_thickness_mm")
    if axial:
        do = _num(v, "damper_pad_outer_diameter_mm", miss)
        rm_dp = _num(v, "damper_pad_mean_radius_mm", miss)
        rm_es = _num(v, "endcap_spacer_mean_radius_mm", miss)
        area_es = _num(v, "endcap_spacer_contact_area_mm2", miss)
        width_es = area_es / (2.0 * math.pi * rm_es) if rm_es > 0 else float("nan")
        h_cs = _num(v, "cone_spring_cone_height_mm", miss)
        s_nom = _num(v, "cone_spring_nominal_deflection_mm", miss)
        t_cs = _num(v, "cone_spring_thickness_mm", miss)
        kw.update(damper_pad_outer_diameter_mm=do, damper_pad_inner_diameter_mm=4.0 * rm_dp - do,
                  damper_pad_axial_height_mm=_num(v, "damper_pad_axial_height_mm", miss),
                  endcap_spacer_outer_diameter_mm=2.0 * rm_es + width_es,
                  endcap_spacer_inner_diameter_mm=2.0 * rm_es - width_es,
                  endcap_spacer_axial_height_mm=_num(v, "endcap_spacer_axial_height_mm", miss),
                  cone_spring_outer_diameter_mm=_num(v, "cone_spring_external_diameter_mm", miss),
                  cone_spring_inner_diameter_mm=_num(v, "cone_spring_internal_diameter_mm", miss),
                  cone_spring_thickness_mm=t_cs, cone_spring_installed_height_mm=t_cs + max(h_cs - s_nom, 0.0))
    if miss:
        raise InputError([Problem(f"result.{k}", None, "a value in the result (needed by the CAD model)") for k in miss])
    kw.update({k: catalog.constant(c) for k, c in _STACK.items()})
    return TensionerGeometry(**kw)


def _example_values() -> dict:
    """A case-1-like result, as ``--json`` writes it (for the doctests)."""
    parts = {"ball_bearing": "6006", "pivot_class_diameter_mm": 16.0, "pivot_bushing_length_mm": 16.0,
             "main_spring_mean_body_diameter_mm": 41.0, "bolt_format": "M8x1.25"}
    values = {"architecture": "rotary_standard", "pulley_type": "toothed", "pulley_width_mm": 20.0,
              "loading_arm_mm": 2.5, "bearing_inner_diameter_mm": 30.0, "bearing_outer_diameter_mm": 55.0,
              "bearing_width_mm": 13.0, "pivot_diameter_mm": 16.0, "pivot_bushing_radial_thickness_mm": 1.0,
              "axial_damping_present": True, "damper_pad_outer_diameter_mm": 31.5,
              "damper_pad_mean_radius_mm": 12.5, "damper_pad_axial_height_mm": 3.5, "endcap_spacer_mean_radius_mm": 13.5,
              "endcap_spacer_contact_area_mm2": 490.0, "endcap_spacer_axial_height_mm": 1.5,
              "cone_spring_external_diameter_mm": 30.0, "cone_spring_internal_diameter_mm": 16.2,
              "cone_spring_thickness_mm": 0.7425, "cone_spring_cone_height_mm": 0.891,
              "cone_spring_nominal_deflection_mm": 0.6685, "spring_housing_height_mm": 14.8,
              "spring_housing_outer_diameter_mm": 45.0, "spring_housing_inner_diameter_mm": 22.0,
              "main_spring_wire_section": "rectangular", "main_spring_wire_size_mm": [2.3, 2.3],
              "main_spring_active_coils_free": 4.09, "pivot_bolt_hole_diameter_mm": 8.2}
    return {"kind": "synth.result", "status": "verified", "parts": parts, "values": values, "checks": []}


def _example_inputs() -> dict:
    return {"middle_plane_belt_height_mm": 29.5, "max_pivot_height_mm": 40.0, "max_axial_displacement_mm": 42.0,
            "pulley_diameter_mm": 66.0, "working_arm_mm": 5.0, "belt_loading_type": "double_eccentric",
            "pulley_shell_type": "toothed", "bolt_head_contact_external_diameter_mm": 11.0}
