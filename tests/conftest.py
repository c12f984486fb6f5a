"""Shared fixtures: the thesis case files shipped in synth/data/cases."""

from pathlib import Path

import pytest
import yaml

from synth.data import CASES_DIR as CASES


def load_case(name: str) -> dict:
    """The whole case file ``name`` (``inputs``, ``thesis_tool``, ``real_tensioner``)."""
    path = CASES / f"{name}.yaml"
    return yaml.safe_load(path.read_text())


@pytest.fixture(params=["case1_as_run", "case3"])
def case(request):
    return load_case(request.param)

# the corpus generator is a script, not a test module (it rewrites tests/bad_inputs/files when run)
collect_ignore = ["bad_inputs/make_corpus.py"]
