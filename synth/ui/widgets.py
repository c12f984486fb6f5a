"""What both pages of ``synth ui`` build with: the header, messages, upload boxes, downloads, a page's jobs.

Every error of a handler becomes a message in the page worded as the command line words it
(:func:`refused`, :mod:`synth.ui.messages`); an upload box posts to its own streaming URL (:func:`upload_box`,
:mod:`synth.ui.uploads`); a file is offered under its own name (:func:`download`).
"""

from __future__ import annotations

import base64
import logging
import math
from pathlib import Path

from nicegui import app, background_tasks, ui

from synth.errors import InputError, Problem
from synth.io.limits import short
from synth.ui import uploads
from synth.ui.guard import is_loopback
from synth.ui.messages import message_of

__all__ = ["refused", "in_page", "upload_box", "count", "png", "header", "stem", "download", "CSS", "FILES_URL"]

#: the URL under which the server serves its own folder (3D parts, pictures)
FILES_URL = "/synth-files"

_log = logging.getLogger("synth.ui")

CSS = """
.synth-ui table{border-collapse:collapse;font-size:.85em;width:100%}
.synth-ui th,.synth-ui td{border:1px solid #c8c8c8;padding:2px 6px;text-align:left;vertical-align:top}
.synth-ui thead th{background:#d9e2ec}
.synth-ui td.num{text-align:right;font-variant-numeric:tabular-nums;white-space:nowrap}
.synth-ui tr.group td{background:#bdd7ee;font-weight:bold}
.synth-ui table.kv th{background:#eef2f6;width:45%}
.synth-ui table.compare th{background:#eef2f6;white-space:nowrap}
.synth-ui table.compare td.differs{background:#fff2cc;font-weight:600}
.synth-ui figure{display:inline-block;margin:.4em;border:3px solid #bbb;padding:4px;vertical-align:top;width:47%}
.synth-ui figure[data-verdict=pass]{border-color:#2e7d32} .synth-ui figure[data-verdict=fail]{border-color:#c62828}
.synth-ui figure[data-verdict=warning]{border-color:#ef6c00}
.synth-ui figure img{width:100%} .synth-ui figcaption{font-size:.85em}
.synth-ui .small{font-size:.85em;color:#555}
.synth-ui h2{font-size:1.4em;line-height:1.6;margin:.6em 0 .2em;font-weight:500}
.synth-ui h3{font-size:1.15em;line-height:1.5;margin:.5em 0 .2em;font-weight:500}
"""


def refused(exc: BaseException, what: str = "synth: invalid input") -> None:
    """``exc`` worded as the command line words it (:func:`synth.ui.messages.message_of`), in a notification that
    stays until closed."""
    if not isinstance(exc, InputError):
        what = "synth ui"
        _log.warning("%s", message_of(exc), exc_info=exc)
    ui.notify(what + ": " + message_of(exc), type="negative", multi_line=True, timeout=0, close_button=True)


def in_page(element, work, *args) -> None:
    """Schedule ``await work(*args)`` in ``element``'s page (a route's work shown there); an error is a message."""
    async def task():
        with element:
            try:
                await work(*args)
            except Exception as exc:  # noqa: BLE001 - every error a message in the page
                refused(exc)
    background_tasks.create(task(), name=f"synth ui: {getattr(work, '__name__', 'work')}")


async def _refuse_async(exc: InputError, what: str) -> None:
    refused(exc, what)


def upload_box(label: str, accept: str, limit: int, folder: Path, what: str, done) -> "ui.upload":
    """An upload box posting to its own streaming URL (:mod:`synth.ui.uploads`), never NiceGUI's route (which reads
    the whole request before a handler sees it). ``done(path, name)``: a coroutine function run in the page."""
    box = ui.upload(label=label, auto_upload=True, max_file_size=limit,
                    on_rejected=lambda: ui.notify(f"synth: {what}: a file of at most {limit / 2**20:g} MB",
                                                  type="negative", multi_line=True, timeout=0, close_button=True))
    box.props(f"accept={accept} flat bordered")
    target = uploads.Target(folder, limit, what, done=lambda path, name: in_page(box, done, path, name),
                            refused=lambda exc: in_page(box, _refuse_async, exc, "synth: " + what + " refused"))
    app.remove_route(box.props["url"])  # NiceGUI's own route for this box: nothing posts there
    box.props["url"] = uploads.register(target)
    box._synth_target = target  # the page holds its upload target (the registry holds it weakly)
    return box


def count(value, field: str, hi: int, lo: int = 1) -> int:
    """A count from a number box (NaN, 2.5, 1e300, text refused with what is accepted)."""
    ok = (isinstance(value, (int, float)) and not isinstance(value, bool) and math.isfinite(value)
          and float(value).is_integer() and lo <= value <= hi)
    if not ok:
        raise InputError(Problem(field, short(value), f"an integer in [{lo}, {hi}]"))
    return int(value)


def number(value, field: str, *, optional: bool = False) -> float | None:
    """A finite number from a number box (empty: None when ``optional``)."""
    if value is None or value == "":
        if optional:
            return None
        raise InputError(Problem(field, None, "a number"))
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
        raise InputError(Problem(field, short(value), "a finite number"))
    return float(value)


def png(path_or_bytes) -> str:
    data = path_or_bytes if isinstance(path_or_bytes, bytes) else Path(path_or_bytes).read_bytes()
    return "data:image/png;base64," + base64.b64encode(data).decode("ascii")


def header(host: str, port: int) -> None:
    with ui.header().classes("items-center bg-blue-10 q-py-xs"):
        ui.label("synth").classes("text-h6 text-weight-bold")
        ui.link("Design", "/").classes("text-white").props("data-testid=nav-design")
        ui.link("Portfolio", "/portfolio").classes("text-white").props("data-testid=nav-portfolio")
        ui.space()
        where = "local only" if is_loopback(host) else "REACHABLE FROM THE NETWORK, with its token"
        shown = f"[{host}]" if ":" in host else host
        ui.label(f"serving http://{shown}:{port}/ ({where}: bound to {host})").classes("text-caption")


def stem(source: str) -> str:
    """A file-name stem of a source's name (letters, digits, ``-_.``; at most 60 characters)."""
    s = Path(source or "design").stem or "design"
    return "".join(c if c.isalnum() or c in "-_." else "_" for c in s)[:60]


def download(path: str | Path, name: str | None = None) -> None:
    """Offer the file ``path`` to the browser under ``name`` (default: its own)."""
    ui.download.file(Path(path), name or Path(path).name)
