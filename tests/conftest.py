"""Shared fixtures: the thesis case files shipped in synth/data/cases, their inputs and flowchart results."""

from functools import lru_cache

import pytest
import yaml

from synth.data import CASES_DIR as CASES


def load_case(name: str) -> dict:
    """The whole case file ``name`` (``inputs``, ``thesis_tool``, ``real_tensioner``)."""
    path = CASES / f"{name}.yaml"
    return yaml.safe_load(path.read_text())


def case_input(name: str, **changes):
    """The validated :class:`synth.schema.DesignInput` of case ``name``, with ``changes`` to its inputs."""
    from synth.schema import load_input, validate
    if not changes:
        return load_input(CASES / f"{name}.yaml")
    return validate({**load_case(name)["inputs"], **changes})


@lru_cache(maxsize=None)
def case_flowchart(name: str):
    """The flowchart :class:`synth.design.result.Result` of case ``name`` (default settings; do not mutate)."""
    from synth import flowchart
    return flowchart.run(case_input(name))


@pytest.fixture(params=["case1_as_run", "case3"])
def case(request):
    return load_case(request.param)
