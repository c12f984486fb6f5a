"""``synth rationalise``: the files it writes and the errors it names."""

import argparse

import pandas as pd
import pytest

from synth.errors import InputError
from synth.platform.data import FAMILIES
from synth.scenes import rationalise as scene


def _run(argv):
    p = argparse.ArgumentParser()
    scene.register(p.add_subparsers())
    args = p.parse_args(argv)
    return args.func(args)


def test_rationalise_writes_platform_assignment_summary_and_tradeoff(tmp_path, capsys):
    out = tmp_path / "plat"
    assert _run(["rationalise", "synthetic:30:2", "--out", str(out), "--points", "3", "--time-limit", "30"]) == 0
    plat = pd.read_csv(out / "platform.csv")
    assign = pd.read_csv(out / "assignment.csv", keep_default_na=False)
    assert list(plat.columns) == ["family", "part", "applications"]
    assert set(plat["family"]) <= set(FAMILIES)
    assert len(assign) == 30 and list(assign.columns[:2]) == ["application_id", "feasible"]
    ok = assign[assign["feasible"].astype(str) == "True"]
    # every assigned part is a platform part, and the counts of platform.csv are the assignment's
    for f in FAMILIES:
        used = ok[f][ok[f] != "none"].astype(str)
        assert set(used) <= set(plat.loc[plat["family"] == f, "part"].astype(str))
        counts = used.value_counts()
        for _, row in plat[plat["family"] == f].iterrows():
            assert counts.get(str(row["part"]), 0) == row["applications"]
    assert (assign.loc[assign["feasible"].astype(str) == "False", "reason"] != "").all()
    trade = pd.read_csv(out / "tradeoff.csv")
    assert len(trade) == 3 and (out / "tradeoff.png").stat().st_size > 1000
    assert trade["parts"].is_monotonic_increasing or trade["served"].iloc[-1] < trade["served"].iloc[0]
    assert "Price of standardisation" in (out / "summary.md").read_text()
    assert "distinct parts" in capsys.readouterr().out


@pytest.mark.parametrize("argv, match", [
    (["--max-variants", "bearing=2"], r"--max-variants: got 'bearing=2'"),
    (["--max-variants", "ball_bearing=0"], r"N a whole number >= 1"),
])
def test_bad_arguments_are_named(tmp_path, argv, match):
    with pytest.raises(InputError, match=match):
        _run(["rationalise", "synthetic:3", "--out", str(tmp_path)] + argv)


def test_a_missing_table_or_unknown_portfolio_is_named(tmp_path):
    with pytest.raises(InputError, match="portfolio: got .*portfolio.csv'; accepted: an existing portfolio table"):
        _run(["rationalise", str(tmp_path / "portfolio.csv"), "--out", str(tmp_path)])
    with pytest.raises(InputError, match="PORTFOLIO: got 'engines.txt'; accepted: synthetic:N"):
        _run(["rationalise", "engines.txt", "--out", str(tmp_path)])


def test_a_progress_line_per_stage(tmp_path, capsys, monkeypatch):
    """On a terminal every stage of the platform has its own line (issue 36: the label sat at "N of N" while the
    MILP ran), then the trade-off curve and the outputs; each line ends "done"."""
    from synth.platform.rationalise import STAGES
    monkeypatch.setenv("SYNTH_PROGRESS", "1")
    assert _run(["rationalise", "synthetic:20:1", "--out", str(tmp_path / "p"), "--points", "2"]) == 0
    lines = [x.strip() for x in capsys.readouterr().err.replace("\r", "\n").splitlines() if x.strip()]
    done = [x for x in lines if x.endswith("done")]
    want = [s if s != "MILP" else "highs MILP" for s in STAGES]
    got = [x.split(":")[1].split(" (")[0].removeprefix(" platform, ") for x in done
           if x.startswith("synth rationalise: platform, ")]
    assert got == want
    assert any(x.startswith("synth rationalise: trade-off curve (margin):") and "2/2" in x for x in lines)
    assert done[-1].startswith("synth rationalise: writing the outputs:")


@pytest.fixture(scope="module")
def fleet(tmp_path_factory):
    from synth.bulk.portfolio import write_table
    from synth.bulk.sample import sample_portfolio
    return str(write_table(sample_portfolio(8, seed=3), tmp_path_factory.mktemp("fleet") / "fleet.csv"))


def _served(out) -> int:
    return int((pd.read_csv(out / "assignment.csv")["feasible"].astype(str) == "True").sum())


def test_rules_judge_every_option_and_are_echoed(fleet, tmp_path, capsys):
    """``--rules`` reaches the feasibility of every option (a margin no design keeps serves no application where
    the same portfolio without it is served) and the outputs say what judged them; ``--spring-limit`` sets the
    rules' basis."""
    base = tmp_path / "base"
    assert _run(["rationalise", fleet, "--out", str(base), "--tradeoff", "none"]) == 0
    assert _served(base) > 0
    rules = tmp_path / "rules.yaml"
    rules.write_text("name: unreachable\nmin_margins:\n  spring_yield: 0.99\n", encoding="utf-8")
    strict = tmp_path / "strict"
    capsys.readouterr()
    _run(["rationalise", fleet, "--out", str(strict), "--tradeoff", "none", "--rules", str(rules),
          "--spring-limit", "en13906"])
    assert _served(strict) == 0
    said = capsys.readouterr().out
    assert "design rules: unreachable" in said and "  minimum margin spring_yield: 99 %" in said
    summary = (strict / "summary.md").read_text(encoding="utf-8")
    assert "## Design rules" in summary and "- spring limit basis: en13906" in summary


def test_rules_the_platform_cannot_honour_are_refused(tmp_path):
    """A capability target (rules or --capability) on synthetic data, which have no designs to evaluate."""
    rules = tmp_path / "capable.yaml"
    rules.write_text("capability:\n  ppk_min: 1.33\n", encoding="utf-8")
    with pytest.raises(InputError, match="design rules \\(capable.yaml\\): got 'synthetic:5'; accepted: a portfolio"):
        _run(["rationalise", "synthetic:5", "--out", str(tmp_path / "a"), "--rules", str(rules)])
    with pytest.raises(InputError, match="--capability: got 'Ppk >= 1.33 .*accepted: a portfolio table"):
        _run(["rationalise", "synthetic:5", "--out", str(tmp_path / "c"), "--capability", "1.33"])
    with pytest.raises(InputError, match="design rules: got 'synthetic:5'; accepted: a portfolio table"):
        _run(["rationalise", "synthetic:5", "--out", str(tmp_path / "b"), "--spring-limit", "en13906"])

