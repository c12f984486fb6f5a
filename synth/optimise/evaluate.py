"""Vectorised evaluation of a design space: normalised margins of every constraint.

Every margin comes from the same :mod:`synth.model` functions the flowchart
uses (one source of truth); this module only arranges their inputs on arrays
of shape ``(n_cores,)`` (core constraints) or ``(n_cores, n_options)``
(subsystem constraints) and never re-implements a formula.

A margin ``>= 0`` passes (:mod:`synth.checks`). Margins a physics function
returns as NaN (it should not) are turned into ``-inf`` (infeasible), never
silently kept. Constraints a scene does not need are not evaluated: no axial
damping means no cone spring, plastic wear or Table 3/4 capacity; a missing
durability test skips step 4 and step 5; missing fixation data skip step 10.

>>> from synth.schema import load_input

>>> from synth.data import case_path
>>> from synth.optimise.space import build_space
>>> ev = evaluate(build_space(load_input(case_path("case1"))))
>>> "self_locking" in ev.core_margins, ev.subs["spring"].margins.shape[2] >= 5
(True, True)
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import pandas as pd

from synth import catalog
from synth.checks import margin_lower, margin_upper
from synth.model import layout as s0, pivot as s2, damping as s3
from synth.model import plain_bushing as s4, friction_wear as s5, stackup as s6
from synth.model import packaging as s7, disc_spring as s8, torsion_spring as s9
from synth.model import bolted_joint as s10
from synth.optimise.space import NONE, SUBSYSTEMS, DesignSpace

__all__ = ["CONSTRAINTS", "SubEval", "Evaluation", "evaluate", "FEAS_TOL", "spring_keys", "spring_margins", "bolt_fixation"]

FEAS_TOL = 1e-9

#: name -> (step, label, equation, counts in the margin objective)
CONSTRAINTS = {
    # input only (step 0)
    "axial_displacement": (0, "pulley within the axial space", "eq. (26)-(27)", True),
    "pin_within_pulley": (0, "lock-up pin within pulley outline", "eq. (22)", True),
    "pin_clearance": (0, "lock-up pin clearance to pulley and belt", "eq. (23)-(25)", True),
    # core
    "bearing_load": (1, "hubload within the bearing's Table 1 range", "Table 1", True),
    "loading_arm": (2, "loading arm within Table 2", "Table 2", True),
    "arm_wall": (2, "arm wall on the eccentric side", "step 2", True),
    "self_locking": (3, "arm free to move (no self-locking)", "eq. (12)", True),
    "damping_upper": (3, "damping within upper tolerance", "eq. (10)-(11)", True),
    "damping_lower": (3, "damping within lower tolerance", "eq. (9)-(11)", True),
    "spring_torque_positive": (3, "spring torque positive", "eq. (12)-(13)", True),
    "damper_pad_capacity": (3, "damper pad class carries the axial damping", "Table 3", True),
    "cone_spring_annulus": (8, "cone spring OD (pad) above its ID (pivot)", "Table 8, step 8", True),
    "spring_cavity": (7, "spring cavity height", "eq. (52)-(53)", True),
    # bushing
    "bushing_p": (4, "pivot bushing pressure", "eq. (28), Table 5", True),
    "bushing_pv": (4, "pivot bushing p*v", "eq. (30), Table 5", True),
    "bushing_pvt": (4, "pivot bushing p*v*t", "eq. (31), Table 5", True),
    "bushing_wear": (4, "bushing end wear vs sliding layer", "eq. (32), (40)-(41)", True),
    "bushing_parallelism": (4, "pulley parallelism at end of life", "eq. (42)", True),
    "bushing_length": (4, "bushing length fits the pivot", "eq. (33)-(34)", True),
    # axial group
    "endcap_spacer_capacity": (3, "endcap spacer class carries the axial damping", "Table 4", True),
    "belt_plane": (7, "belt plane within the pivot stack", "eq. (50)-(51)", True),
    "cone_force_band": (8, "cone spring force band over the gap tolerance", "eq. (9), Fig. 68", True),
    "cone_diameter_ratio": (8, "cone spring De/Di within Table 7", "eq. (55), Table 7", True),
    "cone_aspect_ratio": (8, "cone spring h0/t within Table 7", "eq. (56), Table 7", True),
    "cone_thinness": (8, "cone spring De/t within Table 7", "eq. (57), Table 7", True),
    "cone_not_flattened": (8, "cone spring not flattened at max deflection", "eq. (58)-(60)", True),
    "cone_sigma_om": (8, "cone spring stress sigma_OM", "eq. (61)-(63)", True),
    "cone_table8_range": (8, "cone spring ID within Table 8", "Table 8", True),
    "damping_eol": (5, "damping at end of life", "eq. (43)-(49)", True),
    "damper_pad_wear": (5, "damper pad wear", "eq. (43)-(45)", True),
    "endcap_spacer_wear": (5, "endcap spacer wear", "eq. (43)-(45)", True),
    # main spring
    "spring_yield": (9, "main spring yield at installation", "eq. (72)-(77)", True),
    "spring_fatigue": (9, "main spring Smith-Goodman safety factor", "figure 71", True),
    "spring_outer_contact": (9, "main spring outer contact with housing", "eq. (81)-(84)", True),
    "spring_inner_contact": (9, "main spring inner contact with support", "eq. (85)-(88)", True),
    "spring_coil_gap": (9, "main spring coil gap", "eq. (89)-(93)", True),
    "spring_index_min": (9, "main spring index >= min", "EN 13906-3", True),
    "spring_index_max": (9, "main spring index <= max", "EN 13906-3", True),
    # bolt (the preload is sized for the tilting and sliding targets: those margins are 0 by construction)
    "tilting": (10, "tilting safety factor", "eq. (94)-(97)", False),
    "sliding": (10, "sliding safety factor", "eq. (98)-(99)", False),
    "bolt_yield": (10, "bolt von Mises stress", "eq. (103)-(107)", True),
    "under_head": (10, "under-head stress", "eq. (108)-(109)", True),
    "thread": (10, "thread bearing stress", "eq. (110)-(111)", True),
    "pivot_bore": (10, "pivot bore for the bolt", "step 2 / section 10", True),
    "pivot_base_pressure": (10, "pivot base max contact pressure", "eq. (96), Fig. 74", True),
    "pivot_wall": (2, "pivot wall around the bolt hole", "step 2", True),
}

_SPRING_KEYS = {f"margin_main_spring_{k}": f"spring_{k}" for k in
                ("yield", "fatigue", "outer_contact", "inner_contact", "coil_gap", "index_min", "index_max")}
_CONE_KEYS = {"force_band": "cone_force_band", "diameter_ratio": "cone_diameter_ratio", "aspect_ratio": "cone_aspect_ratio",
              "thinness": "cone_thinness", "not_flattened": "cone_not_flattened", "sigma_om": "cone_sigma_om",
              "table8_range": "cone_table8_range"}
_BOLT_KEYS = {"margin_tilting": "tilting", "margin_sliding": "sliding", "margin_bolt_yield": "bolt_yield",
              "margin_under_head": "under_head", "margin_thread": "thread", "margin_pivot_bore": "pivot_bore",
              "margin_pivot_base_pressure": "pivot_base_pressure"}
_FIX_FIELDS = ("tilting_safety_factor", "sliding_safety_factor", "engine_support_internal_diameter_mm",
               "engine_support_external_diameter_mm", "contact_angle_deg", "support_yield_strength_compression_mpa",
               "support_yield_strength_traction_mpa", "number_of_active_threads")


def _clean(m) -> np.ndarray:
    m = np.asarray(m, dtype=float)
    return np.where(np.isnan(m), -np.inf, m)


@dataclass
class SubEval:
    """Margins of one subsystem: ``margins[c, k, j]`` for constraint ``names[j]``."""

    names: list
    margins: np.ndarray
    available: np.ndarray
    values: dict = field(default_factory=dict)

    def feasible(self) -> np.ndarray:
        ok = self.available.copy()
        if self.margins.shape[2]:
            ok &= np.all(self.margins >= -FEAS_TOL, axis=2)
        return ok

    def objective_margin(self) -> np.ndarray:
        cols = [j for j, n in enumerate(self.names) if CONSTRAINTS[n][3]]
        if not cols:
            return np.full(self.available.shape, np.inf)
        return np.min(self.margins[:, :, cols], axis=2)

    def min_margin(self) -> np.ndarray:
        if not self.margins.shape[2]:
            return np.full(self.available.shape, np.inf)
        return np.min(self.margins, axis=2)


@dataclass
class Evaluation:
    """Margins of a whole space: the core constraints and one :class:`SubEval` per subsystem."""

    space: DesignSpace
    core_names: list
    core_margin_array: np.ndarray  # (n_c, n_con)
    core_available: np.ndarray
    core_values: dict
    subs: dict
    notes: list
    evaluations: int = 0  # physics evaluations (core + subsystem entries)
    rows: np.ndarray = None  # the cores (indices into ``space.cores``) the subsystems were evaluated for

    @property
    def core_margins(self) -> dict:
        return {n: self.core_margin_array[:, j] for j, n in enumerate(self.core_names)}

    def core_feasible(self) -> np.ndarray:
        ok = self.core_available.copy()
        if self.core_margin_array.shape[1]:
            ok &= np.all(self.core_margin_array >= -FEAS_TOL, axis=1)
        return ok

    def core_objective_margin(self) -> np.ndarray:
        m = self.core_margin_array.copy()
        # the damping split meets the target by construction when the axial group is present
        ax = np.asarray(self.core_values["axial_damping_present"], bool)
        for j, n in enumerate(self.core_names):
            if n in ("damping_upper", "damping_lower"):
                m[ax, j] = np.inf
        cols = [j for j, n in enumerate(self.core_names) if CONSTRAINTS[n][3]]
        return np.min(m[:, cols], axis=1) if cols else np.full(len(m), np.inf)


def _stack(d: dict, shape) -> tuple[list, np.ndarray]:
    names = list(d)
    if not names:
        return [], np.zeros(shape + (0,))
    return names, np.stack([np.broadcast_to(_clean(d[n]), shape) for n in names], axis=-1)


def _fixed_margins(sp: DesignSpace) -> dict:
    d, f = sp.inputs, sp.fixed
    out = {"axial_displacement": s0.axial_displacement_margin(d.middle_plane_belt_height_mm, f["pulley_width_mm"],
                                                              d.max_axial_displacement_mm, f["layout"] == "standard")}
    if d.missing("lockup_pin_position_radius_mm", "lockup_pin_angular_position_deg", "lockup_pin_diameter_mm"):
        return out
    out["pin_within_pulley"] = s0.pin_within_pulley_margin(d.lockup_pin_position_radius_mm, d.lockup_pin_diameter_mm,
                                                           d.pulley_diameter_mm)
    if not d.missing("wrap_angle_deg", "nominal_arm_angle_from_EHR_deg"):
        hl = s0.hubload_angle_from_ehr_deg(d.differential_angle_deg, d.nominal_arm_angle_from_EHR_deg)
        tp, tm = s0.wrap_limits_deg(hl, d.wrap_angle_deg)
        out["pin_clearance"] = s0.pin_clearance_margin(d.lockup_pin_position_radius_mm, d.lockup_pin_angular_position_deg,
                                                       d.lockup_pin_diameter_mm, d.pulley_diameter_mm, tp, tm)
    return out


def _core(sp: DesignSpace):
    d, f, c = sp.inputs, sp.fixed, sp.cores
    n = len(c)
    col = {k: c[k].to_numpy() for k in c.columns}
    m = {k: np.full(n, float(v)) for k, v in _fixed_margins(sp).items()}
    v: dict = {}
    lim = col["bearing_max_hubload_n"].astype(float)
    finite = np.isfinite(lim)  # the last Table 1 row has no upper bound
    m["bearing_load"] = np.where(finite, margin_upper(f["hubload_nominal_n"], np.where(finite, lim, 1.0)), np.inf)
    if d.belt_loading_type == "single_eccentric":
        la = np.zeros(n)
    else:
        la = col["table2_max_loading_arm_mm"] if d.loading_arm_mm is None else np.full(n, float(d.loading_arm_mm))
        m["loading_arm"] = margin_upper(la, col["table2_max_loading_arm_mm"])
    v["loading_arm_mm"] = la
    m["arm_wall"] = s2.arm_wall_margin(col["bearing_d_mm"], d.working_arm_mm, col["pivot_class_mm"])
    rho = s3.lever_ratio(col["pivot_diameter_mm"], f["mu_pivot_bushing"], d.working_arm_mm, d.differential_angle_deg,
                         sp.friction_circle)
    m["self_locking"] = s3.self_locking_margin(rho)
    split = s3.damping_split(d.calculated_torque_target_nm, f["damping_target_nm"], np.minimum(rho, 0.999),
                             f["axial_allowed"])
    v.update({k: np.asarray(split[k]) for k in split})
    v["lever_ratio"] = rho
    present = np.asarray(split["axial_damping_present"], bool)
    if d.damping_target_nm is not None and d.damping_tolerance_nm is not None:
        m["damping_upper"] = margin_upper(split["damping_nm"], d.damping_target_nm + d.damping_tolerance_nm)
        m["damping_lower"] = margin_lower(split["damping_nm"], d.damping_target_nm - d.damping_tolerance_nm)
    m["spring_torque_positive"] = margin_lower(split["spring_torque_nominal_nm"], 0.0)
    has_dp = col["damper_pad"] != NONE
    available = has_dp == present
    if f["axial_allowed"] and has_dp.any():
        # each element carries half the axial damping (two friction faces, F mu R_i), as the flowchart's step 5
        share = np.asarray(split["axial_damping_nm"]) / 2.0
        m["damper_pad_capacity"] = np.where(has_dp, margin_upper(share, np.where(has_dp, col["dp_max_axial_damping_nm"], 1.0)), np.inf)
        de = s8.cone_spring_max_external_diameter_mm(col["dp_outer_diameter_mm"])
        di = s8.cone_spring_min_internal_diameter_mm(col["pivot_diameter_mm"])["cone_spring_min_internal_diameter_mm"]
        m["cone_spring_annulus"] = np.where(has_dp, margin_lower(de, di), np.inf)
        v["cone_spring_de_mm"], v["cone_spring_di_mm"] = np.broadcast_to(de, n), np.broadcast_to(di, n)
    pk = s7.packaging(d.middle_plane_belt_height_mm, d.max_pivot_height_mm, d.max_axial_displacement_mm,
                      col["bearing_B_mm"], col["bearing_D_mm"], d.working_arm_mm, f["pulley_width_mm"],
                      layout=f["layout"], axial_damping=present, endcap_spacer_height_mm=0.0,
                      damper_pad_height_mm=col["dp_height_mm"])
    m["spring_cavity"] = pk["margin_spring_cavity"]
    v["spring_housing_height_mm"] = np.asarray(pk["spring_housing_height_mm"], float)
    v["spring_housing_outer_diameter_mm"] = np.asarray(pk["spring_housing_outer_diameter_mm"], float)
    v["spring_housing_inner_diameter_mm"] = np.asarray(s7.spring_housing_inner_diameter_mm(col["pivot_class_mm"]), float)
    v["hubload_nominal_n"] = np.full(n, f["hubload_nominal_n"])
    names, arr = _stack(m, (n,))
    return names, arr, available, v


def _bushing(sp: DesignSpace, cv: dict, rows: np.ndarray, keep_values: bool) -> SubEval:
    d, f = sp.inputs, sp.fixed
    c, t = sp.cores.iloc[rows], sp.subsystems["bushing"]
    nc, nk = len(c), len(t)
    avail = c["supplier"].to_numpy()[:, None] == t["supplier"].to_numpy()[None, :]
    dur = f["durability"]
    if dur is None:
        return SubEval([], np.zeros((nc, nk, 0)), avail)
    par = d.pulley_max_parallelism_eol_mm
    names = ["bushing_p", "bushing_pv", "bushing_pvt", "bushing_wear", "bushing_length"] + (["bushing_parallelism"] if par else [])
    out = np.full((nc, nk, len(names)), -np.inf)
    values: dict = {}
    for s in t["supplier"].unique():
        ci = np.flatnonzero(c["supplier"].to_numpy() == s)
        ki = np.flatnonzero(t["supplier"].to_numpy() == s)
        if not len(ci):
            continue
        try:
            r = s4.evaluate_bushing(f["hubload_nominal_n"], c["pivot_diameter_mm"].to_numpy()[ci, None],
                                    t["bushing_length_mm"].to_numpy()[None, ki], *dur, supplier=s,
                                    environment=d.application_type, belt_plane_height_mm=d.middle_plane_belt_height_mm,
                                    max_pivot_height_mm=d.max_pivot_height_mm,
                                    axial_damping=cv["axial_damping_present"][rows][ci, None],
                                    pulley_diameter_mm=d.pulley_diameter_mm, parallelism_max_mm=par or 1e9)
        except Exception as exc:  # supplier not rated for the environment (Table 5 "NA")
            from synth.errors import InputError
            if not isinstance(exc, InputError):
                raise
            avail[np.ix_(ci, ki)] = False
            continue
        keys = ["margin_p", "margin_pv", "margin_pvt", "margin_wear", "margin_length"] + (["margin_parallelism"] if par else [])
        out[np.ix_(ci, ki)] = np.stack([_clean(r[k]) for k in keys], axis=-1)
        if keep_values:
            for k in ("p_mpa", "v_m_per_s", "pv_mpa_m_per_s", "pvt_mpa_m_per_s_h", "wear_max_mm", "parallelism_mm"):
                values.setdefault(f"pivot_bushing_{k}", np.full((nc, nk), np.nan))[np.ix_(ci, ki)] = r[k]
    return SubEval(names, out, avail, values)


def _axial(sp: DesignSpace, cv: dict, rows: np.ndarray, keep_values: bool) -> SubEval:
    d, f = sp.inputs, sp.fixed
    c, t = sp.cores.iloc[rows], sp.subsystems["axial"]
    nc, nk = len(c), len(t)
    has_dp = (c["damper_pad"].to_numpy() != NONE)[:, None]
    real = (t["endcap_spacer"].to_numpy() != NONE)[None, :]
    avail = has_dp == real
    m: dict = {}
    values: dict = {}
    es_h = t["es_height_mm"].to_numpy()[None, :]
    pk = s7.packaging(d.middle_plane_belt_height_mm, d.max_pivot_height_mm, d.max_axial_displacement_mm,
                      c["bearing_B_mm"].to_numpy()[:, None], c["bearing_D_mm"].to_numpy()[:, None], d.working_arm_mm,
                      f["pulley_width_mm"], layout=f["layout"], axial_damping=has_dp, endcap_spacer_height_mm=es_h,
                      damper_pad_height_mm=c["dp_height_mm"].to_numpy()[:, None])
    m["belt_plane"] = pk["margin_belt_plane"]
    shape = (nc, nk)
    todo = has_dp & real
    if todo.any():
        # evaluate every (core, option) pair; pairs that cannot exist get safe placeholders and stay unavailable
        ok = todo & (cv["cone_spring_annulus_ok"][rows] & (cv["axial_damping_nm"][rows] > 0))[:, None]
        d_ax = np.where(ok, cv["axial_damping_nm"][rows][:, None], 1.0)
        d_rad = cv["radial_damping_nm"][rows][:, None] + 0.0 * d_ax
        dp = {k: np.where(ok, c[k].to_numpy()[:, None], ref) for k, ref in
              (("dp_mean_radius_mm", 12.5), ("dp_outer_diameter_mm", 31.5), ("dp_contact_area_mm2", 460.0), ("dp_height_mm", 3.5))}
        piv = np.where(ok, c["pivot_diameter_mm"].to_numpy()[:, None], 16.0)
        es = {k: np.where(ok, t[k].to_numpy()[None, :], ref) for k, ref in
              (("es_mean_radius_mm", 13.5), ("es_contact_area_mm2", 490.0), ("es_height_mm", 1.5), ("cone_aspect_ratio", 1.2))}
        mat = s5.plastic_material("PPA_CF10_AR10_PTFE", d.application_type)
        mu_pl = float(mat["plastic_friction_coefficient"])
        tol = d.damping_tolerance_nm
        m["endcap_spacer_capacity"] = np.where(real, margin_upper(d_ax / 2.0, np.where(real, t["es_max_axial_damping_nm"].to_numpy()[None, :], 1.0)), np.inf)
        cs = s8.cone_spring(d_ax, f["damping_target_nm"], 0.0 if tol is None else tol, d_rad, mu_pl,
                            dp["dp_mean_radius_mm"], es["es_mean_radius_mm"], dp["dp_outer_diameter_mm"], piv,
                            s6.gap_tolerance_mm(), aspect_ratio=es["cone_aspect_ratio"], fidelity="full")
        for k, name in _CONE_KEYS.items():
            if k == "force_band" and tol is None:
                continue
            m[name] = cs["margins"][k]
        dur = f["durability"]
        if dur is not None:
            eol = d.damping_eol_limit_nm
            pw = s5.plastic_wear(cs["cone_spring_nominal_deflection_mm"], cs["cone_spring_max_external_diameter_mm"],
                                 cs["cone_spring_min_internal_diameter_mm"], cs["cone_spring_thickness_mm"],
                                 cs["cone_spring_cone_height_mm"], dp["dp_contact_area_mm2"], dp["dp_mean_radius_mm"],
                                 dp["dp_height_mm"], es["es_contact_area_mm2"], es["es_mean_radius_mm"], es["es_height_mm"],
                                 *dur, d_rad, 0.0 if eol is None else eol, application_type=d.application_type,
                                 fidelity=sp.fidelity)
            for k in ("damping_eol", "damper_pad_wear", "endcap_spacer_wear"):
                if k == "damping_eol" and eol is None:
                    continue
                m[k] = pw["margins"][k]
            if keep_values:
                values.update({k: pw[k] for k in ("plastic_wear_total_mm", "cone_spring_force_eol_n", "damping_eol_nm",
                                                   "axial_damping_eol_nm")})
        avail &= ~todo | ok
        for k in list(m):
            if k != "belt_plane":
                m[k] = np.where(todo, np.broadcast_to(_clean(m[k]), shape), np.inf)
        if keep_values:
            values.update({k: cs[k] for k in cs if k != "margins"})
    names, arr = _stack(m, shape)
    return SubEval(names, arr, avail, values)


def spring_keys(cv: dict, rows: np.ndarray) -> np.ndarray:
    """``(n, 4)`` array of what a main spring sees of each core of ``rows``: spring torque, housing height,
    housing outer and inner diameter (springs are evaluated once per distinct key)."""
    return np.stack([cv["spring_torque_nominal_nm"][rows], cv["spring_housing_height_mm"][rows],
                     cv["spring_housing_outer_diameter_mm"][rows], cv["spring_housing_inner_diameter_mm"][rows]], axis=1)


def spring_margins(sp: DesignSpace, uniq: np.ndarray, options: np.ndarray | None = None, keep_values: bool = False):
    """Margins ``(n_keys, n_options, n_constraints)`` of the main springs ``options`` (row indices of the
    spring table, all by default) for the spring keys ``uniq`` (:func:`spring_keys`), and their values."""
    d, f = sp.inputs, sp.fixed
    t = sp.subsystems["spring"]
    cols = {k: t[k].to_numpy() for k in ("spring_material", "b_mm", "h_mm", "round_wire", "b_tol_mm", "h_tol_mm",
                                         "spring_mbd_mm")}
    if options is not None:
        cols = {k: v[options] for k, v in cols.items()}
    nu, nk = len(uniq), len(cols["b_mm"])
    theta_pp = f["durability"][0] if f["durability"] else 0.0
    tol_pct = d.spring_torque_tolerance_pct or 0.0
    names = list(_SPRING_KEYS.values())
    out = np.full((nu, nk, len(names)), -np.inf)
    values: dict = {}
    mats = cols["spring_material"]
    for mat in pd.unique(mats):
        ki = np.flatnonzero(mats == mat)
        w = {k: cols[k][ki][None, :] for k in ("b_mm", "h_mm", "round_wire", "b_tol_mm", "h_tol_mm", "spring_mbd_mm")}
        p = s9.material_properties(mat, w["b_mm"], w["h_mm"], w["round_wire"])
        r = s9.main_spring_design(E_mpa=p["E_mpa"], Rm_mpa=p["Rm_mpa"], sigma_y_mpa=p["sigma_y_mpa"],
                                  sigma_A0_mpa=p["sigma_A0_mpa"], b_mm=w["b_mm"], h_mm=w["h_mm"],
                                  round_wire=w["round_wire"], mbd_mm=w["spring_mbd_mm"],
                                  stiffness_nm_per_deg=d.spring_stiffness_nm_per_deg,
                                  spring_torque_nominal_nm=np.maximum(uniq[:, 0:1], 1e-6), torque_tolerance_pct=tol_pct,
                                  theta_pp_deg=theta_pp, housing_height_mm=uniq[:, 1:2],
                                  housing_outer_diameter_mm=uniq[:, 2:3], housing_inner_diameter_mm=uniq[:, 3:4],
                                  b_tol_mm=w["b_tol_mm"], h_tol_mm=w["h_tol_mm"])
        out[:, ki, :] = np.stack([np.broadcast_to(_clean(r[k]), (nu, len(ki))) for k in _SPRING_KEYS], axis=-1)
        if keep_values:
            for k in ("main_spring_active_coils_free", "main_spring_sigma_a_max_mpa", "main_spring_sigma_a_min_mpa",
                      "main_spring_sigma_inst_mpa", "main_spring_safety_factor", "hooks_angle_free_state_deg",
                      "hooks_angle_nominal_deg", "coil_gap_min_mm", "outer_diameter_max_mm", "inner_diameter_min_mm"):
                values.setdefault(k, np.full((nu, nk), np.nan))[:, ki] = r[k]
    return names, out, values


def _spring(sp: DesignSpace, cv: dict, rows: np.ndarray, keep_values: bool) -> SubEval:
    uniq, inv = np.unique(spring_keys(cv, rows), axis=0, return_inverse=True)  # springs see the core only through these
    inv = np.asarray(inv).reshape(-1)
    names, out, values = spring_margins(sp, uniq, None, keep_values)
    avail = np.ones((len(rows), len(sp.subsystems["spring"])), bool)
    return SubEval(names, out[inv], avail, {k: v[inv] for k, v in values.items()})


_BOLT_VALUES = ("bolt_tightening_torque_nm", "bolt_axial_force_n", "bolt_sigma_eqv_mpa", "bolt_under_head_stress_mpa",
                "bolt_thread_stress_mpa", "tilting_safety_factor", "sliding_safety_factor",
                "average_contact_pressure_mpa", "pivot_base_contact_surface_mm2")


def bolt_fixation(d, hubload_n, bolt_format: str, bolt_property_class: str) -> dict:
    """Step 10 (:func:`synth.model.bolted_joint.fixation`) for one bolt row: ``{key: value}`` of the bolt
    margins and values the optimiser keeps. ``d``'s numeric fields and ``hubload_n`` may be arrays over
    applications (then every value is an array, element by element the same as one call per application).

    Precomputed results can be passed to :func:`evaluate` in ``space.fixed["bolt_fixation"]`` as
    ``{(format, class): this dict}``.
    """
    inc = d.middle_plane_belt_height_increment_worst_mm
    r = s10.fixation(hubload_n, d.middle_plane_belt_height_mm, 0.0 if inc is None else inc, d.tilting_safety_factor,
                     d.sliding_safety_factor, d.engine_support_internal_diameter_mm,
                     d.engine_support_external_diameter_mm, d.contact_angle_deg,
                     d.support_yield_strength_compression_mpa, d.support_yield_strength_traction_mpa,
                     number_of_active_threads=d.number_of_active_threads, application_type=d.application_type,
                     bolt_head_contact_external_diameter_mm=d.bolt_head_contact_external_diameter_mm,
                     bolt_format=bolt_format, bolt_property_class=bolt_property_class)
    out = {}
    for k in tuple(_BOLT_KEYS) + _BOLT_VALUES:
        v = np.asarray(r[k], dtype=float)
        out[k] = float(v.reshape(-1)[0]) if v.size == 1 else v
    return out


def _bolt(sp: DesignSpace, cv: dict, rows: np.ndarray, keep_values: bool) -> SubEval:
    d, f = sp.inputs, sp.fixed
    c, t = sp.cores.iloc[rows], sp.subsystems["bolt"]
    nc, nk = len(c), len(t)
    m = {"pivot_wall": s2.pivot_wall_margin(c["pivot_diameter_mm"].to_numpy()[:, None], cv["loading_arm_mm"][rows][:, None],
                                            s2.bolt_hole_diameter_mm(t["d_mm"].to_numpy())[None, :])}
    values: dict = {}
    if not d.missing(*_FIX_FIELDS):
        pre = f.get("bolt_fixation") or {}
        per = [pre.get((fmt, cls)) or bolt_fixation(d, f["hubload_nominal_n"], fmt, cls)
               for fmt, cls in zip(t["bolt_format"], t["bolt_property_class"])]  # catalog rows (<= 32), not designs
        for k, name in _BOLT_KEYS.items():
            m[name] = np.array([r[k] for r in per])[None, :]
        if keep_values:
            for k in _BOLT_VALUES:
                values[k] = np.broadcast_to(np.array([r[k] for r in per])[None, :], (nc, nk))
    names, arr = _stack(m, (nc, nk))
    return SubEval(names, arr, np.ones((nc, nk), bool), values)


_SUB_FUNCS = {"bushing": _bushing, "axial": _axial, "spring": _spring, "bolt": _bolt}


def evaluate(sp: DesignSpace, *, prune: bool = True, keep_values: bool = False) -> Evaluation:
    """Evaluate every constraint of ``sp``.

    With ``prune=True`` the subsystems are evaluated only for the cores that
    pass their own constraints (the others cannot be completed into a
    feasible design); ``prune=False`` evaluates all cores (infeasibility
    diagnosis). Subsystem arrays then have one row per evaluated core:
    ``Evaluation.core_rows`` maps them back (see ``core_values["row"]``).
    ``keep_values`` also keeps the derived values (for one chosen design).
    """
    # placeholder pairs and degenerate designs may overflow inside the physics; every NaN is turned into
    # -inf (infeasible) by _clean, every inf is a real "unbounded" margin
    with np.errstate(over="ignore", divide="ignore", invalid="ignore"):
        return _evaluate(sp, prune, keep_values)


def _evaluate(sp: DesignSpace, prune: bool, keep_values: bool) -> Evaluation:
    names, arr, avail, cv = _core(sp)
    notes = list(sp.notes)
    if "cone_spring_annulus" in names:
        cv["cone_spring_annulus_ok"] = arr[:, names.index("cone_spring_annulus")] > 0
    else:
        cv["cone_spring_annulus_ok"] = np.zeros(len(arr), bool)
    ok = avail & np.all(arr >= -FEAS_TOL, axis=1) if arr.shape[1] else avail
    rows = np.flatnonzero(ok) if prune else np.arange(len(arr))
    cv["row"] = rows
    subs = {name: _SUB_FUNCS[name](sp, cv, rows, keep_values) for name in SUBSYSTEMS}
    n_eval = len(arr) + sum(s.available.size for s in subs.values())
    return Evaluation(sp, names, arr, avail, cv, subs, notes, n_eval, rows)
