"""The catalog design space of a tensioner, as arrays, and its decomposition.

A design is one choice per part family: ball bearing, pivot class, bushing
supplier and length, damper pad and endcap spacer classes, cone spring
variant, main-spring material, wire and mean body diameter, bolt format and
property class. Continuous quantities (damping split, active coils,
cone-spring thickness and force, bolt preload and tightening torque) follow
in closed form from the physics of :mod:`synth.model` and are derived, not
searched.

Decomposition. The choices that set the damping split (bearing, pivot class,
bushing supplier, whose wall thickness sets the pivot diameter) and the
damper pad (it sets the spring-housing height and the cone-spring outer
diameter) form the **core**; every other family is a **subsystem** whose
constraints involve only the application, the core and its own choice:

========== ============================================ ==========================================
subsystem  options                                      constraints (thesis step)
========== ============================================ ==========================================
bushing    supplier x catalog length (core's supplier)  Table 5 rating, p, pv, pvt, wear, parallelism,
                                                        length (4)
axial      endcap spacer x cone spring variant          Table 4 capacity, belt plane (7), cone spring (8),
           (h0/t, s/h0, De below its maximum)           plastic wear and EOL damping (5)
spring     material x wire x mean body diameter         yield, Goodman SF, contacts, coil gap, index (9)
bolt       format x head form x property class          tilting, sliding, bolt, under-head, thread, bore,
                                                        pivot base (10), pivot wall (2)
========== ============================================ ==========================================

Given the core, subsystems share no constraint, so the optimum of an additive
objective (cost, standardisation) is the core's own value plus the best
option of each subsystem, and the max-min margin combines by the minimum.
The main spring sees the core only through a **key** (spring torque, housing
height and diameters), so springs are evaluated once per distinct key.

:class:`Space` holds the application-independent tables of one catalog
setting (each built once and cached); which rows an application may use
(only radial damping, pinned parts, the mean-diameter range of its housing)
is decided per application by :func:`core_rows` and :func:`spring_window`.

>>> s = space()
>>> sorted(SUBSYSTEMS), s.n("core") > 100, s.n("spring") > 1000
(['axial', 'bolt', 'bushing', 'spring'], True, True)
"""

from __future__ import annotations

import functools
import math
from collections.abc import Mapping
from dataclasses import dataclass, field

import numpy as np

from synth import catalog

from synth.parts import Parts, Table, arrays
from synth.cost import columns
from synth.cost.book import book_for, volume_of
from synth.errors import InputError, Problem
from synth.model import packaging, pivot, torsion_spring, disc_spring
from synth.fingerprint import cached, catalogs_sha256, source_stamp
from synth.schema import PART_FIELDS, field_by_name
from synth.design.subsystems import CORE_PART_KEYS, declared, names, pinned_diameter, spring_window

__all__ = ["SUBSYSTEMS", "TABLES", "PART_KEYS", "PART_DEFAULTS", "NONE", "bolt_attributes", "washer_code", "CAPACITY", "Space", "space", "core_rows", "spring_window",
           "table_sizes", "check_capacity", "fixed_fields", "space_for", "pinned_space", "pinned_diameter",
           "design_inputs", "same_input", "spring_cost_from"]

#: the part families beside the core, as declared (:mod:`synth.design.subsystems`), in search and result order
SUBSYSTEMS = names()
TABLES = ("core",) + SUBSYSTEMS
NONE = "none"

#: the part keys of a design (one vocabulary: input file, results, JSON, Excel, report, CAD), by table: the core's,
#: then each declared subsystem's
PART_KEYS_BY_TABLE = {"core": CORE_PART_KEYS, **{f.name: f.part_keys for f in declared()}}
#: part keys a design may leave out, and the value they then take (results saved before the key existed)
PART_DEFAULTS = {"bolt_head_type": "hex", "bolt_washer": NONE, "bolt_tightening": "torque_wrench_tested"}
PART_KEYS = tuple(k for t in TABLES for k in PART_KEYS_BY_TABLE[t])


class RowsRead(Mapping):
    """The columns of a table at rows ``idx``, as :meth:`Space.rows` gives them, each gathered on first access."""

    def __init__(self, table: dict, idx):
        self._table, self._idx, self._got = table, idx, {}

    def __getitem__(self, key):
        if key not in self._got:
            self._got[key] = self._table[key][self._idx]
        return self._got[key]

    def __contains__(self, key) -> bool:  # a column of the table, gathered or not (no gather to answer)
        return key in self._table

    def __iter__(self):
        return iter(self._table)

    def __len__(self) -> int:
        return len(self._table)


def spring_cost_from(cost_eur_times_stiffness, stiffness_nm_per_deg) -> np.ndarray:
    """Main-spring unit cost [EUR] from the catalog's ``cost x stiffness`` column and a stiffness [Nm/deg]
    (:meth:`Space.spring_cost_eur`'s formula: the wire length, so the cost, goes as ``1 / k``).

    >>> float(spring_cost_from(np.array([0.04]), 0.02)[0])
    2.0
    """
    return cost_eur_times_stiffness / np.maximum(np.asarray(stiffness_nm_per_deg, float), 1e-12)


@dataclass
class Space:
    """The option tables (dicts of equal-length arrays) of one catalog setting; see the module docstring.

    Every table has ``cost_eur`` and ``nonstandard`` (weighted count of
    non-standard parts) columns, except the spring table whose cost depends on
    the application's stiffness (:meth:`spring_cost_eur`).
    """

    tables: dict
    parts: Parts
    notes: list = field(default_factory=list)
    #: the part-naming input fields this space keeps (:func:`pinned_space`): () for the whole catalog product
    pinned: tuple = ()

    def n(self, table: str) -> int:
        return len(next(iter(self.tables[table].values())))

    def col(self, table: str, name: str) -> np.ndarray:
        return self.tables[table][name]

    def spring_cost_eur(self, stiffness_nm_per_deg, options=None) -> np.ndarray:
        """Main-spring cost [EUR] of ``options`` for a stiffness (broadcast: (n,1) stiffness x options).

        Wire length ``pi Dm n_a = pi E I / (180 k)`` (eq. 64-65) does not depend
        on the mean diameter, so the cost is ``cost_per_unit_compliance / k``
        and the cost order of the springs is the same for every application.
        """
        c = self.tables["spring"]["cost_eur_times_stiffness"]
        return spring_cost_from(c if options is None else c[options], stiffness_nm_per_deg)

    def rows(self, table: str, idx) -> dict:
        """The columns of ``table`` at rows ``idx`` (gathered arrays)."""
        return {k: v[idx] for k, v in self.tables[table].items()}

    def rows_read(self, table: str, idx) -> "RowsRead":
        """:meth:`rows` for a reader of a few of the columns: each column gathered when first read (a search
        evaluates a group on many blocks of options and reads a handful of the table's columns)."""
        return RowsRead(self.tables[table], idx)

    def design_attributes(self, parts: dict, field_prefix: str = "parts") -> dict:
        """One-row attribute dicts, per table, of the design ``parts`` (its part keys; any pivot class, length,
        cone variant or mean diameter, not only the searched grids). Unknown keys name the part key.

        The cone spring's outer diameter is given absolutely (``cone_spring_external_diameter_mm``) and
        stored as the reduction below the largest one the damper pad allows.
        """
        p = self.parts

        def need(k):
            if parts.get(k) is None:
                raise InputError(Problem(f"{field_prefix}.{k}", None, "a value (every part key of a design)"))
            return parts[k]

        def num(k, upper=None):
            try:
                x = float(need(k))
            except (TypeError, ValueError):
                raise InputError(Problem(f"{field_prefix}.{k}", parts[k], "a number")) from None
            if not (np.isfinite(x) and x > 0 and (upper is None or x <= upper)):
                raise InputError(Problem(f"{field_prefix}.{k}", parts[k], "a positive finite number"
                                         + (f" up to {upper:g}" if upper is not None else "")))
            return x

        def code(table: Table, k, none_ok=False):
            v = str(need(k)).strip()
            if none_ok and v == NONE:
                return -1
            return table.code(v, f"{field_prefix}.{k}")

        pad = code(p.damper_pad, "damper_pad_class", True)
        out = {"core": core_attributes(p, [code(p.bearing, "ball_bearing")], [num("pivot_class_diameter_mm")],
                                       [code(p.bushing, "pivot_bushing_supplier")], [pad])}
        out["bushing"] = bushing_attributes(p, out["core"]["supplier_code"], [num("pivot_bushing_length_mm")])
        spacer = code(p.endcap_spacer, "endcap_spacer_class", True)
        if spacer >= 0:
            de_max = float(disc_spring.cone_spring_max_external_diameter_mm(out["core"]["damper_pad_outer_diameter_mm"])[0])
            di_min = float(disc_spring.cone_spring_min_internal_diameter_mm(out["core"]["pivot_diameter_mm"])[
                "cone_spring_min_internal_diameter_mm"][0])
            red = de_max - num("cone_spring_external_diameter_mm") if pad >= 0 else 0.0
            di = parts.get("cone_spring_internal_diameter_mm")  # absent in older results: the Table 8 minimum
            inc = (num("cone_spring_internal_diameter_mm") - di_min) if di not in (None, 0, 0.0) else 0.0
            out["axial"] = axial_attributes(p, [spacer], [num("cone_spring_aspect_ratio")],
                                            [num("cone_spring_deflection_ratio", 1.0)], [red], [inc])
        else:
            out["axial"] = axial_attributes(p, [-1], [0.0], [0.0], [0.0])
        out["spring"] = spring_attributes(p, [code(p.spring_material, "main_spring_material")],
                                          [code(p.spring_wire, "main_spring_wire")],
                                          [num("main_spring_mean_body_diameter_mm")])
        head = parts.get("bolt_head_type") or PART_DEFAULTS["bolt_head_type"]
        p.bolt.code(str(need("bolt_format")).strip(), f"{field_prefix}.bolt_format")
        hcode = p.bolt_head.code(f"{str(parts['bolt_format']).strip()} {head}", f"{field_prefix}.bolt_head_type")
        series = str(parts.get("bolt_washer") or PART_DEFAULTS["bolt_washer"]).strip()
        wcode = int(washer_code(p, [hcode], [series])[0])
        if wcode == -2:
            names = [NONE, *dict.fromkeys(p.washer.product_standard.tolist())]
            raise InputError(Problem(f"{field_prefix}.bolt_washer", parts.get("bolt_washer"),
                                     "one of " + ", ".join(names) + f" with a washer for {parts['bolt_format']} "
                                     "(none under a flange head)"))
        tcode = p.tightening.code(str(parts.get("bolt_tightening") or PART_DEFAULTS["bolt_tightening"]).strip(),
                                  f"{field_prefix}.bolt_tightening")
        out["bolt"] = bolt_attributes(p, [hcode], [code(p.bolt_class, "bolt_property_class")], [wcode], [tcode])
        if not out["bolt"]["class_defined"][0]:
            raise InputError(Problem(f"{field_prefix}.bolt_property_class", parts["bolt_property_class"],
                                     f"a class ISO 898-1 defines for {parts['bolt_format']} (9.8 only up to 16 mm)"))
        return out


def _w(name: str) -> float:
    return catalog.constant(f"nonstandard_weight_{name}")


def _grid(lo: float, hi: float, count: int) -> np.ndarray:
    return np.round(np.linspace(lo, hi, int(count)), 6) if count > 1 else np.array([round(lo, 6)])


def _pivot_classes(p: Parts) -> np.ndarray:
    lo, hi, step = (catalog.constant(f"optimise_pivot_class_{k}") for k in ("min_mm", "max_mm", "step_mm"))
    classes = set(np.round(np.arange(lo, hi + step / 2, step), 6).tolist())
    for _, cls, _ in p.table2.values():
        classes |= set(cls.tolist())
    return np.array(sorted(classes))


def core_attributes(p: Parts, bearing, pivot_class_mm, supplier, pad) -> dict:
    """The core table's columns for codes (bearing, supplier, pad: -1 = none) and pivot classes (arrays)."""
    b, s, dpad = (np.asarray(x, dtype=np.int64) for x in (bearing, supplier, pad))
    cls = np.asarray(pivot_class_mm, dtype=float)
    has = dpad >= 0
    pc = np.where(has, dpad, 0)

    def padcol(name, none=0.0):
        return np.where(has, p.damper_pad.cols[name][pc], none)

    thick = p.bushing.radial_thickness_mm[s]
    t = {
        "ball_bearing": p.bearing.key[b], "bearing_code": b,
        "pivot_class_diameter_mm": cls,
        "pivot_bushing_supplier": p.bushing.key[s], "supplier_code": s,
        "damper_pad_class": np.where(has, p.damper_pad.key[pc], NONE).astype(object), "pad_code": dpad,
        "axial_group_present": has,
        "bearing_inner_diameter_mm": p.bearing.d_mm[b], "bearing_outer_diameter_mm": p.bearing.D_mm[b],
        "bearing_width_mm": p.bearing.B_mm[b],
        "pivot_bushing_radial_thickness_mm": thick,
        "pivot_diameter_mm": pivot.pivot_diameter_mm(cls, thick),
        "spring_housing_inner_diameter_mm": packaging.spring_housing_inner_diameter_mm(cls),
        "damper_pad_max_axial_damping_nm": padcol("max_axial_damping_nm", np.inf),
        "damper_pad_contact_area_mm2": padcol("contact_area_mm2"),
        "damper_pad_mean_radius_mm": padcol("mean_radius_mm"),
        "damper_pad_outer_diameter_mm": padcol("outer_diameter_mm"),
        "damper_pad_axial_height_mm": padcol("axial_height_mm"),
        "cost_eur": columns.core_eur(p.prices, b, dpad),
        # Table 2's standard class depends on the working arm: the pivot-class part of the score is per application
        "nonstandard": (_w("bearing") * ~p.bearing.standard[b] + _w("bushing") * ~p.bushing.standard[s]
                        + _w("damper_pad") * np.where(has, ~p.damper_pad.standard[pc], False)).astype(float),
    }
    return t


def selectable_bearings(p: Parts) -> np.ndarray:
    """Codes of the bearings the thesis method can size: those with thesis Table 1 rows (both fuels) and Table 2
    rows. The catalog holds more (ISO 15, supplier ratings); no rule reproduces Tables 1-2 from their data
    (``tests/validation/test_thesis_tables_1_2.py``), so they wait for Table 1-2 rows (a user catalog can add
    them: ``bearing_selection.csv``, ``pivot_classes.csv``)."""
    ok = np.isfinite(p.bearing_max_hubload_n).all(axis=1) | np.isinf(p.bearing_max_hubload_n).all(axis=1)
    ok &= ~np.isnan(p.bearing_max_hubload_n).any(axis=1)
    ok &= np.array([len(p.table2[i][0]) > 0 for i in range(len(p.bearing))])
    return np.flatnonzero(ok)


def _core(p: Parts, classes=None) -> dict:
    classes = _pivot_classes(p) if classes is None else np.asarray(classes, dtype=float)
    bearings = selectable_bearings(p)
    b, c, s, dpad = (a.ravel() for a in np.meshgrid(bearings, np.arange(len(classes)),
                                                     np.arange(len(p.bushing)), np.arange(len(p.damper_pad) + 1) - 1,
                                                     indexing="ij"))
    return core_attributes(p, b, classes[c], s, dpad)


def bushing_attributes(p: Parts, supplier, length_mm) -> dict:
    """The bushing table's columns for supplier codes and lengths (any length: the flowchart's trial lengths)."""
    sup = np.asarray(supplier, dtype=np.int64)
    length = np.asarray(length_mm, dtype=float)
    return {"supplier_code": sup, "pivot_bushing_supplier": p.bushing.key[sup], "pivot_bushing_length_mm": length,
            "cost_eur": columns.bushing_eur(p.prices, sup, length),
            "nonstandard": np.zeros(length.shape)}


def _bushing(p: Parts) -> dict:
    sup = np.concatenate([np.full(len(lengths), i) for i, lengths in enumerate(p.bushing_lengths)]).astype(np.int64)
    return bushing_attributes(p, sup, np.concatenate(p.bushing_lengths))


def cone_variants() -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The cone-spring variants searched: ``(h0/t, s/h0, De reduction [mm])`` grids (constants_optimise.csv)."""
    c = catalog.constant
    zeta = _grid(c("optimise_cone_aspect_ratio_min"), c("optimise_cone_aspect_ratio_max"),
                 c("optimise_cone_aspect_ratio_count"))
    phi = _grid(c("optimise_cone_deflection_ratio_min"), c("optimise_cone_deflection_ratio_max"),
                c("optimise_cone_deflection_ratio_count"))
    red = np.arange(int(c("optimise_cone_de_reduction_count"))) * c("cone_spring_od_round_down_mm")
    return zeta, phi, red


def axial_attributes(p: Parts, spacer, aspect_ratio, deflection_ratio, de_reduction_mm, di_increase_mm=0.0) -> dict:
    """The axial table's columns for spacer codes (-1 = none) and cone-spring variants (arrays).

    The cone spring's outer diameter is ``de_reduction_mm`` below the largest the damper pad carries, its inner
    diameter ``di_increase_mm`` above the smallest the pivot allows (Table 8); the searched grid keeps the
    smallest (0), a given design may have any."""
    e = np.asarray(spacer, dtype=np.int64)
    has = e >= 0
    ec = np.where(has, e, 0)
    es = p.endcap_spacer

    def col(name, none=0.0):
        return np.where(has, es.cols[name][ec], none)

    cone_ns = _w("cone_spring") * (1.0 - catalog.constant("cone_spring_design_standard"))
    return {
        "spacer_code": e, "axial_group_present": has,
        "endcap_spacer_class": np.where(has, es.key[ec], NONE).astype(object),
        "cone_spring_aspect_ratio": np.where(has, aspect_ratio, 0.0),
        "cone_spring_deflection_ratio": np.where(has, deflection_ratio, 0.0),
        "cone_spring_de_reduction_mm": np.where(has, de_reduction_mm, 0.0),
        "cone_spring_di_increase_mm": np.where(has, di_increase_mm, 0.0),
        "endcap_spacer_max_axial_damping_nm": col("max_axial_damping_nm", np.inf),
        "endcap_spacer_contact_area_mm2": col("contact_area_mm2"),
        "endcap_spacer_mean_radius_mm": col("mean_radius_mm"),
        "endcap_spacer_axial_height_mm": col("axial_height_mm"),
        "cost_eur": columns.axial_eur(p.prices, e),
        "nonstandard": np.where(has, _w("endcap_spacer") * ~es.standard[ec] + cone_ns, 0.0),
    }


def _axial(p: Parts) -> dict:
    zeta, phi, red = cone_variants()
    e, z, f, r = (a.ravel() for a in np.meshgrid(np.arange(len(p.endcap_spacer)), zeta, phi, red, indexing="ij"))
    return axial_attributes(p, np.concatenate([[-1], e]), np.concatenate([[0.0], z]), np.concatenate([[0.0], f]),
                            np.concatenate([[0.0], r]))


def mbd_grid(p: Parts) -> np.ndarray:
    """Main-spring mean body diameters searched [mm]: the step grid spanning every housing of the catalogs."""
    step = catalog.constant("optimise_mbd_step_mm")
    lo = float(packaging.spring_housing_inner_diameter_mm(catalog.constant("optimise_pivot_class_min_mm")))
    hi = float(np.max(p.bearing.D_mm))
    return np.arange(math.ceil(lo / step) * step, math.floor(hi / step) * step + step / 2, step)


def _supplied(p: Parts) -> np.ndarray:
    """``(materials, wires)``: the material is supplied in the wire's section (``spring_materials.csv``)."""
    mat, wire = p.spring_material, p.spring_wire
    return np.array([[wire.section[wi] in mat.wire_sections[mi].split() for wi in range(len(wire))]
                     for mi in range(len(mat))], dtype=bool).reshape(len(mat), len(wire))


def spring_attributes(p: Parts, material, wire, mbd_mm) -> dict:
    """The spring table's columns for material and wire codes and mean body diameters (any diameter)."""
    m, w = np.asarray(material, dtype=np.int64), np.asarray(wire, dtype=np.int64)
    d = np.asarray(mbd_mm, dtype=float)
    wire_t, mat = p.spring_wire, p.spring_material
    rnd = wire_t.round_wire[w]
    rm = np.empty(m.shape)
    dia = torsion_spring.rm_lookup_diameter_mm(wire_t.b_mm[w], wire_t.h_mm[w], rnd)
    for i in np.unique(m):  # a handful of materials, each with its own strength table (EN 10270)
        sel = m == i
        rm[sel] = torsion_spring.material_strength_mpa(mat.key[int(i)], dia[sel])
    inertia = torsion_spring.second_moment_mm4(wire_t.b_mm[w], wire_t.h_mm[w], rnd)
    area = np.where(rnd, np.pi * wire_t.h_mm[w] ** 2 / 4.0, wire_t.b_mm[w] * wire_t.h_mm[w])
    # wire length x k = pi E I / 180 (eq. 64-65): the wire's cost x k, divided by k per application
    cost_k = columns.spring_eur_times_stiffness(p.prices, m, w, mat.E_mpa[m], inertia, area, mat.density_kg_m3[m])
    return {
        "material_code": m, "wire_code": w,
        "main_spring_material": mat.key[m], "main_spring_wire": wire_t.key[w], "main_spring_mean_body_diameter_mm": d,
        "E_mpa": mat.E_mpa[m], "Rm_mpa": rm, "sigma_y_mpa": mat.sigma_y_bend_fraction[m] * rm,
        "sigma_A0_mpa": mat.sigma_A0_fraction[m] * rm, "sigma_perm_static_mpa": mat.sigma_perm_static_fraction[m] * rm,
        "supplied_in_section": _supplied(p)[m, w],
        "b_mm": wire_t.b_mm[w], "h_mm": wire_t.h_mm[w], "round_wire": rnd, "b_tol_mm": wire_t.b_tol_mm[w],
        "h_tol_mm": wire_t.h_tol_mm[w], "second_moment_mm4": inertia, "wire_section_area_mm2": area,
        "density_kg_m3": mat.density_kg_m3[m],
        "cost_eur_times_stiffness": cost_k,
        "nonstandard": (_w("spring_material") * ~mat.standard[m] + _w("spring_wire") * ~wire_t.standard[w]).astype(float),
    }


def _spring(p: Parts, mbd=None) -> dict:
    mbd = mbd_grid(p) if mbd is None else np.asarray(mbd, dtype=float)
    m, w, d = (a.ravel() for a in np.meshgrid(np.arange(len(p.spring_material)), np.arange(len(p.spring_wire)),
                                              mbd, indexing="ij"))
    # a material pairs only with the wire sections it is supplied in (spring_materials.csv wire_sections)
    supplied = _supplied(p)[m, w]
    return spring_attributes(p, m[supplied], w[supplied], d[supplied])


def washer_code(p: Parts, head, series) -> np.ndarray:
    """The ``washers.csv`` row of washer ``series`` (``"none"``: -1) for the bolt of each head code; -2 where the
    series has no washer for that bolt (or the head is a flange head: its flange is its washer)."""
    hd = np.atleast_1d(np.asarray(head, dtype=np.int64))
    ser = np.broadcast_to(np.asarray(series, dtype=object), hd.shape)
    ws = p.washer
    d = p.bolt.d_mm[p.bolt_head.bolt_code[hd]]
    out = np.full(hd.shape, -2, dtype=np.int64)
    for i in range(len(hd)):
        name = str(ser[i]).strip()
        if name == NONE:
            out[i] = -1
        elif p.bolt_head.head_type[hd[i]] != "flange":
            hit = np.flatnonzero((ws.product_standard == name) & np.isclose(ws.d_mm, d[i]))
            out[i] = hit[0] if len(hit) else -2
    return out


def bolt_attributes(p: Parts, head, property_class, washer=None, tightening=None) -> dict:
    """The bolt table's columns for head codes (``bolt_heads.csv``: a format in a head form), property classes,
    washer codes (``washers.csv`` rows, -1: none; default none) and tightening-method codes
    (``tightening_factors.csv`` rows; default the reference method, :data:`synth.model.vdi2230.DEFAULT_TIGHTENING_METHOD`)."""
    from synth.model.vdi2230 import DEFAULT_TIGHTENING_METHOD
    hd, c = np.asarray(head, dtype=np.int64), np.asarray(property_class, dtype=np.int64)
    bh, bo, cl, ws, tf = p.bolt_head, p.bolt, p.bolt_class, p.washer, p.tightening
    wc = np.broadcast_to(np.asarray(-1 if washer is None else washer, dtype=np.int64), hd.shape)
    tc = np.broadcast_to(np.asarray(tf.code(DEFAULT_TIGHTENING_METHOD) if tightening is None else tightening,
                                    dtype=np.int64), hd.shape)
    b = bh.bolt_code[hd]
    big = bo.d_mm[b] > 16.0
    has = wc >= 0
    wi = np.where(has, wc, 0)

    def wcol(name, none=np.nan):
        return np.where(has, ws.cols[name][wi], none)
    reference = (tf.key[tc] == DEFAULT_TIGHTENING_METHOD) & ~has
    rank_b = np.where(np.isfinite(bo.escalation_rank[b]) & (bh.head_type[hd] == "hex") & reference,
                      bo.escalation_rank[b], np.inf)
    return {
        "head_code": hd, "bolt_code": b, "class_code": c, "bolt_format": bo.key[b], "bolt_head_type": bh.head_type[hd],
        "bolt_property_class": cl.key[c], "bolt_d_mm": bo.d_mm[b], "pivot_bore_min_mm": bo.pivot_bore_min_mm[b],
        "bolt_head_dw_min_mm": bh.dw_min_mm[hd], "bolt_head_outer_mm": bh.head_outer_mm[hd],
        "bolt_head_height_mm": bh.head_height_mm[hd],
        "washer_code": wc, "bolt_washer": np.where(has, ws.product_standard[wi], NONE).astype(object),
        "washer_d1_mm": wcol("d1_mm"), "washer_d2_mm": wcol("d2_mm"), "washer_h_mm": wcol("h_mm", 0.0),
        "tightening_code": tc, "bolt_tightening": tf.key[tc], "tightening_alpha_a": tf.alpha_a_max[tc],
        "tightening_by_yield": tf.preload_set_by[tc] == "yield",
        "rp02_mpa": np.where(big, cl.rp02_min_d_gt16_mpa[c], cl.rp02_min_mpa[c]),
        "escalation_order": rank_b * 100 + cl.escalation_rank[c],  # the thesis escalates hex-head bolts
        "class_defined": ~(np.isfinite(cl.d_max_mm[c]) & (bo.d_mm[b] > cl.d_max_mm[c])),  # ISO 898-1: 9.8 to 16 mm
        "cost_eur": columns.bolt_eur(p.prices, hd, c, wc, tc),
        "nonstandard": (_w("bolt") * ~bo.standard[b] + _w("bolt") * ~bh.standard[hd]
                        + _w("bolt") * ~cl.standard[c] + _w("bolt") * np.where(has, ~ws.standard[wi], False)
                        + _w("bolt") * ~tf.standard[tc]).astype(float),
    }


def _bolt(p: Parts) -> dict:
    """Every bolt option: head (format x head form) x property class x washer series (none, each series of
    ``washers.csv``; flange heads none) x tightening method (the ``design_option`` rows of ``tightening_factors.csv``)."""
    series = [NONE, *dict.fromkeys(p.washer.product_standard.tolist())]
    methods = np.flatnonzero(p.tightening.design_option)
    h, c, s, t = (a.ravel() for a in np.meshgrid(np.arange(len(p.bolt_head)), np.arange(len(p.bolt_class)),
                                                 np.arange(len(series)), methods, indexing="ij"))
    w = washer_code(p, h, np.array(series, dtype=object)[s])
    keep = w >= -1
    tab = bolt_attributes(p, h[keep], c[keep], w[keep], t[keep])
    ok = tab["class_defined"]
    return {k: v[ok] for k, v in tab.items()}


#: table -> (the most rows the evaluator is given, the catalogs whose rows multiply into it). Capacity bounds,
#: measured (benchmarks/bench_readers.py, user catalogs): the evaluation grows linearly with each table, about
#: 0.5 MB and 8 ms per 300 main-spring options (a 1,600-wire spring_wires.csv, 575,535 options: 15.5 s, 0.9 GB;
#: 50,000 wires ran out of memory). Each bound is about ten times the built-in catalogs' table, where one design
#: takes about 5 s and 0.4 GB.
CAPACITY = {"core": (2_000, "ball_bearings.csv, pivot_classes.csv, pivot_bushings.csv, damper_pads.csv"),
            "bushing": (500, "pivot_bushings.csv"),
            "axial": (5_000, "endcap_spacers.csv"),
            "spring": (150_000, "spring_materials.csv, spring_wires.csv (and the bearings' diameters)"),
            "bolt": (10_000, "bolt_heads.csv, bolt_property_classes.csv, washers.csv, tightening_factors.csv")}


def table_sizes(p: Parts) -> dict:
    """The rows of each table of the space of parts ``p``, counted before anything is built (upper bounds)."""
    n_axial = 1 + len(p.endcap_spacer) * int(np.prod([len(g) for g in cone_variants()]))
    return {"core": len(selectable_bearings(p)) * len(_pivot_classes(p)) * len(p.bushing) * (len(p.damper_pad) + 1),
            "bushing": int(sum(len(lengths) for lengths in p.bushing_lengths)), "axial": n_axial,
            "spring": len(p.spring_material) * len(p.spring_wire) * len(mbd_grid(p)),
            "bolt": len(p.bolt_head) * len(p.bolt_class) * (1 + len(set(p.washer.product_standard.tolist())))
            * int(p.tightening.design_option.sum())}


def check_capacity(p: Parts) -> None:
    """An :class:`~synth.errors.InputError` naming the catalogs when a table of the space would exceed
    :data:`CAPACITY` (user catalogs too big for the evaluator), before it is built."""
    problems = [Problem(f"--catalogs ({CAPACITY[t][1]})", f"{n} {t} options",
                        f"catalogs whose design space the evaluator can hold: at most {CAPACITY[t][0]} {t} options "
                        f"(about ten times the built-in catalogs'; give fewer rows)")
                for t, n in table_sizes(p).items() if n > CAPACITY[t][0]]
    if problems:
        raise InputError(problems)


def _build_space() -> Space:
    p = arrays()
    check_capacity(p)
    return Space({"core": _core(p), "bushing": _bushing(p), "axial": _axial(p), "spring": _spring(p),
                  "bolt": _bolt(p)}, p)


@functools.lru_cache(maxsize=8)
def _space_cached(user_dirs: tuple) -> Space:
    """The space of these catalogs, built once per catalog data and builder source (the on-disk cache of
    :func:`synth.fingerprint.cached`: about 5 ms to check and load against about 0.1 s to build)."""
    return cached("space", [catalogs_sha256(user_dirs), source_stamp()], _build_space)


def space() -> Space:
    """The design space of the current catalog setting (cached; do not modify its arrays)."""
    return _space_cached(tuple(catalog.user_dirs()))


def core_rows(sp: Space, d, *, pin_inputs=False) -> np.ndarray:
    """The core rows application ``d`` may use in space ``sp``: only radial damping excludes pads. The parts the
    input names are kept by the space itself (:func:`space_for`); ``pin_inputs`` is accepted for the callers that
    pass it with a space of their own."""
    t = sp.tables["core"]
    ok = np.ones(sp.n("core"), dtype=bool)
    if d.damping_typology == "only_radial":
        ok &= ~t["axial_group_present"]
    return np.flatnonzero(ok)


def fixed_fields(d, pin_inputs=False) -> tuple[str, ...]:
    """The part-naming input fields (:data:`synth.schema.PART_FIELDS`) of ``d`` that the design must keep:
    ``pin_inputs`` True keeps every one the input gives, False none, a collection of field names those (each must
    be given: a field to keep needs its value).

    >>> from synth.data import case_path
    >>> from synth.io.documents import load_input
    >>> d = load_input(case_path("case3"))
    >>> fixed_fields(d, True), fixed_fields(d, ["pivot_class_diameter_mm"])
    (('pivot_class_diameter_mm', 'pivot_bushing_radial_thickness_mm'), ('pivot_class_diameter_mm',))
    """
    if pin_inputs is True:
        return tuple(n for n in PART_FIELDS if getattr(d, n) is not None)
    if not pin_inputs:
        return ()
    names = tuple(dict.fromkeys(pin_inputs))
    bad = [n for n in names if n not in PART_FIELDS]
    if bad:
        raise InputError(Problem("--fix", bad[0], "a field that names a part or a class: " + ", ".join(PART_FIELDS)))
    missing = [n for n in names if getattr(d, n) is None]
    if missing:
        raise InputError(Problem("--fix", missing[0], "a field the input gives a value to (nothing to keep)"))
    return tuple(n for n in PART_FIELDS if n in names)


def space_for(d, pin_inputs=False, inputs=None) -> Space:
    """The design space of input ``d`` with the parts it names kept (:func:`fixed_fields`; the whole
    :func:`space` when none is), priced at the annual volume of ``inputs`` (default ``[d]``: :func:`priced_for`)."""
    fixed = fixed_fields(d, pin_inputs)
    sp = pinned_space(space(), {n: getattr(d, n) for n in fixed}) if fixed else space()
    return priced_for(sp, [d] if inputs is None else inputs)


_PRICED: dict = {}


def priced_for(sp: Space, inputs) -> Space:
    """``sp`` with the cost columns of the inputs' annual volume (:func:`synth.cost.book.book_for`): ``sp`` itself
    at the default volume's breaks; inputs of different breaks keep the default's, and the space says so."""
    vols = {getattr(d, "annual_volume", None) for d in inputs}
    if vols <= {None}:
        return sp
    default = volume_of(None)
    books = {id(b): b for b in (book_for(sp.parts, default if v is None else v) for v in vols)}
    if len(books) > 1:
        return Space(sp.tables, sp.parts, list(sp.notes) + ["annual volumes of different price breaks in one "
                     "batch: priced at the default volume"], pinned=sp.pinned)
    book = next(iter(books.values()))
    if book is sp.parts.prices:
        return sp
    hit = _PRICED.get((id(sp), book.key))
    if hit is None or hit[0] is not sp:
        if len(_PRICED) > 16:
            _PRICED.clear()
        hit = (sp, Space(columns.reprice(book, sp.tables), sp.parts,
                         list(sp.notes) + [f"priced at {book.volume:,.0f} a year"], pinned=sp.pinned))
        _PRICED[(id(sp), book.key)] = hit
    return hit[1]


def _wire_rows(p: Parts, pins: dict) -> np.ndarray:
    """The ``spring_wires.csv`` rows a wire section and size select (a size names one wire; an unknown size lists
    the catalog's)."""
    w = p.spring_wire
    section = pins.get("main_spring_wire_section")
    size = pins.get("main_spring_wire_size_mm")
    ok = np.ones(len(w), dtype=bool)
    if section is not None:
        ok &= w.section == section
    if size is not None:
        sec = section or ("round" if len(size) == 1 else "rectangular")
        b, h = (size[0], size[0]) if len(size) == 1 else (size[0], size[1])
        hit = ok & (w.section == sec) & np.isclose(w.b_mm, b) & np.isclose(w.h_mm, h)
        if not hit.any():
            sizes = ", ".join(f"[{bb:g}]" if s == "round" else f"[{bb:g}, {hh:g}]"
                              for bb, hh, s in zip(w.b_mm, w.h_mm, w.section) if s == sec)
            raise InputError(Problem("main_spring_wire_size_mm", size,
                                     f"a {sec} wire of catalogs/spring_wires.csv: {sizes}"))
        ok = hit
    return np.flatnonzero(ok)


def pinned_space(sp: Space, pins: dict) -> Space:
    """``sp`` restricted to the parts ``pins`` (part-naming field -> input value) name: the pivot class (any
    value, not only the searched grid), the bushing suppliers of a radial thickness, the spring's material, wire
    section and size, mean body diameter (any value), the bolt's format and property class.

    Every solver reads its catalog product from the space it is given (:func:`space_for`), so one restriction
    keeps the inputs' parts for all of them, the diagnosis and its relaxation probes included.
    """
    p = sp.parts
    tables = dict(sp.tables)
    if "pivot_class_diameter_mm" in pins:
        tables["core"] = _core(p, [float(pins["pivot_class_diameter_mm"])])
    if "main_spring_mean_body_diameter_mm" in pins:
        tables["spring"] = _spring(p, [float(pins["main_spring_mean_body_diameter_mm"])])
    masks = {t: np.ones(len(next(iter(tables[t].values()))), dtype=bool) for t in tables}
    if "pivot_bushing_radial_thickness_mm" in pins:
        masks["core"] &= np.isclose(tables["core"]["pivot_bushing_radial_thickness_mm"],
                                    float(pins["pivot_bushing_radial_thickness_mm"]))
    if "main_spring_material" in pins:
        masks["spring"] &= tables["spring"]["main_spring_material"] == str(pins["main_spring_material"])
    if "main_spring_wire_section" in pins or "main_spring_wire_size_mm" in pins:
        masks["spring"] &= np.isin(tables["spring"]["wire_code"], _wire_rows(p, pins))
    for name in ("bolt_format", "bolt_property_class"):
        if name in pins:
            masks["bolt"] &= tables["bolt"][name] == str(pins[name])
    out = {t: ({k: v[masks[t]] for k, v in tables[t].items()} if not masks[t].all() else tables[t]) for t in tables}
    empty = [t for t in out if not len(next(iter(out[t].values())))]
    if empty:
        names = [n for n in pins if _field_table(n) in empty]
        raise InputError(Problem(names[0] if names else "parts", ", ".join(f"{n} {pins[n]}" for n in names),
                                 f"parts the catalogs hold together ({empty[0]}: no catalog row has all of them); "
                                 "free one of them (synth design --free FIELD)"))
    return Space(out, p, list(sp.notes) + [f"inputs kept: {', '.join(pins)}"], pinned=tuple(pins))


def design_inputs(parts: dict) -> dict:
    """The part-naming input fields (:data:`synth.schema.PART_FIELDS`) as design ``parts`` has them, in the input
    file's vocabulary (a wire section as ``round``, a wire size as ``[d]`` or ``[b, h]``, the bushing's radial
    thickness), for comparing a design with the input that asked for it.

    >>> v = design_inputs({"ball_bearing": "6006", "pivot_class_diameter_mm": 16, "pivot_bushing_supplier": "B",
    ...     "damper_pad_class": "none", "pivot_bushing_length_mm": 15, "endcap_spacer_class": "none",
    ...     "cone_spring_aspect_ratio": 0, "cone_spring_deflection_ratio": 0, "cone_spring_external_diameter_mm": 0,
    ...     "main_spring_material": "VDSiCr", "main_spring_wire": "R3.00", "main_spring_mean_body_diameter_mm": 44,
    ...     "bolt_format": "M8x1.25", "bolt_property_class": "8.8"})
    >>> v["main_spring_wire_section"], v["main_spring_wire_size_mm"], v["pivot_class_diameter_mm"]
    ('round', [3.0], 16.0)
    """
    attrs = space().design_attributes(parts)
    out = {}
    for name in PART_FIELDS:
        table, column = field_by_name(name).pins
        a = attrs[table]
        if column == "round_wire":
            out[name] = "round" if bool(a["round_wire"][0]) else "rectangular"
        elif column == "main_spring_wire":
            out[name] = [float(a["b_mm"][0])] if bool(a["round_wire"][0]) else [float(a["b_mm"][0]), float(a["h_mm"][0])]
        else:
            v = a[column][0]
            out[name] = float(v) if isinstance(v, (float, np.floating, int, np.integer)) else str(v)
    return out


def same_input(given, designed) -> bool:
    """Whether an input value and the design's (:func:`design_inputs`) name the same part (numbers to 1e-9)."""
    if isinstance(given, (list, tuple)):
        return isinstance(designed, (list, tuple)) and len(given) == len(designed) and \
            all(abs(float(a) - float(b)) <= 1e-9 * max(1.0, abs(float(a))) for a, b in zip(given, designed))
    if isinstance(given, (int, float)) and not isinstance(given, bool):
        return isinstance(designed, (int, float)) and abs(float(given) - float(designed)) <= 1e-9 * max(1.0, abs(given))
    return str(given).strip() == str(designed).strip()


def _field_table(name: str) -> str:
    return field_by_name(name).pins[0]


