"""The drive's linear rotational model and its natural frequencies and modes.

Degrees of freedom: the rotation ``theta_i`` of every pulley but the crank
(positive in its running direction, so the belt passes at ``r_i theta_i``
whatever side it wraps) and the arm's take-up angle ``psi``. The crank's
rotation is prescribed (the excitation). Span ``j`` (from pulley ``a`` to
``b`` in travel order) stretches by

    e_j = r_b theta_b - r_a theta_a + g_j psi                   (g_j: take-up, m/rad)

and carries ``T_j = T0_j + k_j e_j + c_j de_j/dt`` with ``k_j = EA / L_j`` and
``c_j = c' / L_j`` (the belt's stiffness ``EA`` [N] and damping ``c'`` [N s]
per unit strain, spread over the span length; Hwang, Perkins and Ulsoy 1994,
Beikmann, Perkins and Ulsoy 1996, discrete rotational model). With
``e = B q + b_c theta_c`` the equations of motion are

    M q'' + (B^T C_s B + C_p) q' + (B^T K_s B + K_p) q
        = -B^T (K_s b_c theta_c + C_s b_c theta_c') - e_arm T_f(psi'),

``M = diag(J_i, J_arm)``, ``K_p`` the arm's spring rate plus the tensioned
path's geometric stiffness ``T_t d^2L/dpsi^2``, ``C_p`` the bearings' and the
arm's viscous damping, ``T_f`` the arm's dry friction (:mod:`synth.drive.friction`).
The natural frequencies solve ``det(K - w^2 M) = 0`` (:func:`scipy.linalg.eigh`),
with the arm free (friction slipping) or locked (its row and column removed).

Units: SI inside (m, N, kg m^2, rad, s); frequencies in Hz.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from synth.drive.statics import static_state
from synth.errors import InputError, Problem

__all__ = ["LinearDrive", "linear_drive", "natural_frequencies", "system_modes"]


@dataclass(frozen=True)
class LinearDrive:
    """The assembled linear drive (SI units); ``arm`` is the index of the arm's degree of freedom."""

    M: np.ndarray
    C: np.ndarray
    K: np.ndarray
    B: np.ndarray          # (spans, dofs) stretch per coordinate [m]
    b_crank: np.ndarray    # (spans,) stretch per radian of crank rotation [m]
    k_span: np.ndarray     # (spans,) [N/m]
    c_span: np.ndarray     # (spans,) [N s/m]
    tension0_n: np.ndarray
    arm: int
    pulley_dof: tuple      # the pulley index of each rotational degree of freedom (dofs but the arm)
    dofs: tuple
    span_names: tuple
    static: dict


def linear_drive(drive, static: dict | None = None, *, crank_free: bool = False,
                 ea_n: float | None = None) -> LinearDrive:
    """Assemble ``M, C, K, B`` of a validated drive about its static state.

    ``ea_n``: the belt's EA instead of the drive's [N]. ``crank_free``: the crank is a degree of freedom with its inertia (the free system whose modes a drive
    report lists: a rigid rotation of every pulley at frequency 0 comes first), instead of a prescribed motion.

    >>> from synth.drive.inputs import example_drive
    >>> m = linear_drive(example_drive())
    >>> m.dofs, m.K.shape
    (('TEN', 'CAM', 'IDL', 'WP', 'arm'), (5, 5))
    """
    s = static if static is not None else static_state(drive)
    p = drive.pulleys
    n = len(p)
    crank = -1 if crank_free else drive.crank_index
    free = [i for i in range(n) if i != crank]
    col = {i: k for k, i in enumerate(free)}
    nd = len(free) + 1
    arm = nd - 1
    r_m = s["radii_mm"] / 1000.0
    B = np.zeros((n, nd))
    b_c = np.zeros(n)
    for j in range(n):  # span j from pulley j to pulley j + 1
        a, b = j, (j + 1) % n
        for idx, sign in ((b, 1.0), (a, -1.0)):
            if idx == crank:
                b_c[j] += sign * r_m[idx]
            else:
                B[j, col[idx]] += sign * r_m[idx]
        B[j, arm] = s["take_up_dl_mm_per_rad"][j] / 1000.0
    length_m = s["span_length_mm"] / 1000.0
    k_span = drive.belt_stiffness_n / length_m if ea_n is None else ea_n / length_m
    c_span = drive.belt_damping_n_s / length_m
    ten = drive.tensioner
    missing = [p[i].name for i in free if p[i].inertia_kg_m2 is None] + (
        ["tensioner arm"] if ten.inertia_kg_m2 is None else [])
    if missing:
        raise InputError(Problem("inertia_kg_m2", ", ".join(missing), "an inertia for every pulley that turns and for "
                                 "the tensioner arm (the drive's modes and response need them)"))
    J = np.array([p[i].inertia_kg_m2 for i in free] + [ten.arm_inertia_kg_m2])
    M = np.diag(J)
    k_arm = np.degrees(1.0) * ten.stiffness_nm_per_deg + s["tensioner_tension_n"] * s["path_d2_mm_per_rad2"] / 1000.0
    Kp = np.zeros((nd, nd))
    Kp[arm, arm] = k_arm
    Cp = np.diag([p[i].damping_nm_s_per_rad for i in free] + [ten.damping_nm_s_per_rad])
    K = B.T @ (k_span[:, None] * B) + Kp
    C = B.T @ (c_span[:, None] * B) + Cp
    names = tuple(p[i].name for i in free) + ("arm",)
    spans = tuple(f"{p[j].name}-{p[(j + 1) % n].name}" for j in range(n))
    return LinearDrive(M, C, K, B, b_c, k_span, c_span, np.asarray(s["tension_n"], float), arm, tuple(free), names,
                       spans, s)


def natural_frequencies(model: LinearDrive, arm_locked: bool = False) -> dict:
    """Undamped natural frequencies [Hz] and mass-normalised mode shapes (columns, one per mode).

    ``arm_locked`` removes the arm's degree of freedom (the friction sticks). Two equal pulleys on two equal
    spans (crank fixed) give ``f = sqrt(2 k r^2 / J) / 2 pi``: a hand calculation the tests check.
    """
    from scipy.linalg import eigh
    keep = [i for i in range(len(model.dofs)) if not (arm_locked and i == model.arm)]
    K = model.K[np.ix_(keep, keep)]
    M = model.M[np.ix_(keep, keep)]
    w2, vec = eigh(K, M)
    f = np.sqrt(np.clip(w2, 0.0, None)) / (2.0 * np.pi)
    return {"frequency_hz": f, "modes": vec, "dofs": tuple(model.dofs[i] for i in keep)}


def system_modes(drive, ea_per_rib_n: float | None = None, count: int = 3) -> dict:
    """The free system's first ``count`` modes [Hz] (crank free with its inertia, the arm free), as a drive
    report's vibration page lists them: the rigid rotation (0 Hz) left out.

    ``ea_per_rib_n``: the spans' EA per rib instead of the drive's (a belt of ``ribs``); the drive's EA otherwise.
    Returns ``frequency_hz``, the mode shapes (columns) and the degrees of freedom.
    """
    if ea_per_rib_n is not None and not drive.belt_ribs:
        raise InputError(Problem("belt.ribs", None, "a value (EA per rib needs the belt's ribs)"))
    ea = None if ea_per_rib_n is None else ea_per_rib_n * drive.belt_ribs
    model = linear_drive(drive, crank_free=True, ea_n=ea)
    from scipy.linalg import eigh
    w2, vec = eigh(model.K, model.M)
    f = np.sqrt(np.clip(w2, 0.0, None)) / (2.0 * np.pi)
    keep = np.arange(1, min(len(f), count + 1))  # the first is the rigid rotation of the whole drive
    return {"frequency_hz": f[keep], "modes": vec[:, keep], "dofs": model.dofs}
