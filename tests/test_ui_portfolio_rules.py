"""The web application's portfolio judges by design rules as ``synth bulk --rules`` and ``synth rationalise --rules``
do (issue 33: the rules were dropped between the layers; the portfolio page had none): every row, the platform and
the application a row opens on the design page.

The rule asks the main spring's installation stress check for a 5 % margin. On the three sampled applications
(seed 3) the designs without it keep 4.8 %, 3.0 % and 9.2 %: under it the second has no design, the first another
spring, and the third keeps its design with 5 points less margin (a rule's minimum margin is taken off the check's
margin, :func:`synth.design.evaluate.finish`).
"""

from __future__ import annotations

import pytest

from synth.errors import InputError
from synth.ui.portfolio import PortfolioSession

FIVE = "name: five percent\nmin_margins:\n  spring_yield: 0.05\n"


@pytest.fixture(scope="module")
def screened(tmp_path_factory):
    folder = tmp_path_factory.mktemp("portfolio")
    p = PortfolioSession(folder / "work")
    p.sample(3, seed=3)
    plain = p.run(slices=1, min_slice=1)
    rules = folder / "five.yaml"
    rules.write_text(FIVE, encoding="utf-8")
    said = p.set_rules(rules)
    assert p.results is None  # the screening made under no rules is dropped with them
    return p, plain, p.run(slices=1, min_slice=1), said


def test_the_rules_judge_every_row(screened):
    p, plain, strict, said = screened
    assert said.splitlines()[:2] == ["design rules: five percent (five.yaml)", "  minimum margin spring_yield: 5 %"]
    assert plain["feasible"].astype(bool).tolist() == [True, True, True]
    assert strict["feasible"].astype(bool).tolist() == [True, False, True]
    same = ["part_main_spring_wire", "part_main_spring_mean_body_diameter_mm"]
    assert strict.loc[2, same].tolist() == plain.loc[2, same].tolist()
    assert strict.loc[2, "margin_spring_yield"] == pytest.approx(plain.loc[2, "margin_spring_yield"] - 0.05, abs=1e-12)


def test_the_platform_is_judged_by_the_rules(screened):
    p = screened[0]
    p.rationalise(fidelity="screening")
    assert p.platform.price["applications_served"] == 2


def test_a_row_opens_on_the_design_page_under_the_portfolios_rules(screened):
    from synth.ui.session import DesignSession
    p, _, strict, _ = screened
    opened = DesignSession(p.application(2), source="row 3", rules=p.rules)  # what the design page builds (app.py)
    opened.fidelity = p.fidelity
    assert opened.synthesise().margins["spring_yield"] == pytest.approx(strict.loc[2, "margin_spring_yield"],
                                                                         abs=1e-12)


def test_capability_targets_in_the_rules_are_honoured_by_the_platform_not_dropped(tmp_path):
    import pandas as pd
    from synth.design.evaluate import Settings
    from synth.platform.portfolio_feasibility import load_feasibility
    p = PortfolioSession(tmp_path / "work")
    p.sample(2, seed=3)
    rules = tmp_path / "capable.yaml"
    rules.write_text("capability:\n  ppk_min: 1.33\n", encoding="utf-8")
    p.set_rules(rules)
    p.rationalise(fidelity="screening")
    # the page's platform took the rules' target as synth rationalise does (synth.platform.capable.choose): no
    # catalog design of either application meets Ppk 1.33 with the joint made, so none is served, and each says so
    assert p.platform.capability_line.startswith("capability: Ppk >= 1.33")
    assert not any(r["feasible"] for r in p.platform.records)
    assert all("no design meets Ppk >= 1.33" in r["reason"] for r in p.platform.records)
    assign = pd.read_csv(p.files()["platform/assignment.csv"])
    assert (assign["capability_verdict"] != "PASS").all()
    # a caller whose settings leave the rules' targets behind is refused, never served without them
    with pytest.raises(InputError, match=r"design rules \(capable.yaml\): capability"):
        load_feasibility(str(p.path), Settings(fidelity="screening", rules=p.rules))
    p.set_rules(None)
    assert p.rules.empty()
