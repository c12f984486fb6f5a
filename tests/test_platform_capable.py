"""``synth rationalise --capability`` (:mod:`synth.platform.capable`): the lazy loop and its batch exclusion, on the
real feasibility data of two sample applications cut to one core and three options per subsystem (a few seconds)."""

import argparse
import dataclasses

import numpy as np
import pandas as pd
import pytest

from synth.design.evaluate import Settings
from synth.design.constraints import REGISTRY
from synth.platform import capable
from synth.platform.rationalise import rationalise
from synth.platform.verified import design_parts
from synth.robust.settings import RobustSettings
from synth.robust.synthesis import nominal_capability


def _one_core(a, k=3):
    """Application ``a`` with its first core that has an option of every subsystem, and that core's first ``k``
    options of each."""
    c = next(c for c in range(a.n_cores) if all(len(a.feasible[s][int(a.group[s][c])]) for s in a.group))

    def first(x, s):
        return [np.asarray(x[s][int(a.group[s][c])])[:k]]
    one = slice(c, c + 1)
    return dataclasses.replace(
        a, core_parts={f: np.asarray(v)[one] for f, v in a.core_parts.items()},
        core_cost_eur=np.asarray(a.core_cost_eur)[one], core_margin=np.asarray(a.core_margin)[one],
        group={s: np.zeros(1, dtype=np.int64) for s in a.group}, feasible={s: first(a.feasible, s) for s in a.group},
        option_margin={s: first(a.option_margin, s) for s in a.group},
        option_binding=None if a.option_binding is None else {s: first(a.option_binding, s) for s in a.group},
        core_binding=None if a.core_binding is None else np.asarray(a.core_binding)[one],
        core_rows=np.asarray(a.core_rows)[one])


@pytest.fixture(scope="module")
def portfolio(tmp_path_factory):
    from synth.bulk.portfolio import write_table
    from synth.bulk.sample import sample_portfolio
    return str(write_table(sample_portfolio(3, seed=3), tmp_path_factory.mktemp("cap") / "three.csv"))


#: a bolt that meets Ppk >= 0.01 with the first application's core (its made joint's preload window and head
#: pressure); the first three bolt options of either application do not
CAPABLE_BOLT = "M8x1.25 hex 10.9 washer ISO 7089"


@pytest.fixture(scope="module")
def tiny(portfolio):
    """Application 1 with its first three bolt options and the capable bolt, application 2 as cut."""
    from synth.platform.portfolio_feasibility import load_feasibility
    pf = load_feasibility(portfolio, Settings())
    first, second = (_one_core(a) for a in pf.apps[:2])
    full = _one_core(pf.apps[0], k=1000)
    good = [int(k) for k in full.feasible["bolt"][0] if pf.option_parts("bolt", k)["bolt"] == CAPABLE_BOLT]
    keep = np.isin(full.feasible["bolt"][0], np.r_[first.feasible["bolt"][0], good])
    first = dataclasses.replace(first, feasible={**first.feasible, "bolt": [full.feasible["bolt"][0][keep]]},
                                option_margin={**first.option_margin, "bolt": [full.option_margin["bolt"][0][keep]]},
                                option_binding=None if full.option_binding is None else
                                {**first.option_binding, "bolt": [full.option_binding["bolt"][0][keep]]})
    return dataclasses.replace(pf, apps=[first, second], design_inputs=pf.design_inputs[:2])


def test_capable_designs_are_served_and_the_batch_agrees_with_each_design(tiny):
    rs = RobustSettings(capability=0.01, samples=64)
    settings = Settings(capability=rs)
    r, _, st = capable.capable_rounds(tiny, lambda d: rationalise(d, "variants", time_limit=30), settings)
    # the first round's bolt fails; every bolt option of that core is judged at once, so round 2 finds the capable one
    assert st["rounds"] == 2 and st["options_evaluated"] >= 4
    served, refused = r.records
    assert served["feasible"] and served["capability"]["meets"] and served["design"]["bolt_washer"] != "none"
    full = nominal_capability(tiny.design_inputs[0], served["design"], settings.judge, rs)
    assert full["meets"] and served["capability"]["min_ppk"] == full["min_ppk"] > 0.01
    assert not refused["feasible"] and not refused["capability"]["meets"] and refused["capability"]["failing"]
    assert refused["reason"].startswith("no design meets Ppk >= 0.01") and "the best assigned reached Ppk" in \
        refused["reason"]
    # the batch's verdict on each bolt option is that of the design's own capability (nominal_capability)
    a = tiny.apps[0]
    opts = {s: int(a.feasible[s][0][0]) for s in a.feasible}
    bad = capable.failing_options(tiny, 0, 0, opts, "bolt", settings.judge, rs)
    assert 0 < len(bad) < len(a.feasible["bolt"][0])
    for k in (int(k) for k in a.feasible["bolt"][0]):
        design = design_parts(tiny, [(0, 0, {**opts, "bolt": k})])[0]
        full = nominal_capability(tiny.design_inputs[0], design, settings.judge, rs)
        assert any(REGISTRY[c].group == "bolt" for c in full["failing"]) == (k in bad)


def test_without_a_target_the_loop_is_not_entered(portfolio, tmp_path, monkeypatch):
    from synth.scenes import rationalise as scene

    def refuse(*a, **k):
        raise AssertionError("capable_rounds entered without a target")
    monkeypatch.setattr(capable, "capable_rounds", refuse)
    p = argparse.ArgumentParser()
    scene.register(p.add_subparsers())
    args = p.parse_args(["rationalise", portfolio, "--out", str(tmp_path), "--tradeoff", "none"])
    assert args.func(args) == 0
    assign = pd.read_csv(tmp_path / "assignment.csv")
    assert len(assign) == 3 and not any(c.startswith("capability_") for c in assign.columns)
