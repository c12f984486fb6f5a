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
from synth.model import disc_spring as s8

__all__ = ["Catalogue", "catalogue"]


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
    keys = [f"{s} {_num(L)} mm" for s, L in zip(bu["pivot_bushing_supplier"], bu["pivot_bushing_length_mm"])]
    pf_parts["pivot_bushing"], codes = _codes(keys)
    options["bushing"] = {"pivot_bushing": codes}
    rows["bushing"], cost["bushing"] = np.arange(sp.n("bushing")), bu["cost_eur"].astype(float)
    # axial: "none", then one block of the real rows per damper pad (the cone spring's absolute diameter)
    ax = sp.tables["axial"]
    real = np.flatnonzero(ax["axial_group_present"])
    none = int(np.flatnonzero(~ax["axial_group_present"])[0])
    n_pads = len(p.damper_pad)
    de_max = s8.cone_spring_max_external_diameter_mm(p.damper_pad.cols["outer_diameter_mm"])
    pad = np.repeat(np.arange(n_pads), len(real))
    r = np.tile(real, n_pads)
    de = de_max[pad] - ax["cone_spring_de_reduction_mm"][r]
    cone = [f"h0/t {_num(z)}, s/h0 {_num(f)}, De {_num(round(d, 6))} mm"
            for z, f, d in zip(ax["cone_spring_aspect_ratio"][r], ax["cone_spring_deflection_ratio"][r], de)]
    pf_parts["cone_spring"], cone_codes = _codes(cone)
    pf_parts["endcap_spacer_class"] = [str(k) for k in p.endcap_spacer.key]
    options["axial"] = {"endcap_spacer_class": np.concatenate([[-1], ax["spacer_code"][r]]).astype(np.int64),
                        "cone_spring": np.concatenate([[-1], cone_codes]).astype(np.int64)}
    rows["axial"] = np.concatenate([[none], r]).astype(np.int64)
    cost["axial"] = ax["cost_eur"][rows["axial"]].astype(float)
    spt = sp.tables["spring"]
    keys = [f"{m} {w} Dm {_num(d)} mm" for m, w, d in zip(spt["main_spring_material"], spt["main_spring_wire"],
                                                         spt["main_spring_mean_body_diameter_mm"])]
    pf_parts["main_spring"], codes = _codes(keys)
    options["spring"] = {"main_spring": codes}
    rows["spring"] = np.arange(sp.n("spring"))
    cost["spring"] = spt["cost_eur_times_stiffness"].astype(float)
    bo = sp.tables["bolt"]
    keys = [f"{f} {h} {c}" for f, h, c in zip(bo["bolt_format"], bo["bolt_head_type"], bo["bolt_property_class"])]
    pf_parts["bolt"], codes = _codes(keys)
    options["bolt"] = {"bolt": codes}
    rows["bolt"], cost["bolt"] = np.arange(sp.n("bolt")), bo["cost_eur"].astype(float)
    return Catalogue(space=sp, pf_parts=pf_parts, core_codes=core_codes, options=options, option_row=rows,
                     option_cost_eur=cost, axial_real=real, axial_none=0, n_pads=n_pads)


def catalogue() -> Catalogue:
    """The :class:`Catalogue` of the current catalog setting (cached like :func:`synth.design.space.space`)."""
    return _catalogue(tuple(catalog._user_dirs()))
