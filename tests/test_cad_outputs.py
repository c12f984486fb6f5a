"""CAD outputs for a design review: the STEP header (read back with OCP), the section's dimensions and
hatching, the exploded view's labels."""

from __future__ import annotations

import cadquery as cq
import numpy as np
import pytest

import synth
from synth import flowchart
from synth.cad import export_result, geometry_from
from synth.cad.assembly import build
from synth.cad.dimensions import _example_inputs, _example_values
from synth.cad.pictures import _draw, _figure, _visible_anchors, exploded_parts, section_dimensions, section_parts
from synth.cad.step import DESIGN_KEYS, design_values, read_step_header
from synth.data import CASES_DIR
from synth.io.documents import load_input


@pytest.fixture(scope="module")
def case1(tmp_path_factory):
    r = flowchart.run(load_input(CASES_DIR / "case1.yaml"))
    out = tmp_path_factory.mktemp("cad1")
    model, checks, info = export_result(r, out, stl=False, application="thesis case 1")
    return r, model, out


def test_step_header_names_the_application_and_synth(case1):
    r, model, out = case1
    h = read_step_header(out / "tensioner.step")  # a second reader: OCP's own STEP reader, not cadquery's import
    assert h["name"] == "synth tensioner thesis case 1"
    assert h["author"] == h["organisation"] == f"synth {synth.__version__}"
    assert cq.Assembly.importStep(str(out / "tensioner.step")).name == "synth tensioner thesis case 1"


def test_step_header_carries_the_key_design_values(case1):
    r, model, out = case1
    desc = read_step_header(out / "tensioner.step")["description"]
    values = dict(line.split("=", 1) for line in desc if "=" in line)
    assert values["status"].startswith(r.verdict)
    assert values["ball_bearing"] == r.get("ball_bearing") == "6006"
    assert float(values["pivot_class_diameter_mm"]) == r.get("pivot_class_diameter_mm") == 16
    assert values["main_spring_material"] == r.get("main_spring_material")
    assert values["main_spring_wire"] == "rectangular b x h 2.5 x 2.5 mm"
    assert float(values["main_spring_mean_body_diameter_mm"]) == r.get("main_spring_mean_body_diameter_mm")
    assert values["bolt_format"] == r.get("bolt_format") and values["bolt_property_class"] == r.get("bolt_property_class")
    assert values["damper_pad_class"] == r.get("damper_pad_class") and values["pivot_bushing_supplier"] == "A"
    assert [k for k in values if k != "status"] == [k for k in DESIGN_KEYS if k in values]


def test_design_values_of_a_saved_design_json():
    m = build(geometry_from(_example_values(), inputs=_example_inputs()))
    saved = {"parts": {"ball_bearing": "6006", "pivot_bushing_supplier": "B", "damper_pad_class": "none",
                       "main_spring_material": "VDSiCr", "bolt_property_class": "12.9", "pivot_class_diameter_mm": 16.0},
             "values": {}, "checks": []}
    d = design_values(m, saved)
    assert d["pivot_bushing_supplier"] == "B" and d["main_spring_material"] == "VDSiCr"
    assert d["bolt_property_class"] == "12.9" and "damper_pad_class" not in d  # "none": no pad
    assert d["pivot_class_diameter_mm"] == 16.0


def test_section_dimensions_are_the_designs(case1):
    r, model, _ = case1
    g = model.geometry
    d = {x.label: x for x in section_dimensions(model)}
    assert d["pulley"].value_mm == r.inputs["pulley_diameter_mm"] == 66 and d["pulley"].diameter
    assert d["belt plane"].value_mm == r.inputs["middle_plane_belt_height_mm"] == 29.5
    assert d["pivot height"].value_mm == pytest.approx(model.parts["pivot"].BoundingBox().zmax, abs=0.02)
    assert d["pivot bushing"].value_mm == g.pivot_bushing_length_mm
    assert d["spring housing"].value_mm == r.values["spring_housing_outer_diameter_mm"]
    assert d["housing height"].value_mm == pytest.approx(g.spring_housing_height_mm)
    for x in d.values():  # each line spans its value
        assert np.hypot(x.b[0] - x.a[0], x.b[1] - x.a[1]) == pytest.approx(x.value_mm)


def test_section_hatches_exactly_the_cut_faces(case1):
    _, model, _ = case1
    plt, fig, ax = _figure("t", 4, 50, legend=True)
    shapes = section_parts(model)
    _draw(ax, shapes, "section", hatch_cut=True)
    hatched = [c for c in ax.collections if c.get_hatch()]
    plt.close(fig)
    # every part is cut by the plane through the pivot axis except the balls and coils off the plane
    assert len(hatched) >= len(shapes) - 2
    for c in hatched:  # hatched polygons lie in the section plane (they are drawn in x, z)
        assert c.get_zorder() > 1


def test_exploded_view_labels_every_visible_part(case1):
    _, model, _ = case1
    plt, fig, ax = _figure("t", 6.5, 110, legend=False)
    shapes = exploded_parts(model)
    projected = _draw(ax, shapes, "iso", hatch_cut=False)
    pts = np.concatenate(list(projected.values()))
    ax.set_xlim(pts[:, 0].min(), pts[:, 0].max())
    ax.set_ylim(pts[:, 1].min(), pts[:, 1].max())
    ax.set_aspect("equal")
    anchors = _visible_anchors(shapes, fig, ax, "iso")
    plt.close(fig)
    assert set(anchors) == set(model.parts)
    top = {n: projected[n][:, 1].max() for n in anchors}
    assert anchors["fixation_bolt"][1] == pytest.approx(top["fixation_bolt"], abs=0.1 * (top["fixation_bolt"] - pts[:, 1].min()))


def test_pictures_and_report(case1):
    _, _, out = case1
    import json
    report = json.loads((out / "cad_report.json").read_text())
    assert report["application"] == "thesis case 1" and report["design"]["ball_bearing"] == "6006"
    from matplotlib.image import imread
    for name in ("section.png", "exploded.png"):
        img = imread(out / name)
        assert img.shape[1] > img.shape[0] > 600  # landscape, room for the legend or labels
