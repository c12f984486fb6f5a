"""Cell text as the user typed it: "not given" words, decimal commas, lists of numbers.

The thesis's input tables (Tables 9 and 13) write ``N/A`` where a value is
not given and ``4%`` for a percentage; spreadsheets saved in a European
locale write ``2,5`` for 2.5 and ``2,5 x 2,5`` for a wire of 2.5 by 2.5 mm.

>>> is_not_given("N/A"), is_not_given(" n.a. "), is_not_given("-"), is_not_given(0)
(True, True, True, False)
>>> number_from_text("2,5"), number_from_text("4%"), number_from_text("1e3"), number_from_text(" 12 ")
(2.5, 4.0, 1000.0, 12.0)
>>> number_from_text("1,250") is None  # a thousands separator or a decimal comma: not clear
True
>>> parse_number_list("2,5 x 2,5"), parse_number_list("2.3x4"), parse_number_list("[2.3, 4.0]"), parse_number_list("2,5")
([2.5, 2.5], [2.3, 4.0], [2.3, 4.0], [2.5])
"""

from __future__ import annotations

import math
import re

__all__ = ["NOT_GIVEN", "is_not_given", "number_from_text", "parse_number_list", "AMBIGUOUS_COMMA"]

#: the words that mean "not given" (compared case-insensitively, spaces ignored)
NOT_GIVEN = ("n/a", "n.a.", "n.a", "na", "n/d", "-", "--", "\u2013", "\u2014", "")

_NUMBER = re.compile(r"^[+-]?(\d+\.?\d*|\.\d+)([eE][+-]?\d+)?$")
_DECIMAL_COMMA = re.compile(r"^[+-]?\d+,\d+([eE][+-]?\d+)?$")
#: "1,250": a thousands separator (1250) or a decimal comma (1.25)? Not clear: reported, not guessed
AMBIGUOUS_COMMA = re.compile(r"^[+-]?\d{1,3},\d{3}$")


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
    spaces, a trailing ``%`` (the thesis writes ``4%``), and an exponent.
    ``1,250`` is ambiguous (thousands or decimals) and gives None; a
    non-finite result (``inf``, ``nan``, ``1e400``) gives None too.
    """
    t = str(text).strip().rstrip("%").strip().replace("\u2212", "-")
    if _NUMBER.match(t):
        x = float(t)
    elif _DECIMAL_COMMA.match(t) and not AMBIGUOUS_COMMA.match(t):
        x = float(t.replace(",", "."))
    else:
        return None
    return x if math.isfinite(x) else None


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
