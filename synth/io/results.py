"""Saved results (``synth design --json``, ``synth flowchart --json``), read back with a shape check.

``synth cad RESULT.json``, ``synth flowchart --parts RESULT.json`` and
``synth report`` read results that a user saved, maybe edited, maybe of
another program. :func:`load_result` reads the JSON through the gate
(size, encoding, nesting, huge numbers) and checks its shape: a JSON object
of one of the two kinds, the blocks the consumers read of the right type,
every value whose name carries a unit (``_mm``, ``_n``, ``_nm``, ``_mpa``,
``_deg``...) a number, and the carried ``inputs`` a valid design input.
Each problem names the key as it is in the file and the file.

>>> check_result({"status": "optimal", "parts": [], "derived": {"pulley_width_mm": "wide"}}, "r.json", "result")
Traceback (most recent call last):
...
synth.errors.InputError: parts (r.json): got 'list'; accepted: a mapping of part family to choice (as synth design --json writes)
derived.pulley_width_mm (r.json): got 'wide'; accepted: a number (mm) or null
"""

from __future__ import annotations

import math
import re
from pathlib import Path

from synth.errors import InputError, Problem
from synth.io.limits import short

__all__ = ["load_result", "check_result", "result_kind", "parts_of"]

_UNIT = re.compile(r"_(mm|mm2|mm3|n|nm|mpa|deg|hz|h|s|eur|pct|nm_per_deg|n_per_mm|kg)$")
_ACCEPTED = "a JSON object written by synth design --json or synth flowchart --json"


def result_kind(data) -> str | None:
    """``"design"``, ``"flowchart"`` or None (neither) for a parsed result."""
    if not isinstance(data, dict):
        return None
    if "derived" in data or ("parts" in data and "status" in data):
        return "design"
    if "pulley_width_mm" in data or ("checks" in data and "verdict" in data):
        return "flowchart"
    return None


def load_result(path, what: str = "result") -> dict:
    """The parsed, shape-checked result file ``path`` (see the module doc)."""
    from synth.io.documents import read_document

    if Path(path).suffix.lower() != ".json":
        from synth.io.files import existing_file
        existing_file(path, what, _ACCEPTED)
        raise InputError(Problem(what, str(path), _ACCEPTED + " (a .json file)"))
    # non-finite numbers are allowed in a saved result (a margin of -Infinity); a string "inf" too
    data = read_document(path, what, accepted=_ACCEPTED, allow_nonfinite=True)
    check_result(data, Path(path).name, what)
    return data


def _unit_of(key: str) -> str:
    m = _UNIT.search(key)
    return m.group(1) if m else ""


def _is_number(v) -> bool:
    return isinstance(v, (int, float)) and not isinstance(v, bool)


def _check_values(values: dict, prefix: str, where: str, problems: list) -> None:
    for k, v in values.items():
        unit = _unit_of(str(k))
        if not unit or v is None:
            continue
        if isinstance(v, list):
            if not all(_is_number(x) for x in v):
                problems.append(Problem(f"{prefix}{k} ({where})", short(v), f"numbers ({unit})"))
        elif not _is_number(v):
            problems.append(Problem(f"{prefix}{k} ({where})", short(v), f"a number ({unit}) or null"))


def check_result(data, where: str, what: str = "result") -> str:
    """Raise one :class:`InputError` listing every shape problem of a parsed result; return its kind."""
    if not isinstance(data, dict):
        raise InputError(Problem(what, where, f"{_ACCEPTED} (this file holds a {type(data).__name__}, "
                                              "not an object)"))
    kind = result_kind(data)
    if kind is None:
        keys = ", ".join(sorted(map(str, data))[:8]) or "none"
        raise InputError(Problem(what, where, f"{_ACCEPTED}: a design result has 'status', 'parts' and "
                                              f"'derived', a flowchart result 'pulley_width_mm' and 'checks' "
                                              f"(this one has: {short(keys, 120)})"))
    problems: list[Problem] = []

    def mapping(key: str, accepted: str, required: bool = False) -> dict | None:
        v = data.get(key)
        if v is None:
            if required:
                problems.append(Problem(f"{key} ({where})", None, accepted))
            return None
        if not isinstance(v, dict):
            problems.append(Problem(f"{key} ({where})", type(v).__name__, accepted))
            return None
        return v

    if kind == "design":
        if not isinstance(data.get("status"), str):
            problems.append(Problem(f"status ({where})", short(data.get("status")),
                                    "text: optimal, feasible, infeasible... (as synth design --json writes)"))
        parts = mapping("parts", "a mapping of part family to choice (as synth design --json writes)", True)
        if parts is not None:
            for k, v in parts.items():
                if not (v is None or isinstance(v, (str, int, float, bool))):
                    problems.append(Problem(f"parts.{k} ({where})", short(v), "a part designation or a number"))
        derived = mapping("derived", "a mapping of derived values (as synth design --json writes)")
        if derived is not None:
            _check_values(derived, "derived.", where, problems)
        margins = mapping("margins", "a mapping of constraint to margin")
        if margins is not None:
            for k, v in margins.items():
                if not (v is None or _is_number(v) or (isinstance(v, str) and _finite_text(v) is not None)):
                    problems.append(Problem(f"margins.{k} ({where})", short(v), "a number (or inf/-inf)"))
    else:
        _check_values({k: v for k, v in data.items() if k not in ("checks", "inputs", "settings")}, "", where, problems)
        checks = data.get("checks")
        if checks is not None and not (isinstance(checks, list) and all(isinstance(c, dict) for c in checks)):
            problems.append(Problem(f"checks ({where})", type(checks).__name__, "a list of checks (mappings)"))
        if data.get("verdict") is not None and not isinstance(data.get("verdict"), str):
            problems.append(Problem(f"verdict ({where})", short(data.get("verdict")), "pass, fail or not verified"))
    inputs = mapping("inputs", "the design input the result was computed for (a mapping of fields)")
    if inputs is not None and not problems:
        from synth import schema
        try:
            schema.validate(inputs)
        except InputError as exc:
            problems.extend(Problem(f"inputs.{p.field} ({where})", p.value, p.accepted) for p in exc.problems)
    if problems:
        raise InputError(problems)
    return kind


def _finite_text(v: str):
    try:
        x = float(v)
    except ValueError:
        return None
    return x if not math.isnan(x) else None


def parts_of(data: dict, where: str, what: str = "--parts") -> dict:
    """The part choices of a checked result: a design's ``parts``, or a flowchart result's own choices."""
    kind = check_result(data, where, what)
    if kind == "design":
        return dict(data["parts"])
    from synth import flowchart
    try:
        r = flowchart.FlowchartResult(None, flowchart.Settings(), values=data)
        parts = r.parts
    except (KeyError, TypeError, ValueError, AttributeError):
        parts = None
    if parts is None:
        raise InputError(Problem(what, where, "the JSON of 'synth design --json' or of a complete "
                                              "'synth flowchart --json' run (this flowchart result stopped "
                                              "before every part was chosen)"))
    return parts
