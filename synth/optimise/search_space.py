"""What a black-box search proposes for each subsystem: catalog choices with their lines, continuous dimensions.

The exact solvers search the tables of :mod:`synth.design.space`; a sampler
proposes one **choice** of one subsystem as a few integer parameters, and the
choice's option columns come from the space's own attribute functions (the
evaluator sees the same columns as for a table row). A choice carries the
**line** of its dimensions that change no score (no cost, no standard part),
on the exact solvers' grids, evaluated in the same vectorised call:

========== ============================================= ===============================================
subsystem  choice (the sampler's axis)                   line of options per choice
========== ============================================= ===============================================
bushing    ``row``: catalog row by supplier and length   one
axial      ``spacer`` (endcap spacer), ``de_step`` (outer h0/t x s/h0 grid (``optimise_cone_*``)
           diameter 0, 1, 2 mm below the pad's largest)
spring     ``stock``: (material, wire) pair the material mean body diameters of the housings' window
           is supplied in, by the moment its wire carries  (``optimise_mbd_step_mm``)
bolt       ``row``: catalog row by diameter, proof       one
           strength and head
========== ============================================= ===============================================

The sampler's axes run by size and strength, so neighbouring choices behave
alike; ``choices`` lists them cheapest first (the objective's additive
score), which the search uses to close the gap to its bound.

:func:`refinements` declares the dimensions that may be continuous: the cone
spring's h0/t and s/h0 within the grid ranges (a custom part designed from
Table 7's ranges, step 8) and the main spring's mean body diameter within the
housings' window (a torsion spring is wound on any mandrel; step 9's equations
take any value). The outer diameter of the cone spring stays on the
whole-millimetre steps of thesis step 8 (``cone_spring_od_round_down_mm``) and
the wire is a catalog stock: its cost, tolerances and strength are the
catalog's per size (EN 10270), and no source gives them between sizes.
:func:`snap_parts` moves a design's continuous values back to the nearest grid
point (the catalog snap a continuous result reports).

>>> from synth.data.generated_applications import generate
>>> from synth.optimise.product import evaluate
>>> ev = evaluate(generate(2, seed=0)[1], subsystems=False)
>>> v = variables(ev, {"cost": 1.0})
>>> sorted(v), list(v["spring"].distributions), v["bushing"].size
(['axial', 'bolt', 'bushing', 'spring'], ['stock'], 15)
>>> cols, owner = v["spring"].columns([{"stock": 0}, {"stock": 1}])
>>> len(cols["main_spring_mean_body_diameter_mm"]) == len(owner) == 2 * int((owner == 0).sum())
True
>>> refinements(ev)["spring"].columns({k: c[:1] for k, c in cols.items()}, [{"dm": 40.25}])["main_spring_mean_body_diameter_mm"]
array([40.25])
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Callable

import numpy as np

from synth.design.space import (SUBSYSTEMS, Space, axial_attributes, cone_variants, mbd_grid, spring_attributes,
                                spring_window)
from synth.optimise.batch import wsum
from synth.optimise.objectives import FALLBACK_WEIGHTS
from synth.optimise.product import option_scores
from synth.parts import arrays
from synth.design.space import NONE

__all__ = ["Variables", "Refinement", "variables", "refinements", "snap_parts"]


@dataclass
class Variables:
    """One subsystem's searched parameters (optuna distributions, in suggestion order) and how proposals become
    option columns: ``build`` returns the columns and, per column, the proposal it belongs to (a proposal may
    carry a line of options: the dimensions that change no score, on the exact solvers' grids). ``choices``
    lists every proposal, cheapest first, and ``scores`` their weighted scores."""

    table: str
    distributions: dict
    build: Callable[[dict], tuple]
    locate: Callable[[dict], dict | None]
    choices: list
    scores: np.ndarray

    @property
    def size(self) -> int:
        return len(self.choices)

    def columns(self, params: list) -> tuple[dict, np.ndarray]:
        """``(option columns, owner)`` of parameter dicts ``params`` (``owner[j]``: the proposal of column j)."""
        return self.build({k: np.array([p[k] for p in params]) for k in self.distributions})

    def key(self, params: dict) -> tuple:
        """A hashable identity of a proposal (equal proposals are evaluated once)."""
        return tuple(params[k] for k in self.distributions)


@dataclass
class Refinement:
    """The continuous dimensions of one subsystem's option (no score depends on them): distributions, and the
    option columns of a base option (one-row columns) with proposed values."""

    table: str
    distributions: dict
    build: Callable[[dict, dict], dict]

    def columns(self, base: dict, params: list) -> dict:
        return self.build(base, {k: np.array([p[k] for p in params], dtype=float) for k in self.distributions})


def _weighted(scores: dict, weights: dict) -> np.ndarray:
    return np.asarray(wsum(scores, weights), dtype=float)


def _rank(score: np.ndarray) -> np.ndarray:
    """Row order by score (stable: ties keep the catalog's order)."""
    return np.argsort(np.asarray(score, float), kind="stable")


def _nearest(grid: np.ndarray, x: float) -> int:
    return int(np.argmin(np.abs(np.asarray(grid, float) - float(x))))


def _int(n: int):
    import optuna
    return optuna.distributions.IntDistribution(0, int(n) - 1)


def _ranked(order: np.ndarray, score: np.ndarray, name: str) -> tuple[list, np.ndarray]:
    """``(choices, scores)``: the proposals ``{name: position}`` of the rows ``order`` (the sampler's axis),
    cheapest first."""
    cheap = _rank(score[order])
    return [{name: int(i)} for i in cheap], score[order][cheap]


def _table_rows(sp, table: str, weights: dict, match: tuple, axis: tuple) -> Variables:
    """A catalog table searched by the position of its rows along ``axis`` (columns, the first varying slowest):
    the part's size and strength, so that neighbours on the sampler's axis behave alike (bushing, bolt)."""
    score = _weighted(option_scores(sp, table), weights)
    t = sp.tables[table]
    order = np.lexsort(tuple(np.asarray(t[c], float) for c in reversed(axis)))

    def build(p):
        rows = order[p["row"]]
        return sp.rows(table, rows), np.arange(len(rows))

    def locate(attrs):
        hit = np.ones(len(order), dtype=bool)
        for col in match:
            hit &= np.isclose(np.asarray(t[col], float)[order], float(np.asarray(attrs[col])[0]))
        return {"row": int(np.flatnonzero(hit)[0])} if hit.any() else None
    return Variables(table, {"row": _int(len(order))}, build, locate, *_ranked(order, score, "row"))


def _dm_grid(p, window: tuple) -> np.ndarray:
    grid = mbd_grid(p)
    inside = grid[(grid >= window[0]) & (grid <= window[1])]
    return inside if len(inside) else grid[[_nearest(grid, 0.5 * (window[0] + window[1]))]]


def _spring(sp, weights: dict, stiffness: float, window: tuple) -> Variables:
    t = sp.tables["spring"]
    pair = t["material_code"] * 10_000 + t["wire_code"]
    _, first = np.unique(pair, return_index=True)   # one row per stock: its cost and section do not depend on Dm
    score = _weighted(option_scores(sp, "spring", stiffness, first), weights)
    # the sampler's axis: the elastic bending moment the wire carries, Rm I / (h/2) (eq. (69): the installation
    # stress is the torque over the section modulus), so neighbouring stocks load alike
    capacity = t["Rm_mpa"][first] * t["second_moment_mm4"][first] / (0.5 * t["h_mm"][first])
    axis = np.lexsort((t["material_code"][first], capacity))
    first, score = first[axis], score[axis]
    mat, wire = t["material_code"][first], t["wire_code"][first]
    p = sp.parts
    grid = _dm_grid(p, window)

    def build(q):
        stock = np.repeat(np.asarray(q["stock"], int), len(grid))
        return spring_attributes(p, mat[stock], wire[stock], np.tile(grid, len(q["stock"]))), \
            np.repeat(np.arange(len(q["stock"])), len(grid))

    def locate(attrs):
        hit = np.flatnonzero((mat == attrs["material_code"][0]) & (wire == attrs["wire_code"][0]))
        return {"stock": int(hit[0])} if len(hit) else None
    return Variables("spring", {"stock": _int(len(first))}, build, locate,
                     *_ranked(np.arange(len(first)), score, "stock"))


def _axial(sp, weights: dict) -> Variables:
    p = sp.parts
    zeta, phi, red = cone_variants()
    spacers = np.arange(len(p.endcap_spacer))
    one = axial_attributes(p, spacers, np.full(len(spacers), zeta[0]), np.full(len(spacers), phi[0]),
                           np.zeros(len(spacers)))
    score = _weighted(option_scores(Space({"axial": one}, p), "axial"), weights)
    rank = _rank(score)
    order, score = spacers[rank], score[rank]
    z, f = (a.ravel() for a in np.meshgrid(zeta, phi, indexing="ij"))

    def build(q):
        n, m = len(q["spacer"]), len(z)
        return axial_attributes(p, np.repeat(order[q["spacer"]], m), np.tile(z, n), np.tile(f, n),
                                np.repeat(red[np.asarray(q["de_step"], int)], m)), np.repeat(np.arange(n), m)

    def locate(attrs):
        hit = np.flatnonzero(order == attrs["spacer_code"][0])
        if not len(hit):
            return None
        return {"spacer": int(hit[0]), "de_step": _nearest(red, float(attrs["cone_spring_de_reduction_mm"][0]))}
    return Variables("axial", {"spacer": _int(len(order)), "de_step": _int(len(red))}, build, locate,
                     [{"spacer": i, "de_step": j} for i in range(len(order)) for j in range(len(red))],
                     np.repeat(score, len(red)))


def _window(ev) -> tuple:
    cv = ev.core.values
    return spring_window(float(np.min(cv["spring_housing_inner_diameter_mm"])),
                         float(np.max(cv["spring_housing_outer_diameter_mm"])))


def variables(ev, weights: dict) -> dict:
    """The searched variables of every subsystem for the application of ``ev`` (an evaluation of its cores,
    :func:`synth.optimise.product.evaluate` with ``subsystems=False``), catalog rows ranked by ``weights``
    (over the additive goals); the mean-diameter line spans the housings of the application's cores."""
    sp = ev.space
    w = weights or FALLBACK_WEIGHTS
    out = {"bushing": _table_rows(sp, "bushing", w, ("supplier_code", "pivot_bushing_length_mm"),
                                  ("supplier_code", "pivot_bushing_length_mm")),
           "axial": _axial(sp, w),
           "spring": _spring(sp, w, float(ev.apps.spring_stiffness_nm_per_deg[0]), _window(ev)),
           "bolt": _table_rows(sp, "bolt", w, ("head_code", "class_code"), ("bolt_d_mm", "rp02_mpa", "head_code"))}
    assert tuple(out) == SUBSYSTEMS
    return out


def refinements(ev) -> dict:
    """The continuous dimensions of the subsystems that have them: the main spring's mean body diameter over the
    housings' window, the cone spring's h0/t and s/h0 over the grid ranges (``constants_optimise.csv``)."""
    import optuna
    p = ev.space.parts
    zeta, phi, _ = cone_variants()
    lo, hi = _window(ev)
    grid = _dm_grid(p, (lo, hi))
    real = optuna.distributions.FloatDistribution

    def spring(base, q):
        n = len(q["dm"])
        return spring_attributes(p, np.repeat(base["material_code"], n), np.repeat(base["wire_code"], n), q["dm"])

    def axial(base, q):
        n = len(q["h0_t"])
        return axial_attributes(p, np.repeat(base["spacer_code"], n), q["h0_t"], q["s_h0"],
                                np.repeat(base["cone_spring_de_reduction_mm"], n),
                                np.repeat(base["cone_spring_di_increase_mm"], n))
    return {"spring": Refinement("spring", {"dm": real(float(min(lo, grid[0])), float(max(hi, grid[-1])))}, spring),
            "axial": Refinement("axial", {"h0_t": real(float(zeta[0]), float(zeta[-1])),
                                          "s_h0": real(float(phi[0]), float(phi[-1]))}, axial)}


def snap_parts(parts: dict) -> dict:
    """Design ``parts`` with the values a continuous search sets (the mean body diameter, the cone spring's h0/t
    and s/h0: :func:`refinements`) moved to the nearest point of the exact solvers' grids: mean body diameter (``optimise_mbd_step_mm``), cone-spring h0/t and s/h0
    (``optimise_cone_*``). A design without a cone spring keeps its zeros.

    >>> snap_parts({"main_spring_mean_body_diameter_mm": 40.4, "endcap_spacer_class": "none",
    ...             "cone_spring_aspect_ratio": 0.0, "cone_spring_deflection_ratio": 0.0})
    {'main_spring_mean_body_diameter_mm': 40.0, 'endcap_spacer_class': 'none', 'cone_spring_aspect_ratio': 0.0, 'cone_spring_deflection_ratio': 0.0}
    """
    out = dict(parts)
    grid = mbd_grid(arrays())
    out["main_spring_mean_body_diameter_mm"] = float(grid[_nearest(grid, parts["main_spring_mean_body_diameter_mm"])])
    if str(parts.get("endcap_spacer_class", NONE)) != NONE:
        zeta, phi, _ = cone_variants()
        out["cone_spring_aspect_ratio"] = float(zeta[_nearest(zeta, parts["cone_spring_aspect_ratio"])])
        out["cone_spring_deflection_ratio"] = float(phi[_nearest(phi, parts["cone_spring_deflection_ratio"])])
    return out

