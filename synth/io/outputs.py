r"""The output gate: every file synth writes, and every text that reaches a CSV, JSON or STEP file.

The mirror of the input gate (:mod:`synth.io`): what synth writes is safe by
construction, whatever the user typed or the folder holds.

* :func:`output_file` -- a file is written under a temporary name beside its
  final one (created exclusively, never through a link) and renamed onto it
  when complete: a reader never sees half a file, a symbolic link planted at
  the final name is *replaced*, never followed (its target is untouched), and
  on any failure the temporary file is removed. A file-system refusal
  (read-only folder, full disk, a folder where a file should be...) becomes
  an :class:`~synth.errors.InputError` naming the option and the path (exit 2):
  :func:`os_problem`.
* :func:`output_folder` -- a folder to write into: created when missing,
  refused when it is a file or (inside the output) a symbolic link.
* :func:`output_files` -- a multi-file output (a CAD export, a report, a
  summary): every file is written into a new staging folder and the set is
  moved into place (renames) only when all of it is complete; on a failure
  (a full disk) the folder is left as it was, with no empty or truncated file.
* A file whose writer can fail without saying so (OCCT's STL and STEP
  writers on a full disk) is checked complete by its format before it is
  renamed into place (:func:`incomplete`: an STL's triangle count, a STEP
  file's end, a PNG's last chunk...).
* :func:`csv_safe` -- text cells of a CSV that a spreadsheet would run as a
  formula (``=HYPERLINK(...)``, ``@SUM(...)``, ``=cmd|...``) get the
  apostrophe prefix (OWASP, "CSV Injection"), and a cell holding a line break
  stays one quoted cell of its row; every CSV synth writes calls it, whatever
  the text's source (a portfolio cell, an echoed name, a message).
* :func:`plain` / :func:`json_text` -- JSON that is always valid (RFC 8259: no
  ``NaN`` or ``Infinity``) and holds no subnormal number.
* :func:`step_text` -- a text for an ISO 10303-21 (STEP) string.

>>> csv_cell("=HYPERLINK(\"http://x\")"), csv_cell("-3.5"), csv_cell("dry")
('\'=HYPERLINK("http://x")', '-3.5', 'dry')
>>> json_text({"margin": float("-inf"), "x": 5e-324, "ok": 1.5})
'{"margin": null, "x": 0.0, "ok": 1.5}'
>>> print(step_text("Kia's 1 \u00b5m; x"))
Kia\X2\0027\X0\s 1 \X2\00B5\X0\m\X2\003B\X0\ x
"""

from __future__ import annotations

import contextlib
import errno
import math
import os
import secrets
import sys
from pathlib import Path

from synth.errors import InputError, Problem

__all__ = ["FORMULA_LEADS", "FS_ERRNOS", "os_problem", "output_file", "output_folder", "output_files", "refuse_link",
           "incomplete", "write_text", "write_figure", "write_csv", "csv_rows", "csv_cell",
           "csv_safe", "plain", "json_text", "step_text"]

#: Leading characters that make a spreadsheet read typed text as a formula (OWASP "CSV Injection": ``= + - @``,
#: tab and carriage return).
FORMULA_LEADS = ("=", "+", "-", "@", "\t", "\r")

#: errno of a file-system refusal that is the environment's, not synth's (exit 2 with the path, never 70)
FS_ERRNOS = {errno.EACCES: "permission denied (a read-only or protected folder?)",
             errno.EPERM: "operation not permitted",
             errno.EROFS: "the file system is read-only",
             errno.ENOSPC: "no space left on the device (the disk is full)",
             errno.EDQUOT: "the disk quota is exceeded",
             errno.EFBIG: "the file would exceed the largest file the file system holds",
             errno.EISDIR: "it is a folder, where a file is written",
             errno.ENOTDIR: "a part of the path is a file, where a folder is needed",
             errno.EEXIST: "a file or folder of that name is in the way",
             errno.ENAMETOOLONG: "the name is too long",
             errno.ELOOP: "too many symbolic links",
             errno.ENXIO: "it is a device or socket, not a file",
             errno.ETXTBSY: "the file is busy",
             errno.EIO: "an input/output error of the device (a failing disk or network share?)"}


def os_problem(exc: OSError, what: str, path=None, verb: str = "write") -> Problem:
    """A file-system error as a :class:`~synth.errors.Problem`: the option (``what``), the path and why."""
    why = FS_ERRNOS.get(exc.errno, exc.strerror or type(exc).__name__)
    where = path if path is not None else (exc.filename or "?")
    return Problem(what, str(where), f"a path synth can {verb} ({why})")


def refuse_link(p, what: str) -> None:
    """An :class:`InputError` when ``p`` is a symbolic link: a folder synth makes inside an output is never one
    (checked before the work, and again when the folder is made)."""
    p = Path(p)
    if p.is_symlink():
        raise InputError(Problem(what, str(p), f"a folder that is not a symbolic link (this one points to "
                                               f"{os.readlink(p)}; synth never writes through a link an output "
                                               "folder holds: remove it)"))


def output_folder(path, what: str = "--out", *, inside: bool = False) -> Path:
    """Folder ``path``, created when missing (with its parents); an :class:`InputError` when it cannot be one.

    ``inside=True``: a folder synth makes inside the output folder the user named (``DIR/cad``, ``DIR/stl``):
    it must not be a symbolic link (the user's own ``--out`` may be one: it is what they named).
    """
    p = Path(path)
    if inside:
        refuse_link(p, what)
    if p.exists() and not p.is_dir():
        raise InputError(Problem(what, str(p), "a folder (this is an existing file; give a folder name)"))
    try:
        p.mkdir(parents=True, exist_ok=True)
    except FileExistsError:
        raise InputError(Problem(what, str(p), "a folder (a file of that name is in the way)")) from None
    except OSError as exc:
        raise InputError(os_problem(exc, what, p)) from None
    return p


@contextlib.contextmanager
def output_file(path, what: str = "--out"):
    """Write file ``path`` through a temporary file beside it; yields the temporary :class:`~pathlib.Path`.

    The caller writes the temporary path (any library: it has the final name's extension); when the block
    ends without an error it is renamed onto ``path`` (atomic on POSIX; a symbolic link at ``path`` is replaced,
    its target untouched). On any error the temporary file is removed; an :class:`OSError` of the file system
    (:data:`FS_ERRNOS`) becomes an :class:`~synth.errors.InputError` naming ``what`` and ``path``.
    """
    p = Path(path)
    if p.is_dir() and not p.is_symlink():
        raise InputError(Problem(what, str(p), "a file name (this is a folder)"))
    tmp = None
    try:
        output_folder(p.parent, what)
        tmp = _new_temporary(p)
        yield tmp
        why = incomplete(tmp)
        if why is not None:  # a writer that failed without an error (OCCT's on a full disk)
            raise _disk_full(p.parent) or OSError(errno.EIO, f"the writer left an incomplete file ({why})", str(p))
        os.replace(tmp, p)
        tmp = None
    except OSError as exc:
        if exc.errno in FS_ERRNOS:
            raise InputError(os_problem(exc, what, p)) from None
        raise
    except Exception:
        full = _disk_full(p.parent)  # a library that reports a failed write without the errno (OCCT's writers)
        if full is not None:
            raise InputError(os_problem(full, what, p)) from None
        raise
    finally:
        if tmp is not None:
            with contextlib.suppress(OSError):
                tmp.unlink()


@contextlib.contextmanager
def output_files(folder, what: str = "--out", *, inside: bool = False):
    """A multi-file output into ``folder``: yields a new staging folder; its files are moved into ``folder`` when the
    block ends without an error, all of them, else none.

    The staging folder (``folder/.synth-<random>.tmp``, created exclusively) is on the same file system as
    ``folder``, so the move is a rename per file: no copy, no space needed, nothing half written. Its
    sub-folders (``stl/``) are created in ``folder`` when missing, never through a symbolic link
    (:func:`output_folder` with ``inside=True``); a link at a file's final name is replaced, never followed. On
    any failure (a full disk, a writer that fails, Ctrl-C) the staging folder is removed and ``folder`` holds
    what it held before. A problem names ``what`` and the file's final path, not the staging one.

    >>> import tempfile, pathlib
    >>> out = pathlib.Path(tempfile.mkdtemp()) / "cad"
    >>> with output_files(out, "--cad") as stage:
    ...     _ = write_text(stage / "a.json", "{}")
    ...     _ = write_text(output_folder(stage / "stl") / "b.stl", "solid x\\nendsolid x\\n")
    >>> sorted(str(q.relative_to(out)) for q in out.rglob("*"))
    ['a.json', 'stl', 'stl/b.stl']
    """
    final = output_folder(folder, what, inside=inside)
    stage = None
    try:
        try:
            stage = _new_stage(final)
            yield stage
            _move_into(stage, final, what)
        except OSError as exc:
            if exc.errno in FS_ERRNOS:
                raise InputError(os_problem(exc, what, exc.filename or final)) from None
            raise
    except InputError as exc:  # name the final path and the option, not the staging folder
        if stage is None:
            raise
        raise InputError([Problem(what if p.field == "--out" else p.field,
                                  str(p.value).replace(str(stage), str(final)), p.accepted)
                          for p in exc.problems]) from None
    finally:
        if stage is not None:
            import shutil
            shutil.rmtree(stage, ignore_errors=True)


def _new_stage(final: Path) -> Path:
    for _ in range(100):
        stage = final / f".synth-{secrets.token_hex(6)}.tmp"
        try:
            stage.mkdir()
            return stage
        except FileExistsError:
            continue
    raise FileExistsError(errno.EEXIST, "no free staging name", str(final))  # pragma: no cover


def _move_into(src: Path, dst: Path, what: str) -> None:
    """Move every file of ``src`` into ``dst`` (sub-folders into sub-folders, created never through a link)."""
    for entry in sorted(src.iterdir()):
        target = dst / entry.name
        if entry.is_dir() and not entry.is_symlink():
            _move_into(entry, output_folder(target, what, inside=True), what)
        else:
            if target.is_dir() and not target.is_symlink():
                raise InputError(Problem(what, str(target), "a file name (a folder of that name is in the way)"))
            os.replace(entry, target)


#: the last bytes of a complete file, by extension (a writer that fails silently leaves a file without them)
_ENDINGS = {".step": b"END-ISO-10303-21;", ".stp": b"END-ISO-10303-21;", ".png": b"IEND\xaeB`\x82",
            ".pdf": b"%%EOF", ".parquet": b"PAR1"}


def incomplete(path) -> str | None:
    """Why the file at ``path`` is not a complete file of its format (by extension), or None.

    Checked: a binary STL holds exactly the triangles its header counts (84 + 50 n bytes), an ASCII STL ends
    with ``endsolid``; a STEP, PNG, PDF or Parquet file ends as its format ends (:data:`_ENDINGS`); an .xlsx or
    .ods is a readable zip archive. Any other file is written by Python, which raises on a failed write.

    >>> import tempfile, pathlib
    >>> p = pathlib.Path(tempfile.mkdtemp()) / "a.stl"
    >>> _ = p.write_bytes(b"")
    >>> incomplete(p)
    'an STL file of 0 bytes (a binary STL has at least 84)'
    """
    p = Path(path)
    suffix = p.suffix.lower()
    try:
        size = p.stat().st_size
        if suffix == ".stl":
            with open(p, "rb") as fh:
                head = fh.read(84)
                fh.seek(max(0, size - 256))
                tail = fh.read()
            triangles = int.from_bytes(head[80:84], "little") if size >= 84 else -1
            if size == 84 + 50 * triangles or (head[:5] == b"solid" and b"endsolid" in tail):
                return None
            if size < 84:
                return f"an STL file of {size} bytes (a binary STL has at least 84)"
            return f"an STL file of {size} bytes whose header counts {triangles} triangles ({84 + 50 * triangles} bytes)"
        if suffix in _ENDINGS:
            with open(p, "rb") as fh:
                fh.seek(max(0, size - 1024))
                tail = fh.read()
            return None if _ENDINGS[suffix] in tail else f"a {suffix} file of {size} bytes without its end"
        if suffix in (".xlsx", ".xlsm", ".ods"):
            import zipfile
            return None if zipfile.is_zipfile(p) else f"a {suffix} file of {size} bytes that is no complete zip"
    except OSError as exc:
        return f"unreadable ({exc.strerror})"
    return None


def _new_temporary(p: Path) -> Path:
    """A new empty file beside ``p`` with ``p``'s extension, created exclusively (``O_EXCL``: never an existing
    file or link) with the permissions of the user's umask."""
    for _ in range(100):
        tmp = p.with_name(f".{p.stem[:60]}.{secrets.token_hex(6)}.tmp{p.suffix}")
        try:
            os.close(os.open(tmp, os.O_WRONLY | os.O_CREAT | os.O_EXCL, 0o666))
            return tmp
        except FileExistsError:
            continue
    raise FileExistsError(errno.EEXIST, "no free temporary name", str(p.parent))  # pragma: no cover


def _disk_full(folder: Path) -> OSError | None:
    """An ENOSPC error when the device of ``folder`` has (almost) no space left, else None."""
    import shutil
    try:
        if shutil.disk_usage(folder).free < 64 * 1024:
            return OSError(errno.ENOSPC, os.strerror(errno.ENOSPC), str(folder))
    except OSError:
        pass
    return None


def write_text(path, text: str, what: str = "--out") -> Path:
    """Write ``text`` (UTF-8) to ``path`` through :func:`output_file`; returns the path."""
    with output_file(path, what) as tmp:
        tmp.write_text(text, encoding="utf-8")
    return Path(path)


def figure_path(path: str | None, what: str = "--plot"):
    """Option ``what``'s figure file checked before any work: a file type matplotlib writes, in an existing folder;
    returns ``path`` (None for None)."""
    if path is None:
        return None
    from matplotlib.backend_bases import FigureCanvasBase

    types = sorted(FigureCanvasBase.get_supported_filetypes())
    p = Path(path)
    ext = p.suffix.lower().lstrip(".")
    if ext not in types:
        raise InputError(Problem(what, path, "a file name ending in ." + ", .".join(types) + " (PNG, SVG, PDF...)"))
    if not p.parent.is_dir():
        raise InputError(Problem(what, path, f"a file in an existing folder ({p.parent} does not exist)"))
    if p.is_dir():
        raise InputError(Problem(what, path, "a file name, not a folder"))
    return path


def write_figure(fig, path, what: str = "--out", **savefig) -> Path:
    """Save matplotlib figure ``fig`` to ``path`` (format by its extension) through :func:`output_file`; the
    figure is closed, written or not."""
    import matplotlib.pyplot as plt
    p = Path(path)
    savefig.setdefault("format", p.suffix.lstrip(".").lower() or "png")
    try:
        with output_file(p, what) as tmp:
            fig.savefig(tmp, **savefig)
    finally:
        plt.close(fig)
    return p


def write_csv(df, path, what: str = "--out", *, float_format: str | None = None) -> Path:
    """Write table ``df`` as CSV (no index) through :func:`output_file`, by :func:`csv_rows`."""
    with output_file(path, what) as tmp:
        with open(tmp, "w", newline="", encoding="utf-8") as fh:
            csv_rows(df, fh, float_format=float_format)
    return Path(path)


def csv_rows(df, fh, *, header: bool = True, float_format: str | None = None) -> None:
    """Write ``df`` as CSV rows to the open text file ``fh`` (``header``: the column names first), its text cells
    :func:`csv_safe`, its numbers by ``float_format`` as pandas takes it (None: every digit): the one CSV writer,
    of whole tables (:func:`write_csv`) and chunk by chunk (``synth bulk``'s RESULT)."""
    csv_safe(df).to_csv(fh, index=False, header=header, float_format=float_format)


# ---------------------------------------------------------------- CSV
def csv_cell(value):
    """A text cell as every CSV synth writes it: formula-safe and one cell whatever its line breaks.

    * Text a spreadsheet would read as a formula (:data:`FORMULA_LEADS`, also after leading spaces: `` =1+1``)
      gets the apostrophe prefix; text that is a plain number (``-3.5``, ``+2``) cannot be a formula and is kept.
    * A line break is written as ``\\n`` (a carriage return, bare or before a line feed, becomes one): Python's
      CSV writer quotes a cell holding a line feed but writes a bare carriage return unquoted, which splits the
      row in every reader (and the next physical line may start with ``=``).

    >>> csv_cell(" =1+1"), csv_cell("a\\r=1+1"), csv_cell("\\r\\n=cmd"), csv_cell(" 2.5")
    ("' =1+1", 'a\\n=1+1', "'\\n=cmd", ' 2.5')
    """
    if not _needs_cell(value):
        return value
    text = value
    if text.lstrip(" ").startswith(FORMULA_LEADS):
        try:
            float(text)
        except ValueError:
            text = "'" + text
    if "\r" in text:
        text = text.replace("\r\n", "\n").replace("\r", "\n")
    return text


def _needs_cell(v) -> bool:
    """Whether :func:`csv_cell` changes ``v`` (a formula lead, a carriage return), in one cheap test per cell."""
    return isinstance(v, str) and (v.lstrip(" ").startswith(FORMULA_LEADS) or "\r" in v)


def csv_safe(df):
    """A copy of table ``df`` whose text cells and column names are :func:`csv_cell`-safe (every CSV writer)."""
    import numpy as np
    from pandas.api.types import is_object_dtype, is_string_dtype
    out = df.copy()
    out.columns = [csv_cell(str(c)) if isinstance(c, str) else c for c in out.columns]
    for i in range(out.shape[1]):
        col = out.iloc[:, i]
        if is_object_dtype(col.dtype) or is_string_dtype(col.dtype):
            cells = col.to_numpy(dtype=object)  # one pass over the cells, no pandas per-cell call
            lead = np.fromiter((_needs_cell(v) for v in cells), dtype=bool, count=len(cells))
            if lead.any():
                text = col.astype("object")
                out.isetitem(i, text.where(~lead, text[lead].map(csv_cell)))
    return out


# ---------------------------------------------------------------- JSON
def plain(v, digits: int | None = None):
    """JSON-friendly data: numpy to Python; NaN and infinities to None; subnormal numbers to 0.0; ``digits``: floats
    to that many significant figures.

    A subnormal (below 2.2e-308 in magnitude) is no physical value; it would print as ``5e-324`` and read back
    as zero on some platforms.

    >>> import numpy as np
    >>> plain({"a": np.float64(0.123456789), "b": [np.inf, 2, 5e-324]}, digits=6)
    {'a': 0.123457, 'b': [None, 2, 0.0]}
    """
    if hasattr(v, "tolist") and not isinstance(v, (str, bytes)):
        v = v.tolist()
    if isinstance(v, (list, tuple)):
        return [plain(x, digits) for x in v]
    if isinstance(v, dict):
        return {str(k): plain(x, digits) for k, x in v.items()}
    if isinstance(v, float):
        if not math.isfinite(v):
            return None
        if v != 0.0 and abs(v) < sys.float_info.min:
            return 0.0
        if digits:
            return float(f"{v:.{digits}g}")
    return v


def json_text(data, *, indent: int | None = None, digits: int | None = None) -> str:
    """``data`` as JSON text that every parser reads (:func:`plain` first, floats to ``digits`` significant figures
    when given; ``allow_nan=False`` guards it)."""
    import json
    return json.dumps(plain(data, digits), indent=indent, allow_nan=False, default=str)


# ---------------------------------------------------------------- STEP
_STEP_PLAIN = frozenset("ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789 .,_+-/()#=:")


def step_text(text) -> str:
    r"""``text`` for an ISO 10303-21 (STEP) string: letters, digits, spaces and ``.,_+-/()#=:`` as they are; every
    other character (apostrophe, backslash, semicolon, anything beyond ASCII) as a control directive
    ``\X2\hhhh\X0\`` (``\X4\hhhhhhhh\X0\`` beyond the basic plane; ISO 10303-21 clause 6.4.3.3); control
    characters as a space. Nothing a user types can end the string or the section, and readers decode it back
    (OCCT does: :func:`synth.cad.step.read_step_header`).
    """
    out = []
    for ch in str(text):
        o = ord(ch)
        if ch in _STEP_PLAIN:
            out.append(ch)
        elif o < 32 or o == 127:
            out.append(" ")
        elif o < 0x10000:
            out.append(f"\\X2\\{o:04X}\\X0\\")
        else:
            out.append(f"\\X4\\{o:08X}\\X0\\")
    return "".join(out)
