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

from dataclasses import dataclass, field

import numpy as np

from synth import catalog, parts
from synth.design.assessment import EVALUATED, NOT_APPLICABLE, NOT_VERIFIED_STATE as NOT_VERIFIED, assess_group
from synth.design.constraints import by_group, margin, physics_inputs
from synth.model import bolted_joint, damping, disc_spring
from synth.model import layout, packaging, pivot, plain_bushing, stackup
from synth.model import torsion_spring
from synth.design.rules import NONE as NO_RULES, Rules
from synth.design.settings import (DEFAULT, FIDELITIES, FIDELITY_TEXT, SPRING_LIMIT_BASES, UNVERIFIED_NOTE,
                                   Settings)
from synth.drive.analysis import tensioner_checks
from synth.kernels import axial as axial_engine  # the cone spring and the wear on the caller's engine

__all__ = ["Settings", "DEFAULT", "core_values", "SPRING_KEY_VALUES", "SPRING_LIMIT_BASES", "SPRING_TOLERANCE_COLUMNS", "MADE_CONE_SPRING_COLUMNS", "Group", "finish", "inputs", "core", "bushing", "axial", "spring", "bolt", "spring_keys",
           "EVALUATED", "NOT_APPLICABLE", "NOT_VERIFIED", "FIDELITIES", "SPRING_INPUTS", "spring_inputs",
           "spring_values", "SPRING_OPTION_COLUMNS", "drive_values", "fixation_values", "bolt_core", "bolt_core_checks", "BUSHING_CORE_VALUES", "AXIAL_CORE_VALUES",
           "BOLT_CORE_VALUES", "axial_judged", "axial_full", "FIDELITY_TEXT", "UNVERIFIED_NOTE", "FIDELITY_VALUES",
           "fidelity_free_ok"]  # FIDELITY_FREE: read at call time (__getattr__)

CONSTANT_LIMITS = {"zero": 0.0, "one": 1.0}  # limits (and scales) that are plain numbers


@dataclass
class Group:
    """Values and registry margins of one group's rows (``(n,)`` arrays).

    ``margins[id]`` is ``+inf`` where the constraint does not apply or is not
    verified (``state`` says which), ``-inf`` where its value is NaN. ``search``: the search model's group
    this one was judged from (:func:`axial_judged`); its margins rank nearest designs (:meth:`rank`). ``rules``:
    the design rules its margins are measured beyond (:meth:`synth.design.rules.Rules.required`).
    """

    name: str
    values: dict
    margins: dict = field(default_factory=dict)
    state: dict = field(default_factory=dict)
    search: "Group | None" = None
    #: the design rules the margins were computed under (:func:`finish`): each check's required margin
    rules: Rules = NO_RULES

    def rank(self) -> "Group":
        """The group whose margins rank nearest designs: the search model's (:attr:`search`), else this one."""
        return self.search if self.search is not None else self

    def __len__(self) -> int:
        return len(next(iter(self.values.values()))) if self.values else 0

    def assessment(self):
        """The :class:`~synth.design.assessment.Assessment` of this group's rows (the one judgement of margins)."""
        return assess_group(self)

    def ok(self) -> np.ndarray:
        """``(n,)`` bool: every (non-advisory) constraint of the group passes."""
        return self.assessment().ok

    def min_margin(self, objective_only: bool = True) -> np.ndarray:
        """``(n,)`` smallest margin of the constraints counted in the margin objective (or all non-advisory)."""
        a = self.assessment()
        return a.objective_margin if objective_only else a.margin_min

    def put(self, rows, other: "Group") -> "Group":
        """A copy whose rows ``rows`` are ``other``'s rows (a group of the same function, ``len(rows)`` rows)."""
        def mix(a: dict, b: dict) -> dict:
            out = {}
            for k, v in a.items():
                if k.startswith("_"):
                    out[k] = v
                    continue
                arr = np.array(v, copy=True)
                arr[rows] = b[k]
                out[k] = arr
            return out
        return Group(self.name, mix(self.values, other.values), mix(self.margins, other.margins),
                     mix(self.state, other.state), rules=self.rules)

    def take(self, idx) -> "Group":
        """The rows ``idx`` as a new group."""
        return Group(self.name, {k: v[idx] for k, v in self.values.items()},
                     {k: v[idx] for k, v in self.margins.items()}, {k: v[idx] for k, v in self.state.items()},
                     rules=self.rules)


def finish(name: str, values: dict, apps, a, checks: tuple | None = None, *, rules: Rules = NO_RULES,
           core: dict | None = None) -> Group:
    """The registry margins of group ``name`` (or of its ``checks`` only) from its ``values`` for rows of
    applications ``a`` (an array of any shape: every value broadcasts to it).

    ``apps`` may be None (a group measured on a built model, the CAD checks): a constraint that needs an input
    is then not verified where its limit is NaN. ``rules`` (the configuration's,
    :attr:`synth.design.settings.Settings.rules`) set the limits they name and the margins checks must keep: the
    margin is then the one beyond the rule's. ``core``: the values of the rows' core the group's checks may read
    (:func:`core_values`), for their physics functions (:func:`add_physics`).
    """
    n = np.shape(a)  # the rows' shape: 1-D, or the bulk engine's 2-D grid of core rows x bolt diameters
    margins, state = {}, {}
    met = {}
    checks = by_group(name) if checks is None else checks
    add_physics(checks, values, apps, a, core)
    for c in checks:
        if c.limit in rules.limits:  # a design rule sets this limit (synth.design.rules)
            values[c.limit] = np.full(n, rules.limits[c.limit])
        lim = CONSTANT_LIMITS[c.limit] if c.limit in CONSTANT_LIMITS else values[c.limit]
        with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
            scale = None if c.scale is None else (CONSTANT_LIMITS[c.scale] if c.scale in CONSTANT_LIMITS
                                                  else values[c.scale])
            m = margin(c, values[c.value], lim, scale)
            kept = rules.required(c.id)
            if kept:  # the margin beyond the rule's (x - 0.0 is x: no copy without a rule)
                m = m - kept
        undefined = np.isnan(m)
        if undefined.any():
            m = np.where(undefined, -np.inf, m)
        own = m.shape == n  # an array of the group's rows, new (the margin's), else a scalar or a broadcast
        m = m if own else np.broadcast_to(m, n)
        st = np.zeros(n, dtype=np.int8)
        if c.applies is not None:
            st[~np.asarray(values[c.applies], dtype=bool)] = NOT_APPLICABLE
        if apps is None:
            if c.needs:
                st[(st == EVALUATED) & np.isnan(np.broadcast_to(np.asarray(lim, dtype=float), n))] = NOT_VERIFIED
        else:
            for req in c.needs:
                if req not in met:
                    met[req] = apps.met(req)[a]
                st[(st == EVALUATED) & ~met[req]] = NOT_VERIFIED
        # every row evaluated (the usual case): the margins as they are, in an array of their own
        margins[c.id] = m if own and not st.any() else np.where(st == EVALUATED, m, np.inf)
        state[c.id] = st
    return Group(name, values, margins, state, rules=rules)


def add_physics(checks, values: dict, apps, a, core: dict | None = None) -> None:
    """The values and limits of the ``checks`` that declare a physics function (:attr:`Constraint.physics`), added
    to ``values`` in place: each parameter is read by its name from the group's values, else from its core's
    (``core``: the rows' core values, :func:`core_values`), else from the applications' fields at rows ``a``; a
    name that is none of them is an error naming the check."""
    for c in checks:
        if c.physics is not None:
            kw = {}
            for k in physics_inputs(c):
                if k in values:
                    kw[k] = values[k]
                elif core is not None and k in core:
                    kw[k] = core[k]
                elif apps is not None and k in apps.f:
                    kw[k] = apps.f[k][a]
                else:
                    raise KeyError(f"constraint {c.id}: its physics function reads {k!r}, which is not a value of "
                                   f"group {c.group}, of its core or a field of the application")
            values.update(c.physics(**kw))


def _const(name: str) -> float:
    return catalog.constant(name)


class _Fields(dict):
    """The applications' numeric fields at rows ``a``, gathered on first access (a group reads a handful of the
    many fields; gathering them all for every row was most of the cost of a large chunk)."""

    def __init__(self, apps, a):
        super().__init__()
        self._f, self._a = apps.f, a

    def __missing__(self, key):
        v = self[key] = self._f[key][self._a]
        return v


#: what the bushing group's function reads of its core row (besides the application): declared beside the function;
#: :func:`core_values` adds what the registry's checks read
BUSHING_CORE_VALUES = ("hubload_nominal_n", "pivot_diameter_mm", "axial_group_present")
#: what the axial group's function reads of its core row (besides the application)
AXIAL_CORE_VALUES = ("axial_damping_nm", "radial_damping_nm",
                     "cone_spring_max_external_diameter_mm", "cone_spring_min_internal_diameter_mm",
                     "cone_spring_table8_max_mm", "damper_pad_mean_radius_mm", "damper_pad_contact_area_mm2",
                     "damper_pad_axial_height_mm", "bearing_width_mm", "axial_group_present",
                     "damper_pad_outer_diameter_mm")
#: what a main spring reads of its core row (besides the application): its key
SPRING_KEY_VALUES = ("spring_torque_nominal_nm", "spring_housing_height_mm", "spring_housing_outer_diameter_mm",
                     "spring_housing_inner_diameter_mm")
#: what the bolt group's function reads of its core row: nothing (step 10 sees the application and the bolt); its
#: checks that read the core (the pivot wall's physics: the pivot diameter and the loading arm) add theirs
#: (:func:`core_values`, :func:`bolt_core_checks`)
BOLT_CORE_VALUES = ()
_DECLARED_CORE_VALUES = {"bushing": BUSHING_CORE_VALUES, "axial": AXIAL_CORE_VALUES, "spring": SPRING_KEY_VALUES,
                         "bolt": BOLT_CORE_VALUES}


def core_values(group: str, core) -> tuple:
    """What group ``group`` reads of its core row: its function's declared inputs (:data:`BUSHING_CORE_VALUES`,
    :data:`AXIAL_CORE_VALUES`, :data:`SPRING_KEY_VALUES`, :data:`BOLT_CORE_VALUES`), then every value of the core
    (``core``: a core group's values, or their names) a registered check of the group reads through its physics
    function's parameters (:func:`~synth.design.constraints.physics_inputs`), registry order.

    Derived from the registry as it is now, never kept by hand: the searches that evaluate a group once per
    distinct value of what it reads of the core (:class:`synth.optimise.batch.Batch`, the platform producer, the
    design space's product) key it on this, and the group functions hand these values to the physics
    (:func:`add_physics`). A check of the axial group whose physics reads ``pivot_diameter_mm`` makes the pivot
    diameter part of the axial group's key, with no other edit.

    >>> core_values("bolt", {"pivot_diameter_mm": 0, "loading_arm_mm": 0, "bearing_width_mm": 0})
    ('pivot_diameter_mm', 'loading_arm_mm')
    """
    out = list(_DECLARED_CORE_VALUES[group])
    for c in by_group(group):
        for k in physics_inputs(c):
            if k in core and k not in out:
                out.append(k)
    return tuple(out)


def _core_rows(group: str, cg: "Group", r) -> dict:
    """The core values group ``group`` reads (:func:`core_values`) at core rows ``r`` of core group ``cg``."""
    return {k: cg.values[k][r] for k in core_values(group, cg.values)}


# --------------------------------------------------------------------------- step 0: inputs only
def inputs(apps, a, settings: Settings = DEFAULT) -> Group:
    """Group ``input``: layout, pulley axial space, lock-up pin (eq. (17)-(27)) for applications ``a``."""
    f = _Fields(apps, a)
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
    f = _Fields(apps, a)
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
    f = _Fields(apps, a)
    sup, env = np.asarray(o["supplier_code"]), apps.env[a]
    lim = {k: p.bushing_limits[k][sup, env] for k in p.bushing_limits}
    rated = np.isfinite(lim["pvt_max_mpa_m_per_s_h"]) & np.isfinite(lim["k_w_mm3_per_n_m"])
    cv = _core_rows("bushing", cg, r)
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


# --------------------------------------------------------------------------- steps 5-8: the axial damping group
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


def _fidelity_free() -> tuple:
    """The registry's (non-advisory) axial constraints that read no :data:`FIDELITY_VALUES` value: the screening
    and the full model give them the same margin (``tests/test_fidelity.py`` checks it)."""
    out = []
    for c in by_group("axial"):
        reads = (c.value, c.limit, c.scale, c.applies, c.objective_unless)
        if not c.advisory and not any(k in FIDELITY_VALUES for k in reads if k):
            out.append(c.id)
    return tuple(out)


def __getattr__(name):  # FIDELITY_FREE read from the registry as it is now (a check added with register included)
    if name == "FIDELITY_FREE":
        return _fidelity_free()
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def axial(apps, cg: Group, r, o: dict, settings: Settings = DEFAULT, time_points: int = 0,
          engine: str | None = None) -> Group:
    """Group ``axial`` (Table 4, belt plane, cone spring, plastic wear) for core rows ``r`` and axial options ``o``.

    ``o``: the axial table's columns (spacer, cone-spring variant). Rows pair a core with a damper pad with
    a real option, or a core without one with the ``none`` option. ``time_points`` keeps the wear history.
    ``engine``: the cone spring's and the wear's (:mod:`synth.kernels.axial`; None: the numpy reference), chosen
    by a search of many rows with :func:`synth.kernels.engines.axial`.
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
    f = _Fields(apps, a)
    cv = _core_rows("axial", cg, r)
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
    checks = tuple(c for c in by_group("axial") if c.physics is None
                   and all(k in v or k in CONSTANT_LIMITS for k in (c.value, c.limit, c.scale, c.applies,
                                                                     c.objective_unless) if k))
    return finish("axial", v, apps, a, checks=checks, rules=settings.rules, core=cv)


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
    return assess_group(g, only=_fidelity_free()).ok  # the registry now, never a list frozen at import


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


# --------------------------------------------------------------------------- step 9: the main spring
def spring_keys(cg: Group, r) -> dict:
    """What a main spring sees of core rows ``r``: application, spring torque, housing height and diameters (and
    any other core value a registered spring check reads, :func:`core_values`)."""
    return {"app": cg.values["app"][r], **_core_rows("spring", cg, r)}


#: the per-row inputs of :func:`spring_values` besides the option (what a main spring sees of its application)
SPRING_INPUTS = ("spring_torque_nominal_nm", "housing_height_mm", "housing_outer_diameter_mm",
                 "housing_inner_diameter_mm", "stiffness_nm_per_deg", "torque_tolerance_pct", "theta_pp_deg",
                 "dtheta_inst_nom_deg", "dtheta_nom_free_arm_deg")


#: the option columns :func:`spring_values` reads (of the space's spring table, or any part's
#: :func:`synth.design.space.spring_attributes`)
SPRING_OPTION_COLUMNS = ("E_mpa", "Rm_mpa", "sigma_y_mpa", "sigma_A0_mpa", "b_mm", "h_mm", "round_wire",
                         "main_spring_mean_body_diameter_mm", "b_tol_mm", "h_tol_mm", "sigma_perm_static_mpa",
                         "supplied_in_section")


#: optional option columns of :func:`spring_values`: the worst-case tolerances of eq. (82)-(88) (default: the
#: constants of ``constants_main_spring.csv``); a production-scatter sample (:mod:`synth.robust`) gives 0, or a
#: signed deviation of the housing, per row
SPRING_TOLERANCE_COLUMNS = ("mbd_tol_mm", "housing_outer_tol_mm", "housing_inner_tol_mm")


def spring_inputs(apps, keys: dict, k) -> dict:
    """The :data:`SPRING_INPUTS` of rows ``k`` of ``keys`` (:func:`spring_keys`): the key's torque (at least
    1e-6 N m), housing height and diameters, and its application's stiffness, torque tolerance, theta_pp (0 without
    a durability test: no oscillation, the fatigue check is then not verified) and travels (documented defaults)."""
    a = keys["app"][k]
    f = apps.f
    return {"spring_torque_nominal_nm": np.maximum(keys["spring_torque_nominal_nm"][k], 1e-6),
            "housing_height_mm": keys["spring_housing_height_mm"][k],
            "housing_outer_diameter_mm": keys["spring_housing_outer_diameter_mm"][k],
            "housing_inner_diameter_mm": keys["spring_housing_inner_diameter_mm"][k],
            "stiffness_nm_per_deg": f["spring_stiffness_nm_per_deg"][a],
            "torque_tolerance_pct": f["spring_torque_tolerance_pct"][a],
            "theta_pp_deg": np.nan_to_num(apps.theta_pp_deg[a], nan=0.0),
            "dtheta_inst_nom_deg": f["arm_travel_nominal_to_installation_deg"][a],
            "dtheta_nom_free_arm_deg": f["arm_travel_nominal_to_free_deg"][a]}


def spring_values(o: dict, x: dict, settings: Settings = DEFAULT) -> dict:
    """The values of group ``spring`` (step 9, eq. (64)-(93)) for options ``o`` (the spring table's columns) and
    per-row inputs ``x`` (:data:`SPRING_INPUTS`, :func:`spring_inputs`), all broadcast to one length.

    The one mapping from the physics (:func:`synth.model.torsion_spring.main_spring_design`) to the values the
    registry's spring constraints compare: :func:`spring` adds the application and the registry margins, the
    compiled kernels (:mod:`synth.kernels.main_spring`) use it as their numpy reference.
    """
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        r = torsion_spring.main_spring_design(
            E_mpa=o["E_mpa"], Rm_mpa=o["Rm_mpa"], sigma_y_mpa=o["sigma_y_mpa"], sigma_A0_mpa=o["sigma_A0_mpa"],
            b_mm=o["b_mm"], h_mm=o["h_mm"], round_wire=o["round_wire"], mbd_mm=o["main_spring_mean_body_diameter_mm"],
            stiffness_nm_per_deg=x["stiffness_nm_per_deg"], spring_torque_nominal_nm=x["spring_torque_nominal_nm"],
            torque_tolerance_pct=x["torque_tolerance_pct"], theta_pp_deg=x["theta_pp_deg"],
            housing_height_mm=x["housing_height_mm"], housing_outer_diameter_mm=x["housing_outer_diameter_mm"],
            housing_inner_diameter_mm=x["housing_inner_diameter_mm"], b_tol_mm=o["b_tol_mm"], h_tol_mm=o["h_tol_mm"],
            dtheta_inst_nom_deg=x["dtheta_inst_nom_deg"], dtheta_nom_free_arm_deg=x["dtheta_nom_free_arm_deg"],
            sigma_perm_static_mpa=o["sigma_perm_static_mpa"], **{k: o[k] for k in SPRING_TOLERANCE_COLUMNS if k in o})
    shape = np.broadcast(r["main_spring_active_coils_free"], np.asarray(x["stiffness_nm_per_deg"])).shape
    v = {}
    for key in ("main_spring_active_coils_free", "main_spring_sigma_a_max_mpa", "main_spring_sigma_a_min_mpa",
                "main_spring_sigma_inst_mpa", "main_spring_safety_factor", "hooks_angle_free_state_deg",
                "hooks_angle_nominal_deg", "spring_index", "curvature_factor", "theta_nom_deg", "theta_inst_deg",
                "theta_free_arm_deg", "torque_inst_nm", "block_length_max_mm", "main_spring_sigma_inst_uncorrected_mpa",
                "sigma_perm_static_limit_mpa"):
        v[key] = np.broadcast_to(np.asarray(r[key], dtype=float), shape)
    v["main_spring_index"] = v.pop("spring_index")

    def full(x_):
        return np.broadcast_to(np.asarray(x_, dtype=float), shape)
    # the deciding limit of the installation stress: the design rule of settings.spring_limit_basis
    limit = r["sigma_y_limit_mpa"] if settings.spring_limit_basis == "thesis" else \
        np.asarray(r["sigma_perm_static_limit_mpa"]) * np.asarray(r["curvature_factor"])
    v.update(main_spring_sigma_permissible_mpa=full(limit),
             main_spring_min_safety_factor=np.full(shape, _const("main_spring_min_safety_factor")),
             main_spring_outer_diameter_max_mm=full(r["outer_diameter_max_mm"]),
             spring_housing_outer_diameter_min_mm=full(r["housing_outer_diameter_min_mm"]),
             main_spring_inner_diameter_min_mm=full(r["inner_diameter_min_mm"]),
             spring_housing_inner_diameter_max_mm=full(r["housing_inner_diameter_max_mm"]),
             main_spring_coil_gap_worst_mm=full(r["coil_gap_worst_mm"]),
             main_spring_min_coil_gap_mm=np.full(shape, _const("main_spring_min_coil_gap_mm")),
             main_spring_wire_b_mm=full(o["b_mm"]),
             main_spring_index_min=np.full(shape, _const("main_spring_index_min")),
             main_spring_index_max=np.full(shape, _const("main_spring_index_max")),
             main_spring_mean_body_diameter_mm=full(o["main_spring_mean_body_diameter_mm"]),
             main_spring_supplied_in_section=full(o["supplied_in_section"]))
    v["main_spring_wire_length_m"] = (np.pi * v["main_spring_mean_body_diameter_mm"]
                                      * v["main_spring_active_coils_free"] / 1000.0)
    return v


def spring(apps, keys: dict, k, o: dict, settings: Settings = DEFAULT, inputs: dict | None = None) -> Group:
    """Group ``spring`` (step 9) for rows pairing key ``k[i]`` of ``keys`` (:func:`spring_keys`) with option ``o``.

    ``inputs`` (optional): per-row values replacing some of :func:`spring_inputs` (a made spring's stiffness in
    a production-scatter sample, :mod:`synth.robust`)."""
    a = keys["app"][k]
    x = spring_inputs(apps, keys, k)
    if inputs:
        x.update(inputs)
    v = {"app": a, **spring_values(o, x, settings)}
    core = {c: np.asarray(keys[c])[k] for c in keys if c != "app" and c not in SPRING_KEY_VALUES}
    return finish("spring", v, apps, a, rules=settings.rules, core=core)


# --------------------------------------------------------------------------- step 10 and the pivot wall
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
    for h, w, m in dict.fromkeys(zip(head.tolist(), washer.tolist(), method.tolist())):
        for g in (False, True):
            sel = np.flatnonzero((head == h) & (washer == w) & (method == m) & (given == g))
            if not len(sel):
                continue
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
            for k in _BOLT_VALUES:
                if k in r:
                    out[k][rows[sel]] = np.broadcast_to(np.asarray(r[k], dtype=float), (len(ua), len(pairs)))[ia, ib]
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
    f = _Fields(apps, a)
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
    return finish("bolt", v, apps, a, rules=settings.rules, core=_core_rows("bolt", cg, r))
