"""A bulk run's resumable store: the chunk folder beside RESULT (``<RESULT>.chunks``), its manifest (what must not
change between an interrupted run and its resume), its lock (:class:`RunLock`), the chunk files with their run id,
rows and content checksum, the checks a resume makes, and RESULT assembled from the chunks (:func:`write_result`).
See :mod:`synth.bulk.run` for the run integrity these give.
"""

from __future__ import annotations

import contextlib
import errno
import hashlib
import json
import os
import socket
import time
from pathlib import Path

import numpy as np
import pandas as pd

from synth import catalog
from synth.bulk.execution import result_columns, result_kind, typed
from synth.bulk.portfolio import CSV_FLOAT, FORMATS, arrow_safe, write_table
from synth.design.rules import echo
from synth.design.settings import Settings
from synth.errors import InputError, Problem
from synth.fingerprint import catalogs_sha256
from synth.io.outputs import csv_rows, output_file, output_folder, write_text
from synth.version import __version__

__all__ = ["MANIFEST", "LOCK", "chunk_ranges", "sidecar", "chunk_path", "frame_sha256", "manifest_of",
           "check_manifest", "write_json", "result_schema", "from_arrow", "content_sha256", "write_chunk",
           "chunk_state", "clear_folder", "RunLock", "resumable_chunks", "checked_chunks", "assemble", "write_result"]

MANIFEST = "manifest.json"
LOCK = "run.lock"
_MANIFEST_KEYS = ("portfolio_sha256", "n_rows", "objective", "fidelity", "chunk_size", "diagnose",
                  "synth_version", "catalogs_sha256", "rules", "capability")


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


def chunk_path(folder: Path, i: int) -> Path:
    return folder / f"chunk_{i:05d}.parquet"


def frame_sha256(df: pd.DataFrame) -> str:
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


def check_manifest(old: dict, new: dict, folder: Path) -> None:
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


def write_json(path: Path, data: dict) -> None:
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
        k = result_kind(c)
        t = (pa.bool_() if k == "bool" else pa.float64() if k == "float" else
             pa.float64() if k == "part" and _part_is_number(c[len("part_"):]) else pa.string())
        fields.append(pa.field(c, t))
    return pa.schema(fields)


def _to_arrow(df: pd.DataFrame, start: int):
    """A chunk's typed result rows (:func:`typed`) as an Arrow table of :func:`result_schema`."""
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


def from_arrow(table, columns=None) -> pd.DataFrame:
    """The result columns (or ``columns`` of them) of a chunk table as :func:`typed` gives them (parts: None where
    empty; text: "")."""
    import pyarrow.compute as pc
    out = {}
    columns = result_columns() if columns is None else list(columns)
    for c in columns:
        col, k = table.column(c), result_kind(c)
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


def write_chunk(folder: Path, i: int, start: int, df: pd.DataFrame, run_id: str) -> None:
    """Write chunk ``i`` (rows from ``start``) with its run id, row range and content checksum in its metadata."""
    import pyarrow.parquet as pq

    table = _to_arrow(df, start)
    meta = {b"synth_run_id": run_id.encode(), b"synth_chunk": str(i).encode(),
            b"synth_rows": f"{start}:{start + len(df)}".encode(), b"synth_sha256": content_sha256(table).encode()}
    table = table.replace_schema_metadata(meta)
    with output_file(chunk_path(folder, i), "--out") as tmp:  # renamed when complete, removed on failure
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
    p = chunk_path(folder, i)
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


def clear_folder(folder: Path) -> None:
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


def resumable_chunks(folder: Path, ranges: list, run_id: str) -> list[int]:
    """Chunks of run ``run_id`` that can be reused; an :class:`InputError` naming every unusable chunk file."""
    done, problems = [], []
    for i, (a, b) in enumerate(ranges):
        state = chunk_state(folder, i, a, b, run_id)
        if state == "ok":
            done.append(i)
        elif state != "missing":
            problems.append(Problem(f"--resume: {chunk_path(folder, i).name}", state,
                                    "a chunk of the interrupted run; delete the file to recompute it, or rerun "
                                    "without --resume to start again"))
    known = {chunk_path(folder, i).name for i in range(len(ranges))}
    for p in sorted(folder.glob("chunk_*.parquet")):
        if p.name not in known:
            problems.append(Problem(f"--resume: {p.name}", f"a chunk beyond the run's {len(ranges)} chunks",
                                    "only chunks of the interrupted run; delete the file, or rerun without --resume"))
    if problems:
        raise InputError(problems)
    return done


def checked_chunks(folder: Path, ranges: list, run_id: str | None):
    """Yield ``(i, (start, stop), Arrow table)`` of every chunk in order, each read once; with ``run_id``
    every chunk is checked (:func:`chunk_state`) and a chunk of another run, changed or damaged is an
    :class:`InputError` naming every such chunk (after the last one: nothing is kept of a failed assembly)."""
    import pyarrow.parquet as pq
    problems = []
    for i, (a, b) in enumerate(ranges):
        p = chunk_path(folder, i)
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
    parts = [from_arrow(t) for _, _, t in checked_chunks(folder, ranges, run_id)]
    res = pd.concat(parts, ignore_index=True) if parts else pd.DataFrame(columns=result_columns())
    if len(res) != len(table):
        raise InputError(Problem("chunks", str(folder), f"chunk files covering rows 0..{len(table) - 1}; rerun without --resume"))
    return pd.concat([table.reset_index(drop=True), typed(res)], axis=1)


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
    chunks = checked_chunks(folder, ranges, run_id)
    with output_file(out) as tmp:
        if fmt == "parquet":
            inputs = pa.Table.from_pandas(arrow_safe(table.reset_index(drop=True)), preserve_index=False)
            # a part column of numbers in one chunk and of text in another (another engine's parts) is text
            text = {f.name for i in range(len(ranges)) for f in pq.read_schema(chunk_path(folder, i))
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
                    csv_rows(pd.concat([table.iloc[a:b].reset_index(drop=True), from_arrow(res)], axis=1), fh,
                             header=header, float_format=CSV_FLOAT)
                    header = False
                if header:  # no rows: the columns alone
                    csv_rows(pd.DataFrame(columns=list(table.columns) + result_columns()), fh)
    return out
