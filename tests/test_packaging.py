"""Step 7, packaging (thesis eq. 50-54): hand calculations, case studies 1 and 3, properties."""

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st

from synth import catalog
from synth.checks import FAIL, PASS
from synth.errors import InputError
from synth.model import packaging as s7

from conftest import load_case

# 6006 bearing: B = 13 mm, D = 55 mm
W, D_EXT = 13.0, 55.0


def run_case(name, **kw):
    case = load_case(name)
    inp, out = case["inputs"], case["thesis_tool"]
    axial = bool(out["axial_damping_present"])
    return case, s7.packaging(inp["middle_plane_belt_height_mm"], inp["max_pivot_height_mm"],
                              inp["max_axial_displacement_mm"], W, D_EXT, inp["working_arm_mm"],
                              out["pulley_width_mm"], axial_damping=axial,
                              endcap_spacer_height_mm=out.get("endcap_spacer_axial_height_mm") or 0.0,
                              damper_pad_height_mm=out.get("damper_pad_axial_height_mm") or 0.0, **kw)


@pytest.mark.parametrize("name", ["case1_as_run", "case3"])
def test_spring_housing_height_reproduces_tables(name):
    # eq. (52) + damper pad: case 1: 29.5 - 6.5 - (1.5 + 2.0 + 0.7 + 0.5) - 3.5 = 14.8 (Table 10: 14.8)
    #                        case 3: 20.0 - 6.5 - 4.7 = 8.8 (Table 14: 8.8), no axial damping
    case, r = run_case(name)
    assert float(r["spring_housing_height_mm"]) == pytest.approx(case["thesis_tool"]["spring_housing_height_mm"],
                                                                 rel=1e-3)
    assert bool(r["passes"])


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
    _, r1 = run_case("case1_as_run")
    # belt plane (29.8 - 29.5)/29.8 ; pulley top 29.5 + 10 = 39.5 vs 42 -> 2.5/42
    assert float(r1["margin_belt_plane"]) == pytest.approx(0.3 / 29.8)
    assert float(r1["margin_axial_displacement"]) == pytest.approx(2.5 / 42.0)
    # spring cavity 14.8 vs 3.0 minimum
    assert float(r1["margin_spring_cavity"]) == pytest.approx((14.8 - 3.0) / 3.0)


def test_worst_belt_increment_would_fail_case3():
    # 20 + 2 + 15 = 37 > 36.3: the thesis tool (which passed case 3) used the nominal belt plane
    _, r = run_case("case3", belt_height_increment_mm=2.0)
    assert float(r["reduce_pulley_top_by_mm"]) == pytest.approx(0.7)
    assert float(r["margin_axial_displacement"]) < 0 and not bool(r["passes"])


def test_failing_belt_plane_suggests_correction():
    r = s7.packaging(31.0, 40.0, 45.0, W, D_EXT, 5.0, 20.0, axial_damping=True, endcap_spacer_height_mm=1.5,
                     damper_pad_height_mm=3.5)
    # 31 - 29.8 = 1.2 mm too high
    assert float(r["lower_belt_plane_by_mm"]) == pytest.approx(1.2)
    checks = s7.packaging_checks(r, max_axial_displacement_mm=45.0, belt_plane_height_mm=31.0)
    assert checks[0].verdict == FAIL and "1.20 mm" in checks[0].correction
    assert checks[1].verdict == PASS and checks[1].correction == ""


def test_reverse_layout_by_hand():
    # eq. (51): 6.5 + 1.5 + 3.0 = 11.0 ; eq. (53): 40 - 1.2 - 1.0 - 0.7 - 12 - 6.5 - 1.5 - 3.5 = 13.6
    r = s7.packaging(12.0, 40.0, 30.0, W, D_EXT, 5.0, 20.0, layout="reverse", axial_damping=True,
                     endcap_spacer_height_mm=1.5, damper_pad_height_mm=3.5)
    assert float(r["mpbh_min_mm"]) == pytest.approx(11.0)
    assert float(r["spring_housing_height_mm"]) == pytest.approx(13.6)
    assert float(r["margin_belt_plane"]) == pytest.approx(1.0 / 11.0)
    low = s7.packaging(9.0, 40.0, 30.0, W, D_EXT, 5.0, 20.0, layout="reverse")
    # without endcap spacer mpbh_min = 9.5 -> raise by 0.5
    assert float(low["raise_belt_plane_by_mm"]) == pytest.approx(0.5) and not bool(low["passes"])
    checks = s7.packaging_checks(low, max_axial_displacement_mm=30.0, belt_plane_height_mm=9.0, layout="reverse")
    assert checks[0].verdict == FAIL and "0.50 mm" in checks[0].correction


def test_errors():
    with pytest.raises(InputError, match="max_pivot_height_mm"):
        s7.spring_housing_height_mm(12.0, W, layout="reverse")
    with pytest.raises(InputError, match="standard or reverse"):
        s7.packaging(20.0, 34.0, 36.3, W, D_EXT, 4.0, 30.0, layout="sideways")


def test_constants_have_sources():
    for name in ("endcap_height_mm", "calking_height_mm", "support_plate_thickness_mm", "pivot_base_height_mm"):
        assert str(catalog.constant_row(name)["source"]).strip()


def test_vectorised():
    mpbh = np.linspace(10.05, 40.05, 301)  # grid off the limits 17.7 and 29.8
    r = s7.packaging(mpbh, 40.0, 42.0, W, D_EXT, 5.0, 20.0, axial_damping=True, endcap_spacer_height_mm=1.5,
                     damper_pad_height_mm=3.5)
    assert r["passes"].shape == (301,)
    # spring cavity mpbh - 6.5 - 4.7 - 3.5 >= 3 -> mpbh >= 17.7 ; eq. (50) mpbh <= 29.8 ; top mpbh + 10 <= 42
    expected = (mpbh >= 17.7) & (mpbh <= 29.8)
    assert np.array_equal(r["passes"], expected)


@settings(max_examples=50, deadline=None)
@given(mpbh=st.floats(0.0, 100.0), dm=st.floats(0.0, 20.0), h=st.floats(1.0, 100.0), w=st.floats(1.0, 60.0),
       axial=st.booleans(), layout=st.sampled_from(s7.LAYOUTS))
def test_monotonic_and_finite(mpbh, dm, h, w, axial, layout):
    kw = dict(layout=layout, axial_damping=axial, endcap_spacer_height_mm=1.5 if axial else 0.0,
              damper_pad_height_mm=2.5)
    r1 = s7.packaging(mpbh, h, 50.0, W, D_EXT, 5.0, w, **kw)
    r2 = s7.packaging(mpbh + dm, h, 50.0, W, D_EXT, 5.0, w, **kw)
    for r in (r1, r2):
        assert all(np.all(np.isfinite(np.asarray(v, dtype=float))) for v in r.values())
    # a higher belt plane: less room at the pulley top, more room below a standard bearing
    assert float(r2["margin_axial_displacement"]) <= float(r1["margin_axial_displacement"]) + 1e-12
    if layout == "standard":
        assert float(r2["margin_belt_plane"]) <= float(r1["margin_belt_plane"]) + 1e-12
        assert float(r2["spring_housing_height_mm"]) >= float(r1["spring_housing_height_mm"])
    else:
        assert float(r2["margin_belt_plane"]) >= float(r1["margin_belt_plane"]) - 1e-12
        assert float(r2["spring_housing_height_mm"]) <= float(r1["spring_housing_height_mm"])
