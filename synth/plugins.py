"""Plug-ins: installed packages that declare checks, objectives, tolerance quantities or part families.

A plug-in is a module that makes its declarations when it is imported (:func:`synth.design.constraints.register`,
:func:`synth.optimise.objectives.declare`, :func:`synth.robust.tolerances.declare`,
:func:`synth.design.subsystems.declare`), named as an entry point of group ``synth.plugins`` in its package's
metadata (the mechanism pytest and Flake8 use for theirs)::

    [project.entry-points."synth.plugins"]
    acme_checks = "acme_tensioners.checks"

A declaration made by hand (``register(...)`` in a notebook) lives in the process that made it; a plug-in is
declared in every process that judges a design: :func:`load` runs where a configuration is made (the command line
before it reads its options, so a plug-in's objective is a choice of ``--objective``; the Python API's
:func:`synth.settings`, which every call resolves), and where one arrives (a
:class:`~synth.design.settings.Settings` loads them as it is unpickled: a Dask worker, a process pool's worker),
and in the web application's worker processes as they start. ``synth --version`` names the plug-ins in effect.

A plug-in that does not import is the installation's problem, not synth's: :class:`~synth.errors.InputError` naming
the entry point, what it points at and the error (the command line's exit 2).

>>> load() == load()  # idempotent: each entry point is imported once per process
True
"""

from __future__ import annotations

import inspect
import threading

from synth.errors import InputError, Problem

__all__ = ["GROUP", "load", "loaded"]

#: the entry-point group synth reads its plug-ins from
GROUP = "synth.plugins"

_LOADED: dict = {}     # entry point name -> "name = value (distribution version)"
_LOCK = threading.RLock()
_SCANNED: list = []    # non-empty once the installed entry points were read (once per process: the scan costs)


def _entry_points() -> list:
    from importlib.metadata import entry_points
    return sorted(entry_points(group=GROUP), key=lambda ep: ep.name)


def load() -> tuple:
    """Import every plug-in of group :data:`GROUP` (the installed ones, read once per process); returns
    :func:`loaded`."""
    if _SCANNED:
        return loaded()
    with _LOCK:
        if _SCANNED:
            return loaded()
        for ep in _entry_points():
            if ep.name in _LOADED:
                continue
            _LOADED[ep.name] = None  # a plug-in importing synth.plugins again does not recurse
            try:
                obj = ep.load()
                if callable(obj) and not inspect.ismodule(obj):
                    obj()  # an entry point may name a function that declares, instead of a module that does on import
            except Exception as exc:  # noqa: BLE001 - any failure of foreign code is reported as the plug-in's
                del _LOADED[ep.name]
                raise InputError(Problem(f"plug-in {ep.name} (entry point {ep.value!r} of group {GROUP})",
                                         f"{type(exc).__name__}: {exc}",
                                         "a module that imports without error (fix or uninstall the package "
                                         "that declares it)")) from exc
            dist = getattr(ep, "dist", None)
            made = f" ({dist.name} {dist.version})" if dist is not None else ""
            _LOADED[ep.name] = f"{ep.name} = {ep.value}{made}"
        _SCANNED.append(True)
        return loaded()


def loaded() -> tuple:
    """The plug-ins imported in this process: ``"name = module (distribution version)"``, by name."""
    return tuple(v for _, v in sorted(_LOADED.items()) if v is not None)
