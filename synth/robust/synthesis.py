"""Robust synthesis: the best design of an objective among those whose every check meets a capability target.

``synth design --capability 1.33`` (or ``--ppm N``): among the catalog designs
that pass every registry check (the nominal verdict) **and** whose every
targeted check (:func:`synth.robust.capability.targeted`) meets the target
under the tolerance model, the best one for the objective (its additive part:
standardisation, cost; ties broken by the nominal margin).

Exact, by the decomposition of the design space (:mod:`synth.design.space`):
given the core, each subsystem's checks depend only on the core and its own
option, also in the samples (each sample fixes the application's scatter and
each quantity's random number is the same in every design: common random
numbers), so a check's capability is a property of (core, option). Per core,
the options of each subsystem are tried in objective order; a candidate's
failing checks name the subsystems whose option fails, and only those move on
to their next option (every design with the failing option fails too): the
first candidate that meets the target is the core's best. Cores are taken in
the order of a lower bound (the core's score plus each subsystem's best
nominally feasible option: robust designs are a subset of the feasible ones)
and the search stops when the next bound is no better than the best robust
design found. No better design is skipped; ``tests/test_robust.py`` compares
it with the exhaustive check of every design of a small space.

>>> from synth.scenes.demo import default_input
>>> from synth.robust.settings import RobustSettings
>>> r = robust_solve(default_input(), "cost", rs=RobustSettings(capability=0.2, samples=512), explain=False)
>>> r.robust["meets"], r.stats["robust_candidates"]  # the made joint's VDI 2230 window: no design reaches 0.2
(False, 0)
"""

from __future__ import annotations

import time

import numpy as np

from synth.design.constraints import REGISTRY
from synth.design.evaluate import Settings
from synth.design.space import SUBSYSTEMS
from synth.optimise.objectives import FALLBACK_WEIGHTS, Objective
from synth.robust.capability import capability
from synth.robust.sampling import base_of, production
from synth.robust.settings import RobustSettings
from synth.optimise.solvers.enumerate import tables
from synth.robust.tolerances import tolerances
from synth.optimise.product import evaluate
from synth.optimise.answer import build_result
from synth.optimise.solvers.enumerate import solve as enumerate_solve
from synth.errors import InputError, Problem

__all__ = ["robust_solve", "robust_for", "nominal_capability", "made_capability", "robust_front", "prevented_by", "SearchReport"]

_EPS = 1e-9
#: the groups whose failing checks reject a core outright (no subsystem option changes them)
_CORE_GROUPS = ("input", "core")


class SearchReport:
    """What the robust search did: candidates checked, cores rejected and by which checks, the best index each
    targeted check reached on any candidate (and what drove its scatter there)."""

    def __init__(self):
        self.candidates = 0
        self.cores_checked = 0
        self.cores_rejected = 0
        self.rejected_by: dict = {}   # check id -> cores whose last candidate failed it
        self.best_ppk: dict = {}      # check id -> best Ppk on any candidate
        self.contributors: dict = {}  # check id -> the contributors where it was best
        self.proof = ""

    def record(self, cap) -> None:
        for c in cap.checks:
            if c.target and c.ppk > self.best_ppk.get(c.id, -np.inf):
                self.best_ppk[c.id] = c.ppk
                self.contributors[c.id] = c.contributors

    def reject(self, cap) -> None:
        self.cores_rejected += 1
        for c in cap.failing():
            self.rejected_by[c.id] = self.rejected_by.get(c.id, 0) + 1

    def why_none(self, rs: RobustSettings) -> str:
        """Why no catalog design meets the target: the checks that rejected the cores, how often, their best
        index over every candidate and what drives their scatter."""
        if not self.rejected_by:
            return ("no catalog design passes every check with the made joint (VDI 2230: the design's tightening "
                    "method, its preload window): the capability has nothing to judge")
        parts = []
        for cid, k in sorted(self.rejected_by.items(), key=lambda kv: (-kv[1], self.best_ppk.get(kv[0], 0)))[:4]:
            drivers = ", ".join(f"{q} {s:.0%}" for q, s in self.contributors.get(cid, [])[:2])
            parts.append(f"{cid} rejects {k} of {self.cores_checked} cores (best Ppk {self.best_ppk.get(cid, np.nan):.3g}"
                         + (f"; its scatter: {drivers}" if drivers else "") + ")")
        return (f"no catalog design meets {rs.targets()}: " + "; ".join(parts)
                + ". Tighten the tolerances that drive them (catalogs/tolerances.csv in a user folder) or widen the "
                  "application's windows")


def _order(score: np.ndarray, feas: np.ndarray, margin: np.ndarray) -> np.ndarray:
    """Feasible options of one core by score, ties by the larger margin."""
    k = np.flatnonzero(feas)
    return k[np.lexsort((-np.nan_to_num(margin[k], nan=-np.inf, posinf=1e300), score[k]))]


def _attributes(ev, pos: int, options: dict) -> dict:
    sp = ev.space
    return {"core": sp.rows("core", [ev.cores[pos]]), **{s: sp.rows(s, [options[s]]) for s in SUBSYSTEMS}}


def search(ev, weights: dict, rs: RobustSettings, *, report: SearchReport | None = None, min_margin: float = -np.inf,
           table=None):
    """The best robust design of evaluation ``ev`` for the additive ``weights``: ``(value, core position,
    options, capability)`` or ``(inf, None, None, None)``; ``min_margin``: options' objective margins must be at
    least this (the Pareto front's thresholds)."""
    table = tolerances() if table is None else table
    rep = SearchReport() if report is None else report
    t = tables(ev, weights)
    nR = len(t.rows)
    orders = {}
    lb = np.array(t.core_score, dtype=float)
    lb = np.where(t.core_margin >= min_margin - _EPS, lb, np.inf)
    for s in SUBSYSTEMS:
        orders[s] = [_order(t.score[s], t.feas[s][r] & (t.margin[s][r] >= min_margin - _EPS), t.margin[s][r])
                     for r in range(nR)]
        first = np.array([t.score[s][o[0]] if len(o) else np.inf for o in orders[s]])
        lb = lb + first
    best = (np.inf, None, None, None)
    order = np.argsort(lb, kind="stable")
    walks = _Walks(ev, t, orders, rs, table, order[np.isfinite(lb[order])])
    for r in order:
        if not np.isfinite(lb[r]) or lb[r] >= best[0] - _EPS * max(1.0, abs(best[0])):
            rep.proof = (f"stopped at a core whose lower bound {lb[r]:.6g} is no better than the best robust design "
                         f"{best[0]:.6g}" if np.isfinite(best[0]) else "every core with a feasible design checked")
            break
        rep.cores_checked += 1
        ptr = {s: 0 for s in SUBSYSTEMS}
        while True:
            opts = {s: int(orders[s][r][ptr[s]]) for s in SUBSYSTEMS}
            value = float(t.core_score[r] + sum(t.score[s][opts[s]] for s in SUBSYSTEMS))
            if value >= best[0] - _EPS * max(1.0, abs(best[0])):
                break  # this core cannot beat the best any more
            cap = walks.capability(int(r), ptr)
            rep.candidates += 1
            failing = cap.failing()
            rep.record(cap)
            if not failing:
                best = (value, int(t.rows[r]), opts, cap)
                break
            if _advance(ptr, failing, orders, r):
                rep.reject(cap)
                break
    else:
        rep.proof = "every core with a feasible design checked"
    return best


def _advance(ptr: dict, failing: list, orders: dict, r: int) -> bool:
    """Move core ``r``'s walk ``ptr`` past the options its candidate's ``failing`` checks reject (every design with
    a failing option fails too); True when the core is done (a core check fails, or a subsystem has no option left).
    """
    groups = {REGISTRY[c.id].group for c in failing}
    if groups & set(_CORE_GROUPS):
        return True
    done = False
    for s in groups:
        ptr[s] += 1
        if ptr[s] >= len(orders[s][r]):
            done = True
    return done


class _Walks:
    """The capabilities of the cores' candidates, evaluated ahead of :func:`search` and together.

    Each core's walk (its candidates in the order :func:`search` takes them, :func:`_advance`) depends on its own
    candidates' capabilities alone; the search's best design only cuts walks short and stops the cores. So the
    walks of the next cores (``upcoming``, in the search's order) are run in lockstep, one candidate of each per
    round, every round's candidates in one batch (:func:`synth.robust.capability.capabilities`: the same
    capability as one at a time); the search reads them and the report counts what it reads, as before. A round
    spans 2**k cores (up to :attr:`WIDTH`) when the search has moved past k cores: an application whose first core
    holds its design evaluates no more than before, one that walks many cores shares the evaluator's calls."""

    WIDTH = 16

    def __init__(self, ev, t, orders: dict, rs: RobustSettings, table, upcoming):
        self.ev, self.t, self.orders, self.rs, self.table = ev, t, orders, rs, table
        self.upcoming = [int(r) for r in upcoming]
        self.ptr: dict = {}       # core -> its walk's pointer (None: done)
        self.cache: dict = {}     # (core, options' positions) -> capability

    def _key(self, r: int, ptr: dict) -> tuple:
        return (r, *(ptr[s] for s in SUBSYSTEMS))

    def capability(self, r: int, ptr: dict):
        key = self._key(r, ptr)
        while key not in self.cache:
            if r in self.ptr and self.ptr[r] is None:
                raise RuntimeError(f"robust search: core {r}'s walk ended before {key}")  # synth's own bug
            self._round(r)
        return self.cache[key]

    def _round(self, r: int) -> None:
        from synth.robust.capability import capabilities
        from synth.robust.sampling import bases_of_attributes
        start = self.upcoming.index(r)
        width = min(2 ** start, self.WIDTH)  # the first core alone; wider as the search moves past cores
        cores = []
        for q in self.upcoming[start:]:
            if len(cores) >= width:
                break
            p = self.ptr.setdefault(q, {s: 0 for s in SUBSYSTEMS})
            if p is not None:
                cores.append(q)
        ev, t = self.ev, self.t
        opts = [{s: int(self.orders[s][q][self.ptr[q][s]]) for s in SUBSYSTEMS} for q in cores]
        attrs = [_attributes(ev, int(t.rows[q]), o) for q, o in zip(cores, opts)]
        bases, stacked = bases_of_attributes(ev.inputs, attrs, ev.settings, self.table, apps=ev.apps)
        caps = capabilities(bases, stacked, self.rs, rare=self.rs.ppm is not None, details=False)
        for q, cap in zip(cores, caps):
            p = self.ptr[q]
            self.cache[self._key(q, p)] = cap
            failing = cap.failing()
            if not failing or _advance(p, failing, self.orders, q):
                self.ptr[q] = None


def robust_solve(d, objective="standard", *, settings: Settings = Settings(), rs: RobustSettings = RobustSettings(),
                 pin_inputs: bool = False, details: bool = True, explain: bool = True):
    """The :class:`~synth.design.result.Result` of the robust synthesis (see the module docstring): the best
    design meeting ``rs``'s target with its capability in ``result.robust``; when none does, the nominal
    optimum (or the nearest design) with its capability, a note saying which checks no design meets and what drives
    them, and (``explain``) the one input or tolerance that prevents it with the value that would allow it
    (:func:`prevented_by`, in ``result.robust["prevented_by"]``). The joint is the made one
    (:func:`synth.robust.sampling.production`); the model is the one that judges (``settings.judge``: at fidelity
    ``screening`` the full model throughout, the search, the samples and the nominal answer alike)."""
    t0 = time.perf_counter()
    obj = objective if isinstance(objective, Objective) else Objective.parse(objective)
    if obj.weights and "margin" in obj.weights or obj.order[0] == "margin":
        raise InputError(Problem("objective", objective, "an objective led by standard or cost with --capability/"
                                                         "--ppm (the margin is its last tie-break)"))
    # the model that judges a design (fidelity screening: the full model, as a screened design is verified): every
    # candidate's capability and the design reported are valid under it, whatever fidelity the search was asked at
    asked = settings.judge
    settings = production(asked)
    ev = evaluate(d, settings, pin_inputs=pin_inputs)
    rep = SearchReport()
    w = obj.additive_weights() or FALLBACK_WEIGHTS
    value, pos, opts, cap = search(ev, w, rs, report=rep)
    stats = {"time_s": time.perf_counter() - t0, "robust_candidates": rep.candidates,
             "robust_cores_checked": rep.cores_checked, "robust_cores_rejected": rep.cores_rejected,
             "robust_samples": rs.samples, "robust_proof": rep.proof, "robust_found": pos is not None}
    if pos is None:  # the nominal answer as asked, its production capability, and what prevents the target
        full = Objective(order=tuple(obj.order) + (("margin",) if "margin" not in obj.order else ()))
        r = enumerate_solve(d, full, settings=asked, pin_inputs=pin_inputs)
        r.notes.append(rep.why_none(rs))
        r.stats["robust_why"] = r.notes[-1]
        r.stats.update(stats)
        found = None
        if explain:
            made = r if asked == settings else None
            if rep.cores_checked == 0:  # no design passes with the made joint: its diagnosis names the input
                made = made or enumerate_solve(d, full, settings=settings, pin_inputs=pin_inputs)
            found = prevented_by(d, made or r, w, settings, rs, rep, pin_inputs=pin_inputs)
        if found:
            r.notes.append(found["text"])
            r.stats["robust_explain_time_s"] = found.pop("time_s")
        if r.feasible:
            r.robust = nominal_capability(d, r.parts, settings, rs) if details else {}
        if found:
            r.robust = {**(r.robust or {}), "prevented_by": found}
        return r
    r = build_result(ev, pos, opts, status="optimal", solver="enumerate", objective=obj, stats=stats)
    r.objective = f"{r.objective} | {rs.targets()}"
    r.notes.append(f"robust synthesis: the best design meeting {rs.targets()} on every targeted check "
                   f"({rep.candidates} candidates, {rep.cores_checked} cores checked; {rep.proof})")
    final = capability(base_of(d, r.parts, settings), rs) if details else cap
    r.robust = final.to_dict()
    return r



def nominal_capability(d, parts: dict, settings: Settings, rs: RobustSettings) -> dict:
    """The capability (:meth:`Capability.to_dict <synth.robust.capability.Capability.to_dict>`) that
    :func:`robust_solve` reports beside a nominal design ``parts`` of input ``d`` when no design meets ``rs``'s
    target: the design made (:func:`synth.robust.sampling.production` of ``settings``), every detail; ``synth bulk
    --capability``'s rows without a candidate read it too (:func:`synth.bulk.capability.screen_robust`)."""
    return made_capability(d, parts, settings, rs)[0].to_dict()


def made_capability(d, parts: dict, settings: Settings, rs: RobustSettings) -> tuple:
    """``(capability, base)``: :func:`nominal_capability`'s :class:`~synth.robust.capability.Capability` of design
    ``parts`` and the :class:`~synth.robust.sampling.Base` it rests on (the design's nominal evaluation with the
    joint made, whose assessment the platform's capability loop also reads)."""
    base = base_of(d, parts, production(settings))
    return capability(base, rs), base


def robust_for(rs: RobustSettings):
    """:func:`robust_solve` bound to the target ``rs``: the ``robust`` function
    :func:`synth.optimise.honour.solve_honouring` takes (the robust layer sits above the optimiser)."""
    return lambda d, objective, **kw: robust_solve(d, objective, rs=rs, **kw)

def _with_input(d, name: str, value: float):
    """Input ``d`` with field ``name`` set to ``value`` (validated again: what follows from it is re-derived)."""
    import dataclasses

    from synth.schema import validate
    raw = {k: v for k, v in dataclasses.asdict(d).items() if v is not None}
    raw[name] = value
    return validate(raw)


def _robust_design(d, weights, settings, rs, table=None, pin_inputs=False):
    """``(parts, min Ppk)`` of the best design of input ``d`` meeting ``rs`` (None when none does)."""
    ev = evaluate(d, settings, pin_inputs=pin_inputs)
    _, pos, opts, cap = search(ev, weights, rs, table=table)
    return (ev.parts(pos, opts), cap.min_ppk()) if pos is not None else None


def _design_words(parts: dict) -> str:
    return (f"bolt {parts['bolt_format']} {parts['bolt_property_class']} {parts['bolt_head_type']} "
            f"(washer {parts['bolt_washer']}, {parts['bolt_tightening']}), pivot class "
            f"{parts['pivot_class_diameter_mm']:g}, spring {parts['main_spring_material']} {parts['main_spring_wire']} "
            f"Dm {parts['main_spring_mean_body_diameter_mm']:g}")


def prevented_by(d, nominal, weights: dict, settings: Settings, rs: RobustSettings, rep: SearchReport, *,
                 pin_inputs: bool = False, tries: int = 4) -> dict | None:
    """The one input or tolerance that keeps every catalog design from ``rs``'s target, and the value that allows
    a design (verified: the robust search finds one there), or None when none is found in a few tries.

    * No design passes every nominal check: the nominal diagnosis's single-input relaxations (``nominal.diagnosis``:
      the designer's inputs first, then the specification's, smallest change first); each is tried at its value
      and a little beyond it in its direction (the diagnosis finds the nearest design's, the target may need more).
    * Designs pass nominally but none meets the target: the tolerance that drives the check rejecting most cores
      (its largest contributor); its band is narrowed by bisection (at most ``tries`` searches after the band's
      removal) to the widest that allows a design. A band read from an input (``input.FIELD``) names the input.

    Returns ``{"kind": "input" | "tolerance", "name", "value", "allows", "unit", "design", "min_ppk", "text",
    "time_s"}``.
    """
    import dataclasses

    from synth.schema import field_by_name
    t0 = time.perf_counter()
    diag = getattr(nominal, "diagnosis", None) or {}
    if not nominal.feasible:
        single = [x for x in diag.get("relaxations", []) if len(x.get("inputs", {})) == 1]
        single.sort(key=lambda x: (bool(x.get("specification")), x.get("relative_change", np.inf)))
        for rel in single[:2]:
            (name, ch), = rel["inputs"].items()
            a, b = float(ch["from"]), float(ch["to"])
            for k in range(tries):
                value = round(b + (b - a) * (0.05 * k * (k + 1)), 4)  # the relaxation, then 10 %, 30 %, 60 % beyond
                try:
                    got = _robust_design(_with_input(d, name, value), weights, settings, rs, pin_inputs=pin_inputs)
                except InputError:
                    break
                if got:
                    parts, ppk = got
                    unit = field_by_name(name).unit
                    text = (f"prevented by the input {name} = {a:g} {unit}: {value:g} {unit} allows a design at "
                            f"{rs.targets()} (smallest Ppk {ppk:.3g}): {_design_words(parts)}")
                    return {"kind": "input", "name": name, "value": a, "allows": value, "unit": unit,
                            "design": parts, "min_ppk": ppk, "text": text, "time_s": time.perf_counter() - t0}
        return None
    if not rep.rejected_by:
        return None
    cid = max(rep.rejected_by, key=lambda c: (rep.rejected_by[c], -rep.best_ppk.get(c, 0.0)))
    drivers = [q for q, _ in rep.contributors.get(cid, [])]
    table = tolerances()
    for q in drivers[:2]:
        if q not in table:
            continue

        def attempt(f):
            tab = dict(table)
            tab[q] = dataclasses.replace(table[q], scale=f)
            return _robust_design(d, weights, settings, rs, table=tab, pin_inputs=pin_inputs)
        best = attempt(0.0)
        if not best:
            continue
        lo, hi = 0.0, 1.0
        for _ in range(tries):
            mid = (lo + hi) / 2.0
            got = attempt(mid)
            if got:
                lo, best = mid, got
            else:
                hi = mid
        parts, ppk = best
        tol = table[q]
        where = tol.band_from if tol.band_from else f"band {tol.band:g} {tol.unit}"
        if tol.band_from.startswith("input."):
            name = tol.band_from.split(".", 1)[1]
            value = float(getattr(d, name))
            text = (f"prevented by the input {name} = {value:g} (the band of {q}, which drives {cid}): "
                    f"{value * lo:.3g} allows a design at {rs.targets()} (smallest Ppk {ppk:.3g}): "
                    f"{_design_words(parts)}")
            return {"kind": "input", "name": name, "value": value, "allows": value * lo,
                    "unit": field_by_name(name).unit, "design": parts, "min_ppk": ppk, "text": text,
                    "time_s": time.perf_counter() - t0}
        text = (f"prevented by the tolerance of {q} ({where}; it drives {cid}): {lo:.0%} of it allows a design at "
                f"{rs.targets()} (smallest Ppk {ppk:.3g}): {_design_words(parts)}")
        return {"kind": "tolerance", "name": q, "value": 1.0, "allows": lo, "unit": "x band", "design": parts,
                "min_ppk": ppk, "text": text, "time_s": time.perf_counter() - t0}
    return None


def robust_front(d, *, settings: Settings = Settings(), rs: RobustSettings = RobustSettings(), n_points: int = 8,
                 step: float = 0.02) -> list:
    """Cost against capability, exact (the epsilon-constraint method): the cheapest design meeting ``rs``'s
    target, then the cheapest whose smallest Ppk beats the previous point's by more than ``step``, and so on,
    up to ``n_points`` points. Each point: ``cost_eur``, ``ppk`` (the smallest of its targeted checks), ``ppm``
    (their largest probability of violation, upper 95 % end), ``binding`` (the check of that Ppk) and
    ``parts``. The first target is ``rs.capability`` (0 if only a ppm target is given)."""
    settings = production(settings)
    ev = evaluate(d, settings)
    target = rs.capability if rs.capability is not None else 0.0
    pts = []
    for _ in range(int(n_points)):
        rsc = RobustSettings(capability=float(target) if target > 0 else None, ppm=rs.ppm, samples=rs.samples,
                             seed=rs.seed, rare_samples=rs.rare_samples, rare_min_failures=rs.rare_min_failures)
        if rsc.capability is None and rsc.ppm is None:
            rsc = RobustSettings(capability=1e-6, samples=rs.samples, seed=rs.seed)
        value, pos, opts, cap = search(ev, {"cost": 1.0}, rsc)
        if pos is None:
            break
        worst = min((x for x in cap.checks if x.target), key=lambda x: x.ppk, default=None)
        ppk = cap.min_ppk()
        pts.append({"cost_eur": round(float(value), 6), "ppk": ppk, "ppm": cap.max_p() * 1e6,
                    "binding": worst.id if worst else "", "parts": ev.parts(pos, opts)})
        if not np.isfinite(ppk):
            break
        target = ppk + step
    return pts
