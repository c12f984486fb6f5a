"""ISO 898-1 (stress area, property classes) and ISO 724 (basic diameters) against published tables.

Sources (cited in the fixtures' headers, tests/validation/data/): ``iso898_stress_areas.csv`` (stress areas to
2-3 decimals, GB/T 16823.1 / ISO 898-1 table and Engineers Edge after Bickford), ``iso898_property_classes.csv``
(ISO 898-1:2013 Table 3 minimum Rm and Rp0.2). Tolerance: half a unit of the printed last digit (0.005 or
0.0005 mm^2); the class strengths exactly.
"""

from __future__ import annotations

from pathlib import Path

import pandas as pd
import pytest

from synth import catalog
from synth.model import bolted_joint, vdi2230

DATA = Path(__file__).resolve().parent / "data"
AREAS = pd.read_csv(DATA / "iso898_stress_areas.csv", comment="#", dtype={"stress_area_mm2": str})
CLASSES = pd.read_csv(DATA / "iso898_property_classes.csv", comment="#", dtype={"property_class": str})


@pytest.mark.parametrize("row", list(AREAS.itertuples()), ids=lambda r: r.thread)
def test_stress_area_from_iso724_diameters(row):
    d2, d3, _ = vdi2230.iso724_diameters_mm(row.d_mm, row.pitch_mm)
    decimals = len(row.stress_area_mm2.split(".")[1])
    assert abs(float(vdi2230.stress_area_mm2(d2, d3)) - float(row.stress_area_mm2)) <= 0.5 * 10.0 ** -decimals + 1e-9


def test_catalog_stress_areas_are_the_iso_898_1_values_to_three_figures():
    bolts = catalog.load("bolts")
    for b in bolts.itertuples():
        d2, d3, d1 = vdi2230.iso724_diameters_mm(b.d_mm, b.pitch_mm)
        assert (round(float(d2), 3), round(float(d3), 3), round(float(d1), 3)) == (b.d2_mm, b.d3_mm, b.D1_mm)
        a_s = float(vdi2230.stress_area_mm2(d2, d3))
        assert b.stress_area_mm2 == float(f"{a_s:.3g}")


@pytest.mark.parametrize("row", list(CLASSES.itertuples()), ids=lambda r: f"{r.property_class}-{r.d_range}")
def test_property_classes_iso_898_1_table_3(row):
    c = catalog.row("bolt_property_classes", row.property_class)
    big = row.d_range == "d>16"
    rm = float(c["rm_min_d_gt16_mpa" if big else "rm_min_mpa"])
    rp = float(c["rp02_min_d_gt16_mpa" if big else "rp02_min_mpa"])
    assert (rm, rp) == (row.rm_min_mpa, row.rp02_min_mpa)
    if row.property_class == "9.8":  # defined for d <= 16 mm only
        assert float(c["d_max_mm"]) == 16.0


def test_class_strengths_reach_the_escalation_candidates():
    cands = bolted_joint.bolt_candidates("M8x1.25")
    got = {c["bolt_property_class"]: (c["rm_mpa"], c["rp02_mpa"]) for c in cands}
    table = {r.property_class: (r.rm_min_mpa, r.rp02_min_mpa) for r in CLASSES.itertuples() if r.d_range != "d>16"}
    assert got == table
