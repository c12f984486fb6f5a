"""Bulk run integrity (issue 14): a lock on the output folder, run ids and checksums on chunks, --resume refusals.

An interrupted, concurrent or corrupted run never reports a result assembled
from another run's chunks. The engine is replaced by a fast fake (same
signature) so that these tests exercise the harness, not the physics.
"""

from __future__ import annotations

import json
import threading

import pandas as pd
import pyarrow as pa
import pyarrow.parquet as pq
import pytest

from synth.bulk.portfolio import write_table
from synth.bulk.run import LOCK, MANIFEST, RunLock, chunk_state, run_portfolio, sidecar
from synth.bulk.sample import sample_portfolio
from synth.cli import main
from synth.errors import InputError


def fake_screen(apps, objective="standard", fidelity="screening", diagnose=True, settings=None):
    from synth.bulk.engine import columns
    rows = []
    for a in apps:
        r = {c: None for c in columns()}
        r.update(feasible=True, status="feasible", margin_min=float(a.working_arm_mm), binding="x", violated="",
                 notes="")
        rows.append(r)
    return pd.DataFrame(rows, columns=list(columns()))


@pytest.fixture
def portfolio(tmp_path):
    return write_table(sample_portfolio(9, seed=3), tmp_path / "p.csv")


def _chunks(out):
    return sorted(sidecar(out).glob("chunk_*.parquet"))


def test_chunks_carry_run_id_rows_and_checksum(tmp_path, portfolio):
    out = tmp_path / "r.csv"
    rep = run_portfolio(portfolio, out, chunk_size=4, screen=fake_screen)
    assert rep.complete and len(rep.run_id) == 32
    manifest = json.loads((sidecar(out) / MANIFEST).read_text())
    assert manifest["run_id"] == rep.run_id
    ranges = [(0, 4), (4, 8), (8, 9)]
    assert len(_chunks(out)) == 3
    for i, p in enumerate(_chunks(out)):
        meta = pq.read_schema(p).metadata
        assert meta[b"synth_run_id"].decode() == rep.run_id and len(meta[b"synth_sha256"]) == 64
        assert meta[b"synth_rows"].decode() == "{}:{}".format(*ranges[i])
        assert chunk_state(sidecar(out), i, *ranges[i], rep.run_id) == "ok"
        assert chunk_state(sidecar(out), i, *ranges[i], "another-run").startswith("written by another run")
        assert chunk_state(sidecar(out), i, 0, 1, rep.run_id).startswith("rows")


def test_resume_refuses_a_chunk_of_another_run(tmp_path, portfolio):
    out, other = tmp_path / "r.csv", tmp_path / "other.csv"
    run_portfolio(portfolio, out, chunk_size=4, screen=fake_screen, stop_after_chunks=1)
    run_portfolio(portfolio, other, chunk_size=4, screen=fake_screen)
    # a chunk of the other (complete) run copied into the interrupted run's folder
    (sidecar(out) / "chunk_00001.parquet").write_bytes((sidecar(other) / "chunk_00001.parquet").read_bytes())
    with pytest.raises(InputError) as err:
        run_portfolio(portfolio, out, chunk_size=4, screen=fake_screen, resume=True)
    (p,) = err.value.problems
    assert p.field == "--resume: chunk_00001.parquet" and "another run" in p.value
    assert not out.exists()  # no result assembled


def test_resume_refuses_a_chunk_with_a_bad_checksum(tmp_path, portfolio):
    out = tmp_path / "r.csv"
    run_portfolio(portfolio, out, chunk_size=4, screen=fake_screen, stop_after_chunks=2)
    p = sidecar(out) / "chunk_00000.parquet"
    table = pq.read_table(p)
    df = table.to_pandas()
    df.loc[0, "margin_min"] = 99.0  # edited content, metadata (run id, checksum) kept
    pq.write_table(pa.Table.from_pandas(df, preserve_index=False).replace_schema_metadata(table.schema.metadata), p)
    with pytest.raises(InputError) as err:
        run_portfolio(portfolio, out, chunk_size=4, screen=fake_screen, resume=True)
    (prob,) = err.value.problems
    assert prob.field == "--resume: chunk_00000.parquet" and "checksum" in prob.value
    # the message tells what to do; deleting the file recomputes it
    p.unlink()
    rep = run_portfolio(portfolio, out, chunk_size=4, screen=fake_screen, resume=True)
    assert rep.complete and rep.reused == 1 and rep.computed == 2
    assert (rep.table["margin_min"] != 99.0).all()


def test_resume_refuses_a_damaged_chunk_and_a_stray_one(tmp_path, portfolio):
    out = tmp_path / "r.csv"
    run_portfolio(portfolio, out, chunk_size=4, screen=fake_screen, stop_after_chunks=1)
    (sidecar(out) / "chunk_00000.parquet").write_bytes(b"PAR1 damaged")
    (sidecar(out) / "chunk_00007.parquet").write_bytes(b"stray")
    with pytest.raises(InputError) as err:
        run_portfolio(portfolio, out, chunk_size=4, screen=fake_screen, resume=True)
    fields = {p.field for p in err.value.problems}
    assert fields == {"--resume: chunk_00000.parquet", "--resume: chunk_00007.parquet"}
    assert "unreadable" in err.value.problems[0].value


def test_resumed_run_keeps_its_id_and_result_equals_a_fresh_run(tmp_path, portfolio):
    out = tmp_path / "r.parquet"
    first = run_portfolio(portfolio, out, chunk_size=2, screen=fake_screen, stop_after_chunks=2)
    second = run_portfolio(portfolio, out, chunk_size=2, screen=fake_screen, resume=True)
    assert second.run_id == first.run_id and second.reused == 2 and second.complete
    fresh = run_portfolio(portfolio, tmp_path / "f.parquet", chunk_size=2, screen=fake_screen)
    assert fresh.run_id != first.run_id
    pd.testing.assert_frame_equal(second.table, fresh.table)


def test_a_second_run_on_the_same_out_is_refused_while_the_first_runs(tmp_path, portfolio):
    out = tmp_path / "r.csv"
    started, release = threading.Event(), threading.Event()

    def slow_screen(apps, **kw):
        started.set()
        release.wait(30)
        return fake_screen(apps, **kw)

    result = {}
    t = threading.Thread(target=lambda: result.setdefault("rep", run_portfolio(portfolio, out, chunk_size=4,
                                                                                screen=slow_screen)))
    t.start()
    try:
        assert started.wait(30)
        with pytest.raises(InputError) as err:
            run_portfolio(portfolio, out, chunk_size=4, screen=fake_screen)
        (p,) = err.value.problems
        assert p.field == "--out" and "no other synth bulk run is writing" in p.accepted and LOCK in p.accepted
        with pytest.raises(InputError):  # a resume is refused too: it would read chunks being written
            run_portfolio(portfolio, out, chunk_size=4, screen=fake_screen, resume=True)
    finally:
        release.set()
        t.join(60)
    rep = result["rep"]
    assert rep.complete and len(rep.table) == 9  # the first run was not disturbed
    # once it ended, the lock is free again (and a killed run frees it too: flock is released by the OS)
    again = run_portfolio(portfolio, out, chunk_size=4, screen=fake_screen)
    assert again.complete and again.run_id != rep.run_id


def test_the_cli_reports_a_held_lock_as_invalid_input(tmp_path, portfolio, capsys):
    out = tmp_path / "r.csv"
    with RunLock(sidecar(out), "a" * 32, out):
        assert main(["bulk", str(portfolio), "--out", str(out), "--no-diagnose"]) == 2
    err = capsys.readouterr().err
    assert "--out" in err and "aaaaaaaaaaaa" in err and "Traceback" not in err


def test_assembly_refuses_a_chunk_replaced_during_the_run(tmp_path, portfolio):
    """A chunk swapped for another run's while the run computes the last one: no result is assembled."""
    out, other = tmp_path / "r.csv", tmp_path / "o.csv"
    run_portfolio(portfolio, other, chunk_size=4, screen=fake_screen)
    calls = {"n": 0}

    def screen(apps, **kw):
        calls["n"] += 1
        if calls["n"] == 3:  # the first two chunks are written: replace chunk 0 behind the run's back
            (sidecar(out) / "chunk_00000.parquet").write_bytes((sidecar(other) / "chunk_00000.parquet").read_bytes())
        return fake_screen(apps, **kw)

    with pytest.raises(InputError) as err:
        run_portfolio(portfolio, out, chunk_size=4, screen=screen)
    assert err.value.problems[0].field == "chunk chunk_00000.parquet" and not out.exists()
