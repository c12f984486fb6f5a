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
from synth.cad.solids import AXIAL_PARTS, PART_FUNCTIONS, NotBuildable

__all__ = ["TensionerModel", "build", "part_names", "colour_of", "kernel_failure"]


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
    #: part name -> why it was not built (:class:`~synth.cad.solids.NotBuildable`, a CAD-kernel failure, an
    #: invalid solid); the ``cad_solids`` check fails naming them, and the model holds the other parts
    unbuilt: dict = field(default_factory=dict)

    def assembly(self, name: str | None = None) -> cq.Assembly:
        """A ``cadquery.Assembly`` (``name``, default ``tensioner_<layout>``), one named, coloured child per part."""
        a = cq.Assembly(name=name or f"tensioner_{self.geometry.layout}")
        for name, shape in self.parts.items():
            a.add(shape, name=name, color=cq.Color(*colour_of(name)))
        return a

    def compound(self, exclude=()) -> cq.Compound:
        return cq.Compound.makeCompound([s for n, s in self.parts.items() if n not in exclude])


def build(g: TensionerGeometry) -> TensionerModel:
    """Build every part of ``g`` (about 0.5 s for a case-1 tensioner).

    A part whose geometry the CAD kernel cannot make (OCCT's ``StdFail_NotDone`` on a sweep, an invalid solid)
    or that describes no solid (:class:`~synth.cad.solids.NotBuildable`) is left out and recorded in
    :attr:`TensionerModel.unbuilt`: a design's geometry is a verdict (the ``cad_solids`` check fails, exit 1),
    never an internal error.
    """
    t0 = time.perf_counter()
    parts, timings, unbuilt = {}, {}, {}
    for name in part_names(g):
        t = time.perf_counter()
        try:
            shape = PART_FUNCTIONS[name](g)
            if not shape.isValid():
                raise NotBuildable("the CAD kernel made an invalid solid of it")
            parts[name] = shape
        except NotBuildable as exc:
            unbuilt[name] = str(exc)
        except Exception as exc:  # noqa: BLE001 - only the kernel's own failures become a verdict
            if not kernel_failure(exc):
                raise
            unbuilt[name] = f"the CAD kernel could not build it ({type(exc).__name__}: {' '.join(str(exc).split())[:200]})"
        timings[name] = time.perf_counter() - t
    return TensionerModel(g, parts, time.perf_counter() - t0, timings, unbuilt)


def kernel_failure(exc: BaseException) -> bool:
    """Whether ``exc`` is the CAD kernel's failure on a geometry: an OCCT exception (``StdFail_NotDone``,
    ``Standard_ConstructionError``...: OCP's classes), or an error raised inside CadQuery or OCP themselves
    (``ValueError: Null TopoDS_Shape``), not in synth's own code."""
    if type(exc).__module__.split(".")[0] == "OCP":  # OCP.OCP.StdFail.StdFail_NotDone...
        return True
    tb = exc.__traceback__
    last = None
    while tb is not None:
        last = tb.tb_frame.f_code.co_filename
        tb = tb.tb_next
    return last is not None and any(f"{sep}{pkg}{sep}" in last for pkg in ("cadquery", "OCP")
                                    for sep in ("/", "\\"))
