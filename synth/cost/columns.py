"""The design space's cost columns, from a price book: the one place the optimiser's costs are made.

Every table of :mod:`synth.design.space` carries a cost column the searches add up (a core, one option per
subsystem): ``cost_eur`` of the core (bearing, damper pad and the main spring's per-spring term: every design
has one core and one main spring, and the spring's table keeps a cost per unit compliance), of a bushing
option, of an axial option (endcap spacer and cone spring) and of a bolt option, and the spring's
``cost_eur_times_stiffness`` (wire material and coiling, which scale with the wire length ``L = L k / k``: the
spring's cost is this over the application's stiffness, :meth:`synth.design.space.Space.spring_cost_eur`).
:func:`reprice` gives a space's tables the prices of another book (another annual volume) from the code columns
the tables carry, so that the searches run unchanged.

>>> from synth.parts import arrays
>>> p = arrays()
>>> float(core_eur(p.prices, [p.bearing.code("6006")], [-1])[0]) == float(p.prices.bearing[p.bearing.code("6006")]
...     + p.prices.spring_piece.eur)
True
"""

from __future__ import annotations

import numpy as np

from synth.cost.made import spring_length_times_stiffness_m

__all__ = ["core_eur", "bushing_eur", "axial_eur", "spring_eur_times_stiffness", "bolt_eur", "reprice"]


def core_eur(book, bearing_code, pad_code) -> np.ndarray:
    """Cost [EUR] of core rows: the bearing, the damper pad (code -1: none) and the main spring's per-spring term."""
    b, pad = np.asarray(bearing_code, np.int64), np.asarray(pad_code, np.int64)
    return book.bearing[b] + np.where(pad >= 0, book.damper_pad[np.maximum(pad, 0)], 0.0) + book.spring_piece.eur


def bushing_eur(book, supplier_code, length_mm) -> np.ndarray:
    """Cost [EUR] of bushing options: the supplier's per-part process and wall material, or a quote."""
    s, length = np.asarray(supplier_code, np.int64), np.asarray(length_mm, float)
    out = book.bushing_process.eur + book.bushing_per_mm[s] * length
    for (sup, q_len), p in book.bushing_quotes.items():
        out = np.where((s == sup) & np.isclose(length, q_len), p.eur, out)
    return out


def axial_eur(book, spacer_code) -> np.ndarray:
    """Cost [EUR] of axial options: the endcap spacer and the cone spring (code -1: no axial group, 0)."""
    e = np.asarray(spacer_code, np.int64)
    return np.where(e >= 0, book.endcap_spacer[np.maximum(e, 0)] + book.cone_spring.eur, 0.0)


def spring_eur_times_stiffness(book, material_code, wire_code, E_mpa, second_moment_mm4, area_mm2,
                               density_kg_m3) -> np.ndarray:
    """Wire cost x stiffness [EUR Nm/deg] of spring options: ``L k (rate_coiling + A rho price_kg f_section)``."""
    m, w = np.asarray(material_code, np.int64), np.asarray(wire_code, np.int64)
    lk = spring_length_times_stiffness_m(E_mpa, second_moment_mm4)
    kg_per_m = np.asarray(area_mm2, float) * 1e-6 * np.asarray(density_kg_m3, float)
    return lk * (book.coiling.eur + kg_per_m * book.spring_material[m] * book.wire_factor[w])


def bolt_eur(book, head_code, class_code, washer_code=-1, tightening_code=None) -> np.ndarray:
    """Cost [EUR] of bolt options: the screw (a format in a head form, a property class), its washer (code -1:
    none) and the tightening method's assembly premium (code None: the reference method, 0)."""
    w = np.asarray(washer_code, np.int64)
    out = book.bolt[np.asarray(head_code, np.int64), np.asarray(class_code, np.int64)] \
        + np.where(w >= 0, book.washer[np.maximum(w, 0)], 0.0)
    return out if tightening_code is None else out + book.tightening[np.asarray(tightening_code, np.int64)]


def reprice(book, tables: dict) -> dict:
    """``tables`` (of :class:`synth.design.space.Space`) with the cost columns of ``book``, from their code
    columns (the other columns shared, not copied)."""
    out = {name: dict(t) for name, t in tables.items()}
    c = out["core"]
    c["cost_eur"] = core_eur(book, c["bearing_code"], c["pad_code"])
    b = out["bushing"]
    b["cost_eur"] = bushing_eur(book, b["supplier_code"], b["pivot_bushing_length_mm"])
    a = out["axial"]
    a["cost_eur"] = axial_eur(book, a["spacer_code"])
    s = out["spring"]
    s["cost_eur_times_stiffness"] = spring_eur_times_stiffness(book, s["material_code"], s["wire_code"], s["E_mpa"],
                                                               s["second_moment_mm4"], s["wire_section_area_mm2"],
                                                               s["density_kg_m3"])
    o = out["bolt"]
    o["cost_eur"] = bolt_eur(book, o["head_code"], o["class_code"], o["washer_code"], o["tightening_code"])
    return out
