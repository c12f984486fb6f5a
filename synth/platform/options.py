"""The platform's part vocabulary on the real catalogs: part families, part keys and option tables.

:func:`catalogue` maps the decomposed design space of :mod:`synth.design.space`
(one catalog setting) onto the families of :data:`synth.platform.data.FAMILIES`:

=========================== ================================================== ===========================
family                      part key (one part number)                         from
=========================== ================================================== ===========================
``ball_bearing``            designation, e.g. ``6006``                         core table
``pivot_class_diameter_mm`` pivot class [mm], e.g. ``19``                      core table
``damper_pad_class``        class, e.g. ``DP2`` (none: no part)                core table
``pivot_bushing``           supplier and length, e.g. ``A 18 mm``              bushing table
``endcap_spacer_class``     class, e.g. ``ES2`` (none: no part)                axial table
``cone_spring``             shape and outer diameter, e.g.                     axial table and the pad
                            ``h0/t 0.8, s/h0 0.75, De 30 mm``
``main_spring``             material, wire, mean body diameter, e.g.           spring table
                            ``VDSiCr R2.30 Dm 44 mm``
``bolt``                    format, head, property class, e.g.                 bolt table
                            ``M8x1.25 hex 8.8``
=========================== ================================================== ===========================

What is *not* a part (it follows each application in closed form, as the
space's docstring says): the main spring's active coil count (thesis step 9,
from the application's torsional stiffness: one wire, mandrel and winding
tool serve every stiffness), the cone spring's thickness and force (step 8,
from the application's axial damping) and its inner diameter (Table 8, from
the pivot), the bolt's preload and tightening torque. The bushing supplier is
a property of the core (it sets the pivot diameter), named in the bushing part.

The cone spring is searched as a reduction of the outer diameter below the
largest one the damper pad allows; as a part it is the absolute diameter, so
the axial option table holds one block of options per damper pad
(:attr:`Catalogue.axial_option`), and two pads may share a cone-spring part.

>>> cat = catalogue()
>>> cat.pf_parts["ball_bearing"][:2], cat.n_options("axial") == 1 + cat.n_pads * cat.n_axial_real
(['6006', '6007'], True)
>>> cat.pf_parts["bolt"][0], cat.pf_parts["main_spring"][0]
('M6x1 hex 8.8', 'VDSiCr R2.00 Dm 20 mm')
"""

from __future__ import annotations

import functools
from dataclasses import dataclass

import numpy as np

from synth import catalog
from synth.design.space import Space, space
from synth.model import disc_spring

__all__ = ["Catalogue", "catalogue", "family_keys", "NO_PART_KEY"]

#: the part key of "no part of this family" (no damper pad, no axial group)
NO_PART_KEY = "none"


@dataclass(frozen=True, eq=False)
class Catalogue:
    """The part lists and option tables of one catalog setting (see the module docstring).

    * ``pf_parts[f]``: part keys of family ``f`` (a part's code is its index);
    * ``core_codes[f]``: ``(n_core,)`` part code of family ``f`` per row of the space's core table;
    * ``options[s][f]``: ``(n_options,)`` part code per option of subsystem ``s``;
    * ``option_row[s]``: ``(n_options,)`` the row of the space's table ``s`` each option is;
    * ``option_cost_eur[s]``: ``(n_options,)`` unit cost (spring: ``cost x stiffness``, divide by the
      application's stiffness, :meth:`spring_cost_eur`);
    * ``axial_none``: the option index of "no axial group"; ``axial_real``: the axial table rows of
      the real options, ``axial_option(pad, j)`` their option index for a core with damper pad ``pad``.
    """

    space: Space
    pf_parts: dict
    core_codes: dict
    options: dict
    option_row: dict
    option_cost_eur: dict
    axial_real: np.ndarray
    axial_none: int
    n_pads: int

    @property
    def n_axial_real(self) -> int:
        return int(len(self.axial_real))

    def n_options(self, s: str) -> int:
        return int(len(self.option_row[s]))

    def axial_option(self, pad, j) -> np.ndarray:
        """Option index of real axial row position ``j`` (into :attr:`axial_real`) for damper pad code ``pad``."""
        return 1 + np.asarray(pad, np.int64) * self.n_axial_real + np.asarray(j, np.int64)

    def spring_cost_eur(self, stiffness_nm_per_deg: float) -> np.ndarray:
        """Unit cost [EUR] of every main-spring option for one application's stiffness (the space's formula)."""
        return self.space.spring_cost_eur(stiffness_nm_per_deg, self.option_row["spring"])


def _bushing_key(supplier, length_mm) -> str:
    return f"{supplier} {_num(length_mm)} mm"


def _cone_key(aspect_ratio, deflection_ratio, de_mm) -> str:
    return f"h0/t {_num(aspect_ratio)}, s/h0 {_num(deflection_ratio)}, De {_num(round(float(de_mm), 6))} mm"


def _spring_key(material, wire, mbd_mm) -> str:
    return f"{material} {wire} Dm {_num(mbd_mm)} mm"


def _bolt_key(fmt, head, cls, washer=NO_PART_KEY, tightening="torque_wrench_tested") -> str:
    """A bolt option's key: format, head form, class, and its washer and tightening method where they are not the
    reference (no washer, the torque found by tests): the keys of the reference options are unchanged."""
    extra = "".join(f" {x}" for x in (f"washer {washer}" if str(washer) != NO_PART_KEY else "",
                                      str(tightening) if str(tightening) != "torque_wrench_tested" else "") if x)
    return f"{fmt} {head} {cls}{extra}"


def family_keys(parts: dict) -> dict:
    """``{family: part key}`` of a design given by its part keys (:data:`synth.design.space.PART_KEYS`, as every
    result reports them; ``none`` where the design has no part of the family).

    >>> family_keys({"ball_bearing": "6006", "pivot_class_diameter_mm": 19.0, "pivot_bushing_supplier": "B",
    ...     "damper_pad_class": "none", "pivot_bushing_length_mm": 20.0, "endcap_spacer_class": "none",
    ...     "main_spring_material": "VDSiCr", "main_spring_wire": "R2.30", "main_spring_mean_body_diameter_mm": 44.0,
    ...     "bolt_format": "M8x1.25", "bolt_head_type": "hex", "bolt_property_class": "8.8"})["main_spring"]
    'VDSiCr R2.30 Dm 44 mm'
    """
    none = str(parts.get("endcap_spacer_class", NO_PART_KEY)) == NO_PART_KEY
    return {"ball_bearing": str(parts["ball_bearing"]),
            "pivot_class_diameter_mm": _num(parts["pivot_class_diameter_mm"]),
            "damper_pad_class": str(parts["damper_pad_class"]),
            "pivot_bushing": _bushing_key(parts["pivot_bushing_supplier"], parts["pivot_bushing_length_mm"]),
            "endcap_spacer_class": str(parts["endcap_spacer_class"]),
            "cone_spring": NO_PART_KEY if none else _cone_key(parts["cone_spring_aspect_ratio"],
                                                              parts["cone_spring_deflection_ratio"],
                                                              parts["cone_spring_external_diameter_mm"]),
            "main_spring": _spring_key(parts["main_spring_material"], parts["main_spring_wire"],
                                       parts["main_spring_mean_body_diameter_mm"]),
            "bolt": _bolt_key(parts["bolt_format"], parts.get("bolt_head_type") or "hex", parts["bolt_property_class"],
                              parts.get("bolt_washer") or NO_PART_KEY,
                              parts.get("bolt_tightening") or "torque_wrench_tested")}


def _codes(keys) -> tuple[list, np.ndarray]:
    """Distinct keys in first-seen order and the code of every entry."""
    uniq = list(dict.fromkeys(keys))
    pos = {k: i for i, k in enumerate(uniq)}
    return uniq, np.array([pos[k] for k in keys], np.int64)


def _num(x) -> str:
    return f"{float(x):g}"


@functools.lru_cache(maxsize=4)
def _catalogue(user_dirs: tuple) -> Catalogue:
    sp = space()
    p = sp.parts
    core = sp.tables["core"]
    classes = np.unique(core["pivot_class_diameter_mm"])
    pf_parts = {"ball_bearing": [str(k) for k in p.bearing.key],
                "pivot_class_diameter_mm": [_num(c) for c in classes],
                "damper_pad_class": [str(k) for k in p.damper_pad.key]}
    core_codes = {"ball_bearing": core["bearing_code"].astype(np.int64),
                  "pivot_class_diameter_mm": np.searchsorted(classes, core["pivot_class_diameter_mm"]).astype(np.int64),
                  "damper_pad_class": core["pad_code"].astype(np.int64)}
    options, rows, cost = {}, {}, {}
    bu = sp.tables["bushing"]
    keys = [_bushing_key(s, L) for s, L in zip(bu["pivot_bushing_supplier"], bu["pivot_bushing_length_mm"])]
    pf_parts["pivot_bushing"], codes = _codes(keys)
    options["bushing"] = {"pivot_bushing": codes}
    rows["bushing"], cost["bushing"] = np.arange(sp.n("bushing")), bu["cost_eur"].astype(float)
    # axial: "none", then one block of the real rows per damper pad (the cone spring's absolute diameter)
    ax = sp.tables["axial"]
    real = np.flatnonzero(ax["axial_group_present"])
    none = int(np.flatnonzero(~ax["axial_group_present"])[0])
    n_pads = len(p.damper_pad)
    de_max = disc_spring.cone_spring_max_external_diameter_mm(p.damper_pad.cols["outer_diameter_mm"])
    pad = np.repeat(np.arange(n_pads), len(real))
    r = np.tile(real, n_pads)
    de = de_max[pad] - ax["cone_spring_de_reduction_mm"][r]
    cone = [_cone_key(z, f, d) for z, f, d in zip(ax["cone_spring_aspect_ratio"][r], ax["cone_spring_deflection_ratio"][r],
                                                  de)]
    pf_parts["cone_spring"], cone_codes = _codes(cone)
    pf_parts["endcap_spacer_class"] = [str(k) for k in p.endcap_spacer.key]
    options["axial"] = {"endcap_spacer_class": np.concatenate([[-1], ax["spacer_code"][r]]).astype(np.int64),
                        "cone_spring": np.concatenate([[-1], cone_codes]).astype(np.int64)}
    rows["axial"] = np.concatenate([[none], r]).astype(np.int64)
    cost["axial"] = ax["cost_eur"][rows["axial"]].astype(float)
    spt = sp.tables["spring"]
    keys = [_spring_key(m, w, d) for m, w, d in zip(spt["main_spring_material"], spt["main_spring_wire"],
                                                    spt["main_spring_mean_body_diameter_mm"])]
    pf_parts["main_spring"], codes = _codes(keys)
    options["spring"] = {"main_spring": codes}
    rows["spring"] = np.arange(sp.n("spring"))
    cost["spring"] = spt["cost_eur_times_stiffness"].astype(float)
    bo = sp.tables["bolt"]
    keys = [_bolt_key(*k) for k in zip(bo["bolt_format"], bo["bolt_head_type"], bo["bolt_property_class"],
                                       bo["bolt_washer"], bo["bolt_tightening"])]
    pf_parts["bolt"], codes = _codes(keys)
    options["bolt"] = {"bolt": codes}
    rows["bolt"], cost["bolt"] = np.arange(sp.n("bolt")), bo["cost_eur"].astype(float)
    return Catalogue(space=sp, pf_parts=pf_parts, core_codes=core_codes, options=options, option_row=rows,
                     option_cost_eur=cost, axial_real=real, axial_none=0, n_pads=n_pads)


def catalogue() -> Catalogue:
    """The :class:`Catalogue` of the current catalog setting (cached like :func:`synth.design.space.space`)."""
    return _catalogue(tuple(catalog.user_dirs()))
