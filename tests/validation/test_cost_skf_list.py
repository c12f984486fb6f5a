"""The bearing price relation against the SKF dealer list it is fitted to (relative prices).

Source (cited in the fixture's header, tests/validation/data/skf_dealer_list_2022.csv): the SKF dealer list
prices effective 1 Dec 2022 transcribed in public code (Abhishek-Doshi/skf-codes @8cf3007, data.js, "Domestic.pdf"
entries), 22 deep groove ball bearings 60xx/62xx/63xx with cited boundary dimensions, open and -Z, -2Z, -RS1,
-2RS1, /C3 variants; currency not stated, so only ratios are used. The fit's coefficient and scatter are the
constants of ``catalogs/constants_cost.csv`` to their printed digits (half a unit of the last one).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from synth import catalog
from synth.cost import bought

DATA = Path(__file__).resolve().parent / "data"
LIST = pd.read_csv(DATA / "skf_dealer_list_2022.csv", comment="#", dtype={"designation": str})


def _fit():
    mass = bought.bearing_envelope_mass_kg(LIST.d_mm, LIST.D_mm, LIST.B_mm)
    x, y = np.log(mass), np.log(LIST.open.to_numpy(float))
    b, a = np.polyfit(x, y, 1)
    res = y - (a + b * x)
    return b, a, float(np.corrcoef(x, y)[0, 1]), float(res.std(ddof=2))


def test_fixture_is_the_list_as_transcribed():
    assert len(LIST) == 22
    row = LIST.set_index("designation")
    assert (row.loc["6006", "open"], row.loc["6006", "2RS1"], row.loc["6205", "2Z"]) == (329, 395, 386)
    assert row.loc["6207", "open"] < row.loc["6206", "open"]  # not monotone in size: fit a relation, no interpolation


def test_price_grows_with_mass_to_the_power_of_the_constant():
    b, _, r, scatter = _fit()
    assert b == pytest.approx(catalog.constant("cost_bearing_mass_exponent"), abs=5e-5)
    assert scatter == pytest.approx(catalog.constant("cost_bearing_fit_scatter"), abs=5e-5)
    assert 0.45 < b < 0.55 and r == pytest.approx(0.888, abs=5e-4)  # about the square root, r about 0.9


@pytest.mark.parametrize("variant", ["Z", "2Z", "RS1", "2RS1"])
def test_seal_factors_are_the_lists_geometric_means(variant):
    has = LIST[variant].notna()
    ratio = np.log(LIST[variant][has].to_numpy(float) / LIST.open[has].to_numpy(float))
    assert float(np.exp(ratio.mean())) == pytest.approx(catalog.constant(f"cost_bearing_seal_factor_{variant}"),
                                                        abs=5e-4)
    assert float(ratio.std(ddof=1)) <= catalog.constant("cost_bearing_seal_factor_scatter") + 5e-4


def test_sealed_costs_about_1_3_shielded_about_1_16_clearance_nothing():
    c = catalog.constant
    assert c("cost_bearing_seal_factor_2RS1") == pytest.approx(1.3, abs=0.01)
    assert c("cost_bearing_seal_factor_Z") < 1.16 < c("cost_bearing_seal_factor_2Z")
    assert (LIST.C3 == LIST.open).all()


def test_the_relation_reproduces_the_lists_prices_within_its_scatter():
    """The relation anchored at one listed bearing (6006) is the fit moved by that bearing's own residual, and the
    fit holds 20 of the 22 listed prices within two of its scatters."""
    b, a, _, scatter = _fit()
    mass = bought.bearing_envelope_mass_kg(LIST.d_mm, LIST.D_mm, LIST.B_mm)
    price = LIST.open.to_numpy(float)
    res = np.log(price) - (a + b * np.log(mass))
    i = int(np.flatnonzero(LIST.designation == "6006")[0])
    model = bought.relation_price(price[i], mass, float(mass[i]), catalog.constant("cost_bearing_mass_exponent"))
    assert np.allclose(np.log(price / model), res - res[i], atol=2e-4)
    assert int((np.abs(res) <= 2 * scatter).sum()) >= 20
