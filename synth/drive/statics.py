"""Drive statics: the belt path at the nominal arm angle, span tensions and hub loads.

At the nominal arm angle the spring holds the arm against the belt: with the
tensioner an idler, both its spans carry the tensioner tension

    T_t = M_nom / (dL/dpsi)                                        (arm equilibrium)

(``M_nom`` the arm torque at nominal, ``dL/dpsi`` the take-up in m/rad,
:func:`synth.drive.layout.take_up`). Going round the belt in its travel
direction, a driven pulley's load torque ``Q`` raises the tension by ``Q/r``
(its leaving span pulls it round), the crank gives it all back:

    T_out = T_in + Q_i / r_i,      Q_crank = -r_crank sum_i Q_i / r_i.

A pulley's hub load is ``T_out u_out - T_in u_in``. Tensions are the effective
(strain) tensions: the centrifugal tension ``m v^2`` adds equally to every span
and loads neither a hub nor the tensioner (belt element equilibrium on a
pulley: ``(T - m v^2) dtheta = N ds``), so it is left out.

Torques in N m, forces in N, lengths in mm.
"""

from __future__ import annotations

import numpy as np

from synth.drive import layout as geo
from synth.errors import InputError, Problem

__all__ = ["static_state"]


def static_state(drive) -> dict:
    """Geometry and static tensions of a validated drive (:class:`synth.drive.inputs.Drive`).

    >>> from synth.drive.inputs import example_drive
    >>> s = static_state(example_drive())
    >>> round(s["tensioner_tension_n"], 1), round(s["take_up_mm_per_rad"], 3)
    (573.7, 3.225)
    """
    p = drive.pulleys
    t_idx = drive.tensioner_index
    ten = drive.tensioner
    phi = np.radians(ten.arm_angle_deg)
    centre_t = geo.tensioner_centre_mm([ten.pivot_x_mm, ten.pivot_y_mm], ten.arm_length_mm, phi)
    centres = np.array([[q.x_mm, q.y_mm] for q in p], dtype=float)
    centres[t_idx] = centre_t
    radii = np.array([q.radius_mm for q in p], dtype=float)
    inside = np.array([not q.backside for q in p])
    orient = geo.loop_orientation(centres[inside]) if inside.sum() >= 3 else geo.loop_orientation(centres)
    sigma = np.where(inside, orient, -orient)
    names = [q.name for q in p]
    g = geo.span_geometry(centres, radii, sigma, names)
    tu = geo.take_up(g["direction"], t_idx, ten.arm_length_mm, phi)
    take_up_mm = tu["sign"] * tu["dl_dphi_mm"]
    if tu["total_mm"] == 0.0:
        raise InputError(Problem("tensioner.arm_angle_deg", ten.arm_angle_deg,
                                 "an arm angle at which the arm's swing moves the pulley into the belt (here it "
                                 "moves along the belt: no take-up)"))
    total_m = abs(tu["total_mm"]) / 1000.0
    t_t = ten.nominal_torque_nm / total_m
    n = len(p)
    tension = np.zeros(n)
    loads = np.array([q.load_torque_nm for q in p], dtype=float)
    crank = drive.crank_index
    loads[crank] = 0.0
    loads[crank] = -radii[crank] / 1000.0 * float(np.sum(loads / (radii / 1000.0)))
    tension[t_idx] = t_t
    for k in range(1, n):
        j = (t_idx + k) % n  # span j starts at pulley j
        tension[j] = tension[j - 1] + loads[j] / (radii[j] / 1000.0)
    u = g["direction"]
    hub = tension[:, None] * u - np.roll(tension, 1)[:, None] * np.roll(u, 1, axis=0)
    # the tensioner's differential angle: between the arm (pivot -> pulley) and the hub load's line
    arm_dir = np.array([np.cos(phi), np.sin(phi)])
    h_t = hub[t_idx]
    cos_a = float(np.clip(-(h_t @ arm_dir) / max(np.hypot(*h_t), 1e-300), -1.0, 1.0))
    # second derivative of the path length by the arm angle (geometric stiffness of the tensioned belt)
    h = 1e-4

    def path(dphi):
        c = centres.copy()
        c[t_idx] = geo.tensioner_centre_mm([ten.pivot_x_mm, ten.pivot_y_mm], ten.arm_length_mm, phi + dphi)
        return geo.path_length_mm(c, radii, sigma)
    l0, lp, lm = path(0.0), path(h), path(-h)
    return {"centres_mm": centres, "radii_mm": radii, "sigma": sigma, "names": names,
            "span_length_mm": g["length_mm"], "direction": u, "wrap_deg": np.degrees(g["wrap_rad"]),
            "span_start_mm": g["start_mm"], "span_end_mm": g["end_mm"], "tension_n": tension,
            "load_torque_nm": loads, "hub_load_n": np.hypot(hub[:, 0], hub[:, 1]), "hub_vector_n": hub,
            "take_up_dl_mm_per_rad": take_up_mm, "take_up_mm_per_rad": abs(tu["total_mm"]),
            "take_up_sign": tu["sign"], "tensioner_tension_n": t_t, "path_length_mm": l0,
            "path_d2_mm_per_rad2": (lp - 2.0 * l0 + lm) / h ** 2,
            "path_d1_mm_per_rad": (lp - lm) / (2.0 * h),
            "differential_angle_deg": float(np.degrees(np.arccos(cos_a)))}
