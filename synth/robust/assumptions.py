"""Assumptions that decide verdicts: illustrative limits, their plausible ranges, and the verdicts that flip.

Some limits the registry checks against are illustrative (the spring's
yield fraction 0.88 Rm, the Goodman data, the wear constants...). Each one
that can change a verdict has a plausible range with its reason and source in
``catalogs/assumption_ranges.csv`` (one row per assumption: the catalog, the
row key or ``*`` for every row, the column, ``low`` and ``high`` as values or
as factors of the catalog's value). The ranges live beside the catalogs
rather than as extra columns of them: a user's override of a catalog must
carry every built-in column (:mod:`synth.io.catalogs`), so a new column would
invalidate every existing user folder.

:func:`flips` evaluates a design at both ends of every range, through the
catalog override mechanism itself (a temporary user folder holding the
changed rows, first in line: exactly "what if the catalog said this"), and
lists the checks whose verdict changes: "spring_yield passes at 0.88 (the
catalog), fails at 0.75".

>>> [a.id for a in assumptions()][:2]
['spring_yield_fraction', 'spring_fatigue_fraction']
"""

from __future__ import annotations

import math
import tempfile
from dataclasses import dataclass
from pathlib import Path

from synth import catalog
from synth.errors import InputError, Problem
from synth.parts import arrays
from synth.design.applications import Applications
from synth.design.result import checks_of
from synth.design.space import Space
from synth.design.verify import evaluate_design
from synth.design.constraints import REGISTRY
from synth.design.evaluate import Settings

__all__ = ["Assumption", "assumptions", "flips", "flip_lines", "APPLIES"]

#: the conditions an assumption row may need (``applies``): a sized cone spring, the application type
APPLIES = ("axial", "dry", "belt_in_oil")


@dataclass(frozen=True)
class Assumption:
    """One row of ``catalogs/assumption_ranges.csv``."""

    id: str
    catalog: str
    key: str
    column: str
    low: float
    high: float
    scale: str      # "value" (low/high are values) or "factor" (multipliers of the catalog's value)
    applies: tuple  # conditions, all met: "axial" (a cone spring in the design), "dry", "belt_in_oil"
    source: str
    reason: str


def assumptions() -> list:
    """The assumption ranges (built-in merged with the user's folders), checked: an unknown catalog or column, a
    scale other than value/factor or ``low > high`` is an error naming the row."""
    df = catalog.load("assumption_ranges")
    out, problems = [], []
    names = catalog.names()
    for _, r in df.iterrows():
        where = f"catalog assumption_ranges.csv, row {r['assumption']}"
        cat = str(r["catalog"]).strip()
        if cat != "constants" and cat not in names:
            problems.append(Problem(f"{where}, column catalog", cat, "constants or a catalog: " + ", ".join(names)))
            continue
        scale = str(r["scale"]).strip()
        if scale not in ("value", "factor"):
            problems.append(Problem(f"{where}, column scale", scale, "value or factor"))
            continue
        try:
            lo, hi = float(r["low"]), float(r["high"])
        except (TypeError, ValueError):
            problems.append(Problem(f"{where}, columns low/high", f"{r['low']}/{r['high']}", "two numbers"))
            continue
        if not (math.isfinite(lo) and math.isfinite(hi) and lo <= hi):
            problems.append(Problem(f"{where}, columns low/high", f"{lo}/{hi}", "finite numbers with low <= high"))
            continue
        applies = tuple(str(r["applies"]).split()) if isinstance(r["applies"], str) else ()
        bad = [x for x in applies if x not in APPLIES]
        if bad:
            problems.append(Problem(f"{where}, column applies", bad[0], "blank or any of " + ", ".join(APPLIES)))
            continue
        out.append(Assumption(str(r["assumption"]), cat, str(r["key"]).strip(), str(r["column"]).strip(), lo, hi,
                              scale, applies, str(r["source"]), str(r["reason"])))
    if problems:
        raise InputError(problems)
    return out


def _table_of(a: Assumption) -> tuple:
    """``(catalog name, DataFrame, row mask)`` the assumption changes (a constant: its ``constants*.csv``)."""
    if a.catalog == "constants":
        for name in catalog.names():
            if name == "constants" or name.startswith("constants_"):
                df = catalog.load(name)
                mask = df["name"] == a.key
                if mask.any():
                    return name, df, mask
        raise InputError(Problem(f"catalog assumption_ranges.csv, row {a.id}, column key", a.key, "a named constant"))
    df = catalog.load(a.catalog)
    if a.column not in df.columns:
        raise InputError(Problem(f"catalog assumption_ranges.csv, row {a.id}, column column", a.column,
                                 f"a column of {a.catalog}.csv: " + ", ".join(df.columns)))
    mask = df[df.columns[0]].astype(str) == a.key if a.key != "*" else df[df.columns[0]].notna()
    return a.catalog, df, mask


def _current(a: Assumption, parts: dict) -> list:
    """The catalog's value(s) of the assumption for the design (a ``*`` row: the rows of the design's parts)."""
    _, df, mask = _table_of(a)
    col = "value" if a.catalog == "constants" else a.column
    if a.key == "*":
        mine = mask & df[df.columns[0]].astype(str).isin({str(v) for v in parts.values()})
        mask = mine if mine.any() else mask
    return df.loc[mask, col].astype(float).tolist()


def _verdicts(d, parts: dict, settings) -> dict:
    """``{check: (verdict, margin)}`` of the design under the current catalogs (the evaluator and the registry's
    verdicts, as :func:`synth.design.verify.verify`; the part attributes from the parts tables alone, without
    building the whole design space)."""
    import numpy as np
    apps = Applications.of([d])
    attrs = Space({}, arrays()).design_attributes(parts)
    with np.errstate(all="ignore"):
        groups = evaluate_design(apps, attrs, settings, detail=False)
    return {c.id: (c.verdict, c.margin) for c in checks_of(groups, apps)}


def _with(a: Assumption, end: float, fn):
    """Run ``fn()`` with the assumption at ``end`` (a value, or a factor of the catalog's values)."""
    name, df, mask = _table_of(a)
    col = "value" if a.catalog == "constants" else a.column
    df = df.copy()
    base = df.loc[mask, col].astype(float)
    df.loc[mask, col] = end if a.scale == "value" else base * end
    with tempfile.TemporaryDirectory(prefix="synth-assumption-") as tmp:
        df.to_csv(Path(tmp) / f"{name}.csv", index=False)
        with catalog.overriding(tmp):
            return fn()


def flips(d, parts: dict, settings=None) -> list:
    """For every assumption range, the checks of design ``parts`` whose verdict at the range's ends differs
    from the catalog's: one dict per assumption (``id``, ``catalog``, ``key``, ``column``, ``value`` (the
    catalog's), ``low``, ``high``, ``scale``, ``reason``, ``source``, ``flips``: ``[{check, label, nominal,
    at_low, at_high, margin_low, margin_high}]``)."""
    settings = Settings() if settings is None else settings
    nominal = _verdicts(d, parts, settings)
    met = {"axial": nominal.get("cone_force_band", ("not applicable",))[0] != "not applicable",
           "dry": getattr(d, "application_type", None) == "dry",
           "belt_in_oil": getattr(d, "application_type", None) == "belt_in_oil"}
    out = []
    for a in assumptions():
        if not all(met[x] for x in a.applies):
            continue
        ends = {}
        for which, end in (("low", a.low), ("high", a.high)):
            ends[which] = _with(a, end, lambda: _verdicts(d, parts, settings))
        rows = []
        for cid, (v0, _) in nominal.items():
            lo, hi = ends["low"][cid], ends["high"][cid]
            if (lo[0] != v0 or hi[0] != v0) and not REGISTRY[cid].advisory:
                rows.append({"check": cid, "label": REGISTRY[cid].label, "nominal": v0, "at_low": lo[0],
                             "at_high": hi[0], "margin_low": lo[1], "margin_high": hi[1]})
        values = sorted(set(_current(a, parts)))
        out.append({"id": a.id, "catalog": a.catalog, "key": a.key, "column": a.column,
                    "value": values[0] if len(values) == 1 else values, "low": a.low, "high": a.high,
                    "scale": a.scale, "reason": a.reason, "source": a.source, "flips": rows})
    return out


def flip_lines(items: list) -> list:
    """One readable line per verdict that flips: ``spring_yield: pass at 0.88 (the catalog); fail at 0.75``."""
    lines = []
    for a in items:
        what = a["key"] if a["catalog"] == "constants" else f"{a['catalog']}.{a['column']}"
        unit = "x " if a["scale"] == "factor" else ""
        for f in a["flips"]:
            ends = []
            for which in ("low", "high"):
                if f[f"at_{which}"] != f["nominal"]:
                    ends.append(f"{f['at_' + which]} at {unit}{a[which]:g}")
            lines.append(f"{f['check']} ({what}): {f['nominal']} with the catalog's "
                         f"{a['value'] if not isinstance(a['value'], list) else 'values'}; " + "; ".join(ends)
                         + f" [{a['id']}: {a['reason']}]")
    return lines
