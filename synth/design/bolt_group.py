"""The evaluator's bolt group (step 10, the fixation, and the pivot wall of step 2): the fixation per application
and bolt (:func:`fixation_values`), the checks that read the core (:func:`bolt_core`) and the group (:func:`bolt`).
"""

from __future__ import annotations

import numpy as np

from synth import parts
from synth.design.constraints import by_group
from synth.design.group import Fields, Group, const as _const, core_values, finish, read_core
from synth.design.settings import DEFAULT, Settings
from synth.model import bolted_joint

__all__ = ["fixation_values", "fixation_reads", "bolt_core_checks", "bolt_core", "bolt"]

#: the bolt table's columns :func:`fixation_values` reads (the tightening method too under the VDI 2230 method:
#: :func:`fixation_reads`)
FIXATION_READS = ("bolt_format", "bolt_property_class", "bolt_head_type", "bolt_washer")


def fixation_reads(settings: Settings = DEFAULT) -> tuple:
    """The bolt table's columns :func:`fixation_values` reads under ``settings``: bolts equal in them get the same
    fixation for any application.

    >>> fixation_reads(Settings(bolt_method="vdi2230"))[-1]
    'bolt_tightening'
    """
    return FIXATION_READS + (("bolt_tightening",) if settings.bolt_method == "vdi2230" else ())


_BOLT_VALUES = ("bolt_tightening_torque_nm", "bolt_axial_force_n", "bolt_sigma_mpa", "bolt_tau_mpa",
                "bolt_sigma_eqv_mpa", "bolt_under_head_stress_mpa", "bolt_thread_stress_mpa",
                "pivot_base_contact_surface_mm2", "average_contact_pressure_mpa", "tilting_safety_factor",
                "sliding_safety_factor", "pivot_base_max_pressure_mpa", "bolt_rp02_mpa",
                "min_head_contact_diameter_mm", "min_active_threads", "bolt_force_tilting_n", "bolt_force_sliding_n",
                "bolt_head_contact_diameter_mm", "bolt_clamp_force_required_n", "bolt_permissible_preload_n",
                "bolt_required_preload_min_n", "bolt_required_preload_max_n", "bolt_residual_clamp_force_n",
                "bolt_embedding_loss_n")


def fixation_values(apps, a, o: dict, settings: Settings = DEFAULT) -> dict:
    """Step 10 (:func:`synth.model.bolted_joint.fixation`) for rows of applications ``a`` and bolts ``o``.

    One vectorised call per bolt-head form, washer series, tightening method (the VDI 2230 path only: the
    thesis path tightens to the required force whatever the method) and whether the application gives its
    seat (``bolt_head_contact_external_diameter_mm``): the distinct applications of those rows x the distinct
    bolts (format, property class) among them, every bolt evaluated as the chosen one
    (``fixation(..., candidates=...)``), the friction coefficients of each application's environment passed per
    application; the rows gather their (application, bolt) entry. NaN for applications without their fixation data.
    """
    n = len(a)
    out = {k: np.full(n, np.nan) for k in _BOLT_VALUES}
    has = apps.met("fixation")[a]
    if not has.any():
        return out
    rows = np.flatnonzero(has)
    aa_all = np.asarray(a)[rows]
    fmt, cls = np.asarray(o["bolt_format"], dtype=object)[rows], np.asarray(o["bolt_property_class"], dtype=object)[rows]
    head = np.asarray(o["bolt_head_type"], dtype=object)[rows]
    nr = len(rows)
    washer = np.asarray(o["bolt_washer"], dtype=object)[rows] if "bolt_washer" in o else np.full(nr, bolted_joint.NO_WASHER, object)
    vdi = settings.bolt_method == "vdi2230"
    method = np.asarray(o["bolt_tightening"], dtype=object)[rows] if vdi and "bolt_tightening" in o else \
        np.full(nr, bolted_joint.DEFAULT_TIGHTENING_METHOD, object)
    given = apps.given["bolt_head_contact_external_diameter_mm"][aa_all]
    f = apps.f
    made = apps.derived.get("bolt_clamp_force_n")  # a made joint's preload (synth.robust), NaN: the window
    for h, w, m, g, sel in _groups(head, washer, method, given):
        ua, ia = np.unique(aa_all[sel], return_inverse=True)
        fs, cs = fmt[sel], cls[sel]
        if (fs == fs[0]).all() and (cs == cs[0]).all():  # one bolt (the samples of one design): no dictionary
            ib, pairs = np.zeros(len(sel), dtype=np.int64), [(fs[0], cs[0])]
        else:  # the distinct (format, class) pairs in order of first appearance, and each row's
            ib, pairs = _pair_codes(fs, cs)
        env = apps.env[ua]
        r = bolted_joint.fixation(
            apps.hubload_nominal_n[ua], f["middle_plane_belt_height_mm"][ua],
            f["middle_plane_belt_height_increment_worst_mm"][ua], f["tilting_safety_factor"][ua],
            f["sliding_safety_factor"][ua], f["engine_support_internal_diameter_mm"][ua],
            f["engine_support_external_diameter_mm"][ua], f["contact_angle_deg"][ua],
            f["support_yield_strength_compression_mpa"][ua], f["support_yield_strength_traction_mpa"][ua],
            number_of_active_threads=f["number_of_active_threads"][ua],
            mu_crankcase=_mu(apps, "mu_crankcase", "pivot_base_crankcase", ua, env),
            mu_thread=_mu(apps, "mu_thread", "thread", ua, env), mu_head=_mu(apps, "mu_head", "under_head", ua, env),
            bolt_head_contact_external_diameter_mm=f["bolt_head_contact_external_diameter_mm"][ua] if g else None,
            head_type=str(h), washer=str(w), candidates=pairs, method=settings.bolt_method,
            tightening_method=str(m), clamp_force_n=None if made is None else made[ua])
        ia = np.asarray(ia).reshape(-1)
        at, flat = rows[sel], ia * len(pairs) + ib  # each row's entry of the (application, bolt) table
        for k in _BOLT_VALUES:
            if k in r:
                out[k][at] = np.broadcast_to(np.asarray(r[k], dtype=float), (len(ua), len(pairs))).reshape(-1)[flat]
    return out


def _groups(head, washer, method, given):
    """``(head, washer, method, given, rows)`` for each distinct combination of the rows' bolt-head form,
    washer series, tightening method and given seat, the rows an index array in increasing order (a row in at
    most one group; one holding a value not equal to itself, NaN, in none, as an element-wise ``==`` selects).

    >>> s = lambda *v: np.array(v, dtype=object)
    >>> [(h, w, m, g, r.tolist()) for h, w, m, g, r in _groups(s("a", "b", "a"), s("x", "x", "x"), s("t", "t", "t"),
    ...                                                         np.array([True, False, False]))]
    [('a', 'x', 't', False, [2]), ('a', 'x', 't', True, [0]), ('b', 'x', 't', False, [1])]
    """
    import pandas as pd  # loaded already wherever many rows come (the bulk engine)
    cols = (head, washer, method)
    code = np.zeros(len(given), dtype=np.int64)
    for col in cols:
        c, u = pd.factorize(col, use_na_sentinel=False)
        if not all(isinstance(v, str) for v in u):  # None or NaN among them: compare element-wise, as ever
            return _groups_by_value(head, washer, method, given)
        code = code * len(u) + c
    code = code * 2 + np.asarray(given, dtype=np.int64)
    order = np.argsort(code, kind="stable")  # each group's rows in increasing order
    cut = np.flatnonzero(np.diff(code[order])) + 1
    return [(head[sel[0]], washer[sel[0]], method[sel[0]], bool(given[sel[0]]), sel) for sel in np.split(order, cut)
            if len(sel)]


def _groups_by_value(head, washer, method, given):
    """:func:`_groups` by element-wise comparison (any values)."""
    out = []
    for h, w, m in dict.fromkeys(zip(head.tolist(), washer.tolist(), method.tolist())):
        for g in (False, True):
            sel = np.flatnonzero((head == h) & (washer == w) & (method == m) & (given == g))
            if len(sel):
                out.append((h, w, m, g, sel))
    return out


def _pair_codes(x, y) -> tuple:
    """``(codes, pairs)``: the distinct pairs ``(x[i], y[i])`` in order of first appearance, and each row's index
    among them (a hash factorisation of each column, then of the pairs of codes: no Python tuple per row).

    >>> c, p = _pair_codes(np.array(["M8", "M10", "M8"], dtype=object), np.array(["8.8", "8.8", "8.8"], dtype=object))
    >>> c.tolist(), p
    ([0, 1, 0], [('M8', '8.8'), ('M10', '8.8')])
    """
    import pandas as pd  # loaded already wherever many rows come (the bulk engine)
    cx, ux = pd.factorize(x, use_na_sentinel=False)  # a missing value is a value of its own, as in a dictionary
    cy, uy = pd.factorize(y, use_na_sentinel=False)
    codes, uniq = pd.factorize(cx.astype(np.int64) * len(uy) + cy)
    return codes.astype(np.int64), [(ux[int(k) // len(uy)], uy[int(k) % len(uy)]) for k in uniq]


def _mu(apps, key: str, interface: str, ua, env) -> np.ndarray:
    """The friction coefficient ``key`` of applications ``ua`` (:class:`~synth.design.applications.Applications`
    derives it per application; the catalog's value of their environment ``env`` otherwise)."""
    d = apps.derived.get(key)
    return np.asarray(d[ua] if d is not None else parts.mu(interface, env), dtype=float)


def bolt_core_checks(core) -> tuple:
    """The checks of group ``bolt`` that read the core (a value of ``core``, a core group's values or their
    names, among what their margin reads, :meth:`~synth.design.constraints.Constraint.reads`: the pivot wall of
    step 2, a check added with ``register``); the others depend on the application and the bolt only."""
    read = set(core_values("bolt", core))
    return tuple(c for c in by_group("bolt") if read.intersection(c.reads()))


def bolt_core(apps, a, core: dict, o: dict, settings: Settings = DEFAULT) -> Group:
    """The checks of group ``bolt`` that read the core (:func:`bolt_core_checks`) for rows of applications ``a``
    with core values ``core`` (:func:`core_values`) and bolt columns ``o`` (``bolt_d_mm`` and what else
    they read), broadcasting to ``a``'s shape (the bulk engine: core rows x bolt diameters): the registry's
    margins, state and design rules as :func:`bolt` gives them, without the fixation (the per-core part of the
    bolt group)."""
    v = {"app": a, "bolt_d_mm": np.asarray(o["bolt_d_mm"], dtype=float)}
    return finish("bolt", v, apps, a, checks=bolt_core_checks(core), rules=settings.rules, core=core)


def bolt(apps, cg: Group, r, o: dict, settings: Settings = DEFAULT, fixation: dict | None = None) -> Group:
    """Group ``bolt`` (step 10 and the pivot wall of step 2) for core rows ``r`` and bolt options ``o``.

    ``fixation`` (optional): the :func:`fixation_values` of the rows, when the caller computed them once per
    application and bolt (they do not depend on the core).
    """
    a = cg.values["app"][r]
    f = Fields(apps, a)
    n = len(a)
    fix = fixation if fixation is not None else fixation_values(apps, a, o, settings)
    v = {"app": a, "bolt_d_mm": np.asarray(o["bolt_d_mm"], dtype=float), **fix}
    v["bolt_method_thesis"] = np.full(n, settings.bolt_method == "thesis")
    v["bolt_method_vdi"] = ~v["bolt_method_thesis"]
    v["bolt_sigma_permissible_mpa"] = _const("bolt_yield_utilisation_max") * np.asarray(o["rp02_mpa"], dtype=float)
    v["pivot_bore_min_mm"] = np.asarray(o["pivot_bore_min_mm"], dtype=float)
    for k in ("tilting_safety_factor", "sliding_safety_factor"):
        v[f"{k}_target"] = f[k]
    for k in ("engine_support_internal_diameter_mm", "support_yield_strength_compression_mpa",
              "support_yield_strength_traction_mpa"):
        v[k] = f[k]
    return finish("bolt", v, apps, a, rules=settings.rules, core=read_core("bolt", cg, r))
