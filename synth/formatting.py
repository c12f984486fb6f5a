"""How synth writes numbers, margins and verdicts for people: one module for every text, HTML and Excel output.

Data keep their full values (JSON and CSV: fractions, 6 significant figures); what a person reads goes through
these functions, so the terminal, the report (HTML, PDF), the results workbook, the verdict's reasons and the
derivations say the same thing the same way:

* :func:`number`: plain engineering notation, 4 significant figures, no exponent between 0.001 and 10^9
  (``13880``, not ``1.388e+04``), round-off of zero printed as ``0`` (not ``-2.096e-16``);
* :func:`quantity`: a number and its unit (``1.644 Nm``; no unit for ``-``);
* :func:`percent`: a fraction as a signed percentage (``+5.0 %``), the form of every margin;
* :func:`difference`: a value against a reference, with its unit and in percent (an alternative's cost against the
  optimum's: ``+0.068 EUR (+3.9 %)``);
* :func:`probability`: a probability in percent, or in parts per million below 0.1 %;
* :func:`yes_no`, :func:`part`: logical values and parts, with ``none`` for a part the design does not have
  (never ``0``);
* :func:`shortfall`: how far a failing check misses its limit (``35.2 %``, against a zero limit ``0.5 Nm``);
* :func:`check_relation`, :func:`check_margin`: one check (a :class:`~synth.design.result.Check` with its
  registry constraint) as ``value <= limit unit`` and its margin, ``yes``/``no`` for a logical check (a part
  present or not, a supplier rated or not: no margin), and the value against the limit where the limit is zero
  (a relative margin to a zero limit is not a percentage: ``+164 %`` of nothing).

The module is a leaf (it imports nothing of synth): the core's verdict and derivation use it as the
presentation layers do.

>>> number(13880.0), number(-2.096e-16), number(0.0046512), number(1388000.0)
('13880', '0', '0.004651', '1388000')
>>> percent(0.0502), percent(0.0002545), percent(-2e-16), percent(8.62)
('+5.0 %', '+0.03 %', '0.0 %', '+862 %')
>>> probability(0.32), probability(6.6e-10), probability(0.0011)
('32 %', '0.00066 ppm', '0.11 %')
"""

from __future__ import annotations

import math

__all__ = ["number", "quantity", "percent", "difference", "probability", "yes_no", "part", "ABSENT", "ZERO",
           "is_logical", "zero_limit", "shortfall", "check_relation", "check_margin", "check_words", "SIGNIFICANT",
           "design_label"]

#: significant figures of a number people read (data exports keep 6: :data:`synth.design.result.EXPORT_DIGITS`)
SIGNIFICANT = 4
#: below this magnitude a number is round-off of zero (a margin of -2e-16 is a value on its limit)
ZERO = 1e-9
#: how a part the design does not have is written (a damper pad class ``none``, a cone spring of an absent group)
ABSENT = "none"


def _finite(x) -> bool:
    return isinstance(x, (int, float)) and not isinstance(x, bool) and math.isfinite(x)


def number(x, digits: int = SIGNIFICANT) -> str:
    """``x`` to ``digits`` significant figures in plain notation (see the module docstring); ``-`` for None or NaN,
    ``inf``/``-inf`` for infinities, text as it is.

    >>> number(0.6175), number(1756.4), number(3.0), number(25.0), number(6.25e13), number(None)
    ('0.6175', '1756', '3', '25', '6.25e+13', '-')
    """
    if x is None:
        return "-"
    if isinstance(x, bool):
        return yes_no(x)
    if hasattr(x, "item") and not isinstance(x, (str, bytes)):
        x = x.item()
    if not isinstance(x, (int, float)):
        return str(x)
    if isinstance(x, float) and math.isnan(x):
        return "-"
    if isinstance(x, float) and math.isinf(x):
        return "inf" if x > 0 else "-inf"
    if isinstance(x, int):
        return str(x)
    if abs(x) < ZERO:
        return "0"
    mag = math.floor(math.log10(abs(x)))
    if mag >= 9 or mag < -6:
        return f"{x:.{max(digits - 1, 1)}g}"
    decimals = digits - 1 - mag
    if decimals <= 0:
        return f"{round(x, decimals):.0f}"
    text = f"{x:.{decimals}f}"
    return text.rstrip("0").rstrip(".") if "." in text else text


def quantity(x, unit: str = "", digits: int = SIGNIFICANT) -> str:
    """A number with its unit (``-`` and ``""`` are no unit).

    >>> quantity(1.6444, "Nm"), quantity(0.33381, "-"), quantity(None, "mm")
    ('1.644 Nm', '0.3338', '-')
    """
    text = number(x, digits)
    return text if text == "-" or not unit or unit == "-" else f"{text} {unit}"


def percent(fraction, *, signed: bool = True) -> str:
    """A fraction as a percentage: one decimal (two below 0.1 %, none from 100 %), signed unless ``signed=False``;
    ``-`` for None or NaN; round-off of zero is ``0.0 %``.

    >>> percent(0.0), percent(0.31, signed=False), percent(None), percent(12.991)
    ('0.0 %', '31.0 %', '-', '+1299 %')
    """
    if fraction is None or (isinstance(fraction, float) and math.isnan(fraction)):
        return "-"
    p = 100.0 * float(fraction)
    if math.isinf(p):
        return ("+" if signed else "") + "inf %" if p > 0 else "-inf %"
    if abs(p) < 100 * ZERO:
        return "0.0 %"
    sign = "+" if signed else ""
    if abs(p) >= 100.0:
        return f"{p:{sign}.0f} %"
    return f"{p:{sign}.1f} %" if abs(p) >= 0.1 else f"{p:{sign}.2f} %"


def difference(x, reference, unit: str = "") -> str:
    """``x`` against ``reference``: the signed difference with its unit and as a percentage of the reference
    (``+0.068 EUR (+3.9 %)``; ``0 EUR (0.0 %)`` for none; ``-`` where either is missing).

    >>> difference(1.8124, 1.7444, "EUR"), difference(2.0, 2.0, "EUR"), difference(1.0, 0.0, "EUR")
    ('+0.068 EUR (+3.9 %)', '0 EUR (0.0 %)', '+1 EUR')
    """
    if not (_finite(x) and _finite(reference)):
        return "-"
    d = float(x) - float(reference)
    text = number(d)
    text = ("+" + text if d > 0 and text != "0" else text) + (f" {unit}" if unit and unit != "-" else "")
    return text + (f" ({percent(d / reference)})" if abs(reference) >= ZERO else "")


def probability(p) -> str:
    """A probability for people: ``0``, a percentage from 0.1 % (two significant figures), else parts per million.

    >>> probability(0.0), probability(2.3e-3), probability(7.3e-07)
    ('0', '0.23 %', '0.73 ppm')
    """
    if p is None or (isinstance(p, float) and math.isnan(p)):
        return "-"
    p = float(p)
    if p <= 0.0:
        return "0"
    if p >= 1e-3:
        return f"{number(100.0 * p, 2)} %"
    return f"{number(1e6 * p, 2)} ppm"


def yes_no(v) -> str:
    """``yes``/``no`` of a logical value (a number: nonzero is yes); ``-`` for None.

    >>> yes_no(True), yes_no(0.0), yes_no(None)
    ('yes', 'no', '-')
    """
    if v is None or (isinstance(v, float) and math.isnan(v)):
        return "-"
    return "yes" if bool(v) else "no"


def part(v) -> str:
    """A part or class as people read it: ``none`` for an absent one (``none``, None, an empty text), a number
    plainly, text as it is.

    >>> part("none"), part(None), part(17.0), part("6006")
    ('none', 'none', '17', '6006')
    """
    if v is None or (isinstance(v, str) and v.strip().lower() in ("", "none")):
        return ABSENT
    if isinstance(v, (list, tuple)):
        return " x ".join(number(x) for x in v)
    return number(v)


# --- one check ------------------------------------------------------------------------------------------------
def _num01(x) -> bool:
    return _finite(x) and x in (0.0, 1.0)


def is_logical(constraint, value=None, limit=None) -> bool:
    """Whether a check is a logical one (a part present or not, a supplier rated or not, a material made in the
    section or not): a dimensionless, non-objective check comparing 0/1 values (the registry's note on
    ``objective=False``). Its verdict is yes/no; it has no margin.

    >>> class C: unit, objective = "-", False
    >>> is_logical(C(), 1.0, 1.0), is_logical(C(), 3.0, 3.0)
    (True, False)
    """
    return (getattr(constraint, "unit", "") in ("-", "") and not getattr(constraint, "objective", True)
            and _num01(value) and _num01(limit))


def zero_limit(constraint, limit=None) -> bool:
    """Whether a check's margin is against a zero limit with no scale of its own (its margin is then the value's
    distance in the check's unit, not a percentage: show the value and the limit). Without ``limit``: whether the
    registry entry's limit is the constant zero.

    >>> class C: scale, limit = None, "zero"
    >>> zero_limit(C()), zero_limit(C(), 0.0), zero_limit(C(), 400.0)
    (True, True, False)
    """
    if getattr(constraint, "scale", None) is not None:
        return False
    if limit is None:
        return getattr(constraint, "limit", None) == "zero"
    return _finite(limit) and abs(limit) < ZERO


def _unit(constraint) -> str:
    unit = getattr(constraint, "unit", "")
    return "" if unit in ("-", "") else unit


def shortfall(constraint, margin, limit=None) -> str:
    """How far a failing check misses its limit, without sign: the percentage of the limit (``35.2 %``), or against
    a zero limit the distance in the check's unit (the margin is then absolute: ``0.5 Nm``).

    >>> class C: scale, limit, unit = None, "zero", "Nm"
    >>> class D: scale, limit, unit = None, "limit_mpa", "MPa"
    >>> shortfall(C(), -0.5), shortfall(D(), -0.35216, 400.0)
    ('0.5 Nm', '35.2 %')
    """
    if margin is None:
        return "-"
    if zero_limit(constraint, limit):
        return quantity(abs(margin), _unit(constraint))
    return percent(-margin, signed=False)


def check_relation(check) -> str:
    """A check's comparison as people read it: ``1756 <= 1848 MPa``, ``yes``/``no`` for a logical check, the
    note of one not verified, ``-`` for one that does not apply."""
    c = check.constraint
    if check.value is None or check.limit is None:
        return "-"
    if is_logical(c, check.value, check.limit):
        return yes_no(check.margin is not None and check.margin >= -ZERO)
    unit = c.unit if c.unit not in ("-", "") else ""
    return f"{number(check.value)} {c.sense} {number(check.limit)}" + (f" {unit}" if unit else "")


def check_margin(check) -> str:
    """A check's margin for people: a signed percentage of its limit (of its own scale where the registry names
    one); for a logical check ``-`` (it holds or not: :func:`check_relation` says which); against a zero limit the
    value's distance to it with the unit (``1.644 Nm above``), as a percentage of nothing would mislead."""
    c = check.constraint
    m = check.margin
    if m is None:
        return "-"
    if is_logical(c, check.value, check.limit):
        return "-"
    if zero_limit(c, check.limit) and check.value is not None:
        d = check.value - check.limit
        unit = c.unit if c.unit not in ("-", "") else ""
        side = "above" if d > 0 else ("below" if d < 0 else "on")
        return f"{quantity(abs(d), unit)} {side} the limit" if side != "on" else "on the limit"
    need = getattr(check, "required", 0.0) or 0.0
    return percent(m) + (f" beyond the required {number(100.0 * need)} %" if need else "")


def check_words(check) -> str:
    """A check in one phrase: its label, comparison and margin (``pivot bushing pressure: 1.713 <= 3 MPa,
    +42.9 %``; a logical check ``...: no``)."""
    c = check.constraint
    rel = check_relation(check)
    m = check_margin(check)
    return f"{c.label}: {rel}" + (f", {m}" if m not in ("-", "") else "")


def design_label(parts: dict) -> str:
    """A design in one short line from its part keys (:data:`synth.design.space.PART_KEYS`): bearing, pivot class,
    bushing, damping group, main spring, bolt (``none`` for an absent part).

    >>> design_label({"ball_bearing": "6006", "pivot_class_diameter_mm": 17.0, "pivot_bushing_supplier": "B",
    ...     "pivot_bushing_length_mm": 15.0, "damper_pad_class": "none", "main_spring_material": "VDSiCrV",
    ...     "main_spring_wire": "F2.00x2.00", "main_spring_mean_body_diameter_mm": 43.0, "bolt_format": "M8x1.25",
    ...     "bolt_property_class": "8.8"})
    'bearing 6006, pivot class 17 mm, bushing B x 15 mm, damper pad none, spring VDSiCrV F2.00x2.00 on 43 mm, bolt M8x1.25 8.8'
    """
    p = parts or {}
    pad = part(p.get("damper_pad_class"))
    group = f"damper pad {pad}" + (f", spacer {part(p.get('endcap_spacer_class'))}" if pad != ABSENT else "")
    return (f"bearing {part(p.get('ball_bearing'))}, pivot class {number(p.get('pivot_class_diameter_mm'))} mm, "
            f"bushing {part(p.get('pivot_bushing_supplier'))} x {number(p.get('pivot_bushing_length_mm'))} mm, "
            f"{group}, spring {part(p.get('main_spring_material'))} {part(p.get('main_spring_wire'))} on "
            f"{number(p.get('main_spring_mean_body_diameter_mm'))} mm, bolt {part(p.get('bolt_format'))} "
            f"{part(p.get('bolt_property_class'))}")
