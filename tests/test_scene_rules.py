"""The design rules' options are one pair for every scene that judges (``--rules``, ``--spring-limit``:
:func:`synth.scenes._options.add_rules_options`): ``synth bulk --spring-limit en13906`` judges every row as a rules
file with ``spring_limit_basis: en13906`` does, and differs from the thesis basis (issue 33: the basis once reached
the manifest but not the rows)."""

from __future__ import annotations

import pandas as pd
import pytest

from synth.cli import main


@pytest.fixture(scope="module")
def fleet(tmp_path_factory):
    from synth.bulk.portfolio import write_table
    from synth.bulk.sample import sample_portfolio
    return str(write_table(sample_portfolio(10, seed=5), tmp_path_factory.mktemp("fleet") / "fleet.csv"))


def _bulk(fleet, out, *argv) -> pd.DataFrame:
    assert main(["bulk", fleet, "--out", str(out), "--no-diagnose", *argv]) == 0
    return pd.read_csv(out)


def test_bulk_spring_limit_is_the_rules_basis(fleet, tmp_path, capsys):
    rules = tmp_path / "en.yaml"
    rules.write_text("spring_limit_basis: en13906\n", encoding="utf-8")
    by_option = _bulk(fleet, tmp_path / "a.csv", "--spring-limit", "en13906")
    by_file = _bulk(fleet, tmp_path / "b.csv", "--rules", str(rules))
    thesis = _bulk(fleet, tmp_path / "c.csv")
    assert "spring limit basis: en13906" in capsys.readouterr().out
    pd.testing.assert_frame_equal(by_option, by_file)
    col = "margin_spring_yield"
    assert not by_option[col].equals(thesis[col])  # the basis moves the installation stress check's margin
