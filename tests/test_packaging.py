"""Step 7, packaging (thesis eq. 50-54): hand calculations, case studies 1 and 3, properties."""

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st

from synth import catalog
from synth.design import evaluate
from synth.design.applications import Applications
from synth.design.constraints import REGISTRY, margin
from synth.design.verify import verify
from synth.errors import InputError
from synth.model import packaging as s7

from conftest import case_input, load_case, tool_design, tool_parts

# 6006 bearing: B = 13 mm, D = 55 mm
W, D_EXT = 13.0, 55.0
STEP7 = ("spring_cavity", "belt_plane", "pulley_axial_space")
NO_AXIAL = dict(damper_pad_class="none", endcap_spacer_class="none", cone_spring_aspect_ratio=0.0,
                cone_spring_deflection_ratio=0.0)


def verify_case(name, parts=None, **changes):
    """Case ``name``'s design with the thesis tool's plastic elements (or it with ``parts`` changes) verified for the
    case with input ``changes``."""
    return verify(case_input(name, **changes), dict(tool_parts(name), **(parts or {})))


@pytest.mark.parametrize("name", ["case1_as_run", "case3"])
def test_spring_housing_height_reproduces_tables(name):
    # eq. (52) + damper pad: case 1: 29.5 - 6.5 - (1.5 + 2.0 + 0.7 + 0.5) - 3.5 = 14.8 (Table 10: 14.8)
    #                        case 3: 20.0 - 6.5 - 4.7 = 8.8 (Table 14: 8.8), no axial damping
    case = load_case(name)
    inp, out = case["inputs"], case["thesis_tool"]
    h = s7.spring_housing_height_mm(inp["middle_plane_belt_height_mm"], W, axial_damping=bool(out["axial_damping_present"]),
                                    damper_pad_height_mm=out.get("damper_pad_axial_height_mm") or 0.0)
    assert float(h) == pytest.approx(out["spring_housing_height_mm"], rel=1e-3)
    # the same through the evaluator (with the tool's plastic elements), and step 7's constraints pass
    r = tool_design(name)
    assert r.get("spring_housing_height_mm") == pytest.approx(out["spring_housing_height_mm"], rel=1e-3)
    assert [r.check(c).verdict for c in STEP7] == ["pass"] * 3


def test_printed_eq52_without_damper_pad_misses_case1():
    # as printed (no damper pad): 29.5 - 6.5 - 4.7 = 18.3 mm, 24 % above Table 10's 14.8 mm
    assert float(s7.spring_housing_height_mm(29.5, W, axial_damping=False)) == pytest.approx(18.3)
    # the pad height is ignored without axial damping
    assert float(s7.spring_housing_height_mm(29.5, W, axial_damping=False, damper_pad_height_mm=3.5)) == \
        pytest.approx(18.3)


def test_eq50_eq54_case_values():
    # eq. (50): case 1: 40 - 6.5 - 1.5 - 1.2 - 1.0 = 29.8 ; case 3 (no endcap spacer): 34 - 6.5 - 2.2 = 25.3
    assert s7.max_belt_plane_height_mm([40.0, 34.0], W, [1.5, 0.0]).tolist() == pytest.approx([29.8, 25.3])
    # eq. (54): 55 - 2*5 = 45 (case 1, spring body 41 fits) ; 55 - 2*4 = 47 (case 3, spring body 44)
    assert s7.spring_housing_outer_diameter_mm(D_EXT, [5.0, 4.0]).tolist() == [45.0, 47.0]


def test_case_margins_by_hand():
    r1 = tool_design("case1_as_run")
    # belt plane (29.8 - 29.5)/29.8 ; pulley top 29.5 + 10 = 39.5 vs 42 -> 2.5/42
    assert (r1.check("belt_plane").value, r1.check("belt_plane").limit) == pytest.approx((29.5, 29.8))
    assert r1.check("belt_plane").margin == pytest.approx(0.3 / 29.8)
    assert r1.check("pulley_axial_space").margin == pytest.approx(2.5 / 42.0)
    # spring cavity 14.8 vs 3.0 minimum
    assert r1.check("spring_cavity").margin == pytest.approx((14.8 - 3.0) / 3.0)


def test_worst_belt_increment_would_fail_case3():
    # 20 + 2 + 15 = 37 > 36.3 (0.7 mm over): the thesis tool (which passed case 3) used the nominal belt plane,
    # and so does the registry's pulley-top check (eq. (26)); a belt plane at its worst increment fails it
    nominal = evaluate.inputs(Applications.of([case_input("case3")]), np.zeros(1, int))
    assert nominal.margins["pulley_axial_space"][0] == pytest.approx((36.3 - 35.0) / 36.3)
    worst = evaluate.inputs(Applications.of([case_input("case3", middle_plane_belt_height_mm=22.0)]), np.zeros(1, int))
    assert float(worst.values["pulley_top_mm"][0] - worst.values["max_axial_displacement_mm"][0]) == pytest.approx(0.7)
    assert worst.margins["pulley_axial_space"][0] == pytest.approx(-0.7 / 36.3)


def test_failing_belt_plane_suggests_correction():
    # case 1's design with the belt plane at 31 mm: 31 - 29.8 = 1.2 mm too high (pulley top 41 <= 45 passes)
    r = verify_case("case1_as_run", max_axial_displacement_mm=45.0, middle_plane_belt_height_mm=31.0)
    c = r.check("belt_plane")
    assert c.verdict == "fail" and c.value - c.limit == pytest.approx(1.2)
    assert "lower belt plane" in c.as_dict()["correction"]
    ok = r.check("pulley_axial_space")
    assert ok.verdict == "pass" and ok.as_dict()["correction"] == ""


def test_reverse_layout_by_hand():
    # eq. (51): 6.5 + 1.5 + 3.0 = 11.0 ; eq. (53): 40 - 1.2 - 1.0 - 0.7 - 12 - 6.5 - 1.5 - 3.5 = 13.6
    assert float(s7.min_belt_plane_height_mm(W, 1.5)) == pytest.approx(11.0)
    assert float(s7.spring_housing_height_mm(12.0, W, layout="reverse", max_pivot_height_mm=40.0, axial_damping=True,
                                             damper_pad_height_mm=3.5)) == pytest.approx(13.6)
    # case 1's design with the belt plane at 12 mm (below half the 40 mm pivot height: the reverse layout)
    r = verify_case("case1_as_run", middle_plane_belt_height_mm=12.0, max_axial_displacement_mm=30.0)
    assert r.get("architecture") == "rotary_reverse"
    assert r.get("spring_housing_height_mm") == pytest.approx(13.6)
    assert r.check("belt_plane").verdict == "not applicable"
    assert r.check("belt_plane_reverse").margin == pytest.approx(1.0 / 11.0)
    # without endcap spacer mpbh_min = 9.5: a belt plane at 9 mm is 0.5 mm too low
    assert float(s7.min_belt_plane_height_mm(W, 0.0)) == pytest.approx(9.5)
    low = verify_case("case1_as_run", NO_AXIAL, middle_plane_belt_height_mm=9.0, max_axial_displacement_mm=30.0)
    c = low.check("belt_plane_reverse")
    assert c.verdict == "fail" and c.limit - c.value == pytest.approx(0.5)
    assert "higher belt plane" in c.as_dict()["correction"]


def test_errors():
    with pytest.raises(InputError, match="max_pivot_height_mm"):
        s7.spring_housing_height_mm(12.0, W, layout="reverse")
    with pytest.raises(InputError, match="standard or reverse"):
        s7.spring_housing_height_mm(20.0, W, layout="sideways")


def test_constants_have_sources():
    for name in ("endcap_height_mm", "calking_height_mm", "support_plate_thickness_mm", "pivot_base_height_mm"):
        assert str(catalog.constant_row(name)["source"]).strip()


def test_vectorised():
    # 301 belt planes of case 1 in one call; the registry's margins of spring cavity and belt plane on the arrays
    mpbh = np.linspace(10.05, 40.05, 301)  # grid off the limits 17.7 and 29.8
    h = s7.spring_housing_height_mm(mpbh, W, axial_damping=True, damper_pad_height_mm=3.5)
    lim = s7.max_belt_plane_height_mm(40.0, W, 1.5)
    assert h.shape == (301,) and float(lim) == pytest.approx(29.8)
    # spring cavity mpbh - 6.5 - 4.7 - 3.5 >= 3 -> mpbh >= 17.7 ; eq. (50) mpbh <= 29.8
    ok = (margin(REGISTRY["spring_cavity"], h, catalog.constant("spring_cavity_min_height_mm")) >= 0) & \
         (margin(REGISTRY["belt_plane"], mpbh, lim) >= 0)
    assert np.array_equal(ok, (mpbh >= 17.7) & (mpbh <= 29.8))


@settings(max_examples=50, deadline=None)
@given(mpbh=st.floats(0.0, 100.0), dm=st.floats(0.0, 20.0), h=st.floats(1.0, 100.0), w=st.floats(1.0, 60.0),
       axial=st.booleans(), layout=st.sampled_from(s7.LAYOUTS))
def test_monotonic_and_finite(mpbh, dm, h, w, axial, layout):
    kw = dict(layout=layout, axial_damping=axial, damper_pad_height_mm=2.5, max_pivot_height_mm=h)
    es = 1.5 if axial else 0.0
    h1 = s7.spring_housing_height_mm(mpbh, W, **kw)
    h2 = s7.spring_housing_height_mm(mpbh + dm, W, **kw)
    if layout == "standard":
        lim = s7.max_belt_plane_height_mm(h, W, es)
        m1, m2 = (margin(REGISTRY["belt_plane"], x, lim) for x in (mpbh, mpbh + dm))
    else:
        lim = s7.min_belt_plane_height_mm(W, es)
        m1, m2 = (margin(REGISTRY["belt_plane_reverse"], x, lim) for x in (mpbh, mpbh + dm))
    t1, t2 = (margin(REGISTRY["pulley_axial_space"], x + w / 2.0, 50.0) for x in (mpbh, mpbh + dm))  # eq. (26)
    for v in (h1, h2, lim, m1, m2, t1, t2):
        assert np.all(np.isfinite(np.asarray(v, dtype=float)))
    # a higher belt plane: less room at the pulley top
    assert float(t2) <= float(t1) + 1e-12
    # a higher belt plane: less room below a standard bearing (taller spring housing), more above a reverse one
    if layout == "standard":
        assert float(m2) <= float(m1) + 1e-12
        assert float(h2) >= float(h1)
    else:
        assert float(m2) >= float(m1) - 1e-12
        assert float(h2) <= float(h1)
