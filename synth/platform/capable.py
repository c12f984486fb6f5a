"""``synth rationalise --capability``: a platform whose every assigned design meets the production capability target.

The capability target (:attr:`synth.design.settings.Settings.capability`, a
:class:`~synth.robust.settings.RobustSettings`: ``--capability``/``--ppm``, or the design rules' targets) is
honoured lazily (constraint generation): the platform is chosen on the nominal feasibility data, the capability of
every design the solution assigns is evaluated with the function ``synth design --capability`` reports a design's
capability with (:func:`synth.robust.synthesis.nominal_capability`: the design made, at the judging model), and
every assigned design that misses the target is excluded from the data before the platform is chosen again, until
every assigned design meets it. A design meets it as ``synth design --capability`` judges a candidate
(:func:`failing_made`): its targeted checks meet the target and it passes every check nominally with the joint
made (the platform's data are judged under the thesis's tightening, the preload sized to the requirement).

At an application's first miss, the robust search decides whether any catalog design meets the target at all
(:func:`none_capable`); where none does, the application loses every core at once.

What is excluded rests on the decomposition the robust synthesis rests on (:mod:`synth.robust.synthesis`): given
the core, a subsystem check's capability depends only on that subsystem's option, also in the samples (each
quantity gets the same random numbers in every design: common random numbers). So when an assigned design fails a
check of subsystem ``s``, every option of ``s`` still feasible for that core is evaluated at once
(:func:`failing_options`, the other subsystems at the assigned options, each (application, core, subsystem) once)
and every option failing a check of ``s`` is excluded for that core in the same round: every design with such a
(core, option) pair fails that check too. A failing core or input check excludes the core. Each round's data thus
hold every capable design, and a platform whose assigned designs all meet the target is optimal among the capable
ones (to the MILP's own gap and limits). One approximation: the batch samples as the robust search's
walks do, without importance sampling under a Ppk target, which changes only a bounded check's Ppk (read from the
Monte Carlo's probability bound instead), so an option near the target may be judged otherwise than the full
evaluation would: an option wrongly excluded costs optimality, never capability, since an assigned design is
always judged by the full evaluation (:func:`synth.robust.synthesis.nominal_capability`, which also gives the
reported capability), and its own failing option is always excluded, so the loop ends.
An application whose designs are all excluded is reported not served with the best index its assigned designs
reached and their failing checks.
"""

from __future__ import annotations

import dataclasses
import math
import time

import numpy as np

from synth.design.constraints import REGISTRY
from synth.platform.data import SUBSYSTEMS

__all__ = ["choose", "rules_capability", "capable_rounds", "exclude", "failing_options", "failing_made", "none_capable",
           "capability_words"]

#: designs per batched capability call (bounds the memory of one call: each design holds its samples)
CHUNK = 32

#: the groups whose failing checks exclude the core (no subsystem option changes them): the robust search's own
#: (:data:`synth.robust.synthesis._CORE_GROUPS`); a check of any group that is not a subsystem excludes the core too
_SUBSYSTEM_GROUPS = frozenset(SUBSYSTEMS)


def keep_cores(a, keep):
    """A copy of application ``a`` (:class:`~synth.platform.data.AppFeasibility`) with only the cores ``keep`` (a
    boolean mask)."""
    return dataclasses.replace(
        a, core_parts={f: np.asarray(v)[keep] for f, v in a.core_parts.items()},
        core_cost_eur=np.asarray(a.core_cost_eur)[keep], core_margin=np.asarray(a.core_margin)[keep],
        group={s: np.asarray(g)[keep] for s, g in a.group.items()},
        core_binding=None if a.core_binding is None else np.asarray(a.core_binding)[keep],
        core_rows=None if a.core_rows is None else np.asarray(a.core_rows)[keep])


def none_capable(d, settings, rs) -> bool:
    """Whether no design of the catalogs meets ``rs``'s target for input ``d``: the robust search
    (:func:`synth.robust.synthesis.search`, ``synth design --capability``'s, under the made joint of ``settings``)
    over every core finds none. Its proof covers every design of the platform's data (a subset of the catalogs')."""
    from synth.optimise.objectives import FALLBACK_WEIGHTS
    from synth.optimise.product import evaluate
    from synth.robust.sampling import production
    from synth.robust.synthesis import search
    with np.errstate(all="ignore"):
        return search(evaluate(d, production(settings)), FALLBACK_WEIGHTS, rs)[1] is None


def exclude(a, core: int, drop: dict | None):
    """A copy of application ``a`` (:class:`~synth.platform.data.AppFeasibility`) without the core ``core``
    (``drop`` None) or without, for that core, the options ``drop[s]`` of each subsystem ``s`` (the core moves to a
    group of its own that lacks them; the other cores keep theirs)."""
    if drop is None:
        return keep_cores(a, np.arange(a.n_cores) != int(core))
    group, feasible, margin = dict(a.group), dict(a.feasible), dict(a.option_margin)
    binding = None if a.option_binding is None else dict(a.option_binding)
    for s in sorted(drop):
        g = int(a.group[s][int(core)])
        opts = np.asarray(feasible[s][g])
        keep = ~np.isin(opts, np.asarray(sorted(drop[s]), dtype=opts.dtype))
        feasible[s] = [*feasible[s], opts[keep]]
        margin[s] = [*margin[s], np.asarray(margin[s][g])[keep]]
        if binding is not None and binding.get(s) is not None:
            binding[s] = [*binding[s], np.asarray(binding[s][g])[keep]]
        group[s] = np.array(group[s], copy=True)
        group[s][int(core)] = len(feasible[s]) - 1
    return dataclasses.replace(a, group=group, feasible=feasible, option_margin=margin, option_binding=binding)


def failing_options(pf, i: int, core: int, options: dict, s: str, settings, rs) -> list:
    """The options of subsystem ``s`` still feasible for core ``core`` of application ``i`` (of ``pf``) whose design
    (the other subsystems at ``options``) fails a check of group ``s`` under ``rs``: every option evaluated at once
    (:func:`synth.robust.capability.capabilities`, :data:`CHUNK` designs per call), as the robust search's walks
    evaluate candidates (importance sampling only with a ppm target)."""
    from synth.design.space import space
    from synth.platform.verified import design_parts
    from synth.robust.capability import capabilities
    from synth.robust.sampling import bases_of_attributes
    from synth.robust.tolerances import tolerances
    a, sp, table = pf.apps[i], space(), tolerances()
    opts = [int(k) for k in a.feasible[s][int(a.group[s][int(core)])]]
    bad = []
    for lo in range(0, len(opts), CHUNK):
        chunk = opts[lo:lo + CHUNK]
        parts = design_parts(pf, [(i, core, {**options, s: k}) for k in chunk])
        with np.errstate(all="ignore"):
            bases, stacked = bases_of_attributes(pf.design_inputs[i], [sp.design_attributes(p) for p in parts],
                                                 settings, table)
            caps = capabilities(bases, stacked, rs, rare=rs.ppm is not None, details=False)
        bad += [k for k, b, cap in zip(chunk, bases, caps)
                if any(REGISTRY[c].group == s for c in failing_made(cap.failing(), b))]
    return bad


def failing_made(missed, base) -> list:
    """The ids a design fails as ``synth design --capability`` judges it: its targeted checks that miss the target
    (``missed``, checks or ids), then every other check its nominal verdict under the made joint fails (``base``, a
    :class:`~synth.robust.sampling.Base`: the one assessment of its nominal evaluation): the robust search takes
    only designs that pass every check nominally. A design assembled from the platform's data passes them under the
    thesis's tightening, not always under the made joint (VDI 2230's preload window: ``bolt_preload_vdi``,
    ``thread``)."""
    from synth.design.assessment import assess
    out = [getattr(c, "id", c) for c in missed]
    a = assess(base.groups, base.apps)
    return out + [str(c) for c in a.columns.ids[a.failed[0]] if c not in out]


def capability_words(rs) -> str:
    """The target and the estimator in words (the run's summary line and ``summary.md``)."""
    return f"{rs.targets()}, {rs.samples} samples per design, seed {rs.seed}"


def capable_rounds(pf, run, settings):
    """``(result, pf, stats)``: the platform ``run(pf)`` (a :class:`~synth.platform.rationalise.PlatformResult`
    with verified records) chooses once every assigned design meets ``settings.capability`` (see the module
    docstring); ``pf`` the data of the last round (the failing pairs excluded); ``stats``: ``rounds``,
    ``evaluated`` (distinct assigned designs whose capability was computed), ``options_evaluated`` (designs of
    the batches, :func:`failing_options`), ``excluded`` ((core, option) pairs and cores), ``capability_s``.

    Every served record carries ``capability`` (the dict of :meth:`~synth.robust.capability.Capability.to_dict`'s
    ``meets``, ``min_ppk``, ``failing``); a record not served after an exclusion carries the best of its
    application's evaluated designs, and its reason says so."""
    from synth.robust.synthesis import made_capability
    rs, judge = settings.capability, settings.judge
    memo: dict = {}      # (application, design) -> its capability
    batched: dict = {}   # (application, core row, subsystem) -> the options whose own checks fail
    best: dict = {}      # application index -> the evaluated design with the highest smallest Ppk
    proved: dict = {}    # application index -> the robust search found no capable catalog design
    stats = {"rounds": 0, "evaluated": 0, "options_evaluated": 0, "searched": 0, "excluded": 0, "capability_s": 0.0}
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
                    made, base = made_capability(pf.design_inputs[i], rec["design"], judge, rs)
                full = made.to_dict()  # nominal_capability's
                failing = failing_made(full["failing"], base)
                memo[key] = {"meets": not failing,
                             "min_ppk": math.inf if full["min_ppk"] is None else float(full["min_ppk"]),
                             "failing": failing}
                stats["evaluated"] += 1
            cap = rec["capability"] = memo[key]
            if i not in best or cap["min_ppk"] > best[i]["min_ppk"]:
                best[i] = {**cap, "design": rec["design"]}
            if cap["meets"]:
                continue
            missed = True
            if i not in proved:  # its first miss: is any catalog design capable at all? (one robust search)
                proved[i] = none_capable(pf.design_inputs[i], judge, rs)
                stats["searched"] += 1
            if proved[i]:
                apps[i] = keep_cores(apps[i], np.zeros(apps[i].n_cores, dtype=bool))
                stats["excluded"] += pf.apps[i].n_cores
                continue
            c, a = int(rec["core"]), pf.apps[i]
            groups = {REGISTRY[x].group for x in cap["failing"]}
            if groups - _SUBSYSTEM_GROUPS:   # a core or input check: no option changes it
                apps[i] = exclude(apps[i], c, None)
                stats["excluded"] += 1
                continue
            drop = {}
            for s in sorted(groups):
                b = (i, int(a.core_rows[c]), s)
                if b not in batched:
                    batched[b] = failing_options(pf, i, c, rec["options"], s, judge, rs)
                    stats["options_evaluated"] += len(a.feasible[s][int(a.group[s][c])])
                drop[s] = {*batched[b], int(rec["options"][s])}  # the assigned one always (the loop progresses)
            apps[i] = exclude(apps[i], c, drop)
            stats["excluded"] += sum(len(v) for v in drop.values())
        stats["capability_s"] += time.perf_counter() - t0
        if not missed:
            break
        pf = dataclasses.replace(pf, apps=apps)
    for i, rec in enumerate(r.records):
        if not rec["feasible"] and i in best and best[i]["failing"]:
            b = best[i]
            rec["capability"] = {k: b[k] for k in ("meets", "min_ppk", "failing")}
            rec["reason"] = (f"no design meets {rs.targets()}"
                             + (" (the robust search finds none in the catalogs)" if proved.get(i) else "")
                             + f": the best assigned reached Ppk {b['min_ppk']:.3g} (failing {' '.join(b['failing'])})"
                             + (f"; {rec['reason']}" if rec.get("reason") else ""))
    return r, pf, stats


def rules_capability(rules, samples: int | None = None):
    """The :class:`~synth.robust.settings.RobustSettings` of the design rules' capability targets (``ppk_min``,
    ``ppm_max``: :meth:`~synth.design.rules.Rules.targets`) at ``samples`` per design (default
    :data:`~synth.robust.settings.BULK_SAMPLES`, as ``synth rationalise``), or None without targets: what the web
    page's platform reads (the command line also takes ``--capability``/``--ppm``)."""
    from synth.robust.settings import BULK_SAMPLES, RobustSettings
    cap, ppm = (None, None) if rules is None else rules.targets()
    if cap is None and ppm is None:
        return None
    return RobustSettings(capability=cap, ppm=ppm, samples=BULK_SAMPLES if samples is None else samples)


def choose(pf, run, settings):
    """``(result, pf)``: the platform ``run(pf)`` chooses, honouring ``settings.capability`` when it is set
    (:func:`capable_rounds`, its summary in ``result.capability_line`` and ``result.notes``; ``pf`` then the last
    round's data), else ``run(pf)`` as it is. The one entry ``synth rationalise`` and the web page's platform
    take, so a target never stays behind in one of them."""
    rs = getattr(settings, "capability", None)
    if rs is None:
        return run(pf), pf
    r, pf, st = capable_rounds(pf, run, settings)
    ok = sum(1 for x in r.records if x["feasible"])
    r.capability_line = (
        f"capability: {capability_words(rs)} ({rs.method} method): every assigned design meets it ({ok} "
        f"applications); {st['rounds']} rounds, {st['evaluated']} assigned designs and {st['options_evaluated']} "
        f"options evaluated, {st['searched']} robust searches, {st['excluded']} failing (core, option) exclusions, "
        f"{st['capability_s']:.1f} s")
    r.notes.append(r.capability_line)
    return r, pf
