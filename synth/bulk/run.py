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

import contextlib
import errno
import gc
import hashlib
import json
import logging
import math
import os
import socket
import time
import uuid
import warnings
from dataclasses import dataclass, field
from pathlib import Path
from typing import Callable

import numpy as np
import pandas as pd

from synth import catalog
from synth.version import __version__
from synth.fingerprint import file_sha256, catalogs_sha256
from synth.bulk.portfolio import (CSV_FLOAT, arrow_safe, column_warnings, field_columns, read_portfolio,
                                  validate_record, validate_table, write_table)
from synth.bulk.capability import NUMBERS as CAPABILITY_NUMBERS
from synth.errors import InputError, Problem
from synth.threads import usable_cores, worker_environ
from synth.io.outputs import csv_rows, output_file, output_folder, write_text
from synth.progress import Progress
from synth.bulk.engine import columns
from synth.design.rules import echo
from synth.design.settings import Settings
from synth.optimise.objectives import Objective
from synth.io.limits import check_count
from synth.bulk.portfolio import FORMATS, check_columns

__all__ = ["ENGINES", "FIDELITIES", "DEFAULT_CHUNK_SIZE", "default_chunk_size", "RunReport", "result_columns", "compute_chunk",
           "run_portfolio", "sidecar", "manifest_of", "chunk_ranges", "chunk_state", "RunLock", "usable_cores",
           "dask_pointless", "write_result", "result_schema", "content_sha256"]

ENGINES = ("inprocess", "dask")
from synth.design.evaluate import FIDELITIES  # noqa: E402 - one vocabulary (full, screening, screening-only)
#: applications per chunk when the engine's memory constants are absent (see :func:`default_chunk_size`)
DEFAULT_CHUNK_SIZE = 250
MANIFEST = "manifest.json"
LOCK = "run.lock"
_MANIFEST_KEYS = ("portfolio_sha256", "n_rows", "objective", "fidelity", "chunk_size", "diagnose",
                  "synth_version", "catalogs_sha256", "rules", "capability")


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


def _kind(col: str) -> str:
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
        k = _kind(c)
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


def _run_settings(settings: Settings | None, fidelity: str | None) -> Settings:
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
    settings = _run_settings(settings, fidelity)
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
    except InputError:
        raise  # a bad setting (objective...): the same for every row, reported once
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
    return _typed(pd.DataFrame(out, columns=cols))


def _typed(df: pd.DataFrame) -> pd.DataFrame:
    """Result columns with fixed types whatever the chunking: bool, float, object parts (None), text (column by
    column, no Python object per cell)."""
    out = {}
    for c in df.columns:
        k, col = _kind(c), df[c]
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


def chunk_ranges(n: int, chunk_size: int) -> list[tuple[int, int]]:
    """``[(start, stop)]`` of the chunks of ``n`` rows.

    >>> chunk_ranges(5, 2)
    [(0, 2), (2, 4), (4, 5)]
    """
    return [(s, min(s + chunk_size, n)) for s in range(0, n, chunk_size)]


def sidecar(out) -> Path:
    """The folder of chunk files and manifest of result ``out``: ``<out>.chunks``."""
    p = Path(out)
    return p.with_name(p.name + ".chunks")


def _chunk_path(folder: Path, i: int) -> Path:
    return folder / f"chunk_{i:05d}.parquet"


def _sha256_frame(df: pd.DataFrame) -> str:
    h = hashlib.sha256("\x1f".join(map(str, df.columns)).encode())
    h.update(pd.util.hash_pandas_object(df.astype(str), index=True).values.tobytes())
    return h.hexdigest()


def _catalogs_sha256(settings: Settings | None = None) -> str:
    """Hash of every catalog CSV in use (built-in and the user folders of ``settings``, default this process's): a
    changed catalog invalidates a resume."""
    dirs = None if settings is None else settings.catalogs
    return catalogs_sha256(catalog.user_dirs() if dirs is None else [Path(p) for p in dirs])


def manifest_of(portfolio_hash: str, n_rows: int, *, objective: str, fidelity: str, chunk_size: int,
                diagnose: bool, settings: Settings | None = None) -> dict:
    """The manifest of a run: what must not change between an interrupted run and its resume (the configuration's
    design rules included: :func:`synth.design.rules.echo`, and its catalogs' hash)."""
    s = settings if settings is not None else Settings()
    return {"portfolio_sha256": portfolio_hash, "n_rows": int(n_rows), "objective": str(objective),
            "fidelity": str(fidelity), "chunk_size": int(chunk_size), "diagnose": bool(diagnose),
            "synth_version": __version__, "catalogs_sha256": _catalogs_sha256(s), "rules": echo(s.rules),
            "capability": _capability_echo(s.capability)}


def _capability_echo(rs) -> str:
    """The capability target and estimator of a run (``--capability``/``--ppm``, samples, seed, method), or ""."""
    if rs is None:
        return ""
    return f"{rs.targets()}; {rs.samples} samples, seed {rs.seed}"


def _check_manifest(old: dict, new: dict, folder: Path) -> None:
    labels = {"portfolio_sha256": "the portfolio file (its content changed)", "n_rows": "the number of rows",
              "objective": "--objective", "fidelity": "--fidelity", "chunk_size": "--chunk-size",
              "diagnose": "--no-diagnose", "synth_version": "the synth version",
              "catalogs_sha256": "the catalogs (a CSV or --catalogs folder changed)",
              "rules": "the design rules (--rules)",
              "capability": "the capability target (--capability, --ppm, --samples, --seed, --capability-method)"}
    problems = []
    for k in _MANIFEST_KEYS:
        if k == "rules":  # by content: the same rules in a renamed or copied file are the same rules
            changes = _rules_changes(old.get(k) or {}, new[k] or {})
            if changes:
                problems.append(Problem(f"--resume: {labels[k]}", _rules_name(new[k]),
                                        f"{_rules_name(old.get(k))!r} as in the interrupted run "
                                        f"({folder / MANIFEST}), by content; they differ: {'; '.join(changes)}; "
                                        "give the run's rules, or rerun without --resume to start again"))
            continue
        if old.get(k, "" if k == "capability" else None) != new[k]:  # a run before the target's key: none
            shown_old = old.get(k) if not k.endswith("sha256") else str(old.get(k))[:12]
            shown_new = new[k] if not k.endswith("sha256") else new[k][:12]
            problems.append(Problem(f"--resume: {labels[k]}", shown_new,
                                    f"{shown_old!r} as in the interrupted run ({folder / MANIFEST}); "
                                    "rerun without --resume to start again"))
    if problems:
        raise InputError(problems)


#: what of a set of design rules judges a design (its name and source file are labels: a copy of the rules file
#: under another name judges every row the same)
_RULES_CONTENT = ("limits", "min_margins", "spring_limit_basis", "capability")


def _rules_changes(old: dict, new: dict) -> list[str]:
    """What differs between two manifests' design rules, by content (``min_margins.spring_yield 1 % in the run,
    2 % now``); [] when they judge alike."""
    def flat(rules: dict) -> dict:
        out = {}
        for k in _RULES_CONTENT:
            v = rules.get(k, "thesis" if k == "spring_limit_basis" else {})
            if isinstance(v, dict):
                out.update({f"{k}.{kk}": vv for kk, vv in v.items()})
            else:
                out[k] = v
        return out

    def shown(key: str, v) -> str:
        if v is None:
            return "not set"
        return f"{100 * v:g} %" if key.startswith("min_margins.") and isinstance(v, (int, float)) else f"{v}"
    a, b = flat(old), flat(new)
    return [f"{k} {shown(k, a.get(k))} in the run, {shown(k, b.get(k))} now"
            for k in sorted(set(a) | set(b)) if a.get(k) != b.get(k)]


def _rules_name(rules) -> str:
    if not rules:
        return "no design rules"
    return rules.get("name") or "unnamed design rules"


def _write_atomic_json(path: Path, data: dict) -> None:
    write_text(path, json.dumps(data, indent=2), "--out")


def _part_is_number(key: str) -> bool:
    """A part key with a number for value (a dimension or a ratio, by its unit suffix); the others are names."""
    return key.endswith(("_mm", "_ratio"))


def result_schema():
    """The Arrow schema of a chunk file: ``row`` then :func:`result_columns`, typed by kind (one schema for every
    chunk, so that chunk files are streamed into one Parquet result)."""
    import pyarrow as pa
    fields = [pa.field("row", pa.int64())]
    for c in result_columns():
        k = _kind(c)
        t = (pa.bool_() if k == "bool" else pa.float64() if k == "float" else
             pa.float64() if k == "part" and _part_is_number(c[len("part_"):]) else pa.string())
        fields.append(pa.field(c, t))
    return pa.schema(fields)


def _to_arrow(df: pd.DataFrame, start: int):
    """A chunk's typed result rows (:func:`_typed`) as an Arrow table of :func:`result_schema`."""
    import pyarrow as pa
    fields = [pa.field("row", pa.int64())]
    arrays = [pa.array(np.arange(start, start + len(df), dtype=np.int64))]
    for f in list(result_schema())[1:]:
        col = df[f.name]
        if pa.types.is_string(f.type):
            arr = pa.array(col.to_numpy(dtype=object), type=pa.string(), from_pandas=True)
        else:
            try:
                arr = pa.array(col.to_numpy(dtype=object) if col.dtype == object else col.to_numpy(), type=f.type,
                               from_pandas=True)
            except (pa.ArrowInvalid, pa.ArrowTypeError):  # not numbers (another engine's parts): their text
                arr = pa.array([None if v is None else str(v) for v in col], type=pa.string())
        fields.append(pa.field(f.name, arr.type))
        arrays.append(arr)
    return pa.Table.from_arrays(arrays, schema=pa.schema(fields))


def _from_arrow(table, columns=None) -> pd.DataFrame:
    """The result columns (or ``columns`` of them) of a chunk table as :func:`_typed` gives them (parts: None where
    empty; text: "")."""
    import pyarrow.compute as pc
    out = {}
    columns = result_columns() if columns is None else list(columns)
    for c in columns:
        col, k = table.column(c), _kind(c)
        if k == "bool":
            out[c] = pc.fill_null(col, False).to_numpy()
        elif k == "float":
            out[c] = col.to_numpy()
        elif k == "part":
            v = np.array(col.to_numpy(zero_copy_only=False), dtype=object, copy=True)
            v[pd.isna(v)] = None
            out[c] = pd.Series(v, dtype=object)
        else:
            out[c] = pd.Series(pc.fill_null(col, "").to_numpy(zero_copy_only=False), dtype=object)
    return pd.DataFrame(out, columns=columns)


def content_sha256(table) -> str:
    """SHA-256 of a chunk's content from its Arrow columns: names and types, then per column its null mask and
    values (fixed-width values as their bytes, text as lengths and bytes). One hash per chunk file, computed
    on the column buffers (no Python object per cell); the table read back from the Parquet file gives the same
    hash, any changed cell another. A DataFrame is hashed as its Arrow table (:func:`_to_arrow` layout aside).

    >>> import pyarrow as pa
    >>> t = pa.table({"a": [1.0, None], "b": ["x", None]})
    >>> content_sha256(t) == content_sha256(pa.table({"a": [1.0, None], "b": ["x", None]}))
    True
    >>> content_sha256(t) == content_sha256(pa.table({"a": [1.0, None], "b": ["y", None]}))
    False
    """
    import pyarrow as pa
    import pyarrow.compute as pc
    if isinstance(table, pd.DataFrame):
        table = pa.Table.from_pandas(arrow_safe(table), preserve_index=False)
    h = hashlib.sha256()
    for name, col in zip(table.column_names, table.columns):
        arr = col.combine_chunks() if isinstance(col, pa.ChunkedArray) else col
        t = arr.type
        h.update(f"{name}\x1f{t}\x1e{len(arr)}\x1d".encode())
        h.update(np.packbits(arr.is_valid().to_numpy(zero_copy_only=False)).tobytes())
        if pa.types.is_null(t):
            continue
        if pa.types.is_dictionary(t) or not (pa.types.is_boolean(t) or pa.types.is_integer(t)
                                             or pa.types.is_floating(t) or pa.types.is_string(t)
                                             or pa.types.is_large_string(t) or pa.types.is_binary(t)
                                             or pa.types.is_large_binary(t)):
            arr, t = arr.cast(pa.large_string()), pa.large_string()
        if pa.types.is_boolean(t) or pa.types.is_integer(t) or pa.types.is_floating(t):
            h.update(np.ascontiguousarray(pc.fill_null(arr, pa.scalar(0, t) if not pa.types.is_boolean(t)
                                                       else False).to_numpy(zero_copy_only=False)).tobytes())
        else:
            b = pc.fill_null(arr, "").cast(pa.large_binary())
            offs = np.frombuffer(b.buffers()[1], dtype=np.int64)[b.offset:b.offset + len(b) + 1]
            h.update(np.diff(offs).tobytes())
            if len(offs) and offs[-1] > offs[0]:
                h.update(memoryview(b.buffers()[2])[int(offs[0]):int(offs[-1])])
    return h.hexdigest()


def _write_chunk(folder: Path, i: int, start: int, df: pd.DataFrame, run_id: str) -> None:
    """Write chunk ``i`` (rows from ``start``) with its run id, row range and content checksum in its metadata."""
    import pyarrow.parquet as pq

    table = _to_arrow(df, start)
    meta = {b"synth_run_id": run_id.encode(), b"synth_chunk": str(i).encode(),
            b"synth_rows": f"{start}:{start + len(df)}".encode(), b"synth_sha256": content_sha256(table).encode()}
    table = table.replace_schema_metadata(meta)
    with output_file(_chunk_path(folder, i), "--out") as tmp:  # renamed when complete, removed on failure
        pq.write_table(table, tmp)


def _read_chunk(path: Path):
    """``(Arrow table, synth metadata)`` of a chunk file."""
    import pyarrow.parquet as pq
    table = pq.read_table(path)
    meta = {k.decode(errors="replace"): v.decode(errors="replace") for k, v in (table.schema.metadata or {}).items()
            if k.startswith(b"synth_")}
    return table, meta


def _checked_chunk(folder: Path, i: int, start: int, stop: int, run_id: str):
    """``(state, table)``: :func:`chunk_state` and the chunk's Arrow table when it is ``"ok"`` (read once)."""
    p = _chunk_path(folder, i)
    if not p.is_file():
        return "missing", None
    try:
        table, meta = _read_chunk(p)
    except Exception as exc:  # noqa: BLE001 - a damaged file is reported, never used
        return f"unreadable ({type(exc).__name__}: {' '.join(str(exc).split())[:120]})", None
    if "synth_run_id" not in meta or "synth_sha256" not in meta:
        return "written without a run id and checksum (by an older synth, or not by synth bulk)", None
    if meta["synth_run_id"] != run_id:
        return f"written by another run ({meta['synth_run_id'][:12]}), not by run {run_id[:12]}", None
    rows = table.column("row").to_numpy() if "row" in table.column_names else None
    if rows is None or len(rows) != stop - start or not (rows == np.arange(start, stop)).all():
        return f"rows {meta.get('synth_rows', '?')}, not the chunk's rows {start}:{stop}", None
    if content_sha256(table.replace_schema_metadata(None)) != meta["synth_sha256"]:
        return "its content does not match its checksum (changed or damaged since it was written)", None
    return "ok", table


def chunk_state(folder: Path, i: int, start: int, stop: int, run_id: str) -> str:
    """``"ok"``, ``"missing"`` or why chunk file ``i`` cannot be used by run ``run_id`` for rows ``start..stop-1``.

    A chunk is usable only when it is readable, was written by run
    ``run_id``, covers exactly those rows and its content matches its checksum.
    """
    return _checked_chunk(folder, i, start, stop, run_id)[0]


def _clear(folder: Path) -> None:
    """Remove this module's files (chunks, temporaries, manifest) from ``folder``, nothing else (not the lock)."""
    for p in list(folder.glob("chunk_*.parquet")) + list(folder.glob(".chunk_*.tmp*")) + [folder / MANIFEST]:
        with contextlib.suppress(FileNotFoundError):
            p.unlink()


class RunLock:
    """An exclusive lock on a chunk folder for one run (``run.lock``; ``flock``, released when the process ends).

    >>> import tempfile
    >>> folder = Path(tempfile.mkdtemp())
    >>> with RunLock(folder, "run-a", "r.csv"):
    ...     try:
    ...         RunLock(folder, "run-b", "r.csv").acquire()
    ...     except InputError as exc:
    ...         print(exc.problems[0].field, "refused")
    --out refused
    """

    def __init__(self, folder: Path, run_id: str, out) -> None:
        self.path, self.run_id, self.out = Path(folder) / LOCK, run_id, out
        self._fd: int | None = None

    def acquire(self) -> "RunLock":
        output_folder(self.path.parent, "--out", inside=True)
        try:  # never through a link planted at run.lock (O_NOFOLLOW: ELOOP)
            fd = os.open(self.path, os.O_RDWR | os.O_CREAT | getattr(os, "O_NOFOLLOW", 0), 0o644)
        except OSError as exc:
            if exc.errno == errno.ELOOP:
                raise InputError(Problem("--out", str(self.path), "a lock file that is not a symbolic link (synth "
                                                                  "never writes through a link: remove it)")) from None
            raise
        try:
            import fcntl
            fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except ImportError:  # pragma: no cover - not POSIX: no advisory locks, the per-run id still guards results
            pass
        except OSError:
            try:
                held = json.loads(os.pread(fd, 4096, 0).decode("utf-8", "replace") or "{}")
            except ValueError:
                held = {}
            os.close(fd)
            who = (f"run {str(held.get('run_id', '?'))[:12]} (process {held.get('pid', '?')} on "
                   f"{held.get('host', '?')}, started {held.get('started', '?')})")
            raise InputError(Problem("--out", str(self.out), f"a result that no other synth bulk run is writing: "
                                                             f"{who} holds {self.path}; wait for it to finish, or "
                                                             "give another --out")) from None
        info = {"run_id": self.run_id, "pid": os.getpid(), "host": socket.gethostname(),
                "started": time.strftime("%Y-%m-%d %H:%M:%S")}
        os.ftruncate(fd, 0)
        os.pwrite(fd, json.dumps(info).encode(), 0)
        self._fd = fd
        return self

    def release(self) -> None:
        if self._fd is not None:
            with contextlib.suppress(OSError):
                os.ftruncate(self._fd, 0)
            os.close(self._fd)  # closing the descriptor releases the flock; the file stays (no unlink race)
            self._fd = None

    def __enter__(self) -> "RunLock":
        return self.acquire()

    def __exit__(self, *exc) -> None:
        self.release()


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
        res = pd.concat([_from_arrow(t, want) for _, _, t in _checked_chunks(folder, ranges, run_id)],
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
    settings = _run_settings(settings, fidelity).resolved()  # the catalogs fixed: chunks may run elsewhere
    t0 = time.monotonic()
    out = Path(out)
    if out.suffix.lower() not in FORMATS:
        raise InputError(Problem("--out", str(out), "a file ending in " + ", ".join(sorted(FORMATS))))
    if out.is_dir():
        raise InputError(Problem("--out", str(out), "a file name, not a folder"))
    if isinstance(portfolio, pd.DataFrame):
        table = portfolio.reset_index(drop=True)
        check_columns(table, "DataFrame")
        p_hash = _sha256_frame(table)
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
            _check_manifest(old, manifest, folder)
            if not isinstance(old.get("run_id"), str) or not old["run_id"]:
                raise InputError(Problem("--resume", str(folder / MANIFEST), "the manifest of a run with a run id "
                                         "(written by an older synth); rerun without --resume"))
            run_id = lock.run_id = old["run_id"]  # the resumed run continues the interrupted one
            done = _resumable(folder, ranges, run_id)
        else:
            if resume:
                notes.append(f"nothing to resume in {folder}: starting from the first chunk")
            _clear(folder)
            _write_atomic_json(folder / MANIFEST, {**manifest, "run_id": run_id})
        todo = [i for i in range(len(ranges)) if i not in set(done)]
        todo_set = set(todo)
        kw = dict(objective=objective, diagnose=diagnose, screen=screen, settings=settings)
        computed = 0
        cols = field_columns(table)

        def chunk_records(k: int) -> pd.DataFrame:  # one chunk's field columns at a time (validated as columns)
            a, b = ranges[k]
            return table.iloc[a:b][cols].reset_index(drop=True)

        def write(k: int, df: pd.DataFrame) -> None:
            _write_chunk(folder, k, ranges[k][0], df, run_id)

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
                computed = _run_dask(chunk_records, ranges, todo, write, kw, scheduler, workers, stop_after_chunks,
                                     bar, connect_timeout_s, inprocess, notes)
            seconds = time.monotonic() - t_compute
        complete = all(_chunk_path(folder, i).is_file() for i in range(len(ranges)))
        if complete:
            write_result(out, table, folder, ranges, run_id)
        rows_done = sum(b - a for i, (a, b) in enumerate(ranges) if i in todo_set and _chunk_path(folder, i).is_file())
    finally:
        lock.release()
    rep = RunReport(out=out, n_rows=n, n_chunks=len(ranges), computed=computed, reused=len(done),
                    seconds=seconds, engine=ran["engine"], complete=complete, warnings=notes, rows_computed=rows_done,
                    total_seconds=time.monotonic() - t0, run_id=run_id)
    if complete:
        rep._source = (table, folder, ranges, run_id)
    return rep


def _resumable(folder: Path, ranges: list, run_id: str) -> list[int]:
    """Chunks of run ``run_id`` that can be reused; an :class:`InputError` naming every unusable chunk file."""
    done, problems = [], []
    for i, (a, b) in enumerate(ranges):
        state = chunk_state(folder, i, a, b, run_id)
        if state == "ok":
            done.append(i)
        elif state != "missing":
            problems.append(Problem(f"--resume: {_chunk_path(folder, i).name}", state,
                                    "a chunk of the interrupted run; delete the file to recompute it, or rerun "
                                    "without --resume to start again"))
    known = {_chunk_path(folder, i).name for i in range(len(ranges))}
    for p in sorted(folder.glob("chunk_*.parquet")):
        if p.name not in known:
            problems.append(Problem(f"--resume: {p.name}", f"a chunk beyond the run's {len(ranges)} chunks",
                                    "only chunks of the interrupted run; delete the file, or rerun without --resume"))
    if problems:
        raise InputError(problems)
    return done


def _checked_chunks(folder: Path, ranges: list, run_id: str | None):
    """Yield ``(i, (start, stop), Arrow table)`` of every chunk in order, each read once; with ``run_id``
    every chunk is checked (:func:`chunk_state`) and a chunk of another run, changed or damaged is an
    :class:`InputError` naming every such chunk (after the last one: nothing is kept of a failed assembly)."""
    import pyarrow.parquet as pq
    problems = []
    for i, (a, b) in enumerate(ranges):
        p = _chunk_path(folder, i)
        if run_id is not None:
            state, table = _checked_chunk(folder, i, a, b, run_id)
            if state != "ok":
                problems.append(Problem(f"chunk {p.name}", state, f"a chunk written by this run ({run_id[:12]}); "
                                        "another process wrote into the folder? rerun the command"))
                continue
        else:
            table = pq.read_table(p)
            rows = table.column("row").to_numpy()
            if len(rows) != b - a or not (rows == np.arange(a, b)).all():
                problems.append(Problem("chunks", str(folder), f"chunk files covering rows {a}..{b - 1}; rerun "
                                        "without --resume"))
                continue
        if not problems:
            yield i, (a, b), table
    if problems:
        raise InputError(problems)


def assemble(table: pd.DataFrame, folder: Path, n_chunks: int, run_id: str | None = None,
             ranges: list | None = None) -> pd.DataFrame:
    """The input ``table`` plus the result columns read back from the ``n_chunks`` chunk files, in input order,
    in memory (:func:`write_result` streams the same table into a file).

    With ``run_id`` every chunk is checked first (:func:`chunk_state`): a chunk
    of another run, changed or damaged is an :class:`InputError` naming it, and
    no result is assembled.
    """
    if run_id is not None and (ranges is None or len(ranges) != n_chunks):
        raise ValueError("assemble(run_id=...) needs the run's chunk ranges")
    ranges = ranges if ranges is not None else chunk_ranges(len(table), -(-len(table) // max(n_chunks, 1)) or 1)
    parts = [_from_arrow(t) for _, _, t in _checked_chunks(folder, ranges, run_id)]
    res = pd.concat(parts, ignore_index=True) if parts else pd.DataFrame(columns=result_columns())
    if len(res) != len(table):
        raise InputError(Problem("chunks", str(folder), f"chunk files covering rows 0..{len(table) - 1}; rerun without --resume"))
    return pd.concat([table.reset_index(drop=True), _typed(res)], axis=1)


def write_result(out: Path, table: pd.DataFrame, folder: Path, ranges: list, run_id: str) -> Path:
    """Write RESULT (the input ``table`` plus every chunk's result columns, in input order) chunk by chunk: a
    CSV or Parquet RESULT is streamed (the result columns in memory one chunk at a time, whatever the
    portfolio's size), an Excel or OpenDocument one collected first (their writers need the whole sheet). Every
    chunk is checked as :func:`assemble` checks it; RESULT is written through the output gate
    (:func:`synth.io.outputs.output_file`: a temporary file moved into place; CSV cells by
    :func:`synth.io.outputs.csv_rows`, numbers to :data:`~synth.bulk.portfolio.CSV_FLOAT`)."""
    import pyarrow as pa
    import pyarrow.parquet as pq
    fmt = FORMATS[out.suffix.lower()]
    if fmt not in ("parquet", "csv"):
        return write_table(assemble(table, folder, len(ranges), run_id=run_id, ranges=ranges), out,
                           float_format=CSV_FLOAT)
    chunks = _checked_chunks(folder, ranges, run_id)
    with output_file(out) as tmp:
        if fmt == "parquet":
            inputs = pa.Table.from_pandas(arrow_safe(table.reset_index(drop=True)), preserve_index=False)
            # a part column of numbers in one chunk and of text in another (another engine's parts) is text
            text = {f.name for i in range(len(ranges)) for f in pq.read_schema(_chunk_path(folder, i))
                    if pa.types.is_string(f.type)}
            res_fields = [pa.field(f.name, pa.string() if f.name in text else f.type) for f in list(result_schema())[1:]]
            schema = pa.schema(list(inputs.schema.remove_metadata()) + res_fields)
            with pq.ParquetWriter(tmp, schema) as w:
                for _, (a, b), res in chunks:
                    cols = inputs.slice(a, b - a).columns + [res.column(f.name).cast(f.type) for f in res_fields]
                    w.write_table(pa.Table.from_arrays(cols, schema=schema))
        else:
            with open(tmp, "w", newline="", encoding="utf-8") as fh:
                header = True
                for _, (a, b), res in chunks:
                    csv_rows(pd.concat([table.iloc[a:b].reset_index(drop=True), _from_arrow(res)], axis=1), fh,
                             header=header, float_format=CSV_FLOAT)
                    header = False
                if header:  # no rows: the columns alone
                    csv_rows(pd.DataFrame(columns=list(table.columns) + result_columns()), fh)
    return out


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


def _run_dask(chunk_records, ranges, todo, write, kw, scheduler, workers, stop_after_chunks, bar,
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
