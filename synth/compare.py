"""Ours against the thesis tool and the real tensioner, key by key.

:func:`compare_case` runs the flowchart on a case file's ``inputs`` and lines
up every key of its ``thesis_tool:`` block with our value, the thesis tool's
and the real tensioner's, with relative errors (numbers) or a match flag
(text, lists).
"""

from __future__ import annotations

import math
from pathlib import Path

import yaml

from synth import flowchart, schema
from synth.errors import InputError, Problem

__all__ = ["compare_case", "relative_error"]


def relative_error(ours, ref):
    """``(ours - ref) / |ref|`` for numbers (lists: the largest by magnitude); ``None`` if not comparable.

    >>> round(relative_error(3.07, 3.0), 6)
    0.023333
    >>> round(relative_error([2.3, 2.3], [2.3, 2.4]), 6)
    -0.041667
    """
    if isinstance(ours, bool) or isinstance(ref, bool) or ours is None or ref is None:
        return None
    if isinstance(ours, (list, tuple)) and isinstance(ref, (list, tuple)):
        if len(ours) != len(ref):
            return None
        errs = [relative_error(a, b) for a, b in zip(ours, ref)]
        if any(e is None for e in errs):
            return None
        return max(errs, key=abs)
    try:
        o, r = float(ours), float(ref)
    except (TypeError, ValueError):
        return None
    if not (math.isfinite(o) and math.isfinite(r)):
        return None
    if r == 0:
        return 0.0 if o == 0 else math.inf
    return (o - r) / abs(r)


def _same(ours, ref) -> bool | None:
    if ours is None or ref is None:
        return None
    if isinstance(ref, str) and isinstance(ours, str):
        return ours.strip().lower() == ref.strip().lower()
    if isinstance(ref, bool) or isinstance(ours, bool):
        return bool(ours) == bool(ref)
    return str(ours).strip().lower() == str(ref).strip().lower()


def compare_case(path: str | Path, settings: flowchart.Settings | None = None) -> dict:
    """Run the flowchart on a case file and compare with its ``thesis_tool`` and ``real_tensioner`` blocks.

    Returns ``{"name", "result", "rows": [{key, ours, thesis_tool, real, err_thesis, err_real, match}]}``.
    """
    p = Path(path)
    raw = yaml.safe_load(p.read_text(encoding="utf-8")) if p.is_file() else None
    if not isinstance(raw, dict) or "thesis_tool" not in raw:
        raise InputError(Problem("case file", str(p), "a case YAML with inputs: and thesis_tool: blocks"))
    result = flowchart.run(schema.validate(raw.get("inputs") or {}), settings)
    real = raw.get("real_tensioner") or {}
    rows = []
    for key, ref in (raw["thesis_tool"] or {}).items():
        ours = result.get(key)
        categorical = isinstance(ref, (str, bool))  # a designation ("8.8", "6006") is a name, not a number
        row = {"key": key, "ours": ours, "thesis_tool": ref, "real": real.get(key),
               "err_thesis": None if categorical else relative_error(ours, ref),
               "err_real": None if categorical else relative_error(ours, real.get(key))}
        if categorical:
            row["match"] = _same(ours, ref)
        rows.append(row)
    return {"name": raw.get("name", p.stem), "result": result, "rows": rows}
