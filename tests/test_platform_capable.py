"""``synth rationalise --capability`` (:mod:`synth.platform.capable`): the lazy loop, its robust-search proof and its
batch exclusion, on the real feasibility data of the default input with a 12 mm bolt seat (served) and the default
input (no capable design), as ``synth design --capability`` judges them."""

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


@pytest.fixture(scope="module")
def portfolio(tmp_path_factory):
    from synth.bulk.portfolio import write_table
    from synth.bulk.sample import sample_portfolio
    return str(write_table(sample_portfolio(3, seed=3), tmp_path_factory.mktemp("cap") / "three.csv"))


#: the target and estimator of the served case: at 2,048 samples the robust search finds a design for the default
#: input with a 12 mm bolt seat (synth design --capability 0.5 finds one too), none for the default input itself
RS = RobustSettings(capability=0.5, samples=2048)


@pytest.fixture(scope="module")
def two(tmp_path_factory):
    """The default input with a 12 mm bolt head seat (a capable design exists) and the default input (none: the made
    joint's preload window fails nominally on every bolt), rationalised at :data:`RS`."""
    from synth.bulk.portfolio import write_table
    from synth.platform.portfolio_feasibility import load_feasibility
    from synth.scenes.demo import default_input
    d = default_input()
    rows = [{"application_id": name, **{k: v for k, v in x.as_dict().items() if v is not None}}
            for name, x in (("seat12", dataclasses.replace(d, bolt_head_contact_external_diameter_mm=12.0)),
                            ("default", d))]
    path = write_table(pd.DataFrame(rows), tmp_path_factory.mktemp("cap2") / "two.csv")
    pf = load_feasibility(str(path), Settings())
    settings = Settings(capability=RS)
    r, _, st = capable.capable_rounds(pf, lambda x: rationalise(x, "variants", time_limit=60), settings)
    return pf, settings, r, st


def test_a_served_design_meets_the_target_as_synth_design_judges_it(two):
    from synth.design.verify import verify
    from synth.robust.sampling import production
    from synth.robust.synthesis import robust_solve
    pf, settings, r, st = two
    served, refused = r.records
    assert served["feasible"] and served["capability"]["meets"] and served["capability"]["failing"] == []
    full = nominal_capability(pf.design_inputs[0], served["design"], settings.judge, RS)
    assert full["meets"] and served["capability"]["min_ppk"] == full["min_ppk"] >= 0.5
    # and it passes every check nominally with the joint made (what synth design --capability requires of a
    # candidate); the designs the platform's data hold pass them under the thesis's tightening only
    assert verify(pf.design_inputs[0], served["design"], settings=production(settings.judge)).failed() == []
    # the default input: no catalog design meets the target (the robust search's proof, synth design's answer)
    assert not refused["feasible"] and "the robust search finds none in the catalogs" in refused["reason"]
    assert robust_solve(pf.design_inputs[1], "standard,cost", rs=RS, explain=False).robust["meets"] is False
    assert st["searched"] == 2 and st["rounds"] >= 2


def test_the_batch_judges_each_option_as_the_design_alone(two):
    # the bolt options of the served design's core, judged at once (failing_options), each as its own design
    from synth.robust.capability import capability
    from synth.robust.sampling import base_of, production
    pf, settings, r, _ = two
    rec = r.records[0]
    core, opts = rec["core"], rec["options"]
    a = pf.apps[0]
    options = [int(k) for k in a.feasible["bolt"][int(a.group["bolt"][core])]][:5] + [int(opts["bolt"])]
    small = dataclasses.replace(pf, apps=[dataclasses.replace(
        a, feasible={**a.feasible, "bolt": [*a.feasible["bolt"][:int(a.group["bolt"][core])], np.array(options)]},
        option_margin={**a.option_margin, "bolt": [*a.option_margin["bolt"][:int(a.group["bolt"][core])],
                                                   np.zeros(len(options))]})])
    bad = capable.failing_options(small, 0, core, opts, "bolt", settings.judge, RS)
    assert int(opts["bolt"]) not in bad and bad
    for k in options:
        design = design_parts(pf, [(0, core, {**opts, "bolt": k})])[0]
        base = base_of(pf.design_inputs[0], design, production(settings.judge))
        failing = capable.failing_made(capability(base, RS).failing(), base)
        assert any(REGISTRY[c].group == "bolt" for c in failing) == (k in bad), (k, failing)


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
