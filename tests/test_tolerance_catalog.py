"""A user's tolerance catalog goes through the input gate (issue 39: a band of 1e308 gave NaN samples and a check
reported at P(violation) 1 with margin +1.0; a unit "furlong" and a row with both ``band`` and ``band_from`` were
accepted). Each is refused naming the file, the row, the column, the value and what is accepted, before any
sample is drawn, on the command line too (exit 2, no traceback)."""

from __future__ import annotations

import csv
import io

import pytest

from synth import catalog
from synth.errors import InputError
from synth.robust.tolerances import QUANTITY_UNITS, UNITS, tolerances


def _folder(tmp_path, **rows):
    """A user folder with ``tolerances.csv`` holding the built-in rows ``rows`` names, changed as given."""
    with open(catalog.builtin_dir() / "tolerances.csv", newline="") as fh:
        built = {r["quantity"]: r for r in csv.DictReader(fh)}
    out = io.StringIO()
    w = csv.DictWriter(out, fieldnames=list(next(iter(built.values()))), lineterminator="\n")
    w.writeheader()
    for q, change in rows.items():
        w.writerow({**built[q], **change})
    (tmp_path / "tolerances.csv").write_text(out.getvalue())
    return tmp_path


@pytest.fixture
def user(tmp_path):
    yield lambda **rows: catalog.set_user_dirs(_folder(tmp_path, **rows))
    catalog.set_user_dirs()


@pytest.mark.parametrize("rows, match", [
    ({"pulley_diameter": {"band": "1e308"}},
     r"catalog tolerances.csv, row pulley_diameter, column band: got 1e\+308.*a half-width from 0 to below 10 mm"),
    ({"pivot_bushing_friction": {"band": "150"}},
     r"row pivot_bushing_friction, column band: got 150.0; accepted: a half-width from 0 to below 100 % \(a larger "
     r"one makes the quantity zero or negative\)"),
    ({"pulley_diameter": {"unit": "furlong"}},
     r"row pulley_diameter, column unit: got 'furlong'; accepted: mm \(the unit of pulley_diameter's band\)"),
    ({"spring_torque": {"band": "5"}},
     r"row spring_torque, columns band and band_from: got '5.0 and input.spring_torque_tolerance_pct'; accepted: "
     r"either a band or a band_from, not both"),
    ({"pulley_diameter": {"band": "-0.1"}}, r"catalog tolerances.csv, row 1, line 2, column band: got '-0.1'"),
])
def test_a_bad_tolerance_row_is_refused_naming_file_row_column_value_and_what_is_accepted(user, rows, match):
    with pytest.raises(InputError, match=match):  # the folder's own check (a negative band), or the model's
        user(**rows)
        tolerances()


def test_every_quantity_has_a_unit_the_catalog_uses():
    assert set(QUANTITY_UNITS.values()) <= set(UNITS)
    for t in tolerances().values():
        assert t.unit == QUANTITY_UNITS[t.quantity]


def test_the_command_line_refuses_it_with_exit_2(tmp_path, capsys):
    from importlib import resources

    from synth import cli
    folder = _folder(tmp_path, pulley_diameter={"band": "1e308"})
    case = resources.files("synth").joinpath("data/default_case.yaml")
    try:
        rc = cli.main(["--catalogs", str(folder), "robust", str(case), "--samples", "256", "--no-assumptions"])
    finally:
        catalog.set_user_dirs()
    err = capsys.readouterr().err
    assert rc == 2 and "tolerances.csv, row pulley_diameter, column band" in err and "Traceback" not in err
