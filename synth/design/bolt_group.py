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

__all__ = ["fixation_values", "fixation_reads", "fixation_codes", "bolt_reads", "bolt_codes", "TABLE_ENTRIES_PER_ROW",
           "bolt_core_checks", "bolt_core", "bolt"]

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


#: the bolt table's columns :func:`bolt` reads besides the fixation's (:func:`fixation_reads`)
BOLT_READS = ("bolt_d_mm", "rp02_mpa", "pivot_bore_min_mm")


def bolt_reads(settings: Settings = DEFAULT) -> tuple:
    """The bolt table's columns group ``bolt`` (:func:`bolt`) reads under ``settings``, the fixation's and its own:
    bolts equal in them have the same values and margins for any application and core (:func:`bolt` reads no
    other column: it refuses one, :class:`_Declared`).

    >>> bolt_reads()
    ('bolt_format', 'bolt_property_class', 'bolt_head_type', 'bolt_washer', 'bolt_d_mm', 'rp02_mpa', 'pivot_bore_min_mm')
    """
    return fixation_reads(settings) + BOLT_READS


class _Declared:
    """The bolt columns ``o`` as :func:`bolt` may read them: those of :func:`bolt_reads`, any other a
    :class:`KeyError` naming it (a search evaluates bolts equal in the declared columns once: :func:`bolt_codes`)."""

    def __init__(self, o, keys: tuple):
        self._o, self._keys = o, keys

    def __getitem__(self, k):
        if k not in self._keys:
            raise KeyError(f"group bolt reads the bolt column {k!r}, which bolt_reads() does not declare: add it to "
                           "synth.design.bolt_group.BOLT_READS (searches evaluate bolts equal in the declared columns "
                           "once)")
        return self._o[k]

    def __contains__(self, k) -> bool:
        return k in self._keys and k in self._o


def bolt_codes(o: dict, settings: Settings = DEFAULT) -> tuple:
    """``(code per row, first row of each code)`` of bolt columns ``o``: rows equal in every column group ``bolt``
    reads (:func:`bolt_reads`) share a code, so the same margins for any application and core (as
    :func:`fixation_codes` for the fixation's columns).

    >>> from synth.design.space import space
    >>> code, first = bolt_codes(space().tables["bolt"])
    >>> len(first) < len(code)   # the thesis method reads no tightening method: those bolts are one
    True
    """
    return _codes(o, bolt_reads(settings))


_BOLT_VALUES = ("bolt_tightening_torque_nm", "bolt_axial_force_n", "bolt_sigma_mpa", "bolt_tau_mpa",
                "bolt_sigma_eqv_mpa", "bolt_under_head_stress_mpa", "bolt_thread_stress_mpa",
                "pivot_base_contact_surface_mm2", "average_contact_pressure_mpa", "tilting_safety_factor",
                "sliding_safety_factor", "pivot_base_max_pressure_mpa", "bolt_rp02_mpa",
                "min_head_contact_diameter_mm", "min_active_threads", "bolt_force_tilting_n", "bolt_force_sliding_n",
                "bolt_head_contact_diameter_mm", "bolt_clamp_force_required_n", "bolt_permissible_preload_n",
                "bolt_required_preload_min_n", "bolt_required_preload_max_n", "bolt_residual_clamp_force_n",
                "bolt_embedding_loss_n")


def fixation_codes(o: dict, settings: Settings = DEFAULT) -> tuple:
    """``(code per row, first row of each code)`` of bolt columns ``o`` (a table or rows of one): rows equal in
    every column the fixation reads (:func:`fixation_reads`, those ``o`` has) share a code, so the same fixation
    for any application; codes in order of first appearance (a hash factorisation of each column: no Python tuple
    per row; a missing value is a value of its own).

    >>> o = {"bolt_format": np.array(["M8", "M10", "M8"], dtype=object), "bolt_property_class": ["8.8"] * 3,
    ...      "bolt_head_type": np.array(["hex", "hex", "hex"], dtype=object), "cost_eur": [1.0, 2.0, 3.0]}
    >>> [x.tolist() for x in fixation_codes(o)]
    [[0, 1, 0], [0, 1]]
    """
    return _codes(o, fixation_reads(settings))


def _codes(o: dict, columns: tuple) -> tuple:
    """:func:`fixation_codes` over ``columns`` (those ``o`` has)."""
    import pandas as pd  # loaded already wherever many rows come (the bulk engine)
    cols = [np.asarray(o[k], dtype=object) for k in columns if k in o]
    n = len(cols[0]) if cols else len(next(iter(o.values())))
    code = np.zeros(n, dtype=np.int64)
    for col in cols:
        c, u = pd.factorize(col, use_na_sentinel=False)
        code = pd.factorize(code * len(u) + c)[0].astype(np.int64)  # < n: no overflow however many columns
    return _first_codes(code)


def _first_codes(code) -> tuple:
    """``(codes, first row of each)``: the distinct values of integer array ``code`` numbered in order of first
    appearance.

    >>> [x.tolist() for x in _first_codes(np.array([7, 3, 7, 5]))]
    [[0, 1, 0, 2], [0, 1, 3]]
    """
    import pandas as pd
    code = pd.factorize(np.asarray(code, dtype=np.int64))[0].astype(np.int64)
    first = np.zeros(int(code.max()) + 1 if len(code) else 0, dtype=np.int64)
    first[code[::-1]] = np.arange(len(code))[::-1]  # each code's first row
    return code, first


#: the fixation of many (application, bolt) rows is one call over their distinct applications x distinct bolts (as
#: the fixation reads them, :func:`fixation_codes`) when that table has at most this many entries per row (a few
#: entries nobody asked for cost less than the application-only physics per row); otherwise one call over the
#: distinct (application, bolt) pairs, each application with its own bolt (the production samples of a few
#: designs: each sample its own application, each design its own bolt)
TABLE_ENTRIES_PER_ROW = 2.0


def fixation_values(apps, a, o: dict, settings: Settings = DEFAULT, codes=None) -> dict:
    """Step 10 (:func:`synth.model.bolted_joint.fixation`) for rows of applications ``a`` and bolts ``o``.

    The fixation once per distinct application and bolt as the fixation reads it (:func:`fixation_codes`, the
    columns of :func:`fixation_reads`: the tightening method under the VDI 2230 method only, the thesis path
    tightening to the required force whatever the method), each bolt with its own head form, washer series and
    tightening method, the friction coefficients of each application's environment passed per application; the
    rows gather their (application, bolt) entry. One vectorised call for the rows whose application gives its seat
    (``bolt_head_contact_external_diameter_mm``), one for those whose does not: over their distinct applications x
    distinct bolts (``fixation(..., candidates=...)``) when that table is dense (:data:`TABLE_ENTRIES_PER_ROW`: the
    catalog's bolts for a few applications, the bulk's blocks), else over their distinct (application, bolt) pairs
    (``candidate_of``: a production sample with its design's bolt). Every entry is what the call naming that bolt
    alone gives (element-wise arithmetic). NaN for applications without their fixation data, and for rows whose
    head form, washer or tightening method is missing (NaN). ``codes``: the rows' :func:`fixation_codes` when the
    caller has them (those of the bolt table at the rows' bolts; any labels with the same partition), not
    factorised again.
    """
    n = len(a)
    out = {k: np.full(n, np.nan) for k in _BOLT_VALUES}
    has = apps.met("fixation")[a]
    if not has.any():
        return out
    rows = np.flatnonzero(has)
    nr = len(rows)
    head = np.asarray(o["bolt_head_type"], dtype=object)[rows]
    washer = np.asarray(o["bolt_washer"], dtype=object)[rows] if "bolt_washer" in o else np.full(nr, bolted_joint.NO_WASHER, object)
    vdi = settings.bolt_method == "vdi2230"
    method = np.asarray(o["bolt_tightening"], dtype=object)[rows] if vdi and "bolt_tightening" in o else \
        np.full(nr, bolted_joint.DEFAULT_TIGHTENING_METHOD, object)
    named = (head == head) & (washer == washer) & (method == method)  # a missing name (NaN) has no fixation
    if not named.all():
        rows, head, washer, method = rows[named], head[named], washer[named], method[named]
        nr = len(rows)
    known = None if codes is None else np.asarray(codes)[rows]
    fmt, cls = np.asarray(o["bolt_format"], dtype=object)[rows], np.asarray(o["bolt_property_class"], dtype=object)[rows]
    cols = {"bolt_format": fmt, "bolt_property_class": cls, "bolt_head_type": head, "bolt_washer": washer,
            "bolt_tightening": method}
    if known is not None:
        code = known
    elif nr and all((c == c[0]).all() for c in cols.values()):  # one bolt (one design's samples): no factorisation
        code = np.zeros(nr, dtype=np.int64)
    else:
        code = fixation_codes(cols, settings)[0]
    aa_all = np.asarray(a)[rows]
    given = np.asarray(apps.given["bolt_head_contact_external_diameter_mm"][aa_all], dtype=bool)
    made = apps.derived.get("bolt_clamp_force_n")  # a made joint's preload (synth.robust), NaN: the window
    f = apps.f
    for g in (False, True):
        sel = np.flatnonzero(given == g)
        if not len(sel):
            continue
        ua, ia = np.unique(aa_all[sel], return_inverse=True)
        ia = np.asarray(ia).reshape(-1)
        kc, first = _first_codes(code[sel])  # the bolts among these rows, each row's
        b = sel[first]
        bolts = dict(candidates=list(zip(fmt[b].tolist(), cls[b].tolist())), head_type=[str(x) for x in head[b]],
                     washer=[str(x) for x in washer[b]], tightening_method=[str(x) for x in method[b]])
        flat = ia * len(b) + kc  # each row's entry of the (application, bolt) table
        if len(ua) * len(b) <= TABLE_ENTRIES_PER_ROW * len(sel):  # the table, in one call
            at, pick, shape = ua, None, (len(ua), len(b))
        else:  # the distinct (application, bolt) pairs, each application with its own bolt
            up, flat = np.unique(flat, return_inverse=True)
            at, pick, shape = ua[up // len(b)], up % len(b), (len(up),)
        env = apps.env[at]
        r = bolted_joint.fixation(
            apps.hubload_nominal_n[at], f["middle_plane_belt_height_mm"][at],
            f["middle_plane_belt_height_increment_worst_mm"][at], f["tilting_safety_factor"][at],
            f["sliding_safety_factor"][at], f["engine_support_internal_diameter_mm"][at],
            f["engine_support_external_diameter_mm"][at], f["contact_angle_deg"][at],
            f["support_yield_strength_compression_mpa"][at], f["support_yield_strength_traction_mpa"][at],
            number_of_active_threads=f["number_of_active_threads"][at],
            mu_crankcase=_mu(apps, "mu_crankcase", "pivot_base_crankcase", at, env),
            mu_thread=_mu(apps, "mu_thread", "thread", at, env), mu_head=_mu(apps, "mu_head", "under_head", at, env),
            bolt_head_contact_external_diameter_mm=f["bolt_head_contact_external_diameter_mm"][at] if g else None,
            method=settings.bolt_method, clamp_force_n=None if made is None else made[at], candidate_of=pick,
            **bolts)
        flat = np.asarray(flat).reshape(-1)
        for k in _BOLT_VALUES:
            if k in r:
                out[k][rows[sel]] = np.broadcast_to(np.asarray(r[k], dtype=float), shape).reshape(-1)[flat]
    return out


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


def bolt(apps, cg: Group, r, o: dict, settings: Settings = DEFAULT, fixation: dict | None = None,
         codes=None) -> Group:
    """Group ``bolt`` (step 10 and the pivot wall of step 2) for core rows ``r`` and bolt options ``o``.

    ``fixation`` (optional): the :func:`fixation_values` of the rows, when the caller computed them once per
    application and bolt (they do not depend on the core); ``codes``: the rows' fixation codes, as
    :func:`fixation_values` takes them.
    """
    a = cg.values["app"][r]
    f = Fields(apps, a)
    n = len(a)
    o = _Declared(o, bolt_reads(settings))
    fix = fixation if fixation is not None else fixation_values(apps, a, o, settings, codes)
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
