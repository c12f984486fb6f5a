"""Capability of one design: per registry check, how much of a production run violates it, and why.

From the samples of :mod:`synth.robust.sampling` (the evaluator's margins,
``m >= 0`` passes, scaled by the registry so that the limit is ``m = 0``):

* **P(violation)** = the share of samples with ``m < 0``, with its 95 %
  Clopper-Pearson interval (binomial; conservative for scrambled Sobol
  points, whose error is smaller than independent sampling's). Fewer than
  ``rare_min_failures`` violations: the FORM design point and importance
  sampling of :mod:`synth.robust.rare` give the probability with its own
  interval;
* **Ppk** by ISO 22514-2 (:mod:`synth.robust.stats`, written once): the
  percentile method, ``X50 / (X50 - X0.135 %)`` of the margin (the margin is a
  linear rescaling of the checked value, so this is the index of the value:
  ``(X50 - LSL)/(X50 - X0.135 %)`` or its upper twin), for outputs of any
  distribution, and beside it the moment form ``mean/(3 sd)`` (the index of a
  normal output). The target names its method (:class:`RobustSettings`
  ``method``, default the percentile method). A window (two checks of one
  value with opposite senses, e.g. the damping's upper and lower tolerance)
  has the smaller of its two sides' indices. A simulation has no rational
  subgroups: its one spread is the overall one, so Cpk = Ppk here;
* **bounded outputs**: a check whose scatter comes from bounded (uniform)
  quantities only (every contributor of at least 0.5 % of its variance) is
  judged by its probability of violation, the primary figure: its worst case
  over the bands within the limit is 0 ppm, otherwise P(violation) (the
  Monte Carlo's upper 95 % end, or importance sampling) against the target's
  ppm equivalent ``Phi(-3 Ppk)`` (Ppk 1.33: 33 ppm); its ``ppk`` is the index
  that ppm is equivalent to, its percentile and moment indices are reported beside;
* **worst case** (every quantity at the end of its band that hurts the check,
  the ends chosen from the secant sensitivities over the band; evaluated at
  that vertex) and **RSS** (the root sum of squares of the band contributions,
  linearised) beside it;
* **contributors**: the standardised regression coefficients of the margin on
  the standard-normal inputs, squared and normalised (for a linear check they
  are the first-order Sobol indices), with the regression's R^2.

The **target** (:class:`~synth.robust.settings.RobustSettings`) applies to the
checks the assessment targets (:attr:`synth.design.assessment.Assessment.targeted`:
those the registry counts in the margin objective, and the safety factors of
step 10 that the preload is sized to, ``capability=True``, judged at the made
preload's scatter): every other check is reported, not required.

Closed-form check (tests): a check linear in normal inputs has
``Ppk = m0 / (3 sqrt(sum (s_i sigma_i)^2))``.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from synth import schema
from synth.design.assessment import assess, passes
from synth.design.constraints import FEAS_TOL, REGISTRY
from synth.robust import stats
from synth.design.settings import Settings
from synth.robust.assumptions import flips
from synth.robust.sampling import Base, Samples, base_of, evaluate_deviations, evaluate_u, sobol_u
from synth.robust.settings import RobustSettings
from synth.design.result import plain

#: sample values kept per histogram (the report's 40 bins; the JSON stays small)
HISTOGRAM_SAMPLES = 1000
#: above this Ppk (a normal margin 7.5 standard deviations from its limit, P ~ 1e-13) an unresolved probability
#: keeps the Monte Carlo's Clopper-Pearson bound unless a ppm target needs a smaller one
RARE_PPK_MAX = 2.5
#: a contributor below this share of a check's variance does not make its output unbounded
BOUNDED_SHARE = 0.005

__all__ = ["CheckCapability", "Capability", "capability", "capabilities", "clopper_pearson", "ppk", "targeted", "windows",
           "equivalent_ppk", "add_capability"]

clopper_pearson = stats.clopper_pearson


def ppk(m: np.ndarray, method: str = "moment") -> float:
    """The index of margins ``m`` by ``method`` (:data:`synth.robust.stats.METHODS`).

    >>> round(ppk(np.array([0.3, 0.5, 0.7])), 4)     # 0.5 / (3 * 0.1633)
    1.0206
    """
    return float(stats.ppk_percentile(m) if method == "percentile" else stats.ppk_moment(m))


def equivalent_ppk(p: float) -> float:
    """The index of a normal output violating its limit with probability ``p``: ``-Phi^-1(p)/3`` (0: +inf).

    >>> round(equivalent_ppk(3.3e-5), 2), equivalent_ppk(0.0)
    (1.33, inf)
    """
    from scipy.special import ndtri
    return float("inf") if p <= 0 else float(-ndtri(min(float(p), 1.0)) / 3.0)


def targeted(cid: str, base: Base) -> bool:
    """Whether check ``cid`` of the design counts in the capability target: its assessment's
    (:attr:`synth.design.assessment.Assessment.targeted`: the margin objective's checks that depend on the design)."""
    return cid in _targeted(base, (cid,))


def _targeted(base: Base, checks: tuple) -> set:
    """The checks of ``checks`` that :func:`targeted` says count in the target, from one assessment (each column's
    rule reads its own group)."""
    if not checks:
        return set()
    a = assess(base.groups, rows=slice(0, 1), ids=tuple(checks))
    return {cid for cid, t in zip(a.columns.ids, a.targeted[0]) if t}


def windows(checks) -> dict:
    """``{value key: (check, check)}``: pairs of checks of one group on one value with opposite senses (a
    window, e.g. ``damping_nm``: ``damping_upper`` and ``damping_lower``), from the registry."""
    by = {}
    for cid in checks:
        c = REGISTRY[cid]
        by.setdefault((c.group, c.value), {})[c.sense] = cid
    return {value: (d["<="], d[">="]) for (_, value), d in by.items() if len(d) == 2}


@dataclass
class CheckCapability:
    """The capability of one check (see the module docstring)."""

    id: str
    nominal: float          # the registry's nominal margin (its worst-case stacks where the thesis has them)
    centre: float           # margin with every quantity at the centre of its band
    mean: float
    sd: float
    ppk: float              # the target's figure: the method's index, or a bounded output's ppm-equivalent index
    p: float
    p_lo: float
    p_hi: float
    failures: int
    n: int
    method: str             # "monte carlo" | "importance sampling" | "deterministic" | "bounded"
    worst_case: float
    rss: float
    contributors: list = field(default_factory=list)   # [(quantity, share)], largest first
    r2: float = float("nan")
    target: bool = False
    note: str = ""
    ppk_percentile: float = float("nan")   # ISO 22514-2 percentile method
    ppk_moment: float = float("nan")       # mean / (3 sd)
    bounded: bool = False                  # scatter from bounded quantities only: judged by its ppm

    @property
    def label(self) -> str:
        return REGISTRY[self.id].label

    def meets(self, rs: RobustSettings) -> bool:
        ok = True
        if rs.capability is not None:
            ok &= self.ppk >= rs.capability
        if rs.ppm is not None:
            ok &= self.p_hi <= rs.ppm * 1e-6
        return bool(ok)

    def as_dict(self) -> dict:
        c = REGISTRY[self.id]
        return plain({"id": self.id, "label": c.label, "group": c.group, "nominal_margin": self.nominal,
                      "centre_margin": self.centre, "mean_margin": self.mean, "sd_margin": self.sd, "ppk": self.ppk,
                      "ppk_percentile": self.ppk_percentile, "ppk_moment": self.ppk_moment, "bounded": self.bounded,
                      "p_violation": self.p, "p_lo": self.p_lo, "p_hi": self.p_hi, "ppm": self.p * 1e6,
                      "failures": self.failures, "samples": self.n, "method": self.method,
                      "worst_case_margin": self.worst_case, "rss_margin": self.rss,
                      "contributors": [[q, s] for q, s in self.contributors], "r2": self.r2, "target": self.target,
                      "note": self.note})


@dataclass
class Capability:
    """The capability of one design: its checks, the settings, the tolerance model and the histograms."""

    checks: list
    settings: RobustSettings
    scatter_rows: list
    dropped: list
    histograms: dict = field(default_factory=dict)   # value key -> samples (a thinned copy for plots)
    windows: dict = field(default_factory=dict)      # value key -> (upper check, lower check)
    limits: dict = field(default_factory=dict)       # value key -> (lower, upper) of the histogram's window
    cone: dict = field(default_factory=dict)         # the supplier's centred cone spring (steps 6 and 8), if any

    def check(self, cid: str) -> CheckCapability:
        for c in self.checks:
            if c.id == cid:
                return c
        raise KeyError(cid)

    def failing(self) -> list:
        """The targeted checks that miss the target."""
        return [c for c in self.checks if c.target and not c.meets(self.settings)]

    @property
    def meets(self) -> bool:
        return not self.failing()

    def min_ppk(self) -> float:
        vals = [c.ppk for c in self.checks if c.target]
        return float(min(vals)) if vals else float("inf")

    def max_p(self) -> float:
        vals = [c.p_hi for c in self.checks if c.target]
        return float(max(vals)) if vals else 0.0

    def to_dict(self) -> dict:
        return plain({"kind": "synth.capability", "targets": self.settings.targets(),
                      "settings": {"capability": self.settings.capability, "ppm": self.settings.ppm,
                                   "method": self.settings.method,
                                   "samples": self.settings.samples, "seed": self.settings.seed,
                                   "rare_samples": self.settings.rare_samples},
                      "meets": self.meets, "min_ppk": self.min_ppk(), "max_p_violation": self.max_p(),
                      "failing": [c.id for c in self.failing()],
                      "windows": {k: list(v) for k, v in self.windows.items()},
                      "tolerances": self.scatter_rows, "not_sampled": [list(x) for x in self.dropped],
                      "checks": [{**c.as_dict(), "meets": c.meets(self.settings)} for c in self.checks],
                      "histograms": self.histograms, "limits": {k: list(v) for k, v in self.limits.items()},
                      "cone_spring": self.cone})


def _secant_rows(sc) -> np.ndarray:
    """``(2d + 1, d)`` deviations: every quantity at the centre of its band, then each at its lower and upper end."""
    d = len(sc)
    rows = np.repeat(sc.centre()[None, :], 2 * d + 1, axis=0)
    for j in range(d):
        rows[1 + 2 * j, j], rows[2 + 2 * j, j] = sc.lo[j], sc.hi[j]
    return rows


def _linear(base: Base, checks: tuple, s=None) -> tuple:
    """``(centre, worst case, rss)`` margins per check: secant sensitivities over each band (2d + 1 rows, or their
    margins ``s`` evaluated by the caller: :func:`_secant_rows`), then the adverse vertex of each check (one row per
    check): two evaluator calls (one with ``s``)."""
    sc = base.scatter
    if s is None:
        rows = _secant_rows(sc)
        s = evaluate_deviations(base, {q: rows[:, j] for j, q in enumerate(sc.names)} or {"_n": np.zeros(1)},
                                checks)
    centre, rss, vert = _secants(base, checks, s)
    v = evaluate_deviations(base, {q: vert[:, j] for j, q in enumerate(sc.names)}, checks) if vert is not None \
        else None
    return _worst(checks, centre, rss, v)


def _secants(base: Base, checks: tuple, s) -> tuple:
    """``(centre, rss, vertices)`` of the secant rows' margins ``s``: each check's adverse vertex (one row per check,
    None when there is none to evaluate)."""
    sc = base.scatter
    d = len(sc)
    centre = {cid: float(s.margins[cid][0]) for cid in checks}
    vert = np.repeat(sc.centre()[None, :], len(checks), axis=0)
    rss = {}
    for i, cid in enumerate(checks):
        m = s.margins[cid]
        lo, hi = m[1::2], m[2::2]
        with np.errstate(invalid="ignore"):
            sens = np.where(np.isfinite(hi) & np.isfinite(lo), (hi - lo) / 2.0, 0.0)
        rss[cid] = centre[cid] - float(np.sqrt(np.sum(sens ** 2)))
        vert[i] = np.where(hi < lo, sc.hi, sc.lo) if d else vert[i]
    return centre, rss, vert if d and len(checks) else None


def _worst(checks: tuple, centre: dict, rss: dict, v) -> tuple:
    """:func:`_linear`'s answer from the vertices' margins ``v`` (row i: check i's; None: the centre's)."""
    worst = {cid: float(v.margins[cid][i]) for i, cid in enumerate(checks)} if v is not None else dict(centre)
    return centre, worst, rss


def _contributors(u: np.ndarray, margins: dict, names: tuple) -> dict:
    """``{check: (contributors, R^2)}``: the squared standardised regression coefficients of each check's margin
    on the standard-normal inputs ``u``, normalised, largest first (those >= 0.5 %), and the regression's R^2;
    least squares by the normal equations, every check of finite margins in one matrix product (a check with
    samples where it does not apply: on its own rows)."""
    out = {}
    if not u.shape[1] or not margins:
        return out
    full = [c for c, m in margins.items() if np.isfinite(m).all() and np.std(m) > 0]
    parts = ([(full, np.ones(len(u), dtype=bool))] if full else []) + \
        [([c], np.isfinite(m)) for c, m in margins.items() if c not in full and np.isfinite(m).sum() > u.shape[1] + 2
         and np.std(m[np.isfinite(m)]) > 0]
    for ids, ok in parts:
        x = u[ok] - u[ok].mean(axis=0)
        y = np.column_stack([margins[c][ok] for c in ids])
        y = y - y.mean(axis=0)
        cov = x.T @ x
        b = np.linalg.solve(cov, x.T @ y)                      # (d, C)
        explained = np.einsum("ij,ik,kj->j", b, cov, b)         # b' X'X b per column
        total = np.einsum("ij,ij->j", y, y)
        sd_u = x.std(axis=0)
        src2 = (b * sd_u[:, None]) ** 2 / (total / len(y))[None, :]
        for j, c in enumerate(ids):
            tot = float(src2[:, j].sum())
            order = np.argsort(-src2[:, j])
            contrib = [(names[i], float(src2[i, j] / tot)) for i in order if tot > 0 and src2[i, j] / tot >= 0.005]
            out[c] = (contrib, float(explained[j] / total[j]) if total[j] > 0 else float("nan"))
    return out


def capability(base: Base, rs: RobustSettings = RobustSettings(), *, rare: bool = True, details: bool = True,
               u: np.ndarray | None = None) -> Capability:
    """The :class:`Capability` of the design of ``base`` under settings ``rs``.

    ``details``: the histograms (off in the synthesis; the worst case, which decides a bounded output, and the
    contributors are always computed); ``rare``: importance sampling of the targeted checks the Monte Carlo does
    not resolve; ``u``: given standard-normal points (default: ``rs.samples`` Sobol points of ``rs.seed``).
    """
    sc = base.scatter
    # one Sobol sample over every quantity of the catalog, each design reading its own quantities' columns: the
    # same quantity gets the same numbers in every design (common random numbers: candidates compare fairly)
    u = sobol_u(rs.samples, sc.width, rs.seed)[:, sc.columns] if u is None else u
    s, secant = _samples_and_secants(base, u)
    return _assemble(base, rs, u, s, _linear(base, base.checks, secant), rare=rare, details=details)


def capabilities(bases: list, stacked: Base, rs: RobustSettings = RobustSettings(), *, rare: bool = True,
                 details: bool = True) -> list:
    """``[capability(b, rs, rare=rare, details=details) for b in bases]`` (the same, to the bit), the K designs of
    one application (:func:`synth.robust.sampling.bases_of_attributes`, ``stacked`` their stacked Base) evaluated
    together: the samples and secant rows of the designs whose tolerance models sample the same quantities in one
    evaluator call, their worst-case vertices in another (the robust search's candidates)."""
    from synth.robust.sampling import take
    out: list = [None] * len(bases)
    by: dict = {}
    for i, b in enumerate(bases):
        by.setdefault(b.scatter.names, []).append(i)
    for names, idx in by.items():
        if not names or len(idx) == 1:  # nothing to share
            for i in idx:
                out[i] = capability(bases[i], rs, rare=rare, details=details)
            continue
        sub = take(stacked, idx)
        checks = tuple(dict.fromkeys(c for i in idx for c in bases[i].checks))
        sub.checks = checks
        us = [sobol_u(rs.samples, bases[i].scatter.width, rs.seed)[:, bases[i].scatter.columns] for i in idx]
        xs = [np.vstack([bases[i].scatter.deviations(u), _secant_rows(bases[i].scatter)]) for i, u in zip(idx, us)]
        m = [len(x) for x in xs]
        x = np.vstack(xs)
        rows = np.repeat(np.arange(len(idx)), m)
        both = evaluate_deviations(sub, {q: x[:, j] for j, q in enumerate(names)}, checks, rows=rows)
        starts = np.concatenate([[0], np.cumsum(m)])
        secs, samples = [], []
        for k, (i, u) in enumerate(zip(idx, us)):
            a, n, b_ = starts[k], len(u), starts[k + 1]
            own = bases[i].checks
            samples.append(Samples({c: both.margins[c][a:a + n] for c in own},
                                   {key: v[a:a + n] for key, v in both.values.items()}))
            secs.append(_secants(bases[i], own, Samples({c: both.margins[c][a + n:b_] for c in own}, {})))
        verts = [v for _, _, v in secs]
        have = [k for k, v in enumerate(verts) if v is not None]
        vm: dict = {}
        if have:
            vx = np.vstack([verts[k] for k in have])
            vr = np.repeat(np.asarray(have), [len(verts[k]) for k in have])
            vv = evaluate_deviations(sub, {q: vx[:, j] for j, q in enumerate(names)}, checks, rows=vr)
            at = np.concatenate([[0], np.cumsum([len(verts[k]) for k in have])])
            for j, k in enumerate(have):
                vm[k] = Samples({c: vv.margins[c][at[j]:at[j + 1]] for c in bases[idx[k]].checks}, {})
        for k, i in enumerate(idx):
            centre, rss, _ = secs[k]
            lin = _worst(bases[i].checks, centre, rss, vm.get(k))
            out[i] = _assemble(bases[i], rs, us[k], samples[k], lin, rare=rare, details=details)
    return out


def _assemble(base: Base, rs: RobustSettings, u: np.ndarray, s, lin: tuple, *, rare: bool, details: bool) -> Capability:
    """The :class:`Capability` of ``base`` from its samples' margins ``s`` (of points ``u``) and :func:`_linear`'s
    ``lin``."""
    sc = base.scatter
    d = len(sc)
    n = len(u)
    checks = base.checks
    aimed = _targeted(base, checks)
    contributions = _contributors(u, s.margins, sc.names)
    uniform = {q for q, k in zip(sc.names, sc.kind) if k == 1}
    out = []
    stack = np.vstack([s.margins[cid] for cid in checks]) if checks else np.zeros((0, n))
    counts = (~passes(stack)).sum(axis=1).astype(np.int64) if len(checks) else np.zeros(0, np.int64)
    los, his = clopper_pearson(counts, n)
    pct, mom = stats.ppk_percentile(stack), stats.ppk_moment(stack)
    for j, cid in enumerate(checks):
        m = stack[j]
        k, lo, hi = int(counts[j]), float(los[j]), float(his[j])
        fin = m[np.isfinite(m)]
        mean = float(fin.mean()) if len(fin) else float("inf")
        sd = float(fin.std()) if len(fin) else 0.0
        if sd <= stats.SD_FLOOR * max(1.0, abs(mean)):
            sd = 0.0
        contrib, r2 = contributions.get(cid, ([], float("nan"))) if sd > 0 else ([], float("nan"))
        bounded = sd > 0 and bool(contrib) and all(q in uniform for q, share in contrib if share >= BOUNDED_SHARE)
        worst = lin[1][cid]
        p = k / n
        how = "monte carlo" if sd > 0 else "deterministic"
        if bounded and worst >= -FEAS_TOL:  # every value within the bands passes: no violation, 0 ppm
            p, lo, hi, how = 0.0, 0.0, 0.0, "bounded"
        index = float(pct[j] if rs.method == "percentile" else mom[j])
        out.append(CheckCapability(
            cid, base.nominal_margin(cid), lin[0][cid], mean, sd, equivalent_ppk(hi) if bounded else index, p, lo,
            hi, k, n, how, worst, lin[2][cid], contrib, r2, cid in aimed, ppk_percentile=float(pct[j]),
            ppk_moment=float(mom[j]), bounded=bounded))
    w = windows(checks)
    by_id = {c.id: c for c in out}
    for up, low in w.values():  # a window's index: the smaller side's, on both of its checks
        both = min(by_id[up].ppk, by_id[low].ppk)
        by_id[up].note = by_id[low].note = f"window: Ppk {both:.3g} (the smaller side)"
    if rare and d:
        _rare(base, out, rs, n)
    cap = Capability(out, rs, sc.rows, sc.dropped, windows=w)
    if base.cone is not None and np.isfinite(base.cone["thickness_mm"][0]):
        cap.cone = {"nominal_force_n": float(base.cone["force_n"][0]), "thickness_mm": float(base.cone["thickness_mm"][0]),
                    "band_room_n": float(base.cone["room_n"][0]),
                    "note": "the supplier's cone spring (thesis steps 6 and 8): its nominal height set to centre its "
                            "delivered forces in the damping window's band; the samples are made of it"}
    if details:
        cap.histograms, cap.limits = _histograms(base, s)
    return cap


def _samples_and_secants(base: Base, u: np.ndarray) -> tuple:
    """``(samples, secants)``: :func:`evaluate_u` of ``u`` and the margins of :func:`_secant_rows` (what
    :func:`_linear` reads), every check of the design, in one evaluator call (the rows are independent: each is
    what its own call gives)."""
    sc = base.scatter
    if not len(sc):
        return evaluate_u(base, u), None
    x = np.vstack([sc.deviations(u), _secant_rows(sc)])
    both = evaluate_deviations(base, {q: x[:, j] for j, q in enumerate(sc.names)})
    n = len(u)
    return (Samples({k: v[:n] for k, v in both.margins.items()}, {k: v[:n] for k, v in both.values.items()}),
            Samples({k: v[n:] for k, v in both.margins.items()}, {}))


def _rare(base: Base, out: list, rs: RobustSettings, n: int) -> None:
    """Importance sampling for the targeted, scattering checks with fewer than ``rs.rare_min_failures``
    violations among the ``n`` Monte Carlo samples (their interval is then the importance sampling's)."""
    from synth.robust.rare import form_is

    def needs(c):  # a probability the Monte Carlo does not resolve, and that matters: in the range a target or a
        # report can use (Ppk <= RARE_PPK_MAX, P above ~1e-13), or below a ppm target the MC bound cannot certify
        if not (c.target and c.sd > 0 and c.failures < rs.rare_min_failures) or c.method == "bounded":
            return False
        return c.ppk <= RARE_PPK_MAX or (rs.ppm is not None and c.p_hi > rs.ppm * 1e-6)
    todo = [c for c in out if needs(c)]
    if not todo:
        return
    ids = tuple(c.id for c in todo)

    def g(pts):
        s = evaluate_u(base, pts, ids)
        return np.column_stack([np.where(np.isinf(s.margins[cid]) & (s.margins[cid] > 0), 1e3, s.margins[cid])
                                for cid in ids])
    res = form_is(g, len(base.scatter), n_is=rs.rare_samples, seed=rs.seed)
    for c, r in zip(todo, res):
        c.method = "FORM bound" if r["hits"] == 0 and r["se"] != r["se"] else "importance sampling"
        c.p, c.p_lo, c.p_hi = r["p"], r["p_lo"], r["p_hi"]
        if c.bounded:  # a bounded output's figure is its probability
            c.ppk = equivalent_ppk(c.p_hi)
        extra = f"FORM beta {r['beta']:.3g} (P_FORM {r['p_form']:.3g}); {r['hits']} of {rs.rare_samples} " \
                f"importance samples violate"
        c.note = "; ".join(x for x in (c.note, extra, r["note"]) if x)


def _histograms(base: Base, s) -> tuple:
    """Thinned sample values for the report's histograms, and each value's window (lower, upper) from the
    nominal evaluation's limits (NaN where one side has no limit)."""
    hist = {k: np.round(v[np.isfinite(v)][:HISTOGRAM_SAMPLES], 6).tolist() for k, v in s.values.items()
            if np.isfinite(v).any()}
    g = base.groups
    core, ax = g["core"].values, g["axial"].values
    limits = {"damping_nm": (float(core["damping_lower_nm"][0]), float(core["damping_upper_nm"][0])),
              "hubload_nominal_n": (float("nan"), float(core["bearing_max_hubload_n"][0])),
              "damping_eol_nm": (float(ax["damping_eol_limit_nm"][0]), float("nan"))}
    tol = float(base.apps.f["spring_torque_tolerance_pct"][0]) if "spring_torque_tolerance_pct" in base.apps.f else 0.0
    t0 = float(core["spring_torque_nominal_nm"][0])
    if np.isfinite(tol) and tol > 0:
        limits["spring_torque_nominal_nm"] = (t0 * (1 - tol / 100), t0 * (1 + tol / 100))
    return hist, {k: v for k, v in limits.items() if k in hist}


def add_capability(result, rs) -> None:
    """Set ``result.robust`` (the capability of its design under ``rs``, unless it carries one) and its
    assumptions' flips, through :mod:`synth.robust`."""
    settings = Settings.from_saved(result.settings, result.rules)  # the result's own configuration
    d = schema.validate({k: v for k, v in (result.inputs or {}).items() if v is not None})
    robust = dict(result.robust or {})
    if not robust.get("checks"):
        robust.update(capability(base_of(d, result.parts, settings), rs).to_dict())
    if "assumptions" not in robust:
        robust["assumptions"] = flips(d, result.parts, settings)
    result.robust = robust
