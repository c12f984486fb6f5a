"""Fingerprints of the data and code a result depends on, and the on-disk cache they key.

* :func:`catalogs_sha256`: the built-in ``catalogs/*.csv`` and every user folder's CSVs (file names
  and bytes): two runs with the same hash read the same data (``synth --version`` prints it, :func:`version_text`).
* :func:`cached`: a value built once per fingerprint and kept as a pickle in the user's cache folder
  (``SYNTH_CACHE_DIR``, else ``$XDG_CACHE_HOME/synth``, else ``~/.cache/synth``; ``SYNTH_CACHE_DIR=off``
  disables it). A file that cannot be read or written is rebuilt or skipped silently: the cache only
  saves time, it never changes an answer (its key covers the catalogs and synth's source, :func:`source_stamp`).

No pandas, no numpy at import: ``synth --version`` stays fast.
"""

from __future__ import annotations

import functools
import hashlib
import os
import pickle
from pathlib import Path

from synth.version import __version__

__all__ = ["builtin_catalog_dir", "catalogs_sha256", "file_sha256", "source_stamp", "cache_dir", "cache_path",
           "cached", "version_text"]

#: cached versions kept per name (several catalog settings in use side by side)
_KEEP = 8


def builtin_catalog_dir() -> Path | None:
    """Folder of the built-in catalogs (inside the wheel, or the source tree), or None."""
    here = Path(__file__).resolve().parent
    return next((d for d in (here / "catalogs", here.parent / "catalogs") if d.is_dir()), None)


def catalogs_sha256(user_dirs=()) -> str:
    """Hex sha256 of the built-in catalog CSVs and those of ``user_dirs`` (names and bytes, in order)."""
    builtin = builtin_catalog_dir()
    h = hashlib.sha256()
    for d in ([builtin] if builtin else []) + [Path(d) for d in user_dirs]:
        for f in sorted(d.glob("*.csv")) if d.is_dir() else []:
            h.update(f.name.encode() + b"\0" + f.read_bytes() + b"\0")
    return h.hexdigest()


@functools.lru_cache(maxsize=1)
def source_stamp() -> str:
    """A stamp of synth's own source: every module's path, size and modification time (a ``stat`` each, no
    reading): an edited module makes every cached value stale."""
    root = os.path.dirname(os.path.abspath(__file__))
    parts = []
    for folder, dirs, files in os.walk(root):
        dirs[:] = [d for d in dirs if d != "__pycache__"]
        for e in os.scandir(folder):
            if e.name.endswith(".py") and e.is_file():
                st = e.stat()
                parts.append(f"{os.path.relpath(e.path, root)}:{st.st_size}:{st.st_mtime_ns}")
    return hashlib.sha256("\0".join(sorted(parts)).encode()).hexdigest()


def file_sha256(path) -> str:
    """Hex sha256 of a file's bytes (read in 1 MB blocks)."""
    h = hashlib.sha256()
    with open(path, "rb") as f:
        for block in iter(lambda: f.read(1 << 20), b""):
            h.update(block)
    return h.hexdigest()


def cache_dir() -> Path | None:
    """synth's cache folder: ``SYNTH_CACHE_DIR``, else ``$XDG_CACHE_HOME/synth``, else ``~/.cache/synth``; None when
    ``SYNTH_CACHE_DIR=off`` (also ``0``, ``none``, empty)."""
    env = os.environ.get("SYNTH_CACHE_DIR")
    if env is not None:
        return None if env.strip().lower() in ("", "off", "0", "none") else Path(env)
    base = os.environ.get("XDG_CACHE_HOME") or os.path.join(os.path.expanduser("~"), ".cache")
    return Path(base) / "synth"


def cache_path(name: str, key_parts: list) -> Path | None:
    """The file :func:`cached` keeps ``name`` in under ``key_parts`` (None when the cache is off); it exists once
    a value was stored there."""
    h = hashlib.sha256(__version__.encode())
    for k in key_parts:
        h.update(Path(k).read_bytes() if isinstance(k, Path) else str(k).encode())
        h.update(b"\0")
    folder = cache_dir()
    return folder / f"{name}-{h.hexdigest()[:20]}.pickle" if folder else None


def cached(name: str, key_parts: list, build):
    """``build()``, or its pickle from the cache when one was stored under the same ``name`` and key.

    ``key_parts``: strings or paths (a path contributes its bytes: the source files of the builder).
    """
    path = cache_path(name, key_parts)
    folder = path.parent if path is not None else None
    if path is not None and path.is_file():
        try:
            with open(path, "rb") as f:
                return pickle.load(f)
        except Exception:  # noqa: BLE001 - a damaged or foreign cache file: rebuild
            pass
    value = build()
    if path is not None:
        try:
            folder.mkdir(parents=True, exist_ok=True)
            tmp = path.with_suffix(f".{os.getpid()}.tmp")
            with open(tmp, "wb") as f:
                pickle.dump(value, f, protocol=pickle.HIGHEST_PROTOCOL)
            os.replace(tmp, path)
            old = sorted(folder.glob(f"{name}-*.pickle"), key=lambda f: f.stat().st_mtime)[:-_KEEP]
            for f in old:  # stale versions (an older synth or catalog): the newest _KEEP stay
                f.unlink(missing_ok=True)
        except OSError:
            pass
    return value


def version_text(catalog_dirs=()) -> str:
    """``synth 0.1.0 (catalogs sha256 1a2b3c4d5e6f)``: the package version and a hash of the catalog CSVs in use.

    The hash covers the built-in ``catalogs/*.csv`` and the CSVs of every user folder
    (``--catalogs``, ``SYNTH_CATALOGS``), file names and bytes: two runs with the same hash read the same data. The
    plug-ins in effect (:mod:`synth.plugins`: their checks and objectives judge too) are named after it.
    """
    user = [Path(d) for d in catalog_dirs] + [Path(p) for p in os.environ.get("SYNTH_CATALOGS", "").split(os.pathsep) if p]
    digest = catalogs_sha256(user)
    extra = f"; user catalogs: {', '.join(str(d) for d in user)}" if user else ""
    from synth import plugins
    from synth.errors import InputError
    try:
        named = plugins.load()
    except InputError as exc:  # the version is still printed, with what keeps a plug-in from loading
        named = (f"not loaded: {exc}",)
    extra += f"; plug-ins: {', '.join(named)}" if named else ""
    return f"synth {__version__} (catalogs sha256 {digest[:12]}{extra})"
