"""The pages' long work (a synthesis, a screening, a platform, the 3D model, a report) off the server's loop.

Each job runs in a thread of its own that never holds the server up: a daemon thread, so that SIGTERM (or
Ctrl-C) ends a running job with the server, which exits 143 (130) at once as the command line does. NiceGUI's
``run.io_bound`` pool is joined when the interpreter exits: a 100,000-application screening kept the server
alive for minutes after SIGTERM (issue 39). :data:`STOP` is set when the server stops; a job that works in
steps (the portfolio's slices) checks it between steps (:func:`check`) and ends with :class:`Stopped`.

>>> import asyncio
>>> asyncio.run(run(sum, [1, 2, 3]))
6
"""

from __future__ import annotations

import asyncio
import threading

__all__ = ["run", "STOP", "Stopped", "check", "running", "settle"]

#: set when the server stops: jobs that work in steps end at the next one
STOP = threading.Event()

_RUNNING: set[threading.Thread] = set()


class Stopped(Exception):
    """The server is stopping: the job was ended between two steps."""


def check() -> None:
    """Raise :class:`Stopped` when the server is stopping (a job calls it between its steps)."""
    if STOP.is_set():
        raise Stopped()


def running() -> int:
    """Jobs running now."""
    return len(_RUNNING)


def settle(fut: asyncio.Future, ok: bool, value) -> None:
    """Give ``fut`` its result (``ok``) or exception, unless it is done already (cancelled): the loop's callback of a
    job finished in a thread or a worker process."""
    if fut.done():
        return
    if ok:
        fut.set_result(value)
    else:
        fut.set_exception(value)


async def run(fn, *args, **kw):
    """``fn(*args, **kw)`` in a daemon thread; its result, or its exception raised here."""
    check()
    loop = asyncio.get_running_loop()
    fut = loop.create_future()

    def work():
        try:
            out, ok = fn(*args, **kw), True
        except BaseException as exc:  # noqa: BLE001 - handed to the awaiting page, which words it
            out, ok = exc, False
        finally:
            _RUNNING.discard(threading.current_thread())
        try:
            loop.call_soon_threadsafe(settle, fut, ok, out)
        except RuntimeError:  # the loop is closed: the server stopped while the job ran
            pass

    t = threading.Thread(target=work, daemon=True, name=f"synth-ui-{getattr(fn, '__name__', 'job')}")
    _RUNNING.add(t)
    t.start()
    return await fut
