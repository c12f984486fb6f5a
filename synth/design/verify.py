"""Verify one given design of one application through the one evaluator.

:func:`evaluate_design` evaluates every group for the design's parts (any
part: pivot class, bushing length, cone variant and mean diameter need not lie
on the optimiser's grids) and :func:`verify` wraps it in a
:class:`~synth.design.result.Result`. The flowchart's fixed-parts mode, every
solver's answer and the bulk engine's chosen designs are verified here.

>>> from synth.data import case_path
>>> from synth.io.documents import load_input
>>> r = verify(load_input(case_path("case3")), {"ball_bearing": "6006", "pivot_class_diameter_mm": 19.0,
...     "pivot_bushing_supplier": "B", "damper_pad_class": "none", "pivot_bushing_length_mm": 20.0,
...     "endcap_spacer_class": "none", "cone_spring_aspect_ratio": 0.0, "cone_spring_deflection_ratio": 0.0,
...     "cone_spring_external_diameter_mm": 0.0, "main_spring_material": "VDSiCr", "main_spring_wire": "R2.30",
...     "main_spring_mean_body_diameter_mm": 44.0, "bolt_format": "M8x1.25", "bolt_property_class": "8.8"})
>>> round(r.values["pivot_diameter_mm"], 1), r.check("bearing_load").verdict
(20.0, 'pass')
"""

from __future__ import annotations

import dataclasses

import numpy as np

from synth.design import evaluate
from synth.design.applications import Applications
from synth.design.result import Result, checks_of, plain
from synth.design.space import NONE, PART_KEYS, space
from synth.design.space import SUBSYSTEMS
from synth.design.rules import echo
from synth.design.settings import DEFAULT
from synth.schema import plausibility

__all__ = ["evaluate_design", "verify", "values_of", "inputs_of", "wire_size_mm"]



def evaluate_design(apps: Applications, attrs: dict, settings: evaluate.Settings = DEFAULT, *, detail: bool = True,
                    time_points: int = 0, of=None, engine: str | None = None) -> dict:
    """Every group of N designs (``attrs``: N-row attribute dicts per table), design ``i`` for application ``i``
    of ``apps`` (one design: application 0), or for application ``of[i]`` when ``of`` is given. The one sequence
    of the evaluator's groups for given designs: the flowchart, :func:`verify`, the optimiser's winner, the
    platform's assignments and the bulk engine's verification call it.

    A given design is judged, never screened: at fidelity ``screening`` every group is evaluated at full fidelity
    (:attr:`~synth.design.evaluate.Settings.judge`); only ``screening-only`` evaluates the screening model.

    ``engine``: the axial group's physics engine (:func:`synth.design.evaluate.axial`; None: the numpy reference),
    chosen by a caller that evaluates many rows with :func:`synth.kernels.engines.axial` (the production samples of
    :mod:`synth.robust.sampling`)."""
    settings = settings.judge
    n = len(next(iter(attrs["core"].values())))
    a = np.arange(n, dtype=np.int64) if of is None else np.asarray(of, dtype=np.int64)
    one = np.arange(n, dtype=np.int64)  # design i is row i of the core group
    groups = {"input": evaluate.inputs(apps, a, settings)}
    cg = evaluate.core(apps, a, attrs["core"], settings, detail=detail)
    groups["core"] = cg
    groups["bushing"] = evaluate.bushing(apps, cg, one, attrs["bushing"], settings)
    groups["axial"] = evaluate.axial(apps, cg, one, attrs["axial"], settings, time_points=time_points,
                                     engine=engine)
    groups["spring"] = evaluate.spring(apps, evaluate.spring_keys(cg, one), one, attrs["spring"], settings)
    groups["bolt"] = evaluate.bolt(apps, cg, one, attrs["bolt"], settings)
    return groups


def wire_size_mm(round_wire: bool, b_mm: float, h_mm: float) -> list:
    """The input schema's wire size: ``[d]`` for a round wire, ``[b, h]`` for a rectangular one."""
    return [float(h_mm)] if round_wire else [float(b_mm), float(h_mm)]


def values_of(groups: dict, attrs: dict) -> dict:
    """The derived values of one design: every group's values (row 0) and the chosen parts' dimensions."""
    out: dict = {}
    for g in groups.values():
        for k, v in g.values.items():
            if k.startswith("_") or k == "app" or k in out:
                continue
            arr = np.asarray(v)
            out[k] = plain(arr[0]) if arr.ndim else plain(arr)
    for k in ("layout_standard", "layout_reverse", "axial_group_present", "axial_damping_present", "has_loading_arm",
              "cone_spring_sized", "bushing_rated", "axial_group_mismatch"):
        if k in out and out[k] is not None:
            out[k] = bool(out[k])
    out["architecture"] = "rotary_standard" if out.get("layout_standard") else "rotary_reverse"
    sp = attrs["spring"]
    rnd = bool(sp["round_wire"][0])
    out["main_spring_wire_section"] = "round" if rnd else "rectangular"
    out["main_spring_wire_size_mm"] = wire_size_mm(rnd, sp["b_mm"][0], sp["h_mm"][0])
    out["main_spring_working_condition"] = "winding"
    ax = attrs["axial"]
    if bool(ax["axial_group_present"][0]):
        for k in ("endcap_spacer_contact_area_mm2", "endcap_spacer_mean_radius_mm", "endcap_spacer_axial_height_mm"):
            out[k] = plain(ax[k][0])
    for k in ("damper_pad_contact_area_mm2", "damper_pad_mean_radius_mm", "damper_pad_outer_diameter_mm",
              "damper_pad_axial_height_mm"):
        if not out.get("axial_group_present"):
            out.pop(k, None)
    if not out.get("axial_group_present"):  # no cone spring: none of its dimensions or limits describes the design
        for k in out:
            if k.startswith("cone_spring_") and k != "cone_spring_sized":
                out[k] = None
    out["bolt_d_mm"] = plain(attrs["bolt"]["bolt_d_mm"][0])
    if not out.get("axial_damping_present"):
        out["axial_damping_nm"] = None
    return out


def inputs_of(d) -> dict | None:
    """The design input as a dict of plain values (``None`` if it is not a dataclass)."""
    if not dataclasses.is_dataclass(d):
        return None
    return {k: plain(v) for k, v in dataclasses.asdict(d).items()}


def parts_of_rows(attrs: dict, core_values: dict) -> list:
    """The part keys of N designs (one dict each) from their N-row attributes and their core group's values
    (the cone spring's diameters made absolute: De = De_max - reduction, Di = Di_min + increase; 0 without one)."""
    n = len(np.asarray(attrs["core"]["pivot_bushing_supplier"]))
    de_max = np.broadcast_to(np.asarray(core_values["cone_spring_max_external_diameter_mm"], dtype=float), (n,))
    di_min = np.broadcast_to(np.asarray(core_values.get("cone_spring_min_internal_diameter_mm", np.nan),
                                        dtype=float), (n,))
    cols = {}
    for table in ("core", "bushing", "axial", "spring", "bolt"):
        for k, v in attrs[table].items():
            if k in PART_KEYS:
                cols[k] = np.asarray(v)
    spacer = cols.get("endcap_spacer_class", np.full(n, NONE, dtype=object))
    red = np.asarray(attrs["axial"]["cone_spring_de_reduction_mm"], dtype=float)
    inc = np.asarray(attrs["axial"]["cone_spring_di_increase_mm"], dtype=float)
    out = []
    for j in range(n):
        part = {k: plain(v[j]) for k, v in cols.items()}
        if spacer[j] != NONE and np.isfinite(de_max[j]):
            part["cone_spring_external_diameter_mm"] = plain(de_max[j] - red[j])
            part["cone_spring_internal_diameter_mm"] = plain(di_min[j] + inc[j])
        else:
            part["cone_spring_external_diameter_mm"] = 0.0
            part["cone_spring_internal_diameter_mm"] = 0.0
        part["pivot_bushing_supplier"] = plain(np.asarray(attrs["core"]["pivot_bushing_supplier"])[j])
        out.append({k: part.get(k) for k in PART_KEYS})
    return out


def parts_of_design(sp, core: int, options: dict, core_values: dict, row: int) -> dict:
    """The part keys of one design: core ``core`` and option rows ``options`` of space ``sp``, its core group's
    values at row ``row`` of ``core_values`` (the evaluated core rows of an optimiser)."""
    attrs = {"core": sp.rows("core", [core])}
    attrs.update({s: sp.rows(s, [options[s]]) for s in SUBSYSTEMS})
    cone = {k: np.asarray(v)[[row]] for k, v in core_values.items() if k.startswith("cone_spring_")}
    return parts_of_rows(attrs, cone)[0]


def parts_of_attributes(attrs: dict, groups: dict) -> dict:
    """The part keys of a design from its one-row attributes (see :func:`parts_of_rows`)."""
    return parts_of_rows(attrs, groups["core"].values)[0]


def verify(d, parts: dict, settings: evaluate.Settings = DEFAULT, *, status: str = "verified", solver: str = "",
           detail: bool = True, time_points: int = 0, notes: list | None = None) -> Result:
    """The :class:`~synth.design.result.Result` of design ``parts`` (the keys of PART_KEYS) for input ``d``."""
    apps = Applications.of([d])
    attrs = space().design_attributes(parts)
    groups = evaluate_design(apps, attrs, settings, detail=detail, time_points=time_points)
    values = values_of(groups, attrs)
    notes = [n for n in plausibility(d) if n not in (notes or [])] + list(notes or [])
    res = Result(status=status, solver=solver, parts=parts_of_attributes(attrs, groups),
                 values=values, checks=checks_of(groups, apps), notes=list(notes or []) + settings.notes(),
                 inputs=inputs_of(d), settings=settings.as_dict(), rules=echo(settings.rules))
    if time_points and "_history" in groups["axial"].values:
        res.curves["plastic_wear"] = {k: np.asarray(v).reshape(-1).tolist()
                                      for k, v in groups["axial"].values["_history"].items()}
    return res
