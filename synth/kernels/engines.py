"""Which engine a search runs its physics on: decided here, once, for every path (the bulk engine's
:class:`~synth.optimise.batch.Batch`, the platform producer, the one-application branch and bound).

A path names the engine it would take (``default``: the compiled kernels where many rows are evaluated, the numpy
reference for one application, which must not import numba); the configuration may ask for one
(:attr:`synth.design.settings.Settings.engine`, ``"auto"``: the path's). The compiled main-spring kernels
(:mod:`synth.kernels.main_spring`) compute their own fixed margins (:data:`SPRING_MARGINS`)
against the catalog's limits, on the thesis's limit basis and with no required margin: they run only where that
is the registry's judgement under the configuration (:func:`spring_covers`); anywhere else the spring runs on
its numpy twin, the registry's own group (:func:`synth.design.evaluate.spring`, :func:`~synth.design.evaluate.finish`).
The axial group's compiled twins (:mod:`synth.kernels.axial`) compute the physics only (the cone spring, the wear:
no limit, no margin), so they cover every configuration.

>>> from synth.design.settings import Settings
>>> spring(Settings(), "numba"), spring(Settings(spring_limit_basis="en13906"), "numba")
('numba', 'numpy')
>>> spring(Settings(rules={"min_margins": {"pivot_wall": 0.1}}), "numba"), spring(Settings(engine="numpy"), "numba")
('numba', 'numpy')
>>> axial(Settings(rules={"min_margins": {"spring_coil_gap": 0.6}}), "numba")
'numba'
"""

from __future__ import annotations

from synth.design.constraints import by_group
from synth.errors import InputError, Problem

__all__ = ["ENGINES", "SPRING_MARGINS", "preferred", "spring", "spring_covers", "axial"]

#: the engines of a kernel: the compiled one and the numpy reference
ENGINES = ("numba", "numpy")
#: the margins the compiled main-spring kernels compute, in their layout: the registry's non-advisory spring
#: constraints of step 9 as declared (:data:`synth.kernels.main_spring.MARGIN_NAMES`)
SPRING_MARGINS = ("spring_yield", "spring_material_section", "spring_fatigue", "spring_outer_contact",
                  "spring_inner_contact", "spring_coil_gap", "spring_index_min", "spring_index_max")


def preferred(settings, default: str) -> str:
    """The engine asked for: the configuration's (:attr:`~synth.design.settings.Settings.engine`), or the path's
    ``default`` when it says ``"auto"``."""
    if default not in ENGINES:
        raise InputError(Problem("engine", default, " or ".join(ENGINES)))
    return default if settings.engine == "auto" else settings.engine


def spring_covers(settings) -> bool:
    """Whether the compiled main-spring kernels compute the registry's spring judgement under ``settings``: every
    non-advisory spring check is one of theirs (:data:`SPRING_MARGINS`: none added with ``register``), the spring
    limit basis is the thesis's, and the design rules set no limit a spring check reads and no margin a spring
    check must keep (the kernels hold the catalog's limits and judge at margin 0)."""
    checks = [c for c in by_group("spring") if not c.advisory]
    if any(c.id not in SPRING_MARGINS for c in checks):
        return False
    rules = settings.rules
    if rules.spring_limit_basis != "thesis":
        return False
    spring = by_group("spring")
    if any(rules.required(c.id) for c in spring):
        return False
    return not any(c.limit in rules.limits for c in spring)


def spring(settings, default: str) -> str:
    """The main spring's engine: ``"numba"`` where it is asked for (:func:`preferred`) and covers the registry's
    checks under ``settings`` (:func:`spring_covers`), else ``"numpy"``."""
    return "numba" if preferred(settings, default) == "numba" and spring_covers(settings) else "numpy"


def axial(settings, default: str) -> str:
    """The axial group's physics engine (the cone spring, the wear): the one asked for (:func:`preferred`); the
    compiled twins compute no limit or margin, so every configuration is theirs."""
    return preferred(settings, default)
