"""Every error of the server as a message: in the page for the engineer, one line in the server's output.

The command line turns an :class:`~synth.errors.InputError` into its problems (exit 2), a file-system refusal
into the path and why, and anything else into one line naming the error (exit 70, a bug of synth);
:func:`message_of` words the same for the page. :class:`OneLine` keeps the server's log to one line per error
(NiceGUI, socket.io and uvicorn log a traceback by default); ``SYNTH_DEBUG=1`` keeps the tracebacks, as on the
command line.

>>> from synth.errors import Problem
>>> message_of(InputError(Problem("row", "abc", "a row number in [0, 4]")))
"row: got 'abc'; accepted: a row number in [0, 4]"
>>> message_of(IndexError("list index out of range"))
'internal error: IndexError: list index out of range; please report it (SYNTH_DEBUG=1 shows the traceback in the server output)'
"""

from __future__ import annotations

import logging
import os

from synth.errors import InputError

__all__ = ["message_of", "OneLine", "quiet_tracebacks", "debug"]

#: the loggers of the server's parts that log tracebacks (each gets :class:`OneLine`)
LOGGERS = ("synth.ui", "nicegui", "engineio.server", "socketio.server", "uvicorn.error", "uvicorn.asgi", "asyncio")


def debug() -> bool:
    """``SYNTH_DEBUG`` set (not 0): tracebacks are shown, as on the command line."""
    return os.environ.get("SYNTH_DEBUG", "") not in ("", "0")


def message_of(exc: BaseException) -> str:
    """The message of ``exc`` as the command line words it (its problems; a path and why; an internal error)."""
    from synth.ui.jobs import Stopped
    if isinstance(exc, InputError):
        return "; ".join(str(p) for p in exc.problems)
    if isinstance(exc, Stopped):
        return "stopped: the server is stopping"
    if isinstance(exc, OSError):
        from synth.io.outputs import FS_ERRNOS, os_problem
        if exc.errno in FS_ERRNOS:
            return str(os_problem(exc, "path", verb="use"))
    text = " ".join(str(exc).split())[:300]
    return (f"internal error: {type(exc).__name__}: {text}; please report it (SYNTH_DEBUG=1 shows the traceback "
            "in the server output)")


class OneLine(logging.Filter):
    """A record with a traceback becomes one line: its message, the error's type and text."""

    def filter(self, record: logging.LogRecord) -> bool:
        if record.exc_info and record.exc_info[1] is not None and not debug():
            exc = record.exc_info[1]
            msg, text = " ".join(record.getMessage().split()), " ".join(str(exc).split())[:300]
            record.msg = msg if msg.endswith(text) else f"{msg}: {type(exc).__name__}: {text}"
            record.args = None
            record.exc_info = record.exc_text = None
            record.stack_info = None
        return True


def quiet_tracebacks() -> None:
    """:class:`OneLine` on every logger of the server's parts (:data:`LOGGERS`)."""
    for name in LOGGERS:
        lg = logging.getLogger(name)
        if not any(isinstance(f, OneLine) for f in lg.filters):
            lg.addFilter(OneLine())
