"""The evaluator's main spring group (step 9, eq. (64)-(93)): what a spring sees of its core and application, the
one mapping from the physics to the values the registry's spring checks compare (:func:`spring_values`, the
compiled kernels' numpy reference) and the group (:func:`spring`).
"""

from __future__ import annotations

import numpy as np

from synth.design.group import SPRING_KEY_VALUES, Group, const as _const, finish, read_core
from synth.design.settings import DEFAULT, Settings
from synth.model import torsion_spring

__all__ = ["spring_keys", "SPRING_INPUTS", "SPRING_OPTION_COLUMNS", "SPRING_TOLERANCE_COLUMNS", "spring_inputs",
           "spring_values", "spring"]


def spring_keys(cg: Group, r) -> dict:
    """What a main spring sees of core rows ``r``: application, spring torque, housing height and diameters (and
    any other core value a registered spring check reads, :func:`core_values`)."""
    return {"app": cg.values["app"][r], **read_core("spring", cg, r)}


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
