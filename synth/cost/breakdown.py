"""A design's price lines: one per part, each with its price, what it is (quoted, modelled, assumed) and its basis.

The lines are the price book's entries for the design's parts (:mod:`synth.cost.book`), so their sum is the
design's cost objective as the optimiser adds it from the design space's cost columns
(:mod:`synth.cost.columns`): ``tests/test_cost.py`` checks the two agree.

>>> from synth.scenes.demo import default_input
>>> from synth.optimise import solve
>>> d = default_input()
>>> r = solve(d, "cost")
>>> ls = lines(d, r.parts)
>>> bool(round(sum(x.eur for x in ls), 6) == r.objectives["cost"]), sorted({x.status for x in ls}) <= ["assumed", "modelled", "quoted"]
(True, True)
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from synth.cost import columns
from synth.cost.book import Priced, add_priced, book_for, volume_of
from synth.cost.made import spring_length_times_stiffness_m

__all__ = ["Line", "lines", "attributes", "summary"]


@dataclass(frozen=True)
class Line:
    """One part of a design: ``key`` (``family:name``, the same part has the same key in every design), ``label``
    (words), and its :class:`~synth.cost.book.Priced` (``eur``, ``status``, ``basis``, ``terms``)."""

    key: str
    label: str
    priced: Priced

    @property
    def eur(self) -> float:
        return self.priced.eur

    @property
    def status(self) -> str:
        return self.priced.status

    def as_dict(self) -> dict:
        sig = max((abs(s) for _, fs in self.priced.terms for _, s in fs), default=0.0)
        return {"part": self.key, "label": self.label, "price_eur": round(self.eur, 6), "status": self.status,
                "basis": self.priced.basis, "band_pct": round(100.0 * float(np.expm1(self._sigma())), 1),
                "largest_factor_sigma": round(sig, 4)}

    def _sigma(self) -> float:
        """One standard deviation of ln(price), the terms' factors independent (a first-order combination)."""
        if self.eur <= 0:
            return 0.0
        var = 0.0
        for e, fs in self.priced.terms:
            var += (e / self.eur) ** 2 * sum(s * s for _, s in fs)
        return float(np.sqrt(var))


def attributes(d, parts: dict):
    """``(book, attrs)``: the design ``parts``'s one-row table attributes priced at ``d``'s annual volume."""
    from synth.design.space import space
    sp = space()
    attrs = sp.design_attributes(parts)
    book = book_for(sp.parts, volume_of(d))
    return book, (attrs if book is sp.parts.prices else columns.reprice(book, attrs))


def lines(d, parts: dict) -> list:
    """The price lines of design ``parts`` for input ``d`` (its stiffness sizes the main spring, its annual
    volume selects the breaks)."""
    from synth.design.space import space
    p = space().parts
    book, a = attributes(d, parts)
    core, bush, axial, spring, bolt = (a[t] for t in ("core", "bushing", "axial", "spring", "bolt"))
    out = []
    b = int(core["bearing_code"][0])
    out.append(Line(f"ball_bearing:{p.bearing.key[b]}", f"ball bearing {p.bearing.key[b]}", book.bearing_info[b]))
    pad = int(core["pad_code"][0])
    if pad >= 0:
        out.append(Line(f"damper_pad:{p.damper_pad.key[pad]}", f"damper pad {p.damper_pad.key[pad]}",
                        book.damper_pad_info[pad]))
    s, length = int(bush["supplier_code"][0]), float(bush["pivot_bushing_length_mm"][0])
    out.append(Line(f"pivot_bushing:{p.bushing.key[s]} {length:g}", f"pivot bushing {p.bushing.key[s]} {length:g} mm",
                    book.bushing_priced(s, length)))
    e = int(axial["spacer_code"][0])
    if e >= 0:
        out.append(Line(f"endcap_spacer:{p.endcap_spacer.key[e]}", f"endcap spacer {p.endcap_spacer.key[e]}",
                        book.endcap_spacer_info[e]))
        out.append(Line("cone_spring", "cone spring", book.cone_spring))
    out.append(_spring_line(book, p, spring, float(d.spring_stiffness_nm_per_deg)))
    h, c = int(bolt["head_code"][0]), int(bolt["class_code"][0])
    out.append(Line(f"bolt:{p.bolt_head.key[h]} {p.bolt_class.key[c]}",
                    f"bolt {p.bolt_head.key[h]} {p.bolt_class.key[c]}", book.bolt_info[(h, c)]))
    w = int(bolt["washer_code"][0])
    if w >= 0:
        out.append(Line(f"washer:{p.washer.key[w]}", f"washer {p.washer.key[w]}", book.washer_info[w]))
    t = int(bolt["tightening_code"][0])
    if book.tightening[t] > 0.0:
        out.append(Line(f"tightening:{p.tightening.key[t]}", f"tightening {p.tightening.key[t]} (assembly premium)",
                        book.tightening_info[t]))
    return out


def _spring_line(book, p, spring: dict, k: float) -> Line:
    m, w = int(spring["material_code"][0]), int(spring["wire_code"][0])
    length = float(spring_length_times_stiffness_m(spring["E_mpa"][0], spring["second_moment_mm4"][0])) / max(k, 1e-12)
    kg = length * float(spring["wire_section_area_mm2"][0]) * 1e-6 * float(spring["density_kg_m3"][0])
    f = float(book.wire_factor[w])
    mat = book.spring_material_info[m].scaled(kg * f)
    if f != 1.0:
        from synth import catalog
        mat = Priced(mat.eur, mat.status, mat.basis, tuple((eur, fs + (("factor:wire_rectangular",
                     catalog.constant("cost_assumed_factor_scatter")),)) for eur, fs in mat.terms))
    coil = book.coiling.scaled(length)
    mbd = float(spring["main_spring_mean_body_diameter_mm"][0])
    key = f"main_spring:{p.spring_material.key[m]} {p.spring_wire.key[w]}"  # its price: whatever its mean diameter
    return Line(key, f"main spring {p.spring_material.key[m]} {p.spring_wire.key[w]} (Dm {mbd:g} mm)",
                add_priced(mat, coil, book.spring_piece, status="modelled",
                     basis=f"wire {length:.3f} m, {1000 * kg:.1f} g x {book.spring_material[m]:.3g} EUR/kg"
                           + (f" x {f:g} (rectangular)" if f != 1.0 else "")
                           + f" + coiling {book.coiling.eur:.3g} EUR/m + {book.spring_piece.eur:.3g} EUR per spring"))


def summary(ls: list) -> dict:
    """``{"cost_eur", "counts": {status: n}, "lines": [...]}`` of price lines ``ls``."""
    counts = {s: sum(1 for x in ls if x.status == s) for s in ("quoted", "modelled", "assumed")}
    return {"cost_eur": round(sum(x.eur for x in ls), 6), "counts": counts, "lines": [x.as_dict() for x in ls]}
