"""The record of a check's derivation (:mod:`synth.design.derivation`): plain data, the margin with its numbers, the
value and the limit as :class:`Quantity` trees (a physics call's :class:`Step` with its inputs), and their text
(the terminal's ``synth design --explain CHECK``, the report's appendix) and JSON (the web page).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from synth import formatting as fmt

__all__ = ["UNITS", "unit_of", "Step", "Quantity", "Derivation"]

#: key suffix -> unit (the units-in-names convention of synth), longest first
UNITS = (("_mpa_m_per_s_h", "MPa m/s h"), ("_mpa_m_per_s", "MPa m/s"), ("_mm3_per_n_m", "mm3/(N m)"),
          ("_nm_per_deg", "Nm/deg"), ("_n_per_mm", "N/mm"), ("_m_per_s", "m/s"), ("_kg_m3", "kg/m3"),
          ("_mm4", "mm4"), ("_mm3", "mm3"), ("_mm2", "mm2"), ("_nmm", "N mm"), ("_mpa", "MPa"), ("_deg", "deg"),
          ("_pct", "%"), ("_rpm", "rpm"), ("_eur", "EUR"), ("_hz", "Hz"), ("_mm", "mm"), ("_nm", "Nm"), ("_n", "N"),
          ("_h", "h"), ("_s", "s"), ("_m", "m"))


def unit_of(key: str) -> str:
    """The unit a key's name declares (``_mm`` mm, ``_nm`` Nm, ``_mpa_m_per_s`` MPa m/s...), "" for none.

    >>> unit_of("pivot_bushing_pv_mpa_m_per_s"), unit_of("lever_ratio"), unit_of("spring_stiffness_nm_per_deg")
    ('MPa m/s', '', 'Nm/deg')
    """
    k = key.rstrip("_")
    for suffix, unit in UNITS:
        if k.endswith(suffix):
            return unit
    return ""



# --------------------------------------------------------------------------------------------- the record
@dataclass
class Step:
    """One physics function call: its qualified name, its equation (docstring), its inputs and what it returned."""

    function: str
    equation: str
    inputs: list = field(default_factory=list)
    #: where its result is reused elsewhere in the derivation: shown once
    ref: int = 0

    def as_dict(self) -> dict:
        return {"function": self.function, "equation": self.equation, "ref": self.ref,
                "inputs": [q.as_dict() for q in self.inputs]}


@dataclass
class Quantity:
    """One value of a derivation: its key, value and unit, where it comes from (``origin``: ``input``, ``default``
    (a documented default of an input not given), ``constant``, ``catalog``, ``design`` (a part key), ``rule``
    (a design rule), ``computed`` (a physics call: ``step``), ``evaluator`` (a line of the evaluator: ``formula``),
    ``setting``, ``value``) and its ``source`` in words."""

    key: str
    value: object
    unit: str = ""
    origin: str = "value"
    source: str = ""
    step: Step | None = None
    formula: str = ""
    parts: list = field(default_factory=list)

    def text(self) -> str:
        """``key = value unit``."""
        v = self.value
        shown = fmt.quantity(v, self.unit) if isinstance(v, (int, float)) and not isinstance(v, bool) else fmt.part(v)
        return f"{self.key.rstrip('_')} = {shown}"

    def as_dict(self) -> dict:
        v = self.value
        if isinstance(v, (np.generic,)):
            v = v.item()
        if isinstance(v, float) and not math.isfinite(v):
            v = None if math.isnan(v) else ("inf" if v > 0 else "-inf")
        return {"key": self.key, "value": v, "unit": self.unit, "text": self.text(), "origin": self.origin,
                "source": self.source, "formula": self.formula, "step": self.step.as_dict() if self.step else None,
                "parts": [q.as_dict() for q in self.parts]}


@dataclass
class Derivation:
    """A check's derivation (see the module docstring)."""

    check: str
    label: str
    step: int
    equation: str
    unit: str
    sense: str
    verdict: str
    margin: float | None
    #: the margin with its numbers: ``(limit - value) / |limit| = (1 - 0.3338) / 1 = +66.6 %``
    margin_formula: str
    required_margin: float
    value: Quantity
    limit: Quantity
    scale: Quantity | None = None
    applies: str = ""
    note: str = ""
    #: the sources cited (``[n]`` in the quantities' ``source``): ``[(n, where, source text)]``
    sources: list = field(default_factory=list)

    def lines(self) -> list:
        """The derivation as text lines (the terminal's ``synth design --explain CHECK``, the report's appendix):
        the check and its equation reference, the margin with its numbers, the value and the limit traced through
        the physics calls (each call's equation, then the call with its numbers substituted and its result, then
        where each argument comes from), and the numbered sources."""
        head = f"{self.check}: {self.label} (thesis step {self.step}, {self.equation}): {self.verdict.upper()}"
        out = [head, f"  check: {self.value.key} {self.sense} {self.limit.key}"
                     + (f", {self.value.unit or '-'}" if self.value.unit else "")]
        if self.applies:
            out.append(f"  applies when: {self.applies}")
        if self.margin_formula:
            out.append(f"  {self.margin_formula}")
        for title, q in (("value", self.value), ("limit", self.limit), ("scale", self.scale)):
            if q is not None:
                out.append(f"  {title}:")
                out += _quantity_lines(q, 4)
        if self.sources:
            out.append("  sources:")
            out += [f"    [{n}] {where}: {src or '(no source given)'}" for n, where, src in self.sources]
        return out

    def text(self) -> str:
        """:meth:`lines` joined."""
        return "\n".join(self.lines())

    def as_dict(self) -> dict:
        """Plain data (JSON-ready): what :func:`synth.derive` returns for the web page."""
        return {"check": self.check, "label": self.label, "step": self.step, "equation": self.equation,
                "unit": self.unit, "sense": self.sense, "verdict": self.verdict, "margin": _plain(self.margin),
                "margin_formula": self.margin_formula, "required_margin": self.required_margin,
                "value": self.value.as_dict(), "limit": self.limit.as_dict(),
                "scale": self.scale.as_dict() if self.scale else None, "applies": self.applies, "note": self.note,
                "sources": [{"n": n, "where": w, "source": src} for n, w, src in self.sources]}


_ORIGIN_WORDS = {"input": "", "default": "", "constant": "", "catalog": "", "design": "", "rule": "",
                 "setting": "a setting of the model", "value": "an intermediate value of the evaluation (not traced)"}


def _quantity_lines(q, indent: int) -> list:
    """Text lines of one :class:`Quantity` and, for a computed one, its physics call (see :meth:`Derivation.lines`)."""
    pad = " " * indent
    if q.step is not None:
        args = ", ".join(a.text() for a in q.step.inputs)
        name = q.step.function.rsplit(".", 1)[-1]
        out = [f"{pad}{q.text()}, computed by {q.step.function}",
               f"{pad}  equation: {q.step.equation or '(no docstring equation)'}",
               f"{pad}  {name}({args}) = {q.text().split(' = ', 1)[1]}"]
        for a in q.step.inputs:
            out += _quantity_lines(a, indent + 4)
        return out
    where = q.source or _ORIGIN_WORDS.get(q.origin, "")
    out = [f"{pad}{q.text()}" + (f"  <- {where}" if where else "")]
    if q.formula:
        out.append(f"{pad}  = {q.formula}")
    for a in q.parts:
        out += _quantity_lines(a, indent + 4)
    return out


def _plain(x):
    if x is None or (isinstance(x, float) and not math.isfinite(x)):
        return None
    return float(x)
