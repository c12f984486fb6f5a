"""Export time per assembly of the CAD model (thesis step 11), one row per product family.

Run: ``.venv/bin/python benchmarks/bench_cad.py [OUT_DIR]`` (default ``out/bench_cad``; prints a
markdown table). Cases 1 and 3 run through the flowchart; the other families are the case
inputs modified (reverse layout: case 1 with the belt plane at 16 mm; single eccentric:
case 3). Every export writes the STEP assembly, one STL per part, the exploded and the
section pictures (``OUT_DIR/<family>/exploded.png`` and ``section.png``) and ``cad_report.json``.
"""

from __future__ import annotations

import dataclasses
import sys
import time
from pathlib import Path

from synth import flowchart
from synth.io import documents
from synth.cad import geometry_from
from synth.cad.assembly import build
from synth.cad.export import export_model
from synth.cad.verify import failed, verify_model

from synth.data import CASES_DIR as CASES


def families():
    d1, d3 = (documents.load_input(CASES / f"{c}.yaml") for c in ("case1", "case3"))
    return {
        "case1 (standard, axial, rect. wire, double ecc., toothed)": d1,
        "case3 (standard, radial only, round wire, double ecc., flat)": d3,
        "case1 reverse (belt plane 16 mm)": dataclasses.replace(d1, middle_plane_belt_height_mm=16.0),
        "case3 single eccentric (autosetting)": dataclasses.replace(d3, belt_loading_type="single_eccentric",
                                                                    loading_arm_mm=None),
    }


def main(out=Path("out/bench_cad")) -> None:
    print("| family | parts | build [s] | STEP export [s] | STL [s] | pictures [s] | verification [s] | failed checks |")
    print("|---|---|---|---|---|---|---|---|")
    for i, (label, d) in enumerate(families().items()):
        g = geometry_from(flowchart.run(d))
        model = build(g)
        t = time.perf_counter()
        checks = verify_model(model)
        t_ver = time.perf_counter() - t
        folder = Path(out) / f"family{i + 1}"
        info = export_model(model, folder, checks=checks)["timings_s"]
        bad = ", ".join(c.name for c in failed(checks) if not c.name.startswith("interference ")) or "none"
        print(f"| {label} | {len(model.parts)} | {info['build']:.2f} | {info['step']:.2f} | {info['stl']:.2f} | "
              f"{info['pictures']:.2f} | {t_ver:.2f} | {bad} |")
    print(f"\npictures and STEP files in {out}/family*/")


if __name__ == "__main__":
    main(Path(sys.argv[1]) if len(sys.argv) > 1 else Path("out/bench_cad"))
