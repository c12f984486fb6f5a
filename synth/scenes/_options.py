"""Options and steps every design scene shares: the model settings, the default synthesis, saved results.

One place decides what ``synth design``, ``synth report``, ``synth demo`` and
``synth design --cad`` run for an input, so they show the same design at the
same fidelity by default: the exhaustive optimum (``enumerate``) of the most
standardised design (objective ``standard``, then cost, then the margin as
tie-breaks: :func:`synth.optimise.objectives.with_margin_tiebreak`), full
fidelity; with ``--capability``/``--ppm`` the robust synthesis
(:mod:`synth.robust.synthesis`).
"""

from __future__ import annotations

from pathlib import Path
from synth.design import rules
from synth.optimise import SOLVERS
from synth.robust.settings import DEFAULT_SAMPLES, RobustSettings
from synth.errors import InputError, Problem
from synth.io.limits import check_count
from synth.optimise.honour import solve_honouring
from synth.progress import phase
from synth.io.saved_results import load_result

__all__ = ["add_rules_options", "add_model_options", "settings_from_args", "rules_of", "add_design_options", "add_robust_options",
           "robust_settings_from_args", "synthesise", "load_saved_result",
           "DEFAULT_SOLVER", "DEFAULT_OBJECTIVE", "default_args"]

DEFAULT_SOLVER = "enumerate"
DEFAULT_OBJECTIVE = "standard"


def add_rules_options(p, judged: str = "the input file's own rules: section when not given") -> None:
    """``--rules FILE`` and ``--spring-limit``: the design rules a run is judged by (``judged``: what else gives
    them, or who is judged)."""
    p.add_argument("--rules", metavar="FILE", default=None,
                   help="design rules (required safety factors and limits, minimum margins, spring limit basis, "
                        f"capability targets): a rules file (synth.design.rules); {judged}")
    p.add_argument("--spring-limit", choices=("thesis", "en13906"), default=None,
                   help="design rule of the main spring's installation stress: the thesis's yield check "
                        "(sigma_y_bend_fraction Rm on the curvature-corrected stress, default) or EN 13906-3's "
                        "static rule (0.75 Rm on the stress without curvature factor); default: the design rules' "
                        "spring_limit_basis (rules: section or --rules), else thesis")


def add_model_options(p) -> None:
    add_rules_options(p)
    from synth.design.evaluate import FIDELITIES
    p.add_argument("--fidelity", choices=FIDELITIES, default="full",
                   help="full: Almen-Laszlo cone spring and its exact wear (default); screening: searched with the "
                        "linear, closed forms, the design verified at full fidelity; screening-only: unverified")
    p.add_argument("--linear-friction", action="store_true",
                   help="radial friction on r_p*mu as the thesis tool did (default: friction circle r_p*sin(atan(mu)))")
    p.add_argument("--bolt-method", choices=("thesis", "vdi2230"), default="thesis",
                   help="fixation bolt: the thesis's elastic check of the nominal preload (default) or VDI 2230-1 "
                        "(permissible assembly preload, tightening factor, embedding)")


def rules_of(args):
    """The design rules of a scene's command line (:func:`synth.design.rules.of_args`: ``--rules FILE``, else the
    input file's ``rules:`` section), read once per command line."""
    got = getattr(args, "_synth_rules", None)
    if got is None:
        got = rules.of_args(args)
        setattr(args, "_synth_rules", got)
    return got


def settings_from_args(args):
    """The run's configuration (:class:`~synth.design.settings.Settings`) of the options, resolved once: the model
    settings, the design rules (:func:`rules_of`) and the spring limit basis of ``--spring-limit``, else the
    rules'."""
    from synth.design.settings import Settings
    return Settings(fidelity=args.fidelity, friction_circle=not args.linear_friction,
                    bolt_method=getattr(args, "bolt_method", "thesis"), drive=getattr(args, "drive_model", None),
                    spring_limit_basis=getattr(args, "spring_limit", None), rules=rules_of(args))


def add_design_options(p) -> None:
    """The synthesis options (objective, solver, pinning, trials, time limit) and the model options."""
    p.add_argument("--objective", default=DEFAULT_OBJECTIVE,
                   help="standard | cost | margin, a lexicographic list 'a,b' or weights 'cost=1,margin=5'")
    p.add_argument("--solver", default=DEFAULT_SOLVER, choices=list(SOLVERS),
                   help=f"catalog solver (default {DEFAULT_SOLVER}: exact; every solver answers the same question, "
                        "docs: optimisation)")
    p.add_argument("--pin-inputs", action="store_true",
                   help="keep every part the input names (pivot class, bushing thickness, main spring, bolt), "
                        "feasible or not; by default a named part is kept unless no design with it passes")
    p.add_argument("--fix", nargs="+", metavar="FIELD", default=[],
                   help="keep these named parts whatever the verdict (fields of synth/schema.py that name a part)")
    p.add_argument("--free", nargs="+", metavar="FIELD", default=[],
                   help="let synth choose these parts for the objective, whatever the input names")
    p.add_argument("--top", type=int, default=1, metavar="K",
                   help="also the K best designs in objective order, what differs between them and their margins "
                        "(1 to 50): designs distinct in a catalog part (--distinct); an infeasible input: its K "
                        "nearest designs")
    p.add_argument("--distinct", nargs="+", metavar="KEY", default=None,
                   help="--top: the part keys that make two designs different alternatives (default: every "
                        "catalog part; the main spring's mean diameter and the cone spring's variant are "
                        "dimensions of one part)")
    p.add_argument("--trials", type=int, default=200, help="blackbox: trials per subsystem study (1 to 100000)")
    p.add_argument("--time-limit", type=float, default=None, metavar="S",
                   help="seconds for the solver (minlp, milp-*, blackbox): on expiry the best design found so far")
    add_model_options(p)


def add_robust_options(p, *, default_capability=None) -> None:
    """The capability options (:class:`synth.robust.settings.RobustSettings`): target, ppm, samples, seed."""
    p.add_argument("--capability", type=float, default=default_capability, metavar="PPK",
                   help="production capability target: every checked constraint with Ppk >= PPK under the tolerance "
                        "model (catalogs/tolerances.csv); 1.33 is the usual target")
    p.add_argument("--ppm", type=float, default=None, metavar="N",
                   help="production target: every checked constraint violated by at most N parts per million "
                        "(the upper end of its 95 %% interval)")
    p.add_argument("--samples", type=int, default=DEFAULT_SAMPLES, metavar="N",
                   help=f"Monte Carlo samples per design (scrambled Sobol; default {DEFAULT_SAMPLES}; 64 to 262144, "
                        "the bulk 64 to 2048 per application)")
    p.add_argument("--seed", type=int, default=RobustSettings().seed, help="seed of the samples (same seed, same numbers)")
    p.add_argument("--capability-method", choices=("percentile", "moment"), default=None,
                   help="how Ppk is computed (ISO 22514-2): percentile (default: (X50 - LSL)/(X50 - X0.135%%), for any "
                        "distribution) or moment ((mu - LSL)/(3 sigma)); bounded outputs are judged by their ppm")


def robust_settings_from_args(args, *, default_capability=None, samples: str = "--samples"):
    """The :class:`~synth.robust.settings.RobustSettings` of the options (checked: a bad value names its option;
    ``--samples`` within the bounds of ``samples``, a key of :data:`synth.io.limits.COUNTS`: one design's or the
    bulk's); without ``--capability`` and ``--ppm``, the design rules' capability targets (``ppk_min``,
    ``ppm_max``), else ``default_capability``."""
    if getattr(args, "samples", None) is not None:
        check_count(samples, args.samples)
    names = {"capability": "--capability", "ppm": "--ppm", "samples": "--samples", "seed": "--seed",
             "method": "--capability-method"}
    cap, ppm = getattr(args, "capability", None), getattr(args, "ppm", None)
    if cap is None and ppm is None:
        cap, ppm = rules_of(args).targets()
        if cap is None and ppm is None:
            cap = default_capability
    kw = {"capability": cap, "ppm": ppm, "samples": getattr(args, "samples", None), "seed": getattr(args, "seed", None),
          "method": getattr(args, "capability_method", None)}
    kw = {k: v for k, v in kw.items() if v is not None or k in ("capability", "ppm")}
    try:
        return RobustSettings(**kw)
    except InputError as exc:
        raise InputError([Problem(names.get(p.field, p.field), p.value, p.accepted) for p in exc.problems]) from None


def default_args():
    """The design options at their defaults (the synthesis every scene runs when not told otherwise)."""
    import argparse
    p = argparse.ArgumentParser()
    add_design_options(p)
    return p.parse_args([])


def synthesise(d, args):
    """The :class:`~synth.design.result.Result` of the synthesis the options of ``args`` ask for (with
    ``--capability``/``--ppm``: the robust synthesis of :mod:`synth.robust.synthesis`)."""
    check_count("--trials", getattr(args, "trials", 200))
    check_count("--top", getattr(args, "top", 1))
    limit = getattr(args, "time_limit", None)
    if limit is not None and not (0 < limit <= 86_400):
        raise InputError(Problem("--time-limit", limit, "seconds in (0, 86400]"))
    kw = {"settings": settings_from_args(args), "pin_inputs": getattr(args, "pin_inputs", False),
          "fix": getattr(args, "fix", ()), "free": getattr(args, "free", ()), "top": getattr(args, "top", 1),
          "distinct": getattr(args, "distinct", None)}
    rs = robust_settings_from_args(args)  # --capability/--ppm, else the design rules' targets
    if rs.capability is not None or rs.ppm is not None:
        from synth.robust.synthesis import robust_for  # scipy and pandas: only for a robust synthesis
        kw["robust"] = robust_for(rs)
    if args.solver == "blackbox":
        kw["n_trials"] = args.trials
    if limit is not None:
        kw["time_limit_s"] = limit
    solver = getattr(args, "solver", DEFAULT_SOLVER)
    with phase(f"synth: synthesis ({solver}; an infeasible input is diagnosed)"):  # a terminal only
        return solve_honouring(d, getattr(args, "objective", DEFAULT_OBJECTIVE), solver, **kw)


def load_saved_result(path: str | Path, what: str = "result", *, needs_inputs: bool = False):
    """A :class:`~synth.design.result.Result` saved with ``--json`` (any scene), read through the input gate
    (:func:`synth.io.saved_results.load_result`: size, encoding, shape, carried inputs); errors name the file and
    the key (``needs_inputs``: a result without its ``inputs`` is refused naming it)."""
    from synth.design.result import Result
    return Result.from_dict(load_result(path, what, needs_inputs=needs_inputs), source=str(Path(path).name))
