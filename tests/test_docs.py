"""docs/model.md is assembled from docs/sections and the constants CSVs: it must be current."""

import importlib.util
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def test_model_md_is_current():
    spec = importlib.util.spec_from_file_location("build_model_md", ROOT / "docs" / "build_model_md.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    assert (ROOT / "docs" / "model.md").read_text(encoding="utf-8") == mod.build(), \
        "docs/model.md is stale: run python docs/build_model_md.py"


def test_every_catalog_row_has_a_source():
    import pandas as pd
    for path in sorted((ROOT / "catalogs").glob("*.csv")):
        df = pd.read_csv(path, comment="#")
        assert "source" in df.columns, path.name
        assert df["source"].notna().all() and (df["source"].astype(str).str.strip() != "").all(), path.name
