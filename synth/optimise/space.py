"""The catalog design space of a tensioner and its decomposition.

A design is one choice per part family: ball bearing, pivot class, bushing
supplier and length, damper pad and endcap spacer classes, cone spring (sized
from the Table 7 design ranges for a chosen aspect ratio), main-spring
material, wire and mean body diameter, bolt format and property class.
Continuous quantities (damping split, active coils, cone-spring thickness and
force, bolt preload and tightening torque) follow in closed form from the
physics of :mod:`synth.model` and are derived, not searched.

Decomposition. The choices that set the damping split (bearing, pivot class,
bushing supplier, whose wall thickness sets the pivot diameter) and the
damper pad (it sets the spring-housing height and the cone-spring outer
diameter) form the **core**; every other family is a **subsystem** whose
constraints involve only the core and its own choice:

========== ====================================== ==========================================
subsystem  options                                 constraints (thesis step)
========== ====================================== ==========================================
bushing    supplier x catalog length               p, pv, pvt, wear, parallelism, length (4)
axial      endcap spacer x cone aspect ratio       Table 3/4 capacity, cone spring (8), plastic
                                                   wear and EOL damping (5), belt plane (7)
spring     material x wire x mean body diameter    yield, Goodman SF, contacts, coil gap (9)
bolt       format x property class                 bolt yield, under-head, thread, bore,
                                                   pivot base pressure (10), pivot wall (2)
========== ====================================== ==========================================

Given the core, subsystems share no constraint, so the optimum of an additive
objective (cost, standardisation) is the core's own value plus the best
option of each subsystem, and the max-min margin combines by the minimum.

>>> from synth.optimise.space import build_space
>>> from synth.schema import load_input
>>> from synth.data import case_path
>>> sp = build_space(load_input(case_path("case1")))
>>> sp.n_cores > 0, sorted(sp.subsystems)
(True, ['axial', 'bolt', 'bushing', 'spring'])
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import pandas as pd

from synth import catalog
from synth.errors import InputError, Problem
from synth.friction import mu as friction_mu
from synth.model import layout as s0, ball_bearing as s1, pivot as s2, damping as s3
from synth.model import plain_bushing as s4, torsion_spring as s9, bolted_joint as s10
from synth.optimise.objectives import spring_cost_eur

__all__ = ["DesignSpace", "build_space", "SUBSYSTEMS", "durability_of"]

SUBSYSTEMS = ("bushing", "axial", "spring", "bolt")
NONE = "none"


def _b(x) -> bool:
    return str(x).strip().lower() in ("true", "1", "yes")


@dataclass
class DesignSpace:
    """The choices of one application, as a core table and one option table per subsystem.

    ``fixed`` holds the scalars that follow from the input alone (hubload,
    durability test, layout, pulley width...). ``cores`` and each
    ``subsystems[name]`` are DataFrames, one row per choice, with the part
    keys, their catalog attributes, ``cost_eur`` and ``nonstandard`` (weighted
    count of non-standard parts). ``notes`` lists what is not evaluated and why.
    """

    inputs: object
    fidelity: str
    friction_circle: bool
    fixed: dict
    cores: pd.DataFrame
    subsystems: dict
    notes: list = field(default_factory=list)

    @property
    def n_cores(self) -> int:
        return len(self.cores)

    def size(self) -> int:
        """Number of whole-tensioner candidates (the catalog product, before availability)."""
        n = self.n_cores
        for t in self.subsystems.values():
            n *= max(len(t), 1)
        return int(n)

    def restrict(self, parts: dict) -> "DesignSpace":
        """A copy holding only the rows matching ``parts`` (keys as in :func:`parts_columns`)."""
        cores = self.cores
        for col in ("bearing", "pivot_class_mm", "supplier", "damper_pad"):
            if col in parts and parts[col] is not None:
                cores = cores[cores[col].astype(str) == str(parts[col])]
        subs = {}
        for name, t in self.subsystems.items():
            for col in t.columns:
                if col in PART_COLUMNS[name] and col in parts and parts[col] is not None:
                    t = t[t[col].astype(str) == str(parts[col])]
            subs[name] = t.reset_index(drop=True)
        return DesignSpace(self.inputs, self.fidelity, self.friction_circle, self.fixed,
                           cores.reset_index(drop=True), subs, list(self.notes))


#: the columns naming the chosen part of each table (what a result reports)
PART_COLUMNS = {
    "core": ("bearing", "pivot_class_mm", "supplier", "damper_pad"),
    "bushing": ("supplier", "bushing_length_mm"),
    "axial": ("endcap_spacer", "cone_aspect_ratio"),
    "spring": ("spring_material", "spring_wire", "spring_mbd_mm"),
    "bolt": ("bolt_format", "bolt_property_class"),
}


def _w(name: str) -> float:
    return catalog.constant(f"nonstandard_weight_{name}")


def durability_of(d):
    """``(theta_pp_deg, frequency_hz, duration_h)`` of the durability test, or None when not given."""
    if d.durability_test == "assumed":
        if d.engine_type is None:
            return None
        row = catalog.row("durability_tests", d.engine_type, field="engine_type")
        return float(row["theta_peak_to_peak_deg"]), float(row["frequency_hz"]), float(row["duration_h"])
    vals = (d.durability_theta_peak_to_peak_deg, d.durability_frequency_hz, d.durability_duration_h)
    return None if any(v is None for v in vals) else tuple(float(v) for v in vals)


def _pivot_classes(d) -> np.ndarray:
    lo, hi, step = (catalog.constant(f"optimise_pivot_class_{k}") for k in ("min_mm", "max_mm", "step_mm"))
    classes = set(np.round(np.arange(lo, hi + step / 2, step), 6).tolist())
    classes |= set(catalog.load("pivot_classes")["pivot_class_diameter_mm"].astype(float))
    if d.pivot_class_diameter_mm is not None:
        classes.add(float(d.pivot_class_diameter_mm))
    return np.array(sorted(classes))


def _core_table(d, pin: bool, notes: list) -> pd.DataFrame:
    bearings = catalog.load("ball_bearings")
    rows = []
    for _, b in bearings.iterrows():
        key = str(b["designation"])
        try:
            std_class, max_la = s2.standard_pivot_class(key, d.working_arm_mm)
        except InputError:
            notes.append(f"bearing {key}: working arm {d.working_arm_mm:g} mm beyond its Table 2 columns; not a choice")
            continue
        lim = s1.max_hubload_n(key, d.engine_fuel)
        rows.append({"bearing": key, "bearing_d_mm": float(b["d_mm"]), "bearing_D_mm": float(b["D_mm"]),
                     "bearing_B_mm": float(b["B_mm"]), "bearing_cost_eur": float(b["unit_cost_eur"]),
                     "bearing_standard": _b(b["standard"]),
                     "bearing_max_hubload_n": np.inf if lim is None else lim,
                     "table2_class_mm": std_class, "table2_max_loading_arm_mm": max_la})
    if not rows:
        raise InputError(Problem("working_arm_mm", d.working_arm_mm, "a working arm within thesis Table 2 for some bearing"))
    bear = pd.DataFrame(rows)
    classes = pd.DataFrame({"pivot_class_mm": _pivot_classes(d)})
    sup = catalog.load("pivot_bushings")
    sup = pd.DataFrame({"supplier": sup["supplier"].astype(str), "bushing_thickness_mm": sup["radial_thickness_mm"].astype(float),
                        "supplier_standard": sup["standard"].map(_b)})
    if pin and d.pivot_bushing_radial_thickness_mm is not None:
        sup = sup[np.isclose(sup["bushing_thickness_mm"], float(d.pivot_bushing_radial_thickness_mm))]
    if pin and d.pivot_class_diameter_mm is not None:
        classes = classes[np.isclose(classes["pivot_class_mm"], float(d.pivot_class_diameter_mm))]
    dp = catalog.load("damper_pads")
    dp = pd.DataFrame({"damper_pad": dp["class"].astype(str), "dp_max_axial_damping_nm": dp["max_axial_damping_nm"].astype(float),
                       "dp_contact_area_mm2": dp["contact_area_mm2"].astype(float), "dp_mean_radius_mm": dp["mean_radius_mm"].astype(float),
                       "dp_outer_diameter_mm": dp["outer_diameter_mm"].astype(float), "dp_height_mm": dp["axial_height_mm"].astype(float),
                       "dp_cost_eur": dp["unit_cost_eur"].astype(float), "dp_standard": dp["standard"].map(_b)})
    none = pd.DataFrame([{"damper_pad": NONE, "dp_max_axial_damping_nm": 0.0, "dp_contact_area_mm2": 0.0,
                          "dp_mean_radius_mm": 0.0, "dp_outer_diameter_mm": 0.0, "dp_height_mm": 0.0,
                          "dp_cost_eur": 0.0, "dp_standard": True}])
    dp = pd.concat([none, dp], ignore_index=True) if d.damping_typology != "only_radial" else none
    t = bear.merge(classes, how="cross").merge(sup, how="cross").merge(dp, how="cross")
    t["pivot_diameter_mm"] = s2.pivot_diameter_mm(t["pivot_class_mm"].to_numpy(), t["bushing_thickness_mm"].to_numpy())
    t["pivot_class_standard"] = np.isclose(t["pivot_class_mm"], t["table2_class_mm"])
    t["cost_eur"] = t["bearing_cost_eur"] + t["dp_cost_eur"]
    t["nonstandard"] = (_w("bearing") * ~t["bearing_standard"] + _w("pivot_class") * ~t["pivot_class_standard"]
                        + _w("bushing") * ~t["supplier_standard"] + _w("damper_pad") * ~t["dp_standard"]).astype(float)
    return t.reset_index(drop=True)


def _bushing_table(d, pin: bool) -> pd.DataFrame:
    df = catalog.load("pivot_bushings")
    rows = []
    for _, r in df.iterrows():
        for length in s4.available_lengths_mm(str(r["supplier"])):
            rows.append({"supplier": str(r["supplier"]), "bushing_length_mm": float(length),
                         "cost_eur": float(r["unit_cost_eur"]) + float(r["cost_eur_per_mm"]) * float(length),
                         "nonstandard": 0.0})
    return pd.DataFrame(rows)


def _axial_table(d) -> pd.DataFrame:
    es = catalog.load("endcap_spacers")
    rng = catalog.load("cone_spring_ranges").set_index("parameter").loc["aspect_ratio"]
    zetas = np.linspace(float(rng["min_ratio"]), float(rng["max_ratio"]), int(catalog.constant("optimise_cone_aspect_ratio_count")))
    cone_cost = catalog.constant("cone_spring_unit_cost_eur")
    cone_ns = _w("cone_spring") * (1.0 - catalog.constant("cone_spring_design_standard"))
    rows = [{"endcap_spacer": NONE, "cone_aspect_ratio": 0.0, "es_max_axial_damping_nm": np.inf, "es_contact_area_mm2": 0.0,
             "es_mean_radius_mm": 0.0, "es_height_mm": 0.0, "cost_eur": 0.0, "nonstandard": 0.0}]
    for _, r in es.iterrows():
        for z in zetas:
            rows.append({"endcap_spacer": str(r["class"]), "cone_aspect_ratio": float(round(z, 6)),
                         "es_max_axial_damping_nm": float(r["max_axial_damping_nm"]),
                         "es_contact_area_mm2": float(r["contact_area_mm2"]), "es_mean_radius_mm": float(r["mean_radius_mm"]),
                         "es_height_mm": float(r["axial_height_mm"]),
                         "cost_eur": float(r["unit_cost_eur"]) + cone_cost,
                         "nonstandard": _w("endcap_spacer") * (not _b(r["standard"])) + cone_ns})
    return pd.DataFrame(rows)


def _spring_table(d, cores: pd.DataFrame, pin: bool, cache: "_Cache | None" = None) -> pd.DataFrame:
    from synth.model import packaging as s7
    step = catalog.constant("optimise_mbd_step_mm")
    d_in = float(np.min(s7.spring_housing_inner_diameter_mm(cores["pivot_class_mm"].to_numpy())))
    d_out = float(np.max(s7.spring_housing_outer_diameter_mm(cores["bearing_D_mm"].to_numpy(), d.working_arm_mm)))
    mbd = np.arange(np.ceil(d_in / step) * step, np.floor(d_out / step) * step + step / 2, step)
    manual = pin and d.main_spring_mode == "manual"
    if manual and d.main_spring_mean_body_diameter_mm is not None:
        mbd = np.array([float(d.main_spring_mean_body_diameter_mm)])
    key = ("spring", tuple(mbd.tolist())) + ((d.main_spring_material, _hashable(d.main_spring_wire_size_mm), d.main_spring_wire_section)
                                             if manual else (None, None, None))
    base, inertia = (cache or _Cache(None)).get(key, lambda: _spring_product(d, mbd, manual))
    t = base.copy()
    t["active_coils"] = s9.active_coils(t["E_mpa"].to_numpy(), inertia, t["spring_mbd_mm"].to_numpy(),
                                        d.spring_stiffness_nm_per_deg)
    t["cost_eur"] = spring_cost_eur(t["spring_mbd_mm"], t["active_coils"], t["round_wire"], t["b_mm"], t["h_mm"],
                                    t["wire_cost_eur_per_m"], t["density_kg_m3"], t["material_cost_eur_per_kg"])
    return t


def _spring_product(d, mbd: np.ndarray, manual: bool):
    """Material x wire x mean body diameter table of the main springs and the wires' second moments."""
    mats = catalog.load("spring_materials")
    wires = catalog.load("spring_wires")
    if manual and d.main_spring_material is not None:
        mats = mats[mats["material"].astype(str) == d.main_spring_material]
    m = pd.DataFrame({"spring_material": mats["material"].astype(str), "E_mpa": mats["E_mpa"].astype(float),
                      "density_kg_m3": mats["density_kg_m3"].astype(float),
                      "material_cost_eur_per_kg": mats["unit_cost_eur"].astype(float), "material_standard": mats["standard"].map(_b)})
    w = pd.DataFrame({"spring_wire": wires["designation"].astype(str), "round_wire": (wires["section"].str.strip() == "round"),
                      "b_mm": wires["b_mm"].astype(float), "h_mm": wires["h_mm"].astype(float),
                      "b_tol_mm": wires["b_tol_mm"].astype(float), "h_tol_mm": wires["h_tol_mm"].astype(float),
                      "wire_cost_eur_per_m": wires["unit_cost_eur"].astype(float), "wire_standard": wires["standard"].map(_b)})
    if manual and d.main_spring_wire_size_mm is not None:
        size = list(d.main_spring_wire_size_mm) * (2 if len(d.main_spring_wire_size_mm) == 1 else 1)
        sel = np.isclose(w["b_mm"], size[0]) & np.isclose(w["h_mm"], size[1])
        if d.main_spring_wire_section is not None:
            sel &= w["round_wire"] == (d.main_spring_wire_section == "round")
        w = w[sel]
    t = m.merge(w, how="cross").merge(pd.DataFrame({"spring_mbd_mm": mbd}), how="cross")
    t["nonstandard"] = (_w("spring_material") * ~t["material_standard"] + _w("spring_wire") * ~t["wire_standard"]).astype(float)
    t = t.reset_index(drop=True)
    return t, s9.second_moment_mm4(t["b_mm"].to_numpy(), t["h_mm"].to_numpy(), t["round_wire"].to_numpy())


def _bolt_table(d, pin: bool) -> pd.DataFrame:
    fmt = d.bolt_format if (pin and d.bolt_mode == "manual") else None
    cls = d.bolt_property_class if (pin and d.bolt_mode == "manual") else None
    bolts = catalog.load("bolts").set_index("designation")
    classes = catalog.load("bolt_property_classes").set_index("property_class")
    rows = []
    for fmt_i in ([fmt] if fmt else list(bolts.index)):  # every catalog format, not only the escalation ranks
        try:
            rows += s10.bolt_candidates(fmt_i, cls)
        except InputError:  # class not defined for this diameter
            continue
    t = pd.DataFrame(rows)
    t["cost_eur"] = t["unit_cost_eur"] * t["unit_cost_factor"]
    std_f = t["bolt_format"].map(lambda k: _b(bolts.loc[k, "standard"]))
    std_c = t["bolt_property_class"].map(lambda k: _b(classes.loc[k, "standard"]))
    t["nonstandard"] = (_w("bolt") * (~std_f).astype(float) + _w("bolt") * (~std_c).astype(float))
    return t.reset_index(drop=True)


class _Cache:
    """Memo of tables shared by the spaces of one bulk chunk (no-op without a dict)."""

    def __init__(self, store: dict | None):
        self.store = store

    def get(self, key, make):
        if self.store is None:
            return make()
        if key not in self.store:
            self.store[key] = make()
        return self.store[key]


def _hashable(x):
    return tuple(x) if isinstance(x, (list, tuple)) else x


def _with_notes(fn, d, pin):
    notes: list = []
    return fn(d, pin, notes), notes


def build_space(d, *, fidelity: str = "screening", friction_circle: bool = True, pin_inputs: bool = False,
                cache: dict | None = None) -> DesignSpace:
    """The design space of the validated input ``d`` (a :class:`~synth.schema.DesignInput`).

    ``pin_inputs=True`` keeps the part choices the input names (pivot class,
    bushing thickness, manual main spring and bolt) instead of searching
    them. ``fidelity`` (``screening``/``full``) is the cone-spring and
    plastic-wear model used when the space is evaluated.

    ``cache``: a dict the caller keeps while the catalogs do not change (one
    bulk chunk); the tables that depend on few inputs (core table by working
    arm, fuel, typology and pinned parts; bushing, axial and bolt tables;
    the material x wire product of the springs) are built once and shared
    (read-only) by the spaces built with the same dict.
    """
    if fidelity not in ("screening", "full"):
        raise InputError(Problem("fidelity", fidelity, "screening or full"))
    notes: list = []
    hl = float(s3.hubload_nominal_n(d.calculated_torque_target_nm, d.working_arm_mm, d.differential_angle_deg))
    dur = durability_of(d)
    if dur is None:
        notes.append("durability test not given: bushing, plastic wear and spring-amplitude checks are not evaluated")
    standard = bool(s0.is_standard_layout(d.middle_plane_belt_height_mm, d.max_axial_displacement_mm))
    fixed = {
        "hubload_nominal_n": hl,
        "durability": dur,
        "layout": "standard" if standard else "reverse",
        "pulley_width_mm": float(s0.pulley_width_mm(d.belt_width_mm)),
        "mu_pivot_bushing": friction_mu("pivot_bushing", d.application_type),
        "axial_allowed": d.damping_typology != "only_radial",
        "damping_target_nm": 0.0 if d.damping_target_nm is None else float(d.damping_target_nm),
        "loading_arm_input_mm": d.loading_arm_mm,
    }
    c = _Cache(cache)
    pin = pin_inputs
    core_key = ("core", d.working_arm_mm, d.engine_fuel, d.pivot_class_diameter_mm, d.damping_typology, pin,
                d.pivot_bushing_radial_thickness_mm if pin else None)
    cores, core_notes = c.get(core_key, lambda: _with_notes(_core_table, d, pin))
    notes += core_notes
    bolt_key = ("bolt",) + ((d.bolt_format, d.bolt_property_class) if (pin and d.bolt_mode == "manual") else (None, None))
    subs = {"bushing": c.get(("bushing",), lambda: _bushing_table(d, pin)), "axial": c.get(("axial",), lambda: _axial_table(d)),
            "spring": _spring_table(d, cores, pin, c), "bolt": c.get(bolt_key, lambda: _bolt_table(d, pin))}
    if dur is None:
        subs["bushing"] = subs["bushing"].drop_duplicates("supplier").assign(bushing_length_mm=np.nan, cost_eur=0.0)
    return DesignSpace(d, fidelity, friction_circle, fixed, cores, subs, notes)
