"""A new objective and a new tolerance quantity are one declaration each (plus a catalog row): every scene takes them.

The fixture declares a toy additive objective ``support`` (minus the pivot bushing's length: it prefers the longest
bushing, which no built-in objective does) and a tolerance quantity ``bushing_length`` (the made bushing's length
about the chosen one, with its row in a user tolerance catalog), and withdraws both afterwards. The tests run
``synth design`` and ``synth robust`` through the command line, ``synth bulk`` through :func:`synth.screen` (its
in-memory twin) and ``synth rationalise`` through the command line, and check that each declaration enters the answer.
"""

from __future__ import annotations

import csv
import json

import numpy as np
import pytest

from synth import catalog
from synth.cli import main
from synth.data import CASES_DIR
from synth.optimise import objectives
from synth.robust import tolerances

SAMPLES = "64"


def _zero(sp, cores, core_values):
    return np.zeros(len(np.atleast_1d(cores)))


def _support(sp, table, options, stiffness_nm_per_deg):
    """Minus the bushing's length [mm] (a longer bushing supports the arm better); 0 for every other part."""
    t = sp.tables[table]
    idx = slice(None) if options is None else options
    if table == "bushing":
        return -np.asarray(t["pivot_bushing_length_mm"], float)[idx]
    return np.zeros(sp.n(table))[idx]


@pytest.fixture(scope="module")
def declared(tmp_path_factory):
    goal = objectives.declare(objectives.Goal(
        name="support", words="bushing support", unit="-mm", sense=+1, additive=True, tiebreak=("support", "cost"),
        scores="minus the pivot bushing's length", core=_zero, option=_support))
    quantity = tolerances.declare(tolerances.Quantity(
        "bushing_length", "pivot bushing length (bushing option pivot_bushing_length_mm)", "mm", "bushing",
        "pivot_bushing_length_mm"))
    folder = tmp_path_factory.mktemp("catalogs")
    with open(folder / "tolerances.csv", "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["quantity", "kind", "band", "unit", "band_from", "source", "note"])
        w.writerow(["bushing_length", "normal", "0.5", "mm", "", "a test's toy band", "normal, +/-3 sigma"])
    try:
        yield goal, quantity, folder
    finally:
        objectives.withdraw("support")
        tolerances.withdraw("bushing_length")
        catalog.set_user_dirs()


def _json(capsys, argv):
    capsys.readouterr()
    rc = main(argv)
    return rc, json.loads(capsys.readouterr().out)


@pytest.fixture(scope="module")
def designs(declared, tmp_path_factory):
    """``synth design --json`` of the default application under ``standard`` and under the declared ``support``
    (the first also saved, for ``synth robust``)."""
    import contextlib
    import io
    case = str(CASES_DIR.parent / "default_case.yaml")
    out = {}
    for objective in ("standard", "support"):
        buf = io.StringIO()
        with contextlib.redirect_stdout(buf):
            rc = main(["design", case, "--objective", objective, "--json"])
        out[objective] = (rc, json.loads(buf.getvalue()))
    saved = tmp_path_factory.mktemp("design") / "design.json"
    saved.write_text(json.dumps(out["standard"][1]))
    return out, saved


def test_a_declared_objective_is_scored_and_chooses_in_design(designs):
    (rc0, std), (rc1, sup) = designs[0]["standard"], designs[0]["support"]
    assert rc0 == rc1 == 0
    # the new objective is scored and shown, and it chooses: the longest bushing instead of the most standard design's
    assert sup["objectives"]["support"] == -sup["parts"]["pivot_bushing_length_mm"]
    assert std["objectives"]["support"] == -std["parts"]["pivot_bushing_length_mm"]
    assert sup["parts"]["pivot_bushing_length_mm"] > std["parts"]["pivot_bushing_length_mm"]


def test_a_declared_objective_is_a_bulk_column_and_chooses(declared):
    import synth
    from synth.data.generated_applications import generate
    apps = generate(3, seed=0)
    a = synth.screen(apps, objective="standard", progress=False, diagnose=False)
    b = synth.screen(apps, objective="support", progress=False, diagnose=False)
    ok = b["feasible"].to_numpy(bool)
    assert ok.any() and (ok == a["feasible"].to_numpy(bool)).all()
    length = {k: x["part_pivot_bushing_length_mm"][ok].astype(float).to_numpy() for k, x in (("a", a), ("b", b))}
    assert np.array_equal(b["objective_support"][ok].to_numpy(), -length["b"])
    assert np.array_equal(a["objective_support"][ok].to_numpy(), -length["a"])
    assert (length["b"] >= length["a"]).all() and (length["b"] > length["a"]).any()


def test_a_declared_tolerance_enters_robust(declared, designs, capsys):
    base = ["robust", str(designs[1]), "--samples", SAMPLES, "--seed", "1", "--no-assumptions", "--json"]
    _, plain = _json(capsys, base)
    _, made = _json(capsys, ["--catalogs", str(declared[2])] + base)
    rows = {r["quantity"]: r for r in made["robust"]["tolerances"]}
    assert "bushing_length" not in {r["quantity"] for r in plain["robust"]["tolerances"]}
    assert (rows["bushing_length"]["lo"], rows["bushing_length"]["hi"]) == (-0.5, 0.5)
    # the made bushing's length drives the scatter of bushing checks, and its worst case moves only checks reading it
    p = {c["id"]: c for c in plain["robust"]["checks"]}
    m = {c["id"]: c for c in made["robust"]["checks"]}
    moved = {cid for cid in p if p[cid]["worst_case_margin"] != m[cid]["worst_case_margin"]}
    assert moved and all(m[cid]["group"] == "bushing" for cid in moved), moved
    assert "bushing_length" in {q for q, _ in m["bushing_pv"]["contributors"]}
    assert m["bushing_pv"]["sd_margin"] > p["bushing_pv"]["sd_margin"]


def test_rationalise_runs_with_the_declarations(declared, tmp_path, capsys):
    """``synth rationalise`` optimises platform objectives (variants, cost; no tolerance model): a declared design
    objective or tolerance is none of them; with both in place (the tolerance row in the user catalogs the run
    reads) it serves the portfolio, each application's design verified whole."""
    pf = tmp_path / "p.csv"
    assert main(["portfolio-sample", "3", "--out", str(pf)]) == 0
    assert main(["--catalogs", str(declared[2]), "rationalise", str(pf), "--out", str(tmp_path / "a"),
                 "--tradeoff", "none"]) == 0
    out = capsys.readouterr().out
    assert "synth rationalise:" in out and "of 3 applications served" in out
    with open(tmp_path / "a" / "assignment.csv", newline="") as f:
        assert len(list(csv.DictReader(f))) == 3


def test_a_declared_objective_is_offered_in_the_web_page(declared):
    from synth.ui.session import offered_objectives
    assert offered_objectives()[-1] == "support"
