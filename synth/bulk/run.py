"""Run a portfolio through the bulk engine: chunks, resume, progress, in-process or on Dask.

:func:`run_portfolio` reads the portfolio, cuts its rows into chunks of
``chunk_size`` (by input position, so a chunk is the same rows on every
run), and evaluates each chunk with :func:`compute_chunk`: the rows are
validated one by one (a bad row gets its error text and status ``error``),
the valid ones go to :func:`synth.bulk.engine.screen_applications` in one
vectorised call.

Every finished chunk is written at once to ``<RESULT>.chunks/chunk_NNNNN.parquet``
(through :func:`synth.io.outputs.output_file`: a temporary name, then :func:`os.replace`, so a chunk file
is complete or absent, and never written through a link) next to ``manifest.json`` (portfolio hash, objective, fidelity, chunk
size, diagnosis, synth version, catalog hash). ``resume=True`` checks the
manifest against the current settings (a difference is an
:class:`~synth.errors.InputError` naming the setting) and computes only the
chunks without a file. The final RESULT (CSV, Excel or Parquet by extension)
is the input table, in input order, plus the engine's result columns and
``error``; it is assembled from the chunk files, so a fresh and a resumed run
give the same table.

Run integrity. Every run has an id (a random UUID, in the manifest) and
holds a lock on its chunk folder (``run.lock``, an advisory ``flock``
released by the operating system when the process ends, even killed): a
second ``synth bulk`` on the same ``--out`` is refused while the first one
runs, naming the run that holds it. Every chunk file carries, in its Parquet
metadata, the run id, its row range and the SHA-256 of its content.
``--resume`` continues the run of the manifest (its id) and refuses, naming
them, chunk files of another run, with a bad checksum, or unreadable; before
assembling the RESULT every chunk is checked again, so a result is never
assembled from another run's chunks. RESULT is written to a temporary file
and moved into place (:func:`synth.io.outputs.output_file`; removed on any failure).

``engine="dask"`` submits one task per chunk to a ``dask.distributed``
cluster (a :class:`~distributed.LocalCluster` of ``workers`` one-thread
processes, or the scheduler at ``scheduler``) and writes each chunk as it
arrives; the table is the same as in-process. Every chunk, in this process or on
a worker, is computed under the run's one configuration
(:class:`~synth.design.settings.Settings`: fidelity, design rules and spring limit
basis, user catalogs, engine), an argument of the task.
"""


from __future__ import annotations

import json
import math
import time
import uuid
from dataclasses import dataclass, field
from pathlib import Path
from typing import Callable

import pandas as pd

from synth.fingerprint import file_sha256
from synth.bulk.portfolio import column_warnings, field_columns, read_portfolio
from synth.bulk.execution import (DEFAULT_CHUNK_SIZE, compute_chunk, dask_client, dask_pointless, default_chunk_size,
                                  result_columns, run_dask, run_settings, usable_cores)
from synth.bulk.store import (LOCK, MANIFEST, RunLock, assemble, check_manifest, checked_chunks, chunk_path,
                              chunk_ranges, chunk_state, clear_folder, content_sha256, frame_sha256, from_arrow,
                              manifest_of, result_schema, resumable_chunks, sidecar, write_chunk, write_json,
                              write_result)
from synth.errors import InputError, Problem
from synth.io.outputs import output_folder
from synth.progress import Progress
from synth.design.settings import Settings
from synth.optimise.objectives import Objective
from synth.io.limits import check_count
from synth.bulk.portfolio import FORMATS, check_columns

__all__ = ["ENGINES", "FIDELITIES", "DEFAULT_CHUNK_SIZE", "default_chunk_size", "RunReport", "result_columns", "compute_chunk",
           "run_portfolio", "sidecar", "manifest_of", "chunk_ranges", "chunk_state", "RunLock", "usable_cores",
           "dask_pointless", "write_result", "result_schema", "content_sha256", "assemble", "dask_client", "LOCK",
           "MANIFEST"]

ENGINES = ("inprocess", "dask")
from synth.design.evaluate import FIDELITIES  # noqa: E402 - one vocabulary (full, screening, screening-only)


@dataclass
class RunReport:
    """What a run did: chunk counts and timing; the result table (None while incomplete) is read from the chunk
    files when asked for (:attr:`table`, in memory; :meth:`columns` reads only some columns)."""

    out: Path
    n_rows: int
    n_chunks: int
    computed: int
    reused: int
    seconds: float
    engine: str
    complete: bool
    warnings: list = field(default_factory=list)
    rows_computed: int = 0
    total_seconds: float = 0.0
    run_id: str = ""
    _source: tuple | None = field(default=None, repr=False)
    _table: pd.DataFrame | None = field(default=None, repr=False)

    @property
    def table(self) -> pd.DataFrame | None:
        """The whole result table in memory (input columns and result columns), None while incomplete."""
        if self._table is None and self._source is not None:
            table, folder, ranges, run_id = self._source
            self._table = assemble(table, folder, len(ranges), run_id=run_id, ranges=ranges)
        return self._table

    def columns(self, names) -> pd.DataFrame | None:
        """The result table restricted to the columns ``names`` (those present; memory for just them)."""
        if self._source is None:
            return None
        if self._table is not None:
            return self._table[[c for c in names if c in self._table.columns]]
        table, folder, ranges, run_id = self._source
        want = [c for c in result_columns() if c in names]
        res = pd.concat([from_arrow(t, want) for _, _, t in checked_chunks(folder, ranges, run_id)],
                        ignore_index=True) if ranges else pd.DataFrame(columns=want)
        keep = [c for c in names if c in table.columns and c not in res.columns]
        return pd.concat([table[keep].reset_index(drop=True), res], axis=1)

    @property
    def n_errors(self) -> int:
        t = self.columns(["status"])
        return 0 if t is None else int((t["status"] == "error").sum())

    @property
    def apps_per_s(self) -> float:
        """Applications per second over the chunks computed in this run (reused chunks not counted)."""
        return self.rows_computed / self.seconds if self.seconds > 0 else math.inf

    def message(self) -> str:
        state = "complete" if self.complete else "interrupted"
        return (f"{self.n_rows} applications in {self.n_chunks} chunk{'s' if self.n_chunks != 1 else ''}: "
                f"{self.computed} computed, "
                f"{self.reused} reused ({state}, {self.engine}, {self.seconds:.1f} s)")


def _validate_settings(objective, fidelity, chunk_size, engine, workers) -> None:
    Objective.parse(objective)
    if fidelity not in FIDELITIES:
        raise InputError(Problem("--fidelity", fidelity, "one of " + ", ".join(FIDELITIES)))
    if engine not in ENGINES:
        raise InputError(Problem("--engine", engine, "one of " + ", ".join(ENGINES)))
    check_count("--chunk-size", chunk_size)
    if workers is not None:
        check_count("--workers", workers)


def run_portfolio(portfolio, out, *, objective: str = "standard", fidelity: str = "screening",
                  chunk_size: int | None = None, resume: bool = False, engine: str = "inprocess",
                  scheduler: str | None = None, workers: int | None = None, diagnose: bool = True,
                  stop_after_chunks: int | None = None, screen: Callable | None = None,
                  stream=None, connect_timeout_s: float = 20.0, settings: Settings | None = None) -> RunReport:
    """Evaluate every application of ``portfolio`` (a path or a DataFrame) and write ``out``.

    ``stop_after_chunks=k`` stops after ``k`` chunks computed in this run (a
    test hook simulating an interruption: the report has ``complete=False``
    and no RESULT is written). ``screen`` replaces the engine function (same
    signature as :func:`synth.bulk.engine.screen_applications`; on Dask it
    must be picklable). Progress is drawn on ``stream`` (default stderr) when
    it is a terminal. ``connect_timeout_s`` bounds the wait for a ``scheduler``.
    The run holds the lock of ``<out>.chunks`` from start to end (see the module doc). ``settings``: the run's
    configuration (:class:`~synth.design.settings.Settings`: design rules, spring limit basis, user catalogs,
    engine; its fidelity is ``fidelity``), resolved here once and given to every chunk.
    """

    given = chunk_size is not None
    chunk_size = default_chunk_size() if chunk_size is None else chunk_size
    _validate_settings(objective, fidelity, chunk_size, engine, workers)
    settings = run_settings(settings, fidelity).resolved()  # the catalogs fixed: chunks may run elsewhere
    t0 = time.monotonic()
    out = Path(out)
    if out.suffix.lower() not in FORMATS:
        raise InputError(Problem("--out", str(out), "a file ending in " + ", ".join(sorted(FORMATS))))
    if out.is_dir():
        raise InputError(Problem("--out", str(out), "a file name, not a folder"))
    if isinstance(portfolio, pd.DataFrame):
        table = portfolio.reset_index(drop=True)
        check_columns(table, "DataFrame")
        p_hash = frame_sha256(table)
    else:
        table = read_portfolio(portfolio)
        p_hash = file_sha256(Path(portfolio))
    notes = column_warnings(table)
    rcols = result_columns()
    clash = [c for c in table.columns if c in rcols or c == "row"]
    if clash:
        notes.append("input columns replaced by result columns: " + ", ".join(clash))
        table = table.drop(columns=clash)
    n = len(table)
    if not given and engine == "dask":  # at least two chunks per worker, so that every worker has work
        chunk_size = max(1, min(int(chunk_size), -(-n // (2 * int(workers or 2)))))
    ranges = chunk_ranges(n, int(chunk_size))
    folder = output_folder(sidecar(out), "--out", inside=True)  # never a link: chunks, manifest, lock go in it
    manifest = manifest_of(p_hash, n, objective=objective, fidelity=fidelity, chunk_size=int(chunk_size),
                           diagnose=diagnose, settings=settings)
    run_id = uuid.uuid4().hex
    lock = RunLock(folder, run_id, out).acquire()  # before anything in the folder is read or cleared
    try:
        done: list[int] = []
        if resume and (folder / MANIFEST).is_file():
            try:
                old = json.loads((folder / MANIFEST).read_text(encoding="utf-8"))
                if not isinstance(old, dict):
                    raise ValueError
            except (OSError, ValueError):
                raise InputError(Problem("--resume", str(folder / MANIFEST),
                                         "a readable manifest; rerun without --resume")) from None
            if not given and isinstance(old.get("chunk_size"), int) and old["chunk_size"] >= 1:
                # a resume without --chunk-size continues with the interrupted run's chunks (any engine)
                chunk_size = old["chunk_size"]
                ranges = chunk_ranges(n, chunk_size)
                manifest = manifest_of(p_hash, n, objective=objective, fidelity=fidelity, chunk_size=chunk_size,
                                       diagnose=diagnose, settings=settings)
            check_manifest(old, manifest, folder)
            if not isinstance(old.get("run_id"), str) or not old["run_id"]:
                raise InputError(Problem("--resume", str(folder / MANIFEST), "the manifest of a run with a run id "
                                         "(written by an older synth); rerun without --resume"))
            run_id = lock.run_id = old["run_id"]  # the resumed run continues the interrupted one
            done = resumable_chunks(folder, ranges, run_id)
        else:
            if resume:
                notes.append(f"nothing to resume in {folder}: starting from the first chunk")
            clear_folder(folder)
            write_json(folder / MANIFEST, {**manifest, "run_id": run_id})
        todo = [i for i in range(len(ranges)) if i not in set(done)]
        todo_set = set(todo)
        kw = dict(objective=objective, diagnose=diagnose, screen=screen, settings=settings)
        computed = 0
        cols = field_columns(table)

        def chunk_records(k: int) -> pd.DataFrame:  # one chunk's field columns at a time (validated as columns)
            a, b = ranges[k]
            return table.iloc[a:b][cols].reset_index(drop=True)

        def write(k: int, df: pd.DataFrame) -> None:
            write_chunk(folder, k, ranges[k][0], df, run_id)

        with Progress(total=n, desc=f"synth bulk ({engine})", stream=stream) as bar:
            bar.update(sum(ranges[i][1] - ranges[i][0] for i in done), note="reused")
            t_compute = time.monotonic()
            ran = {"engine": engine}

            def inprocess() -> int:
                ran["engine"] = "inprocess"
                done_here = 0
                for i in todo:
                    if stop_after_chunks is not None and done_here >= stop_after_chunks:
                        break
                    write(i, compute_chunk(chunk_records(i), **kw))
                    done_here += 1
                    bar.update(ranges[i][1] - ranges[i][0])
                return done_here
            why = dask_pointless(scheduler, workers, len(todo)) if engine == "dask" else None
            if engine == "inprocess" or why:
                if why:
                    notes.append(why)
                computed = inprocess()
            else:
                computed = run_dask(chunk_records, ranges, todo, write, kw, scheduler, workers, stop_after_chunks,
                                     bar, connect_timeout_s, inprocess, notes)
            seconds = time.monotonic() - t_compute
        complete = all(chunk_path(folder, i).is_file() for i in range(len(ranges)))
        if complete:
            write_result(out, table, folder, ranges, run_id)
        rows_done = sum(b - a for i, (a, b) in enumerate(ranges) if i in todo_set and chunk_path(folder, i).is_file())
    finally:
        lock.release()
    rep = RunReport(out=out, n_rows=n, n_chunks=len(ranges), computed=computed, reused=len(done),
                    seconds=seconds, engine=ran["engine"], complete=complete, warnings=notes, rows_computed=rows_done,
                    total_seconds=time.monotonic() - t0, run_id=run_id)
    if complete:
        rep._source = (table, folder, ranges, run_id)
    return rep
