"""``synth rationalise --capability``: a platform whose every assigned design meets the production capability target.

The capability target (:attr:`synth.design.settings.Settings.capability`, a
:class:`~synth.robust.settings.RobustSettings`: ``--capability``/``--ppm``, or the design rules' targets) is
honoured lazily (constraint generation): the platform is chosen on the nominal feasibility data, the capability of
every design the solution assigns is evaluated with the function ``synth design --capability`` reports a design's
capability with (:func:`synth.robust.synthesis.nominal_capability`: the design made, at the judging model), and
every assigned design that misses the target is excluded from the data before the platform is chosen again, until
every assigned design meets it.

What is excluded is exact, by the decomposition the robust synthesis rests on (:mod:`synth.robust.synthesis`): a
check's capability is a property of the core and its own subsystem's option (common random numbers), so a failing
check of a subsystem excludes that (core, option) pair for that application (every design with it fails too), and a
failing check of the core or of the input excludes the core for that application. The loop is exact for the MILP:
the data of each round hold every capable design (only designs with a failing pair are removed), so a platform
whose assigned designs all meet the target is optimal among the capable ones (to the MILP's own gap and limits).
An application whose designs are all excluded is reported not served with the best index its assigned designs
reached and their failing checks.

Each distinct (application, design) is evaluated once (:func:`capable_rounds` keeps them across rounds).
"""

from __future__ import annotations

import dataclasses
import math
import time

import numpy as np

from synth.design.constraints import REGISTRY
from synth.platform.data import SUBSYSTEMS

__all__ = ["capable_rounds", "exclude", "capability_words"]

#: the groups whose failing checks exclude the core (no subsystem option changes them): the robust search's own
#: (:data:`synth.robust.synthesis._CORE_GROUPS`); a check of any group that is not a subsystem excludes the core too
_SUBSYSTEM_GROUPS = frozenset(SUBSYSTEMS)


def exclude(a, core: int, options: dict, failing: list):
    """A copy of application ``a`` (:class:`~synth.platform.data.AppFeasibility`) without the pairs the ``failing``
    checks of its design (``core``, ``{subsystem: option}``) reject: the core (a check outside the subsystems fails)
    or the (core, option) of each subsystem with a failing check (the core moves to a group of its own that lacks
    the option; the other cores keep theirs)."""
    groups = {REGISTRY[c].group for c in failing}
    if groups - _SUBSYSTEM_GROUPS:
        keep = np.arange(a.n_cores) != int(core)
        return dataclasses.replace(
            a, core_parts={f: np.asarray(v)[keep] for f, v in a.core_parts.items()},
            core_cost_eur=np.asarray(a.core_cost_eur)[keep], core_margin=np.asarray(a.core_margin)[keep],
            group={s: np.asarray(g)[keep] for s, g in a.group.items()},
            core_binding=None if a.core_binding is None else np.asarray(a.core_binding)[keep],
            core_rows=None if a.core_rows is None else np.asarray(a.core_rows)[keep])
    group, feasible, margin = dict(a.group), dict(a.feasible), dict(a.option_margin)
    binding = None if a.option_binding is None else dict(a.option_binding)
    for s in sorted(groups):
        g = int(a.group[s][int(core)])
        opts = np.asarray(feasible[s][g])
        keep = opts != int(options[s])
        feasible[s] = [*feasible[s], opts[keep]]
        margin[s] = [*margin[s], np.asarray(margin[s][g])[keep]]
        if binding is not None and binding.get(s) is not None:
            binding[s] = [*binding[s], np.asarray(binding[s][g])[keep]]
        group[s] = np.array(group[s], copy=True)
        group[s][int(core)] = len(feasible[s]) - 1
    return dataclasses.replace(a, group=group, feasible=feasible, option_margin=margin, option_binding=binding)


def capability_words(rs) -> str:
    """The target and the estimator in words (the run's summary line and ``summary.md``)."""
    return f"{rs.targets()}, {rs.samples} samples per design, seed {rs.seed}"


def capable_rounds(pf, run, settings):
    """``(result, pf, stats)``: the platform ``run(pf)`` (a :class:`~synth.platform.rationalise.PlatformResult`
    with verified records) chooses once every assigned design meets ``settings.capability`` (see the module
    docstring); ``pf`` the data of the last round (the failing pairs excluded); ``stats``: ``rounds``,
    ``evaluated`` (distinct designs whose capability was computed), ``excluded`` (pairs), ``capability_s``.

    Every served record carries ``capability`` (the dict of :meth:`~synth.robust.capability.Capability.to_dict`'s
    ``meets``, ``min_ppk``, ``failing``); a record not served after an exclusion carries the best of its
    application's evaluated designs, and its reason says so."""
    from synth.robust.synthesis import nominal_capability
    rs, judge = settings.capability, settings.judge
    memo: dict = {}
    best: dict = {}      # application index -> the evaluated design with the highest smallest Ppk
    stats = {"rounds": 0, "evaluated": 0, "excluded": 0, "capability_s": 0.0}
    while True:
        stats["rounds"] += 1
        r = run(pf)
        apps = list(pf.apps)
        missed = False
        t0 = time.perf_counter()
        for i, rec in enumerate(r.records):
            if not rec["feasible"] or "design" not in rec:
                continue
            key = (i, tuple(sorted(rec["design"].items())))
            if key not in memo:
                with np.errstate(all="ignore"):
                    full = nominal_capability(pf.design_inputs[i], rec["design"], judge, rs)
                memo[key] = {"meets": bool(full["meets"]), "min_ppk": math.inf if full["min_ppk"] is None else float(full["min_ppk"]),
                             "failing": list(full["failing"])}
                stats["evaluated"] += 1
            cap = rec["capability"] = memo[key]
            if i not in best or cap["min_ppk"] > best[i]["min_ppk"]:
                best[i] = {**cap, "design": rec["design"]}
            if not cap["meets"]:
                missed = True
                apps[i] = exclude(apps[i], rec["core"], rec["options"], cap["failing"])
                stats["excluded"] += 1
        stats["capability_s"] += time.perf_counter() - t0
        if not missed:
            break
        pf = dataclasses.replace(pf, apps=apps)
    for i, rec in enumerate(r.records):
        if not rec["feasible"] and i in best and best[i]["failing"]:
            b = best[i]
            rec["capability"] = {k: b[k] for k in ("meets", "min_ppk", "failing")}
            rec["reason"] = (f"no design meets {rs.targets()}: the best assigned reached Ppk {b['min_ppk']:.3g} "
                             f"(failing {' '.join(b['failing'])})" + (f"; {rec['reason']}" if rec.get("reason") else ""))
    return r, pf, stats
