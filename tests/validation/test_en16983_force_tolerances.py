"""DIN EN 16983 (DIN 2093) manufacturing tolerance of a disc spring's force at the test length l0 - 0.75 h0.

Source: DIN EN 16983:2016 (formerly DIN 2093), force tolerances by thickness, as reproduced by two
manufacturers: Vinsco (vinscospring.com/support/tolerance: group 1 t < 1.25 mm +25/-7.5 %, group 2
1.25-3.0 mm +15/-7.5 %, > 3.0-6.0 mm +10/-5 %, group 3 > 6.0-16 mm +/-5 %) and Mubea
(mubeadiscsprings.com, standard disc springs, general tolerances, Table A: the same percentages).
Tolerance: the percentages are exact numbers of the standard (assertions to 1e-12).
"""

import pytest

from synth.errors import InputError
from synth.model import disc_spring as ds


@pytest.mark.parametrize("t_mm, group, plus, minus", [
    (0.2, 1, 25.0, 7.5), (1.2499, 1, 25.0, 7.5),     # group 1: t < 1.25
    (1.25, 2, 15.0, 7.5), (3.0, 2, 15.0, 7.5),        # group 2: 1.25 <= t <= 3.0
    (3.0001, 2, 10.0, 5.0), (6.0, 2, 10.0, 5.0),      # group 2: 3.0 < t <= 6.0
    (6.0001, 3, 5.0, 5.0), (16.0, 3, 5.0, 5.0),       # group 3: 6.0 < t <= 16
])
def test_tolerance_by_thickness(t_mm, group, plus, minus):
    r = ds.force_tolerance_band_n(1000.0, t_mm)
    assert int(r["group"]) == group
    assert float(r["tol_plus_pct"]) == pytest.approx(plus, abs=1e-12)
    assert float(r["tol_minus_pct"]) == pytest.approx(minus, abs=1e-12)
    assert float(r["force_max_n"]) == pytest.approx(1000.0 * (1 + plus / 100), rel=1e-12)
    assert float(r["force_min_n"]) == pytest.approx(1000.0 * (1 - minus / 100), rel=1e-12)


@pytest.mark.parametrize("t_mm", [0.0, -1.0, 16.5])
def test_thickness_outside_the_standard(t_mm):
    with pytest.raises(InputError, match="thickness_mm"):
        ds.force_tolerance_band_n(100.0, t_mm)
