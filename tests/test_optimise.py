"""Design space, vectorised evaluation, enumerate against brute force, diagnosis, objectives and the scenes."""

from __future__ import annotations

import dataclasses
import itertools
import json

import numpy as np
import pytest
import yaml
from synth.data import case_path
from hypothesis import given, settings, strategies as st

from synth.cli import main
from synth.data.generated_applications import generate
from synth.errors import InputError
from synth.optimise import solve
from synth.optimise.diagnose import diagnose, is_feasible
from synth.optimise.evaluate import evaluate
from synth.optimise.objectives import Objective
from synth.optimise.result import verify
from synth.optimise.solvers.enumerate import solve_space, tables
from synth.optimise.space import SUBSYSTEMS, build_space
from synth.model import plain_bushing as s4
from synth.schema import load_input

CASE1 = str(case_path("case1"))
CASE3 = str(case_path("case3"))
APP = generate(2, seed=0)[1]  # a feasible generated application (dry, radial damping)


def test_space_of_case1_excludes_6007_and_counts_the_product():
    sp = build_space(load_input(CASE1))
    # Table 2 lists the 6007 only for a 4.5 mm working arm: case 1's 5 mm arm rules it out
    assert set(sp.cores["bearing"]) == {"6006"}
    assert any("6007" in n for n in sp.notes)
    n = sp.n_cores
    for t in sp.subsystems.values():
        n *= len(t)
    assert sp.size() == n > 10**8


def test_verify_reproduces_hand_calculations_case3():
    d = load_input(CASE3)
    parts = {"bearing": "6006", "pivot_class_mm": 19.0, "supplier": "B", "damper_pad": "none",
             "bushing_length_mm": 20.0, "endcap_spacer": "none", "cone_aspect_ratio": 0.0,
             "spring_material": "VDSiCr", "spring_wire": "R2.30", "spring_mbd_mm": 44.0,
             "bolt_format": "M8x1.25", "bolt_property_class": "8.8"}
    v = verify(d, parts)
    # arm wall = d_bearing/2 - e_w - class/2 = 15 - 4 - 9.5 = 1.5 mm against 1 mm -> margin 0.5
    assert v.margins["arm_wall"] == pytest.approx(0.5)
    # pivot = class + 2 (1 - 0.5) = 20 mm (thinner bushing, step 2)
    assert v.values["pivot_diameter_mm"] == pytest.approx(20.0)
    # the bushing margins are those of step 4's own function (one source of truth)
    r = s4.evaluate_bushing(462.5, 20.0, 20.0, 16, 50, 1200, supplier="B", environment="dry",
                            belt_plane_height_mm=20.0, max_pivot_height_mm=34.0, axial_damping=False,
                            pulley_diameter_mm=65.5, parallelism_max_mm=0.5)
    assert v.margins["bushing_p"] == pytest.approx(float(r["margin_p"]), rel=1e-3)
    # hubload 1.85 Nm / (4 mm sin 90) = 462.5 N, p = 462.5 / (20 * 20) = 1.156 MPa vs 3.0 -> margin 0.615
    assert v.margins["bushing_p"] == pytest.approx(1 - 462.5 / 400 / 3.0, rel=1e-3)


def test_enumerate_equals_brute_force_over_the_full_product():
    d = APP
    sp = build_space(d)
    t = sp.subsystems["spring"]
    # three VDSiCr wires with feasible springs for APP (with the EN 10270-2 strength table R2.80, R3.00 and
    # F2.50x2.50 have none left: the brute force would compare two empty sets)
    keep = t[(t["spring_material"] == "VDSiCr") & t["spring_wire"].isin(["R3.20", "F2.80x2.80", "F3.00x2.50"])]
    sp.subsystems["spring"] = keep.reset_index(drop=True)
    ev = evaluate(sp)
    tb = tables(ev, {"cost": 1.0})
    best = np.inf
    # brute force over every combination of the evaluated tables (the decomposition must lose nothing)
    for r in range(len(tb.rows)):
        ranges = [np.flatnonzero(tb.feas[s][r]) for s in SUBSYSTEMS]
        for combo in itertools.product(*ranges):
            c = tb.core_score[r] + sum(tb.score[s][k] for s, k in zip(SUBSYSTEMS, combo))
            best = min(best, c)
    core, options, stats = solve_space(sp, Objective.parse("cost"), ev)
    got = sp.cores["cost_eur"][core] + sum(sp.subsystems[s]["cost_eur"][options[s]] for s in SUBSYSTEMS)
    assert got == pytest.approx(best)
    assert stats["candidates"] >= sp.n_cores


def test_infeasible_case1_yields_a_diagnosis_not_an_exception():
    r = solve(load_input(CASE1), "standard", "enumerate", relax=False)
    assert r.status == "infeasible"
    names = [v["constraint"] for v in r.diagnosis["violated"]]
    assert names and set(names) <= set(r.margins)
    assert all(v["margin"] < 0 for v in r.diagnosis["violated"])


def test_relaxation_of_case3_is_the_smallest_and_works():
    d = load_input(CASE3)
    assert not is_feasible(d)
    r = diagnose(d)
    rel = {k: x for item in r.diagnosis["relaxations"] for k, x in item["inputs"].items()}
    # With the EN 10270-2 strength table (VDSiCr/TDSiCr Rm_min 1960 MPa at 2.0 < d <= 2.5 mm instead of ~2000)
    # the nearest design violates spring_yield, spring_index_max and damping_upper (-0.3 %), and the diagnosis
    # relaxes the damping tolerance 0.2 -> 0.339 N m (+70 %), which verifies. A stiffness of 0.0192 N m/deg
    # (+17 %, the relaxation found before) is still feasible but no longer tried: reported to the lead as a
    # search artefact (issue 12).
    assert rel, r.diagnosis
    assert is_feasible(dataclasses.replace(d, **{k: x["to"] for k, x in rel.items()}))
    assert is_feasible(dataclasses.replace(d, spring_stiffness_nm_per_deg=0.0192))


def test_objective_parsing():
    assert Objective.parse("margin").order == ("margin", "cost")
    assert Objective.parse("cost,standard").order == ("cost", "standard")
    with pytest.raises(InputError, match="objective"):
        Objective.parse("weight")
    with pytest.raises(InputError, match="numeric weights"):
        Objective.parse("cost=a")
    with pytest.raises(InputError, match="solver"):
        solve(APP, "cost", "simplex")


def test_lexicographic_standard_then_cost_and_margin_objective():
    std = solve(APP, "standard")
    cost = solve(APP, "cost")
    marg = solve(APP, "margin")
    assert std.objectives["standard"] <= cost.objectives["standard"]
    assert cost.objectives["cost"] <= std.objectives["cost"]
    assert marg.objectives["margin"] >= max(std.objectives["margin"], cost.objectives["margin"])
    assert marg.binding and marg.binding[0]["margin"] == pytest.approx(marg.objectives["margin"])


def test_design_scene_json(tmp_path, capsys):
    main(["design", CASE1, "--json"])
    out = json.loads(capsys.readouterr().out)
    assert set(out) >= {"parts", "margins", "objectives", "diagnosis"}
    assert out["parts"]["bearing"] == "6006"
    path = tmp_path / "app.yaml"
    path.write_text(yaml.safe_dump({"inputs": {k: v for k, v in APP.as_dict().items() if v is not None}}))
    assert main(["design", str(path), "--objective", "cost", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["status"] == "optimal" and out["objectives"]["cost"] > 0
    assert main(["pareto", str(path), "--out", str(tmp_path / "front"), "--points", "6"]) == 0
    assert (tmp_path / "front" / "front.png").stat().st_size > 1000
    assert "| cost [EUR] |" in (tmp_path / "front" / "front.md").read_text()


@settings(max_examples=4, deadline=None)
@given(st.integers(min_value=0, max_value=10_000))
def test_margins_never_nan_for_generated_applications(seed):
    ev = evaluate(build_space(generate(1, seed=seed)[0]))
    assert not np.isnan(ev.core_margin_array).any()
    for sub in ev.subs.values():
        assert not np.isnan(sub.margins).any()
