"""The synthesis of the input ``synth ui`` opens, started before the server imports NiceGUI.

The server's start is mostly imports (NiceGUI, FastAPI, socket.io: about half of it) and the synthesis of the
input it opens (the evaluator, the optimiser); one after the other they are the sum, on two cores they need not be.
:func:`start` hands the synthesis to the ``design`` worker (:mod:`synth.ui.worker`) before the server imports
NiceGUI; the first design page whose input is that one takes a copy of its result instead of synthesising
(every later page too: a new tab opens at once). This module imports no NiceGUI.
"""

from __future__ import annotations

import asyncio
import copy

from synth.ui import worker

__all__ = ["Launch"]


class Launch:
    """The synthesis of the input the server opened, started in the ``design`` worker before the server imported
    NiceGUI (the two use two cores): a page whose input is that one takes its result instead of synthesising."""

    def __init__(self, call: tuple, future):
        self.call, self.future = call, future
        self.warmed = False

    @classmethod
    def start(cls, session) -> "Launch | None":
        """The launch of ``session``'s synthesis (None for an input that is not valid: the page says why)."""
        if session.input is None:
            return None
        call = session.synthesis_call()
        return cls(call, worker.lane("design").submit_threadsafe("synthesise", *call))

    async def result_for(self, session):
        """A copy of the launch's result when ``session`` asks for the same synthesis; None otherwise or when the
        worker failed (the page then synthesises itself)."""
        if session.input is None or session.synthesis_call() != self.call:
            return None
        try:
            return copy.deepcopy(await asyncio.wrap_future(self.future))
        except Exception:  # noqa: BLE001 - the worker could not: the page's own synthesis says why, if anything
            return None
