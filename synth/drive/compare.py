"""A drive's computed tables beside a drive-design report's printed ones: ours, the report's, the difference.

A report is a mapping (the YAML fixtures under ``tests/validation/data/gates_*.yaml`` are examples):

* ``listing``: the report's pulley names in its own order; a row's span (``span_mm``, the duty's ``T``) is the
  span from that pulley to the next in the listing (the drive file may list them the other way round: a span is
  found by the two pulleys it joins);
* ``span_mm``, ``wrap_deg`` per pulley and ``take_up_mm_per_deg`` at the nominal position;
* ``positions``: rows ``{name, rel, abs, X, Y, beta, dir, hub, T, wrap, EDL, REBL}`` under the report's names
  (Free Arm, Replace, Max, Mean, Min, Load; :data:`synth.drive.positions.POSITION_NAMES`);
* ``duty``: rows ``{rpm, T: {pulley: N}, H: {pulley: N}}``;
* ``mode1_hz``: the first system mode (optional).

Angles are compared by their difference in degrees; everything else relative to the report's value. Only values
the report prints and the drive computes are compared.
"""

from __future__ import annotations

import numpy as np

from synth.drive.analysis import analyse
from synth.drive.positions import POSITION_NAMES

__all__ = ["compare_with_report", "ANGLES", "summary"]

#: the report's angle quantities (compared in degrees, not relative)
ANGLES = ("rel", "abs", "beta", "dir", "wrap", "wrap_deg")
_POSITION_KEYS = {"rel": "from_free_arm_deg", "abs": "arm_angle_deg", "X": "centre_x_mm", "Y": "centre_y_mm",
                  "beta": "beta_deg", "dir": "hub_direction_deg", "hub": "hub_load_n", "T": "tension_n",
                  "wrap": "wrap_deg", "EDL": "drive_length_mm", "REBL": "required_belt_length_mm"}
_REPORT_NAME = {v: k for k, v in POSITION_NAMES.items()}


def _row(table, where, quantity, ours, theirs):
    if ours is None or theirs is None:
        return
    if quantity in ANGLES:
        diff = float((ours - theirs + 180.0) % 360.0 - 180.0)
        table.append({"table": where[0], "row": where[1], "quantity": quantity, "ours": float(ours),
                      "report": float(theirs), "difference": diff, "unit": "deg"})
    else:
        table.append({"table": where[0], "row": where[1], "quantity": quantity, "ours": float(ours),
                      "report": float(theirs), "difference": (float(ours) - theirs) / abs(theirs), "unit": "rel"})


def _span_index(names: list, a: str, b: str) -> int:
    n = len(names)
    for j in range(n):
        if {names[j], names[(j + 1) % n]} == {a, b}:
            return j
    raise KeyError(f"no span joins {a} and {b}")


def compare_with_report(drive, report: dict, res: dict | None = None) -> list[dict]:
    """Every value the report prints that :func:`synth.drive.analysis.analyse` computes, as rows
    ``{table, row, quantity, ours, report, difference, unit}`` (``difference``: degrees for angles, relative
    otherwise)."""
    res = res or analyse(drive, check=False)
    names = res["pulleys"]
    listing = report["listing"]
    nxt = {p: listing[(i + 1) % len(listing)] for i, p in enumerate(listing)}
    out: list[dict] = []
    st = res["static"]
    for p, value in report.get("span_mm", {}).items():
        _row(out, ("geometry", p), "span_mm", st["span_length_mm"][_span_index(names, p, nxt[p])], value)
    for p, value in report.get("wrap_deg", {}).items():
        _row(out, ("geometry", p), "wrap_deg", st["wrap_deg"][names.index(p)], value)
    if report.get("take_up_mm_per_deg") is not None:
        _row(out, ("geometry", "tensioner"), "take_up_mm_per_deg", st["take_up_mm_per_rad"] * np.pi / 180.0,
             report["take_up_mm_per_deg"])
    rows = {r["position"]: r for r in res.get("positions", {}).get("rows", [])}
    for pos in report.get("positions", []):
        ours = rows.get(_REPORT_NAME[pos["name"]])
        if ours is None or not ours["found"]:
            out.append({"table": "positions", "row": pos["name"], "quantity": "found", "ours": None, "report": None,
                        "difference": float("inf"), "unit": "missing"})
            continue
        for key, field in _POSITION_KEYS.items():
            if key in pos:
                _row(out, ("positions", pos["name"]), key, ours.get(field), pos[key])
    duty = res.get("duty")
    for k, point in enumerate(report.get("duty", [])):
        if duty is None:
            break
        i = int(np.argmin(np.abs(np.asarray(duty["speed_rpm"]) - point["rpm"])))
        for p, value in point.get("T", {}).items():
            _row(out, ("duty", f"{point['rpm']} rpm"), f"T {p}", duty["tension_n"][i][_span_index(names, p, nxt[p])],
                 value)
        for p, value in point.get("H", {}).items():
            _row(out, ("duty", f"{point['rpm']} rpm"), f"H {p}", duty["hub_load_n"][i][names.index(p)], value)
    system = res.get("modes", {}).get("system")
    if report.get("mode1_hz") is not None and system:
        _row(out, ("modes", "first"), "mode1_hz", system["frequency_hz"][0], report["mode1_hz"])
    return out


def summary(rows: list[dict], table: str | None = None) -> dict:
    """The largest differences: ``angle_deg`` (absolute, degrees) and ``relative`` (absolute) over ``rows`` (of
    one table, or all), with the row of each; missing positions count as infinite."""
    sel = [r for r in rows if table is None or r["table"] == table]
    ang = [r for r in sel if r["unit"] == "deg"]
    rel = [r for r in sel if r["unit"] != "deg"]
    worst_a = max(ang, key=lambda r: abs(r["difference"]), default=None)
    worst_r = max(rel, key=lambda r: abs(r["difference"]), default=None)
    return {"values": len(sel), "angle_deg": abs(worst_a["difference"]) if worst_a else 0.0, "angle_row": worst_a,
            "relative": abs(worst_r["difference"]) if worst_r else 0.0, "relative_row": worst_r}
