"""The shipped catalogs: one declaration per constant, every row sourced."""
from __future__ import annotations

import collections
from pathlib import Path

import pandas as pd
import pytest

CATALOGS = Path(__file__).resolve().parents[1] / "catalogs"


def test_every_constant_is_declared_once():
    """The loader keeps the first of two declarations: a second one would be silently ignored."""
    names = collections.Counter()
    for path in sorted(CATALOGS.glob("constants*.csv")):
        names.update(pd.read_csv(path)["name"])
    assert [n for n, k in names.items() if k > 1] == []


@pytest.mark.parametrize("path", sorted(CATALOGS.glob("*.csv")), ids=lambda p: p.name)
def test_every_catalog_row_names_its_source(path):
    df = pd.read_csv(path, dtype=str, keep_default_na=False)
    assert "source" in df.columns, f"{path.name} has no source column"
    blank = df.index[df["source"].str.strip() == ""].tolist()
    assert blank == [], f"{path.name}: rows {blank} have no source"
