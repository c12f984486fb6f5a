"""Step 4 of the thesis flowchart: pivot bushing size selection, eq. (28)-(42).

The pivot bushing (a metal-polymer sleeve pressed into the arm, sliding on the
pivot) carries the hubload. This module computes, for thousands of designs at
once (numpy broadcasting, no loops over designs):

* the mean projected pressure, eq. (28), the mean sliding speed of the
  durability test, eq. (29), and the p*v and p*v*t terms, eq. (30)-(31),
  checked against the supplier thresholds of thesis Table 5 (dry / BIO);
* the bushing wear over the durability test, eq. (32), in two fidelities:
  ``"screening"`` (closed form, constant pressure) and ``"full"``
  (running-in of a clearance fit, integrated with :func:`scipy.integrate.solve_ivp`);
* the maximum bushing length on the pivot, eq. (33)-(34);
* the end reactions and end pressures from the tilting moment of a belt plane
  that is not centred on the bushing, eq. (35)-(39), the end wear by Reye's
  hypothesis, eq. (40)-(41), and the pulley parallelism at end of life, eq. (42);
* the "lengthen the bushing" iteration: the shortest candidate length that
  passes every check, vectorised over the candidate lengths.

Units: lengths in mm, forces in N, pressures in MPa (N/mm2), speeds in m/s,
durations in h, wear constants in mm3/(N*m) (= mm per MPa per metre slid).

>>> r = evaluate_bushing(652.5, 16.0, 16.0, 16.0, 50.0, 1200.0, supplier="A",
...                      environment="belt_in_oil", belt_plane_height_mm=29.5,
...                      max_pivot_height_mm=40.0, axial_damping=True,
...                      pulley_diameter_mm=66.0, parallelism_max_mm=0.3)
>>> round(float(r["p_mpa"]), 3), round(float(r["pvt_mpa_m_per_s_h"]), 1), bool(r["passes"])
(2.549, 683.2, True)
"""

from __future__ import annotations

import functools

import numpy as np
from scipy.integrate import solve_ivp

from synth import catalog
from synth.checks import Check, margin_lower, margin_upper
from synth.errors import InputError, Problem

__all__ = [
    "ENVIRONMENTS", "FIDELITIES", "PRESSURE_MODELS", "SCHEMES",
    "supplier_for_thickness", "supplier_limits", "available_lengths_mm",
    "bushing_pressure_mpa", "sliding_speed_m_per_s", "pv_mpa_m_per_s", "pvt_mpa_m_per_s_h",
    "wear_mm", "max_bushing_length_mm", "bushing_eccentricity_mm",
    "end_reactions_n", "end_pressures_mpa", "pulley_parallelism_mm",
    "evaluate_bushing", "select_bushing_length", "next_catalog_length_mm", "bushing_checks",
]

ENVIRONMENTS = ("dry", "belt_in_oil")
FIDELITIES = ("screening", "full")
#: "linear": rigid arm on rigid pivot, pressure linear along the bushing (force + moment
#: equilibrium; the only distribution that Reye's wear law keeps unchanged in time).
#: "two_point": the thesis's eq. (36)-(39), each end reaction spread over half the length.
PRESSURE_MODELS = {"linear": 6.0, "two_point": 2.0}
SCHEMES = ("catalog", "thesis")

_SECONDS_PER_HOUR = 3600.0
_MM_PER_M = 1000.0
_ENV_SUFFIX = {"dry": "dry", "belt_in_oil": "bio"}


# --------------------------------------------------------------------------- catalog access
def _check_environment(environment: str) -> str:
    if environment not in ENVIRONMENTS:
        raise InputError(Problem("application_type", environment, " or ".join(ENVIRONMENTS)))
    return _ENV_SUFFIX[environment]


def supplier_for_thickness(radial_thickness_mm: float) -> str:
    """The pivot-bushing supplier whose wall has the given radial thickness.

    Thesis step 2: one supplier offers a 1 mm wall, the other 0.5 mm.

    >>> supplier_for_thickness(1.0), supplier_for_thickness(0.5)
    ('A', 'B')
    """
    df = catalog.load("pivot_bushings")
    hit = df[np.isclose(df["radial_thickness_mm"].astype(float), float(radial_thickness_mm))]
    if hit.empty:
        raise InputError(Problem("pivot_bushing_radial_thickness_mm", radial_thickness_mm,
                                 "one of " + ", ".join(f"{t:g}" for t in df["radial_thickness_mm"])))
    return str(hit.iloc[0]["supplier"])


def supplier_limits(supplier: str, environment: str) -> dict:
    """Table 5 thresholds, wear constant, layer depth and clearance of one supplier.

    Returns ``p_max_mpa``, ``pv_max_mpa_m_per_s``, ``pvt_max_mpa_m_per_s_h``,
    ``k_w_mm3_per_n_m``, ``sliding_layer_depth_mm``, ``radial_clearance_mm``,
    ``radial_thickness_mm``. A supplier without a rating for the environment
    (Table 5 "NA") raises :class:`~synth.errors.InputError`.

    >>> supplier_limits("A", "belt_in_oil")["pvt_max_mpa_m_per_s_h"]
    850.0
    """
    suffix = _check_environment(environment)
    row = catalog.row("pivot_bushings", supplier, field="pivot_bushing_supplier")
    out = {
        "p_max_mpa": row[f"p_max_{suffix}_mpa"],
        "pv_max_mpa_m_per_s": row[f"pv_max_{suffix}_mpa_m_per_s"],
        "pvt_max_mpa_m_per_s_h": row[f"pvt_max_{suffix}_mpa_m_per_s_h"],
        "k_w_mm3_per_n_m": row[f"k_w_{suffix}_mm3_per_n_m"],
        "sliding_layer_depth_mm": row["sliding_layer_depth_mm"],
        "radial_clearance_mm": row["radial_clearance_mm"],
        "radial_thickness_mm": row["radial_thickness_mm"],
    }
    out = {k: float(v) for k, v in out.items()}
    if any(np.isnan(v) for v in out.values()):
        df = catalog.load("pivot_bushings")
        rated = [s for s in df["supplier"]
                 if not np.isnan(float(catalog.row("pivot_bushings", s)[f"pvt_max_{suffix}_mpa_m_per_s_h"]))]
        raise InputError(Problem("pivot_bushing_supplier", supplier,
                                 f"a supplier rated for {environment} (thesis Table 5): " + ", ".join(rated)))
    return out


def available_lengths_mm(supplier: str) -> np.ndarray:
    """The supplier's catalog lengths (ascending).

    >>> available_lengths_mm("B")[-3:]
    array([22., 25., 30.])
    """
    row = catalog.row("pivot_bushings", supplier, field="pivot_bushing_supplier")
    return np.sort(np.array([float(x) for x in str(row["lengths_mm"]).split(";") if x.strip()]))


def _positive(field, value):
    """``value`` as a float array; raises InputError if any entry is not > 0 (or not finite)."""
    arr = np.asarray(value, dtype=float)
    bad = ~(np.isfinite(arr) & (arr > 0.0))
    if np.any(bad):
        raise InputError(Problem(field, arr[bad].ravel()[0].item() if arr.ndim else arr.item(),
                                 "a finite value > 0"))
    return arr


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
    peak-to-peak angle twice.

    >>> round(float(sliding_speed_m_per_s(16.0, 50.0, 16.0)), 5)
    0.22340
    """
    th, f, d = (np.asarray(x, dtype=float) for x in (theta_peak_to_peak_deg, frequency_hz, sliding_diameter_mm))
    return 2.0 * np.deg2rad(th) * (d / 2.0) / _MM_PER_M * f


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


# --------------------------------------------------------------------------- high level
def evaluate_bushing(hubload_n, pivot_diameter_mm, length_mm, theta_peak_to_peak_deg, frequency_hz, duration_h,
                     *, supplier, environment, belt_plane_height_mm, max_pivot_height_mm, axial_damping,
                     pulley_diameter_mm, parallelism_max_mm, fidelity="screening", pressure_model="linear"):
    """All of step 4 for given bushing lengths (vectorised): eq. (28)-(42) and checks.

    Returns a dict (arrays broadcast over the inputs):

    * ``p_mpa``, ``v_m_per_s``, ``pv_mpa_m_per_s``, ``pvt_mpa_m_per_s_h`` (eq. 28-31);
    * ``wear_mean_mm`` (eq. 32), ``wear_a_mm``, ``wear_b_mm`` (lower/upper end, eq. 40-41),
      ``wear_max_mm``, ``eccentricity_mm``, ``p_a_mpa``, ``p_b_mpa``, ``reaction_a_n``,
      ``reaction_b_n``, ``parallelism_mm`` (eq. 42), ``length_max_mm`` (eq. 33-34);
    * margins (>= 0 passes): ``margin_p``, ``margin_pv``, ``margin_pvt`` (Table 5),
      ``margin_wear`` (end wear <= sliding-layer depth), ``margin_parallelism``
      (<= ``parallelism_max_mm``), ``margin_length`` (L <= L_max); ``passes`` (all).

    The end wear uses the bushing's own pressure model; the reactions are the
    thesis's eq. (36)-(37) whatever the model.
    """
    lim = supplier_limits(supplier, environment)
    d = _positive("pivot_diameter_mm", pivot_diameter_mm)
    length = _positive("pivot_bushing_length_mm", length_mm)
    _positive("pulley_diameter_mm", pulley_diameter_mm)
    _positive("pulley_max_parallelism_eol_mm", parallelism_max_mm)
    p = bushing_pressure_mpa(hubload_n, d, length)
    v = sliding_speed_m_per_s(theta_peak_to_peak_deg, frequency_hz, d)
    pv = pv_mpa_m_per_s(p, v)
    pvt = pvt_mpa_m_per_s_h(p, v, duration_h)
    e = bushing_eccentricity_mm(length, belt_plane_height_mm, max_pivot_height_mm, axial_damping)
    p_a, p_b = end_pressures_mpa(p, e, length, model=pressure_model)
    r_a, r_b = end_reactions_n(hubload_n, e, length)
    kw = dict(fidelity=fidelity, radial_clearance_mm=lim["radial_clearance_mm"])
    k = lim["k_w_mm3_per_n_m"]
    w_mean = wear_mm(k, p, v, duration_h, **kw)
    w_a, w_b = wear_mm(k, p_a, v, duration_h, **kw), wear_mm(k, p_b, v, duration_h, **kw)
    w_max = np.maximum(np.abs(w_a), np.abs(w_b))
    par = pulley_parallelism_mm(pulley_diameter_mm, w_a, w_b, length)
    l_max = max_bushing_length_mm(max_pivot_height_mm, axial_damping)
    out = {
        "p_mpa": p, "v_m_per_s": v, "pv_mpa_m_per_s": pv, "pvt_mpa_m_per_s_h": pvt,
        "eccentricity_mm": e, "reaction_a_n": r_a, "reaction_b_n": r_b, "p_a_mpa": p_a, "p_b_mpa": p_b,
        "wear_mean_mm": w_mean, "wear_a_mm": w_a, "wear_b_mm": w_b, "wear_max_mm": w_max,
        "parallelism_mm": par, "length_max_mm": l_max,
        "margin_p": margin_upper(p, lim["p_max_mpa"]),
        "margin_pv": margin_upper(pv, lim["pv_max_mpa_m_per_s"]),
        "margin_pvt": margin_upper(pvt, lim["pvt_max_mpa_m_per_s_h"]),
        "margin_wear": margin_upper(w_max, lim["sliding_layer_depth_mm"]),
        "margin_parallelism": margin_upper(par, parallelism_max_mm),
        "margin_length": margin_upper(length, l_max),
    }
    shape = np.broadcast_shapes(*(np.shape(v) for v in out.values()))
    out = {key: np.broadcast_to(val, shape) for key, val in out.items()}
    out["passes"] = np.all([out[m] >= 0.0 for m in out if m.startswith("margin_")], axis=0)
    return out


def select_bushing_length(hubload_n, pivot_diameter_mm, theta_peak_to_peak_deg, frequency_hz, duration_h, *,
                          supplier, environment, belt_plane_height_mm, max_pivot_height_mm, axial_damping,
                          pulley_diameter_mm, parallelism_max_mm, scheme="catalog", fidelity="screening",
                          pressure_model="linear"):
    """The "lengthen the bushing" iteration of step 4, vectorised over candidate lengths.

    ``scheme="catalog"``: candidates are the supplier's available lengths;
    ``scheme="thesis"``: candidates are ``(start + k * step) * D_pivot``
    (``bush_length_ratio_start/step``), the progression the thesis tool's
    case studies imply (first re-iteration = pivot diameter). Candidates longer
    than ``L_max`` (eq. 33-34) fail their length check.

    Returns the :func:`evaluate_bushing` dict at the chosen length plus
    ``length_mm`` (shortest passing candidate; where none passes, the longest
    candidate that fits, with ``found = False``: the thesis's next step is a
    larger pivot diameter), ``found`` and ``length_catalog_mm`` (the next
    available catalog length >= ``length_mm``, see :func:`next_catalog_length_mm`).

    >>> r = select_bushing_length(462.5, 21.0, 16.0, 50.0, 1200.0, supplier="B",
    ...     environment="dry", belt_plane_height_mm=20.0, max_pivot_height_mm=34.0,
    ...     axial_damping=False, pulley_diameter_mm=65.5, parallelism_max_mm=0.5, scheme="thesis")
    >>> float(r["length_mm"]), float(r["length_catalog_mm"]), bool(r["found"])
    (21.0, 22.0, True)
    """
    if scheme not in SCHEMES:
        raise InputError(Problem("scheme", scheme, " or ".join(SCHEMES)))
    args = np.broadcast_arrays(*(np.asarray(x, dtype=float) for x in (
        hubload_n, pivot_diameter_mm, theta_peak_to_peak_deg, frequency_hz, duration_h,
        belt_plane_height_mm, max_pivot_height_mm, pulley_diameter_mm, parallelism_max_mm)),
        np.asarray(axial_damping, dtype=bool))
    hl, d, th, f, t, mpbh, hmax, dp, parmax, ax = (a[..., None] for a in args)
    l_max = max_bushing_length_mm(hmax, ax)
    if scheme == "catalog":
        cand = available_lengths_mm(supplier)
    else:
        start, step = catalog.constant("bush_length_ratio_start"), catalog.constant("bush_length_ratio_step")
        d_min = max(float(np.min(d)), np.finfo(float).eps)
        n = int(np.ceil((float(np.max(l_max)) / d_min - start) / step)) + 1
        cand = (start + step * np.arange(max(n, 1))) * d
    cand = np.broadcast_to(cand, np.broadcast_shapes(np.shape(cand), hl.shape))
    res = evaluate_bushing(hl, d, cand, th, f, t, supplier=supplier, environment=environment,
                           belt_plane_height_mm=mpbh, max_pivot_height_mm=hmax, axial_damping=ax,
                           pulley_diameter_mm=dp, parallelism_max_mm=parmax, fidelity=fidelity,
                           pressure_model=pressure_model)
    ok = res["passes"]
    found = ok.any(axis=-1)
    fits = res["margin_length"] >= 0.0
    first_ok = np.argmax(ok, axis=-1)
    # fallback: longest candidate that fits (or the shortest one if none fits)
    last_fit = np.where(fits.any(axis=-1), fits.shape[-1] - 1 - np.argmax(fits[..., ::-1], axis=-1), 0)
    idx = np.where(found, first_ok, last_fit)[..., None]
    out = {key: np.take_along_axis(val, idx, axis=-1)[..., 0] for key, val in res.items()}
    out["length_mm"] = np.take_along_axis(cand, idx, axis=-1)[..., 0]
    out["found"] = found
    out["length_catalog_mm"] = next_catalog_length_mm(out["length_mm"], supplier)
    return out


def next_catalog_length_mm(length_mm, supplier):
    """The shortest catalog length >= ``length_mm`` (the longest one if none is).

    The thesis tool returns 16 and 21 mm; the real tensioners use 18 and 22 mm
    because those formats were "not available" (case studies 1 and 3).

    >>> float(next_catalog_length_mm(16.0, "A")), float(next_catalog_length_mm(21.0, "B"))
    (18.0, 22.0)
    """
    lengths = available_lengths_mm(supplier)
    length = np.asarray(length_mm, dtype=float)
    idx = np.clip(np.searchsorted(lengths, length - 1e-9), 0, len(lengths) - 1)
    return lengths[idx]


def bushing_checks(result: dict, *, supplier: str, environment: str, parallelism_max_mm: float) -> list[Check]:
    """Report records (:class:`~synth.checks.Check`) for one scalar design of step 4."""
    lim = supplier_limits(supplier, environment)
    s = {k: float(np.asarray(v).ravel()[0]) for k, v in result.items()}
    lengthen = "lengthen the bushing; if L_max is reached, increase the pivot diameter"
    return [
        Check("pivot bushing pressure", 4, s["p_mpa"], lim["p_max_mpa"], "<=", "MPa", "eq. (28), Table 5", lengthen),
        Check("pivot bushing p*v", 4, s["pv_mpa_m_per_s"], lim["pv_max_mpa_m_per_s"], "<=", "MPa*m/s",
              "eq. (30), Table 5", lengthen),
        Check("pivot bushing p*v*t", 4, s["pvt_mpa_m_per_s_h"], lim["pvt_max_mpa_m_per_s_h"], "<=", "MPa*m/s*h",
              "eq. (31), Table 5", lengthen),
        Check("pivot bushing wear (most loaded end) vs sliding layer", 4, s["wear_max_mm"],
              lim["sliding_layer_depth_mm"], "<=", "mm", "eq. (32), (40)-(41)", lengthen),
        Check("pulley parallelism at end of life", 4, s["parallelism_mm"], parallelism_max_mm, "<=", "mm",
              "eq. (42)", "centre the bushing on the belt plane or lengthen it"),
        Check("pivot bushing length vs space on the pivot", 4, s.get("length_mm"), s["length_max_mm"], "<=", "mm",
              "eq. (33)-(34)", "increase the pivot diameter or the maximum pivot height"),
    ]
