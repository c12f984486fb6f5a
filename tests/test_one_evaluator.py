"""One evaluator: the flowchart, the optimiser's product layout and the bulk applications axis give the same
margin for every registry constraint of the same design (to 1e-9), and the same verdicts.

300 generated applications across the schema's choices, every optional input present and absent
(``generate(..., vary=True)``). For each, the design is the one the thesis flowchart builds:

* path A: ``flowchart.run(d)`` (one row per group, the flowchart's own calls);
* path B: the optimiser's layout, the design's rows inside the catalog product of its application
  (every core of the application; every option of each subsystem for the design's core);
* path C: the bulk layout, every application's design as one row of one call per group.
"""

from __future__ import annotations

import json

import numpy as np
import pytest

from synth import flowchart
from synth.data.generated_applications import generate
from synth.design import evaluate
from synth.design.applications import Applications
from synth.design.constraints import REGISTRY
from synth.design.result import FAIL, NOT_APPLICABLE, NOT_VERIFIED, PASS, WARNING
from synth.design.space import SUBSYSTEMS, core_rows, space

SETTINGS = evaluate.Settings(fidelity="screening-only")  # the screening model itself, on every path
APPS = generate(300, seed=11, vary=True)
TOL = 1e-9
GROUPS = ("input", "core", "bushing", "axial", "spring", "bolt")


@pytest.fixture(scope="module")
def designs():
    """``[(input, Result, attrs)]`` of the applications whose flowchart completes a design."""
    out = []
    sp = space()
    for d in APPS:
        r = flowchart.run(d, SETTINGS, time_points=0)
        if r.parts:
            out.append((d, r, sp.design_attributes(r.parts)))
    assert len(out) >= 250  # a few stop early (self-locking arm, no Table 2 class): their checks say so
    return out


def _concat(rows: list) -> dict:
    return {k: np.concatenate([np.asarray(r[k]) for r in rows]) for k in rows[0]}


def _margin_of(result, cid):
    c = result.check(cid)
    return c.margin, c.verdict


def _compare(result, group: evaluate.Group, row: int, where: str):
    """Every constraint of ``group``: the margin at ``row`` equals the result's check, and so does the verdict."""
    from synth.design.evaluate import EVALUATED
    for cid, m in group.margins.items():
        ref, verdict = _margin_of(result, cid)
        state = int(group.state[cid][row])
        if verdict == NOT_APPLICABLE:
            assert state == evaluate.NOT_APPLICABLE, (where, cid)
            continue
        if verdict == NOT_VERIFIED:
            assert state == evaluate.NOT_VERIFIED, (where, cid)
            continue
        assert state == EVALUATED, (where, cid, state)
        got = float(m[row])
        if np.isinf(ref) or np.isinf(got):
            assert ref == got, (where, cid, ref, got)
        else:
            assert abs(got - ref) <= TOL * max(1.0, abs(ref)), (where, cid, got, ref)
        ok = got >= -1e-9
        expected = {PASS: True, FAIL: False, WARNING: False}[verdict]
        if REGISTRY[cid].advisory and verdict == PASS:
            expected = True
        assert ok == expected, (where, cid, got, verdict)


def test_every_registry_constraint_is_checked_by_the_flowchart(designs):
    ids = {c.id for _, r, _ in designs for c in r.checks}
    assert ids == {cid for cid, c in REGISTRY.items() if c.group in GROUPS}  # not the 3D model's, not the shrink fit's


def test_product_layout_equals_the_flowchart(designs):
    """Path B against path A, for every constraint of every group (every third application: the layout is the
    same for all, and each takes its whole catalog product)."""
    sp = space()
    for d, r, attrs in designs[::3]:
        apps = Applications.of([d])
        cores = core_rows(sp, d)
        table = sp.rows("core", cores)
        core_all = _concat([table, attrs["core"]])               # the design's core as the last row
        cg = evaluate.core(apps, np.zeros(len(cores) + 1, dtype=np.int64), core_all, SETTINGS)
        me = len(cores)
        _compare(r, cg, me, "core")
        _compare(r, evaluate.inputs(apps, np.zeros(1, dtype=np.int64)), 0, "input")
        for s in SUBSYSTEMS:
            t = sp.tables[s]
            if s == "bushing":
                opts = np.flatnonzero(t["supplier_code"] == attrs["core"]["supplier_code"][0])
            elif s == "axial":
                opts = np.flatnonzero(t["axial_group_present"] == attrs["axial"]["axial_group_present"][0])
            elif s == "spring":
                opts = np.arange(0, sp.n("spring"), 97)
            else:
                opts = np.arange(sp.n("bolt"))
            o = _concat([sp.rows(s, opts), attrs[s]])
            k = len(opts)
            rows = np.full(k + 1, me)
            if s == "spring":
                keys = evaluate.spring_keys(cg, np.arange(len(cores) + 1))  # every core's key; the design's last
                g = evaluate.spring(apps, keys, np.full(k + 1, me), o, SETTINGS)
            else:
                g = getattr(evaluate, s)(apps, cg, rows, o, SETTINGS)
            _compare(r, g, k, s)


def test_applications_axis_equals_the_flowchart(designs):
    """Path C against path A: one call per group for every application's design at once."""
    inputs = [d for d, _, _ in designs]
    apps = Applications.of(inputs)
    n = len(inputs)
    a = np.arange(n)
    attrs = {t: _concat([x[t] for _, _, x in designs]) for t in ("core",) + SUBSYSTEMS}
    cg = evaluate.core(apps, a, attrs["core"], SETTINGS)
    groups = {"input": evaluate.inputs(apps, a), "core": cg,
              "bushing": evaluate.bushing(apps, cg, a, attrs["bushing"], SETTINGS),
              "axial": evaluate.axial(apps, cg, a, attrs["axial"], SETTINGS),
              "spring": evaluate.spring(apps, evaluate.spring_keys(cg, a), a, attrs["spring"], SETTINGS),
              "bolt": evaluate.bolt(apps, cg, a, attrs["bolt"], SETTINGS)}
    for i, (_, r, _) in enumerate(designs):
        for name, g in groups.items():
            _compare(r, g, i, f"{name} (application {i})")


def test_bulk_engine_margins_equal_the_flowchart_on_the_same_design(designs):
    """The bulk engine's row margins of its design equal the flowchart's fixed-parts verification of it."""
    from synth.bulk.engine import constraint_ids, screen_applications
    sample = [d for d, _, _ in designs[:24]]
    df = screen_applications(sample, objective="standard", fidelity=SETTINGS.fidelity, diagnose=False)
    from synth.design.space import PART_KEYS
    for i, d in enumerate(sample):
        row = df.iloc[i]
        parts = {k: row[f"part_{k}"] for k in PART_KEYS}
        if parts["ball_bearing"] is None:
            continue
        f = flowchart.run(d, SETTINGS, parts=parts, time_points=0)
        for cid in constraint_ids():
            c = f.check(cid)
            got = row[f"margin_{cid}"]
            if c.verdict in (PASS, FAIL, WARNING) and np.isinf(c.margin):
                assert got == c.margin, (i, cid, got, c.margin)
            elif c.verdict in (PASS, FAIL, WARNING):
                assert abs(got - c.margin) <= TOL * max(1.0, abs(c.margin)), (i, cid, got, c.margin)
            else:
                assert np.isnan(got), (i, cid, got, c.verdict)


@pytest.mark.parametrize("case", ["case3", "case1_as_run"])
def test_flowchart_parts_of_a_saved_design_give_the_design_s_values(case, tmp_path, capsys):
    """``synth design --json`` then ``synth flowchart --parts``: the same value for every key they share."""
    from synth.cli import main
    from synth.data import case_path
    path = str(case_path(case))
    main(["design", path, "--json"])
    saved = capsys.readouterr().out
    (tmp_path / "design.json").write_text(saved)
    main(["flowchart", path, "--parts", str(tmp_path / "design.json"), "--json"])
    flow = json.loads(capsys.readouterr().out)
    design = json.loads(saved)
    assert flow["parts"] == design["parts"]
    shared = set(flow["values"]) & set(design["values"])
    assert len(shared) > 80
    for k in shared:
        a, b = flow["values"][k], design["values"][k]
        if isinstance(a, float) and isinstance(b, float):
            assert abs(a - b) <= 1e-9 * max(1.0, abs(b)), k
        else:
            assert a == b, k
    assert [(c["id"], c["verdict"]) for c in flow["checks"]] == [(c["id"], c["verdict"]) for c in design["checks"]]
