"""A tiny progress bar for long runs: drawn on a terminal, silent when piped.

No dependency: the bar is drawn on ``sys.stderr`` with carriage returns when
that stream is a TTY, and nothing at all is written otherwise (so piped or
redirected output, CI logs and tests stay clean). ``SYNTH_PROGRESS=0`` turns it
off on a terminal too, ``SYNTH_PROGRESS=1`` forces it on.

Use it around a loop, or as a context with explicit updates::

    for item in progress(items, "graphs"):
        ...
    with Progress(total=n_steps, desc="wear integration") as bar:
        bar.update(1)

>>> import io
>>> sink = io.StringIO()                       # not a TTY: stays quiet
>>> list(progress(range(3), "x", stream=sink)), sink.getvalue()
([0, 1, 2], '')
"""

from __future__ import annotations

import os
import sys
import time

__all__ = ["Progress", "progress", "enabled"]


def enabled(stream=None) -> bool:
    """Whether a bar is drawn on ``stream`` (default ``sys.stderr``)."""
    flag = os.environ.get("SYNTH_PROGRESS", "")
    if flag in ("0", "1"):
        return flag == "1"
    stream = sys.stderr if stream is None else stream
    try:
        return bool(stream.isatty())
    except (AttributeError, ValueError):
        return False


class Progress:
    """A progress bar of ``total`` steps (``total=None``: a counter without a bar)."""

    width = 30

    def __init__(self, total: int | None = None, desc: str = "", stream=None, min_interval_s: float = 0.1):
        self.total, self.desc, self.n = total, desc, 0
        self.stream = sys.stderr if stream is None else stream
        self.on = enabled(self.stream)
        self._min, self._last, self._t0 = min_interval_s, 0.0, time.monotonic()

    def update(self, n: int = 1, note: str = "") -> None:
        self.n += n
        if not self.on:
            return
        now = time.monotonic()
        if now - self._last < self._min and (self.total is None or self.n < self.total):
            return
        self._last = now
        if self.total:
            frac = min(self.n / self.total, 1.0)
            full = int(round(frac * self.width))
            bar = f"[{'#' * full}{'.' * (self.width - full)}] {self.n}/{self.total}"
        else:
            bar = f"{self.n}"
        text = f"\r{self.desc}: {bar} {now - self._t0:5.1f} s {note}"[:200]
        self.stream.write(text.ljust(80))
        self.stream.flush()

    def close(self) -> None:
        if self.on:
            self.stream.write("\n")
            self.stream.flush()
            self.on = False

    def __enter__(self) -> "Progress":
        return self

    def __exit__(self, *exc) -> None:
        self.close()


def progress(iterable, desc: str = "", total: int | None = None, stream=None):
    """Yield the items of ``iterable`` while drawing a bar (on a TTY only)."""
    if total is None:
        try:
            total = len(iterable)
        except TypeError:
            total = None
    with Progress(total, desc, stream) as bar:
        for item in iterable:
            yield item
            bar.update(1)
