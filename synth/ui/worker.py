"""The pages' heavy work in worker processes: the server's own process stays free to answer the page.

The 3D model (CadQuery and OpenCascade hold Python's GIL for the whole of a build), the graphs and pictures
(matplotlib), the report and its PDF, and a capability study take from 0.5 to 20 s of CPU. Run in the server's
process, even in a thread, they held the GIL so long that the checks of an edit reached the page 0.72 s late
(issue 35) and the first import of CadQuery (2 to 10 s) froze the page. Here each kind of work has its **lane**:
one worker process (``python -m synth.ui.worker``) that runs its tasks one after the other and keeps what it
built (the CAD models by the design's hash, the graphs by the result's) for the next task:

* ``design``: the graphs, the report and its PDF, the capability studies;
* ``cad``: the 3D model, its STL, STEP, pictures and geometric checks.

A lane's process is started on first use (or by :func:`warm`), connects back to the server over a local socket
that asks for a per-launch key (``multiprocessing.connection``'s HMAC challenge: no other program of the
machine can hand it work), and ends with the server: it is a child that dies with its parent (Linux's
``PR_SET_PDEATHSIG``), ignores Ctrl-C (the server stops it) and is terminated by :func:`stop_all`. A task that
fails raises here, in the page's coroutine, as it would have in the server (an :class:`~synth.errors.InputError`
with its problems, anything else an error of its type and text); a process that dies fails its running task with
a message and is started again for the next one.

A task may carry a ``coalesce`` key: a pending task with the same key is dropped for the newer one (a prefetch of
graphs for a result the page has already left).

>>> import asyncio
>>> lane = Lane("doctest")
>>> asyncio.run(lane.call("echo", 42)), lane.started
(42, True)
>>> lane.stop()
"""

from __future__ import annotations

import asyncio
import collections
import os
import secrets
import subprocess
import sys
import threading

from synth.ui.browser import PACKAGE_HOME  # a worker runs this same code, never another installed copy
from synth.ui.jobs import settle

__all__ = ["Lane", "lane", "warm", "stop_all", "WorkerError", "main"]


#: the environment variable that hands a worker its key (never the command line, which ``ps`` shows)
KEY_ENV = "SYNTH_UI_WORKER_KEY"
#: seconds a new worker process has to connect back (its interpreter's start and a few imports)
CONNECT_TIMEOUT_S = 120.0


class WorkerError(RuntimeError):
    """A worker's task failed with an error that is not an input error: its type's name and text."""

    def __init__(self, kind: str, text: str):
        super().__init__(text)
        self.kind = kind


class _Task:
    __slots__ = ("name", "args", "kw", "future", "loop", "coalesce")

    def __init__(self, name, args, kw, future, loop, coalesce):
        self.name, self.args, self.kw, self.future, self.loop, self.coalesce = name, args, kw, future, loop, coalesce


def _error_of(payload) -> BaseException:
    """The exception a worker reported: ``("input", [(field, value, accepted)])`` or ``("error", kind, text)``."""
    from synth.errors import InputError, Problem
    if payload[0] == "input":
        return InputError([Problem(*p) for p in payload[1]])
    return WorkerError(payload[1], payload[2])


class Lane:
    """One worker process and its queue of tasks (see the module docstring)."""

    def __init__(self, name: str):
        self.name = name
        self._queue: collections.deque[_Task] = collections.deque()
        self._cv = threading.Condition()
        self._proc: subprocess.Popen | None = None
        self._thread: threading.Thread | None = None
        self._stopped = False
        self.busy = False
        self.started = False
        self.tasks_done = 0

    # --- the server's side ----------------------------------------------------------------------------------------
    def submit(self, name: str, *args, coalesce: str | None = None, **kw) -> asyncio.Future:
        """Queue task ``name`` (a function of :mod:`synth.ui.work`) from a coroutine; returns its future."""
        loop = asyncio.get_running_loop()
        fut = loop.create_future()
        self._put(_Task(name, args, kw, fut, loop, coalesce))
        return fut

    async def call(self, name: str, *args, coalesce: str | None = None, **kw):
        """``await`` task ``name``'s result (its error raised here)."""
        return await self.submit(name, *args, coalesce=coalesce, **kw)

    def submit_threadsafe(self, name: str, *args, **kw):
        """Queue task ``name`` from any thread, without an event loop; returns a :class:`concurrent.futures.Future`."""
        import concurrent.futures
        fut = concurrent.futures.Future()
        self._put(_Task(name, args, kw, fut, None, None))
        return fut

    def _put(self, task: _Task) -> None:
        with self._cv:
            if self._stopped:
                raise RuntimeError(f"the {self.name} worker is stopped")
            if task.coalesce is not None:
                for old in [t for t in self._queue if t.coalesce == task.coalesce]:
                    self._queue.remove(old)
                    self._resolve(old, True, None)
            self._queue.append(task)
            self._cv.notify()
            if self._thread is None:
                self._thread = threading.Thread(target=self._run, daemon=True, name=f"synth-ui-lane-{self.name}")
                self._thread.start()

    def pending(self) -> int:
        with self._cv:
            return len(self._queue) + (1 if self.busy else 0)

    @staticmethod
    def _resolve(task: _Task, ok: bool, value) -> None:
        if task.loop is None:
            if not task.future.done():
                (task.future.set_result if ok else task.future.set_exception)(value)
            return
        try:
            task.loop.call_soon_threadsafe(settle, task.future, ok, value)
        except RuntimeError:  # the loop is closed: the server stopped
            pass

    def _start(self):
        """Start the process and return its connection (called in the lane's thread)."""
        from multiprocessing.connection import Listener
        key = secrets.token_bytes(32)
        listener = Listener(("127.0.0.1", 0), authkey=key)
        try:
            env = {**os.environ, KEY_ENV: key.hex(), "PYTHONPATH": str(PACKAGE_HOME) + os.pathsep
                   + os.environ.get("PYTHONPATH", "")}
            env.pop("PYTEST_CURRENT_TEST", None)
            host, port = listener.address
            safe = ["-P"] if sys.version_info >= (3, 11) else []  # never a ``synth`` folder of the working folder
            self._proc = subprocess.Popen([sys.executable, *safe, "-m", "synth.ui.worker", self.name, host, str(port)],
                                          env=env, stdin=subprocess.DEVNULL)
            sock = getattr(getattr(listener, "_listener", None), "_socket", None)
            if sock is not None:  # a process that never connects (it failed to start) is an error, not a hang
                sock.settimeout(CONNECT_TIMEOUT_S)
            conn = listener.accept()
        finally:
            listener.close()
        self.started = True
        return conn

    def _run(self) -> None:
        conn = None
        while True:
            with self._cv:
                while not self._queue and not self._stopped:
                    self._cv.wait()
                if self._stopped:
                    break
                task = self._queue.popleft()
                self.busy = True
            try:
                if conn is None:
                    conn = self._start()
                conn.send((task.name, task.args, task.kw))
                ok, payload = conn.recv()
                self._resolve(task, ok, payload if ok else _error_of(payload))
                self.tasks_done += 1
            except (EOFError, OSError) as exc:  # the process died (or never connected): a message, then anew
                code = self._proc.poll() if self._proc is not None else None
                if not self._stopped:
                    self._resolve(task, False, WorkerError(
                        "WorkerEnded", f"the {self.name} worker process ended (exit code {code}; {type(exc).__name__})"
                                       f" while running {task.name}"))
                conn = None
                self._kill()
            except Exception as exc:  # noqa: BLE001 - e.g. an argument that cannot be pickled: that task's error
                self._resolve(task, False, exc)
            finally:
                with self._cv:
                    self.busy = False
        if conn is not None:
            conn.close()

    def _kill(self) -> None:
        p, self._proc = self._proc, None
        if p is not None and p.poll() is None:
            p.terminate()
            try:
                p.wait(2)
            except subprocess.TimeoutExpired:
                p.kill()

    def stop(self) -> None:
        """End the process and fail the tasks still queued."""
        with self._cv:
            self._stopped = True
            queued, self._queue = list(self._queue), collections.deque()
            self._cv.notify_all()
        for t in queued:
            self._resolve(t, False, WorkerError("Stopped", "stopped: the server is stopping"))
        self._kill()


_LANES: dict[str, Lane] = {}
_LOCK = threading.Lock()


def lane(name: str) -> Lane:
    """The lane ``name`` (``design`` or ``cad``), made on first use."""
    with _LOCK:
        if name not in _LANES or _LANES[name]._stopped:
            _LANES[name] = Lane(name)
        return _LANES[name]


def warm(name: str) -> None:
    """Start lane ``name``'s process now and import what its tasks need (:func:`synth.ui.work.warm`)."""
    lane(name).submit_threadsafe("warm", name)


def stop_all() -> None:
    """End every lane's process (the server stops)."""
    with _LOCK:
        lanes = list(_LANES.values())
    for ln in lanes:
        ln.stop()


# --- the worker's side ----------------------------------------------------------------------------------------------
def _die_with_parent() -> None:
    """Linux: this process gets SIGTERM when the server's process ends, however it ends."""
    try:
        import ctypes
        import signal
        libc = ctypes.CDLL(None, use_errno=True)
        libc.prctl(1, int(signal.SIGTERM), 0, 0, 0)  # PR_SET_PDEATHSIG
    except (OSError, AttributeError):  # not Linux: the closed connection ends the loop below
        pass


def _payload_of(exc: BaseException):
    from synth.errors import InputError
    if isinstance(exc, InputError):
        return ("input", [(p.field, p.value if _picklable(p.value) else repr(p.value), p.accepted)
                          for p in exc.problems])
    return ("error", type(exc).__name__, " ".join(str(exc).split())[:2000])


def _picklable(v) -> bool:
    import pickle
    try:
        pickle.dumps(v)
        return True
    except Exception:  # noqa: BLE001 - anything pickle refuses
        return False


#: the niceness a worker adds to its own (POSIX): the server's answers to the page (an edit's checks) and the
#: browser's drawing take a busy machine's cores before a model build, a graph or a print
NICE = 5
#: tasks that run at the server's priority when they come first: the launch's synthesis, which the first page waits
#: for (:class:`synth.ui.launch.Launch`); the worker takes :data:`NICE` before its first other task
PROMPT = ("open_input", "synthesise")


def _yield_cpu() -> None:
    try:
        os.nice(NICE)
    except (AttributeError, OSError):  # no os.nice (Windows), or not allowed: the default priority
        pass


def main(argv: list[str] | None = None) -> int:
    """The worker's loop: ``python -m synth.ui.worker NAME HOST PORT`` with the key in ``SYNTH_UI_WORKER_KEY``."""
    import signal
    from multiprocessing.connection import Client
    argv = sys.argv[1:] if argv is None else argv
    signal.signal(signal.SIGINT, signal.SIG_IGN)  # Ctrl-C reaches the whole process group: the server stops us
    _die_with_parent()
    key = bytes.fromhex(os.environ.pop(KEY_ENV))
    conn = Client((argv[1], int(argv[2])), authkey=key)
    from synth import plugins
    from synth.ui import work
    niced = False
    while True:
        try:
            name, args, kw = conn.recv()
        except (EOFError, OSError):
            return 0
        if not niced and name not in PROMPT:
            _yield_cpu()
            niced = True
        try:
            plugins.load()  # the installed plug-ins' declarations (read once; a broken one is each answer's error)
            out = (True, getattr(work, name)(*args, **kw))
        except BaseException as exc:  # noqa: BLE001 - every error goes back to the page that asked
            out = (False, _payload_of(exc))
        try:
            conn.send(out)
        except Exception as exc:  # noqa: BLE001 - a result that cannot be sent: its error instead
            conn.send((False, _payload_of(exc)))


if __name__ == "__main__":
    sys.exit(main())
