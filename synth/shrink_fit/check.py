"""Checks and normalised margins of the shrink fit (the crankshaft pulley scene; the tensioner's checks are the
registry's, :mod:`synth.design.constraints`).

A margin is normalised so that ``margin >= 0`` passes and its size is the
relative distance to the limit, whatever the unit:

* upper limit (``value <= limit``): ``(limit - value) / |limit|``
* lower limit (``value >= limit``): ``(value - limit) / |limit|``

Both are pure numpy functions, so the optimiser evaluates thousands of
designs with the same code as the flowchart report.

>>> float(margin_upper(8.0, 10.0)), float(margin_lower(2.5, 2.0))
(0.2, 0.25)
"""

from __future__ import annotations

from dataclasses import dataclass, field

from synth.design.constraints import normalised_margin
from synth.design.result import FAIL, NOT_VERIFIED, PASS

__all__ = ["margin_upper", "margin_lower", "Check", "PASS", "FAIL", "NOT_VERIFIED"]

def margin_upper(value, limit):
    """Normalised margin of ``value <= limit`` (positive passes; absolute if the limit is 0): the registry's."""
    return normalised_margin(value, limit, "<=")


def margin_lower(value, limit):
    """Normalised margin of ``value >= limit`` (positive passes; absolute if the limit is 0).

    >>> float(margin_lower(3.0, 0.0))
    3.0
    """
    return normalised_margin(value, limit, ">=")


@dataclass
class Check:
    """One verified (or skipped) constraint of the flowchart, for reports.

    ``kind`` is ``"<="`` (value must not exceed limit) or ``">="``.
    A check whose input data is missing carries ``verdict = NOT_VERIFIED``
    and a ``note`` such as ``"not verified: lockup_pin_diameter_mm missing"``.
    """

    name: str
    step: int
    value: float | None
    limit: float | None
    kind: str = "<="
    unit: str = ""
    equation: str = ""
    correction: str = ""
    note: str = ""
    verdict: str = field(init=False)
    margin: float | None = field(init=False)

    def __post_init__(self):
        if self.value is None or self.limit is None:
            self.verdict, self.margin = NOT_VERIFIED, None
            return
        m = margin_upper(self.value, self.limit) if self.kind == "<=" else margin_lower(self.value, self.limit)
        self.margin = float(m)
        self.verdict = PASS if self.margin >= -1e-12 else FAIL

    @classmethod
    def skipped(cls, name: str, step: int, missing: str, **kw) -> "Check":
        """A check that cannot run because input ``missing`` is absent."""
        return cls(name, step, None, None, note=f"not verified: {missing} missing", **kw)

    def as_dict(self) -> dict:
        return {k: getattr(self, k) for k in
                ("name", "step", "value", "limit", "kind", "unit", "verdict", "margin", "equation", "correction", "note")}
