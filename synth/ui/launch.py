"""The synthesis of the input ``synth ui`` opens, made in a worker process while the server starts.

The server's start is imports (NiceGUI, FastAPI, socket.io; synth's evaluator with numpy and pandas) and the
synthesis of the input it opens. :meth:`Launch.submit` (called before NiceGUI is imported) hands that synthesis to
the design lane's worker process (:mod:`synth.ui.worker`, :func:`synth.ui.work.synthesise`): its imports and
the synthesis run on a second core while the server imports NiceGUI and the browser loads the page. The worker is
the one the page's graphs, report and capability use later, so no process is started for it alone; it takes its
niceness only after this task (:data:`synth.ui.worker.PROMPT`). :meth:`Launch.start` (run when the server listens)
imports the page's modules in a thread while the browser loads the page's scripts. The first design page whose
input is that one takes a copy of the result instead of synthesising, and every later page too (a new tab opens at
once); a launch that failed (the worker could not start) leaves the page to synthesise itself, and say why. A
second ``synth ui`` of the same input finds both answers on disk (:func:`synth.ui.work.launch_on_disk`) and reads
them in this process instead, with no worker beside NiceGUI's import.

>>> import asyncio
>>> from synth.ui.session import DesignSession, default_values
>>> launch = Launch(default_values(), "default")
>>> launch.submit()
>>> launch.start() if launch.here else None
>>> s = DesignSession(default_values(), opened=asyncio.run(launch.opened()))
>>> s.input == DesignSession(default_values()).input
True
>>> r = asyncio.run(launch.result_for(s))
>>> r.verdict, r is launch.future.result()[1]
('pass', False)
>>> from synth.ui import worker; worker.stop_all()
"""

from __future__ import annotations

import asyncio
import concurrent.futures
import copy
import threading

__all__ = ["Launch", "core_to_spare"]


def core_to_spare() -> bool:
    """Whether the machine has a core to spare for the worker now: the load average (1 minute) under twice the
    processors. Measured on 2 cores (``benchmarks/bench_ui.py --only-cold``, docs "the cold start with the launch in
    the design worker"): the worker won at load 3.7 (3.81 s against 5.05 s) and lost from load 4.2 (its repeated
    imports then wait for a core); without a load average (Windows) it is used."""
    import os
    try:
        return os.getloadavg()[0] < 2 * (os.cpu_count() or 1)
    except (AttributeError, OSError):
        return True


class Launch:
    """The synthesis of ``values`` under ``rules`` (see the module docstring)."""

    def __init__(self, values: dict, source: str, rules=None):
        self.values, self.source, self.rules = values, source, rules
        self.catalogs: list = []
        #: the worker's :func:`synth.ui.work.open_input` and :func:`synth.ui.work.synthesise` of the input
        self.opening: concurrent.futures.Future = concurrent.futures.Future()
        self.future: concurrent.futures.Future = concurrent.futures.Future()
        self.warmed = False
        self.here = False  # opened and synthesised in this process (:meth:`start`), not the worker

    def submit(self) -> None:
        """Hand the opening and the synthesis to the design lane's worker (its process starts now); leave them to
        :meth:`start`, in this process, when their answers are on disk (:func:`synth.ui.work.launch_on_disk`: a
        second ``synth ui`` of the same input, version and catalogs) or the machine has no core to spare
        (:func:`core_to_spare`). Reading the answers is a fraction of a second; a worker starting beside NiceGUI's
        import slows it by a third on a 2-core machine (the two share more than the cores), which made the cold
        start 0.35-0.45 s longer than reading them here (``benchmarks/bench_ui.py``, docs/sections/ui.md)."""
        from synth import catalog
        from synth.ui import work, worker
        from synth.ui.trace import mark
        try:
            self.catalogs = catalog.user_dirs()
            here = ("the input's answers on disk, read by the server"
                    if work.launch_on_disk(self.values, self.source, self.rules, self.catalogs)
                    else None if core_to_spare() else "the input left to the server (no core to spare)")
            if here:
                self.here = True
                mark("launch: " + here)
                return
            mark("launch: the input handed to the design worker")
            design = worker.lane("design")
            args = (self.values, self.source, self.rules, self.catalogs)
            self.opening = design.submit_threadsafe("open_input", *args)
            self.future = design.submit_threadsafe("synthesise", *args)
        except Exception as exc:  # noqa: BLE001 - the page's own synthesis says what is wrong, if anything
            for f in (self.opening, self.future):
                if not f.done():
                    f.set_exception(exc)

    async def opened(self) -> dict | None:
        """The state of a session opened on the launch's input (for
        :class:`~synth.ui.session.DesignSession`'s ``opened``), its drop-downs' designations kept for the form
        (:data:`synth.ui.form.KEYS`); None when the worker could not open it (the page then validates itself)."""
        try:
            got = await asyncio.wrap_future(self.opening)
        except Exception:  # noqa: BLE001 - see above
            return None
        from synth.ui import form
        dirs = tuple(self.catalogs)
        for name, keys in got["keys"].items():
            form.KEYS.setdefault((name, dirs), keys)
        return got["opened"]

    def start(self) -> None:
        """Import the page's modules in a daemon thread (the server's ``on_startup``: it listens already), and open
        and synthesise the input there when :meth:`submit` left them to this process."""
        threading.Thread(target=self._here if self.here else self._imports, daemon=True,
                         name="synth-ui-launch").start()

    def _here(self) -> None:
        """The worker's two tasks (:func:`synth.ui.work.open_input`, :func:`synth.ui.work.synthesise`) in this
        process, the page's modules imported between them."""
        from synth.ui import work
        args = (self.values, self.source, self.rules, self.catalogs)
        for future, task in ((self.opening, work.open_input), (self.future, work.synthesise)):
            try:
                future.set_result(task(*args))
            except BaseException as exc:  # noqa: BLE001 - the page's own synthesis says what is wrong, if anything
                future.set_exception(exc)
            if task is work.open_input:
                self._imports()

    def warm_server(self, parts: dict | None) -> None:
        """Validate the launch's input and verify ``parts`` (the design shown) in a daemon thread of the server: the
        catalogs, pandas and the evaluator an edit uses are loaded before the first edit (the first page took the
        worker's validation and synthesis, and loaded none of them)."""
        def run():
            from synth.ui.session import DesignSession
            from synth.ui.trace import mark
            try:
                s = DesignSession(self.values, source=self.source, rules=self.rules)
                if s.input is not None and parts:
                    s.verify(dict(parts))
            except Exception:  # noqa: BLE001 - a warm-up only: the edit that needs it says what is wrong
                pass
            mark("launch: the server's evaluator warm")
        threading.Thread(target=run, daemon=True, name="synth-ui-warm").start()

    @staticmethod
    def _imports() -> None:
        from synth.ui.trace import mark
        mark("launch: importing the page's modules (the server listens)")
        import synth.ui.design_page  # noqa: F401 - imported while the browser loads the page
        mark("launch: the page's modules imported")

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
