"""The one evaluator: every derived value and every margin of the registry, on arrays.

Each evaluation group of :data:`synth.design.constraints.GROUPS` has one
function here that computes, for aligned arrays of rows (an application, a
core, an option of the group), the values its constraints compare, by calling
the physics of :mod:`synth.model`; :func:`finish` then turns values into the
registry's margins, with "not applicable" and "not verified" derived from the
registry. Every consumer calls these functions:

* the flowchart with the one design its sequential procedure builds (and with
  the candidates of its selection loops);
* the optimiser with the catalog product of one application (cores x options);
* the bulk engine with the rows of many applications at once.

Rows are flat: row ``i`` of a group is application ``a[i]``, core row
``r[i]`` of the core group, option ``i`` of the option attributes given
(gathered from :class:`synth.design.space.Space` tables, or built for any part
with its ``*_attributes`` functions). Physics functions never see invalid
placeholders: rows that cannot be evaluated get NaN values, and a NaN margin is
``-inf`` (infeasible), never silently kept.

>>> from synth.data import case_path
>>> from synth.io.documents import load_input
>>> from synth.design.applications import Applications
>>> from synth.design.space import space
>>> apps, sp = Applications.of([load_input(case_path("case3"))]), space()
>>> g = core(apps, np.zeros(sp.n("core"), int), sp.rows("core", np.arange(sp.n("core"))))
>>> sorted(g.margins)[:3], round(float(g.values["hubload_nominal_n"][0]), 1)
(['arm_wall', 'axial_group_matches_split', 'axial_group_not_superfluous'], 462.5)
"""


from __future__ import annotations

import numpy as np

from synth import parts
from synth.design.settings import (DEFAULT, FIDELITIES, FIDELITY_TEXT, SPRING_LIMIT_BASES, UNVERIFIED_NOTE,
                                   Settings)
from synth.design.group import (AXIAL_CORE_VALUES, BOLT_CORE_VALUES, BUSHING_CORE_VALUES, CONSTANT_LIMITS, EVALUATED,
                                NOT_APPLICABLE, NOT_VERIFIED, SPRING_KEY_VALUES, Fields, Group, add_physics,
                                const as _const, core_values, finish, read_core)
from synth.design.axial_group import (CONE_SPRING_VALUES, FIDELITY_VALUES, MADE_CONE_SPRING_COLUMNS,
                                      PLASTIC_WEAR_VALUES, axial, axial_before_physics, axial_before_wear, axial_full,
                                      axial_judged,
                                      fidelity_free, fidelity_free_ok)
from synth.design.spring_group import (SPRING_INPUTS, SPRING_OPTION_COLUMNS, SPRING_TOLERANCE_COLUMNS, spring,
                                       spring_inputs, spring_keys, spring_values)
from synth.design.bolt_group import bolt, bolt_core, bolt_core_checks, fixation_values
from synth.drive.analysis import tensioner_checks
from synth.model import damping, disc_spring, layout, packaging, pivot, plain_bushing

__all__ = ["Settings", "DEFAULT", "core_values", "SPRING_KEY_VALUES", "SPRING_LIMIT_BASES", "SPRING_TOLERANCE_COLUMNS", "MADE_CONE_SPRING_COLUMNS", "Group", "finish", "inputs", "core", "bushing", "axial", "spring", "bolt", "spring_keys",
           "EVALUATED", "NOT_APPLICABLE", "NOT_VERIFIED", "FIDELITIES", "SPRING_INPUTS", "spring_inputs",
           "spring_values", "SPRING_OPTION_COLUMNS", "drive_values", "fixation_values", "bolt_core", "bolt_core_checks", "BUSHING_CORE_VALUES", "AXIAL_CORE_VALUES",
           "BOLT_CORE_VALUES", "axial_judged", "axial_full", "FIDELITY_TEXT", "UNVERIFIED_NOTE", "FIDELITY_VALUES",
           "fidelity_free_ok",
           "CONSTANT_LIMITS", "add_physics", "CONE_SPRING_VALUES", "PLASTIC_WEAR_VALUES", "axial_before_physics", "axial_before_wear",
           "fidelity_free"]  # FIDELITY_FREE: read at call time (__getattr__)


def __getattr__(name):  # FIDELITY_FREE read from the registry as it is now (a check added with register included)
    if name == "FIDELITY_FREE":
        return fidelity_free()
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


# --------------------------------------------------------------------------- step 0: inputs only
def inputs(apps, a, settings: Settings = DEFAULT) -> Group:
    """Group ``input``: layout, pulley axial space, lock-up pin (eq. (17)-(27)) for applications ``a``."""
    f = Fields(apps, a)
    v = {"layout_standard": apps.layout_standard[a], "layout_reverse": apps.layout_reverse[a]}
    w = apps.pulley_width_mm[a]
    mpbh = f["middle_plane_belt_height_mm"]
    v.update(pulley_width_mm=w, pulley_top_mm=mpbh + w / 2.0, pulley_bottom_mm=mpbh - w / 2.0,
             max_axial_displacement_mm=f["max_axial_displacement_mm"],
             min_belt_crankcase_clearance_mm=f["min_belt_crankcase_clearance_mm"],
             pulley_radius_mm=f["pulley_diameter_mm"] / 2.0,
             pin_inner_radius_mm=f["lockup_pin_position_radius_mm"] - f["lockup_pin_diameter_mm"] / 2.0)
    hl = layout.hubload_angle_from_ehr_deg(f["differential_angle_deg"], f["nominal_arm_angle_from_EHR_deg"])
    tp, tm = layout.wrap_limits_deg(hl, f["wrap_angle_deg"])
    with np.errstate(invalid="ignore"):
        c, req = layout.pin_clearance_mm(f["lockup_pin_position_radius_mm"], f["lockup_pin_angular_position_deg"],
                                     f["lockup_pin_diameter_mm"], f["pulley_diameter_mm"], tp, tm)
    v.update(hubload_angle_from_EHR_deg=hl, wrap_upper_limit_deg=tp, wrap_lower_limit_deg=tm, pin_clearance_mm=c,
             pin_clearance_required_mm=req)
    return finish("input", v, apps, a, rules=settings.rules)


# --------------------------------------------------------------------------- steps 1-3, 7: the core
def _table2(p, bearing, working_arm_mm):
    """Thesis Table 2 per row: standard pivot class, max loading arm and the largest working arm of the bearing.

    A working arm between two columns takes the next larger arm's column (the smaller, conservative class);
    beyond the last column the last one is used and the Table 2 constraint fails.
    """
    n = len(bearing)
    cls, la, arm_max = np.full(n, np.nan), np.full(n, np.nan), np.full(n, np.nan)
    for b in np.unique(bearing):
        sel = bearing == b
        arms, classes, max_la = p.table2[int(b)]
        if not len(arms):
            continue
        i = pivot.table2_column(arms, working_arm_mm[sel])[0]
        cls[sel], la[sel], arm_max[sel] = classes[i], max_la[i], arms[-1]
    return cls, la, arm_max


def core(apps, a, c: dict, settings: Settings = DEFAULT, detail: bool = False) -> Group:
    """Group ``core`` (steps 1-3, 7 and the cone-spring annulus of step 8) for applications ``a`` and core rows ``c``.

    ``c`` holds the core table's columns for the rows (:meth:`synth.design.space.Space.rows`).
    ``detail`` adds the characterisation at nominal (hubloads in loading and unloading, asymmetry).
    """
    p = parts.arrays()
    f = Fields(apps, a)
    n = len(a)
    wa, alpha = f["working_arm_mm"], f["differential_angle_deg"]
    b = c["bearing_code"]
    v = {"app": np.asarray(a), "layout_standard": apps.layout_standard[a], "layout_reverse": apps.layout_reverse[a]}
    v["hubload_nominal_n"] = apps.hubload_nominal_n[a]
    lim = p.bearing_max_hubload_n[b, apps.fuel[a]]
    v["bearing_max_hubload_n"] = lim
    std_class, la_max, arm_max = _table2(p, b, wa)
    v.update(working_arm_mm=wa, working_arm_max_table2_mm=arm_max, pivot_class_standard_mm=std_class)
    single = apps.single_eccentric[a]
    la_in = f["loading_arm_mm"]
    v["loading_arm_mm"] = np.where(single, 0.0, np.where(np.isnan(la_in), la_max, la_in))
    v["loading_arm_max_mm"] = la_max
    v["has_loading_arm"] = ~single
    v["loading_arm_defaulted"] = np.isnan(la_in)  # the Table 2 limit itself: met by construction
    for k in ("pivot_class_diameter_mm", "pivot_diameter_mm", "pivot_bushing_radial_thickness_mm",
              "bearing_inner_diameter_mm", "bearing_outer_diameter_mm", "bearing_width_mm",
              "spring_housing_inner_diameter_mm", "damper_pad_max_axial_damping_nm", "damper_pad_contact_area_mm2",
              "damper_pad_mean_radius_mm", "damper_pad_outer_diameter_mm", "damper_pad_axial_height_mm",
              "supplier_code"):
        v[k] = c[k]
    v["arm_wall_mm"] = pivot.arm_wall_mm(c["bearing_inner_diameter_mm"], wa, c["pivot_class_diameter_mm"])
    v["arm_min_wall_mm"] = np.full(n, _const("arm_min_wall_mm"))
    v["pulley_diameter_mm"] = f["pulley_diameter_mm"]
    v["pulley_min_diameter_mm"] = c["bearing_outer_diameter_mm"] + 2.0 * _const("pulley_min_wall_mm")
    mu = apps.mu_pivot_bushing[a]
    v["mu_pivot_bushing"] = mu
    rho = damping.lever_ratio(c["pivot_diameter_mm"], mu, wa, alpha, settings.friction_circle)
    v["lever_ratio"], v["lever_ratio_max"] = rho, np.ones(n)
    target = apps.damping_target_or_zero_nm[a]
    split = damping.damping_split(f["calculated_torque_target_nm"], target, np.minimum(rho, 0.999), apps.axial_allowed[a])
    v.update({k: np.asarray(val, dtype=float) for k, val in split.items()})
    made = apps.derived.get("spring_torque_made_nm")  # a made spring's torque (synth.robust's samples): eq. (12)-(13)
    if made is not None:
        d_ax = np.where(np.asarray(c["axial_group_present"], dtype=bool), v["axial_damping_nm"], 0.0)  # the design's
        t = damping.made_tensioner(made[a], d_ax, np.minimum(rho, 0.999))
        v.update(spring_torque_nominal_nm=np.asarray(made[a], dtype=float), damping_nm=t["damping_nm"],
                 radial_damping_nm=t["radial_damping_nm"],
                 hubload_nominal_n=damping.hubload_nominal_n(t["calculated_torque_nm"], wa, alpha))
    v["damping_upper_nm"] = f["damping_target_nm"] + f["damping_tolerance_nm"]
    v["damping_lower_nm"] = f["damping_target_nm"] - f["damping_tolerance_nm"]
    pad = np.asarray(c["axial_group_present"], dtype=bool)
    v["axial_group_present"] = pad.astype(float)
    v["cone_spring_max_external_diameter_mm"] = np.where(
        pad, disc_spring.cone_spring_max_external_diameter_mm(c["damper_pad_outer_diameter_mm"]), np.nan)
    di = disc_spring.cone_spring_min_internal_diameter_mm(c["pivot_diameter_mm"])
    v["cone_spring_min_internal_diameter_mm"] = di["cone_spring_min_internal_diameter_mm"]
    v["cone_spring_table8_max_mm"] = np.full(n, di["table8_max_mm"])
    mpbh, hmax_p = f["middle_plane_belt_height_mm"], f["max_pivot_height_mm"]
    kw = dict(axial_damping=pad, damper_pad_height_mm=c["damper_pad_axial_height_mm"])
    h_std = packaging.spring_housing_height_mm(mpbh, c["bearing_width_mm"], layout="standard", **kw)
    h_rev = packaging.spring_housing_height_mm(mpbh, c["bearing_width_mm"], layout="reverse", max_pivot_height_mm=hmax_p, **kw)
    v["spring_housing_height_mm"] = np.where(apps.layout_standard[a], h_std, h_rev)
    v["spring_housing_outer_diameter_mm"] = packaging.spring_housing_outer_diameter_mm(c["bearing_outer_diameter_mm"], wa)
    v["spring_cavity_min_height_mm"] = np.full(n, _const("spring_cavity_min_height_mm"))
    v.update(drive_values(settings.drive, v["damping_nm"]))
    if detail:
        ch = damping.characterisation(v["spring_torque_nominal_nm"], f["spring_stiffness_nm_per_deg"],
                                 np.where(v["axial_damping_present"] > 0, v["axial_damping_nm"], 0.0), wa, alpha,
                                 c["pivot_diameter_mm"], mu, np.zeros(n), settings.friction_circle)
        for k in ("hubload_loading_n", "hubload_unloading_n", "asymmetry_ratio"):
            v[k] = np.asarray(ch[k], dtype=float)
    return finish("core", v, apps, a, rules=settings.rules)


def drive_values(drive, damping_nm) -> dict:
    """The values of the registry's drive constraints (``drive_belt_slack``, ``drive_arm_lock``) for rows of
    damping ``damping_nm`` [N m]: with no drive, ``drive_given`` is False (the constraints do not apply)."""
    n = len(damping_nm)
    if drive is None:
        return {"drive_given": np.zeros(n, dtype=bool),
                **{k: np.full(n, np.nan) for k in ("drive_min_span_tension_n", "drive_belt_min_tension_n",
                                                   "drive_static_tension_n", "drive_critical_friction_nm")}}
    t = tensioner_checks(drive, damping_nm)
    return {"drive_given": np.ones(n, dtype=bool), "drive_min_span_tension_n": t["min_span_tension_n"],
            "drive_belt_min_tension_n": np.full(n, t["belt_min_tension_n"]),
            "drive_static_tension_n": np.full(n, t["static_tension_n"]),
            "drive_critical_friction_nm": np.full(n, t["critical_friction_nm"])}


# --------------------------------------------------------------------------- step 4: the pivot bushing
def bushing(apps, cg: Group, r, o: dict, settings: Settings = DEFAULT) -> Group:
    """Group ``bushing`` (step 4) for core rows ``r`` of core group ``cg`` and bushing options ``o``.

    ``o``: ``supplier_code`` and ``pivot_bushing_length_mm`` per row (any length); the option's supplier
    must be the core's (the pivot diameter depends on its wall).
    """
    p = parts.arrays()
    a = cg.values["app"][r]
    f = Fields(apps, a)
    sup, env = np.asarray(o["supplier_code"]), apps.env[a]
    lim = {k: p.bushing_limits[k][sup, env] for k in p.bushing_limits}
    rated = np.isfinite(lim["pvt_max_mpa_m_per_s_h"]) & np.isfinite(lim["k_w_mm3_per_n_m"])
    cv = read_core("bushing", cg, r)
    pad = cv["axial_group_present"] > 0
    res = plain_bushing.evaluate_bushing(cv["hubload_nominal_n"], cv["pivot_diameter_mm"],
                              o["pivot_bushing_length_mm"], apps.theta_pp_deg[a], apps.frequency_hz[a],
                              apps.duration_h[a], k_w_mm3_per_n_m=np.where(rated, lim["k_w_mm3_per_n_m"], 0.0),
                              radial_clearance_mm=p.bushing.radial_clearance_mm[sup],
                              belt_plane_height_mm=f["middle_plane_belt_height_mm"],
                              max_pivot_height_mm=f["max_pivot_height_mm"], axial_damping=pad,
                              pulley_diameter_mm=f["pulley_diameter_mm"],
                              fidelity="full" if settings.bushing_running_in else "screening")
    v = {f"pivot_bushing_{k}": np.asarray(val, dtype=float) for k, val in res.items() if k != "length_max_mm"}
    v.update(app=a, bushing_rated=rated.astype(float), pivot_bushing_length_mm=np.asarray(o["pivot_bushing_length_mm"],
                                                                                         dtype=float),
             pivot_bushing_length_max_mm=np.asarray(res["length_max_mm"], dtype=float),
             pivot_bushing_p_max_mpa=lim["p_max_mpa"], pivot_bushing_pv_max_mpa_m_per_s=lim["pv_max_mpa_m_per_s"],
             pivot_bushing_pvt_max_mpa_m_per_s_h=lim["pvt_max_mpa_m_per_s_h"],
             pivot_bushing_sliding_layer_mm=p.bushing.sliding_layer_depth_mm[sup],
             pulley_max_parallelism_eol_mm=f["pulley_max_parallelism_eol_mm"])
    return finish("bushing", v, apps, a, rules=settings.rules, core=cv)
