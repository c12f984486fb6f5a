"""The evaluator's axial damping group (steps 5-8: Table 4, the belt plane, the cone spring, the plastic wear) and
its model fidelity: the values the fidelity changes, the checks it does not, and screen-then-judge
(:func:`axial_judged`, :func:`axial_full`).
"""

from __future__ import annotations

import numpy as np

from synth import parts
from synth.design.assessment import assess_group
from synth.design.constraints import by_group
from synth.design.group import CONSTANT_LIMITS, Fields, Group, const as _const, finish, read_core
from synth.design.settings import DEFAULT, Settings
from synth.kernels import axial as axial_engine  # the cone spring and the wear on the caller's engine
from synth.model import packaging, stackup

__all__ = ["MADE_CONE_SPRING_COLUMNS", "CONE_SPRING_VALUES", "PLASTIC_WEAR_VALUES", "FIDELITY_VALUES",
           "fidelity_free", "axial", "axial_before_physics", "axial_before_wear", "axial_judged", "axial_full",
           "fidelity_free_ok"]


#: optional axial option columns of a made cone spring -> the argument of synth.model.disc_spring.cone_spring
MADE_CONE_SPRING_COLUMNS = {"thickness_mm": "cone_spring_made_thickness_mm",
                            "deflection_offset_mm": "cone_spring_deflection_offset_mm",
                            "force_factor": "cone_spring_force_factor"}
#: the cone spring's values (step 8, :func:`synth.model.disc_spring.cone_spring`): the model fidelity changes them
CONE_SPRING_VALUES = (
    "cone_spring_fax_max_tolerance_n", "cone_spring_fax_min_tolerance_n", "cone_spring_fax_nominal_n",
    "cone_spring_fax_band_n", "cone_spring_force_band_room_n", "cone_spring_gap_band_room_n", "cone_spring_thickness_mm",
    "cone_spring_cone_height_mm", "cone_spring_free_height_mm", "cone_spring_nominal_deflection_mm",
    "cone_spring_max_deflection_mm", "cone_spring_rate_n_per_mm", "sigma_om_mpa", "sigma_i_mpa", "sigma_ii_mpa",
    "sigma_iii_mpa", "sigma_iv_mpa", "cone_spring_diameter_ratio", "cone_spring_aspect_ratio", "cone_spring_thinness",
    "cone_spring_force_tolerance_plus", "cone_spring_force_tolerance_minus")
#: the plastic wear's values (step 5, :func:`synth.model.friction_wear.plastic_wear`): the fidelity changes them
PLASTIC_WEAR_VALUES = ("damping_eol_nm", "axial_damping_eol_nm", "damper_pad_wear_mm", "endcap_spacer_wear_mm",
                       "plastic_wear_total_mm", "cone_spring_force_eol_n", "damper_pad_wear_max_mm",
                       "endcap_spacer_wear_max_mm")
#: every value of group ``axial`` the model fidelity may change (those two, and what :func:`axial` derives of them)
FIDELITY_VALUES = CONE_SPRING_VALUES + PLASTIC_WEAR_VALUES + ("cone_spring_sigma_om_abs_mpa",)


def fidelity_free() -> tuple:
    """The registry's (non-advisory) axial constraints that read no :data:`FIDELITY_VALUES` value: the screening
    and the full model give them the same margin (``tests/test_fidelity.py`` checks it)."""
    out = []
    for c in by_group("axial"):
        reads = (c.value, c.limit, c.scale, c.applies, c.objective_unless)
        if not c.advisory and not any(k in FIDELITY_VALUES for k in reads if k):
            out.append(c.id)
    return tuple(out)




def axial(apps, cg: Group, r, o: dict, settings: Settings = DEFAULT, time_points: int = 0,
          engine: str | None = None, wear: bool = True) -> Group:
    """Group ``axial`` (Table 4, belt plane, cone spring, plastic wear) for core rows ``r`` and axial options ``o``.

    ``o``: the axial table's columns (spacer, cone-spring variant). Rows pair a core with a damper pad with
    a real option, or a core without one with the ``none`` option. ``time_points`` keeps the wear history.
    ``engine``: the cone spring's and the wear's (:mod:`synth.kernels.axial`; None: the numpy reference), chosen
    by a search of many rows with :func:`synth.kernels.engines.axial`. ``wear=False``: without the plastic wear,
    only the checks that read none of its values (:func:`axial_before_wear`).
    """
    p = parts.arrays()
    v, a, f, cv, real, es_h, de, di = _axial_base(apps, cg, r, o)
    n = len(a)
    pad = cv["axial_group_present"] > 0
    zeta = np.asarray(o["cone_spring_aspect_ratio"], dtype=float)
    phi = np.asarray(o["cone_spring_deflection_ratio"], dtype=float)
    # a made cone spring is there whatever the sample's damping split says (its force then decides the band)
    made_rows = np.isfinite(np.asarray(o[MADE_CONE_SPRING_COLUMNS["thickness_mm"]], dtype=float)) \
        if MADE_CONE_SPRING_COLUMNS["thickness_mm"] in o else False
    act = real & pad & ((cv["axial_damping_nm"] > 0) | made_rows) & (de > di) & (zeta > 0) & (phi > 0) & (phi <= 1)
    v["cone_spring_sized"] = act
    keys = CONE_SPRING_VALUES
    i = np.flatnonzero(act)
    every, sized = _rows_of(i, n)  # every row sized (the usual block of options): whole columns
    for k in keys:
        v[k] = np.empty(n) if every else np.full(n, np.nan)
    v.update(_cone_diameters(cv, real, de, di))
    tol = f["damping_tolerance_nm"]
    mu_pl = apps.mu_plastic[a]
    gap = stackup.gap_tolerance_mm("worst_case")
    if len(i):
        # a made cone spring (synth.robust's production-scatter samples): its thickness, the realised deflection
        # offset of the gap stack and its force factor, per row (see synth.model.disc_spring.cone_spring)
        made = {k: sized(np.asarray(o[c], dtype=float)) for k, c in MADE_CONE_SPRING_COLUMNS.items() if c in o}
        cs = axial_engine.cone_spring(sized(cv["axial_damping_nm"]), sized(apps.damping_target_or_zero_nm[a]),
                                 np.nan_to_num(sized(tol), nan=0.0), sized(cv["radial_damping_nm"]), sized(mu_pl),
                                 sized(cv["damper_pad_mean_radius_mm"]),
                                 sized(np.asarray(o["endcap_spacer_mean_radius_mm"])), sized(de), sized(di), gap,
                                 aspect_ratio=sized(zeta), deflection_ratio=sized(phi), fidelity=settings.model,
                                 engine=engine or "numpy", **made)
        _put_columns(v, keys, cs, None if every else i)
    v["cone_spring_gap_tolerance_mm"] = np.full(n, gap)
    v["cone_spring_sigma_om_abs_mpa"] = np.abs(v["sigma_om_mpa"])
    v["cone_spring_sigma_om_max_mpa"] = np.full(n, _const("cone_spring_sigma_om_max_mpa"))
    for key, rng in (("diameter_ratio", "diameter_ratio"), ("aspect_ratio", "aspect_ratio"), ("thinness", "thinness")):
        lo, hi = p.cone_ranges[rng]
        v[f"cone_spring_{key}_min"], v[f"cone_spring_{key}_max"] = np.full(n, lo), np.full(n, hi)
    v["damping_eol_limit_nm"] = f["damping_eol_limit_nm"]
    if not wear:
        return finish("axial", v, apps, a, checks=_known_checks(v), rules=settings.rules, core=cv)
    w = i[apps.durability_given[a][i]]
    worn, at = _rows_of(w, n)  # every row worn: whole columns, as above
    for k in PLASTIC_WEAR_VALUES:
        v[k] = np.empty(n) if worn else np.full(n, np.nan)
    history = None
    if len(w):
        pw = axial_engine.plastic_wear(at(v["cone_spring_nominal_deflection_mm"]), at(de), at(di),
                                  at(v["cone_spring_thickness_mm"]), at(v["cone_spring_cone_height_mm"]),
                                  at(cv["damper_pad_contact_area_mm2"]), at(cv["damper_pad_mean_radius_mm"]),
                                  at(cv["damper_pad_axial_height_mm"]),
                                  at(np.asarray(o["endcap_spacer_contact_area_mm2"])),
                                  at(np.asarray(o["endcap_spacer_mean_radius_mm"])), at(es_h),
                                  at(apps.theta_pp_deg[a]), at(apps.frequency_hz[a]), at(apps.duration_h[a]),
                                  at(cv["radial_damping_nm"]),
                                  k_wear_mm3_per_n_m=at(apps.k_wear_plastic_mm3_per_n_m[a]),
                                  plastic_friction_coefficient=at(mu_pl), fidelity=settings.model,
                                  time_points=time_points, engine=engine or "numpy")
        _put_columns(v, PLASTIC_WEAR_VALUES, pw, None if worn else w)
        history = pw.get("history")
    g = finish("axial", v, apps, a, rules=settings.rules, core=cv)
    if history is not None:
        g.values["_history_rows"] = w
        g.values["_history"] = history
    return g


def _axial_base(apps, cg: Group, r, o: dict) -> tuple:
    """What group ``axial`` reads and derives before its physics (the cone spring, the wear): ``(values, a, fields,
    core values, real, spacer height, De, Di)``: Table 4's spacer, the belt plane, the cone spring's diameters."""
    a = cg.values["app"][r]
    f = Fields(apps, a)
    cv = read_core("axial", cg, r)
    real = np.asarray(o["axial_group_present"], dtype=bool)
    std = apps.layout_standard[a]
    es_h = np.asarray(o["endcap_spacer_axial_height_mm"], dtype=float)
    pad = cv["axial_group_present"] > 0
    v = {"app": a, "layout_standard": std, "layout_reverse": ~std, "axial_group_present": real.astype(float),
         "axial_group_mismatch": (real != pad).astype(float),
         "middle_plane_belt_height_mm": f["middle_plane_belt_height_mm"],
         "belt_plane_limit_mm": np.where(std, packaging.max_belt_plane_height_mm(f["max_pivot_height_mm"],
                                                                          cv["bearing_width_mm"], es_h),
                                         packaging.min_belt_plane_height_mm(cv["bearing_width_mm"], es_h)),
         "endcap_spacer_max_axial_damping_nm": np.asarray(o["endcap_spacer_max_axial_damping_nm"], dtype=float),
         "axial_damping_nm": cv["axial_damping_nm"],
         "cone_spring_min_internal_diameter_mm": cv["cone_spring_min_internal_diameter_mm"],
         "cone_spring_table8_max_mm": cv["cone_spring_table8_max_mm"],
         "damper_pad_outer_diameter_mm": cv["damper_pad_outer_diameter_mm"]}
    de = cv["cone_spring_max_external_diameter_mm"] - np.asarray(o["cone_spring_de_reduction_mm"], dtype=float)
    di = cv["cone_spring_min_internal_diameter_mm"] + np.asarray(o["cone_spring_di_increase_mm"], dtype=float)
    return v, a, f, cv, real, es_h, de, di


def _cone_diameters(cv: dict, real, de, di) -> dict:
    """The cone spring's largest, outer and inner diameters of the axial rows (NaN without an axial group)."""
    return {"cone_spring_max_external_diameter_mm": np.where(real, cv["cone_spring_max_external_diameter_mm"], np.nan),
            "cone_spring_external_diameter_mm": np.where(real, de, np.nan),
            "cone_spring_internal_diameter_mm": np.where(real, di, np.nan)}


def axial_before_physics(apps, cg: Group, r, o: dict, settings: Settings = DEFAULT) -> Group:
    """The checks of group ``axial`` that read only what it derives before its physics (:func:`_axial_base`: no
    cone spring, no wear; so none the fidelity changes), at their cost: the same margins as :func:`axial` gives
    them (a search discards the rows that fail one before the physics). A check added with ``register`` that reads
    a value of the physics is left out (the registry as it is now)."""
    v, a, _, cv, real, _, de, di = _axial_base(apps, cg, r, o)
    v.update(_cone_diameters(cv, real, de, di))
    return finish("axial", v, apps, a, checks=_known_checks(v), rules=settings.rules, core=cv)


def _known_checks(v: dict) -> tuple:
    """The checks of group ``axial`` whose margin reads only values ``v`` has (or constants), without a physics
    function: those an evaluation that stops early (:func:`axial_before_physics`, :func:`axial_before_wear`) can
    judge, with the margins the whole group gives them (the registry as it is now)."""
    return tuple(c for c in by_group("axial") if c.physics is None
                 and all(k in v or k in CONSTANT_LIMITS for k in (c.value, c.limit, c.scale, c.applies,
                                                                   c.objective_unless) if k))


def axial_before_wear(apps, cg: Group, r, o: dict, settings: Settings = DEFAULT, engine: str | None = None) -> Group:
    """The checks of group ``axial`` that read nothing of the plastic wear (Table 4, the belt plane, the cone
    spring), with the margins :func:`axial` gives them, at the cost of the cone spring: a row that fails one fails
    the group at ``settings``'s fidelity, and the group's smallest margin is at most theirs (a search need not
    solve its wear; the wear is most of the group's cost). ``engine``: as :func:`axial`'s."""
    return axial(apps, cg, r, o, settings, engine=engine, wear=False)


def _rows_of(idx: np.ndarray, n: int):
    """``(every, take)``: whether the rows ``idx`` are all ``n`` rows, and the function giving a column's values at
    them (the column itself when they are: no gather and scatter per value)."""
    every = len(idx) == n
    return every, ((lambda x: x) if every else (lambda x: x[idx]))


def _put_columns(v: dict, keys, got: dict, rows) -> None:
    """``v[k][rows] = got[k]`` for each of ``keys``; ``rows`` None: every row, a value of the right length and type
    taken as it is (the compiled twins return each value as a column of its own: no copy)."""
    for k in keys:
        col = got[k]
        if rows is None and isinstance(col, np.ndarray) and col.shape == v[k].shape and col.dtype == v[k].dtype:
            v[k] = col
        else:
            v[k][slice(None) if rows is None else rows] = col


def axial_judged(apps, cg: Group, r, o: dict, settings: Settings = DEFAULT, engine: str | None = None) -> Group:
    """Group ``axial`` as a search reads it: screen, then judge.

    At fidelity ``screening`` the rows the screening model passes are evaluated again by the full model
    (:attr:`Settings.judge`) and carry its values, margins and states: a row passes only when both models pass
    it, and a passing row's margins (the margin objective's) are the full model's. Nearest designs are ranked
    by the search model (:meth:`Group.rank`: the screening group, kept as ``search``), as the bulk engine ranks
    them; a reported design is verified again. At the other fidelities :func:`axial` itself. ``engine``: as
    :func:`axial`'s, for both models.
    """
    g = axial(apps, cg, r, o, settings, engine=engine)
    if settings.judge is settings:
        return g
    return _judged_rows(apps, cg, r, o, settings, g, g.ok(), engine)


def axial_full(apps, cg: Group, r, o: dict, settings: Settings = DEFAULT, engine: str | None = None) -> Group:
    """The full model's verdicts of group ``axial`` at the cost of the rows that can pass it (``settings``: the
    search's, fidelity ``screening``).

    The screening model everywhere, then the full model on the rows that pass every constraint whose margin the
    fidelity does not change (:data:`FIDELITY_FREE`: the others fail at any fidelity): ``ok()`` is the full
    model's verdict; nearest designs are ranked by the screening group (:meth:`Group.rank`). At the other
    fidelities :func:`axial` itself.
    """
    g = axial(apps, cg, r, o, settings, engine=engine)
    if settings.judge is settings:
        return g
    return _judged_rows(apps, cg, r, o, settings, g, fidelity_free_ok(g), engine)


def fidelity_free_ok(g: Group) -> np.ndarray:
    """``(n,)`` bool: the rows of an axial group that pass every :data:`FIDELITY_FREE` constraint (the others fail
    at any fidelity)."""
    return assess_group(g, only=fidelity_free()).ok  # the registry now, never a list frozen at import


def _judged_rows(apps, cg, r, o, settings, g: Group, which, engine=None) -> Group:
    """``g`` (the search model's group) with the rows ``which`` replaced by the judge's, and ``g`` as ``search``."""
    rows = np.flatnonzero(which)
    if not len(rows):
        return Group(g.name, g.values, g.margins, g.state, search=g, rules=g.rules)
    full = axial(apps, cg, np.asarray(r)[rows], {k: np.asarray(v)[rows] for k, v in o.items()}, settings.judge,
                 engine=engine)
    out = g.put(rows, full)
    out.search = g
    return out
