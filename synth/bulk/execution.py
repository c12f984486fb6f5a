"""Executing a bulk run's chunks: one chunk validated and evaluated (:func:`compute_chunk`, in this process or a Dask
worker), its result columns typed alike whatever the chunking (:func:`typed`), and the chunks on a Dask cluster
(:func:`run_dask`, :func:`dask_client`) or the reason they stay in this process (:func:`dask_pointless`).
"""

from __future__ import annotations

import contextlib
import gc
import logging
import math
import warnings
from typing import Callable

import numpy as np
import pandas as pd

from synth import catalog
from synth.bulk.capability import NUMBERS as CAPABILITY_NUMBERS
from synth.bulk.engine import columns
from synth.bulk.portfolio import validate_record, validate_table
from synth.design.settings import Settings
from synth.errors import DeclarationError, InputError, Problem
from synth.threads import usable_cores, worker_environ

__all__ = ["DEFAULT_CHUNK_SIZE", "default_chunk_size", "result_columns", "result_kind", "run_settings",
           "compute_chunk", "typed", "dask_pointless", "run_dask", "dask_client", "usable_cores"]

#: applications per chunk when the engine's memory constants are absent (see :func:`default_chunk_size`)
DEFAULT_CHUNK_SIZE = 250


def default_chunk_size() -> int:
    """Applications per chunk: the engine's memory budget over its peak memory per application.

    Both are constants of ``catalogs/constants_bulk.csv`` (``bulk_memory_budget_mb``,
    ``bulk_memory_per_application_mb``); :data:`DEFAULT_CHUNK_SIZE` if they are absent.

    >>> default_chunk_size() >= 1
    True
    """
    try:
        return max(1, int(catalog.constant("bulk_memory_budget_mb") / catalog.constant("bulk_memory_per_application_mb")))
    except InputError:
        return DEFAULT_CHUNK_SIZE


def result_columns() -> list[str]:
    """The engine's result columns (:func:`synth.bulk.engine.columns`) followed by ``error``."""
    return list(columns()) + ["error"]


def result_kind(col: str) -> str:
    """How a result column is typed: bool, float, part (object) or text."""
    if col == "feasible":
        return "bool"
    if col.startswith("part_"):
        return "part"
    if col.startswith(("margin_", "objective_")) or col in ("binding_margin", *CAPABILITY_NUMBERS):
        return "float"
    return "text"


def _error_row(cols: list[str], message: str) -> dict:
    row = {}
    for c in cols:
        k = result_kind(c)
        row[c] = False if k == "bool" else (math.nan if k == "float" else (None if k == "part" else ""))
    row["status"], row["error"] = "error", message
    row["notes"] = "not evaluated: input error"
    return row


def _screen_default():
    from synth.bulk.engine import screen_applications
    return screen_applications


def _call_engine(screen, apps, objective, settings, diagnose) -> pd.DataFrame:
    df = screen(apps, objective=objective, fidelity=settings.fidelity, diagnose=diagnose, settings=settings)
    if len(df) != len(apps):
        raise RuntimeError(f"engine returned {len(df)} rows for {len(apps)} applications")
    return df.reset_index(drop=True)


def run_settings(settings: Settings | None, fidelity: str | None) -> Settings:
    """The configuration of a run: ``settings`` (default: no rules, this process's catalogs) at ``fidelity`` when
    given (the bulk's default: ``screening``)."""
    s = settings if settings is not None else Settings(fidelity="screening")
    return s if fidelity is None or fidelity == s.fidelity else s.replace(fidelity=fidelity)


def compute_chunk(recs, *, objective: str = "standard", fidelity: str | None = None,
                  diagnose: bool = True, screen: Callable | None = None,
                  settings: Settings | None = None) -> pd.DataFrame:
    """Validate and evaluate one chunk: one result row per record, in order.

    ``recs``: a table of the chunk's rows (its design-input columns, validated column by column:
    :func:`synth.bulk.portfolio.validate_table`) or a list of design-input records (validated one by one).
    Valid rows go to the engine in one call; a row that fails validation gets ``status = "error"`` and its
    problems in ``error``. If the engine raises on the chunk, the chunk is evaluated one application at a
    time and only the failing ones get ``error = "engine: ..."``: one bad row never stops a portfolio.
    ``settings``: the run's configuration (:class:`~synth.design.settings.Settings`: the design rules and spring
    limit basis every row is judged by, the user catalog folders read here, in a Dask worker process too);
    ``fidelity`` (default ``screening``) sets its fidelity.
    """
    settings = run_settings(settings, fidelity)
    with catalog.using(settings.catalogs):
        return _compute_chunk(recs, objective, diagnose, screen, settings)


def _compute_chunk(recs, objective, diagnose, screen, settings) -> pd.DataFrame:
    screen = screen or _screen_default()
    cols = result_columns()
    if isinstance(recs, pd.DataFrame):
        checked, errors = validate_table(recs)
    else:
        pairs = [validate_record(r) for r in recs]
        checked, errors = [a for a, _ in pairs], [e for _, e in pairs]
    n = len(checked)
    valid = [i for i, a in enumerate(checked) if a is not None]
    apps = [checked[i] for i in valid]
    res = None
    try:
        res = _call_engine(screen, apps, objective, settings, diagnose)
    except (InputError, DeclarationError):
        raise  # a bad setting (objective...) or declaration (a check): the same for every row, reported once
    except Exception:
        rows = []
        for a in apps:
            try:
                rows.append({**_call_engine(screen, [a], objective, settings, diagnose).iloc[0].to_dict(),
                             "error": ""})
            except Exception as exc:  # noqa: BLE001 - reported in the row, never swallowed
                rows.append(_error_row(cols, f"engine: {type(exc).__name__}: {exc}"))
        res = pd.DataFrame(rows, columns=cols)
    err, out = _error_row(cols, ""), {}
    for c in cols:  # the engine's rows where valid, an input-error row's cells elsewhere
        col = np.empty(n, dtype=object)
        col[:] = errors if c == "error" else [err[c]] * n
        if valid:
            col[valid] = res[c].to_numpy(dtype=object) if c in res.columns else ""
        out[c] = pd.Series(col, dtype=object)
    return typed(pd.DataFrame(out, columns=cols))


def typed(df: pd.DataFrame) -> pd.DataFrame:
    """Result columns with fixed types whatever the chunking: bool, float, object parts (None), text (column by
    column, no Python object per cell)."""
    out = {}
    for c in df.columns:
        k, col = result_kind(c), df[c]
        if k == "bool":
            out[c] = col.fillna(False).astype(bool).to_numpy()
        elif k == "float":
            out[c] = pd.to_numeric(col, errors="coerce").astype(float).to_numpy()
        elif k == "part":
            v = np.array(col.to_numpy(dtype=object), dtype=object, copy=True)
            v[pd.isna(v)] = None
            out[c] = pd.Series(v, index=df.index, dtype=object)
        else:
            v = np.array(col.to_numpy(dtype=object), dtype=object, copy=True)
            v[pd.isna(v)] = ""
            out[c] = pd.Series(pd.Series(v).astype(str).to_numpy(dtype=object), index=df.index, dtype=object)
    return pd.DataFrame(out, index=df.index, columns=list(df.columns))

def dask_pointless(scheduler: str | None, workers: int | None, tasks: int, threads: int | None = None) -> str | None:
    """Why ``--engine dask`` would not help (the note saying the work runs in this process instead), or None.

    The in-process engine computes a chunk on one core: Dask helps only with more cores than that, and more
    than one chunk to share among them. A local cluster runs on this machine's usable cores
    (:func:`usable_cores`), whatever ``--workers`` asks; a scheduler's cluster has its workers' threads
    (``threads``, known once connected).

    >>> dask_pointless(None, 2, 1).startswith("--engine dask: 1 chunk")
    True
    """
    if tasks <= 1:
        return f"--engine dask: {tasks} chunk to compute, nothing to share among workers: computed in this process"
    if scheduler:
        if threads is not None and threads <= 1:
            return (f"--engine dask: the cluster at {scheduler} has {threads} thread, no more cores than this "
                    "process: computed in this process")
        return None
    cores = min(int(workers or 2), usable_cores())
    if cores <= 1:
        return (f"--engine dask: a local cluster of {int(workers or 2)} worker(s) on {usable_cores()} usable core(s) "
                "has no more cores than this process: computed in this process")
    return None


def run_dask(chunk_records, ranges, todo, write, kw, scheduler, workers, stop_after_chunks, bar,
              connect_timeout_s: float = 20.0, inprocess=None, notes: list | None = None) -> int:
    """Compute chunks ``todo`` on Dask, writing each (``write(k, df)``) as it completes; returns how many were written.
    A scheduler's cluster with no more than one thread computes in this process instead (``inprocess()``, and a
    note in ``notes``)."""
    try:
        from dask.distributed import as_completed
    except ImportError:  # pragma: no cover - dask[distributed] is a dependency
        raise InputError(Problem("--engine", "dask", "an installation with dask[distributed] (pip install 'dask[distributed]')")) from None
    if not todo:
        return 0
    computed = 0
    with dask_client(scheduler, workers, connect_timeout_s) as client:
        # a bounded number of chunks in flight: the records of a huge portfolio are not all shipped at once
        nthreads = sum(client.nthreads().values()) or 1
        why = dask_pointless(scheduler, workers, len(todo), nthreads) if inprocess is not None else None
        if why:
            if notes is not None:
                notes.append(why)
            return inprocess()
        in_flight = max(2 * nthreads, 2)
        pending = list(todo)
        futures: dict = {}

        def submit(k: int):
            fut = client.submit(compute_chunk, chunk_records(k), pure=False, **kw)
            futures[fut] = k
            return fut

        queue = as_completed([submit(pending.pop(0)) for _ in range(min(in_flight, len(pending)))])
        try:
            for fut in queue:
                i = futures.pop(fut)
                a, b = ranges[i]
                write(i, fut.result())
                computed += 1
                bar.update(b - a)
                if stop_after_chunks is not None and computed >= stop_after_chunks:
                    break
                if pending:
                    queue.add(submit(pending.pop(0)))
        finally:
            for fut in futures:
                if not fut.done():
                    fut.cancel()
    return computed


@contextlib.contextmanager
def dask_client(scheduler: str | None, workers: int | None, connect_timeout_s: float = 20.0):
    """A Dask client: of the scheduler at ``scheduler``, or of a local cluster of ``workers`` one-thread processes
    (the one way bulk and the platform producer start Dask). Logs silenced for the span of the run.

    distributed starts its workers with ``MALLOC_TRIM_THRESHOLD_=65536``: glibc then returns every large numpy
    temporary to the system and faults it back in, and the group functions (arrays of 10^5 rows) run 3-4x
    slower than in a plain process (measured by the platform producer); the local workers keep glibc's default.
    Their BLAS and numba pools are those of one-thread processes (:func:`synth.threads.worker_environ`).
    """
    import dask
    from dask.distributed import Client, LocalCluster
    with _quiet_dask(), contextlib.ExitStack() as stack, warnings.catch_warnings(), \
            dask.config.set({"distributed.nanny.pre-spawn-environ.MALLOC_TRIM_THRESHOLD_": None}):
        warnings.filterwarnings("ignore", message="Port .* is already in use")
        if scheduler:
            try:
                client = stack.enter_context(Client(scheduler, timeout=f"{connect_timeout_s}s"))
            except (OSError, TimeoutError, ValueError) as exc:  # unreachable, or not an address ("tcp://", "foo")
                raise InputError(Problem("--scheduler", scheduler,
                                         f"the address of a running Dask scheduler ({exc})")) from None
        else:
            cluster = stack.enter_context(LocalCluster(n_workers=int(workers or 2), threads_per_worker=1,
                                                       processes=True, dashboard_address=None, env=worker_environ(1),
                                                       silence_logs=logging.CRITICAL))
            client = stack.enter_context(Client(cluster))
        yield client


@contextlib.contextmanager
def _quiet_dask():
    """Silence distributed's shutdown chatter (log lines, resource warnings) for the span of a run."""
    loggers = [logging.getLogger(n) for n in ("distributed", "distributed.nanny", "distributed.worker",
                                              "distributed.scheduler", "distributed.core", "tornado")]
    levels = [lg.level for lg in loggers]
    for lg in loggers:
        lg.setLevel(logging.CRITICAL)
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", ResourceWarning)
            warnings.simplefilter("ignore", DeprecationWarning)
            try:
                yield
            finally:
                # a failed connection leaves never-awaited coroutines: collect them now, while their
                # RuntimeWarning is silenced, not later in the middle of unrelated code
                warnings.simplefilter("ignore", RuntimeWarning)
                gc.collect()
    finally:
        for lg, lv in zip(loggers, levels):
            lg.setLevel(lv)
