"""Step 4 of the thesis flowchart: the pivot bushing (a metal-polymer plain bearing), eq. (28)-(42).

The pivot bushing (a metal-polymer sleeve pressed into the arm, sliding on the
pivot) carries the hubload. This module computes, for thousands of designs at
once (numpy broadcasting, no loops over designs):

* the mean projected pressure, eq. (28), the mean sliding speed of the
  durability test, eq. (29), and the p*v and p*v*t terms, eq. (30)-(31),
  which the supplier thresholds of thesis Table 5 (dry / BIO) limit;
* the bushing wear over the durability test, eq. (32), in two fidelities:
  ``"screening"`` (closed form, constant pressure) and ``"full"``
  (running-in of a clearance fit, integrated with :func:`scipy.integrate.solve_ivp`);
* the maximum bushing length on the pivot, eq. (33)-(34);
* the end reactions and end pressures from the tilting moment of a belt plane
  that is not centred on the bushing, eq. (35)-(39), the end wear by Reye's
  hypothesis, eq. (40)-(41), and the pulley parallelism at end of life, eq. (42).

Verdicts are not made here: the limits (Table 5, eq. (33)-(34), the input's
parallelism) and the constraints live in :mod:`synth.design.constraints`.

Units: lengths in mm, forces in N, pressures in MPa (N/mm2), speeds in m/s,
durations in h, wear constants in mm3/(N*m) (= mm per MPa per metre slid).

>>> r = evaluate_bushing(652.5, 16.0, 16.0, 16.0, 50.0, 1200.0, k_w_mm3_per_n_m=1e-8,
...                      radial_clearance_mm=0.03, belt_plane_height_mm=29.5,
...                      max_pivot_height_mm=40.0, axial_damping=True, pulley_diameter_mm=66.0)
>>> round(float(r["p_mpa"]), 3), round(float(r["pvt_mpa_m_per_s_h"]), 1), float(r["length_max_mm"])
(2.549, 683.2, 26.0)
"""

from __future__ import annotations

import functools

import numpy as np

from synth import catalog
from synth.errors import InputError, Problem
from synth.model.friction_wear import sliding_speed_m_per_s as at_radius

__all__ = [
    "ENVIRONMENTS", "FIDELITIES", "PRESSURE_MODELS",
    "bushing_pressure_mpa", "sliding_speed_m_per_s", "pv_mpa_m_per_s", "pvt_mpa_m_per_s_h",
    "wear_mm", "max_bushing_length_mm", "bushing_eccentricity_mm",
    "end_reactions_n", "end_pressures_mpa", "pulley_parallelism_mm", "evaluate_bushing",
]

ENVIRONMENTS = ("dry", "belt_in_oil")
FIDELITIES = ("screening", "full")
#: "linear": rigid arm on rigid pivot, pressure linear along the bushing (force + moment
#: equilibrium; the only distribution that Reye's wear law keeps unchanged in time).
#: "two_point": the thesis's eq. (36)-(39), each end reaction spread over half the length.
PRESSURE_MODELS = {"linear": 6.0, "two_point": 2.0}

_SECONDS_PER_HOUR = 3600.0


# --------------------------------------------------------------------------- eq. (28)-(31)
def bushing_pressure_mpa(hubload_n, sliding_diameter_mm, length_mm):
    """Mean projected pressure on the bushing, eq. (28): ``p = HL / (D * L)`` [MPa].

    ``D`` is the sliding diameter (the pivot diameter, i.e. the bushing bore):
    the thesis prints the bushing *external* diameter; the load is carried on
    the bore, and supplier ratings (Table 5, GGB) use ``F / (D_bore * L)``.

    >>> float(bushing_pressure_mpa(652.5, 16.0, 16.0))
    2.548828125
    """
    hl, d, length = (np.asarray(x, dtype=float) for x in (hubload_n, sliding_diameter_mm, length_mm))
    return hl / (d * length)


def sliding_speed_m_per_s(theta_peak_to_peak_deg, frequency_hz, sliding_diameter_mm):
    """Mean sliding speed of the durability oscillation, eq. (29) [m/s].

    ``v = 2 * theta_pp * pi * (D/2) * f / 180``: each cycle sweeps the
    peak-to-peak angle twice; the plastic elements' eq. (46)/(49) at the
    radius ``D/2`` (:func:`synth.model.friction_wear.sliding_speed_m_per_s`).

    >>> round(float(sliding_speed_m_per_s(16.0, 50.0, 16.0)), 5)
    0.22340
    """
    return at_radius(theta_peak_to_peak_deg, 0.5 * np.asarray(sliding_diameter_mm, dtype=float), frequency_hz)


def pv_mpa_m_per_s(p_mpa, v_m_per_s):
    """The p*v term, eq. (30) [MPa*m/s].

    >>> float(pv_mpa_m_per_s(2.0, 0.25))
    0.5
    """
    return np.asarray(p_mpa, dtype=float) * np.asarray(v_m_per_s, dtype=float)


def pvt_mpa_m_per_s_h(p_mpa, v_m_per_s, duration_h):
    """The p*v*t term, eq. (31) [MPa*m/s*h] (durability test duration in hours).

    >>> float(pvt_mpa_m_per_s_h(2.0, 0.25, 1200.0))
    600.0
    """
    return pv_mpa_m_per_s(p_mpa, v_m_per_s) * np.asarray(duration_h, dtype=float)


# --------------------------------------------------------------------------- eq. (32), (40)-(41)
def _conformity_factor(u):
    """Running-in factor (pi/2) / g(phi0) of a clearance fit worn to u = w / c.

    The worn arc has half-angle phi0 = arccos(1 / (1 + u)); Reye's law with a
    rigid pivot gives p(phi) = p0 cos(phi) over it, and radial equilibrium
    HL = p0 R L (phi0 + sin phi0 cos phi0). The factor is the load-line pressure
    relative to its run-in value (phi0 = 90 deg), so it is 1 when run in and
    grows without bound (integrably, ~ u**-0.5) at the first contact.

    >>> float(_conformity_factor(1e9))
    1.0
    """
    u = np.maximum(np.asarray(u, dtype=float), 0.0)
    phi0 = np.arccos(1.0 / (1.0 + u))
    g = phi0 + np.sin(phi0) * np.cos(phi0)
    return (np.pi / 2.0) / np.maximum(g, np.finfo(float).tiny)


# Seed of the universal running-in ODE (numerics, not physics): u0 = w0 / c, and
# the dimensionless time tau0 reached by the small-u asymptote du/dtau = pi/(4 sqrt(2u)).
_U0 = 1e-6
_TAU0 = 8.0 * np.sqrt(2.0) / (3.0 * np.pi) * _U0 ** 1.5


@functools.lru_cache(maxsize=32)
def _running_in_curve(tau_max: float):
    """Dense solution u(tau) of du/dtau = F(u) on [tau0, tau_max] (solve_ivp, cached)."""
    from scipy.integrate import solve_ivp  # imported here: only the running-in option needs scipy
    sol = solve_ivp(lambda t, u: _conformity_factor(u), (_TAU0, max(tau_max, 2 * _TAU0)), [_U0],
                    method="LSODA", dense_output=True, rtol=1e-8, atol=1e-12)
    return sol


def _running_in_u(tau):
    """u(tau) of the running-in ODE for any tau >= 0 (vectorised)."""
    tau = np.maximum(np.asarray(tau, dtype=float), 0.0)
    tau_max = float(np.max(tau)) if tau.size else 0.0
    # round the horizon up so the cache is reused across calls
    horizon = float(10.0 ** np.ceil(np.log10(max(tau_max, 1.0))))
    sol = _running_in_curve(horizon)
    small = tau <= _TAU0
    u_small = (tau * 3.0 * np.pi / (8.0 * np.sqrt(2.0))) ** (2.0 / 3.0)
    u_big = sol.sol(np.clip(tau, _TAU0, horizon).ravel())[0].reshape(tau.shape)
    return np.where(small, u_small, u_big)


def wear_mm(k_w_mm3_per_n_m, p_mpa, v_m_per_s, duration_h, *, fidelity="screening", radial_clearance_mm=0.0):
    """Bushing wear depth after the durability test, eq. (32) and (40)-(41) [mm].

    ``fidelity="screening"``: closed form of eq. (32) at constant pressure,
    ``w = k_w * p * v * t`` (k_w in mm3/(N*m) = mm/(MPa*m), t in s).

    ``fidelity="full"``: the fit starts with radial clearance ``c``; the worn
    arc widens as the wear grows (half-angle ``arccos(c / (c + w))``), so the
    contact pressure at the load line falls from very high values to the
    run-in value and ``dw/dt = k_w * v * p * F(w / c)`` with ``F >= 1``
    (``F -> 1`` when run in). Integrated with ``solve_ivp`` on the universal
    dimensionless curve. Full wear >= screening wear; the difference tends to a
    constant of the order of the clearance.

    ``p`` may be negative (end reaction on the opposite side): the wear keeps
    its sign (displacement of the arm against the pressure direction).

    >>> round(float(wear_mm(1e-8, 2.5488, 0.2234, 1200.0)), 4)
    0.0246
    >>> bool(wear_mm(1e-8, 2.5488, 0.2234, 1200.0, fidelity="full", radial_clearance_mm=0.03)
    ...      > wear_mm(1e-8, 2.5488, 0.2234, 1200.0))
    True
    """
    if fidelity not in FIDELITIES:
        raise InputError(Problem("fidelity", fidelity, " or ".join(FIDELITIES)))
    k, p, v, t = (np.asarray(x, dtype=float) for x in (k_w_mm3_per_n_m, p_mpa, v_m_per_s, duration_h))
    t_s = np.maximum(t, 0.0) * _SECONDS_PER_HOUR
    w_screen = k * np.abs(p) * v * t_s
    if fidelity == "screening":
        return np.sign(p) * w_screen
    c = np.asarray(radial_clearance_mm, dtype=float)
    c_safe = np.where(c > 0.0, c, 1.0)
    u = _running_in_u(np.broadcast_to(w_screen / c_safe, np.broadcast_shapes(w_screen.shape, c.shape)))
    return np.sign(p) * np.where(c > 0.0, c_safe * u, w_screen)


# --------------------------------------------------------------------------- eq. (33)-(34)
def max_bushing_length_mm(max_pivot_height_mm, axial_damping):
    """Longest bushing that fits on the pivot, eq. (33) (radial damping only) and (34).

    ``L_max = h_pivot_max - gap_crank - gap_head``, gaps from
    ``constants_bushing.csv`` (larger with the axial damping group).

    >>> float(max_bushing_length_mm(40.0, True)), float(max_bushing_length_mm(34.0, False))
    (26.0, 25.0)
    """
    h, ax = np.asarray(max_pivot_height_mm, dtype=float), np.asarray(axial_damping, dtype=bool)
    return h - _gap_crank_mm(ax) - np.where(ax, catalog.constant("bush_gap_head_ax_damp_mm"),
                                            catalog.constant("bush_gap_head_no_ax_damp_mm"))


def _gap_crank_mm(axial_damping):
    return np.where(axial_damping, catalog.constant("bush_gap_crank_ax_damp_mm"),
                    catalog.constant("bush_gap_crank_no_ax_damp_mm"))


def bushing_eccentricity_mm(length_mm, belt_plane_height_mm, max_pivot_height_mm, axial_damping):
    """Axial offset ``e`` of the belt plane above the bushing centre [mm].

    The bushing is centred on the belt middle plane as far as the available
    span ``[gap_crank, h_pivot_max - gap_head]`` (eq. 33-34) allows; ``e > 0``
    when the belt plane lies above the centre (towards the pivot head). The
    thesis gives the distances ``a``, ``b`` of eq. (36)-(37) without a rule:
    ``a = L/2 + e``, ``b = L/2 - e``.

    >>> float(bushing_eccentricity_mm(16.0, 29.5, 40.0, True))
    3.5
    """
    length, mpbh = np.asarray(length_mm, dtype=float), np.asarray(belt_plane_height_mm, dtype=float)
    ax = np.asarray(axial_damping, dtype=bool)
    z_lo = _gap_crank_mm(ax)
    z_hi = z_lo + max_bushing_length_mm(max_pivot_height_mm, ax)
    lo, hi = z_lo + length / 2.0, z_hi - length / 2.0
    centre = np.clip(mpbh, np.minimum(lo, hi), np.maximum(lo, hi))
    return mpbh - centre


# --------------------------------------------------------------------------- eq. (35)-(39), (42)
def end_reactions_n(hubload_n, eccentricity_mm, length_mm):
    """End reactions at the lower (A) and upper (B) bushing ends, eq. (35)-(37) [N].

    ``R_A = HL * b / (a + b)``, ``R_B = HL * a / (a + b)`` with ``a = L/2 + e``,
    ``b = L/2 - e``; a negative reaction acts on the opposite side of the pivot
    (belt plane outside the bushing). ``R_A + R_B = HL`` always (eq. 35).

    >>> [float(x) for x in end_reactions_n(600.0, 2.0, 16.0)]
    [225.0, 375.0]
    """
    hl, e, length = (np.asarray(x, dtype=float) for x in (hubload_n, eccentricity_mm, length_mm))
    a, b = length / 2.0 + e, length / 2.0 - e
    return hl * b / length, hl * a / length


def end_pressures_mpa(p_mean_mpa, eccentricity_mm, length_mm, *, model="linear"):
    """Pressure at the lower (A) and upper (B) bushing ends [MPa], eq. (38)-(39).

    ``p_A,B = p_mean * (1 -/+ c * e / L)``. ``model="two_point"`` (thesis,
    eq. 38-39: each end reaction over half the length) has ``c = 2``;
    ``model="linear"`` (default: rigid arm, rigid pivot, pressure linear along
    the bushing from force and moment equilibrium) has ``c = 6``. The linear
    distribution is the one Reye's law (wear proportional to p*v) leaves
    unchanged as the bushing wears; the two-point one does not.

    >>> [round(float(x), 3) for x in end_pressures_mpa(2.0, 2.0, 16.0, model="two_point")]
    [1.5, 2.5]
    >>> [round(float(x), 3) for x in end_pressures_mpa(2.0, 2.0, 16.0)]
    [0.5, 3.5]
    """
    if model not in PRESSURE_MODELS:
        raise InputError(Problem("pressure_model", model, " or ".join(PRESSURE_MODELS)))
    c = PRESSURE_MODELS[model]
    p, e, length = (np.asarray(x, dtype=float) for x in (p_mean_mpa, eccentricity_mm, length_mm))
    return p * (1.0 - c * e / length), p * (1.0 + c * e / length)


def pulley_parallelism_mm(pulley_diameter_mm, wear_a_mm, wear_b_mm, length_mm):
    """Pulley parallelism error from uneven bushing wear, eq. (42) [mm].

    ``// = D_pulley * |w_B - w_A| / L`` (tilt of the arm times the pulley
    diameter; signed wears, so opposite-side wear adds).

    >>> float(pulley_parallelism_mm(66.0, 0.01, 0.03, 16.0))
    0.0825
    """
    d, wa, wb, length = (np.asarray(x, dtype=float) for x in (pulley_diameter_mm, wear_a_mm, wear_b_mm, length_mm))
    return d * np.abs(wb - wa) / length


# --------------------------------------------------------------------------- the step
def evaluate_bushing(hubload_n, pivot_diameter_mm, length_mm, theta_peak_to_peak_deg, frequency_hz, duration_h,
                     *, k_w_mm3_per_n_m, radial_clearance_mm, belt_plane_height_mm, max_pivot_height_mm,
                     axial_damping, pulley_diameter_mm, fidelity="screening", pressure_model="linear"):
    """All of step 4 for given bushings (vectorised, every argument broadcasts): eq. (28)-(42).

    ``k_w_mm3_per_n_m`` and ``radial_clearance_mm`` are the supplier's wear
    constant for the environment and fit clearance (``catalogs/pivot_bushings.csv``).
    Returns a dict of arrays: ``p_mpa``, ``v_m_per_s``, ``pv_mpa_m_per_s``,
    ``pvt_mpa_m_per_s_h`` (eq. 28-31); ``wear_mean_mm`` (eq. 32), ``wear_a_mm``,
    ``wear_b_mm`` (lower/upper end, eq. 40-41), ``wear_max_mm``,
    ``eccentricity_mm``, ``p_a_mpa``, ``p_b_mpa``, ``reaction_a_n``,
    ``reaction_b_n``, ``parallelism_mm`` (eq. 42) and ``length_max_mm`` (eq. 33-34).
    The end wear uses the bushing's own pressure model; the reactions are the
    thesis's eq. (36)-(37) whatever the model. Invalid geometry gives NaN, never an exception.
    """
    with np.errstate(divide="ignore", invalid="ignore"):
        length = np.asarray(length_mm, dtype=float)
        p = bushing_pressure_mpa(hubload_n, pivot_diameter_mm, length)
        v = sliding_speed_m_per_s(theta_peak_to_peak_deg, frequency_hz, pivot_diameter_mm)
        pv = pv_mpa_m_per_s(p, v)
        pvt = pvt_mpa_m_per_s_h(p, v, duration_h)
        e = bushing_eccentricity_mm(length, belt_plane_height_mm, max_pivot_height_mm, axial_damping)
        p_a, p_b = end_pressures_mpa(p, e, length, model=pressure_model)
        r_a, r_b = end_reactions_n(hubload_n, e, length)
        kw = dict(fidelity=fidelity, radial_clearance_mm=radial_clearance_mm)
        w_mean = wear_mm(k_w_mm3_per_n_m, p, v, duration_h, **kw)
        w_a, w_b = wear_mm(k_w_mm3_per_n_m, p_a, v, duration_h, **kw), wear_mm(k_w_mm3_per_n_m, p_b, v, duration_h, **kw)
        out = {
            "p_mpa": p, "v_m_per_s": v, "pv_mpa_m_per_s": pv, "pvt_mpa_m_per_s_h": pvt,
            "eccentricity_mm": e, "reaction_a_n": r_a, "reaction_b_n": r_b, "p_a_mpa": p_a, "p_b_mpa": p_b,
            "wear_mean_mm": w_mean, "wear_a_mm": w_a, "wear_b_mm": w_b,
            "wear_max_mm": np.maximum(np.abs(w_a), np.abs(w_b)),
            "parallelism_mm": pulley_parallelism_mm(pulley_diameter_mm, w_a, w_b, length),
            "length_max_mm": max_bushing_length_mm(max_pivot_height_mm, axial_damping),
        }
    shape = np.broadcast_shapes(*(np.shape(v) for v in out.values()))
    return {key: np.broadcast_to(val, shape) for key, val in out.items()}
