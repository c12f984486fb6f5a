"""A new check is one registry entry and one physics function (issue 21): added with ``register`` and seen by the
flowchart, the design, the bulk engine's fast path, the diagnosis, the report and the platform, no other file
touched.

Each probe check reads one value its group computes (``v``) and returns ``value = |v| + 1`` against
``limit = 2 (|v| + 1)``: a margin of exactly 0.5 (``(limit - value) / |limit|``) wherever the group runs, so every
surface must show 0.5. The main spring's compiled kernel (:mod:`synth.kernels.main_spring`, the bulk engine's and
the platform's spring search) computes its own fixed margins: while the registry holds a spring check it does not
know, every kernel call runs on the numpy twin (the registry's own group), so the spring group takes a new check
like the others.
"""

from __future__ import annotations

import inspect

import numpy as np
import pandas as pd
import pytest

import synth
from synth.data import case_path
from synth.design.constraints import Constraint, registered
from synth.io.documents import load_input

#: one value each group computes, non-zero in the cases below (the physics function's one parameter)
READS = {"core": "hubload_nominal_n", "bushing": "pivot_bushing_p_mpa", "axial": "axial_damping_nm",
         "bolt": "tilting_safety_factor", "spring": "main_spring_sigma_inst_mpa"}


def probe(group: str, value_factor: float = 1.0, limit_factor: float = 2.0) -> Constraint:
    """A check of ``group``: ``value = value_factor (|v| + 1)`` <= ``limit = limit_factor (|v| + 1)``."""
    key = READS[group]

    def physics(**kw):
        a = np.abs(np.asarray(kw[key], dtype=float)) + 1.0
        return {f"probe_{group}_value": value_factor * a, f"probe_{group}_limit": limit_factor * a}
    physics.__signature__ = inspect.Signature([inspect.Parameter(key, inspect.Parameter.KEYWORD_ONLY)])
    return Constraint(id=f"probe_{group}", label=f"probe check of the {group} group", step=0, equation="test",
                      unit="-", group=group, value=f"probe_{group}_value", limit=f"probe_{group}_limit",
                      sense="<=", physics=physics)


GROUPS = ("core", "bushing", "axial", "bolt", "spring")
IDS = [f"probe_{g}" for g in GROUPS]


@pytest.fixture(scope="module")
def inputs():
    return load_input(case_path("case1_as_run")), load_input(case_path("case3"))


def test_a_new_check_reaches_flowchart_design_bulk_and_report(inputs, tmp_path):
    d1, d3 = inputs
    with registered(*(probe(g) for g in GROUPS)):
        walk = synth.run_flowchart(d3)
        assert {i: walk.margins[i] for i in IDS} == {i: 0.5 for i in IDS}
        design = synth.synthesise(d3)
        assert {i: design.margins[i] for i in IDS} == {i: 0.5 for i in IDS}
        bulk = synth.screen([d1, d3], diagnose=False, progress=False)
        assert bulk[[f"margin_{i}" for i in IDS]].to_numpy().tolist() == [[0.5] * len(IDS)] * 2
        out = synth.write_report(design, tmp_path, pdf=False, cad_pictures=False)
        html = open(out["html"], encoding="utf-8").read()
        assert all(f"probe check of the {g} group" in html for g in GROUPS)
    assert "probe_core" not in synth.run_flowchart(d3).margins      # gone with the registration


def test_a_new_check_that_fails_is_diagnosed_and_binds_in_the_platform(inputs):
    from synth.platform.portfolio_feasibility import feasibility
    d1, d3 = inputs
    with registered(probe("bolt", value_factor=2.0, limit_factor=1.0)):          # margin -1 everywhere
        r = synth.synthesise(d3)
        assert r.status == "infeasible"
        violated = {v["constraint"]: v["margin"] for v in r.diagnosis["violated"]}
        assert violated["probe_bolt"] == -1.0
    with registered(probe("bolt", limit_factor=1.0 + 1e-9)):                    # passes by 1e-9: it binds
        pf = feasibility([d1, d3])
        bindings = {str(b) for a in pf.apps for g in a.option_binding["bolt"] for b in g}
        assert bindings == {"probe_bolt"}


def test_a_spring_check_runs_the_kernels_on_their_numpy_twin_and_binds_in_the_platform():
    """The compiled kernels know their own margins only: a registered spring check sends every kernel call to the
    numpy twin (its column after theirs), the platform's spring search binds on it; unregistered, the kernels run."""
    from synth.design.constraints import by_group
    from synth.kernels import main_spring
    from synth.platform.portfolio_feasibility import feasibility
    from synth.scenes.demo import default_input
    d = default_input()  # cases 1 and 3 have no feasible spring option to bind
    from synth.design.settings import DEFAULT
    from synth.kernels import engines
    assert main_spring.compiled_covers() and main_spring.checks() == main_spring.MARGIN_NAMES
    with registered(probe("spring", limit_factor=1.0 + 1e-9)):                  # passes by 1e-9: it binds
        assert not main_spring.compiled_covers()
        assert main_spring.checks() == tuple(c.id for c in by_group("spring") if not c.advisory)
        assert engines.spring(DEFAULT, "numba") == "numpy"
        pf = feasibility([d])
        assert {str(b) for g in pf.apps[0].option_binding["spring"] for b in g} == {"probe_spring"}
    assert engines.spring(DEFAULT, "numba") == "numba"
    pf = feasibility([d])   # the kernels again: the step-9 checks bind
    assert {str(b) for g in pf.apps[0].option_binding["spring"] for b in g} == {
        "spring_coil_gap", "spring_fatigue", "spring_index_max", "spring_outer_contact", "spring_inner_contact"}


def test_a_bolt_check_reading_the_core_is_judged_per_core_in_the_bulk_fast_path():
    """A bolt check whose physics reads a core value, as the pivot wall's does, is judged per core row and bolt
    by the bulk engine's fast path (:func:`synth.design.evaluate.bolt_core_checks`), never per application: a
    pivot of at most 18 mm (margin ``(18 - d_p) / 18``, failing for the 19-25 mm pivots) gives the answers of
    the exhaustive enumeration (before issue 21's mend such a check was evaluated with the application's first
    core, or not found: a KeyError)."""
    from synth.bulk.engine import screen_applications, screen_applications_reference
    from synth.data.generated_applications import generate
    from synth.design.evaluate import bolt_core_checks

    def physics(pivot_diameter_mm, bolt_d_mm):
        d = np.asarray(pivot_diameter_mm, dtype=float) + 0.0 * np.asarray(bolt_d_mm, dtype=float)
        return {"probe_pivot_value": d, "probe_pivot_limit": np.full(np.shape(d), 18.0)}
    probe_pivot = Constraint(id="probe_pivot", label="probe: pivot at most 18 mm", step=2, equation="test",
                             unit="mm", group="bolt", value="probe_pivot_value", limit="probe_pivot_limit",
                             sense="<=", physics=physics)
    apps = generate(4, seed=3)
    with registered(probe_pivot):
        assert [c.id for c in bolt_core_checks({"pivot_diameter_mm": 0, "loading_arm_mm": 0})] == [
            "pivot_wall", "probe_pivot"]
        fast = screen_applications(apps, diagnose=False)
        ref = screen_applications_reference(apps, diagnose=False)
    pd.testing.assert_frame_equal(fast, ref, check_exact=False, rtol=1e-9, atol=1e-12)
    # every chosen pivot passes (the feasible designs) and one sits on the limit: the check bound the choice
    pivots = 18.0 - 18.0 * fast["margin_probe_pivot"].to_numpy()
    assert fast["feasible"].all() and (pivots <= 18.0 + 1e-9).all() and np.isclose(pivots, 18.0).any()
    assert set(np.round(pivots, 9)) <= {float(d) for d in range(14, 26)}                 # pivot diameters [mm]


def test_a_check_reading_another_part_family_stops_the_command_line_with_exit_2(capsys):
    """A bolt check whose physics reads the main spring's mean body diameter (another family's part, which the input
    field of that name only pins): ``synth design`` says which check and value, as a declaration error, exit 2 (not
    the internal error's 70, not a design failing with margin -inf as before)."""
    from synth.cli import main

    def reads_spring(main_spring_mean_body_diameter_mm):
        a = np.abs(np.asarray(main_spring_mean_body_diameter_mm, dtype=float)) + 1.0
        return {"coupled_value": a, "coupled_limit": 2.0 * a}
    check = Constraint(id="bolt_reads_spring", label="a bolt check reading the main spring", step=10,
                       equation="test", unit="mm", group="bolt", value="coupled_value", limit="coupled_limit",
                       sense="<=", physics=reads_spring)
    with registered(check):
        code = main(["design", str(case_path("case3"))])
    err = capsys.readouterr().err
    assert code == 2, err
    assert "synth: invalid declaration" in err
    assert "constraint bolt_reads_spring (group bolt)" in err and "'main_spring_mean_body_diameter_mm'" in err
