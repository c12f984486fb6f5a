"""Catalogs of standard parts and named constants, read from plain CSV.

Every catalog is one CSV file in ``catalogs/`` (shipped inside the wheel as
``synth/catalogs``). The first column is the key (a designation such as
``6006`` or ``M8x1.25``), units are in the column names (``d_mm``,
``C_n``), and every row has a ``source`` column.

A user's own folder overrides the built-in data: set it for the process with
:func:`set_user_dirs` (``synth --catalogs``) or the ``SYNTH_CATALOGS`` environment variable
(``os.pathsep``-separated), or for one block of work with :func:`using` (this thread or task only: a run's
configuration, :attr:`synth.design.settings.Settings.catalogs`, applied where the run starts or a worker takes its
chunk). A user CSV with the same file name is merged on
the key column: its rows replace built-in rows with the same key and new keys
are appended, so a user can add a part or change one cost without copying the
whole table. Every cache is keyed by the folders in use (:func:`user_dirs`), never by a process-wide flag.

Named constants (friction coefficients, wear constants, tolerances...) live in
``catalogs/constants.csv`` with value, unit and source; read them with
:func:`constant`.

>>> bearings = load("ball_bearings")
>>> float(row("ball_bearings", "6006")["D_mm"])
55.0
"""

from __future__ import annotations

import contextlib
import contextvars
import functools
import os
from pathlib import Path
from typing import TYPE_CHECKING

from synth.errors import CatalogError, InputError, Problem
from synth.io.catalogs import check_user_dir, read_user_catalog
from synth.fingerprint import cached, catalogs_sha256, source_stamp

if TYPE_CHECKING:  # annotations only: pandas is imported where a table is read (start-up: about 60 ms)
    import pandas as pd

__all__ = ["builtin_dir", "set_user_dirs", "user_dirs", "using", "overriding", "names", "load", "row", "keys",
           "constant", "constant_row"]

_USER_DIRS: list[Path] = []
#: the user folders of the block of work in this thread or task (:func:`using`), None: the process's
_SCOPED: contextvars.ContextVar = contextvars.ContextVar("synth_user_catalogs", default=None)
_CHECKED: set = set()  # the folder lists checked through the input gate (once each)


def builtin_dir() -> Path:
    """Folder of the built-in catalogs (inside the wheel, or the source tree)."""
    here = Path(__file__).resolve().parent
    for candidate in (here / "catalogs", here.parent / "catalogs"):
        if candidate.is_dir():
            return candidate
    raise CatalogError(Problem("catalogs", str(here), "a synth installation with its catalogs/ folder"))


def set_user_dirs(*dirs: str | os.PathLike) -> None:
    """Use the given folders (first wins) to override built-in catalogs.

    Each folder is checked at once through the input gate
    (:func:`synth.io.catalogs.check_user_dir`): a folder that does not exist,
    a CSV not named like a built-in catalog, a malformed or empty CSV, text
    in a number column, a missing ``source`` column are each an
    :class:`~synth.errors.InputError` naming the file, row and column.
    """

    _USER_DIRS[:] = []
    load.cache_clear()
    problems = []
    for d in dirs:
        try:
            check_user_dir(d, names(), lambda n: load_cached(n, ()))
        except InputError as exc:
            problems.extend(exc.problems)
    if problems:
        raise InputError(problems)
    _USER_DIRS[:] = [Path(d) for d in dirs]
    load.cache_clear()


def _check_dirs(dirs, option: str = "--catalogs") -> None:
    problems = []
    for d in dirs:
        try:
            check_user_dir(d, names(), lambda n: load_cached(n, ()), option=option)
        except InputError as exc:
            problems.extend(exc.problems)
    if problems:
        raise InputError(problems)


@contextlib.contextmanager
def using(dirs):
    """Read the catalogs with the user folders ``dirs`` (first wins; None: the process's, :func:`user_dirs`) for
    the block, in this thread or task only: the user catalogs of a run's configuration
    (:attr:`synth.design.settings.Settings.catalogs`) where it starts or a worker takes its chunk. Each list of
    folders is checked through the input gate once, as :func:`set_user_dirs` checks them; no cache is cleared
    (every cache is keyed by the folders)."""
    if dirs is None:
        yield
        return
    dirs = tuple(Path(d) for d in dirs)
    if dirs and dirs not in _CHECKED and dirs != tuple(_user_dirs()):
        _check_dirs(dirs)
        _CHECKED.add(dirs)
    token = _SCOPED.set(dirs)
    try:
        yield
    finally:
        _SCOPED.reset(token)


@contextlib.contextmanager
def overriding(folder):
    """Use ``folder`` as the first user catalog folder for the duration of the block, in this thread or task only
    (synth's own generated CSVs, e.g. an assumption at the end of its range, :mod:`synth.robust.assumptions`: not
    checked again, and no cache cleared: every cache is keyed by the folders, so the tables without a file in
    ``folder`` stay parsed)."""
    token = _SCOPED.set((Path(folder), *_user_dirs()))
    try:
        yield
    finally:
        _SCOPED.reset(token)


_ENV_CHECKED: dict[str, list[Path]] = {}


def user_dirs() -> list[Path]:
    """The user catalog folders in use here (first wins): the block's (:func:`using`), else the process's
    (:func:`set_user_dirs`, then ``SYNTH_CATALOGS``)."""
    return list(_user_dirs())


def _user_dirs() -> list[Path]:
    scoped = _SCOPED.get()
    if scoped is not None:
        return list(scoped)
    env = os.environ.get("SYNTH_CATALOGS", "")
    dirs = _ENV_CHECKED.get(env)
    if dirs is None:  # checked once per value of the variable, like --catalogs (see set_user_dirs)
        dirs = [Path(p) for p in env.split(os.pathsep) if p]
        problems = []
        for d in dirs:
            try:
                check_user_dir(d, names(), lambda n: load_cached(n, ()), option="SYNTH_CATALOGS")
            except InputError as exc:
                problems.extend(exc.problems)
        if problems:
            raise InputError(problems)
        _ENV_CHECKED[env] = dirs
    return _USER_DIRS + dirs


def names() -> list[str]:
    """Names of the built-in catalogs (file names without ``.csv``)."""
    return sorted(p.stem for p in builtin_dir().glob("*.csv"))


def _read(path: Path) -> pd.DataFrame:
    import pandas as pd
    df = pd.read_csv(path, comment="#", skipinitialspace=True, dtype={0: str})
    df.columns = [c.strip() for c in df.columns]
    key = df.columns[0]
    df[key] = df[key].astype(str).str.strip()
    return df


@functools.lru_cache(maxsize=None)
def load_cached(name: str, user_dirs: tuple[Path, ...]) -> pd.DataFrame:
    """The table ``name`` under the folders ``user_dirs`` (:func:`user_dirs`), parsed once per folders: the same
    object until the folders or the cache change (a memo of what is derived from it keys on that identity)."""
    import pandas as pd
    path = builtin_dir() / f"{name}.csv"
    if not path.is_file():
        raise CatalogError(Problem("catalog", name, "one of " + ", ".join(names())))
    if user_dirs and not any((d / f"{name}.csv").is_file() for d in user_dirs):
        return load_cached(name, ())  # no user file for it: the built-in table, parsed once
    df = _read(path)
    key = df.columns[0]
    for d in reversed(user_dirs):
        upath = d / f"{name}.csv"
        if upath.is_file():
            udf = read_user_catalog(upath, df if not user_dirs else load_cached(name, ()))
            df = pd.concat([df[~df[key].isin(udf[key])], udf], ignore_index=True)
    return df


def load(name: str) -> pd.DataFrame:
    """Return catalog ``name`` as a DataFrame (a copy: safe to modify)."""
    return load_cached(name, tuple(_user_dirs())).copy()


_PARSED: dict = {}


def parsed(name: str, build):
    """``build(table)`` of catalog ``name`` (``table``: :func:`load`'s copy), computed once per loaded table: a
    user folder or a cleared catalog cache gives a new table, and so a new value. For what a hot path derives
    from a small table (a lookup array, a sum) every call.

    >>> parsed("stackup_tolerances", len) == len(load("stackup_tolerances"))
    True
    """
    dirs = tuple(_user_dirs())
    src = load_cached(name, dirs)
    hit = _PARSED.get((name, build, dirs))
    if hit is not None and hit[0] is src:
        return hit[1]
    value = build(src.copy())
    _PARSED[(name, build, dirs)] = (src, value)
    return value


@functools.lru_cache(maxsize=None)
def _index_cached(name: str, user_dirs: tuple[Path, ...]) -> dict:
    """``{key: row position}`` of catalog ``name`` (first occurrence wins, as :func:`row` always did)."""
    df = load_cached(name, user_dirs)
    out: dict = {}
    for i, k in enumerate(df[df.columns[0]]):
        out.setdefault(k, i)
    return out


def _clear_caches() -> None:
    for f in (load_cached, _index_cached, constants_cached, _constant_values):
        f.cache_clear()


load.cache_clear = _clear_caches  # type: ignore[attr-defined]


def keys(name: str) -> list[str]:
    """The designations (first-column values) of catalog ``name``."""
    df = load(name)
    return df[df.columns[0]].tolist()


def row(name: str, key: str, field: str | None = None) -> pd.Series:
    """One catalog row by designation; an unknown key lists the valid ones.

    ``field`` names the input field that asked for it, for the error message.
    """
    dirs = tuple(_user_dirs())
    df = load_cached(name, dirs)
    i = _index_cached(name, dirs).get(str(key).strip())
    if i is None:
        col = df.columns[0]
        raise CatalogError(Problem(field or f"{name}.{col}", key, "one of " + ", ".join(df[col])))
    return df.iloc[i].copy()


@functools.lru_cache(maxsize=None)
def constants_cached(user_dirs: tuple[Path, ...]) -> tuple[pd.DataFrame, dict]:
    """Every ``constants*.csv`` merged, and ``{name: row position}`` (first occurrence wins)."""
    import pandas as pd
    frames = [load_cached(n, user_dirs) for n in names() if n == "constants" or n.startswith("constants_")]
    df = pd.concat(frames, ignore_index=True)
    index: dict = {}
    for i, n in enumerate(df["name"]):
        index.setdefault(n, i)
    return df, index


def _constants() -> pd.DataFrame:
    return constants_cached(tuple(_user_dirs()))[0].copy()


def constant_row(name: str) -> pd.Series:
    """The row for constant ``name`` (value, unit, source).

    Constants live in ``constants.csv`` and the topic files ``constants_*.csv``
    (one per flowchart step or model), all with columns
    ``name,value,unit,source,note``.
    """
    df, index = constants_cached(tuple(_user_dirs()))
    i = index.get(name)
    if i is None:
        raise CatalogError(Problem("constant", name, "one of " + ", ".join(sorted(df["name"]))))
    return df.iloc[i].copy()


def constant(name: str) -> float:
    """The value of a named constant from ``catalogs/constants.csv``.

    >>> constant("pulley_width_margin_mm")
    4.0

    Lookups are cached per user-folder setting (:func:`set_user_dirs` clears
    the cache): a constant costs a dict lookup, not a CSV merge.
    """
    values = _constant_values(tuple(_user_dirs()))
    if name in values:
        return float(values[name])
    return float(constant_row(name)["value"])  # unknown name: raises, listing the known ones


@functools.lru_cache(maxsize=None)
def _constant_values(user_dirs: tuple[Path, ...]) -> dict:
    """``{name: value}`` of every constant, read once per catalog data (:func:`synth.fingerprint.cached`)."""

    def build():
        df, index = constants_cached(user_dirs)
        return {n: df["value"].iloc[i] for n, i in index.items()}
    return cached("constants", [catalogs_sha256(user_dirs), source_stamp()], build)
