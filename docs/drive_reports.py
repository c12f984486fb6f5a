"""Print the drive-report tables of docs/sections/drive.md: ours, the report's, the difference.

    PYTHONPATH=. .venv/bin/python docs/drive_reports.py

Reads the four reports of the validation tests (``tests/validation/data/gates_*.yaml``), the report kept out of
the tests (``synth/data/drives/reports/gates_ag0868_8pk.yaml``) and the drives of ``synth/data/drives/``; compares
them with :func:`synth.drive.compare.compare_with_report`; fits EA per rib on each drive whose vibration inputs are
transcribed (:func:`synth.drive.modes.system_modes`, :func:`scipy.optimize.brentq`).
"""

from __future__ import annotations

from pathlib import Path

import yaml
from scipy.optimize import brentq

ROOT = Path(__file__).resolve().parents[1]
DRIVES = ROOT / "synth" / "data" / "drives"
REPORTS = [ROOT / "tests" / "validation" / "data" / f"{n}.yaml"
           for n in ("gates_ag00686", "gates_ag00810", "gates_ag00879", "gates_ag00976_1715")] + \
    [DRIVES / "reports" / "gates_ag0868_8pk.yaml"]
#: drives with the vibration page's inputs, and the report's Mode 1 [Hz] (the PDF's where the fixture differs)
MODES = {"gates_ag00686": 12.61, "gates_ag00810": 15.05, "gates_ag0868_8pk": 45.62, "gates_ag00686_1520": 12.61,
         "gates_ag0868_6pk": 37.61, "gates_ag0868_4pk": 28.28}


def _where(row):
    return f"{row['row']} {row['quantity']}" if row else "-"


def main() -> None:
    from synth.drive.belt import EA_PER_RIB_N, EA_PER_RIB_RANGE_N
    from synth.drive.compare import compare_with_report, summary
    from synth.drive.inputs import load_drive
    from synth.drive.modes import system_modes

    print("| report | in tests | values | positions: largest angle diff [deg] | positions: largest relative diff "
          "| duty: largest relative diff | geometry (spans, wraps, take-up) |")
    print("|---|---|---|---|---|---|---|")
    detail = None
    for path in REPORTS:
        rep = yaml.safe_load(path.read_text(encoding="utf-8"))
        drive = load_drive(DRIVES / rep["drive"])
        rows = [r for r in compare_with_report(drive, rep) if r["table"] != "modes"]
        p, d, g = summary(rows, "positions"), summary(rows, "duty"), summary(rows, "geometry")
        print(f"| {rep['report']} | {'yes' if 'tests' in path.parts else 'no'} | {len(rows)} "
              f"| {p['angle_deg']:.3f} ({_where(p['angle_row'])}) | {100 * p['relative']:.2f} % "
              f"({_where(p['relative_row'])}) | {100 * d['relative']:.2f} % ({_where(d['relative_row'])}) "
              f"| {100 * g['relative']:.2f} %, {g['angle_deg']:.3f} deg |")
        if rep["report"] == "AG00686":
            detail = rows
    print("\nAG00686, the position table (ours / the report's / the difference: degrees for angles, % otherwise):\n")
    names = ["Free Arm", "Replace", "Max", "Mean", "Min", "Load"]
    print("| quantity | " + " | ".join(names) + " |")
    print("|---|" + "---|" * len(names))
    for q in ("rel", "abs", "X", "Y", "beta", "dir", "hub", "T", "wrap", "EDL", "REBL"):
        cells = []
        for n in names:
            r = next(x for x in detail if x["table"] == "positions" and x["row"] == n and x["quantity"] == q)
            diff = f"{r['difference']:+.2f}" if r["unit"] == "deg" else f"{100 * r['difference']:+.2f} %"
            cells.append(f"{r['ours']:.1f} / {r['report']:g} / {diff}")
        print(f"| {q} | " + " | ".join(cells) + " |")
    lo, hi = EA_PER_RIB_RANGE_N
    print(f"\nThe first system mode with one EA per rib ({EA_PER_RIB_N:g} N, fitted on AG00686), the EA per rib each "
          f"drive alone would need, and the first mode over the range {lo:g}-{hi:g} N:\n")
    print("| drive | report's Mode 1 [Hz] | ours [Hz] | difference | EA per rib fitted on it alone [N] "
          f"| ours at {lo:g} / {hi:g} N [Hz] |")
    print("|---|---|---|---|---|---|")
    for name, f_report in MODES.items():
        drive = load_drive(DRIVES / f"{name}.yaml")
        f = system_modes(drive)["frequency_hz"][0]
        fit = brentq(lambda ea: system_modes(drive, ea)["frequency_hz"][0] - f_report, 1000.0, 100000.0)
        f_lo, f_hi = (system_modes(drive, e)["frequency_hz"][0] for e in (lo, hi))
        print(f"| {drive.name} | {f_report:g} | {f:.2f} | {100 * (f / f_report - 1):+.1f} % | {fit:.0f} "
              f"| {f_lo:.2f} / {f_hi:.2f} |")


if __name__ == "__main__":
    main()
