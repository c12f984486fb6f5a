"""The parametric assembly of one synthesised tensioner (thesis step 11).

:func:`build` turns a :class:`~synth.cad.dimensions.TensionerGeometry` into a
:class:`TensionerModel`: the named parts (``cadquery.Shape``, assembly frame),
their colours (``catalogs/cad_colours.csv``) and a ``cadquery.Assembly`` that
keeps names and colours in STEP. Product families: layout standard/reverse,
with or without the axial damping group (damper pad, endcap spacer, cone
spring), round or rectangular main-spring wire, single or double eccentric
pivot, flat or toothed pulley.

>>> from synth.cad.dimensions import geometry_from, _example_values, _example_inputs
>>> m = build(geometry_from(_example_values(), inputs=_example_inputs()))
>>> len(m.parts), "cone_spring" in m.parts, all(s.isValid() for s in m.parts.values())
(13, True, True)
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field

import cadquery as cq

from synth import catalog
from synth.cad.dimensions import TensionerGeometry
from synth.cad.solids import AXIAL_PARTS, PART_FUNCTIONS

__all__ = ["TensionerModel", "build", "part_names", "colour_of"]


def part_names(g: TensionerGeometry) -> list[str]:
    """The parts of the family of ``g`` (no axial damping: no pad, spacer, cone spring)."""
    return [n for n in PART_FUNCTIONS if g.axial_damping or n not in AXIAL_PARTS]


def colour_of(name: str) -> tuple:
    """``(r, g, b, a)`` of part ``name`` from ``catalogs/cad_colours.csv``."""
    r = catalog.row("cad_colours", name, "part")
    return (float(r["r"]), float(r["g"]), float(r["b"]), float(r["a"]))


@dataclass
class TensionerModel:
    """Parts of one tensioner in the assembly frame (z up from the crankcase face, pivot on the z axis)."""

    geometry: TensionerGeometry
    parts: dict
    build_s: float = 0.0
    timings: dict = field(default_factory=dict)

    def assembly(self, name: str | None = None) -> cq.Assembly:
        """A ``cadquery.Assembly`` (``name``, default ``tensioner_<layout>``), one named, coloured child per part."""
        a = cq.Assembly(name=name or f"tensioner_{self.geometry.layout}")
        for name, shape in self.parts.items():
            a.add(shape, name=name, color=cq.Color(*colour_of(name)))
        return a

    def compound(self, exclude=()) -> cq.Compound:
        return cq.Compound.makeCompound([s for n, s in self.parts.items() if n not in exclude])


def build(g: TensionerGeometry) -> TensionerModel:
    """Build every part of ``g`` (about 0.5 s for a case-1 tensioner)."""
    t0 = time.perf_counter()
    parts, timings = {}, {}
    for name in part_names(g):
        t = time.perf_counter()
        parts[name] = PART_FUNCTIONS[name](g)
        timings[name] = time.perf_counter() - t
    return TensionerModel(g, parts, time.perf_counter() - t0, timings)
