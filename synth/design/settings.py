"""The configuration of an evaluation: one immutable object, resolved once where a run starts, passed as an argument.

Everything that changes a margin travels in one :class:`Settings`: the model's speed against accuracy (the
fidelity) and conventions (friction circle, bushing running-in, bolt method, the belt drive), the design rules
(:class:`synth.design.rules.Rules`: required limits and margins, the spring limit basis, capability targets),
the user catalog folders and the engine of the compiled kernels. Each entry point resolves it once (the command
line from its options and ``--rules``, the Python API from its keywords and the input's ``rules:`` section, a
saved result from what it carries: :meth:`Settings.from_saved`) and hands it to every search, every worker (a Dask
task or a process pool receives it with its chunk) and every kernel choice (:mod:`synth.kernels.engines`). Nothing
is read from process-wide state: two threads evaluating under two configurations each get their own.

``spring_limit_basis`` lives in one place, the rules (:attr:`Rules.spring_limit_basis`); ``Settings(...,
spring_limit_basis=...)`` (the ``--spring-limit`` option, the API's keyword) sets it there, over the rules' own.

>>> s = Settings(fidelity="screening", rules={"min_margins": {"spring_yield": 0.05}}, spring_limit_basis="en13906")
>>> s.spring_limit_basis, s.rules.required("spring_yield"), s.judge.rules is s.rules
('en13906', 0.05, True)
>>> list(s.as_dict())[-2:], s.as_dict()["spring_limit_basis"]
(['drive', 'spring_limit_basis'], 'en13906')
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass
from pathlib import Path

from synth.design.rules import NONE, SPRING_LIMIT_BASES, Rules
from synth.drive.inputs import drive_from_mapping
from synth.errors import InputError, Problem

__all__ = ["Settings", "FIDELITIES", "FIDELITY_TEXT", "UNVERIFIED_NOTE", "SPRING_LIMIT_BASES", "ENGINES",
           "MODEL_KEYS", "DEFAULT"]

#: ``full``: the full model everywhere; ``screening``: the searches rank and prune with the screening model and the
#: full model judges every design they keep (what is reported is valid under the full model); ``screening-only``:
#: the screening model alone, unverified (every output says so)
FIDELITIES = ("full", "screening", "screening-only")
#: the note of every design reported at screening-only fidelity (in its notes, and in every bulk row)
UNVERIFIED_NOTE = "screening-only fidelity: not verified at full fidelity (the full model may reject this design)"
#: what a reported design's fidelity means (the reports' and the command lines' words)
FIDELITY_TEXT = {
    "full": "full: Almen-Laszlo cone-spring characteristic and its exact plastic wear along it",
    "screening": "screening, verified: designs searched with the linear cone spring and closed-form plastic wear, "
                 "every reported design checked at full fidelity (its checks and values are the full model's)",
    "screening-only": "screening only: linear cone spring and closed-form plastic wear, NOT verified at full "
                      "fidelity (the full model may reject the design)"}
#: the engines of the compiled kernels a configuration may ask for: ``auto`` (each path's own: the compiled
#: kernels where many rows are evaluated, the numpy reference for one application), ``numba``, ``numpy``; the
#: compiled kernels run only where they cover the registry's checks under the configuration
#: (:func:`synth.kernels.engines.spring`)
ENGINES = ("auto", "numba", "numpy")
#: the model settings a result records (``Result.settings``, in this order): the rest of the configuration is
#: recorded apart (``Result.rules``) or changes no number (the engine; the catalogs are in the fingerprint)
MODEL_KEYS = ("fidelity", "friction_circle", "bushing_running_in", "bushing_length_scheme", "bolt_method", "drive",
              "spring_limit_basis")


@dataclass(frozen=True, init=False)
class Settings:
    """The configuration of an evaluation (immutable; see the module docstring).

    * ``fidelity``: ``"full"`` (Almen-Laszlo cone spring, exact plastic wear
      along it), ``"screening"`` (the searches rank and prune with the linear
      cone spring and closed-form wear; every design they keep is judged by
      the full model: :attr:`judge`) or ``"screening-only"`` (the screening
      model alone, unverified);
    * ``friction_circle``: radial friction on ``r_p sin(atan(mu))`` (physics,
      default) or on ``r_p mu`` (the thesis tool's tables);
    * ``bushing_running_in``: integrate the running-in of the pivot clearance in
      the bushing wear (an extension with illustrative constants; off: the
      thesis's closed-form eq. (32));
    * ``bushing_length_scheme`` (the flowchart's selection only): ``"thesis"``
      (the thesis tool's trial lengths, multiples of half the pivot diameter,
      then the next catalog length is the part) or ``"catalog"`` (the shortest
      catalog length that passes);
    * ``bolt_method``: ``"thesis"`` (the elastic von Mises check of the nominal
      preload, eq. (103)-(107): the default, it reproduces the thesis tool and
      its safety targets already hold the preload scatter) or ``"vdi2230"``
      (permissible assembly preload with the plastic torsion factor, tightening
      factor and embedding loss, VDI 2230-1; the clamped length is taken as the
      maximum pivot height);
    * ``drive``: the belt drive around the tensioner (:class:`synth.drive.inputs.Drive`, ``synth design
      --drive``) or None; with a drive the core group adds the registry's ``drive_belt_slack`` and
      ``drive_arm_lock`` checks at each design's own damping (a saved result's dict form is read back).
    * ``rules``: the design rules (:class:`~synth.design.rules.Rules`, or a mapping of them): the limits they
      tighten and the margins the checks must keep (:func:`synth.design.evaluate.finish`), the spring limit basis,
      the capability targets;
    * ``spring_limit_basis`` (a property: the rules' own; the keyword sets it in the rules): what the main
      spring's installation stress is checked against (constraint ``spring_yield``): ``"thesis"`` (the
      curvature-corrected stress against the material's ``sigma_y_bend_fraction * Rm``, the thesis tool's yield
      check, eq. (72)-(77): the default) or ``"en13906"`` (the spring makers' static rule, EN 13906-3 practice:
      the stress without the curvature factor against ``sigma_perm_static_fraction * Rm``, 0.75 Rm; expressed on
      the corrected stress as ``0.75 Rm k_f``, the same relative margin). The advisory
      ``spring_static_permissible`` shows the static rule either way;
    * ``catalogs``: the user catalog folders (``--catalogs``) the run reads, first wins; None: this process's
      (:func:`synth.catalog.user_dirs`, resolved by :meth:`resolved` before the settings leave the process);
    * ``engine``: the compiled kernels' engine (:data:`ENGINES`): ``"auto"`` lets each path take its own;
    * ``capability``: the production capability target and its estimator (a
      :class:`synth.robust.settings.RobustSettings`, ``--capability``/``--ppm``) or None: with it the searches
      that honour it (``synth bulk``'s rows, ``synth rationalise``'s options) keep only designs that meet it,
      through the robust synthesis (:mod:`synth.robust.synthesis`); it changes no margin.
    """

    fidelity: str = "full"
    friction_circle: bool = True
    bushing_running_in: bool = False
    bushing_length_scheme: str = "thesis"
    bolt_method: str = "thesis"
    drive: object = None
    rules: Rules = NONE
    catalogs: tuple | None = None
    engine: str = "auto"
    capability: object = None

    def __init__(self, fidelity: str = "full", friction_circle: bool = True, bushing_running_in: bool = False,
                 bushing_length_scheme: str = "thesis", bolt_method: str = "thesis", drive=None,
                 spring_limit_basis: str | None = None, *, rules=None, catalogs=None, engine: str = "auto", capability=None):
        if isinstance(drive, dict):
            drive = drive_from_mapping(drive)
        if fidelity not in FIDELITIES:
            raise InputError(Problem("fidelity", fidelity, "one of " + ", ".join(FIDELITIES)))
        if bolt_method not in ("thesis", "vdi2230"):
            raise InputError(Problem("bolt_method", bolt_method, "thesis or vdi2230"))
        if bushing_length_scheme not in ("thesis", "catalog"):
            raise InputError(Problem("bushing_length_scheme", bushing_length_scheme, "thesis or catalog"))
        if engine not in ENGINES:
            raise InputError(Problem("engine", engine, " or ".join(ENGINES)))
        if capability is not None and not all(hasattr(capability, k) for k in ("capability", "ppm", "samples")):
            raise InputError(Problem("capability", capability, "None or a synth.robust.settings.RobustSettings"))
        rules = NONE if rules is None else Rules.from_mapping(rules)
        if spring_limit_basis is not None and spring_limit_basis != rules.spring_limit_basis:
            if spring_limit_basis not in SPRING_LIMIT_BASES:
                raise InputError(Problem("spring_limit_basis", spring_limit_basis, " or ".join(SPRING_LIMIT_BASES)))
            rules = dataclasses.replace(rules, spring_limit_basis=spring_limit_basis)
        if catalogs is not None:
            if isinstance(catalogs, (str, Path)):
                catalogs = (catalogs,)
            catalogs = tuple(str(p) for p in catalogs)
        for name, value in (("fidelity", fidelity), ("friction_circle", bool(friction_circle)),
                            ("bushing_running_in", bool(bushing_running_in)),
                            ("bushing_length_scheme", bushing_length_scheme), ("bolt_method", bolt_method),
                            ("drive", drive), ("rules", rules), ("catalogs", catalogs), ("engine", engine),
                            ("capability", capability)):
            object.__setattr__(self, name, value)

    def __setstate__(self, state: dict) -> None:
        """Unpickled in a worker (a Dask task, a process pool): the installed plug-ins' declarations first
        (:func:`synth.plugins.load`), so the worker judges by the checks and objectives the sender did."""
        from synth import plugins
        plugins.load()
        self.__dict__.update(state)

    @property
    def spring_limit_basis(self) -> str:
        """The main spring's installation check's basis: the rules' (:attr:`Rules.spring_limit_basis`)."""
        return self.rules.spring_limit_basis

    @property
    def model(self) -> str:
        """The physics the groups compute with these settings: ``"full"`` or ``"screening"``."""
        return "full" if self.fidelity == "full" else "screening"

    @property
    def judge(self) -> "Settings":
        """The settings whose model decides a design's verdict: full fidelity for ``"screening"`` (screen, then
        verify), these settings otherwise (``"screening-only"`` is not verified).

        >>> Settings(fidelity="screening").judge.fidelity, Settings(fidelity="screening-only").judge.model
        ('full', 'screening')
        """
        if self.fidelity != "screening":
            return self
        return dataclasses.replace(self, fidelity="full")

    def notes(self) -> list:
        """What a reported design's notes say about its fidelity: :data:`UNVERIFIED_NOTE` at screening-only."""
        return [UNVERIFIED_NOTE] if self.fidelity == "screening-only" else []

    def as_dict(self) -> dict:
        """The model settings a result records (:data:`MODEL_KEYS`; the rules are recorded apart, ``Result.rules``)."""
        out = {}
        for k in MODEL_KEYS:
            v = getattr(self, k)
            out[k] = dataclasses.asdict(v) if dataclasses.is_dataclass(v) and not isinstance(v, type) else v
        return out

    def resolved(self) -> "Settings":
        """These settings with the user catalog folders fixed (:attr:`catalogs`: this process's when None), as they
        must be before they leave the process (a Dask task, a process pool)."""
        if self.catalogs is not None:
            return self
        from synth import catalog
        return dataclasses.replace(self, catalogs=tuple(str(p) for p in catalog.user_dirs()))

    def replace(self, **changes) -> "Settings":
        """A copy with ``changes`` (any keyword of the constructor, ``spring_limit_basis`` included)."""
        basis = changes.pop("spring_limit_basis", None)
        out = dataclasses.replace(self, **changes) if changes else self
        return out if basis is None or basis == out.spring_limit_basis else dataclasses.replace(
            out, rules=dataclasses.replace(out.rules, spring_limit_basis=_basis(basis)))

    @classmethod
    def from_saved(cls, settings: dict | None, rules=None) -> "Settings":
        """The settings a saved result was made under: its model settings (``Result.settings``) and its rules
        (``Result.rules``); a key this version does not know is left out."""
        s = {k: v for k, v in (settings or {}).items() if k in MODEL_KEYS}
        return cls(**s, rules=Rules.from_mapping(rules) if rules else NONE)


def _basis(value: str) -> str:
    if value not in SPRING_LIMIT_BASES:
        raise InputError(Problem("spring_limit_basis", value, " or ".join(SPRING_LIMIT_BASES)))
    return value


#: the default configuration (full fidelity, no rules, this process's catalogs, each path's engine)
DEFAULT = Settings()
