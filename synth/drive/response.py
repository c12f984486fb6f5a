"""The drive's steady periodic response over an engine-speed sweep: harmonic balance on the arm.

The crank turns at ``Omega`` with the angular fluctuation of its orders
``theta_c(t) = sum_k A_k cos(n_k Omega t + phi_k)`` (given, or from the
thesis's irregularity, eq. (3): ``delta = 2 n A`` for one order ``n``). The
response is periodic at the base frequency ``w_b`` (the largest common
divisor of the orders) and expanded in harmonics ``h = 0..H`` of it:
``x(t) = Re sum_h X_h exp(i h w_b t)``.

Everything but the arm's friction is linear, so the linear part is condensed
onto the arm (the partition of Zhu and Parker 2008: "a linear subsystem ...
and a nonlinear subsystem addressing tensioner arm vibration, which reduces
the dimension of the iteration matrices when employing the harmonic balance
method"). With ``Z_h = K - (h w_b)^2 M + i h w_b C``, the excitation's
harmonics ``F_h`` and ``G_h = Z_h^-1``, the arm's harmonics satisfy

    Psi_h - (G_h F_h)_arm + (G_h)_arm,arm T_f,h(Psi) = 0,     h = 0..H,

where ``T_f,h`` are the harmonics of the friction torque evaluated in time
(alternating frequency/time: the arm speed at 8H samples a period, the regularised
Coulomb torque of :mod:`synth.drive.friction` there, its harmonics back; both
maps are real matrices built once per H). The 2H+1 real equations are solved by
:func:`scipy.optimize.root` (MINPACK's hybrj) with their exact Jacobian, made
only when hybrj re-linearises; the other coordinates and the span tensions follow
linearly. :func:`time_response` integrates the same equations with
:func:`scipy.integrate.solve_ivp` (the tests compare the two).

Tolerance of the periodic solution: the regularisation ``eps_rel`` and the
harmonics ``H`` (time samples ``8 H``). :func:`sweep` with ``check=True``
solves again with ``eps_rel / 2`` and ``2 H`` and reports how far the arm's
peak-to-peak angle and the lowest span tension moved (relative to the
sweep's largest peak-to-peak angle and to the static tension).
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache
from math import gcd

import numpy as np

from synth.drive.friction import critical_friction_torque_nm, friction_slope, friction_torque_nm

__all__ = ["Excitation", "excitation", "harmonic_balance", "speed_response", "sweep", "time_response"]


def nd_of(model) -> int:
    return len(model.dofs)


@dataclass(frozen=True)
class Excitation:
    """The excitation at one speed: base frequency [rad/s], the crank's complex harmonics [rad] and each
    pulley's load-torque harmonics [N m] (``(pulleys, H + 1)``)."""

    omega_b: float
    theta: np.ndarray  # (H + 1,) complex
    torque: np.ndarray  # (pulleys, H + 1) complex


def _base_and_index(orders) -> tuple[float, list[int]]:
    """Base frequency as a multiple of the crank speed and each order's harmonic index."""
    half = [int(round(2 * o)) for o in orders]
    g = 0
    for m in half:
        g = gcd(g, m)
    g = max(g, 1)
    return g / 2.0, [m // g for m in half]


def excitation(drive, speed_rpm: float, harmonics: int) -> Excitation:
    """The crank's harmonics at ``speed_rpm`` for ``harmonics`` retained harmonics of the base frequency.

    >>> from synth.drive.inputs import example_drive
    >>> e = excitation(example_drive(), 3000.0, 4)
    >>> round(e.omega_b, 3), [round(float(abs(x)), 5) for x in e.theta]
    (628.319, [0.0, 0.01745, 0.0, 0.0, 0.0])
    """
    loads = [(i, p) for i, p in enumerate(drive.pulleys) if p.torque_amplitude_nm > 0]
    base, index = _base_and_index([o.order for o in drive.orders] + [p.torque_order for _, p in loads])
    omega = 2.0 * np.pi * speed_rpm / 60.0
    theta = np.zeros(harmonics + 1, dtype=complex)
    torque = np.zeros((len(drive.pulleys), harmonics + 1), dtype=complex)
    for o, h in zip(drive.orders, index):
        if h <= harmonics:
            theta[h] += np.radians(o.amplitude_deg) * np.exp(1j * np.radians(o.phase_deg))
    for (i, p), h in zip(loads, index[len(drive.orders):]):
        if h <= harmonics:
            torque[i, h] += p.torque_amplitude_nm * np.exp(1j * np.radians(p.torque_phase_deg))
    return Excitation(base * omega, theta, torque)


@lru_cache(maxsize=16)
def _frames(H: int, n_time: int):
    """The time samples of harmonics ``0..H`` (``E``) and the harmonics of samples (``P``); read-only, shared."""
    th = 2.0 * np.pi * np.arange(n_time) / n_time
    h = np.arange(H + 1)
    E = np.exp(1j * np.outer(th, h))                      # samples <- harmonics
    P = np.exp(-1j * np.outer(h, th)) * (2.0 / n_time)   # harmonics <- samples
    P[0] *= 0.5
    E.flags.writeable = False
    P.flags.writeable = False
    return E, P


@lru_cache(maxsize=16)
def _real_frames(H: int, n_time: int):
    """The same maps on ``z = [Re X_0, Re X_1, Im X_1, ...]``: ``A`` (samples of sum_h i h X_h exp(i h theta),
    the speed over the base frequency, ``(N, 2H+1)``), ``Pc`` and ``Ps`` (the real and imaginary part of each
    harmonic of the samples, ``(H+1, N)``); read-only, shared."""
    E, P = _frames(H, n_time)
    h = np.arange(1, H + 1)
    A = np.zeros((n_time, 2 * H + 1))
    A[:, 1::2] = -(E[:, 1:].imag * h)   # Re(i h exp(i h theta)) = -h sin(h theta)
    A[:, 2::2] = -(E[:, 1:].real * h)   # Re(i h i exp(i h theta)) = -h cos(h theta)
    Pc, Ps = np.ascontiguousarray(P.real), np.ascontiguousarray(P.imag)
    for x in (A, Pc, Ps):
        x.flags.writeable = False
    return A, Pc, Ps


def _to_complex(z, H):
    out = np.zeros(H + 1, dtype=complex)
    out[0] = z[0]
    out[1:] = z[1::2] + 1j * z[2::2]
    return out


def _to_real(c):
    out = np.empty(2 * len(c) - 1)
    out[0] = c[0].real
    out[1::2] = c[1:].real
    out[2::2] = c[1:].imag
    return out


def harmonic_balance(lin, receptance, omega_b: float, friction_nm: float, eps_rad_s: float, *,
                     n_time: int | None = None, start=None, xtol: float = 1e-11) -> dict:
    """Solve ``Psi_h - lin_h + R_h T_f,h(Psi) = 0`` for the harmonics ``Psi`` of one friction coordinate.

    ``lin``: its harmonics without friction; ``receptance``: ``R_h`` (its dynamic compliance) at each harmonic
    ``h = 0..H`` of ``omega_b``. Returns ``psi`` (complex harmonics), ``friction`` (the friction torque's
    harmonics), ``converged`` and the solver's message. A single mass-spring (``R_h = 1/(k - m (h w)^2)``) is
    Den Hartog's problem (:func:`synth.drive.friction.den_hartog_amplitude`).
    """
    from scipy.optimize import root
    lin = np.asarray(lin, dtype=complex)
    R = np.asarray(receptance, dtype=complex)
    H = len(lin) - 1
    N = n_time or max(64, 8 * H)
    A, Pc, Ps = _real_frames(H, N)
    V = omega_b * A                                   # speed samples <- z (linear)
    Rr, Ri = R.real[:, None], R.imag[:, None]
    M = np.empty((2 * H + 1, N))                      # [Re, Im] of R_h T_h <- torque samples
    M[0] = Rr[0] * Pc[0]
    M[1::2] = Rr[1:] * Pc[1:] - Ri[1:] * Ps[1:]
    M[2::2] = Ri[1:] * Pc[1:] + Rr[1:] * Ps[1:]
    lin_r = _to_real(lin)
    ident = np.eye(2 * H + 1)

    def speed(psi):
        return V @ _to_real(psi)

    def fun(z):
        return z - lin_r + M @ friction_torque_nm(V @ z, friction_nm, eps_rad_s)

    def jac(z):   # asked for only when MINPACK's hybrj re-linearises, a few times a solve
        return ident + M @ (friction_slope(V @ z, friction_nm, eps_rad_s)[:, None] * V)

    if start is None:
        start = _describing_function(lin, R, omega_b, friction_nm, speed)
    sol = root(fun, _to_real(np.asarray(start, dtype=complex)), jac=jac, method="hybr", options={"xtol": xtol})
    psi = _to_complex(sol.x, H)
    t = friction_torque_nm(V @ sol.x, friction_nm, eps_rad_s)
    tf = Pc @ t + 1j * (Ps @ t)
    resid = np.max(np.abs(psi - lin + R * tf)) / max(np.max(np.abs(lin)), 1e-300)
    return {"psi": psi, "friction": tf, "converged": bool(sol.success) or resid < 1e-8, "residual": float(resid),
            "message": str(sol.message)}


def _attempt(lin, R, omega_b, friction_nm, eps, n_time, start, restarts: int = 2) -> dict:
    """:func:`harmonic_balance` from ``start``, restarted from where it stopped while that lowers the residual
    (MINPACK's hybrj stops "not making good progress" on a stale Broyden model; a restart takes a fresh Jacobian)."""
    hb = harmonic_balance(lin, R, omega_b, friction_nm, eps, n_time=n_time, start=start)
    for _ in range(restarts):
        if hb["converged"]:
            break
        again = harmonic_balance(lin, R, omega_b, friction_nm, eps, n_time=n_time, start=hb["psi"])
        if again["residual"] >= hb["residual"]:
            break
        hb = again
    return hb


def _solve_arm(lin, R, omega_b, friction_nm, eps, n_time, start, done, steps: int = 24) -> dict:
    """The arm's harmonics at regularisation ``eps``: from ``start``; failing that from the held arm (the answer at
    the critical friction, which is where the hard solves are: the arm barely slipping); failing that by
    continuation in the regularisation from ``done`` (a converged ``(eps, psi)``, else the held arm's answer at ten
    times ``eps``) in ratios of at most 2, a step's ratio shortened (square root) where it fails and lengthened
    again (squared) where it converges. Returns the converged answer, or
    the attempt of smallest residual (``converged`` False: the caller says so)."""
    held = np.zeros(len(lin), dtype=complex)
    tries = [_attempt(lin, R, omega_b, friction_nm, eps, n_time, start)]
    if not tries[-1]["converged"]:
        tries.append(_attempt(lin, R, omega_b, friction_nm, eps, n_time, held))
    if tries[-1]["converged"]:
        return tries[-1]
    if done is None:
        tries.append(_attempt(lin, R, omega_b, friction_nm, 10.0 * eps, n_time, held))
        if not tries[-1]["converged"]:
            return min(tries, key=lambda t: t["residual"])
        done = (10.0 * eps, tries[-1]["psi"])
    e_ok, psi_ok = done
    ratio = 2.0
    for _ in range(steps):
        e = max(eps, e_ok / ratio)
        hb = _attempt(lin, R, omega_b, friction_nm, e, n_time, psi_ok)
        if hb["converged"]:
            if e <= eps:
                return hb
            e_ok, psi_ok = e, hb["psi"]
            ratio = min(2.0, ratio * ratio)
        else:
            ratio = np.sqrt(ratio)
            if e <= eps:
                tries.append(hb)
    return min(tries, key=lambda t: t["residual"])


def _describing_function(lin, R, omega_b, friction_nm, speed):
    """Start of the solve: the friction as its equivalent viscous damper ``4 D / (pi V)`` (V: peak speed)."""
    hw = 1j * omega_b * np.arange(len(lin))
    psi = lin.copy()
    for _ in range(40):
        v = np.max(np.abs(speed(psi)))
        if v <= 0:
            break
        c = 4.0 * friction_nm / (np.pi * v)
        new = lin / (1.0 + R * hw * c)
        psi = 0.5 * psi + 0.5 * new
    return psi


def _dynamic(model, omega_b, H):
    h = np.arange(H + 1)
    w = h * omega_b
    return (model.K[None] - (w ** 2)[:, None, None] * model.M[None] + 1j * w[:, None, None] * model.C[None])


def _forcing(model, exc: Excitation, H):
    """Harmonics of the generalised forces: the crank's motion through the spans, the pulleys' load torques
    (a load resists its pulley's rotation)."""
    w = np.arange(H + 1) * exc.omega_b
    stretch = (model.k_span[None] + 1j * w[:, None] * model.c_span[None]) * model.b_crank[None] * exc.theta[:, None]
    F = -(stretch @ model.B)   # (H+1, dofs)
    F[:, :len(model.pulley_dof)] -= exc.torque[list(model.pulley_dof)].T
    return F


def _samples(X, n_time):
    """Time samples over one base period of harmonics ``X`` (last axis: harmonics)."""
    H = X.shape[-1] - 1
    E, _ = _frames(H, n_time)
    return (X @ E.T).real


def _peak_speed(hw, psi, n_time) -> float:
    """The largest speed [rad/s] over a period of the angle of harmonics ``psi`` (``hw``: ``i h omega_b``)."""
    return float(np.max(np.abs(_samples((hw * psi)[None], n_time))))


def speed_response(model, drive, speed_rpm: float, friction_nm: float, *, harmonics: int, eps_rel: float,
                   start=None, v_peak=None) -> dict:
    """The periodic response at one engine speed: arm angle, span tensions, the locked-arm limit.

    The arm held still is solved first (linear): when the friction is at least the critical torque
    (:func:`synth.drive.friction.critical_friction_torque_nm`) the held arm *is* the Coulomb solution and it is
    returned (``locked``). Otherwise the arm slips and :func:`harmonic_balance` solves for it from ``start``
    (:func:`_solve_arm`: restarts, the held arm, continuation in the regularisation), the regularisation
    ``eps_rel`` times the answer's own peak speed (a fixed point; the first pass from ``v_peak`` [rad/s], else from
    the peak speed without friction). ``converged`` False: no attempt converged, the values are the attempt of
    smallest residual.
    """
    H = harmonics
    N = max(64, 8 * H)
    exc = excitation(drive, speed_rpm, H)
    Z = _dynamic(model, exc.omega_b, H)
    F = _forcing(model, exc, H)
    nd = len(model.dofs)
    a = model.arm
    hw = 1j * exc.omega_b * np.arange(H + 1)
    # the arm held: its row and column out; the belt's torque on it is -sum_j g_j dT_j
    keep = [i for i in range(nd) if i != a]
    Xl = np.zeros((H + 1, nd), dtype=complex)
    Xl[:, keep] = np.linalg.solve(Z[:, keep][:, :, keep], F[:, keep][:, :, None])[:, :, 0]
    dTl = (model.k_span[None] + hw[:, None] * model.c_span[None]) * (Xl @ model.B.T + exc.theta[:, None]
                                                                     * model.b_crank[None])
    t_crit = critical_friction_torque_nm(-_samples((dTl @ model.B[:, a])[None], N)[0])
    locked = friction_nm >= t_crit
    if locked:
        X, tf_h, psi_h = Xl, np.zeros(H + 1, dtype=complex), np.zeros(H + 1, dtype=complex)
        hb = {"converged": True, "residual": 0.0}
        eps = 0.0
    else:
        rhs = np.zeros((H + 1, nd, 2), dtype=complex)
        rhs[:, :, 0] = F
        rhs[:, a, 1] = 1.0
        sol = np.linalg.solve(Z, rhs)
        X_lin, G_a = sol[:, :, 0], sol[:, :, 1]
        v_ref = _peak_speed(hw, X_lin[:, a], N)
        eps = max(eps_rel * (v_ref if v_peak is None else v_peak), 1e-12)
        done = None
        for _ in range(3):   # eps follows the solution's own peak speed (a fixed point, a few passes)
            hb = _solve_arm(X_lin[:, a], G_a[:, a], exc.omega_b, friction_nm, eps, N, start, done)
            if not hb["converged"]:   # no better eps from an answer that is not one
                break
            done = (eps, hb["psi"])
            start = hb["psi"]
            v_sol = _peak_speed(hw, hb["psi"], N)
            new = max(eps_rel * v_sol, 1e-12)
            if abs(new - eps) <= 0.25 * eps:
                break
            eps = new
        psi_h, tf_h = hb["psi"], hb["friction"]
        X = X_lin - G_a * tf_h[:, None]
    e_h = X @ model.B.T + exc.theta[:, None] * model.b_crank[None]          # (H+1, spans)
    dT_h = (model.k_span[None] + hw[:, None] * model.c_span[None]) * e_h
    T = model.tension0_n[:, None] + _samples(dT_h.T, N)                       # (spans, N)
    psi = _samples(psi_h[None], N)[0]
    amp = np.abs(psi_h[1:]) if not locked else np.abs(exc.theta[1:])
    h_dom = int(np.argmax(amp)) + 1 if amp.size and amp.max() > 0 else 1
    return {"speed_rpm": float(speed_rpm), "theta_pp_deg": float(np.degrees(psi.max() - psi.min())),
            "arm_frequency_hz": h_dom * exc.omega_b / (2.0 * np.pi), "locked": bool(locked),
            "tension_min_n": T.min(axis=1), "tension_max_n": T.max(axis=1), "critical_friction_nm": t_crit,
            "converged": hb["converged"], "residual": hb["residual"], "psi_harmonics": psi_h,
            "psi_rad": psi, "friction_nm_t": _samples(tf_h[None], N)[0], "tension_n_t": T,
            "omega_b": exc.omega_b, "eps_rad_s": eps, "v_peak": _peak_speed(hw, psi_h, N)}


def sweep(model, drive, friction_nm: float, speeds_rpm, *, harmonics: int | None = None,
          eps_rel: float | None = None, check: bool = False, coarse=None) -> dict:
    """The periodic response over ``speeds_rpm`` (each solve starts from the previous speed's solution).

    With ``check``, the sweep is solved again at half the regularisation and twice the harmonics; ``change``
    gives the largest move of the arm's peak-to-peak angle (over the sweep's largest) and of the lowest span
    tension (over the tensioner's static tension), and ``within_tolerance`` whether both stay within
    ``drive.tolerance``.
    """
    H = harmonics or drive.harmonics
    eps_rel = eps_rel or drive.regularisation
    rows = []
    start = None
    for i, s in enumerate(speeds_rpm):
        v_peak = None
        if coarse is not None and not coarse[i]["locked"]:
            start = np.zeros(H + 1, dtype=complex)
            c = coarse[i]["psi_harmonics"]
            start[:len(c)] = c[:H + 1]
            v_peak = coarse[i]["v_peak"]
        r = speed_response(model, drive, float(s), friction_nm, harmonics=H, eps_rel=eps_rel, start=start,
                           v_peak=v_peak)
        start = None if r["locked"] else r["psi_harmonics"]
        rows.append(r)
    out = {"speed_rpm": np.array([r["speed_rpm"] for r in rows]),
           "theta_pp_deg": np.array([r["theta_pp_deg"] for r in rows]),
           "arm_frequency_hz": np.array([r["arm_frequency_hz"] for r in rows]),
           "tension_min_n": np.array([r["tension_min_n"] for r in rows]),
           "tension_max_n": np.array([r["tension_max_n"] for r in rows]),
           "critical_friction_nm": np.array([r["critical_friction_nm"] for r in rows]),
           "converged": np.array([r["converged"] for r in rows]),
           "locked": np.array([r["locked"] for r in rows]),
           "harmonics": H, "regularisation": eps_rel, "rows": rows}
    if check:
        fine = sweep(model, drive, friction_nm, speeds_rpm, harmonics=2 * H, eps_rel=eps_rel / 2.0, coarse=rows)
        scale_pp = max(float(np.max(out["theta_pp_deg"])), 1e-12)
        d_pp = float(np.max(np.abs(fine["theta_pp_deg"] - out["theta_pp_deg"]))) / scale_pp
        d_t = float(np.max(np.abs(fine["tension_min_n"].min(axis=1) - out["tension_min_n"].min(axis=1)))) / \
            max(float(model.static["tensioner_tension_n"]), 1e-12)
        out["change"] = {"theta_pp": d_pp, "tension_min": d_t}
        out["check_unconverged_rpm"] = fine["speed_rpm"][~fine["converged"]]
        out["within_tolerance"] = bool(max(d_pp, d_t) <= drive.tolerance)
    return out


def time_response(model, drive, speed_rpm: float, friction_nm: float, *, eps_rad_s: float, periods: int = 200,
                  rtol: float = 1e-8, atol: float = 1e-12, samples: int = 256) -> dict:
    """Integrate the same equations in time (:func:`scipy.integrate.solve_ivp`, LSODA) from the static state
    for ``periods`` base periods; the last period's arm angle and span tensions (the tests' reference)."""
    from scipy.integrate import solve_ivp
    probe = excitation(drive, speed_rpm, 64)
    used = np.flatnonzero((np.abs(probe.theta) > 0) | (np.abs(probe.torque).sum(axis=0) > 0))
    exc = excitation(drive, speed_rpm, max(1, int(used.max(initial=1))))
    torque_dof = np.zeros((nd_of(model), len(exc.theta)), dtype=complex)
    torque_dof[:len(model.pulley_dof)] = exc.torque[list(model.pulley_dof)]
    w = exc.omega_b
    hs = np.arange(len(exc.theta))
    nd = len(model.dofs)
    a = model.arm
    Minv = np.linalg.inv(model.M)
    kb = model.B.T @ (model.k_span * model.b_crank)
    cb = model.B.T @ (model.c_span * model.b_crank)

    def crank(t):
        ph = np.exp(1j * hs * w * t)
        return float((exc.theta * ph).real.sum()), float((1j * hs * w * exc.theta * ph).real.sum())

    def rhs(t, y):
        q, v = y[:nd], y[nd:]
        th, thd = crank(t)
        f = -kb * th - cb * thd - model.K @ q - model.C @ v - (torque_dof @ np.exp(1j * hs * w * t)).real
        f[a] -= friction_nm * np.tanh(v[a] / eps_rad_s)
        return np.concatenate([v, Minv @ f])

    period = 2 * np.pi / w
    t_end = periods * period
    t_eval = t_end - period + period * np.arange(samples) / samples
    sol = solve_ivp(rhs, (0.0, t_end), np.zeros(2 * nd), method="LSODA", rtol=rtol, atol=atol, t_eval=t_eval)
    q, v = sol.y[:nd], sol.y[nd:]
    th = np.array([crank(t) for t in sol.t])
    e = model.B @ q + model.b_crank[:, None] * th[:, 0]
    ed = model.B @ v + model.b_crank[:, None] * th[:, 1]
    T = model.tension0_n[:, None] + model.k_span[:, None] * e + model.c_span[:, None] * ed
    psi = q[a]
    return {"theta_pp_deg": float(np.degrees(psi.max() - psi.min())), "tension_min_n": T.min(axis=1),
            "tension_max_n": T.max(axis=1), "psi_rad": psi, "success": bool(sol.success)}
