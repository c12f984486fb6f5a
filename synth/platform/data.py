"""The feasibility data a platform is chosen from: which designs each application accepts.

The design space of one application is decomposed (:mod:`synth.optimise.space`): a
**core** (ball bearing x pivot class x bushing supplier x damper pad class) and four
**subsystems** whose options are independent given the core. A design is one feasible
core plus one feasible option per subsystem. Feasibility of an option depends on the
core only through a **group** id: cores of one application with the same group id for a
subsystem accept the same options of that subsystem.

Part families (the vocabulary of the platform, :data:`FAMILIES`):

=========================== ========== ==================================================
family                      belongs to part key
=========================== ========== ==================================================
``ball_bearing``            core       catalog designation
``pivot_class_diameter_mm`` core       pivot class diameter [mm]
``damper_pad_class``        core       pad class (code ``-1``: no pad, no part)
``pivot_bushing``           bushing    supplier and length, e.g. ``"A/12"``
``endcap_spacer_class``     axial      spacer class (``-1`` in the "no axial group" option)
``cone_spring``             axial      cone-spring variant id (``-1`` likewise)
``main_spring``             spring     material, wire and mean body diameter: a spring
                                       variant is its wire and winding tooling
``bolt``                    bolt       format and property class
=========================== ========== ==================================================

The active coil count of a main spring is not a part: it follows each application's
torsional stiffness (thesis step 9) on the same wire, mandrel and tooling, so two
applications with different stiffness share the spring variant. The bushing supplier is
not a part either: it is a property of the core that restricts the bushing options (only
the supplier's own lengths are available), and the bushing part names it.

The producer of these data (the vectorised evaluator run over a portfolio) fills the
dataclasses below; :func:`validate` checks a producer's output and names what is wrong.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from synth.errors import InputError, Problem

__all__ = ["FAMILIES", "CORE_FAMILIES", "SUBSYSTEM_FAMILIES", "SUBSYSTEMS", "NO_PART",
           "AppFeasibility", "PortfolioFeasibility", "validate", "default_weights", "default_fixed_costs"]

#: core part families
CORE_FAMILIES = ("ball_bearing", "pivot_class_diameter_mm", "damper_pad_class")
#: subsystem -> the part families of its options
SUBSYSTEM_FAMILIES = {"bushing": ("pivot_bushing",), "axial": ("endcap_spacer_class", "cone_spring"),
                      "spring": ("main_spring",), "bolt": ("bolt",)}
SUBSYSTEMS = tuple(SUBSYSTEM_FAMILIES)
#: every part family, in report order
FAMILIES = CORE_FAMILIES + tuple(f for fs in SUBSYSTEM_FAMILIES.values() for f in fs)
#: part code meaning "no part of this family" (no damper pad; no axial group)
NO_PART = -1


@dataclass
class AppFeasibility:
    """The feasible designs of one application.

    ``n_c`` is the number of feasible cores (cores failing their own constraints are
    left out by the producer). Arrays are numpy; group ids index the lists of
    ``feasible`` (so ``group[s].max() < len(feasible[s])``).

    * ``core_parts[f]``: ``(n_c,)`` part code of family ``f`` per core (``-1``: no part);
    * ``core_cost_eur``: ``(n_c,)`` unit cost of the core's parts;
    * ``core_margin``: ``(n_c,)`` smallest margin of the core's own constraints;
    * ``group[s]``: ``(n_c,)`` group id of each core for subsystem ``s``;
    * ``feasible[s][g]``: indices (into the portfolio's option table of ``s``) of the
      options feasible with the cores of group ``g``; may be empty;
    * ``option_margin[s][g]``: the smallest margin of each of those options (same shape);
    * ``volume``: units per year (weights unit costs in the cost objective);
    * ``option_cost_eur[s]``: optional ``(n_options,)`` unit cost of every option of ``s``
      for this application (e.g. a main spring's cost follows its coil count); the
      portfolio's ``option_cost_eur`` otherwise;
    * ``core_binding`` / ``option_binding``: optional names of the binding constraint
      (same shapes as the margins), reported in ``assignment.csv``;
    * ``note``: why the application has no feasible design, when it has none;
    * ``core_rows``: optional ``(n_c,)`` row of each core in the design space's core table
      (:mod:`synth.design.space`; real data only: how a design is rebuilt and verified).
    """

    app_id: str
    core_parts: dict
    core_cost_eur: np.ndarray
    core_margin: np.ndarray
    group: dict
    feasible: dict
    option_margin: dict
    volume: float = 1.0
    option_cost_eur: dict | None = None
    core_binding: np.ndarray | None = None
    option_binding: dict | None = None
    note: str = ""
    core_rows: np.ndarray | None = None

    @property
    def n_cores(self) -> int:
        return int(len(self.core_cost_eur))


class ScaledCost:
    """One application's main-spring unit costs, computed when read (:func:`synth.design.space.spring_cost_from`,
    the formula :meth:`synth.design.space.Space.spring_cost_eur` uses): an array's stand-in. The catalog's
    ``cost x stiffness`` vector is held once for every application of a chunk instead of a vector of floats each (issue 36: about 86 MB per 1,000 applications)."""

    __slots__ = ("numerator", "stiffness")

    def __init__(self, numerator: np.ndarray, stiffness: float):
        self.numerator, self.stiffness = numerator, float(stiffness)

    def __array__(self, dtype=None, copy=None):
        from synth.design.space import spring_cost_from
        a = spring_cost_from(self.numerator, self.stiffness)
        return a if dtype is None else a.astype(dtype, copy=False)

    def __len__(self) -> int:
        return len(self.numerator)

    def __getitem__(self, i):
        return np.asarray(self)[i]

    @property
    def shape(self) -> tuple:
        return self.numerator.shape


class Names:
    """The binding constraint names of one group's options, held as codes into a names table shared by a chunk
    (:func:`synth.platform.producer.margins_and_binding`'s registry indices): an array of names' stand-in. Reads as
    the object array ``names[codes]``; 2 bytes an option instead of an 8-byte pointer (issue 36: about 44 MB per
    1,000 applications, 440 MB at 10,000).

    >>> n = Names(np.array([1, 0, 1], np.int16), np.array(["a", "b"], dtype=object))
    >>> n[0], len(n), list(n), np.asarray(n).tolist()
    ('b', 3, ['b', 'a', 'b'], ['b', 'a', 'b'])
    """

    __slots__ = ("codes", "names")

    def __init__(self, codes: np.ndarray, names: np.ndarray):
        self.codes, self.names = codes, names

    def __array__(self, dtype=None, copy=None):
        a = self.names[self.codes]
        return a if dtype is None else a.astype(dtype, copy=False)

    def __len__(self) -> int:
        return len(self.codes)

    def __iter__(self):
        return iter(np.asarray(self))

    def __getitem__(self, i):
        return np.asarray(self)[i] if not isinstance(i, (int, np.integer)) else self.names[self.codes[i]]

    @property
    def shape(self) -> tuple:
        return self.codes.shape


@dataclass
class PortfolioFeasibility:
    """The applications of a portfolio and the global part and option tables.

    * ``parts[f]``: part keys of family ``f`` (a part's code is its index);
    * ``part_cost_eur[f]``: ``(n_f,)`` per-variant fixed cost of each part (tooling,
      qualification, stock keeping), used by the cost objective;
    * ``options[s][f]``: ``(n_options,)`` part code of family ``f`` per option of
      subsystem ``s`` (``-1``: no part), for the families of :data:`SUBSYSTEM_FAMILIES`;
    * ``option_cost_eur[s]``: ``(n_options,)`` unit cost per option;
    * real data only (:mod:`synth.platform.producer`): ``design_inputs`` (the validated input
      of each application, None for a row that failed validation), the evaluator
      ``settings``, the ``catalogue`` (:class:`synth.platform.options.Catalogue`: how an
      option is a row of the design space) and ``stats`` (times); ``volumes_given``: the portfolio has an annual
      volume column (:mod:`synth.platform.volume` prices each part at the summed volume of its applications).
    """

    apps: list
    parts: dict
    part_cost_eur: dict
    options: dict
    option_cost_eur: dict
    notes: list = field(default_factory=list)
    design_inputs: list | None = None
    settings: object = None
    catalogue: object = None
    stats: dict = field(default_factory=dict)
    volumes_given: bool = False

    def n_options(self, s: str) -> int:
        return int(len(self.option_cost_eur[s]))

    def part_key(self, family: str, code: int) -> str:
        return "none" if code < 0 else str(self.parts[family][code])

    def option_parts(self, s: str, k: int) -> dict:
        """``{family: part key}`` of option ``k`` of subsystem ``s``."""
        return {f: self.part_key(f, int(self.options[s][f][k])) for f in SUBSYSTEM_FAMILIES[s]}


def default_weights() -> dict:
    """``{family: weight}`` of one distinct part in the variants objective (``catalogs/constants_platform.csv``)."""
    from synth import catalog
    return {f: catalog.constant(f"platform_weight_{f}") for f in FAMILIES}


def default_fixed_costs(parts: dict) -> dict:
    """``{family: (n_f,) per-variant fixed cost [EUR]}`` from ``catalogs/constants_platform.csv`` (one value per family)."""
    from synth import catalog
    return {f: np.full(len(parts[f]), catalog.constant(f"platform_fixed_cost_eur_{f}")) for f in FAMILIES}


def _shape_problem(where: str, got, want) -> Problem:
    return Problem(where, got, f"an array of shape {want}")


def _groups_fine(groups: list, margins: list, n_opt: int) -> bool:
    """Whether the feasible options of an application's groups (1-D integer arrays) are option indices
    ``0..n_opt-1`` with one margin each (1-D arrays of their length), checked in one pass over all groups; False
    where they are not, or are of another form (then :func:`validate` checks group by group and names the fault)."""
    if not all(type(x) is np.ndarray and x.ndim == 1 for x in groups) \
            or not all(type(m) is np.ndarray and m.ndim == 1 for m in margins):
        return False
    if [len(x) for x in groups] != [len(m) for m in margins]:
        return False
    idx = np.concatenate(groups) if groups else np.zeros(0, np.int64)
    return not idx.size or (idx.dtype.kind in "iu" and idx.min() >= 0 and idx.max() < n_opt)


def validate(pf: PortfolioFeasibility) -> PortfolioFeasibility:
    """Check the shapes and codes of a producer's output; raise :class:`InputError` naming each fault.

    >>> from synth.platform.synthetic import synthetic_portfolio
    >>> validate(synthetic_portfolio(3, seed=0)).apps[0].app_id
    'APP-0000'
    """
    probs: list = []
    for f in FAMILIES:
        if f not in pf.parts:
            probs.append(Problem("parts", f, f"a part list for every family {list(FAMILIES)}"))
            continue
        n = len(pf.parts[f])
        if np.shape(pf.part_cost_eur.get(f, ())) != (n,):
            probs.append(_shape_problem(f"part_cost_eur[{f}]", np.shape(pf.part_cost_eur.get(f, ())), (n,)))
    if probs:
        raise InputError(probs)
    for s, fams in SUBSYSTEM_FAMILIES.items():
        n = len(pf.option_cost_eur.get(s, ()))
        for f in fams:
            codes = np.asarray(pf.options.get(s, {}).get(f, np.zeros(0)))
            if codes.shape != (n,):
                probs.append(_shape_problem(f"options[{s}][{f}]", codes.shape, (n,)))
            elif n and (codes.min() < NO_PART or codes.max() >= len(pf.parts[f])):
                probs.append(Problem(f"options[{s}][{f}]", int(codes.max()), f"codes -1..{len(pf.parts[f]) - 1}"))
    for a in pf.apps:
        nc = a.n_cores
        where = f"application {a.app_id}"
        for name, arr in [("core_margin", a.core_margin)] + [(f"core_parts[{f}]", a.core_parts.get(f)) for f in CORE_FAMILIES] \
                + [(f"group[{s}]", a.group.get(s)) for s in SUBSYSTEMS]:
            if arr is None or np.shape(arr) != (nc,):
                probs.append(_shape_problem(f"{where}: {name}", None if arr is None else np.shape(arr), (nc,)))
        for f in CORE_FAMILIES:
            codes = np.asarray(a.core_parts.get(f, np.zeros(0)))
            if codes.size and (codes.min() < NO_PART or codes.max() >= len(pf.parts[f])):
                probs.append(Problem(f"{where}: core_parts[{f}]", int(codes.max()), f"codes -1..{len(pf.parts[f]) - 1}"))
        for s in SUBSYSTEMS:
            groups, n_opt = a.feasible.get(s, []), pf.n_options(s)
            g = np.asarray(a.group.get(s, np.zeros(0)))
            if g.size and (g.min() < 0 or g.max() >= len(groups)):
                probs.append(Problem(f"{where}: group[{s}]", int(g.max()), f"group ids 0..{len(groups) - 1}"))
            margins = a.option_margin.get(s, [])
            if len(margins) != len(groups):
                probs.append(Problem(f"{where}: option_margin[{s}]", len(margins), f"{len(groups)} groups as in feasible[{s}]"))
            elif _groups_fine(groups, margins, n_opt):
                groups = ()   # every group checked at once: nothing to name
            for gi, idx in enumerate(groups):
                idx = np.asarray(idx)
                if idx.size and (idx.min() < 0 or idx.max() >= n_opt):
                    probs.append(Problem(f"{where}: feasible[{s}][{gi}]", int(idx.max()), f"option indices 0..{n_opt - 1}"))
                if gi < len(margins) and np.shape(margins[gi]) != idx.shape:
                    probs.append(_shape_problem(f"{where}: option_margin[{s}][{gi}]", np.shape(margins[gi]), idx.shape))
            if a.option_cost_eur is not None and s in a.option_cost_eur and np.shape(a.option_cost_eur[s]) != (n_opt,):
                probs.append(_shape_problem(f"{where}: option_cost_eur[{s}]", np.shape(a.option_cost_eur[s]), (n_opt,)))
        if not (np.isfinite(a.volume) and a.volume >= 0):
            probs.append(Problem(f"{where}: volume", a.volume, "a finite number >= 0"))
    if probs:
        raise InputError(probs)
    return pf
