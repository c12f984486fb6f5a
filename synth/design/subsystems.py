"""The part families of a design beside its core, each one declaration: :class:`Subsystem`.

A subsystem is a family of parts whose constraints involve only the application, the core and its own choice
(:mod:`synth.design.space`'s decomposition). Its declaration says, in one place:

* ``name``: its option table in the design space and its group in the registry (:mod:`synth.design.constraints`);
* ``part_keys``: the part keys of a design it sets (one vocabulary: input file, results, JSON, Excel, CAD);
* ``match``: which options a core may take: ``(core value, option column)`` pairs that must be equal (the bushing:
  the core's supplier; the axial group: present with a damper pad, absent without), none: every option;
* ``evaluate``: its group over ``(core row x option)`` pairs, as a :class:`SubTable` and the number of pairs the
  evaluator computed (the main spring: once per distinct key, within the housings' window);
* what its group reads of the core (:meth:`Subsystem.core_reads`): the group function's declared inputs and every
  registered check's physics parameters (:func:`synth.design.group.core_values`), derived, never kept by hand.

Its scores are the declared goals' (:func:`synth.optimise.objectives.additive_goals`: a goal scores any table by
its name). :func:`declared` lists the declarations in the order every search and result takes them; the design
space's :data:`~synth.design.space.SUBSYSTEMS` and :data:`~synth.design.space.PART_KEYS_BY_TABLE`, the catalog
product (:func:`synth.optimise.product.subsystem`) and the part keys of a design
(:func:`synth.design.verify.parts_of_design`) read them.

>>> [s.name for s in declared()]
['bushing', 'axial', 'spring', 'bolt']
>>> family("bushing").core_reads(["hubload_nominal_n", "pivot_diameter_mm", "axial_group_present"])
('hubload_nominal_n', 'pivot_diameter_mm', 'axial_group_present')
"""

from __future__ import annotations

import dataclasses

from dataclasses import dataclass
from typing import Callable

import numpy as np

from synth.design.evaluate import (SPRING_OPTION_COLUMNS, Group, axial_judged, bolt, bushing, fixation_values, spring,
                                   spring_keys)
from synth.design.bolt_group import bolt_codes
from synth.design.group import core_values

__all__ = ["SubTable", "Subsystem", "declared", "CORE_PART_KEYS", "family", "names", "declare", "withdraw",
           "scatter", "pairs", "spring_window", "pinned_diameter", "SPRING_BLOCK_PAIRS", "evaluate_axial"]

#: (key, option) pairs of main springs evaluated per block (bounds the memory of one evaluation)
SPRING_BLOCK_PAIRS = 200_000

#: the part keys of a design's core (the choices that set the damping split and the damper pad)
CORE_PART_KEYS = ("ball_bearing", "pivot_class_diameter_mm", "pivot_bushing_supplier", "damper_pad_class")


@dataclass
class SubTable:
    """One subsystem over ``(n_rows, n_options)``: availability, feasibility and margins of each pair."""

    available: np.ndarray
    feasible: np.ndarray
    margin: np.ndarray          # smallest margin counted in the margin objective (+inf: none counted)
    min_margin: np.ndarray      # smallest margin of every non-advisory constraint (the nearest design)
    #: the second smallest margin and the number of failing checks of every non-advisory constraint (with
    #: ``min_margin`` the option's near figures: :func:`synth.design.combine.near_figures`)
    second: np.ndarray | None = None
    fails: np.ndarray | None = None

    def near(self) -> tuple:
        """``(smallest, second, failing, available)``: what :func:`synth.design.combine.nearest_choice` reads."""
        return self.min_margin, self.second, self.fails, self.available

    def take(self, idx) -> "SubTable":
        """The rows ``idx`` (an index array or a slice) of every column."""
        return SubTable(**{f.name: None if getattr(self, f.name) is None else getattr(self, f.name)[idx]
                           for f in dataclasses.fields(self)})


@dataclass(frozen=True)
class Subsystem:
    """One part family beside the core (see the module docstring)."""

    name: str
    part_keys: tuple
    #: ``(core value, option column)`` pairs an available option matches; () : every option is available
    match: tuple
    #: ``(apps, sp, cg, pos, settings, subsystem, span=None) -> (SubTable, evaluations)``: its group over the core
    #: rows ``pos`` of core group ``cg`` and every option of ``sp``'s table ``name`` (``span``: the core rows whose
    #: housings bound the main springs searched, default ``pos``: a part of the cores keeps the whole's options)
    evaluate: Callable
    #: ``(apps, cg, core_rows, option_columns, settings) -> Group``: its group over (core row, option) pairs, for a
    #: family whose pairs are judged one by one (the bushing, the axial group): the scans of
    #: :class:`synth.optimise.batch.Batch` call it on the available options of each distinct core key; None: the
    #: family has its own scans (the main spring by key, the bolt per application)
    group: Callable | None = None

    def core_reads(self, core) -> tuple:
        """What its group reads of its core row (``core``: a core group's values, or their names)."""
        return core_values(self.name, core)

    def allows(self, sp, core_values: dict, rows, options) -> np.ndarray:
        """Whether core rows ``rows`` may take options ``options`` of ``sp``'s table (index arrays, broadcast
        against each other): every ``match`` pair equal. A re-declaration narrows it here: every search asks this."""
        t = sp.tables[self.name]
        out = np.ones(np.broadcast_shapes(np.shape(rows), np.shape(options)), dtype=bool)
        for cv, col in self.match:
            out &= np.asarray(core_values[cv])[rows] == np.asarray(t[col])[options]
        return out

    def available(self, sp, core_values: dict, pos) -> np.ndarray:
        """``(len(pos), options)``: which options of ``sp``'s table core rows ``pos`` may take."""
        return self.allows(sp, core_values, np.asarray(pos)[:, None], np.arange(sp.n(self.name))[None, :])

    def run(self, apps, sp, cg: Group, pos, settings, span=None) -> tuple[SubTable, int]:
        """Its :class:`SubTable` over ``(len(pos), options)`` and the number of pairs the evaluator computed."""
        return self.evaluate(apps, sp, cg, pos, settings, self, span=span)


def scatter(avail, i, k, g: Group, row=None) -> SubTable:
    """The :class:`SubTable` of group ``g`` evaluated at the available pairs ``(i, k)`` of ``avail`` (``row``: the
    row of ``g`` of each pair, where pairs the group reads alike share one; default row ``j`` for pair ``j``)."""
    shape = avail.shape
    feas = np.zeros(shape, dtype=bool)
    marg = np.full(shape, -np.inf)
    mmin, second, fails = np.full(shape, -np.inf), np.full(shape, -np.inf), np.zeros(shape)
    at = (lambda x: x) if row is None else (lambda x: x[row])  # noqa: E731
    a = g.assessment()
    feas[i, k], marg[i, k] = at(a.ok), at(a.objective_margin)
    # nearest: ranked by the search model
    mmin[i, k], second[i, k], fails[i, k] = (at(x) for x in (a if g.rank() is g else g.rank().assessment()).near)
    return SubTable(avail, feas & avail, marg, mmin, second, fails)


def pairs(apps, sp, cg, pos, settings, sub, group_fn=None, span=None) -> tuple[SubTable, int]:
    """The evaluation of a family judged pair by pair: its group (``group_fn``, else the declared one) over the
    available (core row, option) pairs, in one call."""
    avail = sub.available(sp, cg.values, pos)
    i, k = np.nonzero(avail)
    out = scatter(avail, i, k, (group_fn or sub.group)(apps, cg, pos[i], sp.rows(sub.name, k), settings))
    return out, int(avail.sum())


def evaluate_axial(group_fn):
    """The axial group's evaluation with group function ``group_fn`` (the screened-then-judged search model, or the
    full model: :func:`synth.design.evaluate.axial_full`)."""
    def run(apps, sp, cg, pos, settings, sub, span=None):
        return pairs(apps, sp, cg, pos, settings, sub, group_fn)
    return run


def _bolt(apps, sp, cg, pos, settings, sub, span=None):
    """Every bolt against core rows ``pos``: the group once per core row and bolt as it reads it
    (:func:`~synth.design.bolt_group.bolt_codes`: bolts equal in every column it reads have the same values and
    margins), each pair given its key's figures."""
    nk = sp.n(sub.name)
    code, first = bolt_codes(sp.tables[sub.name], settings)
    nc = len(first)
    opts = sp.rows(sub.name, first)
    fix = fixation_values(apps, np.zeros(nc, dtype=np.int64), opts, settings)  # per bolt key: no core dependence
    i, c = (x.ravel() for x in np.meshgrid(np.arange(len(pos)), np.arange(nc), indexing="ij"))
    g = bolt(apps, cg, pos[i], sp.rows(sub.name, first[c]), settings, fixation={key: v[c] for key, v in fix.items()})
    i, k = (x.ravel() for x in np.meshgrid(np.arange(len(pos)), np.arange(nk), indexing="ij"))
    out = scatter(sub.available(sp, cg.values, pos), i, k, g, row=i * nc + code[k])
    return out, int(out.available.sum())


def pinned_diameter(sp) -> bool:
    """Whether ``sp`` keeps a mean body diameter the input names: its springs are then searched whatever the
    housing (the spring checks say where it does not fit), not only within :func:`spring_window`."""
    return "main_spring_mean_body_diameter_mm" in sp.pinned


def spring_window(housing_inner_mm, housing_outer_mm):
    """``(lo, hi)`` [mm]: the mean body diameters searched for a housing (elementwise): from the inner diameter
    rounded down to the outer rounded up, 1e-9 mm wider so that grid values on the bounds stay in."""
    return np.floor(housing_inner_mm) - 1e-9, np.ceil(housing_outer_mm) + 1e-9


def _spring(apps, sp, cg, pos, settings, sub, span=None):
    nk = sp.n(sub.name)
    keys = spring_keys(cg, pos)  # the key: torque, housing height and diameters, and what else its checks read
    cols = [k for k in keys if k != "app"]
    stack = np.stack([np.asarray(keys[k], dtype=float) for k in cols], axis=1)
    uniq, inv = np.unique(stack, axis=0, return_inverse=True)
    inv = np.asarray(inv).reshape(-1)
    if not len(uniq):
        empty = np.zeros((0, nk), dtype=bool)
        return SubTable(empty, empty, *(np.zeros((0, nk)) for _ in range(4))), 0
    t = sp.tables[sub.name]
    mbd = t["main_spring_mean_body_diameter_mm"]
    ukeys = {"app": np.zeros(len(uniq), dtype=np.int64), **{k: uniq[:, j] for j, k in enumerate(cols)}}
    around = pos if span is None else span  # the cores whose housings bound the springs searched
    lo, hi = spring_window(np.min(cg.values["spring_housing_inner_diameter_mm"][around]),
                           np.max(cg.values["spring_housing_outer_diameter_mm"][around]))
    opts_idx = np.flatnonzero((mbd >= lo) & (mbd <= hi) | pinned_diameter(sp))
    shape = (len(uniq), nk)
    feas = np.zeros(shape, dtype=bool)
    marg = np.full(shape, -np.inf)
    mmin, second, fails = np.full(shape, -np.inf), np.full(shape, -np.inf), np.zeros(shape)
    avail = np.zeros(shape, dtype=bool)
    avail[:, opts_idx] = True
    block = max(1, SPRING_BLOCK_PAIRS // max(len(uniq), 1))
    count = 0
    for start in range(0, len(opts_idx), block):
        oi = opts_idx[start:start + block]
        kk, oo = (x.ravel() for x in np.meshgrid(np.arange(len(uniq)), oi, indexing="ij"))
        g = spring(apps, ukeys, kk, {c: t[c][oo] for c in SPRING_OPTION_COLUMNS}, settings)
        a = g.assessment()
        feas[kk, oo], marg[kk, oo] = a.ok, a.objective_margin
        mmin[kk, oo], second[kk, oo], fails[kk, oo] = a.near
        count += len(kk)
    return SubTable(avail[inv], feas[inv], marg[inv], mmin[inv], second[inv], fails[inv]), count


_DECLARED: dict = {}


def declare(sub: Subsystem) -> Subsystem:
    """Declare part family ``sub`` (a name already declared is replaced in place: its order kept). Returns it."""
    _DECLARED[sub.name] = sub
    return sub


def withdraw(name: str) -> None:
    """Withdraw the declaration of part family ``name`` (a test's toy family)."""
    _DECLARED.pop(name, None)


def declared() -> tuple:
    """The declared part families, in the order every search and result takes them."""
    return tuple(_DECLARED.values())


def family(name: str) -> Subsystem:
    """The declaration of part family ``name``."""
    return _DECLARED[name]


def names() -> tuple:
    """The declared part families' names, in order."""
    return tuple(_DECLARED)


declare(Subsystem("bushing", ("pivot_bushing_length_mm",), (("supplier_code", "supplier_code"),), pairs, bushing))
declare(Subsystem("axial", ("endcap_spacer_class", "cone_spring_aspect_ratio", "cone_spring_deflection_ratio",
                            "cone_spring_external_diameter_mm", "cone_spring_internal_diameter_mm"),
                  (("axial_group_present", "axial_group_present"),), pairs, axial_judged))
declare(Subsystem("spring", ("main_spring_material", "main_spring_wire", "main_spring_mean_body_diameter_mm"), (),
                  _spring))
declare(Subsystem("bolt", ("bolt_format", "bolt_head_type", "bolt_property_class", "bolt_washer", "bolt_tightening"),
                  (), _bolt))

