"""Bought-in parts: the relations that price a catalog part from one reference price of its family.

A dealer's or distributor's list gives relative prices where it gives no absolute euro figure; the relation
carries them to every catalog size from the one reference row the user replaces (``catalogs/prices.csv``,
``reference`` true):

* **ball bearing**: ``price = p_ref (m / m_ref)^b s(v) / s(v_ref)``, with ``m`` the ring-envelope mass
  ``rho pi/4 (D^2 - d^2) B`` (the real mass is a constant fraction of it for one bearing type, which the ratio
  cancels), ``b`` = ``cost_bearing_mass_exponent`` and ``s`` the seal factor of the variant (open, ``-Z``,
  ``-2Z``, ``-RS1``, ``-2RS1``; ``/C3`` costs nothing), both fitted to the SKF dealer list of 1 Dec 2022
  (``tests/validation/test_cost_skf_list.py``; scatter ``cost_bearing_fit_scatter``);
* **bolt**: ``price = p_ref (m / m_ref)^b f_pitch f_class``, ``m`` the mass of the screw at the nominal length
  ``cost_bolt_nominal_length_mm`` (shank and head), ``b`` = ``cost_fastener_mass_exponent`` fitted to a fastener
  distributor's M8 list (``tests/validation/test_cost_fastener_list.py``), ``f_pitch`` the assumed fine-pitch
  factor, ``f_class`` the property class's ``unit_cost_factor`` (assumed);
* **quantity**: a relation price at an annual volume ``V`` other than the reference's break quantity ``q`` is
  scaled by ``c(V) / c(q)``, ``c`` the distributor's break curve (``catalogs/price_breaks.csv``).

>>> round(float(bearing_envelope_mass_kg(30, 55, 13)), 4)
0.1703
>>> round(float(relation_price(1.0, 0.4, 0.2, 0.5)), 4)
1.4142
>>> seal_variant("6205-2RS1/C3"), seal_variant("6006")
(('6205', '2RS1'), ('6006', ''))
"""

from __future__ import annotations

import math

import numpy as np

__all__ = ["SEALS", "bearing_envelope_mass_kg", "seal_variant", "relation_price", "bolt_mass_kg",
           "quantity_factor"]

#: the seal and shield variants of a deep groove ball bearing's designation suffix (SKF: -Z, -2Z, -RS1, -2RS1)
SEALS = ("Z", "2Z", "RS1", "2RS1")


def bearing_envelope_mass_kg(d_mm, D_mm, B_mm, density_kg_m3=7850.0):
    """Mass [kg] of the ring envelope of a radial bearing: ``rho pi/4 (D^2 - d^2) B``.

    A size measure proportional to a bearing's mass within one type (the balls and the rings' grooves fill a
    nearly constant fraction of the envelope); ``d``, ``D``, ``B`` [mm] the boundary dimensions (ISO 15).

    >>> round(float(bearing_envelope_mass_kg(25, 52, 15)), 4)
    0.1923
    """
    return density_kg_m3 * np.pi / 4.0 * (np.asarray(D_mm, float) ** 2 - np.asarray(d_mm, float) ** 2) \
        * np.asarray(B_mm, float) * 1e-9


def seal_variant(designation: str) -> tuple:
    """``(base designation, seal variant)`` of a bearing designation: the variant is ``Z``, ``2Z``, ``RS1`` or
    ``2RS1`` after a hyphen, ``""`` without one; a ``/`` suffix (clearance, ``/C3``) is dropped (it costs
    nothing)."""
    text = str(designation).strip().split("/")[0]
    base, _, suffix = text.partition("-")
    return base.strip(), suffix.strip().upper() if suffix.strip().upper() in SEALS else ""


def relation_price(p_ref: float, size, size_ref: float, exponent: float):
    """``p_ref (size / size_ref)^exponent``: the price of a part of ``size`` by a power relation anchored at the
    reference part (``size_ref``, price ``p_ref``)."""
    return p_ref * (np.asarray(size, float) / size_ref) ** exponent


def bolt_mass_kg(d_mm, length_mm, head_outer_mm, head_height_mm, hexagon, density_kg_m3=7850.0):
    """Mass [kg] of a screw: the shank ``pi/4 d^2 L`` and the head, a hexagonal prism ``sqrt(3)/2 s^2 k``
    (``hexagon`` True: ``head_outer`` is the width across flats ``s``) or a cylinder ``pi/4 D^2 k`` (a flange or a
    socket head: ``head_outer`` its diameter), ``k`` the head height. The thread's root is not deducted (a few
    per cent, the same for every screw of one pitch family).

    >>> round(float(bolt_mass_kg(8, 45, 13, 5.3, True)) * 1000, 2)
    23.85
    """
    d, length = np.asarray(d_mm, float), np.asarray(length_mm, float)
    s, k = np.asarray(head_outer_mm, float), np.asarray(head_height_mm, float)
    head = np.where(np.asarray(hexagon, bool), math.sqrt(3.0) / 2.0 * s ** 2, np.pi / 4.0 * s ** 2) * k
    return density_kg_m3 * (np.pi / 4.0 * d ** 2 * length + head) * 1e-9


def quantity_factor(volume: float, quantity: float, curve: tuple) -> tuple:
    """``(c(volume) / c(quantity), scatter)``: the distributor's break curve ``curve`` (``((break quantity,
    factor, scatter), ...)`` ascending, :data:`catalogs/price_breaks.csv`) carried from the reference's break
    ``quantity`` to ``volume``; ``c(q)`` the factor of the largest break not above ``q``; ``scatter`` the larger
    of the two breaks' (0 when both fall in one break).

    >>> curve = ((1, 1.0, 0.0), (100, 0.8, 0.24), (1000, 0.52, 0.06), (10000, 0.5, 0.001))
    >>> quantity_factor(500, 100000, curve), quantity_factor(50000, 100000, curve)
    ((1.6, 0.24), (1.0, 0.0))
    """
    def pick(q):
        hit = curve[0]
        for row in curve:
            if row[0] <= q:
                hit = row
        return hit
    a, b = pick(volume), pick(quantity)
    if a is b:
        return 1.0, 0.0
    return a[1] / b[1], max(a[2], b[2])
