"""Cell text as the user typed it: "not given" words, decimal commas, percentages, lists of numbers.

The thesis's input tables (Tables 9 and 13) write ``N/A`` where a value is
not given and ``4%`` for a percentage; spreadsheets saved in a European
locale write ``2,5`` for 2.5 and ``2,5 x 2,5`` for a wire of 2.5 by 2.5 mm.

A percentage is read by one parser, :func:`percentage`, for every field that
takes one: a field whose unit is ``%`` (``spring_torque_tolerance_pct``: ``8``,
``"8 %"`` and ``8%`` are all 8 %) and a field that is a fraction (a design
rule's minimum margin: ``0.05``, ``"5 %"`` and ``5%`` are all 0.05; ``"0.5 %"`` is
0.005). Any other number field refuses a ``%`` (``4%`` of a length means
nothing): :func:`number_from_text` reads plain numbers only.

>>> is_not_given("N/A"), is_not_given(" n.a. "), is_not_given("-"), is_not_given(0)
(True, True, True, False)
>>> number_from_text("2,5"), number_from_text("1e3"), number_from_text(" 12 "), number_from_text("4%")
(2.5, 1000.0, 12.0, None)
>>> percentage("0.5 %", "fraction"), percentage("1%", "fraction"), percentage(0.05, "fraction")
(0.005, 0.01, 0.05)
>>> percentage("8 %", "%"), percentage("8", "%"), percentage(8, "%"), percentage("8 %%", "%")
(8.0, 8.0, 8.0, None)
>>> number_from_text("1,250") is None  # a thousands separator or a decimal comma: not clear
True
>>> parse_number_list("2,5 x 2,5"), parse_number_list("2.3x4"), parse_number_list("[2.3, 4.0]"), parse_number_list("2,5")
([2.5, 2.5], [2.3, 4.0], [2.3, 4.0], [2.5])
"""

from __future__ import annotations

import math
import re
import sys

__all__ = ["NOT_GIVEN", "is_not_given", "number_from_text", "percentage", "PERCENT_UNITS", "parse_number_list",
           "AMBIGUOUS_COMMA"]

#: the words that mean "not given" (compared case-insensitively, spaces ignored)
NOT_GIVEN = ("n/a", "n.a.", "n.a", "na", "n/d", "-", "--", "\u2013", "\u2014", "")

NUMBER_RE = re.compile(r"^[+-]?(\d+\.?\d*|\.\d+)([eE][+-]?\d+)?$")
_DECIMAL_COMMA = re.compile(r"^[+-]?\d+,\d+([eE][+-]?\d+)?$")
#: "1,250": a thousands separator (1250) or a decimal comma (1.25)? Not clear: reported, not guessed
AMBIGUOUS_COMMA = re.compile(r"^[+-]?\d{1,3},\d{3}$")
#: a number followed by one percent sign, spaces allowed around it (``5 %``, ``5%``, ``0,5 %``)
_PERCENT = re.compile(r"^(?P<number>[^%]*?)\s*%$")
#: the units of the fields that take a percentage: a value in percent (``%``) or a fraction of one (``fraction``)
PERCENT_UNITS = ("%", "fraction")


def is_not_given(value) -> bool:
    """True for None and the "not given" words of :data:`NOT_GIVEN` (``N/A``, ``n.a.``, ``-``, empty)."""
    if value is None:
        return True
    if not isinstance(value, str):
        return False
    return value.strip().lower().replace(" ", "") in NOT_GIVEN


def number_from_text(text: str) -> float | None:
    """The number a cell's text means, or None when it is not one number.

    Accepts a decimal point or a decimal comma (``2,5``), surrounding
    spaces and an exponent. ``1,250`` is ambiguous (thousands or decimals)
    and gives None; a non-finite result (``inf``, ``nan``, ``1e400``) gives
    None too, and so does a percentage (``4%``: read by :func:`percentage`,
    for the fields that take one).
    """
    t = str(text).strip().replace("\u2212", "-")
    if NUMBER_RE.match(t):
        x = float(t)
    elif _DECIMAL_COMMA.match(t) and not AMBIGUOUS_COMMA.match(t):
        x = float(t.replace(",", "."))
    else:
        return None
    return x if math.isfinite(x) else None


def percentage(value, unit: str) -> float | None:
    """The value of a field that takes a percentage, in the field's ``unit`` (:data:`PERCENT_UNITS`), or None.

    ``unit="%"`` (a tolerance in percent): a number is in percent already (``8``), a percentage text is its
    number (``"8 %"``, ``"8%"``: 8.0). ``unit="fraction"`` (a margin): a number is a fraction (``0.05``), a
    percentage text its hundredth (``"5 %"``, ``"0.5 %"``: 0.05, 0.005). The number of a percentage is read by
    :func:`number_from_text` (a decimal comma too: ``"0,5 %"``); None for anything else (two ``%``, text, a
    non-finite or subnormal number), for the caller to report with the field's name and what it accepts.
    """
    if unit not in PERCENT_UNITS:
        raise ValueError(f"unit {unit!r}: one of {PERCENT_UNITS}")
    if isinstance(value, bool) or value is None:
        return None
    if isinstance(value, str):
        m = _PERCENT.match(value.strip())
        number = number_from_text(m.group("number") if m else value)
        if number is not None and m and unit == "fraction":
            number = number / 100.0
    else:
        try:
            number = float(value)
        except (TypeError, ValueError, OverflowError):
            return None
    if number is None or not math.isfinite(number) or (number != 0.0 and abs(number) < sys.float_info.min):
        return None
    return number


def parse_number_list(value):
    """A list-valued cell (a wire size: ``2.3 x 2.3``, ``2,5 x 2,5``, ``2.3; 2.3``, ``[2.3, 2.3]``) as floats.

    Separators: ``x``, ``X``, ``×``, ``*``, ``;``, whitespace; a comma
    separates list items only inside brackets or when followed by a space
    (``[2.3, 4.0]``, ``2.3, 4.0``), otherwise it is a decimal comma (``2,5``).
    Text that does not parse is returned as it is, for the validator to
    report with the field's name.
    """
    import numpy as np

    def as_float(v):  # a number too large for a float stays as it is: the validator names the field
        try:
            return float(v)
        except OverflowError:
            return v

    if isinstance(value, (list, tuple, np.ndarray)):
        return [as_float(v) if isinstance(v, (int, float, np.number)) and not isinstance(v, bool) else v for v in value]
    if isinstance(value, bool):
        return value
    if isinstance(value, (int, float, np.number)):
        return [as_float(value)]
    text = str(value).strip()
    bracketed = text.startswith("[") and text.endswith("]")
    if bracketed:
        text = text[1:-1]
    if bracketed or ", " in text or ("," in text and "." in text):
        text = text.replace(",", " ")
    parts = [p for p in re.split(r"[xX×*;\s]+", text) if p]
    out = [number_from_text(p) for p in parts]
    if not parts or any(x is None for x in out):
        return value
    return out
