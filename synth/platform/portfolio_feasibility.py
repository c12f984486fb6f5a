"""Where ``synth rationalise`` gets its feasibility data: a portfolio read, split into chunks, run, gathered.

``PORTFOLIO`` is a portfolio table (``.csv``, ``.xlsx``, ``.ods``, ``.parquet``: the
table ``synth bulk`` reads, :mod:`synth.bulk.portfolio`) or ``synthetic:N[:SEED]``
(:func:`synth.platform.synthetic.synthetic_portfolio`, illustrative data).

:func:`from_table` reads and validates the table row by row (a bad row is reported, never evaluated);
:func:`feasibility` splits the valid inputs into chunks of :data:`CHUNK_SIZE`, has each chunk's feasible pairs
computed by :func:`synth.platform.producer.chunk_feasibility` (in this process, on forked processes, or on Dask)
and gathers them in order into one :class:`~synth.platform.data.PortfolioFeasibility`. ``engine="dask"`` computes the chunks on a ``dask.distributed`` cluster (a local one of
``workers`` processes, or ``scheduler``), the pattern of :mod:`synth.bulk.run`; the data
are the same as in-process: every chunk is given the run's configuration
(:class:`~synth.design.settings.Settings`: the design rules, the spring limit basis, the user catalogs, the engine).

>>> from synth.data.generated_applications import generate
>>> pf = feasibility(generate(3, seed=0), ["a", "b", "c"])
>>> [a.app_id for a in pf.apps], sorted(pf.options)
(['a', 'b', 'c'], ['axial', 'bolt', 'bushing', 'spring'])
>>> load_feasibility("synthetic:many")
Traceback (most recent call last):
...
synth.errors.InputError: PORTFOLIO: got 'synthetic:many'; accepted: synthetic:N[:SEED] with whole numbers N >= 1, SEED >= 0, or a portfolio table (.csv, .ods, .parquet, .pq, .xlsm, .xlsx)
"""

from __future__ import annotations

import math
import time
from pathlib import Path

import numpy as np

from synth import catalog
from synth.bulk.portfolio import FORMATS, read_portfolio, records, validate_record
from synth.bulk.run import ENGINES, chunk_ranges, dask_client, dask_pointless
from synth.design import evaluate
from synth.design.space import SUBSYSTEMS
from synth.errors import InputError, Problem
from synth.platform.data import AppFeasibility, PortfolioFeasibility, default_fixed_costs, validate
from synth.platform.options import Catalogue, catalogue
from synth.platform.producer import chunk_feasibility
from synth.platform.synthetic import synthetic_portfolio

__all__ = ["load_feasibility", "feasibility", "from_table", "VOLUME_COLUMNS", "CHUNK_SIZE", "PROCESSES",
           "PRODUCER", "processes_for"]

#: portfolio columns read as the annual volume of an application (weights its unit cost; 1 when absent)
VOLUME_COLUMNS = ("annual_volume", "volume")
#: applications per chunk (one vectorised evaluation; the unit of work on Dask and of the forked processes)
CHUNK_SIZE = 250
#: the processes the in-process engine shares the chunks among by default (``feasibility(processes=...)``): one.
#: Measured on the 2-core development machine under its usual load (load average 7), 500 applications on two
#: forked processes took 1.3-1.9x the wall time and 1.3x the CPU seconds of one process (issue 36): where the
#: cores are busy, a second process only competes with the first. On an idle machine ask for 2.
PROCESSES = 1


def _error_app(app_id: str, error: str, cat: Catalogue, volume: float) -> AppFeasibility:
    z = np.zeros(0, np.int64)
    return AppFeasibility(app_id=app_id, core_parts={f: z for f in cat.core_codes}, core_cost_eur=np.zeros(0),
                          core_margin=np.zeros(0), group={s: z for s in SUBSYSTEMS}, feasible={s: [] for s in SUBSYSTEMS},
                          option_margin={s: [] for s in SUBSYSTEMS}, volume=volume, note=f"input error: {error}",
                          core_rows=z)


def feasibility(inputs: list, ids: list | None = None, volumes=None, settings: evaluate.Settings = evaluate.DEFAULT, *,
                errors: list | None = None, diagnose: bool = False, chunk_size: int = CHUNK_SIZE,
                engine: str = "inprocess", workers: int | None = None, scheduler: str | None = None,
                progress=None, processes: int | None = None) -> PortfolioFeasibility:
    """The :class:`~synth.platform.data.PortfolioFeasibility` of validated design inputs.

    ``inputs[i]`` may be None when ``errors[i]`` says why (a row that failed validation: it is
    reported, never evaluated). ``volumes``: units per year (1 each by default). ``engine``:
    ``inprocess`` or ``dask`` (see the module docstring). ``progress(done, total)`` is called
    after each chunk. ``settings``: the configuration every chunk is evaluated under (shipped with it to a Dask
    worker). ``processes``: with ``inprocess``, the forked processes the chunks are shared among (None:
    :data:`PROCESSES`, one; at most the usable cores; the data do not depend on it).
    """
    if engine not in ENGINES:
        raise InputError(Problem("--engine", engine, " or ".join(ENGINES)))
    if not (isinstance(chunk_size, (int, np.integer)) and chunk_size >= 1):
        raise InputError(Problem("chunk size", chunk_size, "a whole number >= 1"))
    settings = settings.resolved()  # the user catalogs fixed: a chunk may run in another process
    with catalog.using(settings.catalogs):
        return _feasibility(inputs, ids, volumes, settings, errors, diagnose, chunk_size, engine, workers, scheduler,
                            progress, processes)


def _feasibility(inputs, ids, volumes, settings, errors, diagnose, chunk_size, engine, workers, scheduler,
                 progress, processes=None) -> PortfolioFeasibility:
    t0 = time.perf_counter()
    n = len(inputs)
    ids = [f"row {i + 1}" for i in range(n)] if ids is None else [str(x) for x in ids]
    volumes = np.ones(n) if volumes is None else np.asarray(volumes, dtype=float)
    errors = errors or [""] * n
    cat = catalogue()
    valid = [i for i in range(n) if inputs[i] is not None]
    if engine == "dask" and not scheduler:   # at least one chunk per local worker
        chunk_size = max(1, min(int(chunk_size), -(-len(valid) // int(workers or 2))))
    ranges = chunk_ranges(len(valid), int(chunk_size))
    kw = dict(diagnose=diagnose)
    jobs = [([inputs[i] for i in valid[lo:hi]], [ids[i] for i in valid[lo:hi]], volumes[valid[lo:hi]])
            for lo, hi in ranges]
    run_notes: list = []
    results = _run_chunks(jobs, settings, kw, engine, workers, scheduler, progress, run_notes, processes)
    stats = {"engine": "inprocess" if run_notes else engine, "chunks": len(ranges)}
    for _, st in results:
        for k, v in st.items():
            stats[k] = stats.get(k, 0) + v
    results = [res for res, _ in results]
    apps: list = [None] * n
    for (lo, hi), res in zip(ranges, results):
        for i, af in zip(valid[lo:hi], res):
            apps[i] = af
    for i in range(n):
        if apps[i] is None:
            apps[i] = _error_app(ids[i], errors[i] or "not a valid design input", cat, float(volumes[i]))
    fixed = default_fixed_costs(cat.pf_parts)
    pf = PortfolioFeasibility(
        apps=apps, parts=cat.pf_parts, part_cost_eur=fixed, options=cat.options,
        option_cost_eur={s: (cat.option_cost_eur[s] if s != "spring" else np.zeros(cat.n_options(s)))
                         for s in SUBSYSTEMS},
        notes=[f"feasibility from the evaluator (synth.design.evaluate, fidelity {settings.fidelity}); "
               "per-variant fixed costs: illustrative constants (catalogs/constants_platform.csv)"] + run_notes,
        design_inputs=list(inputs), settings=settings, catalogue=cat,
        stats={"feasibility_s": time.perf_counter() - t0, **stats})
    return validate(pf)


def _chunk_job(inputs, ids, volumes, settings, **kw) -> tuple:
    """One chunk and its statistics (what a Dask task returns)."""
    stats: dict = {}
    return chunk_feasibility(inputs, ids, volumes, settings, stats=stats, **kw), stats


def processes_for(n_jobs: int, processes: int | None = None) -> int:
    """The processes the in-process engine computes ``n_jobs`` chunks on: ``processes`` (None:
    :data:`PROCESSES`), never more than the chunks nor the usable cores (:func:`synth.threads.usable_cores`); 1
    where this process cannot fork (another platform than POSIX, or a daemonic process such as a pool's worker)."""
    import multiprocessing as mp
    from synth import threads
    if n_jobs < 2 or "fork" not in mp.get_all_start_methods() or mp.current_process().daemon:
        return 1
    asked = PROCESSES if processes is None else int(processes)
    return max(1, min(asked, n_jobs, threads.usable_cores()))


def _forked_pool(processes: int):
    """A pool of ``processes`` forked workers (they inherit the loaded catalogs and compiled kernels: no import,
    no compilation), or a null context giving None for one process."""
    from contextlib import nullcontext
    if processes < 2:
        return nullcontext()
    import multiprocessing as mp
    return mp.get_context("fork").Pool(processes)


def _chunk_star(job) -> tuple:
    inp, ids, vol, settings, kw = job
    with catalog.using(settings.catalogs):
        return _chunk_job(inp, ids, vol, settings, **kw)


def _run_chunks(jobs, settings, kw, engine, workers, scheduler, progress, notes: list | None = None,
                processes: int | None = None) -> list:
    """The chunks' results in order, in this process or on Dask (where Dask cannot help, in this process, and
    ``notes`` says why: :func:`synth.bulk.run.dask_pointless`). In process, the chunks go to ``processes`` forked
    workers (:func:`_processes`: one by default, :data:`PROCESSES`); each chunk is computed as in one process, and
    the results are taken in the chunks' order, so the data are the same whatever the count."""
    total = sum(len(j[0]) for j in jobs)
    why = dask_pointless(scheduler, workers, len(jobs)) if engine == "dask" else None
    if why and notes is not None:
        notes.append(why)
    if engine == "inprocess" or why:
        out, done = [], 0
        procs = processes_for(len(jobs), processes)
        with _forked_pool(procs) as pool:
            results = (pool.imap(_chunk_star, [(*job, settings, kw) for job in jobs]) if pool is not None
                       else (_chunk_job(inp, ids, vol, settings, **kw) for inp, ids, vol in jobs))
            for (inp, _, _), res in zip(jobs, results):   # in order: the same data as one process computes
                out.append(res)
                done += len(inp)
                if progress:
                    progress(done, total)
        return out
    try:
        from dask.distributed import as_completed
    except ImportError:  # pragma: no cover - dask[distributed] is a dependency
        raise InputError(Problem("--engine", "dask", "an installation with dask[distributed]")) from None
    out: list = [None] * len(jobs)
    with dask_client(scheduler, workers) as client:
        futures = {client.submit(_chunk_job, inp, ids, vol, settings, pure=False, **kw): j
                   for j, (inp, ids, vol) in enumerate(jobs)}
        done = 0
        for fut in as_completed(list(futures)):
            j = futures[fut]
            out[j] = fut.result()
            done += len(jobs[j][0])
            if progress:
                progress(done, total)
    return out


def _volumes(table, n: int):
    # an empty column is no column (the design input's field annual_volume, left empty: synth.schema)
    col = next((c for c in VOLUME_COLUMNS if c in table.columns and table[c].notna().any()), None)
    if col is None:
        return np.ones(n), None
    probs, vol = [], np.ones(n)
    for i, v in enumerate(table[col].tolist()):
        try:
            x = float(v)
        except (TypeError, ValueError):
            x = math.nan
        if not (math.isfinite(x) and x >= 0):
            probs.append(Problem(f"{col} (row {i + 1})", v, "a number of units per year >= 0"))
        vol[i] = x
    if probs:
        raise InputError(probs)
    return vol, col


def from_table(portfolio, settings: evaluate.Settings = evaluate.DEFAULT, **kw) -> PortfolioFeasibility:
    """Feasibility of a portfolio table (a path or a DataFrame, :mod:`synth.bulk.portfolio`).

    Rows are validated one by one; a bad row is reported (``note``: ``input error: ...``) and
    never stops the others. Ids: the ``application_id`` column, else ``row N``; volumes: the
    first of :data:`VOLUME_COLUMNS` present (else 1 per application, and the cost objective
    weighs every application alike).
    """
    import pandas as pd
    table = portfolio.reset_index(drop=True) if isinstance(portfolio, pd.DataFrame) else read_portfolio(portfolio)
    checked = [validate_record(r) for r in records(table)]
    n = len(checked)
    ids = ([str(x) for x in table["application_id"]] if "application_id" in table.columns
           else [f"row {i + 1}" for i in range(n)])
    volumes, col = _volumes(table, n)
    pf = feasibility([d for d, _ in checked], ids, volumes, settings, errors=[e for _, e in checked], **kw)
    pf.volumes_given = col is not None
    pf.notes.append(f"volumes: column {col}" if col else
                    "volumes: no annual_volume column, every application counts 1 unit")
    return pf


def load_feasibility(portfolio: str, settings: evaluate.Settings | None = None, **kw) -> PortfolioFeasibility:
    """The feasibility data of ``portfolio`` (see the module docstring), validated. A design rule the platform
    cannot honour is refused, never dropped: any rule (a capability target included) on ``synthetic:`` data
    (illustrative feasibility, not judged by the evaluator). Capability targets are honoured on the assigned designs
    (:mod:`synth.platform.capable`), not here: the options are judged at their nominal values."""
    rules = getattr(settings, "rules", None)
    named = f"design rules ({rules.source or rules.name})" if rules is not None and (rules.source or rules.name) \
        else "design rules"
    if rules is not None and not rules.empty() and str(portfolio).startswith("synthetic:"):
        raise InputError(Problem(named, str(portfolio),
                                 "a portfolio table: synthetic:N data are illustrative feasibility, not judged by "
                                 "the evaluator, its rules or a capability target"))
    rs = getattr(settings, "capability", None)
    if rules is not None and rules.capability and rs is None:  # a target would stay behind: never dropped
        raise InputError(Problem(f"{named}: capability", dict(rules.capability),
                                 "targets carried in the settings (Settings(capability=...): synth rationalise and "
                                 "the web page read them from the rules, synth.platform.capable.rules_capability), "
                                 "which every assigned design then meets (synth.platform.capable.choose)"))
    if rs is not None and str(portfolio).startswith("synthetic:"):
        raise InputError(Problem("--capability", rs.targets(),
                                 "a portfolio table: synthetic:N data are illustrative feasibility, with no designs "
                                 "whose production capability could be evaluated"))
    if str(portfolio).startswith("synthetic:"):
        parts = str(portfolio).split(":")[1:]
        try:
            n, seed = int(parts[0]), int(parts[1]) if len(parts) > 1 else 0
        except (ValueError, IndexError):
            n, seed = -1, -1
        if len(parts) > 2 or n < 1 or seed < 0:
            raise InputError(Problem("PORTFOLIO", portfolio, "synthetic:N[:SEED] with whole numbers N >= 1, SEED >= 0, "
                                     "or a portfolio table (" + ", ".join(sorted(FORMATS)) + ")"))
        return validate(synthetic_portfolio(n, seed=seed))
    if Path(str(portfolio)).suffix.lower() not in FORMATS:
        raise InputError(Problem("PORTFOLIO", portfolio, "synthetic:N[:SEED] with whole numbers N >= 1, SEED >= 0, "
                                 "or a portfolio table (" + ", ".join(sorted(FORMATS)) + ")"))
    return PRODUCER(portfolio, settings or evaluate.DEFAULT, **kw)


#: ``(portfolio path, settings, **kw) -> PortfolioFeasibility``: the evaluator's producer
PRODUCER = from_table
