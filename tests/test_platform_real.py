"""Platform rationalisation on real data: the producer against the optimiser's catalog product, every assigned
design verified, the platform against the union of the per-application optima.

The fast tests use a 12-application ``portfolio-sample``. The 200-application tests of issue 16 take a few
minutes (they solve every application with ``synth.optimise.solve``): they are marked ``slow`` and run with
``SYNTH_SLOW=1 pytest tests/test_platform_real.py``.
"""

import os

import numpy as np
import pandas as pd
import pytest

from synth.bulk.portfolio import records, validate_record
from synth.bulk.sample import sample_portfolio
from synth.design import evaluate
from synth.design.applications import Applications
from synth.design.constraints import REGISTRY
from synth.design.space import SUBSYSTEMS, core_rows
from synth.design.verify import verify
from synth.errors import InputError
from synth.platform import portfolio_feasibility as F
from synth.platform import producer as P
from synth.platform.data import FAMILIES
from synth.platform.options import NO_PART_KEY, catalogue, family_keys
from synth.platform.outputs import report_section
from synth.platform.rationalise import rationalise

slow = pytest.mark.skipif(not os.environ.get("SYNTH_SLOW"), reason="slow (minutes): set SYNTH_SLOW=1 to run")

SETTINGS = evaluate.Settings()


@pytest.fixture(scope="module")
def sample():
    table = sample_portfolio(12, seed=5)
    return table, F.from_table(table, SETTINGS)


@pytest.fixture(scope="module")
def platform(sample):
    return rationalise(sample[1], "variants", time_limit=60)


def test_producer_equals_the_optimiser_product(sample):
    """Per application, per feasible core, per subsystem: the feasible options (and their margins) of the
    producer's grouped, staged evaluation are those of ``synth.optimise.product`` (every core against every
    option of the optimiser's design space, ungrouped). The sets are equal; the margins equal bit for bit except the
    axial group's, which the producer evaluates on the compiled wear (:mod:`synth.kernels.axial`, within
    :data:`synth.kernels.axial.RTOL` of the reference): within :data:`synth.platform.producer.MARGIN_TOL`."""
    from synth.optimise.product import evaluate
    _, pf = sample
    cat = catalogue()
    checked = 0
    for a, d in zip(pf.apps, pf.design_inputs):
        ev = evaluate(d, SETTINGS)
        feasible_cores = ev.cores[ev.rows]
        assert sorted(a.core_rows.tolist()) == sorted(feasible_cores.tolist())
        for r_idx, row in enumerate(feasible_cores):
            c = int(np.flatnonzero(a.core_rows == row)[0])
            assert a.core_margin[c] == ev.core.min_margin()[ev.rows[r_idx]]
            for s in SUBSYSTEMS:
                g = int(a.group[s][c])
                mine = dict(zip([int(cat.option_row[s][int(o)]) for o in a.feasible[s][g]], a.option_margin[s][g]))
                sub = ev.subs[s]
                theirs = np.flatnonzero(sub.feasible[r_idx])
                assert set(mine) == set(theirs.tolist()), (a.app_id, s, int(row))
                for k in theirs[:50]:
                    if s == "axial":
                        assert abs(mine[int(k)] - sub.margin[r_idx, k]) <= P.MARGIN_TOL
                    else:
                        assert mine[int(k)] == sub.margin[r_idx, k]
                checked += len(theirs)
    assert checked > 500


def test_spring_stages_declare_what_the_margins_read(sample):
    """A stage's constraints give the same margins whatever the key columns outside the stage's."""
    _, pf = sample
    d = next(x for x, a in zip(pf.design_inputs, pf.apps) if a.n_cores)
    apps = Applications.of([d])
    sp = catalogue().space
    rows = core_rows(sp, d)
    with np.errstate(all="ignore"):
        cg = evaluate.core(apps, np.zeros(len(rows), np.int64), sp.rows("core", rows), SETTINGS)
    keys = evaluate.spring_keys(cg, np.arange(len(rows))[:1])
    opts = sp.rows("spring", np.arange(0, sp.n("spring"), 7))
    k = np.zeros(len(opts["E_mpa"]), np.int64)
    base = P.spring_group(apps, keys, k, opts, SETTINGS)
    cols = ("spring_torque_nominal_nm", "spring_housing_height_mm", "spring_housing_outer_diameter_mm",
            "spring_housing_inner_diameter_mm")
    assert all(set(P.SPRING_STAGES[i][0]) <= set(P.SPRING_STAGES[i + 1][0]) for i in range(len(P.SPRING_STAGES) - 1))
    for stage_cols, ids, _ in P.SPRING_STAGES:
        assert all(REGISTRY[c].group == "spring" for c in ids)
        for col in cols:
            if col in stage_cols:
                continue
            moved = dict(keys)
            moved[col] = keys[col] * 1.37 + 3.0
            other = P.spring_group(apps, moved, k, opts, SETTINGS)
            for cid in (c for c in ids if not REGISTRY[c].advisory):  # advisory ones decide nothing (not kept)
                np.testing.assert_array_equal(other.margins[cid], base.margins[cid], err_msg=f"{cid} reads {col}")
    # each stage's margins move one way along its monotone column (a spring failing at one value is not tried
    # again where it must fail too)
    for _, ids, (mcol, direction) in P.SPRING_STAGES:
        prev = base
        for f in (1.1, 1.5, 2.5):
            moved = dict(keys)
            moved[mcol] = keys[mcol] * f
            more = P.spring_group(apps, moved, k, opts, SETTINGS)
            for cid in ids:
                if not REGISTRY[cid].advisory:
                    step = more.margins[cid] - prev.margins[cid]
                    assert np.all(direction * step[np.isfinite(step)] <= 1e-12), (cid, mcol)
            prev = more
        assert any(not np.array_equal(prev.margins[c], base.margins[c]) for c in ids)
    # and the exercise is not empty: moving a stage column does change a stage margin
    moved = dict(keys)
    moved["spring_housing_height_mm"] = keys["spring_housing_height_mm"] * 0.5
    assert not np.array_equal(P.spring_group(apps, moved, k, opts, SETTINGS).margins["spring_coil_gap"],
                              base.margins["spring_coil_gap"])


def test_margins_and_binding_is_the_groups_min_margin(sample):
    _, pf = sample
    apps = Applications.of([pf.design_inputs[0]])
    sp = catalogue().space
    with np.errstate(all="ignore"):
        cg = evaluate.core(apps, np.zeros(sp.n("core"), np.int64), sp.rows("core", np.arange(sp.n("core"))), SETTINGS)
    for objective_only in (True, False):
        m, b = P.margins_and_binding(cg, objective_only)
        np.testing.assert_array_equal(m, cg.min_margin(objective_only))
        ids = list(REGISTRY)
        for i in np.flatnonzero(np.isfinite(m))[:20]:
            assert cg.margins[ids[b[i]]][i] == m[i]


def test_every_assigned_design_verifies_and_uses_platform_parts(sample, platform):
    table, pf = sample
    r = platform
    assert r.status == "optimal"
    served = [x for x in r.records if x["feasible"]]
    assert len(served) == sum(x["feasible"] for x in r.per_app_optima) >= 3
    keys_of = {f: {pf.part_key(f, c) for c in r.platform[f]} for f in FAMILIES}
    for i, rec in enumerate(r.records):
        if not rec["feasible"]:
            continue
        res = verify(pf.design_inputs[i], rec["design"], SETTINGS, detail=False)
        assert not res.failed() and res.verdict == rec["verdict"]
        assert (res.binding(1)[0].id, res.binding(1)[0].margin) == (rec["binding"], rec["margin"])
        fk = family_keys(rec["design"])
        assert fk == rec["parts"]                                    # the option tables name the parts right
        for f, key in fk.items():
            assert key == NO_PART_KEY or key in keys_of[f]
    assert r.n_parts <= r.n_parts_union_optima


def test_flowchart_fixed_parts_agrees(sample, platform):
    from synth.flowchart import run
    _, pf = sample
    done = 0
    for i, rec in enumerate(platform.records):
        if rec["feasible"] and done < 2:
            res = run(pf.design_inputs[i], parts=rec["design"], time_points=0)
            assert not res.failed()
            assert res.binding(1)[0].id == rec["binding"]
            done += 1
    assert done == 2


def test_applications_with_no_design_say_why_and_are_infeasible(sample):
    from synth.optimise.diagnose import is_feasible
    _, pf = sample
    bad = [(a, d) for a, d in zip(pf.apps, pf.design_inputs) if a.note]
    good = [(a, d) for a, d in zip(pf.apps, pf.design_inputs) if not a.note]
    assert bad and good
    ids = set(REGISTRY)
    for a, d in bad[:1]:
        assert a.note.startswith("no ")
        assert any(cid in a.note for cid in ids)
        assert not is_feasible(d, SETTINGS)
    assert is_feasible(good[0][1], SETTINGS)


def test_diagnose_option_names_the_nearest_design():
    table = sample_portfolio(12, seed=5)
    d, _ = validate_record(records(table)[0])
    pf = F.feasibility([d], ["x"], settings=SETTINGS, diagnose=True)
    note = pf.apps[0].note
    if note:  # an application with no design: the diagnosis of the whole catalog product
        assert note.startswith("no feasible design (synth.optimise.diagnose)")


def test_broken_rows_are_reported_not_evaluated(tmp_path):
    table = sample_portfolio(4, seed=1, broken=2)
    pf = F.from_table(table, SETTINGS)
    notes = [a.note for a in pf.apps]
    assert sum(n.startswith("input error: ") for n in notes) == 2
    r = rationalise(pf, time_limit=30)
    for rec, n in zip(r.records, notes):
        if n.startswith("input error"):
            assert not rec["feasible"] and rec["reason"].startswith("input error: ")


def test_volume_column_weighs_the_cost_and_a_bad_volume_is_named():
    table = sample_portfolio(3, seed=1)
    table["annual_volume"] = [1000, 50000, 200]
    pf = F.from_table(table, SETTINGS)
    assert [a.volume for a in pf.apps] == [1000.0, 50000.0, 200.0]
    table["annual_volume"] = [1000, "lots", -3]
    with pytest.raises(InputError) as e:
        F.from_table(table, SETTINGS)
    text = str(e.value)
    assert "annual_volume (row 2): got 'lots'" in text and "annual_volume (row 3): got -3" in text


def test_dask_engine_gives_the_same_data():
    table = sample_portfolio(2, seed=2)
    a = F.from_table(table, SETTINGS, chunk_size=1)
    b = F.from_table(table, SETTINGS, chunk_size=1, engine="dask", workers=1)
    for x, y in zip(a.apps, b.apps):
        assert x.note == y.note
        np.testing.assert_array_equal(x.core_rows, y.core_rows)
        for s in SUBSYSTEMS:
            np.testing.assert_array_equal(x.group[s], y.group[s])
            assert all(np.array_equal(p, q) for p, q in zip(x.feasible[s], y.feasible[s]))


def test_forked_chunks_give_the_same_data():
    """The in-process engine's chunks on forked processes (issue 36; two where the machine has two cores): the same
    data, in the same order, as one process computes."""
    table = sample_portfolio(3, seed=2)
    a = F.from_table(table, SETTINGS, chunk_size=1, processes=1)
    b = F.from_table(table, SETTINGS, chunk_size=1, processes=2)
    assert F.processes_for(3, None) == F.PROCESSES and F.processes_for(1, 2) == 1
    for x, y in zip(a.apps, b.apps, strict=True):
        assert (x.app_id, x.note, x.volume) == (y.app_id, y.note, y.volume)
        for f in ("core_rows", "core_margin", "core_cost_eur", "core_binding"):
            np.testing.assert_array_equal(getattr(x, f), getattr(y, f))
        for s in SUBSYSTEMS:
            np.testing.assert_array_equal(x.group[s], y.group[s])
            for attr in ("feasible", "option_margin", "option_binding"):
                assert all(np.array_equal(p, q) for p, q in zip(getattr(x, attr)[s], getattr(y, attr)[s], strict=True))


def test_spring_costs_computed_when_read_are_the_catalogs(sample):
    """Each application's main-spring costs are held as one shared vector and its stiffness (issue 36's memory):
    read, they are the catalogue's per-application vector, bit for bit."""
    table, pf = sample
    cat = catalogue()
    for d, a in zip(pf.design_inputs, pf.apps):
        got = np.asarray(a.option_cost_eur["spring"], float)
        assert np.array_equal(got, cat.spring_cost_eur(float(d.spring_stiffness_nm_per_deg)))
        assert len(a.option_cost_eur["spring"]) == np.shape(a.option_cost_eur["spring"])[0] == len(got)


def test_report_section_is_self_contained(platform):
    platform.tradeoff = [{"margin_floor": 0.0, "parts": platform.n_parts, "weighted_parts": platform.n_parts,
                          "cost_eur": 1.0, "worst_margin": 0.0, "served": 3, "status": "optimal"},
                         {"margin_floor": 0.05, "parts": platform.n_parts + 2, "weighted_parts": platform.n_parts + 2,
                          "cost_eur": 1.0, "worst_margin": 0.05, "served": 3, "status": "optimal"}]
    html = report_section(platform)
    platform.tradeoff = None
    assert html.startswith('<section id="platform">') and html.endswith("</section>")
    assert html.count("data:image/png;base64,") == 2
    for row in platform.table:
        assert f"<td>{row['part']}</td>" in html.replace("&quot;", '"')
    assert "<script" not in html and "http" not in html


def test_scene_on_a_real_portfolio(tmp_path, capsys):
    import argparse
    from synth.scenes import rationalise as scene
    path = tmp_path / "portfolio.csv"
    sample_portfolio(8, seed=5, broken=1).to_csv(path, index=False)
    p = argparse.ArgumentParser()
    scene.register(p.add_subparsers())
    args = p.parse_args(["rationalise", str(path), "--out", str(tmp_path / "out"), "--tradeoff", "none"])
    assert args.func(args) == 0
    assign = pd.read_csv(tmp_path / "out" / "assignment.csv", keep_default_na=False)
    plat = pd.read_csv(tmp_path / "out" / "platform.csv")
    assert len(assign) == 8 and "verdict" in assign.columns
    ok = assign[assign["feasible"].astype(str) == "True"]
    assert len(ok) and set(ok["verdict"]) <= {"pass", "incomplete"}
    for f in FAMILIES:
        used = set(ok[f][ok[f] != "none"].astype(str))
        assert used <= set(plat.loc[plat["family"] == f, "part"].astype(str))
    bad = assign[assign["feasible"].astype(str) == "False"]
    assert (bad["reason"] != "").all() and bad["reason"].str.startswith("input error").sum() == 1
    summary = (tmp_path / "out" / "summary.md").read_text()
    assert "## Feasibility data" in summary and "variables" in summary
    assert "applications served by" in capsys.readouterr().out


# ------------------------------------------------------------------------------------------- 200 applications

@pytest.fixture(scope="module")
def big():
    table = sample_portfolio(200, seed=0)
    pf = F.from_table(table, SETTINGS)
    return pf, rationalise(pf, "variants", time_limit=120)


@slow
def test_200_every_assigned_design_verifies_through_verify(big):
    pf, r = big
    keys_of = {f: {pf.part_key(f, c) for c in r.platform[f]} for f in FAMILIES}
    n = 0
    for i, rec in enumerate(r.records):
        if not rec["feasible"]:
            continue
        res = verify(pf.design_inputs[i], rec["design"], SETTINGS, detail=False)
        assert res.feasible and res.verdict == rec["verdict"]
        assert all(k == NO_PART_KEY or k in keys_of[f] for f, k in family_keys(rec["design"]).items())
        n += 1
    assert n == sum(x["feasible"] for x in r.per_app_optima) > 100


@slow
def test_200_a_sample_verifies_through_the_flowchart(big):
    from synth.flowchart import run
    pf, r = big
    served = [i for i, rec in enumerate(r.records) if rec["feasible"]]
    for i in served[:: max(1, len(served) // 12)]:
        res = run(pf.design_inputs[i], parts=r.records[i]["design"], time_points=0)
        assert not res.failed()


@slow
def test_200_platform_no_larger_than_the_union_of_per_application_optima(big):
    """The union of the designs ``synth.optimise.solve(d, "standard")`` picks is itself a platform; the MILP's
    is no larger, and the applications it serves are exactly those ``solve`` finds feasible."""
    from synth.optimise import solve
    pf, r = big
    union = {f: set() for f in FAMILIES}
    for i, (d, rec) in enumerate(zip(pf.design_inputs, r.records)):
        res = solve(d, "standard", "enumerate", settings=SETTINGS, relax=False)
        assert (res.status == "optimal") == rec["feasible"], pf.apps[i].app_id
        if res.status == "optimal":
            for f, k in family_keys(res.parts).items():
                if k != NO_PART_KEY:
                    union[f].add(k)
    assert r.n_parts <= sum(len(v) for v in union.values())


def test_array_build_and_pyomo_build_choose_the_same_platform():
    """A 60-application ``portfolio-sample``: the MILP built from arrays for highspy (the default) and built through
    Pyomo (the reference) give the same objective, platform and assignment, design by design."""
    pf = F.from_table(sample_portfolio(60, seed=1), SETTINGS)
    fast = rationalise(pf, "variants", time_limit=60, details=False)
    ref = rationalise(pf, "variants", time_limit=60, details=False, build="pyomo")
    assert fast.status == ref.status == "optimal" and fast.n_parts >= 5
    assert (fast.objective_value, fast.platform, fast.size) == (ref.objective_value, ref.platform, ref.size)
    assert fast.records == ref.records and sum(r["feasible"] for r in fast.records) >= 20


def test_feasibility_data_are_held_compactly(sample):
    """Issue 36's memory: each feasible option is held as an int32 index and its binding constraint as an int16 code
    into a names table shared by the chunk (read, the names are the registry's ids, as the object arrays were)."""
    _, pf = sample
    ids = set(REGISTRY) | {""}
    n = 0
    for a in pf.apps:
        for s in SUBSYSTEMS:
            for f, m, b in zip(a.feasible[s], a.option_margin[s], a.option_binding[s], strict=True):
                assert f.dtype == np.int32 and b.codes.dtype == np.int16 and len(b) == len(f) == len(m)
                names = np.asarray(b).tolist()
                assert set(names) <= ids and [b[i] for i in range(len(b))] == list(b) == names
                n += len(f)
    assert n > 0 and len({id(b.names) for a in pf.apps for g in a.option_binding.values() for b in g}) == 1


@pytest.mark.parametrize("batch", [None, 64])
def test_dominated_cores_removes_what_the_pairwise_definition_does(sample, batch, monkeypatch):
    """R3 (:func:`synth.platform.prune.dominated_cores`: every pair of an application's cores at once, subset tests
    on bit sets) removes exactly the cores its definition does, checked pair by pair on Python sets, on real data in
    a second round of the reductions (where it removes some: synthetic data never exercise it; the cost objective
    removes none on this sample, its cores' costs differ); also with the applications judged in batches of at most
    64 pairs of cores (:data:`synth.platform.prune.CORE_PAIRS`, which bounds its memory)."""
    from synth.platform import prune as R
    from synth.platform.compile import compile_portfolio
    if batch is not None:
        monkeypatch.setattr(R, "CORE_PAIRS", batch)
    w = compile_portfolio(sample[1], "variants")
    R.prune(w, max_rounds=1)
    R.dominated_options(w)
    R.dominated_variants(w)
    row = {}                                   # (core, subsystem) -> its live row
    for i, live in enumerate(w.row_alive):
        for c in (w.row_cores[i] if live else ()):
            row[int(c), w.row_sub[i]] = i

    def better(a, b):   # a's parts among b's, a's rows hold b's options (a dropped row holds all)
        if not set(w.patterns[w.core_pattern[a]]) <= set(w.patterns[w.core_pattern[b]]):
            return False
        for si in range(len(SUBSYSTEMS)):
            ra, rb = row.get((a, si), -1), row.get((b, si), -1)
            if ra >= 0 and (rb < 0 or not set(w.row_pats[rb].tolist()) <= set(w.row_pats[ra].tolist())):
                return False
        return True

    alive = np.flatnonzero(w.core_alive)
    expect = set()
    for app in np.unique(w.core_app[alive]):
        cs = alive[w.core_app[alive] == app].tolist()
        expect |= {b for b in cs if any(better(a, b) and (not better(b, a) or a < b) for a in cs if a != b)}
    n = R.dominated_cores(w)
    assert n == len(expect) > 0
    assert set(alive[~w.core_alive[alive]].tolist()) == expect
