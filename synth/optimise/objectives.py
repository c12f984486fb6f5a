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
"""

from __future__ import annotations

from dataclasses import dataclass


from synth.errors import InputError, Problem

__all__ = ["OBJECTIVES", "UNITS", "Objective"]

OBJECTIVES = ("standard", "cost", "margin")
#: each objective's words and unit, for every output that prints a value of it (the margin is a fraction in the
#: data, shown in percent)
UNITS = {"standard": ("non-standard parts", "(weighted count)"), "cost": ("cost", "EUR"),
         "margin": ("smallest margin", "%")}
_TIEBREAK = {"standard": ("standard", "cost"), "cost": ("cost", "standard"), "margin": ("margin", "cost")}


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
            raise InputError(Problem("objective", text, "standard, cost, margin, a lexicographic list or name=weight pairs"))
        if any("=" in p for p in parts):
            w = {}
            for p in parts:
                name, _, val = p.partition("=")
                try:
                    w[name.strip()] = float(val)
                except ValueError:
                    raise InputError(Problem("objective", text, "name=weight pairs with numeric weights")) from None
            bad = [k for k in w if k not in OBJECTIVES]
            if bad:
                raise InputError(Problem("objective", bad[0], "one of " + ", ".join(OBJECTIVES)))
            return cls(order=tuple(w), weights=w)
        bad = [p for p in parts if p not in OBJECTIVES]
        if bad:
            raise InputError(Problem("objective", bad[0], "one of " + ", ".join(OBJECTIVES)))
        if len(parts) == 1:
            return cls(order=_TIEBREAK[parts[0]])
        return cls(order=tuple(dict.fromkeys(parts)))

    def additive_weights(self) -> dict:
        """Weights of the additive parts (cost, standard) when the margin is not in play, for a scalar score."""
        if self.weights:
            return {k: v for k, v in self.weights.items() if k != "margin"}
        # lexicographic on additive objectives: a big weight on the first (standard counts are integers,
        # costs stay far below 1e4 EUR)
        out, scale = {}, 1.0
        for name in reversed(self.order):
            if name == "margin":
                continue
            out[name] = scale
            scale *= 1e4
        return out

    def uses_margin(self) -> bool:
        return "margin" in self.order

    def score(self, values: dict) -> float:
        """Scalar to minimise for a dict ``{standard, cost, margin}`` (lexicographic orders with the margin
        are compared with :meth:`key` instead)."""
        if self.weights:
            return sum(w * (-values[k] if k == "margin" else values[k]) for k, w in self.weights.items())
        return sum(w * values[k] for k, w in self.additive_weights().items())

    def key(self, values: dict) -> tuple:
        """Lexicographic sort key (smaller is better)."""
        if self.weights:
            return (self.score(values),)
        return tuple(-values[k] if k == "margin" else values[k] for k in self.order)
