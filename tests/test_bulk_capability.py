"""``synth bulk --capability``: each row is the design ``synth design --capability`` returns (issue 34).

The rows' one mechanism is the design's (:func:`synth.optimise.honour.solve_honouring` with ``robust=``); what the
bulk adds is the chunk-wide shortcut for applications with no design under the made joint, and the run's one
configuration carrying the target into the chunk (:func:`synth.bulk.run.compute_chunk`, also a Dask worker's
task). The 50-row sample and the throughput on 2,000 rows: ``benchmarks/bench_bulk_capability.py``.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from synth.bulk.run import compute_chunk
from synth.data.generated_applications import generate
from synth.design.settings import Settings
from synth.design.space import PART_KEYS
from synth.robust.settings import RobustSettings

RS = RobustSettings(capability=1.33, samples=256)


def test_a_row_without_a_made_design_is_the_robust_synthesis_s_answer():
    """Generated application 2 (seed 0) passes nominally but none of its designs passes with the made joint (its
    VDI 2230 preload window): the robust search has no candidate (no core checked), so ``synth design
    --capability`` returns the nominal optimum with the search's reason; the bulk's chunk-wide shortcut row (the
    run's chunk path, the target in its settings) is that nominal row, failed by the target, with that reason and
    the nominal design's capability (before the 50-row check of ``bench_bulk_capability_equality.py``: left out,
    the smallest Ppk empty where ``synth design`` prints -0.836 at 1024 samples)."""
    from synth.optimise.product import evaluate
    from synth.robust.sampling import production
    from synth.robust.synthesis import SearchReport, search
    d = generate(3, seed=0)[2]
    settings = Settings(fidelity="full", capability=RS)
    row = compute_chunk([d.as_dict()], settings=settings, diagnose=False).iloc[0]
    nominal = compute_chunk([d.as_dict()], settings=settings.replace(capability=None), diagnose=False).iloc[0]
    assert nominal["capability_verdict"] == "" and math.isnan(nominal["capability_min_ppk"])  # no target: empty
    rep = SearchReport()
    assert search(evaluate(d, production(settings)), {"standard": 1.0}, RS, report=rep)[1] is None
    assert rep.cores_checked == 0 and rep.candidates == 0
    assert {k: row[f"part_{k}"] for k in PART_KEYS} == {k: nominal[f"part_{k}"] for k in PART_KEYS}
    assert bool(row["feasible"]) and nominal["verdict"] != "fail" and row["verdict"] == "fail"
    # the nominal design's capability beside it, as synth design reports it: below the target
    assert row["capability_verdict"] == "FAIL" and row["capability_min_ppk"] < 1.33 and row["capability_failing"]
    assert row["capability_why"] == rep.why_none(RS) and rep.why_none(RS) in row["notes"]
    assert row["capability_why"].startswith("no catalog design passes every check with the made joint")


def test_a_shortcut_row_at_full_fidelity_is_synth_design_s_at_full_fidelity():
    """Generated application 10 (seed 0) has no design under the made joint: its row at full fidelity is the
    bulk's nominal row, which must be the full model's (``synth design``'s ``standard,cost,margin``: cone spring
    aspect ratio 0.94). Before issue 34's mend the nominal rows took ``screen_applications``' default fidelity
    (``screening``) over the run's settings and named the screening search's design of equal objective (1.3); so did
    ``screen_applications(apps, settings=full)`` without a fidelity argument (the benchmark's call)."""
    from synth.bulk.engine import screen_applications
    from synth.optimise import solve
    d = generate(11, seed=0)[10]
    full = Settings(fidelity="full")
    want = solve(d, "standard,cost,margin", "enumerate", settings=full, relax=False).parts
    assert want["cone_spring_aspect_ratio"] == 0.94
    row = compute_chunk([d.as_dict()], settings=full.replace(capability=RS), diagnose=False).iloc[0]
    assert row["capability_verdict"] == "FAIL" and row["capability_why"].startswith("no catalog design passes")
    assert {k: row[f"part_{k}"] for k in PART_KEYS} == want
    row = screen_applications([d], settings=full, diagnose=False).iloc[0]
    assert {k: row[f"part_{k}"] for k in PART_KEYS} == want


def test_the_target_is_part_of_the_configuration():
    with pytest.raises(Exception, match="capability"):
        Settings(capability=1.33)
    s = Settings(capability=RS)
    assert s.capability is RS and s.replace(capability=None).capability is None and s != Settings()


def test_a_resume_under_another_target_is_refused(tmp_path):
    from synth.bulk.store import check_manifest as _check_manifest, manifest_of
    from synth.errors import InputError

    def manifest(rs):
        return manifest_of("x", 3, objective="standard", fidelity="full", chunk_size=1, diagnose=True,
                           settings=Settings(catalogs=(), capability=rs))
    old = manifest(RS)
    _check_manifest(old, manifest(RS), tmp_path)
    with pytest.raises(InputError, match="--capability"):
        _check_manifest(old, manifest(RobustSettings(capability=1.0, samples=256)), tmp_path)
    with pytest.raises(InputError, match="--capability"):
        _check_manifest(old, manifest(None), tmp_path)
    _check_manifest({k: v for k, v in manifest(None).items() if k != "capability"}, manifest(None), tmp_path)


def test_bulk_rows_equal_synth_design_capability_on_generated_applications():
    """``synth bulk --capability`` rows (the run's chunk path at the bulk's default fidelity, ``screening``) equal
    ``synth design --capability`` (its default, full fidelity; :func:`synth.optimise.honour.solve_honouring` with
    ``robust=``, ``explain=False`` as the bulk row leaves out the search of the value that would allow a design) on
    generated applications 0-2 (seed 0), at 64 samples on both sides: 0 infeasible (no design passes nominally), 1
    a design meeting the target (the robust search), 2 missing it (no design under the made joint: the bulk's
    shortcut). Every part, the verdict, feasible, the capability verdict, the smallest Ppk and the failing checks.
    Before the 50-row check (``benchmarks/bench_bulk_capability_equality.py``) row 0 named another cone spring of
    equal objective (the screening search's nearest design) and row 2 had no smallest Ppk nor failing checks where
    ``synth design`` prints them."""
    from synth.optimise.honour import solve_honouring
    from synth.robust.synthesis import robust_for
    from synth.scenes.bulk import register
    import argparse
    sub = argparse.ArgumentParser().add_subparsers()
    register(sub)
    bulk_fidelity = sub.choices["bulk"].get_default("fidelity")
    assert bulk_fidelity == "screening"
    rs = RobustSettings(capability=1.33, samples=64)
    apps = generate(3, seed=0)
    rows = compute_chunk([d.as_dict() for d in apps], settings=Settings(fidelity=bulk_fidelity, capability=rs),
                         diagnose=False)
    seen = []
    for d, (_, row) in zip(apps, rows.iterrows()):
        with np.errstate(all="ignore"):  # as the bulk row calls it
            r = solve_honouring(d, "standard", "enumerate", settings=Settings(fidelity="full"), explain=False,
                                robust=robust_for(rs))
        assert {k: row[f"part_{k}"] for k in PART_KEYS} == r.parts
        assert (row["verdict"], bool(row["feasible"])) == (r.verdict, r.feasible)
        found = bool(r.stats.get("robust_found"))
        assert row["capability_verdict"] == ("PASS" if found else "FAIL")
        rob = r.robust or {}
        if rob.get("min_ppk") is None:
            assert math.isnan(row["capability_min_ppk"]) and row["capability_failing"] == ""
        else:
            assert row["capability_min_ppk"] == rob["min_ppk"]
            assert row["capability_failing"] == " ".join(rob["failing"])
        if not found:
            assert row["capability_why"] == r.stats["robust_why"]
        seen.append((r.feasible, found, r.stats["robust_candidates"] > 0, row["capability_min_ppk"]))
    assert [x[:3] for x in seen] == [(False, False, False), (True, True, True), (True, False, False)]
    assert math.isnan(seen[0][3]) and seen[1][3] >= 1.33 > seen[2][3]
