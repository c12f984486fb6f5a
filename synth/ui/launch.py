"""The synthesis of the input ``synth ui`` opens, made while the browser loads the page.

The server's start is imports (NiceGUI, FastAPI, socket.io, then synth's evaluator and optimiser) and the synthesis
of the input it opens. The server listens as soon as NiceGUI is imported; :meth:`Launch.start` (run when the server
starts) then imports the rest of synth and synthesises in a thread, while the browser loads the page's scripts (about
1 s of the browser's own processes); the first design page whose input is that one takes a copy of its result
instead of synthesising, and every later page too (a new tab opens at once). A thread, not a second process: a
process would import numpy and the evaluator again, which a machine busy with other work pays in full (measured:
``docs/sections/ui.md``, "Speed").

>>> import asyncio
>>> from synth.ui.session import DesignSession, default_values
>>> launch = Launch(default_values(), "default")
>>> launch.start()
>>> r = asyncio.run(launch.result_for(DesignSession(default_values())))
>>> r.verdict, r is launch.future.result()[1]
('pass', False)
"""

from __future__ import annotations

import asyncio
import concurrent.futures
import copy
import threading

__all__ = ["Launch"]


class Launch:
    """The synthesis of ``values`` under ``rules`` (see the module docstring)."""

    def __init__(self, values: dict, source: str, rules=None):
        self.values, self.source, self.rules = values, source, rules
        self.future: concurrent.futures.Future = concurrent.futures.Future()
        self.warmed = False

    def start(self) -> None:
        """Synthesise in a daemon thread (the server's ``on_startup``: it listens already)."""
        threading.Thread(target=self._run, daemon=True, name="synth-ui-launch").start()

    def _run(self) -> None:
        from synth.ui.trace import mark
        mark("launch started (the server listens)")
        try:
            from synth.ui.session import DesignSession
            s = DesignSession(self.values, source=self.source, rules=self.rules)
            call = s.synthesis_call() if s.input is not None else None
            import synth.ui.design_page  # noqa: F401 - the page's modules, imported while the browser loads
            mark("launch: the input validated, the page's modules imported")
            result = s.synthesise() if call is not None else None
            mark("launch: synthesised")
            self.future.set_result((call, result))
        except BaseException as exc:  # noqa: BLE001 - the page's own synthesis says what is wrong, if anything
            self.future.set_exception(exc)

    async def result_for(self, session):
        """A copy of the launch's result when ``session`` asks for the same synthesis; None otherwise, or when the
        launch failed (the page then synthesises itself and says why)."""
        if session.input is None:
            return None
        try:
            call, result = await asyncio.wrap_future(self.future)
        except Exception:  # noqa: BLE001 - see above
            return None
        if result is None or call != session.synthesis_call():
            return None
        return copy.deepcopy(result)
