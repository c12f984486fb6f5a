"""Step 10: tilting, sliding and the fixation bolt (thesis eq. (94)-(111)).

The tensioner is clamped on the engine by one bolt. The bolt preload must keep
the pivot base in contact with the crankcase under the tilting moment of the
hubload (which acts at the belt middle-plane height) and must hold the
hubload by friction (sliding). The preload is carried by a bolt format and
property class, and the clamped parts are checked under the head (on the
head's own bearing face, or a washer's, within the support's seat) and in
the threads.

Units: forces in N, lengths in mm, torques in N*mm inside and N*m at the
public outputs (``_nm``), stresses in MPa (= N/mm^2), angles in degrees.

Where the printed thesis equations are wrong or ambiguous the physically
correct form is implemented and the thesis tool's convention is offered as a
keyword option; see ``docs/sections/bolted_joint.md``.

Two paths size and judge the joint (:func:`fixation` ``method``): ``"thesis"``
(the thesis tool's elastic stress check at exactly the required clamp force:
the reproduction path of the thesis cases) and ``"vdi2230"`` (VDI 2230 Part 1:
the made joint of a tightening method, its preload window ``[F_M,min,
alpha_A F_M,min]`` sized to the requirement, or the bolt's yield point for
yield- and angle-controlled tightening). Thread data: ``catalogs/bolts.csv``
(ISO 261/262/724, ISO 898-1 A_s), head forms ``catalogs/bolt_heads.csv``
(hex, flange, socket), washers ``catalogs/washers.csv`` (ISO 7089, ISO 7093-1),
classes ``catalogs/bolt_property_classes.csv`` (ISO 898-1), tightening methods
``catalogs/tightening_factors.csv``. This module computes the values of the
step-10 checks for a given bolt; which bolt passes is the registry's verdict and
the flowchart's (or an optimiser's) choice. The VDI 2230 equations are
:mod:`synth.model.vdi2230`; the pivot base's tilting and sliding :mod:`synth.model.pivot_base`, the bolt's stresses
:mod:`synth.model.bolt_stress`, the bolts, heads and washers of the catalogs :mod:`synth.model.bolt_parts` (their
functions are named here too).

Thesis case 1 as run (its 13 mm contact: a head bearing on at least 13 mm, e.g. a flange head on a 13 mm seat):

>>> hl = nominal_hubload_n(3.25, 5.0, 85.0)
>>> round(float(hl), 1)
652.5
>>> out = fixation(hl, 29.5, 2.0, 2.5, 2.5, 8.2, 22.9, 360.0, 400.0, 400.0,
...                application_type="belt_in_oil", number_of_active_threads=2.3,
...                bolt_head_contact_external_diameter_mm=13.0, head_type="flange",
...                bolt_format="M8x1.25", bolt_property_class="8.8")
>>> round(float(out["bolt_tightening_torque_nm"]), 2), round(float(out["bolt_under_head_stress_mpa"]), 1)
(19.64, 204.1)
"""

from __future__ import annotations

import numpy as np

from synth.catalog import constant
from synth.errors import InputError, Problem
from synth.model.input_guards import as_array as _arr, require as _require
from synth.model.vdi2230 import (DEFAULT_EMBEDDING_LOADING, DEFAULT_EMBEDDING_ROUGHNESS, DEFAULT_TIGHTENING_METHOD,
                                 HEAD_TYPES, assembly_torque_nm, bolt_resilience_mm_per_n,
                                 clamped_parts_resilience_mm_per_n, embedding_preload_loss_n, embedding_um,
                                 head_mean_diameter_mm, permissible_assembly_preload_n)
from synth.model import vdi2230 as _vdi
from synth import parts
from synth.model.damping import hubload_nominal_n
from synth.model.pivot_base import (bolt_force_sliding_n, bolt_force_tilting_n, pivot_base_bending_factor_per_mm3,
                                    pivot_base_contact_area_mm2, pivot_base_pressure_mpa, required_bolt_force_n,
                                    sliding_safety_factor, tilting_lever_mm, tilting_safety_factor)
from synth.model.bolt_stress import (bolt_normal_stress_mpa, bolt_torsion_stress_mpa, min_active_threads,
                                     min_head_contact_diameter_mm, thread_area_mm2, thread_bearing_stress_mpa,
                                     thread_torque_nmm, tightening_torque_nm, under_head_stress_mpa,
                                     under_head_torque_nmm, von_mises_stress_mpa)
from synth.model.bolt_parts import (NO_WASHER, bolt_candidates, bolt_head, head_bearing_diameter_mm,
                                    head_friction_diameter_mm, washer_dimensions, washer_series)

__all__ = [
    "friction_coefficient", "nominal_hubload_n",
    "tilting_lever_mm", "pivot_base_contact_area_mm2", "pivot_base_bending_factor_per_mm3",
    "bolt_force_tilting_n", "bolt_force_sliding_n", "required_bolt_force_n",
    "tilting_safety_factor", "sliding_safety_factor", "pivot_base_pressure_mpa",
    "thread_torque_nmm", "under_head_torque_nmm", "tightening_torque_nm",
    "bolt_normal_stress_mpa", "bolt_torsion_stress_mpa", "von_mises_stress_mpa",
    "under_head_stress_mpa", "thread_area_mm2", "thread_bearing_stress_mpa",
    "min_head_contact_diameter_mm", "min_active_threads",
    "METHODS", "bolt_head", "bolt_candidates", "NO_WASHER", "washer_series", "washer_dimensions",
    "head_bearing_diameter_mm", "head_friction_diameter_mm", "fixation",
]

STEP = 10
ENVIRONMENTS = ("dry", "belt_in_oil")


# ----------------------------------------------------------------------------------------------
# catalog helpers
# ----------------------------------------------------------------------------------------------

def friction_coefficient(interface: str, environment: str) -> float:
    """Friction coefficient of an ``interface`` in an ``environment``.

    Reads ``catalogs/friction_coefficients.csv`` (columns
    ``interface,environment,mu,source,note``). Interfaces: ``thread``,
    ``under_head``, ``pivot_bushing``, ``pivot_base_crankcase``; environments:
    ``dry`` and ``belt_in_oil`` (the case files' ``application_type``).
    Values are those that reproduce thesis cases 1 and 3 (cases/NOTES.md).

    >>> friction_coefficient("pivot_base_crankcase", "dry")
    0.1
    >>> friction_coefficient("under_head", "belt_in_oil")
    0.08
    """
    return parts.mu(str(interface).strip(), str(environment).strip())


def nominal_hubload_n(calculated_torque_nm, working_arm_mm, differential_angle_deg):
    """Nominal hubload from the calculated-torque target, eq. (7) corrected.

    ``HL = T_calc / (l_arm * sin(alpha))`` [N], torque in N*m, working arm in
    mm. The printed eq. (7) has ``cos(alpha)``; the lever of the hubload about
    the pivot is ``l_arm * sin(alpha)`` as in eq. (12)-(13) (with cos, case 3 at
    alpha = 90 deg would divide by zero). This is the hubload the thesis tool
    uses elsewhere (cases/NOTES.md). ``alpha`` must lie in (0, 180) deg.

    >>> round(float(nominal_hubload_n(1.85, 4.0, 90.0)), 1)
    462.5
    """
    t = _require("calculated_torque_target_nm", calculated_torque_nm)
    arm = _require("working_arm_mm", working_arm_mm)
    a = _require("differential_angle_deg", differential_angle_deg, low=0.0, high=180.0,
                 accepted="an angle in (0, 180) deg")
    if np.any(a >= 180.0):
        raise InputError(Problem("differential_angle_deg", 180.0, "an angle in (0, 180) deg"))
    return hubload_nominal_n(t, arm, a)


#: the two paths that size and judge the joint (:func:`fixation` ``method``)
METHODS = ("thesis", "vdi2230")


# ----------------------------------------------------------------------------------------------
# the flowchart step
# ----------------------------------------------------------------------------------------------

def fixation(hubload_n, middle_plane_belt_height_mm, middle_plane_belt_height_increment_worst_mm,
             tilting_safety_factor_target, sliding_safety_factor_target,
             engine_support_internal_diameter_mm, engine_support_external_diameter_mm, contact_angle_deg,
             support_yield_strength_compression_mpa, support_yield_strength_traction_mpa, *,
             number_of_active_threads, application_type="dry",
             bolt_head_contact_external_diameter_mm=None, head_type="hex", washer=NO_WASHER,
             bolt_format=None, bolt_property_class=None,
             mu_crankcase=None, mu_thread=None, mu_head=None,
             contact_model="sector", torque_model="vdi", normal_stress_area="stress",
             torsion_diameter="minor", thread_area_model="triangle",
             method="thesis", tightening_method=DEFAULT_TIGHTENING_METHOD, alpha_a=None,
             embedding=False, clamp_length_mm=None,
             embedding_roughness=DEFAULT_EMBEDDING_ROUGHNESS, embedding_loading=DEFAULT_EMBEDDING_LOADING,
             clamped_interfaces=None, joint_type="tapped", clamped_parts_modulus_mpa=None,
             free_thread_length_mm=0.0, utilisation=None, candidates=None, clamp_force_n=None,
             candidate_of=None):
    """Step 10 of the flowchart: the joint of one named bolt, or of each of ``candidates`` (eq. (94)-(111)).

    Vectorised over designs: every numeric argument broadcasts. The clamp
    force the joint needs is ``F_req = max(F_tilting, F_sliding)`` for the
    safety targets (eq. (100)). This function computes the values of the
    registry's step-10 checks for the bolt it is given; choosing the bolt
    (the thesis's escalation: the first format and class that passes) is the
    caller's (:mod:`synth.flowchart`, the optimisers), from those checks.

    **The head's bearing diameter** on the support is the part's own: the
    head's ``dw_min`` (``bolt_heads.csv``, ``head_type``), or with a
    ``washer`` (``washers.csv`` series, ``"none"``: no washer) the washer's
    outer diameter as far as the head's load spreads through it
    (:func:`head_bearing_diameter_mm`). The application's
    ``bolt_head_contact_external_diameter_mm`` is a given seat: the support's
    bearing face ends there, so the contact is never larger
    (a head overhanging the seat bears on the seat).

    Two paths size and judge the joint (``method``):

    ``"thesis"`` (the reproduction path): the bolt is tightened to exactly
    ``F_req`` and judged by the elastic von Mises stress (eq. (103)-(107))
    against ``bolt_yield_utilisation_max * Rp0.2``; it reproduces the thesis
    cases (case 1 as run: M8x1.25 8.8, 19.64 N*m).

    ``"vdi2230"`` (the made joint of a tightening method, VDI 2230 Part 1):
    ``tightening_method`` (``catalogs/tightening_factors.csv``) tightens the
    joint into the window ``[F_M,min, F_M,max]``, ``F_M,max = alpha_A
    F_M,min`` (Table A8, the method's upper factor, or ``alpha_a``). A
    torque-controlled method sizes the window to the requirement:
    ``F_M,min = F_req`` (+ the embedding loss ``F_Z`` with ``embedding=True``,
    R4/R5: it needs ``clamp_length_mm``), and the bolt must carry the
    window's top: ``F_M,max <= F_M,zul`` (R7/2, plastic torsion, ``nu``).
    A yield- or angle-controlled method takes the bolt to its yield point:
    ``F_M,min`` is the bolt's own yield preload (R7/2 at ``nu = 1``) and the
    bolt is dimensioned for it (VDI 2230-1: ``alpha_A`` is the scatter of the
    lot's yield point; no ``F_M,zul`` check). The safety factors are those
    of the window's bottom (the smallest residual clamp force), the head,
    thread and pivot-base pressures and the bolt stresses those of its top
    (R10); ``bolt_axial_force_n`` is the window's mean and the tightening
    torque (R13/1) is set for it.

    ``clamp_force_n`` (broadcast like the designs, NaN where not given): a
    made joint, tightened to this preload (a production-scatter sample of
    :mod:`synth.robust`); every value then follows from it (the safety
    factors at it less the embedding loss, the pressures and stresses at
    it) and ``bolt_clamp_force_required_n`` stays ``F_req``.

    Friction coefficients default to ``friction_coefficients.csv`` for the
    ``application_type`` (``dry`` or ``belt_in_oil``).

    Options (thesis-tool conventions vs defaults): ``contact_model``
    (``sector``/``thesis``, see :func:`pivot_base_bending_factor_per_mm3`),
    ``torque_model`` (``vdi``/``helix``), ``normal_stress_area``
    (``stress`` = ISO 898-1 A_s / ``core`` = printed eq. (103)-(104)),
    ``torsion_diameter`` (``minor`` = eq. (105) / ``stress`` = VDI 2230),
    ``thread_area_model`` (see :func:`thread_area_mm2`); these apply to the
    thesis path. VDI-path options: ``embedding`` with ``clamp_length_mm``
    (the clamped length l_K), ``embedding_roughness``, ``embedding_loading``,
    ``clamped_interfaces``, ``joint_type``, ``clamped_parts_modulus_mpa``,
    ``free_thread_length_mm``, ``utilisation`` (``nu`` of R7, default 0.9).

    The bolt: ``bolt_format`` and ``bolt_property_class`` (one bolt), or
    ``candidates`` (a list of ``(bolt_format, bolt_property_class)`` pairs):
    every pair is evaluated and every returned array gains a trailing axis,
    one entry per pair (each entry equals the call naming that bolt).
    ``head_type``, ``washer`` and ``tightening_method`` are then each one
    name, or a sequence of names aligned with ``candidates`` (each bolt's own
    head form, washer series and tightening method). ``candidate_of`` (an
    index array broadcasting with the designs): design ``i`` is judged with
    ``candidates[candidate_of[i]]`` alone, no trailing axis (each design its
    own bolt: a production sample of its design's bolt; each entry again
    equals the call naming that bolt).

    Returns a dict of arrays with the case keys ``bolt_tightening_torque_nm``,
    ``bolt_axial_force_n``, ``bolt_sigma_mpa``, ``bolt_tau_mpa``,
    ``bolt_sigma_eqv_mpa``, ``bolt_under_head_stress_mpa``,
    ``bolt_thread_stress_mpa``, ``bolt_format``, ``bolt_property_class``,
    ``pivot_base_contact_surface_mm2``, ``average_contact_pressure_mpa``,
    ``tilting_safety_factor``, ``sliding_safety_factor``; intermediates
    (``bolt_force_tilting_n``, ``bolt_force_sliding_n``, ``bolt_clamp_force_required_n``,
    ``tilting_moment_nmm``, ``pivot_base_max_pressure_mpa``,
    ``pivot_base_min_pressure_mpa``, ``bolt_utilisation``, ``bolt_rp02_mpa``,
    ``bolt_head_contact_diameter_mm`` (the bearing diameter on the support));
    column-G corrections (``min_head_contact_diameter_mm``, ``min_active_threads``,
    ``pivot_bore_min_mm``) -- the limits and verdicts are the registry's
    (:mod:`synth.design.constraints`); and for ``"vdi2230"`` also
    ``bolt_permissible_preload_n`` (F_M,zul; +inf for a yield-controlled
    method), ``bolt_required_preload_min_n`` (F_M,min), ``bolt_required_preload_max_n``
    (F_M,max), ``bolt_embedding_um`` (f_Z), ``bolt_embedding_loss_n`` (F_Z),
    ``bolt_residual_clamp_force_n`` (the smallest residual clamp force) and
    ``tightening_factor``.

    >>> r = fixation(462.5, 20.0, 2.0, 3.0, 3.0, 8.2, 28.0, 360.0, 400.0, 400.0, number_of_active_threads=2.6,
    ...              bolt_head_contact_external_diameter_mm=11.0, bolt_format="M8x1.25", bolt_property_class="8.8")
    >>> round(float(r["bolt_axial_force_n"])), round(float(r["tilting_safety_factor"]), 2)
    (13875, 5.18)
    >>> v = fixation(462.5, 20.0, 2.0, 3.0, 3.0, 8.2, 28.0, 360.0, 400.0, 400.0, method="vdi2230",
    ...              number_of_active_threads=2.6, head_type="flange", bolt_format="M8x1.25",
    ...              bolt_property_class="10.9")
    >>> round(float(v["bolt_required_preload_min_n"])), round(float(v["bolt_required_preload_max_n"]))
    (13875, 22200)
    >>> round(float(v["bolt_under_head_stress_mpa"]), 1), round(float(v["sliding_safety_factor"]), 2)
    (182.7, 3.0)
    """
    if method not in METHODS:
        raise InputError(Problem("method", method, "one of " + ", ".join(METHODS)))
    if application_type not in ENVIRONMENTS:
        raise InputError(Problem("application_type", application_type, "one of " + ", ".join(ENVIRONMENTS)))
    heads = _per_candidate("head_type", head_type, candidates)
    for h in dict.fromkeys(heads):
        if h not in HEAD_TYPES:
            raise InputError(Problem("head_type", h, "one of " + ", ".join(HEAD_TYPES)))
    washers = _per_candidate("washer", washer, candidates)
    methods = _per_candidate("tightening_method", tightening_method, candidates)
    if normal_stress_area not in ("stress", "core"):
        raise InputError(Problem("normal_stress_area", normal_stress_area, "'stress' or 'core'"))
    if torsion_diameter not in ("minor", "stress"):
        raise InputError(Problem("torsion_diameter", torsion_diameter, "'minor' or 'stress'"))
    if method == "vdi2230" and embedding and clamp_length_mm is None:
        raise InputError(Problem("clamp_length_mm", None, "a clamped length > 0 mm (e.g. the pivot height) for the "
                                 "VDI 2230 embedding loss"))
    mu_cc = friction_coefficient("pivot_base_crankcase", application_type) if mu_crankcase is None else mu_crankcase
    mu_g = friction_coefficient("thread", application_type) if mu_thread is None else mu_thread
    mu_k = friction_coefficient("under_head", application_type) if mu_head is None else mu_head

    hl = _require("hubload_n", hubload_n, inclusive=True)
    lever = tilting_lever_mm(middle_plane_belt_height_mm, middle_plane_belt_height_increment_worst_mm)
    d_int = _arr(engine_support_internal_diameter_mm)
    d_ext = _arr(engine_support_external_diameter_mm)
    s_comp = _require("support_yield_strength_compression_mpa", support_yield_strength_compression_mpa)
    s_trac = _require("support_yield_strength_traction_mpa", support_yield_strength_traction_mpa)
    n_thr = _require("number_of_active_threads", number_of_active_threads)

    f_tilt = bolt_force_tilting_n(hl, tilting_safety_factor_target, lever, d_ext, d_int, contact_angle_deg,
                                  model=contact_model)
    f_slide = bolt_force_sliding_n(hl, sliding_safety_factor_target, mu_cc)
    required = required_bolt_force_n(f_tilt, f_slide)
    made = None if clamp_force_n is None else _arr(clamp_force_n)
    area = pivot_base_contact_area_mm2(d_ext, d_int, contact_angle_deg)
    k = pivot_base_bending_factor_per_mm3(d_ext, d_int, contact_angle_deg, model=contact_model)
    moment = hl * lever

    # --- the bolts: one named, or candidates on a trailing axis (no choice among them here) --------------
    if candidates is not None:
        if bolt_format is not None or bolt_property_class is not None:
            raise InputError(Problem("candidates", "given with bolt_format/bolt_property_class",
                                     "either a list of (format, class) pairs or one format and class"))
        cands = [bolt_candidates(f, c, h)[0] for (f, c), h in zip(candidates, heads)]
        if not cands:
            raise InputError(Problem("candidates", "[]", "at least one (format, class) pair"))
    elif candidate_of is not None:
        raise InputError(Problem("candidate_of", "given without candidates", "an index into a list of candidates"))
    else:
        if bolt_format is None or bolt_property_class is None:
            raise InputError(Problem("bolt_format", bolt_format, "a bolt format and a property class (or a list of "
                                     "candidates): choosing the bolt is the flowchart's step, from the checks"))
        cands = bolt_candidates(bolt_format, bolt_property_class, head_type)
    col = {key: np.array([c[key] for c in cands], dtype=float) for key, v in cands[0].items() if isinstance(v, float)}
    names_f = np.array([c["bolt_format"] for c in cands])
    names_c = np.array([c["bolt_property_class"] for c in cands])
    wsh = _washers(washers, col["d_mm"])
    seat = None if bolt_head_contact_external_diameter_mm is None else _arr(bolt_head_contact_external_diameter_mm)
    if seat is not None and np.any(seat <= d_int):
        s_, d_ = np.broadcast_arrays(seat, d_int)
        raise InputError(Problem("bolt_head_contact_external_diameter_mm", float(np.ravel(s_[s_ <= d_])[0]),
                                 "a seat diameter > the support internal diameter"))
    tight = _tightening(methods, alpha_a) if method == "vdi2230" else None
    heads_a = np.array(heads, dtype=object)
    if candidate_of is not None:  # each design its own bolt: the bolts' values gathered onto the designs' axis
        pick = np.asarray(candidate_of, dtype=np.int64)
        col, wsh = {k: v[pick] for k, v in col.items()}, {k: v[pick] for k, v in wsh.items()}
        names_f, names_c, heads_a = names_f[pick], names_c[pick], heads_a[pick]
        tight = None if tight is None else (tight[0][pick], tight[1][pick] if np.ndim(tight[1]) else tight[1])
        ex = _arr
        shape = np.broadcast_shapes(np.shape(required), pick.shape)
    else:
        ex = _on_candidates
        shape = np.broadcast_shapes(np.shape(required)[:], ()) + (len(cands),)
    seat = None if seat is None else ex(seat)
    dw = head_bearing_diameter_mm(col["dw_min_mm"], wsh["d2_mm"], wsh["h_mm"], seat)   # on the support
    d_in = np.fmax(ex(d_int), wsh["d1_mm"])                                         # its bore (a washer's)
    dk = head_friction_diameter_mm(col["dw_min_mm"], wsh["d2_mm"], seat)               # the turning face
    mu_gk = ex(mu_g)

    a_thr = thread_area_mm2(col["d_mm"], col["pitch_mm"], col["d2_mm"], col["d3_mm"], col["D1_mm"],
                            model=thread_area_model)
    if method == "thesis":
        f_top, f_bottom, f_bolt, sigma_s, tau_s, eqv_s, torque, vdi = _thesis_joint(
            ex(required), None if made is None else ex(made), col, mu_gk, dk, d_in, ex(mu_k), torque_model,
            normal_stress_area, torsion_diameter)
    else:
        f_top, f_bottom, f_bolt, sigma_s, tau_s, eqv_s, torque, vdi = _vdi2230_joint(
            ex(required), None if made is None else ex(made), col, mu_gk, dk, dw, d_in, ex(d_ext), ex(mu_k), shape,
            tightening=tight, utilisation=utilisation, embedding=embedding,
            clamp_length_mm=None if clamp_length_mm is None else ex(clamp_length_mm),
            embedding_roughness=embedding_roughness, embedding_loading=embedding_loading,
            clamped_interfaces=clamped_interfaces, joint_type=joint_type, head_type=heads_a,
            clamped_parts_modulus_mpa=clamped_parts_modulus_mpa, free_thread_length_mm=ex(free_thread_length_mm))
    sf_t = tilting_safety_factor(np.maximum(f_bottom, 0.0), ex(hl), ex(lever), ex(d_ext), ex(d_int),
                                 ex(contact_angle_deg), model=contact_model)
    sf_s = sliding_safety_factor(np.maximum(f_bottom, 0.0), ex(hl), ex(mu_cc))
    p_top = f_top / ex(area)
    out = {
        "bolt_tightening_torque_nm": torque,
        "bolt_axial_force_n": f_bolt,
        "bolt_sigma_mpa": sigma_s,
        "bolt_tau_mpa": tau_s,
        "bolt_sigma_eqv_mpa": eqv_s,
        "bolt_under_head_stress_mpa": under_head_stress_mpa(f_top, dw, d_in),
        "bolt_thread_stress_mpa": thread_bearing_stress_mpa(f_top, a_thr, ex(n_thr)),
        "bolt_format": names_f,
        "bolt_property_class": names_c,
        "pivot_base_contact_surface_mm2": ex(area),
        "average_contact_pressure_mpa": f_bolt / ex(area),
        "tilting_safety_factor": sf_t,
        "sliding_safety_factor": sf_s,
        "bolt_force_tilting_n": ex(f_tilt),
        "bolt_force_sliding_n": ex(f_slide),
        "bolt_clamp_force_required_n": ex(required),
        "tilting_moment_nmm": ex(moment),
        "pivot_base_max_pressure_mpa": p_top + ex(moment) * ex(k),
        "pivot_base_min_pressure_mpa": f_bottom / ex(area) - ex(moment) * ex(k),
        "bolt_rp02_mpa": col["rp02_mpa"],
        "bolt_utilisation": eqv_s / col["rp02_mpa"],
        "bolt_head_contact_diameter_mm": dw,
        "min_head_contact_diameter_mm": min_head_contact_diameter_mm(f_top, d_in, ex(s_comp)),
        "min_active_threads": min_active_threads(f_top, a_thr, ex(s_trac)),
        "pivot_bore_min_mm": col["pivot_bore_min_mm"],
        **vdi,
    }
    full = np.broadcast_shapes(*(np.shape(v) for v in out.values()), shape)
    out = {key: np.broadcast_to(v, full) for key, v in out.items()}
    if candidates is None:  # one named bolt: no trailing axis
        out = {key: v[..., 0] for key, v in out.items()}
    return out


def _per_candidate(name: str, value, candidates) -> list:
    """One name per bolt of :func:`fixation`: ``value`` for each (a name), or with ``candidates`` a sequence of
    names aligned with them (each bolt's own head form, washer series or tightening method)."""
    n = 1 if candidates is None else len(candidates)
    if isinstance(value, str) or value is None or np.ndim(value) == 0:
        return [value] * n
    names = list(value)
    if candidates is None or len(names) != n:
        raise InputError(Problem(name, f"{len(names)} names", f"one name, or one per candidate ({n})"
                                 if candidates is not None else "one name (a sequence needs candidates)"))
    return names


def _washers(series: list, d_mm) -> dict:
    """:func:`washer_dimensions` of each bolt's own washer ``series`` (one per entry of ``d_mm``), one catalog
    look-up per distinct series."""
    d = np.asarray(d_mm, dtype=float)
    names = list(dict.fromkeys(series))
    if len(names) == 1:
        return washer_dimensions(names[0], d)
    out = {k: np.empty(d.shape) for k in ("d1_mm", "d2_mm", "h_mm")}
    which = np.array([names.index(s) for s in series])
    for i, s in enumerate(names):
        at = which == i
        for k, v in washer_dimensions(s, d[at]).items():
            out[k][at] = v
    return out


def _tightening(methods: list, alpha_a) -> tuple:
    """``(yield-set, alpha_A)`` of each bolt's tightening method ``methods`` (``catalogs/tightening_factors.csv``: the
    preload set by the bolt's yield point; Table A8's upper factor, or ``alpha_a`` for every bolt), one look-up
    per distinct method."""
    names = list(dict.fromkeys(methods))
    tms = [_vdi.tightening_method(m) for m in names]
    which = np.array([names.index(m) for m in methods])
    yield_set = np.array([tm["preload_set_by"] == "yield" for tm in tms])[which]
    alpha = np.array([tm["alpha_a_max"] for tm in tms])[which] if alpha_a is None else float(_require(
        "alpha_a", alpha_a, low=1.0, inclusive=True, accepted="a tightening factor >= 1"))
    return yield_set, alpha


def _on_candidates(a):
    """A design array on the candidates' (trailing) axis."""
    return np.asarray(a, dtype=float)[..., None]


def _thesis_joint(required, made, col, mu_gk, dk, d_in, mu_k, torque_model, normal_stress_area, torsion_diameter):
    """The thesis path of :func:`fixation` (eq. (101)-(107)): the bolt tightened to exactly the required force
    ``required`` (or a made joint's ``made`` preload where finite), judged by its elastic stresses. Arrays on the
    candidates' axis; returns ``(F top, F bottom, F bolt, sigma, tau, sigma_eqv, torque [N m], {})``."""
    force = required if made is None else np.where(np.isfinite(made), made, required)
    f_top = f_bottom = f_bolt = force
    t_thread = thread_torque_nmm(force, col["pitch_mm"], col["d2_mm"], mu_gk, model=torque_model)
    a_norm = col["stress_area_mm2"] if normal_stress_area == "stress" else np.pi / 4.0 * col["d3_mm"] ** 2
    d_tors = col["d3_mm"] if torsion_diameter == "minor" else (col["d2_mm"] + col["d3_mm"]) / 2.0
    sigma_s = bolt_normal_stress_mpa(force, a_norm)
    tau_s = bolt_torsion_stress_mpa(t_thread, d_tors)
    eqv_s = von_mises_stress_mpa(sigma_s, tau_s)
    torque = (t_thread + under_head_torque_nmm(force, dk, d_in, mu_k)) / 1000.0
    return f_top, f_bottom, f_bolt, sigma_s, tau_s, eqv_s, torque, {}


def _vdi2230_joint(required, made, col, mu_gk, dk, dw, d_in, d_ext, mu_k, shape, *, tightening, utilisation,
                   embedding, clamp_length_mm, embedding_roughness, embedding_loading, clamped_interfaces, joint_type,
                   head_type, clamped_parts_modulus_mpa, free_thread_length_mm):
    """The VDI 2230 path of :func:`fixation` (Part 1, R4-R13): the made joint of a tightening method, its preload
    window sized to the requirement ``required`` (or the bolt's yield preload), the embedding loss, the stresses at
    the window's top. Arrays on the candidates' axis; returns ``(F top, F bottom, F bolt, sigma, tau, sigma_eqv,
    torque [N m], the VDI values)``; ``tightening``: each bolt's :func:`_tightening`, ``head_type`` its head form
    (arrays on the bolts' axis, as ``col``)."""
    yield_set, alpha = tightening
    f_zul = permissible_assembly_preload_n(col["pitch_mm"], col["d2_mm"], col["d3_mm"], col["rp02_mpa"], mu_gk,
                                           utilisation=utilisation)
    f_z = np.zeros(shape)
    fz_um = 0.0
    if embedding:
        fz_um = embedding_um(embedding_roughness, embedding_loading, interfaces=clamped_interfaces,
                             joint_type=joint_type)
        lk = clamp_length_mm
        d_s = 0.0
        for h in dict.fromkeys(head_type.tolist()):  # each bolt's own head form
            d_h = bolt_resilience_mm_per_n(col["d_mm"], col["d3_mm"], lk, head_type=h, joint_type=joint_type,
                                           free_thread_length_mm=free_thread_length_mm,
                                           internal_thread_modulus_mpa=clamped_parts_modulus_mpa)
            d_s = np.where(head_type == h, d_h, d_s)
        d_p = clamped_parts_resilience_mm_per_n(dw, d_in, d_ext, lk, modulus_mpa=clamped_parts_modulus_mpa,
                                                joint_type=joint_type)
        f_z = np.broadcast_to(embedding_preload_loss_n(fz_um, d_s, d_p), shape)
    # a yield- or angle-controlled bolt: its own yield preload (nu = 1, Rp0.2 min) is the window's bottom, no limit;
    # a torque-controlled one: the requirement, up to its permissible preload
    f_min = np.broadcast_to(required + f_z, shape)
    limit = np.broadcast_to(f_zul, shape)
    if yield_set.any():
        f_min = np.where(yield_set, permissible_assembly_preload_n(col["pitch_mm"], col["d2_mm"], col["d3_mm"],
                                                                   col["rp02_mpa"], mu_gk, utilisation=1.0), f_min)
        limit = np.where(yield_set, np.inf, limit)
    f_max = alpha * f_min
    if made is None:
        f_bottom, f_top, f_bolt = f_min, f_max, (f_min + f_max) / 2.0
    else:
        mf = made
        f_bottom = np.where(np.isfinite(mf), mf, f_min)
        f_top = np.where(np.isfinite(mf), mf, f_max)
        f_bolt = np.where(np.isfinite(mf), mf, (f_min + f_max) / 2.0)
    d0 = (col["d2_mm"] + col["d3_mm"]) / 2.0
    thread_moment = f_top / 2.0 * (col["pitch_mm"] / np.pi + mu_gk * col["d2_mm"] /
                                   np.cos(np.radians(constant("thread_flank_half_angle_deg"))))
    sigma_s = f_top / (np.pi / 4.0 * d0**2)
    tau_s = 12.0 * thread_moment / (np.pi * d0**3)  # plastic torsion section pi d0^3/12 (VDI R7)
    eqv_s = von_mises_stress_mpa(sigma_s, tau_s)
    torque = assembly_torque_nm(f_bolt, col["pitch_mm"], col["d2_mm"], mu_gk, head_mean_diameter_mm(dk, d_in),
                                mu_k)
    f_bottom = f_bottom - f_z
    vdi = {"bolt_permissible_preload_n": limit, "bolt_required_preload_min_n": f_min,
           "bolt_required_preload_max_n": f_top, "bolt_embedding_um": np.full(shape, fz_um),
           "bolt_embedding_loss_n": f_z, "bolt_residual_clamp_force_n": f_bottom,
           "tightening_factor": np.broadcast_to(alpha, shape)}
    return f_top, f_bottom, f_bolt, sigma_s, tau_s, eqv_s, torque, vdi
