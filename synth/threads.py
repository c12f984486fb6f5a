"""Thread pools owned by synth (issue 36): how many threads BLAS, OpenMP and numba may run, set per task.

OpenBLAS starts one thread per processor of the machine and keeps them spinning between calls. On a machine
that other processes keep busy, a small dense solve split among those threads waits for a core at each of its
many short steps: ``synth drive`` (harmonic balance, a few dozen unknowns per speed) took 102 s wall and 64 s of
CPU beside other work with two BLAS threads, 6.9 s with one (``docs/sections/performance.md``). So synth, not
the libraries, sets the thread counts, from what the task is:

============  ==============================================================  ==========================
task          what                                                            threads
============  ==============================================================  ==========================
``"small"``   small dense algebra (the drive's solves and eigenproblems);     1
              every scene by default
``"batch"``   big vectorised batches: numba's ``parallel=True`` kernels, a    :func:`budget`
              large matrix product
============  ==============================================================  ==========================

:func:`budget` is ``--threads N`` (``synth --threads N COMMAND``) or ``SYNTH_THREADS``, never more than
:func:`usable_cores`: the processors this process may run on (its affinity mask) capped by its cgroup CPU quota
(cgroup v2 ``cpu.max``, v1 ``cpu.cfs_quota_us`` / ``cpu.cfs_period_us``). Without a setting it is the usable cores.

* :func:`scene`: what the command line wraps every scene in. It exports the settings to the environment for the
  libraries not loaded yet and for child processes (``OPENBLAS_NUM_THREADS=1`` and its kin, ``SYNTH_THREADS``),
  limits the libraries already loaded (threadpoolctl), and restores all of it after.
* :func:`numba_threads`: the size of numba's pool, set by :mod:`synth.kernels.numba_setup` before numba loads.
* :func:`call`: what every Python API call runs under (the command line's settings, the environment untouched).
* :func:`limits`: one task's thread counts for the span of a block, a context manager and a decorator
  (``@limits("small")``), for code called through the API as well as the command line.
* :func:`worker_environ`: the environment a worker process starts with (the local Dask cluster's).

>>> parse_threads("2", "--threads"), parse_threads("auto", "--threads")
(2, None)
>>> threads_for("small")
1
>>> budget(1)
1
"""

from __future__ import annotations

import contextlib
import math
import os
import sys
from pathlib import Path

from synth.errors import InputError, Problem

__all__ = ["ENV", "TASKS", "THREAD_ENV", "call", "usable_cores", "affinity_cores", "cgroup_cpu_limit", "parse_threads",
           "budget", "threads_for", "limits", "scene", "worker_environ", "numba_threads"]

#: the environment variable of the setting (``--threads`` wins over it)
ENV = "SYNTH_THREADS"
#: the tasks :func:`threads_for` knows, with what each is
TASKS = {"small": "small dense algebra: one thread", "batch": "big vectorised batches: the thread budget"}
#: the variables BLAS and OpenMP runtimes read when they load (OpenBLAS, MKL, BLIS, Apple Accelerate, OpenMP)
THREAD_ENV = ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS", "BLIS_NUM_THREADS",
              "VECLIB_MAXIMUM_THREADS")
#: where the CPU controller's files are (Linux)
CGROUP_ROOT = Path("/sys/fs/cgroup")
PROC_CGROUP = Path("/proc/self/cgroup")


def affinity_cores() -> int:
    """The processors this process may be scheduled on (its affinity mask; the machine's count where unknown)."""
    try:
        return len(os.sched_getaffinity(0))
    except (AttributeError, OSError):  # pragma: no cover - not Linux
        return os.cpu_count() or 1


def _read(path: Path) -> str | None:
    try:
        return path.read_text(encoding="ascii").strip()
    except (OSError, UnicodeDecodeError):
        return None


def _up_to(mount: Path, rel: str):
    """``mount/rel`` and each of its parents down to ``mount`` (a parent's limit binds its children)."""
    d = mount / rel.strip("/")
    while True:
        yield d
        if d == mount or mount not in d.parents:
            return
        d = d.parent


def _v2_limit(folder: Path) -> float | None:
    text = _read(folder / "cpu.max")  # "max 100000" (none) or "150000 100000" (1.5 processors)
    if not text:
        return None
    quota, _, period = text.partition(" ")
    try:
        return int(quota) / int(period) if quota != "max" and int(quota) > 0 and int(period) > 0 else None
    except ValueError:
        return None


def _v1_limit(folder: Path) -> float | None:
    quota, period = _read(folder / "cpu.cfs_quota_us"), _read(folder / "cpu.cfs_period_us")
    try:
        return int(quota) / int(period) if quota and period and int(quota) > 0 and int(period) > 0 else None
    except ValueError:
        return None


def cgroup_cpu_limit(root: Path = CGROUP_ROOT, proc_cgroup: Path = PROC_CGROUP) -> float | None:
    """The processors' worth of CPU time this process's cgroups allow (``1.5``), or None when none is set.

    Reads ``/proc/self/cgroup`` for the process's groups and, in each group and every parent up to the mount,
    the quota: cgroup v2 ``cpu.max`` (``QUOTA PERIOD``, ``max`` for none; the unified hierarchy at ``root`` or,
    on a hybrid system, ``root/unified``), cgroup v1 ``cpu.cfs_quota_us / cpu.cfs_period_us`` (``-1`` for none)
    under ``root/cpu,cpuacct`` or ``root/cpu``. The smallest limit found binds. Inside a container the group's
    path may name the host's hierarchy: the mount's own files (the container's group) are read too.
    """
    text = _read(proc_cgroup)
    if text is None:
        return None
    found = []
    for line in text.splitlines():
        hier, _, rest = line.partition(":")
        controllers, _, rel = rest.partition(":")
        if hier == "0" and controllers == "":
            mounts = [root] if (root / "cgroup.controllers").exists() else [root / "unified"]
            read = _v2_limit
        elif "cpu" in controllers.split(","):
            mounts = [root / name for name in ("cpu,cpuacct", "cpuacct,cpu", "cpu")]
            read = _v1_limit
        else:
            continue
        for mount in mounts:
            if mount.is_dir():
                found += [x for x in (read(d) for d in _up_to(mount, rel)) if x is not None]
    return min(found) if found else None


def usable_cores() -> int:
    """The processors this process may use: its affinity mask, capped by its cgroup CPU quota (a quota of 1.5
    processors counts as 2: two threads then share it), at least 1."""
    cores = affinity_cores()
    quota = cgroup_cpu_limit()
    if quota is not None:
        cores = min(cores, max(1, math.ceil(quota - 1e-9)))
    return max(1, cores)


def parse_threads(value, field: str = "--threads") -> int | None:
    """A thread count as the user gave it: a whole number >= 1, or ``auto`` (None: the usable cores).

    >>> parse_threads("0", "SYNTH_THREADS")
    Traceback (most recent call last):
    ...
    synth.errors.InputError: SYNTH_THREADS: got '0'; accepted: ...
    """
    if isinstance(value, int) and not isinstance(value, bool) and value >= 1:
        return value
    text = str(value).strip().lower()
    if text == "auto":
        return None
    if text.isdigit() and int(text) >= 1:
        return int(text)
    raise InputError(Problem(field, value, f"a whole number of threads, 1 or more, or 'auto' (the usable cores, "
                                           f"{usable_cores()} here; synth never uses more than those)"))


def budget(threads=None) -> int:
    """The threads a big batch may use: ``threads`` (``--threads``), else ``SYNTH_THREADS``, else the usable
    cores; never more than :func:`usable_cores`. A bad value is an :class:`~synth.errors.InputError`."""
    cores = usable_cores()
    if threads is None and os.environ.get(ENV, "").strip():
        threads, field = os.environ[ENV], ENV
    else:
        field = "--threads"
    asked = None if threads is None else parse_threads(threads, field)
    return cores if asked is None else min(asked, cores)


def threads_for(task: str, threads=None) -> int:
    """The thread count of a task of :data:`TASKS` (``threads``: as :func:`budget`'s)."""
    if task == "small":
        return 1
    if task == "batch":
        return budget(threads)
    raise ValueError(f"unknown task {task!r}; known: {', '.join(TASKS)}")


def numba_threads() -> int:
    """The size of numba's thread pool for a process about to import numba: the thread budget, and no more than
    a ``NUMBA_NUM_THREADS`` already set (numba's own default is the machine's processor count, whatever the
    affinity or quota). A bad ``SYNTH_THREADS`` counts as unset here (loading the kernels must not fail on it:
    the command line refuses it first)."""
    try:
        n = budget()
    except InputError:
        n = usable_cores()
    given = os.environ.get("NUMBA_NUM_THREADS", "").strip()
    return min(n, int(given)) if given.isdigit() and int(given) >= 1 else n


# ----------------------------------------------------------------------------------- the libraries' pools

_CONTROLLER: tuple | None = None  # (len(sys.modules) when scanned, threadpoolctl.ThreadpoolController)


def _controller():
    """threadpoolctl's controller of the loaded BLAS/OpenMP libraries, scanned again when modules were imported
    since (a scan costs about 1 ms, a limit through a kept controller 0.1 ms)."""
    global _CONTROLLER
    n = len(sys.modules)
    if _CONTROLLER is None or _CONTROLLER[0] != n:
        from threadpoolctl import ThreadpoolController
        _CONTROLLER = (n, ThreadpoolController())
    return _CONTROLLER[1]


def _numba_pool():
    """numba's threading layer when this process launched it (else None: its pool starts at
    ``NUMBA_NUM_THREADS`` threads when first used, and asking its size would start it)."""
    par = sys.modules.get("numba.np.ufunc.parallel")
    return par if par is not None and getattr(par, "_is_initialized", False) else None


@contextlib.contextmanager
def _limited(blas: int, numba: int):
    """BLAS/OpenMP libraries loaded at ``blas`` threads, numba's pool (in this thread) at ``numba``, for the block."""
    limiter = None
    if "numpy" in sys.modules:  # no BLAS before numpy (scipy loads its own after numpy)
        ctl = _controller()
        if any(lib.num_threads != blas for lib in ctl.lib_controllers):
            limiter = ctl.limit(limits=blas)
    pool, before = _numba_pool(), None
    if pool is not None:
        before = pool.get_num_threads()
        pool.set_num_threads(max(1, min(numba, pool.get_thread_count())))
    try:
        yield
    finally:
        if limiter is not None:
            limiter.restore_original_limits()
        if before is not None:
            pool.set_num_threads(before)


@contextlib.contextmanager
def limits(task: str = "small", *, threads=None):
    """The thread counts of ``task`` (:data:`TASKS`) for the span of the block: every BLAS and OpenMP library
    loaded (threadpoolctl) and numba's threads in this thread; the previous counts after. Also a decorator
    (``@limits("small")``).

    A library loaded inside the block starts with the environment's count (:func:`scene` sets it to 1).

    >>> with limits("small") as n:
    ...     n
    1
    """
    n = threads_for(task, threads)
    with _limited(n, n):
        yield n


@contextlib.contextmanager
def call(threads=None):
    """The thread settings of one Python API call (:mod:`synth`'s functions), as :func:`scene` sets a command's:
    the BLAS and OpenMP libraries at one thread (numpy loaded first, so that its BLAS is limited, not started at a
    thread per processor), numba's pool in this thread at :func:`budget`; the environment is left as it is and the
    previous counts are restored after.

    >>> with call() as n:
    ...     n >= 1
    True
    """
    import numpy  # noqa: F401 - its BLAS loaded, so that the limit applies to it
    n = budget(threads)
    with _limited(1, n):
        yield n


def worker_environ(threads: int = 1) -> dict[str, str]:
    """The environment of a worker process that runs ``threads`` tasks at once (the local Dask cluster's
    one-thread workers): its BLAS pools at one thread, numba's pool and its own :data:`ENV` at ``threads``."""
    n = str(max(1, int(threads)))
    return {**{k: "1" for k in THREAD_ENV}, "NUMBA_NUM_THREADS": n, ENV: n}


@contextlib.contextmanager
def scene(threads=None):
    """The thread settings of a command for its span (the command line wraps every scene in it).

    Resolves :func:`budget` (a bad ``--threads`` or ``SYNTH_THREADS`` raises :class:`~synth.errors.InputError`:
    exit 2). Then the default task is ``"small"``: the variables of :data:`THREAD_ENV` say 1, for the libraries
    loaded later and for child processes, and the libraries already loaded are limited to 1 (threadpoolctl);
    ``SYNTH_THREADS`` says the budget, which children (the web application's server) and numba's pool
    (:func:`numba_threads`, read when synth's kernels load numba) take. The environment and the limits are
    restored after, so that a command run in-process (tests, notebooks) leaves nothing behind but numba's pool size.
    """
    n = budget(threads)
    env = {**{k: "1" for k in THREAD_ENV}, ENV: str(n)}
    saved = {k: os.environ.get(k) for k in env}
    os.environ.update(env)
    try:
        with _limited(1, n):
            yield n
    finally:
        for k, v in saved.items():
            if v is None:
                os.environ.pop(k, None)
            else:
                os.environ[k] = v
