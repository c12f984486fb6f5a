"""The tensioner's positions and the duty table, as a drive-design report states them.

The arm turns about the pivot; its angle ``phi`` is counter-clockwise from +x
[deg] and the pulley centre is ``pivot + l (cos phi, sin phi)``. The belt runs
the pitch line (the cord): the spans are the pitch circles' common tangents
(:func:`synth.drive.layout.span_geometry`) and the drive length ``L(phi)`` is
measured on the effective line (:func:`synth.drive.layout.effective_length_mm`),
as belt lengths are.

**Spring and sense.** The belt pushes the arm the way that shortens the path
(its loading sense ``s = -sign(dL/dphi)``); the spring's torque grows that way:

    M(phi) = M_nom + k s (phi - phi_nom),          preload = M(phi_free)   [N m]

**Equilibrium** (virtual work, both spans of the tensioner at ``T``):

    T = M / |dL/dphi|,   |dL/dphi| = l sin(beta) 2 sin(wrap/2)         (the take-up)

with ``beta`` the angle between the arm (pulley centre to pivot) and the hub
load ``H = T (u_out - u_in)``, ``|H| = 2 T sin(wrap/2)``. The take-up is
computed by projection (:func:`synth.drive.layout.take_up`) and equals the
path's derivative.

**Positions** (a report's "tensioner geometry" table). The nominal position
is the stated arm angle, or the spring's nominal torque, or the belt length
(:func:`nominal_angle_deg`). The others are the arm angles where the drive
length is the nominal one changed by the belt's length tolerance ``tol``,
its wear ``w`` (% of the longest belt, at replacement) and its thermal change
``dT`` (% of the length, signed: the hot belt):

    longest  L_n + tol + max(dT, 0) L          worn  L_longest + (L + tol) w
    shortest L_n - tol + min(dT, 0) L

and the stops: the free arm (no belt) and the installation stop. A length the
arm cannot reach between its stops is a finding: the position is reported
beyond the stop, with by how much.

**Required belt length.** The belt is measured under its measuring tension;
at the nominal tension it is longer by :func:`synth.drive.belt.elongation_mm`
(the reports take it at the design tension for every position), so the belt
a position needs is ``L(phi) - dL(T_nom)``.

**Duty table.** At the nominal arm position, each duty point's loads
(power ``P`` or torque ``Q = P / omega``) change the tension across each
pulley by ``P / v`` (``v`` the belt speed on the crank's pitch radius): a
driven pulley raises it in the travel direction, the crank gives it all back.
The span arriving at the tensioner carries the nominal tension, as in the
reports (the tensioner pulley's own loss, a bearing's 0.01 kW in them, would
move the arm's balance by a fraction of a newton-metre, far inside the arm's
friction, so it is not balanced on the arm). The belt's elastic stretch under the duty's tensions would swing the arm; like the
reports, the table keeps the arm at its nominal position.

Lengths in mm, angles in degrees unless a name says ``_rad``.
"""

from __future__ import annotations

from functools import lru_cache

import numpy as np

from synth.drive import layout as geo
from synth.drive.belt import elongation_mm
from synth.errors import InputError, Problem

__all__ = ["frame", "arm_state", "loading_sense", "spring_torque_nm", "nominal_angle_deg", "positions",
           "duty_table", "POSITION_NAMES", "travels"]

#: the positions of a report's tensioner table, in its order, with the report's own names
POSITION_NAMES = {"free arm": "Free Arm", "worn": "Replace", "longest": "Max", "nominal": "Mean",
                  "shortest": "Min", "installation": "Load"}


@lru_cache(maxsize=256)
def frame(pulleys, pivot_mm, arm_length_mm, reference_angle_deg) -> dict:
    """The fixed part of the layout: centres (the tensioner's filled at run time), pitch and effective radii,
    wrap senses (from the loop at ``reference_angle_deg``), names."""
    t = next(i for i, p in enumerate(pulleys) if p.role == "tensioner")
    centres = np.array([[p.x_mm, p.y_mm] for p in pulleys], dtype=float)
    centres[t] = geo.tensioner_centre_mm(pivot_mm, arm_length_mm, np.radians(reference_angle_deg))
    radii = np.array([p.radius_mm for p in pulleys], dtype=float)
    eff = np.array([p.effective_radius_mm or p.radius_mm for p in pulleys], dtype=float)
    inside = np.array([not p.backside for p in pulleys])
    orient = geo.loop_orientation(centres[inside]) if inside.sum() >= 3 else geo.loop_orientation(centres)
    sigma = np.where(inside, orient, -orient)
    return {"centres": centres, "radii": radii, "effective": eff, "sigma": sigma, "t": t,
            "names": [p.name for p in pulleys], "pivot": np.asarray(pivot_mm, float), "arm": float(arm_length_mm)}


def frame_of(drive, reference_angle_deg=None) -> dict:
    """The layout :func:`frame` of ``drive``'s pulleys and tensioner, its arm at ``reference_angle_deg`` (default: the
    drive's arm angle)."""
    ten = drive.tensioner
    ref = ten.arm_angle_deg if reference_angle_deg is None else reference_angle_deg
    return frame(drive.pulleys, (ten.pivot_x_mm, ten.pivot_y_mm), ten.arm_length_mm, float(ref))


def arm_state(fr: dict, phi_deg, *, strict: bool = False) -> dict:
    """The layout with the arm at ``phi_deg`` (scalar or array): spans, wraps, the drive length on the effective
    line, the take-up ``dL/dphi`` [mm/rad], the tensioner's wrap, ``beta`` [deg] and hub-load direction [deg].
    Arm angles where the belt cannot run give NaN (``strict``: an input error)."""
    phi = np.radians(np.atleast_1d(np.asarray(phi_deg, dtype=float)))
    t = fr["t"]
    centres = np.broadcast_to(fr["centres"], phi.shape + fr["centres"].shape).copy()
    arm = np.stack([np.cos(phi), np.sin(phi)], axis=-1)
    centres[:, t] = fr["pivot"] + fr["arm"] * arm
    g = geo.span_geometry(centres, fr["radii"], fr["sigma"], fr["names"], strict=strict)
    n = len(fr["names"])
    u = g["direction"]
    u_in, u_out = u[:, (t - 1) % n], u[:, t]
    dx = fr["arm"] * np.stack([-np.sin(phi), np.cos(phi)], axis=-1)
    dl = np.einsum("ij,ij->i", u_in, dx) - np.einsum("ij,ij->i", u_out, dx)      # layout.take_up, vectorised
    f = u_out - u_in
    to_pivot = -arm
    cos_b = np.einsum("ij,ij->i", f, to_pivot) / np.maximum(np.hypot(f[:, 0], f[:, 1]), 1e-300)
    ok = g["closed"] & np.all(np.isfinite(g["length_mm"]), axis=-1)
    edl = np.where(ok, geo.effective_length_mm(g, fr["effective"]), np.nan)
    return {"phi_deg": np.degrees(phi), "geometry": g, "centres": centres, "drive_length_mm": edl,
            "dl_dphi_mm": np.where(ok, dl, np.nan), "wrap_deg": np.degrees(g["wrap_rad"][:, t]),
            "beta_deg": np.degrees(np.arccos(np.clip(cos_b, -1.0, 1.0))),
            "hub_direction_deg": np.mod(np.degrees(np.arctan2(f[:, 1], f[:, 0])), 360.0), "ok": ok}


def loading_sense(fr: dict, phi_deg: float) -> float:
    """``+1`` when the belt pushes the arm counter-clockwise at ``phi_deg`` (the path shortens that way)."""
    s = arm_state(fr, phi_deg, strict=True)
    dl = float(s["dl_dphi_mm"][0])
    if not np.isfinite(dl) or dl == 0.0:
        raise InputError(Problem("tensioner", f"arm at {phi_deg:g} deg", "an arm angle at which the arm's swing "
                                 "moves the pulley into the belt (here it moves along the belt: no take-up)"))
    return -1.0 if dl > 0 else 1.0


def spring_torque_nm(ten, sense: float, phi_deg):
    """The spring's torque at arm angle ``phi_deg`` [N m]: ``M_nom + k s (phi - phi_nom)``."""
    return ten.nominal_torque_nm + ten.stiffness_nm_per_deg * sense * _wrap180(np.asarray(phi_deg, float)
                                                                               - ten.arm_angle_deg)


def _wrap180(a):
    return (np.asarray(a, float) + 180.0) % 360.0 - 180.0


def nominal_angle_deg(pulleys, ten, belt) -> dict:
    """The nominal arm angle and spring of a tensioner stated by its stops and spring (before a :class:`Drive`
    exists): ``ten`` holds ``free_arm_angle_deg``, ``preload_nm``, ``stiffness_nm_per_deg`` and either
    ``nominal_torque_nm`` (the report's "spring mean load": ``rel = (M_nom - preload) / k``) or nothing, when
    ``belt`` (its ``length_mm``, ``ribs``, elongation stiffness and measuring tension) sets it: the angle at
    which the path on the effective line equals the belt's length stretched by the arm's own tension.

    Returns ``arm_angle_deg``, ``nominal_torque_nm``, ``sense``.
    """
    fr = frame(pulleys, (ten["pivot_x_mm"], ten["pivot_y_mm"]), ten["arm_length_mm"], ten["free_arm_angle_deg"])
    free = ten["free_arm_angle_deg"]
    s = loading_sense(fr, free)
    k = ten["stiffness_nm_per_deg"]
    if ten.get("nominal_torque_nm") is not None:
        rel = (ten["nominal_torque_nm"] - ten["preload_nm"]) / k
        if rel < 0:
            raise InputError(Problem("tensioner.nominal_torque_nm", ten["nominal_torque_nm"],
                                     f"a torque above preload_nm = {ten['preload_nm']:g} Nm (below it the arm rests "
                                     "on its free-arm stop)"))
        return {"arm_angle_deg": free + s * rel, "nominal_torque_nm": ten["nominal_torque_nm"], "sense": s}
    length = belt["length_mm"]

    def gap(rel):
        st = arm_state(fr, free + s * rel)
        dl = abs(float(st["dl_dphi_mm"][0])) / 1000.0
        tension = (ten["preload_nm"] + k * rel) / dl
        stretched = length + elongation_mm(length, tension, belt["ribs"], belt["elongation_stiffness_per_rib_n"],
                                           belt["measuring_tension_per_rib_n"])
        return float(st["drive_length_mm"][0]) - stretched

    hi = _reach(fr, free, s, ten.get("installation_angle_deg"))
    grid = np.linspace(0.0, hi, 91)
    vals = np.array([gap(r) for r in grid])
    if not vals[0] > 0:
        raise InputError(Problem("belt.length_mm", length, "a belt shorter than the path with the arm at its free "
                                 f"angle ({vals[0] + length:.1f} mm stretched; the belt would hang slack)"))
    j = np.flatnonzero(np.isfinite(vals) & (vals <= 0))
    if not len(j):
        raise InputError(Problem("belt.length_mm", length, "a belt the arm can tension before its installation "
                                 "stop (or before the belt leaves the pulley): a longer belt"))
    from scipy.optimize import brentq  # here: a design without a drive never loads scipy.optimize
    rel = brentq(gap, grid[j[0] - 1], grid[j[0]], xtol=1e-10)
    return {"arm_angle_deg": free + s * rel, "nominal_torque_nm": ten["preload_nm"] + k * rel, "sense": s}


def _reach(fr, free, s, installation):
    """How far the arm can turn from the free arm [deg]: to the installation stop, or to where the belt leaves the
    pulley (at most 180 deg)."""
    if installation is not None:
        return abs(float(_wrap180(installation - free)))
    rel = np.linspace(0.0, 180.0, 361)
    ok = arm_state(fr, free + s * rel)["ok"]
    bad = np.flatnonzero(~ok)
    return float(rel[bad[0] - 1]) if len(bad) else 180.0


def _state_row(fr, ten, sense, phi, name, t_nom=None):
    st = arm_state(fr, phi)
    dl = abs(float(st["dl_dphi_mm"][0]))
    m = float(spring_torque_nm(ten, sense, phi))
    tension = m / (dl / 1000.0)
    wrap = float(st["wrap_deg"][0])
    c = st["centres"][0, fr["t"]]
    return {"position": name, "arm_angle_deg": float(np.mod(phi, 360.0)),
            "from_free_arm_deg": (float(sense * _wrap180(phi - ten.free_arm_angle_deg)) + 0.0
                                  if ten.free_arm_angle_deg is not None else None),
            "from_nominal_deg": float(sense * _wrap180(phi - ten.arm_angle_deg)) + 0.0,
            "centre_x_mm": float(c[0]), "centre_y_mm": float(c[1]), "beta_deg": float(st["beta_deg"][0]),
            "hub_direction_deg": float(st["hub_direction_deg"][0]),
            "hub_load_n": 2.0 * tension * np.sin(np.radians(wrap) / 2.0), "tension_n": tension, "wrap_deg": wrap,
            "drive_length_mm": float(st["drive_length_mm"][0]), "spring_torque_nm": m,
            "take_up_mm_per_deg": dl * np.pi / 180.0, "found": True,
            "span_length_mm": st["geometry"]["length_mm"][0].tolist(),
            "pulley_wrap_deg": np.degrees(st["geometry"]["wrap_rad"][0]).tolist()}


def positions(drive) -> dict:
    """The tensioner table: every position the drive states (free arm, worn, longest, nominal, shortest,
    installation), each a dict of :func:`_state_row`'s values, and the belt lengths they stand for.

    A position beyond a stop is ``found: False`` with ``beyond_mm``: how much longer (worn, longest) or shorter
    (shortest) the belt is than the arm can take up.
    """
    ten = drive.tensioner
    fr = frame_of(drive)
    s = drive.loading_sense
    nom = _state_row(fr, ten, s, ten.arm_angle_deg, "nominal")
    l_n = nom["drive_length_mm"]
    length = drive.belt_length_mm if drive.belt_length_mm is not None else l_n
    tol = drive.belt_length_tolerance_mm
    hot = drive.belt_thermal_change_pct / 100.0 * length
    targets = {"worn": l_n + tol + max(hot, 0.0) + (length + tol) * drive.belt_wear_pct / 100.0,
               "longest": l_n + tol + max(hot, 0.0), "shortest": l_n - tol + min(hot, 0.0)}
    # the arm's reach from nominal [deg, loading sense]: to its stops, or 90 deg either way
    lo = -90.0 if ten.free_arm_angle_deg is None else float(s * _wrap180(ten.free_arm_angle_deg - ten.arm_angle_deg))
    hi = 90.0 if ten.installation_angle_deg is None else float(s * _wrap180(ten.installation_angle_deg
                                                                            - ten.arm_angle_deg))
    psi = np.linspace(lo, hi, 721)
    grid = arm_state(fr, ten.arm_angle_deg + s * psi)["drive_length_mm"]
    rows = []
    if ten.free_arm_angle_deg is not None:
        rows.append(_state_row(fr, ten, s, ten.free_arm_angle_deg, "free arm"))
    for name in ("worn", "longest"):
        rows.append(_solve(fr, ten, s, psi, grid, targets[name], name))
    rows.append(nom)
    rows.append(_solve(fr, ten, s, psi, grid, targets["shortest"], "shortest"))
    if ten.installation_angle_deg is not None:
        rows.append(_state_row(fr, ten, s, ten.installation_angle_deg, "installation"))
    required = None
    if drive.belt_ribs:
        stretch = elongation_mm(length, nom["tension_n"], drive.belt_ribs, drive.belt_elongation_stiffness_per_rib_n,
                                drive.belt_measuring_tension_per_rib_n)
        required = stretch
        for r in rows:
            if r["found"]:
                r["required_belt_length_mm"] = r["drive_length_mm"] - stretch
    return {"rows": rows, "targets_mm": targets, "nominal_drive_length_mm": l_n, "belt_length_mm": length,
            "elongation_mm": required, "sense": s}


def _solve(fr, ten, s, psi, grid, target, name):
    """The position where the drive length is ``target``: bracketed on the grid (the path shortens as the arm
    loads), then :func:`scipy.optimize.brentq`."""
    f = grid - target
    ok = np.isfinite(f)
    if not ok.any():
        return {"position": name, "found": False, "beyond_mm": float("nan"), "target_mm": target}
    first, last = np.flatnonzero(ok)[[0, -1]]
    if f[first] < 0:   # the belt is longer than the path at the free arm: beyond the free-arm stop
        return {"position": name, "found": False, "beyond_mm": float(-f[first]), "stop": "free arm",
                "target_mm": target}
    if f[last] > 0:
        return {"position": name, "found": False, "beyond_mm": float(f[last]), "stop": "installation",
                "target_mm": target}
    j = first + int(np.flatnonzero(f[first:last + 1] <= 0)[0])
    if j == first:
        phi = ten.arm_angle_deg + s * psi[j]
    else:
        from scipy.optimize import brentq
        phi = ten.arm_angle_deg + s * brentq(
            lambda p: float(arm_state(fr, ten.arm_angle_deg + s * p)["drive_length_mm"][0]) - target,
            psi[j - 1], psi[j], xtol=1e-10)
    return {**_state_row(fr, ten, s, phi, name), "target_mm": target}


def travels(drive, table: dict | None = None) -> dict:
    """The arm's travels a tensioner is designed to [deg]: nominal to installation, nominal to free arm, and the
    working range over the belt's tolerance, wear and thermal change (shortest to worn), from :func:`positions`."""
    table = table or positions(drive)
    by = {r["position"]: r for r in table["rows"]}
    out = {}
    if "installation" in by:
        out["nominal_to_installation_deg"] = by["installation"]["from_nominal_deg"]
    if "free arm" in by:
        out["nominal_to_free_deg"] = -by["free arm"]["from_nominal_deg"]
    if by["worn"]["found"] and by["shortest"]["found"]:
        out["working_range_deg"] = by["shortest"]["from_nominal_deg"] - by["worn"]["from_nominal_deg"]
    return out


def duty_table(drive) -> dict:
    """Span tensions and hub loads at every duty point, the arm at its nominal position.

    Returns ``speed_rpm``, ``time_pct``, ``belt_speed_m_s`` per point and, per point and pulley (in the drive's
    order), ``tension_n`` (the span leaving the pulley, in the travel direction), ``hub_load_n``,
    ``hub_direction_deg`` and ``load_w`` (each pulley's power; the crank's negative: it gives).
    """
    ten = drive.tensioner
    fr = frame_of(drive)
    st = arm_state(fr, ten.arm_angle_deg, strict=True)
    u = st["geometry"]["direction"][0]
    n = len(drive.pulleys)
    t, c = drive.tensioner_index, drive.crank_index
    r = fr["radii"] / 1000.0
    names = fr["names"]
    points = drive.duty
    m = len(points)
    speed = np.array([p.speed_rpm for p in points], dtype=float)
    v = 2.0 * np.pi * speed / 60.0 * r[c]                                       # belt speed [m/s]
    power = np.zeros((m, n))
    for k, p in enumerate(points):
        for name, kw in p.power_kw:
            power[k, names.index(name)] += 1000.0 * kw
        for name, nm in p.torque_nm:
            i = names.index(name)
            power[k, i] += nm * v[k] / r[i]                                   # P = Q omega_i, omega_i = v / r_i
    power[:, c] = -(power.sum(axis=1) - power[:, c])
    step = power / v[:, None]                                                 # tension rise across each pulley [N]
    # the span arriving at the tensioner carries the nominal tension (the reports' anchor); the pulley's own loss
    # (a bearing's drag) moves the arm's balance by a fraction of a newton-metre, far inside the arm's friction
    t_in = np.full(m, 1000.0 * ten.nominal_torque_nm / abs(float(st["dl_dphi_mm"][0])))
    tension = np.zeros((m, n))                                                # span j leaves pulley j
    tension[:, (t - 1) % n] = t_in
    for k in range(n):
        j = (t + k) % n
        tension[:, j] = tension[:, (j - 1) % n] + step[:, j]
    hub = tension[:, :, None] * u[None] - np.roll(tension, 1, axis=1)[:, :, None] * np.roll(u, 1, axis=0)[None]
    return {"speed_rpm": speed, "time_pct": np.array([np.nan if p.time_pct is None else p.time_pct for p in points]),
            "belt_speed_m_s": v, "tension_n": tension, "hub_load_n": np.hypot(hub[..., 0], hub[..., 1]),
            "hub_direction_deg": np.mod(np.degrees(np.arctan2(hub[..., 1], hub[..., 0])), 360.0),
            "load_w": power, "pulleys": list(names),
            "spans": [f"{names[j]}-{names[(j + 1) % n]}" for j in range(n)]}
