"""Objectives: standardisation, cost, margin; one, a lexicographic order, or a weighted sum.

* ``standard``: weighted count of non-standard parts (weights
  ``nonstandard_weight_*`` in ``catalogs/constants_optimise.csv``; a part is
  standard when its catalog row says ``standard=true``; a pivot class is
  standard when it is thesis Table 2's class for the bearing and working arm;
  a cone spring sized from the Table 7 ranges is custom);
* ``cost``: sum of the catalog unit costs [EUR] (bushing: unit cost + cost
  per mm of length; main spring: wire length x cost per metre + mass x
  material cost per kg; bolt: format cost x property-class factor);
* ``margin``: the smallest normalised margin of the design (maximised),
  over the constraints that are not met by construction (the bolt preload is
  sized for the tilting and sliding targets, the damping split meets the
  damping target when the axial group is present).

Cost and standardisation are additive over the parts, so they decompose
over the subsystems of :mod:`synth.optimise.space`; the margin combines by
the minimum.

>>> o = Objective.parse("standard")
>>> o.order, o.weights
(('standard', 'cost'), None)
>>> Objective.parse("cost=1,standard=0.5").weights
{'cost': 1.0, 'standard': 0.5}
>>> Objective.parse("margin").key({"margin": 0.25, "cost": 12.0, "standard": 1.0})
(-0.25, 12.0)
>>> Objective.parse("cost=1,margin=100").score({"margin": 0.25, "cost": 12.0, "standard": 1.0})
-13.0
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Callable

import numpy as np

from synth.errors import InputError, Problem

__all__ = ["Goal", "GOALS", "OBJECTIVES", "UNITS", "MAX_WEIGHT", "TIE", "Objective", "with_margin_tiebreak", "weighted_sum",
           "ties", "FALLBACK_WEIGHTS", "declare", "withdraw", "goal", "additive_goals", "core_reads", "additive_totals"]


def _nonstandard_core(sp, cores, core_values):
    """Weighted count of the core's non-standard parts, plus ``nonstandard_weight_pivot_class`` for a pivot class other
    than thesis Table 2's for the bearing and working arm (core values ``pivot_class_*``)."""
    from synth import catalog
    std = core_values["pivot_class_standard_mm"]
    flag = ~np.isclose(core_values["pivot_class_diameter_mm"], np.nan_to_num(std, nan=-1.0))
    return sp.tables["core"]["nonstandard"][cores] + catalog.constant("nonstandard_weight_pivot_class") * flag


def _column(name: str):
    """A part's score read from its table's column ``name`` (a core's at its rows, an option's at ``options``)."""
    def core(sp, cores, core_values):
        return sp.tables["core"][name][cores].astype(float)

    def option(sp, table, options, stiffness_nm_per_deg):
        return sp.tables[table][name][slice(None) if options is None else options].astype(float)
    return core, option


def _cost_option(sp, table, options, stiffness_nm_per_deg):
    """Catalog unit cost [EUR] of the options; a main spring's from its wire length and mass, which scale as the
    compliance (:meth:`synth.design.space.Space.spring_cost_eur`)."""
    if table == "spring":
        return sp.spring_cost_eur(stiffness_nm_per_deg, options)
    return _column("cost_eur")[1](sp, table, options, stiffness_nm_per_deg)


@dataclass(frozen=True)
class Goal:
    """One objective, declared once: every list of objective names, unit, sense, tie-break, score and result column
    derives from the registry (:data:`GOALS`, :func:`declare`).

    ``sense`` is +1 for an objective minimised, -1 for one maximised (a sort key and a weighted sum take
    ``sense * value``); ``additive`` says how a design scores: the sum of its parts' scores (it decomposes over
    the subsystems) or, when false, the smallest of the design's normalised margins (it combines by the minimum);
    ``tiebreak`` is the order a single name expands to; ``scores`` says in words how a part scores.

    An additive goal carries its score functions: ``core(space, cores, core_values)`` the scores of core rows
    ``cores`` of ``space``'s core table (``core_values``: the core group's values at those rows, of the names in
    ``reads``), ``option(space, table, options, stiffness_nm_per_deg)`` those of a subsystem's option rows
    (``options`` None: every row; the stiffness broadcasts against them). :func:`synth.optimise.product.core_scores`
    and :func:`~synth.optimise.product.option_scores` ask every additive goal. ``digits`` rounds a design's total
    (None: kept); ``column`` is its column in a bulk result (``objective_<name>`` unless given);
    ``per_stiffness`` marks the goal whose main-spring score is a catalog column over the application's stiffness
    (the compiled spring ordering handles that one goal: :meth:`synth.optimise.spring_scan.SpringScan.list_order`).
    """

    name: str
    words: str
    unit: str
    sense: int
    additive: bool
    tiebreak: tuple
    scores: str
    core: Callable | None = None
    option: Callable | None = None
    reads: tuple = ()
    digits: int | None = None
    column: str = ""
    per_stiffness: bool = False

    def __post_init__(self):
        if self.additive and (self.core is None or self.option is None):
            raise ValueError(f"goal {self.name}: an additive goal declares its core and option score functions")
        if not self.column:
            object.__setattr__(self, "column", f"objective_{self.name}")

    def total(self, x) -> float:
        """A design's total as results show it (a float, rounded to ``digits``)."""
        return float(x) if self.digits is None else round(float(x), self.digits)

    def totals(self, x) -> np.ndarray:
        """Designs' totals as a bulk result's column holds them (floats, rounded to ``digits``)."""
        x = np.asarray(x).astype(float)
        return x if self.digits is None else np.round(x, self.digits)


#: the objectives, in the order the CLI and the pages offer them
GOALS = (
    Goal(name="standard", words="non-standard parts", unit="(weighted count)", sense=+1, additive=True,
         tiebreak=("standard", "cost"),
         scores="catalog column nonstandard of each part, plus nonstandard_weight_pivot_class for a pivot class "
                "other than thesis Table 2's",
         core=_nonstandard_core, option=_column("nonstandard")[1],
         reads=("pivot_class_standard_mm", "pivot_class_diameter_mm")),
    Goal(name="cost", words="cost", unit="EUR", sense=+1, additive=True, tiebreak=("cost", "standard"),
         scores="catalog unit costs of the parts (the main spring's from its wire length and mass)",
         core=_column("cost_eur")[0], option=_cost_option, digits=6, column="objective_cost_eur", per_stiffness=True),
    Goal(name="margin", words="smallest margin", unit="%", sense=-1, additive=False, tiebreak=("margin", "cost"),
         scores="smallest normalised margin over the constraints not met by construction (a fraction, shown in %)"),
)
_BY_NAME = {g.name: g for g in GOALS}
OBJECTIVES = tuple(_BY_NAME)
#: the largest weight of a weighted objective: weights are relative, and the lexicographic orders use 1e4 between
#: levels (:meth:`Objective.additive_weights`); above 1e6 a sum of costs (EUR) loses its cents in float precision
MAX_WEIGHT = 1e6
#: the additive weights a search ranks catalog rows by when the objective has none (the margin alone)
FALLBACK_WEIGHTS = {"cost": 1.0}
#: each objective's words and unit, for every output that prints a value of it
UNITS = {g.name: (g.words, g.unit) for g in GOALS}


def declare(goal: Goal) -> Goal:
    """Add ``goal`` to the registry (after the declared ones; a name declared already is an error): every scene
    then offers, scores and shows it. :func:`withdraw` undoes it."""
    global GOALS, OBJECTIVES
    if goal.name in _BY_NAME:
        raise ValueError(f"goal {goal.name} is declared already")
    _BY_NAME[goal.name] = goal
    GOALS, OBJECTIVES = tuple(_BY_NAME.values()), tuple(_BY_NAME)
    UNITS[goal.name] = (goal.words, goal.unit)
    return goal


def withdraw(name: str) -> None:
    """Remove the goal ``name`` that :func:`declare` added."""
    global GOALS, OBJECTIVES
    del _BY_NAME[name], UNITS[name]
    GOALS, OBJECTIVES = tuple(_BY_NAME.values()), tuple(_BY_NAME)


def goal(name: str) -> Goal:
    """The declared goal ``name``."""
    return _BY_NAME[name]


def additive_goals() -> tuple:
    """The additive goals, in declaration order: the scores every design sums over its parts."""
    return tuple(g for g in _BY_NAME.values() if g.additive)


def core_reads() -> tuple:
    """The core values the additive goals' core scores read."""
    return tuple(dict.fromkeys(k for g in additive_goals() for k in g.reads))


def additive_totals(core: dict, options) -> dict:
    """Per additive goal, ``core[name] + sum(o[name] for o in options)`` (the scores of a design or of designs:
    scalars or arrays), unrounded: the one sum of a design's scores."""
    return {g.name: core[g.name] + sum(o[g.name] for o in options) for g in additive_goals()}


@dataclass(frozen=True)
class Objective:
    """What to optimise: a lexicographic ``order`` of objectives, or ``weights`` of a weighted sum.

    Standardisation and cost are minimised, the margin maximised (in a
    weighted sum it enters with a minus sign: ``sum w_i f_i - w_margin margin``).
    """

    order: tuple = ("standard", "cost")
    weights: dict | None = None

    @property
    def primary(self) -> str:
        return "weighted" if self.weights else self.order[0]

    @classmethod
    def parse(cls, text: str) -> "Objective":
        """``standard`` | ``cost`` | ``margin`` (each with its tie-break), ``a,b,...``
        (lexicographic) or ``a=w,b=w`` (weighted sum)."""
        text = str(text).strip().lower()
        parts = [p.strip() for p in text.split(",") if p.strip()]
        if not parts:
            raise InputError(Problem("--objective", text, ", ".join(OBJECTIVES) + ", a lexicographic list or name=weight "
                                                         "pairs"))
        if any("=" in p for p in parts):
            w = {}
            weights = ("name=weight pairs whose weights are finite, non-negative numbers of at most 1e6, at least "
                       "one of them positive (a weight of 1e400 is infinite, NaN no number, and a negative weight "
                       "would maximise what the objective minimises)")
            for p in parts:
                name, _, val = p.partition("=")
                name = name.strip()
                if name not in OBJECTIVES:
                    raise InputError(Problem("--objective", name, "one of " + ", ".join(OBJECTIVES)))
                if name in w:
                    raise InputError(Problem("--objective", text, f"each objective once ({name} is given twice)"))
                try:
                    x = float(val)
                except ValueError:
                    raise InputError(Problem("--objective", text, weights)) from None
                if not (math.isfinite(x) and 0.0 <= x <= MAX_WEIGHT):
                    raise InputError(Problem("--objective", p, weights))
                w[name] = x
            if not any(x > 0 for x in w.values()):
                raise InputError(Problem("--objective", text, weights))
            return cls(order=tuple(w), weights=w)
        bad = [p for p in parts if p not in OBJECTIVES]
        if bad:
            raise InputError(Problem("--objective", bad[0], "one of " + ", ".join(OBJECTIVES)))
        if len(parts) == 1:
            return cls(order=_BY_NAME[parts[0]].tiebreak)
        return cls(order=tuple(dict.fromkeys(parts)))

    def additive_weights(self) -> dict:
        """Weights of the additive parts (cost, standard) when the margin is not in play, for a scalar score."""
        if self.weights:
            return {k: v for k, v in self.weights.items() if _BY_NAME[k].additive}
        # lexicographic on additive objectives: a big weight on the first (standard counts are integers,
        # costs stay far below 1e4 EUR)
        out, scale = {}, 1.0
        for name in reversed(self.order):
            if not _BY_NAME[name].additive:
                continue
            out[name] = scale
            scale *= 1e4
        return out

    def uses_margin(self) -> bool:
        """Whether an objective that is not additive (the margin) is in play."""
        return any(not _BY_NAME[k].additive for k in self.order)

    def score(self, values: dict) -> float:
        """Scalar to minimise for a dict ``{standard, cost, margin}`` (lexicographic orders with the margin
        are compared with :meth:`key` instead)."""
        if self.weights:
            return sum(w * _BY_NAME[k].sense * values[k] for k, w in self.weights.items())
        return sum(w * values[k] for k, w in self.additive_weights().items())

    def key(self, values: dict) -> tuple:
        """Lexicographic sort key (smaller is better)."""
        if self.weights:
            return (self.score(values),)
        return tuple(_BY_NAME[k].sense * values[k] for k in self.order)


def weighted_sum(scores: dict, weights: dict):
    """``sum_k w_k score_k`` over the additive goals of ``weights`` (a design's or many designs' scores: arrays of
    any shapes that broadcast), in the weights' order: the one scalar score the exact solvers and the bulk engine
    compare (the same doubles everywhere).

    >>> weighted_sum({"standard": 2, "cost": 1.5}, {"standard": 1e6, "cost": 1.0, "margin": 3.0})
    2000001.5
    """
    out = 0.0
    for k, w in weights.items():
        if _BY_NAME[k].additive:
            out = out + w * scores[k]
    return out


#: relative tolerance of a tie between two additive scores (:func:`weighted_sum`): the same sums formed in another
#: order differ by float rounding (about 1e-15 relative), a real price difference of 1e-6 EUR under a lexicographic
#: score of 1e5 (standard x 1e4 + cost) is 1e-11 relative: a tie is closer than 1e-12, never a cent or a tenth of one
TIE = 1e-12


def ties(scores, best):
    """Whether additive scores ``scores`` tie the best score ``best`` (within :data:`TIE` relative, at least 1 in
    absolute): the one definition of "equal objective" the exact solvers break by the margin.

    >>> bool(ties(10002.14665 + 1e-12, 10002.14665)), bool(ties(10002.147511, 10002.14665))
    (True, False)
    """
    return scores <= best + TIE * max(1.0, abs(best))


def weighted_sum_around(scores: dict, weights: dict, goal: str) -> tuple:
    """:func:`weighted_sum` split around one goal ``goal`` (whose score ``scores`` need not hold), for a caller that
    adds that goal's term itself: ``(before, w, after)``, with the sum ``before`` of the terms ahead of it (from
    0.0), its weight ``w`` (0.0 without it: the sum is then ``before``) and the terms ``after`` it, in order.
    ``((before + w * s) + after[0]) + ...`` is :func:`weighted_sum` to the last bit.

    >>> before, w, after = weighted_sum_around({"standard": 2.0}, {"cost": 1.0, "standard": 1e4}, "cost")
    >>> (before + w * 1.5) + after[0] == weighted_sum({"standard": 2.0, "cost": 1.5}, {"cost": 1.0, "standard": 1e4})
    True
    """
    before, w_goal, after, seen = 0.0, 0.0, [], False
    for k, w in weights.items():
        if not _BY_NAME[k].additive:
            continue
        if k == goal:
            w_goal, seen = w, True
        elif seen:
            after.append(w * scores[k])
        else:
            before = before + w * scores[k]
    return before, w_goal, after


def with_margin_tiebreak(objective) -> str:
    """The objective the scenes synthesise for ``objective``: one name (``standard`` or ``cost``) gets the
    margin as its last tie-break, so that among designs of equal standardisation and cost the one with the
    largest margin is returned, never a zero-margin design where an equal one with margin exists; an explicit
    order or weights are kept as given.

    >>> with_margin_tiebreak("standard"), with_margin_tiebreak("cost"), with_margin_tiebreak("cost,standard")
    ('standard,cost,margin', 'cost,standard,margin', 'cost,standard')
    """
    if isinstance(objective, Objective):
        return objective
    o = Objective.parse(objective)
    if o.weights is None and "margin" not in o.order and "," not in str(objective):
        return ",".join(o.order + ("margin",))
    return str(objective).strip().lower()
