"""The bolt price relation and the quantity breaks against the fastener distributor's list they are fitted to.

Source (cited in the fixture's header, tests/validation/data/oomlout_m8_set_screw_breaks.csv): ISO 4017 M8 8.8
zinc-plated set screws, 23 lengths 10-150 mm, unit prices at 1, 100, 200, 1,000 and 10,000 pieces, transcribed in
public code (oomlout/oomlout_oomp_version_1_only_yaml, parts/hardware_set_screw_m8_*); currency not stated, so
only ratios are used. The fit's coefficient and scatter, and the break factors, are the constants of
``catalogs/constants_cost.csv`` and the rows of ``catalogs/price_breaks.csv`` to their printed digits.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from synth import catalog
from synth.cost import bought

DATA = Path(__file__).resolve().parent / "data"
LIST = pd.read_csv(DATA / "oomlout_m8_set_screw_breaks.csv", comment="#")
BREAKS = {1: "price_1", 100: "price_100", 200: "price_200", 1000: "price_1000", 10000: "price_10000"}


def _mass():  # ISO 4017 M8 head: s 13, k 5.3 (catalogs/bolt_heads.csv, the reference bolt's head)
    return bought.bolt_mass_kg(8.0, LIST.length_mm.to_numpy(float), 13.0, 5.3, True)


def _fit(rows):
    x, y = np.log(_mass()[rows]), np.log(LIST.price_10000.to_numpy(float)[rows])
    b, a = np.polyfit(x, y, 1)
    return b, float(np.corrcoef(x, y)[0, 1]), float((y - (a + b * x)).std(ddof=2))


def test_fixture_is_the_list_as_transcribed():
    assert len(LIST) == 23 and LIST.length_mm.min() == 10 and LIST.length_mm.max() == 150
    row = LIST.set_index("length_mm")
    assert tuple(row.loc[45, list(BREAKS.values())]) == (0.0874, 0.0874, 0.0546, 0.0492, 0.0437)


def test_price_at_1000_is_about_half_the_price_at_one():
    ratio = LIST.price_1000 / LIST.price_1
    assert ratio.between(0.49, 0.57).all() and float(np.exp(np.log(ratio).mean())) == pytest.approx(0.52, abs=0.01)


@pytest.mark.parametrize("q", sorted(BREAKS))
def test_break_factors_are_the_lists_geometric_means(q):
    row = catalog.row("price_breaks", str(q))
    r = np.log(LIST[BREAKS[q]] / LIST.price_1)
    assert float(np.exp(r.mean())) == pytest.approx(float(row["factor"]), abs=5e-5)
    assert float(r.std(ddof=1)) == pytest.approx(float(row["scatter"]), abs=5e-5)


def test_mass_exponent_over_the_stock_lengths_and_scatter_over_the_whole_list():
    stock = LIST.length_mm.to_numpy() <= 55
    b, r, scatter = _fit(stock)
    assert b == pytest.approx(catalog.constant("cost_fastener_mass_exponent"), abs=5e-5)
    assert r > 0.999 and scatter < 0.02
    b_all, _, scatter_all = _fit(np.ones(len(LIST), bool))
    assert scatter_all == pytest.approx(catalog.constant("cost_fastener_fit_scatter"), abs=5e-5)
    assert b_all == pytest.approx(1.297, abs=5e-4)  # the long lengths are another price class: not the fixation bolt's


def test_the_quantity_relation_carries_a_reference_to_a_small_volume():
    curve = tuple(sorted((float(r["quantity"]), float(r["factor"]), float(r["scatter"]))
                         for _, r in catalog.load("price_breaks").iterrows()))
    k, s = bought.quantity_factor(500, 100000, curve)
    assert k == pytest.approx(0.6252 / 0.4999) and s == pytest.approx(0.0011)
    assert bought.quantity_factor(250000, 100000, curve) == (1.0, 0.0)
