"""Where the server's time goes: ``SYNTH_UI_TRACE=1`` prints one line per milestone of a page to stderr.

``synth ui: trace <what> at <unix time> cpu <s>``: the wall clock (to compare with the time the process was
started, as ``benchmarks/bench_ui.py`` does) and the process's CPU seconds so far (every thread). Off by default: a
milestone then costs one dictionary lookup.

>>> mark("nothing")  # off unless SYNTH_UI_TRACE is set
"""

from __future__ import annotations

import os
import sys
import time

__all__ = ["mark", "ENABLED"]

ENABLED = os.environ.get("SYNTH_UI_TRACE", "") not in ("", "0")


def mark(what: str) -> None:
    if ENABLED:
        sys.stderr.write(f"synth ui: trace {what} at {time.time():.3f} cpu {time.process_time():.3f}\n")
        sys.stderr.flush()
