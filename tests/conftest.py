"""Shared fixtures: the thesis case files from ../shared/cases."""

from pathlib import Path

import pytest
import yaml

CASES = Path(__file__).resolve().parents[2] / "shared" / "cases"


def load_case(name: str) -> dict:
    """The whole case file ``name`` (``inputs``, ``thesis_tool``, ``real_tensioner``)."""
    path = CASES / f"{name}.yaml"
    if not path.is_file():
        pytest.skip(f"case file {path} not available")
    return yaml.safe_load(path.read_text())


@pytest.fixture(params=["case1_as_run", "case3"])
def case(request):
    return load_case(request.param)
