r"""Opening a file the user named: it exists, it is not too big, it is UTF-8 text (or a workbook).

Every error is an :class:`~synth.errors.InputError` whose field is what the
user wrote (``input file``, ``--parts``, ``portfolio``...) and whose value is
the path.

>>> import tempfile, pathlib
>>> p = pathlib.Path(tempfile.mkdtemp()) / "latin1.yaml"
>>> _ = p.write_bytes("name: caf\xe9".encode("latin-1"))
>>> try:
...     read_text(p, "input file")
... except InputError as exc:
...     print(exc.problems[0].accepted[:60])
UTF-8 text (byte 0xe9 at offset 9 is not UTF-8: the file was
"""

from __future__ import annotations

import os
import zipfile
from pathlib import Path

from synth.errors import InputError, Problem
from synth.io.limits import LIMITS, MB

__all__ = ["existing_file", "read_text", "check_size", "check_zip", "suffix_of", "content_kind", "kind_of_file",
           "WORKBOOK_SUFFIXES"]

#: the workbook files a user may name (the Excel template, or it saved by LibreOffice)
WORKBOOK_SUFFIXES = (".xlsx", ".xlsm", ".ods")


def suffix_of(path: str | os.PathLike) -> str:
    """The lower-case extension of ``path`` (``.yaml``)."""
    return Path(path).suffix.lower()


def existing_file(path, what: str, accepted: str) -> Path:
    """``path`` as a :class:`~pathlib.Path` if it is an existing regular file, else a Problem."""
    p = Path(path)
    try:
        ok = p.is_file()
    except (OSError, ValueError):  # a name too long, a NUL byte in it
        ok = False
    if not ok:
        state = "a folder" if _is_dir(p) else "no such file"
        raise InputError(Problem(what, str(path), f"{accepted} ({state})"))
    return p


def _is_dir(p: Path) -> bool:
    try:
        return p.is_dir()
    except (OSError, ValueError):
        return False


def check_size(path: Path, what: str, limit: int, kind: str = "file") -> int:
    """The size of ``path`` in bytes, or a Problem when it is above ``limit``."""
    try:
        size = path.stat().st_size
    except OSError as exc:
        raise InputError(Problem(what, str(path), f"a readable {kind} ({exc.strerror})")) from None
    if size > limit:
        raise InputError(Problem(what, str(path), f"a {kind} of at most {_mb(limit)} (this one has {_mb(size)})"))
    return size


def _mb(n: int) -> str:
    return f"{n / MB:.3g} MB" if n >= MB else f"{n / 1024:.3g} kB" if n >= 1024 else f"{n} bytes"


def read_text(path, what: str, *, limit: int | None = None, accepted: str = "a UTF-8 text file") -> str:
    """The text of file ``path``: existing, at most ``limit`` bytes, UTF-8 (a BOM is accepted).

    A binary file (NUL bytes) or a file in another encoding (Latin-1,
    UTF-16...) gets a Problem that says so and what is accepted.
    """
    p = existing_file(path, what, accepted)
    check_size(p, what, LIMITS.text_input_bytes if limit is None else limit)
    try:
        data = p.read_bytes()
    except OSError as exc:
        raise InputError(Problem(what, str(p), f"a readable file ({exc.strerror})")) from None
    kind = content_kind(data)
    if kind == "UTF-16 text":
        raise InputError(Problem(what, str(p), "UTF-8 text (this file is UTF-16: save it as UTF-8)"))
    if kind is not None:
        raise InputError(Problem(what, str(p), f"{accepted}; this is {kind}"))
    try:
        text = data.decode("utf-8-sig")
    except UnicodeDecodeError as exc:
        raise InputError(Problem(what, str(p), f"UTF-8 text (byte 0x{data[exc.start]:02x} at offset {exc.start} is "
                                               "not UTF-8: the file was saved in another encoding, e.g. Latin-1 "
                                               "or Windows-1252; save it as UTF-8)")) from None
    if "\x00" in text:
        raise InputError(Problem(what, str(p), f"{accepted}; this file holds NUL characters (binary data)"))
    return text


#: leading bytes of the binary files a user may name by mistake, and what they are
_MAGIC = ((b"%PDF-", "a PDF document, not text"), (b"\x89PNG", "a PNG picture, not text"),
          (b"\xff\xd8\xff", "a JPEG picture, not text"), (b"\x1f\x8b", "a gzip archive, not text"),
          (b"PAR1", "a Parquet table, not text"), (b"ISO-10303-21", "a STEP file (a 3D model), not an input"),
          (b"\xd0\xcf\x11\xe0", "an old Excel (.xls) or Word file, not text"))


def content_kind(data: bytes) -> str | None:
    r"""What the bytes of a file are when they are not UTF-8 text of an input, judged by content (never by the
    file's name), else None.

    >>> content_kind(b"PK\x03\x04" + bytes(40)), content_kind(b"%PDF-1.7"), content_kind(b"name: x\n")
    ('a zip archive (a workbook? give it its .xlsx or .ods extension)', 'a PDF document, not text', None)
    """
    if data.startswith((b"\xff\xfe", b"\xfe\xff")):
        return "UTF-16 text"
    if data.startswith(b"PK\x03\x04"):
        return _zip_kind(data)
    for magic, kind in _MAGIC:
        if data.startswith(magic):
            return kind
    if b"\x00" in data[:8192]:
        return "a binary file, not text"
    return None


def kind_of_file(path) -> str | None:
    """:func:`content_kind` of the file at ``path`` (its first 8 kB; a zip archive's directory), None when it reads
    as text or cannot be read (the reader then says why)."""
    try:
        with open(path, "rb") as fh:
            head = fh.read(8192)
    except (OSError, ValueError):
        return None
    if head.startswith(b"PK\x03\x04"):
        return _zip_kind(path)
    return content_kind(head)


def _zip_kind(data) -> str:
    """A zip archive's kind by its members: an Excel workbook, an OpenDocument spreadsheet, or a zip archive
    (``data``: its bytes, or its path)."""
    import io
    try:
        with zipfile.ZipFile(io.BytesIO(data) if isinstance(data, bytes) else data) as zf:
            names = set(zf.namelist()[:10_000])
    except (zipfile.BadZipFile, OSError, ValueError, EOFError, RuntimeError):
        names = set()
    if "xl/workbook.xml" in names:
        return "an Excel workbook (the design-input template?), not a text file"
    if "content.xml" in names and "mimetype" in names:
        return "an OpenDocument spreadsheet, not a text file"
    return "a zip archive (a workbook? give it its .xlsx or .ods extension)"


def check_zip(path: Path, what: str, unpacked_limit: int, kind: str, part_limit: int | None = None) -> None:
    """A workbook (.xlsx/.ods are zip archives): readable as a zip, unpacking to at most ``unpacked_limit`` bytes,
    and no part (``xl/sharedStrings.xml``, ``styles.xml``, ``content.xml``...) above ``part_limit`` bytes.

    Refuses a "zip bomb" (a small file that unpacks to gigabytes), and a part
    the XML readers would take minutes over (a 156 kB .xlsx holding 63 MB of
    shared strings), before any XML is parsed: the sizes are the archive's
    directory, read in microseconds.
    """
    try:
        with zipfile.ZipFile(path) as zf:
            parts = [(i.filename, i.file_size) for i in zf.infolist()]
    except (zipfile.BadZipFile, OSError, ValueError, EOFError):
        raise InputError(Problem(what, str(path), f"a valid {kind} (this file is not a zip archive, "
                                                  "or it is damaged)")) from None
    total = sum(size for _, size in parts)
    if total > unpacked_limit:
        raise InputError(Problem(what, str(path), f"a {kind} that unpacks to at most {_mb(unpacked_limit)} "
                                                  f"(this one unpacks to {_mb(total)})"))
    big = [(name, size) for name, size in parts if part_limit is not None and size > part_limit]
    if big:
        name, size = max(big, key=lambda x: x[1])
        raise InputError(Problem(what, str(path), f"a {kind} whose parts unpack to at most {_mb(part_limit)} each "
                                                  f"(its {name[:80]} unpacks to {_mb(size)})"))
