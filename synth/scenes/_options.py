"""Options and steps every design scene shares: the model settings, the default synthesis, saved results.

One place decides what ``synth design``, ``synth report``, ``synth demo`` and
``synth design --cad`` run for an input, so they show the same design at the
same fidelity by default: the exhaustive optimum (``enumerate``) of the most
standardised design (objective ``standard``, cost as tie-break), full fidelity.
"""

from __future__ import annotations

from pathlib import Path

__all__ = ["add_model_options", "settings_from_args", "add_design_options", "synthesise", "load_saved_result",
           "DEFAULT_SOLVER", "DEFAULT_OBJECTIVE"]

DEFAULT_SOLVER = "enumerate"
DEFAULT_OBJECTIVE = "standard"


def add_model_options(p) -> None:
    from synth.design.evaluate import FIDELITIES
    p.add_argument("--fidelity", choices=FIDELITIES, default="full",
                   help="full: Almen-Laszlo cone spring and its exact wear (default); screening: searched with the "
                        "linear, closed forms, the design verified at full fidelity; screening-only: unverified")
    p.add_argument("--linear-friction", action="store_true",
                   help="radial friction on r_p*mu as the thesis tool did (default: friction circle r_p*sin(atan(mu)))")
    p.add_argument("--bolt-method", choices=("thesis", "vdi2230"), default="thesis",
                   help="fixation bolt: the thesis's elastic check of the nominal preload (default) or VDI 2230-1 "
                        "(permissible assembly preload, tightening factor, embedding)")


def settings_from_args(args):
    from synth.design.evaluate import Settings
    return Settings(fidelity=args.fidelity, friction_circle=not args.linear_friction,
                    bolt_method=getattr(args, "bolt_method", "thesis"))


def add_design_options(p) -> None:
    """The synthesis options (objective, solver, pinning, trials, time limit) and the model options."""
    from synth.optimise import SOLVERS
    p.add_argument("--objective", default=DEFAULT_OBJECTIVE,
                   help="standard | cost | margin, a lexicographic list 'a,b' or weights 'cost=1,margin=5'")
    p.add_argument("--solver", default=DEFAULT_SOLVER, choices=list(SOLVERS))
    p.add_argument("--pin-inputs", action="store_true", help="keep the part choices the input names")
    p.add_argument("--trials", type=int, default=200, help="blackbox: number of trials (1 to 100000)")
    p.add_argument("--time-limit", type=float, default=None, metavar="S",
                   help="seconds for the solver (minlp, milp-*, blackbox): on expiry the best design found so far")
    add_model_options(p)


def synthesise(d, args):
    """The :class:`~synth.design.result.Result` of the synthesis the options of ``args`` ask for."""
    from synth.errors import InputError, Problem
    from synth.optimise import solve
    if not 1 <= int(getattr(args, "trials", 200)) <= 100_000:
        raise InputError(Problem("--trials", args.trials, "an integer from 1 to 100000"))
    limit = getattr(args, "time_limit", None)
    if limit is not None and not (0 < limit <= 86_400):
        raise InputError(Problem("--time-limit", limit, "seconds in (0, 86400]"))
    kw = {"settings": settings_from_args(args)}
    if args.solver not in ("blackbox", "flowchart"):
        kw["pin_inputs"] = getattr(args, "pin_inputs", False)
    if args.solver == "blackbox":
        kw["n_trials"] = args.trials
    if limit is not None:
        kw["time_limit_s"] = limit
    return solve(d, getattr(args, "objective", DEFAULT_OBJECTIVE), getattr(args, "solver", DEFAULT_SOLVER), **kw)


def load_saved_result(path: str | Path, what: str = "result"):
    """A :class:`~synth.design.result.Result` saved with ``--json`` (any scene), read through the input gate
    (:func:`synth.io.results.load_result`: size, encoding, shape, carried inputs); errors name the file."""
    from synth.design.result import Result
    from synth.io.results import load_result
    return Result.from_dict(load_result(path, what), source=str(Path(path).name))
