"""Files the pages open, received as they stream: size and name checked before anything big is kept.

NiceGUI's own upload route reads the whole request (Starlette's form parser spools it to a temporary file) and then
copies it once more before a handler sees it: a 2 GB upload was read whole, 61 s, before synth could refuse it,
and the copy stayed until the server stopped (issue 39). Here each upload box of a page posts to its own URL
(``/synth-upload/KEY``, :func:`register`); :func:`receive` parses the multipart body as it arrives
(``python-multipart``'s streaming parser, NiceGUI's own dependency) and writes the one file straight into the
page's folder, counting:

* a request whose ``Content-Length`` is above the box's limit is refused before a byte is read;
* a body that crosses the limit while streaming is refused at that chunk, its partial file removed at once;
* a file name is the file's own name (its last path component, control characters dropped), at most
  :data:`NAME_CHARS` characters (and 240 bytes): a longer one is refused with a message, never a file-system
  error;
* anything else that is not one file in a ``multipart/form-data`` body is refused with a message.

A refusal answers 413 (too large) or 400 with ``Connection: close`` (the sender stops), and the page shows why.
The limits are the input gate's (:data:`synth.io.limits.LIMITS`): a design input is at most the Excel template's
16 MB, a portfolio the portfolio's 128 MB.

>>> safe_name("../../etc/passwd"), safe_name("C:\\\\Users\\\\me\\\\case 1.yaml"), safe_name("a\\x00b.csv")
('passwd', 'case 1.yaml', 'ab.csv')
"""

from __future__ import annotations

import secrets
import shutil
import weakref
from dataclasses import dataclass
from pathlib import Path
from typing import Callable

from synth.errors import InputError, Problem
from synth.io.limits import MB, short

__all__ = ["UPLOAD_URL", "Target", "register", "forget", "receive", "safe_name", "NAME_CHARS", "OVERHEAD",
           "body_limit"]

#: the URL prefix of the upload boxes
UPLOAD_URL = "/synth-upload"
#: the longest file name kept (most file systems take 255 bytes; a name is shown in messages and reports)
NAME_CHARS = 200
#: the multipart framing around the one file (boundaries, part headers with the file name)
OVERHEAD = 64 * 1024
#: the longest file name in bytes (UTF-8) kept: ext4, XFS and btrfs take 255, the folder's prefix aside
_NAME_BYTES = 240
#: the largest part header block (a file name of NAME_CHARS characters fits many times)
_HEADER_BYTES = 16 * 1024


@dataclass
class Target:
    """One upload box: the ``folder`` its files go to, the ``limit`` in bytes, ``what`` the file is (for messages:
    ``input file``), ``done(path, name)`` the page's handler (it schedules the page's work and returns) and
    ``refused(exc)`` the page's message."""

    folder: Path
    limit: int
    what: str
    done: Callable[[Path, str], None]
    refused: Callable[[InputError], None]


_TARGETS: "weakref.WeakValueDictionary[str, Target]" = weakref.WeakValueDictionary()
#: the largest limit of any box (the server's body limit for the upload URLs)
_LARGEST = [16 * MB]


def register(target: Target) -> str:
    """The URL the box posts to (its key is unguessable; the target is held by its page, not here)."""
    key = secrets.token_urlsafe(16)
    _TARGETS[key] = target
    _LARGEST[0] = max(_LARGEST[0], target.limit)
    return f"{UPLOAD_URL}/{key}"


def forget(url: str) -> None:
    _TARGETS.pop(url.rsplit("/", 1)[-1], None)


def body_limit(path: str) -> int | None:
    """The largest request body for ``path`` when it is an upload URL (the box's limit and the framing), else None."""
    if not path.startswith(UPLOAD_URL + "/"):
        return None
    t = _TARGETS.get(path[len(UPLOAD_URL) + 1:])
    return (t.limit if t is not None else _LARGEST[0]) + OVERHEAD


def safe_name(name: str) -> str:
    """The file's own name: its last path component (``/`` or ``\\``), without control characters."""
    base = name.replace("\\", "/").rsplit("/", 1)[-1]
    return "".join(c for c in base if c.isprintable()).strip()


def _size(n: int) -> str:
    return f"{n / MB:g} MB" if n >= MB else f"{n:,} bytes"


class _Refused(Exception):
    def __init__(self, status: int, exc: InputError):
        super().__init__(str(exc))
        self.status, self.exc = status, exc


class _File:
    """The multipart body's one file, written as it streams (python-multipart's callbacks)."""

    def __init__(self, target: Target):
        self.t = target
        self.folder: Path | None = None
        self.path: Path | None = None
        self.name = ""
        self.fh = None
        self.size = 0
        self.files = 0
        self.header_bytes = 0
        self._field, self._value, self._headers = b"", b"", {}

    def _too_large(self) -> _Refused:
        return _Refused(413, InputError(Problem(self.t.what, self.name or "the upload",
                                                f"a file of at most {_size(self.t.limit)} "
                                                f"(this one is larger)")))

    # python-multipart's callbacks -------------------------------------------------------------------------------
    def on_part_begin(self):
        self._headers = {}

    def on_header_field(self, data, start, end):
        self._field += data[start:end]
        self._count(end - start)

    def on_header_value(self, data, start, end):
        self._value += data[start:end]
        self._count(end - start)

    def _count(self, n):
        self.header_bytes += n
        if self.header_bytes > _HEADER_BYTES:
            raise _Refused(400, InputError(Problem(self.t.what, "part headers of more than 16 kB",
                                                   "one file as the page sends it")))

    def on_header_end(self):
        self._headers[self._field.decode("latin-1").lower()] = self._value
        self._field, self._value = b"", b""

    def on_headers_finished(self):
        from python_multipart.multipart import parse_options_header
        _, opts = parse_options_header(self._headers.get("content-disposition", b""))
        if b"filename" not in opts:
            self.fh = None  # a plain form field: skipped
            return
        self.files += 1
        if self.files > 1:
            raise _Refused(400, InputError(Problem(self.t.what, "several files", "one file at a time")))
        raw = opts[b"filename"].decode("utf-8", errors="replace")
        name = safe_name(raw)
        if len(name) > NAME_CHARS or len(name.encode("utf-8")) > _NAME_BYTES:
            raise _Refused(400, InputError(Problem(f"{self.t.what} name", short(name, 60),
                                                   f"a file name of at most {NAME_CHARS} characters "
                                                   f"(this one has {len(name)}): rename the file")))
        self.name = name or "upload"
        self.folder = Path(self.t.folder) / f"upload-{secrets.token_hex(6)}"
        self.folder.mkdir(parents=True)
        self.path = self.folder / self.name
        self.fh = open(self.path, "xb")  # noqa: SIM115 - closed in on_part_end or discard()

    def on_part_data(self, data, start, end):
        if self.fh is None:
            return
        self.size += end - start
        if self.size > self.t.limit:
            raise self._too_large()
        self.fh.write(data[start:end])

    def on_part_end(self):
        if self.fh is not None:
            self.fh.close()
            self.fh = None

    def discard(self) -> None:
        """Remove what was written (at once: never left for the server's end)."""
        if self.fh is not None:
            self.fh.close()
            self.fh = None
        if self.folder is not None:
            shutil.rmtree(self.folder, ignore_errors=True)


async def receive(request) -> tuple[int, str]:
    """The upload endpoint (a Starlette route): ``(status, text)`` of the answer; the page is told either way."""
    from python_multipart.multipart import MultipartParser, parse_options_header

    from synth.ui.guard import TooLarge
    target = _TARGETS.get(request.path_params.get("key", ""))
    if target is None:
        return 404, "no such upload box (the page was closed or reloaded: reload it)"
    f = _File(target)
    try:
        length = request.headers.get("content-length")
        if length is not None and length.isdigit() and int(length) > target.limit + OVERHEAD:
            f.name = "the upload"
            raise _Refused(413, InputError(Problem(target.what, f"a file of {_size(int(length))}",
                                                   f"a file of at most {_size(target.limit)}")))
        ctype, opts = parse_options_header(request.headers.get("content-type", ""))
        if ctype != b"multipart/form-data" or not opts.get(b"boundary"):
            raise _Refused(400, InputError(Problem(target.what, ctype.decode("latin-1") or "no content type",
                                                   "a file sent as multipart/form-data (as the page sends it)")))
        parser = MultipartParser(opts[b"boundary"], {
            "on_part_begin": f.on_part_begin, "on_header_field": f.on_header_field,
            "on_header_value": f.on_header_value, "on_header_end": f.on_header_end,
            "on_headers_finished": f.on_headers_finished, "on_part_data": f.on_part_data,
            "on_part_end": f.on_part_end}, max_size=target.limit + OVERHEAD)
        seen = 0
        async for chunk in request.stream():
            seen += len(chunk)
            if seen > target.limit + OVERHEAD:
                raise f._too_large()
            parser.write(chunk)
        parser.finalize()
        if f.path is None or f.fh is not None:
            raise _Refused(400, InputError(Problem(target.what, "no complete file", "one file (the upload was cut)")))
    except TooLarge:  # the server's own count (synth.ui.guard), a step ahead of the parser's
        f.discard()
        r = f._too_large()
        target.refused(r.exc)
        return r.status, str(r.exc)
    except _Refused as r:
        f.discard()
        target.refused(r.exc)
        return r.status, str(r.exc)
    except Exception as exc:  # noqa: BLE001 - a malformed body (python-multipart's errors), a disconnect, a full disk
        f.discard()
        from synth.ui.messages import message_of
        e = InputError(Problem(target.what, f.name or "the upload", f"a file the page sends whole ({message_of(exc)})"))
        target.refused(e)
        return 400, str(e)
    target.done(f.path, f.name)
    return 200, "received"
