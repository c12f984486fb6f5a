"""VDI 2230 Part 1: permissible assembly preload (R7/2) and tightening torque (R13/1) against published tables.

Sources (cited in the fixtures' headers, tests/validation/data/):

- ``vdi2230_table_a2_bossard.csv``: VDI 2230 Table A2 (fine threads, nu = 0.9, mu_G = mu_K = 0.10/0.12/0.14,
  classes 8.8/10.9/12.9, M8x1 to M24x2) as reprinted in the Bossard technical catalogue (page 685, "based on the
  2001 edition of VDI 2230", 90 % utilisation of Rp0.2). 81 preloads and 81 torques.
- ``vdi2230_coarse_example.csv``: Bossard's worked example from its VDI 2230:2015-based tables (M12, mu 0.14,
  F_M max 41.9 kN).

Tolerance: the table rounds (3 significant figures; torques from 40 N*m to whole N*m). Our preloads lie within
half a unit of the last printed digit plus 0.2 % (raw deviation -0.33 % to +0.33 %, e.g. M8x1 10.9 at mu 0.14:
28.98 vs 28.9 kN; beyond the rounding at most 0.13 %), our torques within half a unit plus 0.5 % (beyond the
rounding at most 0.41 %). The table was computed with data we do not have exactly (its d_w, d_h and the
rounding of d2/d3); the residuals are far below the 5-23 % that separate the thesis form from VDI 2230
(tests/test_bolted_joint.py).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from synth.model import vdi2230

DATA = Path(__file__).resolve().parent / "data"
TABLE = pd.read_csv(DATA / "vdi2230_table_a2_bossard.csv", comment="#")
# ISO 898-1:2013 Table 3 Rp0.2 min (tests/validation/test_iso898.py checks the catalog against the standard)
RP02 = {"8.8": (640.0, 660.0), "10.9": (940.0, 940.0), "12.9": (1100.0, 1100.0)}


def _rp(cls, d):
    small, big = RP02[str(cls)]
    return small if d <= 16 else big


def _unit(value):
    """Half a unit of the last printed digit: 3 significant figures, integers from 40 up (torques)."""
    return 0.5 * (1.0 if value >= 100 else 0.1)


def _torque_unit(value):
    return 0.5 * (1.0 if value >= 40 else 0.1)


def _preload_kn(row):
    d2, d3, _ = vdi2230.iso724_diameters_mm(row.d_mm, row.pitch_mm)
    return float(vdi2230.permissible_assembly_preload_n(row.pitch_mm, d2, d3, _rp(row.property_class, row.d_mm),
                                                    row.mu)) / 1e3


def test_fixture_is_complete():
    assert len(TABLE) == 81
    assert set(TABLE["property_class"].astype(str)) == {"8.8", "10.9", "12.9"}
    assert set(TABLE["mu"]) == {0.10, 0.12, 0.14}


@pytest.mark.parametrize("row", list(TABLE.itertuples()), ids=lambda r: f"{r.thread}-{r.property_class}-{r.mu}")
def test_permissible_preload_reproduces_table_a2(row):
    f = _preload_kn(row)
    assert abs(f - row.preload_kn) <= _unit(row.preload_kn) + 0.002 * row.preload_kn


@pytest.mark.parametrize("row", list(TABLE.itertuples()), ids=lambda r: f"{r.thread}-{r.property_class}-{r.mu}")
def test_tightening_torque_reproduces_table_a2(row):
    d2, _, _ = vdi2230.iso724_diameters_mm(row.d_mm, row.pitch_mm)
    m = float(vdi2230.assembly_torque_nm(_preload_kn(row) * 1e3, row.pitch_mm, d2, row.mu,
                                     vdi2230.head_mean_diameter_mm(row.dw_mm, row.dh_mm), row.mu))
    assert abs(m - row.torque_nm) <= _torque_unit(row.torque_nm) + 0.005 * row.torque_nm


def test_largest_deviation_is_a_third_of_a_percent():
    dev = np.array([_preload_kn(r) / r.preload_kn - 1.0 for r in TABLE.itertuples()])
    assert 0.002 < np.abs(dev).max() < 0.0035
    # without the plastic torsion factor (3/2 -> 2, the elastic section) the table is missed by 5-9 %
    d2, d3, _ = vdi2230.iso724_diameters_mm(8.0, 1.0)
    d0 = (d2 + d3) / 2
    elastic = np.pi / 4 * d0**2 * 0.9 * 640 / np.sqrt(1 + 3 * (2 * d2 / d0 * (1 / (np.pi * d2) + 1.155 * 0.14)) ** 2)
    assert 0.05 < 1 - elastic / 19.7e3 < 0.09


def test_coarse_thread_example():
    row = pd.read_csv(DATA / "vdi2230_coarse_example.csv", comment="#").iloc[0]
    d2, d3, _ = vdi2230.iso724_diameters_mm(row.d_mm, row.pitch_mm)
    f = float(vdi2230.permissible_assembly_preload_n(row.pitch_mm, d2, d3, _rp(row.property_class, row.d_mm), row.mu))
    assert f / 1e3 == pytest.approx(row.preload_kn, rel=0.0035)  # 41.98 vs 41.9 kN printed
