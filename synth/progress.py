"""Progress bars for long runs: drawn on a terminal, a ``tqdm.auto`` bar in Jupyter, silent when piped.

On a terminal the bar is drawn on ``sys.stderr`` with carriage returns (no
dependency); nothing at all is written when that stream is not a TTY (so
piped or redirected output, CI logs and tests stay clean). In a Jupyter
kernel, where stderr is no terminal, the bar is ``tqdm.auto``'s (a widget
where ipywidgets is installed, else text) when tqdm is installed (an
optional dependency: ``pip install synth[notebook]``). ``SYNTH_PROGRESS=0``
turns every bar off, ``SYNTH_PROGRESS=1`` forces the terminal bar on,
``SYNTH_PROGRESS=tqdm`` forces the tqdm one.

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

__all__ = ["Progress", "progress", "enabled", "in_notebook", "phase"]


def in_notebook() -> bool:
    """Whether this process is a Jupyter kernel (IPython's ``ZMQInteractiveShell``); IPython is never imported."""
    ipython = sys.modules.get("IPython")
    if ipython is None:
        return False
    try:
        shell = ipython.get_ipython()
    except Exception:  # noqa: BLE001 - a half-imported IPython: no notebook
        return False
    return type(shell).__name__ == "ZMQInteractiveShell"


def _tqdm_bar(total, desc, stream):
    """A ``tqdm.auto`` bar when asked for (``SYNTH_PROGRESS=tqdm``) or in a notebook, tqdm installed; else None."""
    flag = os.environ.get("SYNTH_PROGRESS", "")
    if flag == "0" or not (flag == "tqdm" or (flag != "1" and in_notebook())):
        return None
    try:
        from tqdm.auto import tqdm
    except ImportError:
        return None
    return tqdm(total=total, desc=desc, file=stream, leave=True, dynamic_ncols=True)


def enabled(stream=None) -> bool:
    """Whether the terminal bar is drawn on ``stream`` (default ``sys.stderr``)."""
    flag = os.environ.get("SYNTH_PROGRESS", "")
    if flag in ("0", "1", "tqdm"):
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
        self._tqdm = _tqdm_bar(total, desc, stream)
        self.on = self._tqdm is None and enabled(self.stream)
        self._min, self._last, self._t0 = min_interval_s, 0.0, time.monotonic()

    def update(self, n: int = 1, note: str = "") -> None:
        self.n += n
        if self._tqdm is not None:
            if note:
                self._tqdm.set_postfix_str(note, refresh=False)
            self._tqdm.update(n)
            return
        if not self.on:
            return
        now = time.monotonic()
        if self._last and now - self._last < self._min and (self.total is None or self.n < self.total):
            return
        self._last = now
        if self.total:
            frac = min(self.n / self.total, 1.0)
            full = int(round(frac * self.width))
            bar = f"[{'#' * full}{'.' * (self.width - full)}] {self.n}/{self.total}"
        else:
            bar = f"{self.n}" if self.n else ""  # a phase without steps: its time only
        text = f"\r{self.desc}: {bar} {now - self._t0:5.1f} s {note}"[:200]
        self.stream.write(text.ljust(80))
        self.stream.flush()

    def close(self) -> None:
        if self._tqdm is not None:
            self._tqdm.close()
            self._tqdm = None
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


class phase:  # noqa: N801 - used as a context manager, like Progress
    """A phase without steps (a solver call): its name and the elapsed time, redrawn every ``every_s`` seconds
    while the block runs (on a terminal; quiet elsewhere, as :class:`Progress`)::

        with phase("synth rationalise: platform MILP"):
            solve()
    """

    def __init__(self, desc: str, stream=None, every_s: float = 0.5):
        import threading
        self.bar = Progress(total=None, desc=desc, stream=stream, min_interval_s=every_s)
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._tick, args=(every_s,), daemon=True)

    def _tick(self, every_s: float) -> None:
        while not self._stop.wait(every_s):
            self.bar.update(0, "running")

    def __enter__(self) -> "phase":
        if self.bar.on or self.bar._tqdm is not None:
            self.bar.update(0, "running")
            self._thread.start()
        return self

    def __exit__(self, *exc) -> None:
        self._stop.set()
        if self._thread.is_alive():
            self._thread.join()
        self.bar._last = 0.0
        self.bar.update(0, "done")
        self.bar.close()
