"""Saved results (the ``--json`` of any scene), read back with a shape check.

``synth cad RESULT.json``, ``synth flowchart --parts RESULT.json`` and
``synth report RESULT.json`` read results that a user saved, maybe edited, maybe of
another program. :func:`load_result` reads the JSON through the gate
(size, encoding, nesting, huge numbers) and checks its shape: the one result
shape of :class:`synth.design.result.Result` (``parts``, ``values``,
``checks``), every value whose name carries a unit (``_mm``, ``_n``, ``_nm``,
``_mpa``, ``_deg``...) a number, and the carried ``inputs`` a valid design
input. Each problem names the key as it is in the file and the file.

>>> check_result({"kind": "synth.result", "parts": [], "values": {"pulley_width_mm": "wide"}, "checks": []},
...              "r.json", "result")
Traceback (most recent call last):
...
synth.errors.InputError: parts (r.json): got 'list'; accepted: a mapping of part key to choice (as --json writes)
values.pulley_width_mm (r.json): got 'wide'; accepted: a number (mm) or null
>>> check_result({"kind": "synth.result", "parts": {}, "checks": []}, "r.json", "result", needs_inputs=True)
Traceback (most recent call last):
...
synth.errors.InputError: values (r.json): missing; expected a mapping of derived values (as --json writes)
inputs (r.json): missing; expected the design input the result was made from (a result of synth design/flowchart --json, 0.2 or later, carries it under 'inputs')
"""

from __future__ import annotations

import math
import re
from pathlib import Path

from synth.errors import InputError, Problem
from synth.io.limits import short
from synth.io.structured import read_document
from synth.io.files import existing_file

__all__ = ["load_result", "check_result", "result_kind", "parts_of", "INPUTS_ACCEPTED"]

_UNIT = re.compile(r"_(mm|mm2|mm3|n|nm|mpa|deg|hz|h|s|eur|pct|nm_per_deg|n_per_mm|kg)$")
_ACCEPTED = "a JSON object written by the --json option of a synth scene (design, flowchart, demo...)"


def result_kind(data) -> str | None:
    """``"result"`` for the one result shape, ``"old"`` for a result of synth before the one result type,
    ``"parts"`` for an object with part choices only (enough for ``--parts``), else None."""
    if not isinstance(data, dict):
        return None
    if data.get("kind") == "synth.result" or ("parts" in data and "values" in data and "checks" in data):
        return "result"
    if "derived" in data:
        return "old"
    if "parts" in data:
        return "parts"
    return None


def load_result(path, what: str = "result", *, needs_inputs: bool = False) -> dict:
    """The parsed, shape-checked result file ``path`` (see the module doc; ``needs_inputs``: a scene that
    re-verifies the design needs the carried ``inputs``, and a result without them is refused naming the key)."""

    if Path(path).suffix.lower() != ".json":
        existing_file(path, what, _ACCEPTED)
        raise InputError(Problem(what, str(path), _ACCEPTED + " (a .json file)"))
    # non-finite numbers are allowed in a saved result (a margin of -Infinity); a string "inf" too
    data = read_document(path, what, accepted=_ACCEPTED, allow_nonfinite=True)
    check_result(data, Path(path).name, what, needs_inputs=needs_inputs)
    return data


def _unit_of(key: str) -> str:
    m = _UNIT.search(key)
    return m.group(1) if m else ""


def _is_number(v) -> bool:
    return isinstance(v, (int, float)) and not isinstance(v, bool)


def _check_values(values: dict, prefix: str, where: str, problems: list) -> None:
    for k, v in values.items():
        if not isinstance(k, str) or not _unit_of(k) or v is None or isinstance(v, list):
            continue
        if _is_number(v) and (math.isfinite(v) or math.isinf(v)):
            continue
        if isinstance(v, str) and _finite_text(v) is not None:
            continue
        problems.append(Problem(f"{prefix}{k} ({where})", short(v), f"a number ({_unit_of(k)}) or null"))


#: what a scene that re-verifies a saved result needs under its ``inputs`` key
INPUTS_ACCEPTED = ("the design input the result was made from (a result of synth design/flowchart --json, 0.2 or "
                   "later, carries it under 'inputs')")


def check_result(data, where: str, what: str = "result", *, needs_inputs: bool = False) -> str:
    """Raise one :class:`InputError` listing every shape problem of a parsed result (a key it lacks named as
    missing; ``needs_inputs``: its ``inputs`` too); return its kind."""
    if not isinstance(data, dict):
        raise InputError(Problem(what, where, f"{_ACCEPTED} (this file holds a {type(data).__name__}, "
                                              "not an object)"))
    kind = result_kind(data)
    if kind == "old":
        raise InputError(Problem(what, where, f"{_ACCEPTED}: this one was written by an older synth (before the one "
                                              "result type); run the scene again"))
    if kind is None or (kind == "parts" and what != "--parts"):
        keys = ", ".join(sorted(map(str, data))[:8]) or "none"
        raise InputError(Problem(what, where, f"{_ACCEPTED}: a result has 'parts', 'values' and 'checks' "
                                              f"(this one has: {short(keys, 120)})"))
    problems: list[Problem] = []
    if kind == "parts":  # --parts reads the part choices only: {"parts": {...}} is enough
        data = {"values": {}, "checks": [], **data}

    def block(key: str, kind_, accepted: str):
        v = data.get(key)
        if not isinstance(v, kind_):  # a key the result lacks is said missing, by its name
            problems.append(Problem(f"{key} ({where})", None if key not in data else type(v).__name__, accepted))
            return None
        return v

    parts = block("parts", dict, "a mapping of part key to choice (as --json writes)")
    if parts is not None:
        for k, v in parts.items():
            if not (v is None or isinstance(v, (str, int, float, bool))):
                problems.append(Problem(f"parts.{k} ({where})", short(v), "a part designation or a number"))
    values = block("values", dict, "a mapping of derived values (as --json writes)")
    if values is not None:
        _check_values(values, "values.", where, problems)
    verdict = data.get("verdict")
    if verdict is not None and verdict not in ("pass", "incomplete", "fail"):
        problems.append(Problem(f"verdict ({where})", short(verdict), "pass, incomplete or fail (or absent)"))
    checks = block("checks", list, "a list of checks (as --json writes)")
    if checks is not None and not all(isinstance(c, dict) for c in checks):
        problems.append(Problem(f"checks ({where})", "a list with non-objects", "a list of checks (mappings)"))
    inputs = data.get("inputs")
    if inputs is None and needs_inputs:
        problems.append(Problem(f"inputs ({where})", None, INPUTS_ACCEPTED))
    if inputs is not None and not isinstance(inputs, dict):
        problems.append(Problem(f"inputs ({where})", type(inputs).__name__, "the design input (a mapping of fields)"))
    elif inputs is not None and not problems:
        from synth import schema
        try:
            schema.validate({k: v for k, v in inputs.items() if v is not None})
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
    """The part choices of a checked result or of a parts-only object ``{"parts": {...}}`` (every part key
    present)."""
    check_result(data, where, what)
    from synth.design.space import PART_DEFAULTS, PART_KEYS
    parts = dict(data["parts"])
    missing = [k for k in PART_KEYS if k not in parts and k not in PART_DEFAULTS
               and k != "cone_spring_internal_diameter_mm"]
    if missing:
        raise InputError(Problem(what, where, "a result with a complete design (this one has no "
                                              + ", ".join(missing[:4]) + ")"))
    return parts
