"""What synth sets before numba loads (issue 36): where its compiled kernels are kept, the size of numba's thread
pool, and a line on stderr when a kernel compiles.

* **Compiled once per install and version.** :func:`configure` (run by ``import synth.kernels``, before any
  ``_*_jit`` module imports numba) sets ``NUMBA_CACHE_DIR`` to ``numba-VERSION-DIGEST`` in synth's cache folder
  (:func:`synth.fingerprint.cache_dir`: ``SYNTH_CACHE_DIR``, else ``$XDG_CACHE_HOME/synth``, else
  ``~/.cache/synth``), unless the user set ``NUMBA_CACHE_DIR`` (or ``SYNTH_CACHE_DIR=off``: numba's own place,
  ``__pycache__`` beside the module), in a folder named by synth's version and a digest of the kernels' sources
  (:func:`sources_digest`). numba keys each entry by the source file's size and modification time, the signature
  and the CPU, but not by the files its kernel calls into: "cache invalidation fails to recognize changes in
  symbols defined in a different file" (numba's *Notes on Caching*, Caching Limitations), and the scans and rounds
  call the pair physics of ``_main_spring_jit`` (and the axial and main-spring kernels ``_ieee``'s helpers). So
  any edit of a ``_*_jit`` or helper source starts a new folder, and a new synth version too. The environment
  variable is inherited by child processes (Dask workers), which therefore read the same cache.
* **numba's pool** is :func:`synth.threads.numba_threads` threads (the thread budget), not numba's default of
  every processor of the machine; set while numba is not imported yet.
* **A line when a kernel compiles**: :func:`announce_compiles` (called by each ``_*_jit`` module after importing
  numba) prints :func:`notice` on stderr at the first compile of the process (numba's ``numba:compile`` event
  fires only on a cache miss, never when a kernel loads from the cache).

Measured (``benchmarks/bench_first_run.py``, docs/sections/performance.md): the first ``synth bulk`` compiles the
five kernels it calls and their helpers (26 functions, one signature each: about :data:`COMPILE_S` s of CPU);
``synth design`` and ``synth robust`` compile nothing (the one-application path never imports numba).
"""

from __future__ import annotations

import os
import sys

from synth.fingerprint import cache_dir
from synth.threads import numba_threads
from synth.version import __version__

__all__ = ["COMPILE_S", "configure", "kernel_cache_dir", "sources_digest", "announce_compiles", "notice", "Compiled"]

#: seconds of CPU the first ``synth bulk`` spends compiling the kernels: its CPU time less the second run's, 10-18 s
#: on the shared 2-core machine of ``benchmarks/bench_first_run.py`` (load 12-17), about half on a quiet one
#: (issue 36)
COMPILE_S = 12

_ANNOUNCED = False
_LISTENING = False


def sources_digest() -> str:
    """The first 12 hex digits of the SHA-256 of the compiled kernels' sources: every ``_*.py`` of
    ``synth/kernels`` (the ``_*_jit`` modules and the helpers they call), in name order, each as its name and bytes."""
    import hashlib
    from pathlib import Path
    h = hashlib.sha256()
    for path in sorted(Path(__file__).parent.glob("_*.py")):
        if path.name != "__init__.py":
            h.update(path.name.encode() + b"\0" + path.read_bytes() + b"\0")
    return h.hexdigest()[:12]


def kernel_cache_dir():
    """The folder of the compiled kernels of this synth version and these kernel sources (a :class:`~pathlib.Path`:
    ``numba-VERSION-DIGEST``, :func:`sources_digest`), or None when synth's cache is off (``SYNTH_CACHE_DIR=off``)."""
    base = cache_dir()
    return None if base is None else base / f"numba-{__version__}-{sources_digest()}"


def configure() -> None:
    """Point numba's cache at :func:`kernel_cache_dir` and size its pool (:func:`synth.threads.numba_threads`),
    unless the user set ``NUMBA_CACHE_DIR``. Safe to call again; once numba is imported its pool size stays."""
    folder = kernel_cache_dir()
    if folder is not None and not os.environ.get("NUMBA_CACHE_DIR"):
        os.environ["NUMBA_CACHE_DIR"] = str(folder)
        config = sys.modules.get("numba.core.config")
        if config is not None:  # numba already imported (by the user): its config was read at import
            config.CACHE_DIR = str(folder)
    if "numba" not in sys.modules:
        os.environ["NUMBA_NUM_THREADS"] = str(numba_threads())


def notice() -> str:
    """The line printed when synth's kernels compile."""
    where = os.environ.get("NUMBA_CACHE_DIR") or "numba's cache"
    return (f"synth: compiling synth's kernels (first run after install, about {COMPILE_S} s; "
            f"later runs load them from {where})")


def announce_compiles() -> None:
    """Print :func:`notice` on stderr when numba first compiles (not loads) a kernel in this process: registers a
    listener of numba's ``numba:compile`` event (once; numba must be imported)."""
    global _LISTENING
    if _LISTENING:
        return
    from numba.core import event

    class _Notice(event.Listener):
        def on_start(self, ev):
            global _ANNOUNCED
            if not _ANNOUNCED:
                _ANNOUNCED = True
                print(notice(), file=sys.stderr, flush=True)

        def on_end(self, ev):
            pass

    event.register("numba:compile", _Notice())
    _LISTENING = True


class Compiled:
    """A compiled kernels module loaded on the first call (importing it imports numba; later calls are an attribute
    lookup). ``load`` imports and returns the module (an import statement in the caller's module, so that the
    architecture test's import graph sees the edge); :meth:`loaded` says whether this process has loaded it yet.

    >>> import math
    >>> k = Compiled(lambda: math)
    >>> k.loaded(), k() is math, k.loaded()
    (False, True, True)
    """

    def __init__(self, load):
        self._load = load
        self._module = None

    def __call__(self):
        if self._module is None:
            self._module = self._load()
        return self._module

    def loaded(self) -> bool:
        return self._module is not None
