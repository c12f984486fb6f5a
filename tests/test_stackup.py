"""Step 6, axial stack-up of the cone-spring gap (thesis Table 6)."""

import math

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st

from synth.errors import InputError
from synth.model.stackup import component_tolerances_mm, gap_stackup, gap_tolerance_mm


def test_table6_worst_case_is_the_printed_overall():
    # thesis Table 6: pivot 0.07 + endcap spacer 0.05 + arm 0.05 + damper pad 0.05 = "Overall +/-0.22"
    assert component_tolerances_mm() == {"pivot": 0.07, "endcap_spacer": 0.05, "arm": 0.05, "damper_pad": 0.05}
    assert gap_tolerance_mm("worst_case") == pytest.approx(0.22, abs=1e-12)


def test_rss_hand_calculation():
    # sqrt(0.07^2 + 3 * 0.05^2) = sqrt(0.0049 + 0.0075) = sqrt(0.0124) = 0.11136
    assert gap_tolerance_mm("rss") == pytest.approx(math.sqrt(0.0124), rel=1e-12)
    assert gap_tolerance_mm("rss") == pytest.approx(0.11136, rel=1e-4)


def test_override_one_component():
    # a tighter pivot (0.03): worst case 0.03 + 0.15 = 0.18
    assert gap_tolerance_mm("worst_case", {"pivot": 0.03}) == pytest.approx(0.18)


def test_gap_nominal_and_limits_hand_calculation():
    # case-1-like stack: pivot 40, endcap spacer 1.5 (Table 4), arm 30, damper pad 3.5 (Table 3): 40-1.5-30-3.5 = 5.0
    r = gap_stackup(40.0, 1.5, 30.0, 3.5)
    assert float(r["gap_height_nominal_mm"]) == pytest.approx(5.0)
    assert float(r["gap_height_min_mm"]) == pytest.approx(4.78)
    assert float(r["gap_height_max_mm"]) == pytest.approx(5.22)
    assert float(r["margin_gap_positive"]) == pytest.approx(4.78 / 0.22)


def test_vectorised_and_negative_gap_flagged():
    r = gap_stackup(np.array([40.0, 35.1]), 1.5, 30.0, 3.5, method="rss")
    assert r["gap_height_nominal_mm"].shape == (2,)
    assert r["margin_gap_positive"][0] > 0 and r["margin_gap_positive"][1] < 0   # 0.1 mm gap < 0.111 tolerance


def test_errors():
    with pytest.raises(InputError, match="stackup_method"):
        gap_tolerance_mm("monte_carlo")
    with pytest.raises(InputError, match="tolerances_mm"):
        gap_tolerance_mm("rss", {"bolt": 0.1})


@settings(max_examples=60, deadline=None)
@given(st.floats(0.0, 0.5), st.floats(0.0, 0.5), st.floats(0.0, 0.5), st.floats(0.0, 0.5))
def test_rss_never_exceeds_worst_case(a, b, c, d):
    tol = {"pivot": a, "endcap_spacer": b, "arm": c, "damper_pad": d}
    assert gap_tolerance_mm("rss", tol) <= gap_tolerance_mm("worst_case", tol) + 1e-12
    assert gap_tolerance_mm("rss", tol) >= max(a, b, c, d) - 1e-12
