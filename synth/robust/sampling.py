"""Production samples of one design through the one evaluator.

A sample is the design as made and the application as met: the tolerance
model's deviations (:mod:`synth.robust.tolerances`) applied to the
evaluator's inputs, N samples evaluated in **one** call of
:func:`synth.design.verify.evaluate_design` (N aligned rows: one application
row and one design row per sample). No physics and no margin is computed
here: every value and every margin is the evaluator's, the registry's.

What the design fixes stays fixed (its drawing): the main spring's active
coils (its stiffness then follows from the made wire and coil diameter,
eq. (64)-(65)) and its torque at the nominal position (the made spring's
torque scatters within its tolerance, eq. (66); the tensioner's damping,
calculated torque and hubload follow from it by eq. (12)-(13)), the cone
spring's thickness and cone height (its force then follows from the realised
gap stack), the bolt's tightening method (the made joint's preload lies in
its window). The application's specification stays the application's: its
calculated torque target, and the hubload the safety factors of step 10 are
defined on (eq. (94)-(99)). The worst-case tolerances of the nominal model
that a sampled quantity replaces are set to 0 for the sample
(:data:`synth.robust.tolerances.DECLARED`: each quantity's declaration says
what it perturbs, :func:`perturb` reads them).

The made joint is always the VDI 2230 path's (:func:`production`): a
production run tightens its bolts with a method and its scatter, which the
thesis path (tightened to exactly the required force) has not.

>>> from synth.scenes.demo import default_input
>>> from synth.optimise import solve
>>> d = default_input()
>>> b = base_of(d, solve(d, "standard,cost,margin").parts)
>>> s = evaluate_u(b, sobol_u(256, len(b.scatter), seed=1))
>>> s.margins["damping_upper"].shape, "spring_torque" in b.scatter.names
((256,), True)
"""

from __future__ import annotations

import functools
from dataclasses import dataclass, field

import numpy as np

from synth.design import evaluate
from synth.design.applications import Applications
from synth.design.constraints import REGISTRY
from synth.design.space import space
from synth.design.verify import evaluate_design, parts_of_attributes
from synth.kernels import engines
from synth.model import torsion_spring
from synth.robust.tolerances import DECLARED, Quantity, Scatter, resolve

__all__ = ["AXIAL_ENGINE", "Base", "Samples", "production", "base_of", "base_of_attributes", "bases_of_attributes", "take", "context", "perturb", "evaluate_deviations", "evaluate_u", "sobol_u", "HISTOGRAM_VALUES",
           "design_checks"]

#: the axial group's engine of the samples (:func:`synth.kernels.engines.axial`; ``Settings(engine="numpy")``
#: overrides it): N rows a call, so the compiled wear (:mod:`synth.kernels.axial`: within its ``RTOL`` of the
#: reference; a made cone spring is the reference's own); every capability figure synth reports is the same with
#: ``"numpy"`` (``benchmarks/bench_bulk_capability.py --engines``)
AXIAL_ENGINE = "numba"
#: the values a sample keeps besides the margins (the report's histograms): value key -> group
HISTOGRAM_VALUES = {"damping_nm": "core", "hubload_nominal_n": "core", "spring_torque_nominal_nm": "core",
                    "damping_eol_nm": "axial", "cone_spring_fax_nominal_n": "axial",
                    "main_spring_sigma_inst_mpa": "spring", "main_spring_safety_factor": "spring",
                    "main_spring_coil_gap_worst_mm": "spring", "sliding_safety_factor": "bolt"}


@dataclass
class Base:
    """One design of one application at nominal: what the samples perturb and what they keep."""

    inputs: object
    parts: dict
    settings: evaluate.Settings
    apps: Applications           # the application (one row)
    attrs: dict                  # the design's one-row attributes per table
    groups: dict                 # the nominal evaluation (the registry's verdicts)
    scatter: Scatter
    checks: tuple                # registry ids evaluated at nominal (not "not applicable", not "not verified")
    notes: list = field(default_factory=list)
    #: per design row, the supplier's centred cone spring (:func:`centred_cone`): its thickness (NaN: none) and
    #: nominal force; None: the sized spring's own thickness
    cone: dict | None = None

    def nominal_margin(self, cid: str) -> float:
        return float(self.groups[REGISTRY[cid].group].margins[cid][0])


@dataclass
class Samples:
    """The evaluator's margins (``(N,)`` per check; +inf where a check does not apply in a sample) and the
    :data:`HISTOGRAM_VALUES` of N samples."""

    margins: dict
    values: dict

    def __len__(self) -> int:
        return len(next(iter(self.margins.values()))) if self.margins else 0


def design_checks(groups: dict) -> tuple:
    """The registry ids a design's nominal evaluation evaluated (CAD checks aside)."""
    out = []
    for cid, c in REGISTRY.items():
        g = groups.get(c.group)
        if g is not None and int(g.state[cid][0]) == evaluate.EVALUATED:
            out.append(cid)
    return tuple(out)


def production(settings: evaluate.Settings) -> evaluate.Settings:
    """The settings of the production view: ``settings`` with the made joint of VDI 2230 (``bolt_method
    "vdi2230"``: the design's tightening method, its preload window; the thesis path tightens to exactly the
    required force, which no tightening method does).

    >>> production(evaluate.Settings()).bolt_method
    'vdi2230'
    """
    import dataclasses
    return settings if settings.bolt_method == "vdi2230" else dataclasses.replace(settings, bolt_method="vdi2230")


def base_of(d, parts: dict, settings: evaluate.Settings = evaluate.Settings(), table: dict | None = None) -> Base:
    """The :class:`Base` of design ``parts`` for input ``d``: its nominal evaluation and its tolerance model."""
    return base_of_attributes(d, space().design_attributes(parts), settings, table, parts=parts)


def base_of_attributes(d, attrs: dict, settings: evaluate.Settings = evaluate.Settings(), table: dict | None = None, *,
                       apps: Applications | None = None, parts: dict | None = None) -> Base:
    """:func:`base_of` from the design's one-row attributes per table (the optimiser's rows); the settings of the
    production view (:func:`production`)."""
    settings = production(settings)
    apps = Applications.of([d]) if apps is None else apps
    with np.errstate(all="ignore"):
        groups = evaluate_design(apps, attrs, settings, detail=False)
    sc = resolve(context(apps, attrs, groups, settings, 0), table)
    if parts is None:
        parts = parts_of_attributes(attrs, groups)
    return Base(d, dict(parts), settings, apps, attrs, groups, sc, design_checks(groups),
                cone=centred_cone(apps, attrs, groups, settings))


def bases_of_attributes(d, attrs_list: list, settings: evaluate.Settings = evaluate.Settings(), table: dict | None = None,
                        *, apps: Applications | None = None) -> tuple:
    """``([base_of_attributes(d, a, settings, table, apps=apps) for a in attrs_list], stacked)``: the K designs'
    nominal evaluations in one evaluator call (rows are independent: each is what its own call gives), and
    ``stacked``, the :class:`Base` of the K designs (K-row apps, attrs, groups, cone; no scatter) that
    :func:`perturb` takes with ``rows`` (:func:`take`)."""
    settings = production(settings)
    apps = Applications.of([d]) if apps is None else apps
    k = len(attrs_list)
    attrs = {t: {c: np.concatenate([np.asarray(a[t][c]) for a in attrs_list]) for c in attrs_list[0][t]}
             for t in attrs_list[0]}
    with np.errstate(all="ignore"):
        groups = evaluate_design(apps, attrs, settings, detail=False, of=np.zeros(k, dtype=np.int64))
        appsk = apps.subset(np.zeros(k, dtype=np.int64))
        cone = centred_cone(appsk, attrs, groups, settings)
    stacked = Base(d, {}, settings, appsk, attrs, groups, None, (), cone=cone)
    out = []
    for i, a in enumerate(attrs_list):
        gi = {name: g.take([i]) for name, g in groups.items()}
        sc = resolve(context(apps, a, gi, settings, 0), table)
        out.append(Base(d, dict(parts_of_attributes(a, gi)), settings, apps, a, gi, sc, design_checks(gi),
                        cone={key: v[[i]] for key, v in cone.items()}))
    return out, stacked


def take(stacked: Base, idx) -> Base:
    """The designs ``idx`` of a stacked :class:`Base` (:func:`bases_of_attributes`) as a stacked Base."""
    idx = np.asarray(idx, dtype=np.int64)
    return Base(stacked.inputs, {}, stacked.settings, stacked.apps.subset(idx),
                {t: {c: v[idx] for c, v in cols.items()} for t, cols in stacked.attrs.items()},
                {name: g.take(idx) for name, g in stacked.groups.items()}, None, stacked.checks,
                cone=None if stacked.cone is None else {key: v[idx] for key, v in stacked.cone.items()})


def centred_cone(apps: Applications, attrs: dict, groups: dict, settings: evaluate.Settings) -> dict:
    """The made cone spring of each design row: the supplier's, its nominal height (force) centred in the damping
    window's band (:func:`synth.model.disc_spring.centred_cone_spring`, thesis steps 6 and 8), at the design's own
    variant (outer and inner diameter, ``h0/t``, ``s/h0``); ``{"thickness_mm", "force_n", "room_n"}`` arrays, NaN
    where the design has no sized cone spring."""
    from synth.model import disc_spring, stackup
    ax, core = groups["axial"].values, groups["core"].values
    sized = np.asarray(ax["cone_spring_sized"], dtype=bool)
    k = len(sized)
    out = {key: np.full(k, np.nan) for key in ("thickness_mm", "force_n", "room_n")}
    i = np.flatnonzero(sized)
    if not len(i):
        return out
    a = np.asarray(groups["axial"].values["app"])[i]
    with np.errstate(all="ignore"):
        cs = disc_spring.centred_cone_spring(
            np.asarray(core["axial_damping_nm"])[i], apps.damping_target_or_zero_nm[a],
            np.nan_to_num(apps.f["damping_tolerance_nm"][a], nan=0.0), np.asarray(core["radial_damping_nm"])[i],
            apps.mu_plastic[a], np.asarray(core["damper_pad_mean_radius_mm"])[i],
            np.asarray(attrs["axial"]["endcap_spacer_mean_radius_mm"])[i],
            np.asarray(ax["cone_spring_external_diameter_mm"])[i], np.asarray(ax["cone_spring_internal_diameter_mm"])[i],
            stackup.gap_tolerance_mm("worst_case"), aspect_ratio=np.asarray(attrs["axial"]["cone_spring_aspect_ratio"])[i],
            deflection_ratio=np.asarray(attrs["axial"]["cone_spring_deflection_ratio"])[i], fidelity=settings.model)
    out["thickness_mm"][i] = cs["cone_spring_thickness_mm"]
    out["force_n"][i] = cs["cone_spring_fax_nominal_n"]
    out["room_n"][i] = cs["cone_spring_force_band_room_n"]
    return out


def context(apps: Applications, attrs: dict, groups: dict, settings: evaluate.Settings, k: int) -> dict:
    """What :func:`synth.robust.tolerances.resolve` reads of design ``k`` of N-row ``apps``/``attrs``/``groups``:
    its application's fields, its spring option, the strength range of its wire, its pivot, its cone spring."""
    sp = {key: np.asarray(v)[k] for key, v in attrs["spring"].items()}
    mat = str(sp["main_spring_material"])
    dia = torsion_spring.rm_lookup_diameter_mm(sp["b_mm"], sp["h_mm"], bool(sp["round_wire"]))
    ax = groups["axial"].values
    cone = bool(np.asarray(ax["cone_spring_sized"])[k])

    def fld(name):
        return float(apps.f[name][k]) if name in apps.f else float("nan")

    return {"field": fld, "spring": sp, "rm_min": float(torsion_spring.material_strength_mpa(mat, dia, "min")),
            "rm_max": float(torsion_spring.material_strength_mpa(mat, dia, "max")),
            "pivot_diameter_mm": float(np.asarray(attrs["core"]["pivot_diameter_mm"])[k]), "cone": cone,
            "cone_force_tolerance": (float(np.asarray(ax["cone_spring_force_tolerance_plus"])[k]),
                                     float(np.asarray(ax["cone_spring_force_tolerance_minus"])[k])) if cone
            else (np.nan, np.nan),
            "bolt": bool(apps.met("fixation")[k]),
            "tightening_alpha_a": float(np.asarray(attrs["bolt"]["tightening_alpha_a"])[k])
            if "tightening_alpha_a" in attrs["bolt"] else float("nan")}


@functools.lru_cache(maxsize=8)
def sobol_u(n: int, d: int, seed: int) -> np.ndarray:
    """``(n, d)`` standard-normal points from a scrambled Sobol sequence (``scipy.stats.qmc.Sobol``, seeded:
    the same seed gives the same points), mapped through the normal quantile; ``d = 0`` gives ``(n, 0)``.
    Kept per ``(n, d, seed)`` (read-only)."""
    import warnings

    from scipy.special import ndtri
    from scipy.stats import qmc
    if d == 0:
        return np.zeros((n, 0))
    with warnings.catch_warnings():  # n need not be a power of two (its balance is then only approximate)
        warnings.simplefilter("ignore", UserWarning)
        p = qmc.Sobol(d, scramble=True, seed=seed).random(n)
    u = ndtri(np.clip(p, 1e-12, 1.0 - 1e-12))
    u.setflags(write=False)
    return u


def _col(dev: dict, name: str, n: int) -> np.ndarray:
    return dev[name] if name in dev else np.zeros(n)


def _entered(x, q: Quantity, nominal, by=None):
    """The perturbed value of declared quantity ``q`` at deviations ``x`` (:class:`~synth.robust.tolerances.Quantity`
    ``how``)."""
    if q.how == "add":
        return nominal + x
    if q.how == "set":
        return x
    if q.how == "negate":
        return -x
    if q.how == "relative":
        return nominal * (1.0 + x / 100.0)
    if q.how == "factor":
        return 1.0 + x / 100.0
    return nominal * (1.0 + x / by)  # scale_by


def perturb(base: Base, dev: dict, rows=None) -> tuple:
    """``(apps, attrs)`` of the samples: ``dev`` maps quantities to ``(M,)`` deviations (in their units,
    :class:`~synth.robust.tolerances.Scatter`; 0 for a design the quantity is not in play for), ``rows`` the design
    of each sample (a :class:`Base` of K designs: K-row apps, attrs and groups; default all design 0). Each quantity
    enters as its declaration says (:data:`synth.robust.tolerances.DECLARED`); see the module docstring for what
    stays fixed and follows."""
    n = len(next(iter(dev.values()))) if dev else 1
    rows = np.zeros(n, dtype=np.int64) if rows is None else np.asarray(rows, dtype=np.int64)
    one = len(base.apps) == 1
    a0, f0 = base.apps, base.apps.f

    def at(a):
        a = np.asarray(a)
        return np.broadcast_to(a[:1], (n,)) if one else a[rows]
    live = [q for q in DECLARED.values() if q.name in dev]
    fields = {}
    # the design's columns (one design: read-only views; the perturbed ones are replaced, never written)
    attrs = {t: {k: at(v) for k, v in cols.items()} for t, cols in base.attrs.items()}
    for q in live:  # the worst cases of the nominal model a sample replaces
        for z in q.zero:
            where, _, name = z.partition(":")
            (fields if where == "field" else attrs[where])[name] = np.zeros(n)
    for q in live:
        if q.into == "field":
            fields[q.target] = _entered(dev[q.name], q, at(f0[q.target]) if q.how == "add" else None)
        elif q.into in attrs:
            t = attrs[q.into]
            by = t[q.by] if q.how == "scale_by" else None
            for col in (q.target,) if isinstance(q.target, str) else q.target:
                t[col] = _entered(dev[q.name], q, t.get(col), by)  # set, negate: no nominal needed
    sp = attrs["spring"]
    b0, h0, d0 = (at(base.attrs["spring"][k]) for k in ("b_mm", "h_mm", "main_spring_mean_body_diameter_mm"))
    rnd = sp["round_wire"].astype(bool)
    if any(q.into == "spring" and q.target == "h_mm" for q in live):  # a round wire has one diameter: b = h
        sp["b_mm"] = np.where(rnd, sp["h_mm"], sp["b_mm"])
        sp["b_tol_mm"] = np.where(rnd, 0.0, sp["b_tol_mm"])
    # the made spring keeps its active coils: its stiffness follows from the made wire and diameter (eq. 64-65)
    k0 = at(f0["spring_stiffness_nm_per_deg"])
    with np.errstate(divide="ignore", invalid="ignore"):
        n_nom = torsion_spring.active_coils(sp["E_mpa"], torsion_spring.second_moment_mm4(b0, h0, rnd), d0, k0)
        n_made = torsion_spring.active_coils(sp["E_mpa"], torsion_spring.second_moment_mm4(sp["b_mm"], sp["h_mm"], rnd),
                                 sp["main_spring_mean_body_diameter_mm"], k0)
        fields["spring_stiffness_nm_per_deg"] = k0 * n_made / n_nom
    sized = at(base.groups["axial"].values["cone_spring_sized"]).astype(bool)
    if sized.any():  # the made cone spring: its thickness, the realised gap stack and its force scatter
        ax = attrs["axial"]
        gap = np.zeros(n)
        for q in DECLARED.values():  # each height adds to the gap or takes from it
            if q.into == "gap":
                x = _col(dev, q.name, n)
                gap = gap + x if q.how == "add" else gap - x
        made_t = base.groups["axial"].values["cone_spring_thickness_mm"] if base.cone is None else \
            base.cone["thickness_mm"]  # the supplier's centred spring (steps 6 and 8), its thickness at the variant
        ax[evaluate.MADE_CONE_SPRING_COLUMNS["thickness_mm"]] = np.where(sized, at(made_t), np.nan)
        ax[evaluate.MADE_CONE_SPRING_COLUMNS["deflection_offset_mm"]] = -gap  # a smaller gap deflects the spring more
        for q in DECLARED.values():
            if q.into == "cone":
                ax[evaluate.MADE_CONE_SPRING_COLUMNS[q.target]] = _entered(_col(dev, q.name, n), q, None)
    apps = a0.with_fields(rows, **fields)
    # derived values: the frictions, the made spring (its torque within its tolerance, or the design's own where no
    # tolerance is in play: the tensioner follows from it by eq. (12)-(13), never a spring re-sized to the sample's
    # friction), the made joint's preload about its window's mean (NaN without fixation data)
    for q in DECLARED.values():
        if q.into == "derived" and (q.name in dev or q.always):
            group, _, key = q.by.partition(".")
            nominal = at(base.groups[group].values[key]).astype(float) if q.by else apps.derived[q.target]
            apps.derived[q.target] = _entered(_col(dev, q.name, n), q, nominal)
    return apps, attrs


def evaluate_deviations(base: Base, dev: dict, checks=None, rows=None) -> Samples:
    """The evaluator's margins and histogram values of the samples ``dev`` (one vectorised call; checks of the
    input and core groups alone evaluate those two groups only); ``rows``: see :func:`perturb`."""
    apps, attrs = perturb(base, dev, rows)
    wanted = base.checks if checks is None else checks
    with np.errstate(all="ignore"):
        if {REGISTRY[c].group for c in wanted} <= {"input", "core"}:
            idx = np.arange(len(apps), dtype=np.int64)
            groups = {"input": evaluate.inputs(apps, idx), "core": evaluate.core(apps, idx, attrs["core"], base.settings)}
        else:
            groups = evaluate_design(apps, attrs, base.settings, detail=False,
                                     engine=engines.axial(base.settings, AXIAL_ENGINE))
    margins = {}
    for cid in (base.checks if checks is None else checks):
        margins[cid] = np.asarray(groups[REGISTRY[cid].group].margins[cid], dtype=float)
    values = {}
    for k, g in HISTOGRAM_VALUES.items():
        if g in groups and k in groups[g].values:
            values[k] = np.asarray(groups[g].values[k], dtype=float)
    return Samples(margins, values)


def evaluate_u(base: Base, u: np.ndarray, checks=None) -> Samples:
    """:func:`evaluate_deviations` of standard-normal points ``u`` (``(N, d)``, d = the quantities in play)."""
    x = base.scatter.deviations(u) if len(base.scatter) else np.zeros((len(u), 0))
    return evaluate_deviations(base, {q: x[:, j] for j, q in enumerate(base.scatter.names)} or
                               {"_n": np.zeros(len(u))}, checks)
