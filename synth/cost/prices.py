"""The price file: ``catalogs/prices.csv`` and a company's own ``prices.csv`` (``--catalogs DIR``), row by row.

One row prices one *item*: a part (``ball_bearing:6006``, ``bolt:M8x1.25 hex 8.8``, ``washer:ISO 7089 8 300HV``,
``damper_pad:DP1``, ``endcap_spacer:ES1``, ``pivot_bushing:A 18``), a tightening method's assembly premium per
joint over the torque-controlled reference (``tightening:angle_controlled``), a material per kg
(``material:VDSiCr``), a process rate (``process:main_spring`` per part, ``process:main_spring_coiling`` per metre of wire) or an exchange rate
(``fx:USD``: EUR per USD). Columns:

========= =====================================================================================================
item      ``family:name`` (the families above and ``material``, ``process``, ``fx``)
price     the unit price at ``quantity``, in ``currency`` per ``per``
currency  ``EUR``, or a currency with an ``fx:<CUR>`` row
per       ``part``, ``kg``, ``m`` (what one unit is; an ``fx`` row: its currency)
quantity  the (annual) quantity from which the price holds: its quantity break
breaks    further breaks ``quantity:price; quantity:price`` (same currency and unit), or empty
date      when the price was set (``YYYY-MM-DD``)
supplier  who quotes it (empty for synth's assumptions)
status    ``quoted`` (a supplier's price) or ``assumed`` (a named default)
reference ``true`` for the one row of a bought-in family (``ball_bearing``, ``bolt``, ``washer``): its relation's start
band_pct  one standard deviation of the price, in percent (the band of :mod:`synth.cost.decision`)
source    where the price comes from
========= =====================================================================================================

A user's ``prices.csv`` merges with the built-in one on ``item`` like every catalog (:mod:`synth.catalog`): a
row with the item of a built-in row replaces it (a quote for the reference bearing re-anchors every modelled
bearing), a new item adds a quote. The input gate reads every user ``prices.csv`` through :func:`check_rows`
(:mod:`synth.io.catalogs`), naming the file, row, line and column of a problem.

The annual volume selects, in each row, the break with the largest quantity not above it
(:meth:`PriceRow.at`).

>>> r = PriceRow("bolt:M8x1.25 hex 8.8", ((1000, 0.06), (10000, 0.05)), "EUR", "part", "2026-01-05", "ACME",
...              "quoted", False, 5.0, "quote 17")
>>> r.at(5000), r.at(20000), r.at(10)
((0.06, 1000.0, False), (0.05, 10000.0, False), (0.06, 1000.0, True))
"""

from __future__ import annotations

import datetime
import math
import re
from dataclasses import dataclass

from synth.errors import InputError, Problem

__all__ = ["FAMILIES", "STATUSES", "PriceRow", "check_rows", "rows_of", "parse_breaks"]

#: item family -> the units (``per``) a row of it may be priced in
FAMILIES = {"ball_bearing": ("part",), "bolt": ("part",), "washer": ("part",), "damper_pad": ("part",),
            "endcap_spacer": ("part",), "pivot_bushing": ("part",), "tightening": ("part",), "material": ("kg",),
            "process": ("part", "m"), "fx": ()}
#: the families priced by a relation from one reference row
RELATIONAL = ("ball_bearing", "bolt", "washer")
STATUSES = ("quoted", "assumed")
_CURRENCY = re.compile(r"^[A-Z]{3}$")


@dataclass(frozen=True)
class PriceRow:
    """One row of the price file, checked (see the module docstring); ``breaks``: ``((quantity, price), ...)``
    ascending, the row's own ``quantity``/``price`` among them."""

    item: str
    breaks: tuple
    currency: str
    per: str
    date: str
    supplier: str
    status: str
    reference: bool
    band_pct: float
    source: str

    @property
    def family(self) -> str:
        return self.item.split(":", 1)[0]

    @property
    def name(self) -> str:
        return self.item.split(":", 1)[1]

    @property
    def sigma(self) -> float:
        """One standard deviation of ln(price): ``ln(1 + band_pct / 100)``."""
        return math.log1p(self.band_pct / 100.0)

    def at(self, volume: float) -> tuple:
        """``(price, quantity of the break, below)`` at annual ``volume``: the break with the largest quantity not
        above it; below every break, the smallest (``below`` True)."""
        chosen = None
        for q, p in self.breaks:
            if q <= volume:
                chosen = (p, float(q), False)
        return chosen if chosen is not None else (self.breaks[0][1], float(self.breaks[0][0]), True)

    def words(self) -> str:
        """``quoted by ACME 2026-01-05`` or ``assumed 2026-11-01``: what the price is, in a few words."""
        who = f" by {self.supplier}" if self.supplier else ""
        return f"{self.status}{who} {self.date}"


def parse_breaks(text) -> list:
    """``"1000:0.9; 10000:0.8"`` as ``[(1000.0, 0.9), (10000.0, 0.8)]`` (empty text: ``[]``); a malformed entry
    raises ``ValueError`` naming it.

    >>> parse_breaks("1000:0.9; 10000:0.8"), parse_breaks("")
    ([(1000.0, 0.9), (10000.0, 0.8)], [])
    """
    out = []
    for part in _text(text).replace(",", ";").split(";"):
        part = part.strip()
        if not part:
            continue
        q, sep, p = part.partition(":")
        try:
            qv, pv = float(q), float(p)
        except ValueError:
            raise ValueError(part) from None
        if not sep or not (math.isfinite(qv) and math.isfinite(pv) and qv >= 1 and pv > 0):
            raise ValueError(part)
        out.append((qv, pv))
    return out


def _text(v) -> str:
    if v is None or (isinstance(v, float) and math.isnan(v)):
        return ""
    return str(v).strip()


def _bool(v) -> bool:
    return _text(v).lower() in ("true", "1", "yes", "y")


def check_rows(df, at) -> list:
    """The problems of a price table ``df`` (typed as the catalog reader types it), one per cell;
    ``at(i, column)`` names row ``i``'s cell (file, row, line, column)."""
    problems = []
    cols = set(df.columns)
    for i in range(len(df)):
        row = {c: df[c].iloc[i] for c in cols}
        item = _text(row.get("item"))
        family, sep, name = item.partition(":")
        if not sep or family not in FAMILIES or not name.strip():
            problems.append(Problem(at(i, "item"), item, "family:name, the family one of " + ", ".join(FAMILIES)
                                    + " (ball_bearing:6006, material:VDSiCr, process:main_spring, fx:USD)"))
            continue
        per = _text(row.get("per"))
        allowed = FAMILIES[family] or (name.strip(),)
        if per not in allowed:
            problems.append(Problem(at(i, "per"), per, f"for a {family} row: " + " or ".join(allowed)))
        cur = _text(row.get("currency"))
        if not _CURRENCY.match(cur) or (family == "fx" and cur != "EUR"):
            problems.append(Problem(at(i, "currency"), cur, "EUR for an fx row (its price is EUR per unit)" if
                                    family == "fx" else "a three-letter ISO 4217 code: EUR, or one with an fx row "
                                                        "(fx:USD, price in EUR per USD)"))
        try:
            datetime.date.fromisoformat(_text(row.get("date")))
        except ValueError:
            problems.append(Problem(at(i, "date"), _text(row.get("date")), "a date YYYY-MM-DD (when the price was "
                                                                            "set)"))
        status = _text(row.get("status"))
        if status not in STATUSES:
            problems.append(Problem(at(i, "status"), status, "quoted (a supplier's price) or assumed (a named "
                                                             "default)"))
        if _bool(row.get("reference")) and family not in RELATIONAL:
            problems.append(Problem(at(i, "reference"), "true", "false: only a " + " or ".join(RELATIONAL)
                                    + " row anchors a relation"))
        qty = row.get("quantity")
        try:
            qty_ok = float(qty) >= 1
        except (TypeError, ValueError):
            qty_ok = False
        if not qty_ok:
            problems.append(Problem(at(i, "quantity"), qty, "a quantity of at least 1 (the break's pieces)"))
        try:
            extra = parse_breaks(row.get("breaks"))
            if qty_ok and any(q == float(qty) for q, _ in extra):
                problems.append(Problem(at(i, "breaks"), _text(row.get("breaks")),
                                        "breaks at quantities other than the row's own quantity"))
        except ValueError as exc:
            problems.append(Problem(at(i, "breaks"), _text(row.get("breaks")),
                                    f"quantity:price pairs separated by ';' (quantity >= 1, price > 0; not '{exc}')"))
    return problems


def rows_of(df, where: str = "catalogs/prices.csv") -> dict:
    """``{item: PriceRow}`` of a merged price table; problems raise an :class:`~synth.errors.InputError`."""
    problems = check_rows(df, lambda i, c: f"{where}, item {_text(df['item'].iloc[i])!r}, column {c}")
    if problems:
        raise InputError(problems)
    out = {}
    for i in range(len(df)):
        r = {c: df[c].iloc[i] for c in df.columns}
        breaks = sorted([(float(r["quantity"]), float(r["price"]))] + parse_breaks(r.get("breaks")))
        item = _text(r["item"])
        out[item] = PriceRow(item, tuple(breaks), _text(r["currency"]), _text(r["per"]), _text(r["date"]),
                             _text(r.get("supplier")), _text(r["status"]), _bool(r.get("reference")),
                             float(r["band_pct"]), _text(r.get("source")))
    return out
