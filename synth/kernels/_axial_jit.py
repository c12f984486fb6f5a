"""numba twins of the axial group's physics (thesis steps 5 and 8); imported only by :mod:`synth.kernels.axial`.

This module imports numba at import time, so nothing imports it except the lazy loader of
:mod:`synth.kernels.axial` (the one-application path never pays for numba). Each function repeats, row by row and
in the same order of operations, the lines of the reference functions of :mod:`synth.model.disc_spring`
(:func:`~synth.model.disc_spring.cone_spring`: eq. (9), (55)-(63), Fig. 68, DIN EN 16984 / 16983) and of
:mod:`synth.model.friction_wear` (:func:`~synth.model.friction_wear.plastic_wear`: eq. (43)-(49)); what the
reference reads of the catalogs (elastic constants, the force-tolerance rows of DIN EN 16983, the relaxation and
the wear limit) arrives as scalars and small arrays read by the caller. Compiled with ``error_model="numpy"`` (IEEE
division) and without fast-math: no operation is fused or reordered. :func:`cone_spring_rows` receives the
reference's thickness and nominal force and numpy's powers and log of them, and is arithmetic alone: it equals the
reference bit for bit. :func:`plastic_wear_rows` (given the same powers) evaluates the wear root's ``log``, ``exp``,
``arctan`` and the screening model's ``expm1`` with the C library's routines where numpy uses its own SIMD routines
(SVML on AVX-512 machines): the two may differ in the last bit, so it equals the reference to a stated tolerance
(``tests/test_axial_kernels.py``).

The wear root (the deflection at the end of the test, :func:`synth.model.friction_wear._deflection_after`) is found
by scipy's own compiled Brent solver, ``scipy.optimize.cython_optimize`` ``brentq`` (the C routine behind
:func:`scipy.optimize.brentq`), called through its C address with the residual as a compiled callback
(:data:`wear_residual`), in the reference's proven bracket and to its tolerance (``xtol = 0``, ``rtol = 4 eps``;
the reference uses scipy's Chandrupatla solver, ``scipy.optimize.elementwise.find_root``: both stop within
``4 eps |v|`` of the root). Both addresses are arguments of the kernels, never compiled-in constants, so the kernels
stay in numba's on-disk cache.

A row the reference would refuse (a geometry, force or input outside its validity: it raises
:class:`~synth.errors.InputError`) is flagged in ``bad``; the caller then calls the reference on the whole call,
which raises the same error.
"""

from __future__ import annotations

import math

import numpy as np
from llvmlite import ir
from numba import carray, cfunc, njit, types
from numba.extending import intrinsic

from synth.kernels._ieee import maximum as _maximum, minimum as _minimum
from synth.kernels.numba_setup import announce_compiles

announce_compiles()  # a line on stderr when this process compiles a kernel (synth.kernels.numba_setup)

#: outputs of :func:`cone_spring_rows`, in column order (the keys of :func:`synth.model.disc_spring.cone_spring`)
CONE_SPRING_OUT = (
    "cone_spring_fax_max_tolerance_n", "cone_spring_fax_min_tolerance_n", "cone_spring_fax_nominal_n",
    "cone_spring_fax_band_n", "cone_spring_force_band_room_n", "cone_spring_gap_band_room_n",
    "cone_spring_internal_diameter_mm", "cone_spring_external_diameter_mm", "cone_spring_thickness_mm",
    "cone_spring_cone_height_mm", "cone_spring_free_height_mm", "cone_spring_nominal_deflection_mm",
    "cone_spring_max_deflection_mm", "cone_spring_rate_n_per_mm", "cone_spring_force_tolerance_plus",
    "cone_spring_force_tolerance_minus", "sigma_om_mpa", "sigma_i_mpa", "sigma_ii_mpa", "sigma_iii_mpa",
    "sigma_iv_mpa", "cone_spring_diameter_ratio", "cone_spring_aspect_ratio", "cone_spring_thinness")
#: outputs of :func:`plastic_wear_rows` (the keys of :func:`synth.model.friction_wear.plastic_wear`, no history)
PLASTIC_WEAR_OUT = (
    "damper_pad_wear_mm", "endcap_spacer_wear_mm", "plastic_wear_total_mm", "cone_spring_force_initial_n",
    "cone_spring_force_eol_n", "cone_spring_deflection_eol_mm", "damper_pad_pressure_initial_mpa",
    "endcap_spacer_pressure_initial_mpa", "damper_pad_sliding_speed_m_per_s", "endcap_spacer_sliding_speed_m_per_s",
    "axial_damping_initial_nm", "axial_damping_eol_nm", "damping_initial_nm", "damping_eol_nm",
    "damper_pad_wear_max_mm", "endcap_spacer_wear_max_mm")
(CS_FMAX, CS_FMIN, CS_FNOM, CS_BAND, CS_ROOM, CS_GAP_ROOM, CS_DI, CS_DE, CS_T, CS_H0, CS_L0, CS_SN, CS_SMAX,
 CS_RATE, CS_TOL_PLUS, CS_TOL_MINUS, CS_OM, CS_I, CS_II, CS_III, CS_IV, CS_DRATIO, CS_ARATIO,
 CS_THIN) = range(len(CONE_SPRING_OUT))
(PW_WDP, PW_WES, PW_W, PW_F0, PW_FEOL, PW_SEOL, PW_PDP, PW_PES, PW_VDP, PW_VES, PW_DAX0, PW_DAXEOL, PW_D0,
 PW_DEOL, PW_WDP_MAX, PW_WES_MAX) = range(len(PLASTIC_WEAR_OUT))

_EPS = np.finfo(float).eps
_SQRT_EPS = math.sqrt(np.finfo(float).eps)
#: the reference's relative tolerance of the wear root (``find_root``'s ``xrtol``) and an iteration cap
ROOT_RTOL = 4 * np.finfo(float).eps
ROOT_MAXITER = 100
#: slots of the residual's parameter block (see :data:`wear_residual`)
P_S0, P_LOG_S0, P_PHI0, P_TARGET, P_ALPHA, P_BETA, P_GAMMA, P_ROOT = range(8)
N_P = 8


@njit(cache=True, error_model="numpy")
def _clip(s, lo, hi):
    """``numpy.clip(s, lo, hi)`` (``minimum(maximum(s, lo), hi)``, a NaN propagates)."""
    return _minimum(_maximum(s, lo), hi)


@njit(cache=True, error_model="numpy")
def _tolerance_row(t, lo, hi, inc_lo, inc_hi):
    """Row of the force-tolerance table for thickness ``t`` (``_tolerance_row_index``): the first whose range holds
    it, -1 outside every row."""
    for r in range(len(lo)):
        above = t >= lo[r] if inc_lo[r] else t > lo[r]
        below = t <= hi[r] if inc_hi[r] else t < hi[r]
        if above and below:
            return r
    return -1


@njit(cache=True, error_model="numpy")
def _force_p(s, t, t4, h0, scale):
    """Almen-Laszlo force without contact flats (``disc_spring_force_n``, fidelity full, K4 = 1) [N], with ``t ** 4``
    given (computed by numpy, as the reference computes it)."""
    s = _clip(s, 0.0, h0)
    x = s / t
    z = h0 / t
    return scale * t4 * 1.0 * x * (1.0 * (z - x) * (z - 0.5 * x) + 1.0)


@njit(cache=True, error_model="numpy")
def _rate_p(s, t, t3, h0, scale):
    """Almen-Laszlo rate dF/ds (``disc_spring_rate_n_per_mm``, fidelity full, K4 = 1) [N/mm], with ``t ** 3``
    given."""
    base = scale * t3 * 1.0
    s = _clip(s, 0.0, h0)
    x = s / t
    z = h0 / t
    return base * (1.0 * (z * z - 3.0 * z * x + 1.5 * x * x) + 1.0)


@njit(cache=True, error_model="numpy")
def cone_spring_rows(f_nom_in, t_in, t3_in, t4_in, ln_in, target, tol, rad, mu, r_dp, r_es, de, di, gap, zeta, phi,
                     screening, c_e, tab_lo, tab_hi, tab_inc_lo, tab_inc_hi, tab_plus_pct, tab_minus_pct, out, bad):
    """:func:`synth.model.disc_spring.cone_spring` row by row after its steps 1-3 (no made spring, DIN EN 16983's
    force tolerances): ``out[i, CS_*]`` (:data:`CONE_SPRING_OUT`); ``bad[i]``: the reference refuses row ``i``.
    ``f_nom_in``, ``t_in``: the nominal force and the thickness (the reference's own functions); ``t3_in``,
    ``t4_in``, ``ln_in``: ``t ** 3``, ``t ** 4`` and ``ln(De/Di)`` computed by numpy. What is left is arithmetic
    (no ``pow``, ``log`` or ``exp``): the same IEEE operations in the same order, so the values equal the
    reference's bit for bit. ``c_e``: ``4 E / (1 - nu^2)`` [MPa]; ``tab_*``: the rows of
    ``disc_spring_force_tolerances.csv``."""
    for i in range(len(f_nom_in)):
        m, rs = mu[i], r_dp[i] + r_es[i]
        f_nom, t, t3, t4 = f_nom_in[i], t_in[i], t3_in[i], t4_in[i]
        d = de[i] / di[i]
        ln = ln_in[i]
        u = (d - 1.0) / d
        k1 = u * u / ((d + 1.0) / (d - 1.0) - 2.0 / ln) / np.pi
        scale = c_e / (k1 * (de[i] * de[i]))
        h0 = zeta[i] * t
        s_n = phi[i] * h0
        dh = gap[i]
        bad[i] = not (t > 0) or not (h0 >= 0)
        r = _tolerance_row(t, tab_lo, tab_hi, tab_inc_lo, tab_inc_hi)
        plus = tab_plus_pct[r] / 100.0 if r >= 0 else np.nan
        minus = tab_minus_pct[r] / 100.0 if r >= 0 else np.nan
        # step 4: force shifts over the gap tolerance (gap_force_shifts_n)
        if screening:
            rate_sec = scale * t3 * 1.0
            up = rate_sec * dh
            down = -rate_sec * dh
        else:
            f0 = _force_p(s_n, t, t4, h0, scale)
            up = _force_p(s_n + dh, t, t4, h0, scale) - f0
            down = _force_p(s_n - dh, t, t4, h0, scale) - f0
        # the tolerance band (axial_force_tolerance_band)
        mu_r = m * rs * 1e-3
        bad[i] = bad[i] or not (mu_r > 0)
        f_up = _maximum(target[i] + tol[i] - rad[i], 0.0) / mu_r
        f_lo = _maximum(target[i] - tol[i] - rad[i], 0.0) / mu_r
        f_nom_b = _maximum(target[i] - rad[i], 0.0) / mu_r
        f_max = f_up - _maximum(_maximum(up, down), 0.0)
        f_min = f_lo - _minimum(_minimum(up, down), 0.0)
        o = out[i]
        o[CS_FMAX] = f_max
        o[CS_FMIN] = f_min
        o[CS_FNOM] = f_nom
        o[CS_BAND] = f_up - f_lo
        o[CS_ROOM] = _minimum(f_max - f_nom_b * (1.0 + plus), f_nom_b * (1.0 - minus) - f_min)
        o[CS_GAP_ROOM] = _minimum(f_max - f_nom_b, f_nom_b - f_min)
        o[CS_DI] = di[i]
        o[CS_DE] = de[i]
        o[CS_T] = t
        o[CS_H0] = h0
        o[CS_L0] = h0 + t
        o[CS_SN] = s_n
        s_max = s_n + dh
        o[CS_SMAX] = s_max
        if screening:
            o[CS_RATE] = scale * t3 * 1.0
        else:
            o[CS_RATE] = _rate_p(s_n, t, t3, h0, scale)
        o[CS_TOL_PLUS] = plus + 0.0 * t
        o[CS_TOL_MINUS] = minus + 0.0 * t
        # step 5: stresses at the maximum-material deflection (disc_spring_stresses_mpa, eq. (59))
        s = _clip(_minimum(s_max, h0), 0.0, h0)
        a = scale * (t * t) * 1.0 * s / t
        b = 1.0 * (h0 / t - 0.5 * s / t)
        k2 = 6.0 / np.pi * ((d - 1.0) / ln - 1.0) / ln
        k3 = 3.0 / np.pi * (d - 1.0) / ln
        o[CS_OM] = -a * 3.0 / np.pi
        o[CS_I] = -a * (k2 * b + k3)
        o[CS_II] = -a * (k2 * b - k3)
        o[CS_III] = -a / d * ((k2 - 2.0 * k3) * b - k3)
        o[CS_IV] = -a / d * ((k2 - 2.0 * k3) * b + k3)
        # Table 7 ratios
        o[CS_DRATIO] = de[i] / di[i]
        o[CS_ARATIO] = h0 / t
        o[CS_THIN] = de[i] / t


@njit(cache=True, error_model="numpy")
def _wear_phi(log_u, u, alpha, beta, gamma, root):
    """The antiderivative of 1/F (``friction_wear._wear_phi``) [mm/N]."""
    q = alpha + beta * u + gamma * u * u
    return log_u / alpha - np.log(q) / (2.0 * alpha) - beta / (alpha * root) * np.arctan(
        (2.0 * gamma * u + beta) / root)


@cfunc(types.float64(types.float64, types.voidptr), cache=True, error_model="numpy")
def wear_residual(v, params):
    """The wear root's residual ``Phi(s0) - Phi(s0 e^-v) - target`` (``friction_wear._deflection_after``'s ``f``),
    as a C callback of scipy's ``brentq``; ``params``: the block of ``P_*`` slots."""
    p = carray(params, N_P, dtype=np.float64)
    u = p[P_S0] * np.exp(-v)
    return p[P_PHI0] - _wear_phi(p[P_LOG_S0] - v, u, p[P_ALPHA], p[P_BETA], p[P_GAMMA], p[P_ROOT]) - p[P_TARGET]


@intrinsic
def _call_solver(typingctx, solver, callback, xa, xb, params, xtol, rtol, maxiter):
    """Call the C root finder at address ``solver`` (``scipy.optimize.cython_optimize``'s signature:
    ``double (callback_type f, double xa, double xb, void *args, double xtol, double rtol, int iter,
    zeros_full_output *full_output)``, ``full_output`` NULL) with the callback at address ``callback`` and the
    parameter block at address ``params``."""
    sig = types.float64(solver, callback, xa, xb, params, xtol, rtol, maxiter)

    def codegen(context, builder, signature, args):
        fn, cb, lo, hi, prm, xt, rt, it = args
        dbl, vp, i32 = ir.DoubleType(), ir.IntType(8).as_pointer(), ir.IntType(32)
        cb_t = ir.FunctionType(dbl, [dbl, vp]).as_pointer()
        fn_t = ir.FunctionType(dbl, [cb_t, dbl, dbl, vp, dbl, dbl, i32, vp]).as_pointer()
        return builder.call(builder.inttoptr(fn, fn_t),
                            [builder.inttoptr(cb, cb_t), lo, hi, builder.inttoptr(prm, vp), xt, rt,
                             builder.trunc(it, i32), ir.Constant(vp, None)])
    return sig, codegen


@njit(cache=True, error_model="numpy")
def _deflection_after(s0, target, alpha, beta, gamma, root, params, solver, callback):
    """``friction_wear._deflection_after`` for one row: ``v = ln(s0/s)`` in ``[0, target q_max]`` by the solver at
    ``solver`` (the reference's bracket and tolerance), first order below ``sqrt(eps)``."""
    v_first = target * (alpha + beta * s0 + gamma * s0 * s0)
    if v_first < _SQRT_EPS:
        v = v_first
    else:
        q_max = _maximum(alpha, alpha + beta * s0 + gamma * s0 * s0)
        log_s0 = np.log(s0)
        params[P_S0], params[P_LOG_S0], params[P_TARGET] = s0, log_s0, target
        params[P_ALPHA], params[P_BETA], params[P_GAMMA], params[P_ROOT] = alpha, beta, gamma, root
        params[P_PHI0] = _wear_phi(log_s0, s0, alpha, beta, gamma, root)
        hi = _maximum(target * q_max, 0.0) * (1.0 + 1e-9) + 1e-300
        f_hi = params[P_PHI0] - _wear_phi(log_s0 - hi, s0 * np.exp(-hi), alpha, beta, gamma, root) - target
        if not (-target < 0.0) or f_hi != f_hi or f_hi < 0.0:   # no sign change in the bracket: find_root's NaN
            v = np.nan
        elif f_hi == 0.0:
            v = hi
        else:
            v = _call_solver(solver, callback, 0.0, hi, params.ctypes.data, 0.0, ROOT_RTOL, ROOT_MAXITER)
    return s0 * np.exp(-v) if target > 0 else s0


@njit(cache=True, error_model="numpy")
def plastic_wear_rows(t3_in, t4_in, ln_in, s0_in, de, di, t, h0, a_dp, r_dp, h_dp, a_es, r_es, h_es, theta, freq,
                      dur, rad, kw, mu, screening, c_e, relax_pct, relax_time_h, wear_frac, passes, solver, callback,
                      out, bad):
    """:func:`synth.model.friction_wear.plastic_wear` row by row (no history): ``out[i, PW_*]``
    (:data:`PLASTIC_WEAR_OUT`); ``bad[i]``: the reference refuses row ``i``. ``relax_*``: the relaxation of
    ``relaxation_factor``; ``wear_frac``: ``plastic_max_wear_fraction``; ``passes``: the screening model's secant
    passes; ``solver``, ``callback``: addresses of scipy's ``brentq`` and of :data:`wear_residual`; ``t3_in``,
    ``t4_in``, ``ln_in``: ``t ** 3``, ``t ** 4`` and ``ln(De/Di)`` computed by numpy (the force at new, the
    pressures and the damping at new equal the reference's bit for bit; the wear root and what follows from it
    within the stated tolerance)."""
    params = np.empty(N_P)
    x_rel = relax_pct / 100.0
    for i in range(len(s0_in)):
        bad[i] = not (kw[i] >= 0) or not (dur[i] >= 0) or not (a_dp[i] > 0) or not (a_es[i] > 0) \
            or not (di[i] > 0) or not (de[i] > di[i]) or not (t[i] > 0) or not (h0[i] >= 0)
        v_dp = 2.0 * theta[i] * np.pi * r_dp[i] * 1e-3 * freq[i] / 180.0
        v_es = 2.0 * theta[i] * np.pi * r_es[i] * 1e-3 * freq[i] / 180.0
        c_dp = kw[i] * v_dp / a_dp[i]
        c_es = kw[i] * v_es / a_es[i]
        s0 = s0_in[i]
        ti, hi0 = t[i], h0[i]
        t3, t4 = t3_in[i], t4_in[i]
        d = de[i] / di[i]
        u = (d - 1.0) / d
        k1 = u * u / ((d + 1.0) / (d - 1.0) - 2.0 / ln_in[i]) / np.pi
        scale = c_e / (k1 * (de[i] * de[i]))
        f0 = _force_p(s0, ti, t4, hi0, scale)
        t_end_h = dur[i]
        # relaxation_factor at the end of the test
        if relax_time_h > 0:
            frac = _minimum(t_end_h / relax_time_h, 1.0)
        else:
            frac = 1.0
        if not (t_end_h > 0):
            frac = 0.0
        rho_end = 1.0 - relax_pct / 100.0 * frac
        t_end_s = t_end_h * 3600.0
        rate_c = c_dp + c_es
        if screening:
            rate = _maximum(_rate_p(s0, ti, t3, hi0, scale), 0.0)
            w = _wear_total(t_end_s, rate, c_dp, c_es, f0)
            for _ in range(passes):
                drop = f0 - _force_p(s0 - w, ti, t4, hi0, scale)
                rate = _maximum(drop / (w if w > _EPS else 1.0) if w > _EPS else rate, 0.0)
                w = _wear_total(t_end_s, rate, c_dp, c_es, f0)
            f_eol = rho_end * _maximum(f0 - rate * w, 0.0)
        else:
            z = hi0 / ti
            alpha = scale * t3 * (z * z + 1.0)
            beta = -1.5 * scale * ti * ti * z
            gamma = 0.5 * scale * ti
            root = np.sqrt(4.0 * alpha * gamma - beta * beta)
            # relaxation_integral_h at the end of the test
            tt = _maximum(t_end_h, 0.0)
            y_safe = relax_time_h if relax_time_h > 0 else 1.0
            if relax_time_h > 0:
                lost = tt * tt / (2.0 * y_safe) if tt <= relax_time_h else tt - relax_time_h / 2.0
            else:
                lost = tt
            target = rate_c * 3600.0 * (tt - x_rel * lost)
            if s0 > 0:
                s_end = _deflection_after(s0, target, alpha, beta, gamma, root, params, solver, callback)
            else:
                s_end = 0.0
            w = s0 - s_end
            f_eol = rho_end * _force_p(s_end, ti, t4, hi0, scale)
        share_dp = c_dp / (rate_c if rate_c > 0 else 1.0) if rate_c > 0 else 0.5
        w_dp = share_dp * w
        r_m = (r_dp[i] + r_es[i]) / 1000.0
        dax0 = _maximum(f0, 0.0) * mu[i] * r_m
        dax_eol = _maximum(f_eol, 0.0) * mu[i] * r_m
        o = out[i]
        o[PW_WDP] = w_dp
        o[PW_WES] = w - w_dp
        o[PW_W] = w
        o[PW_F0] = f0
        o[PW_FEOL] = f_eol
        o[PW_SEOL] = s0 - w
        o[PW_PDP] = _maximum(f0, 0.0) / a_dp[i]
        o[PW_PES] = _maximum(f0, 0.0) / a_es[i]
        o[PW_VDP] = v_dp
        o[PW_VES] = v_es
        o[PW_DAX0] = dax0
        o[PW_DAXEOL] = dax_eol
        o[PW_D0] = dax0 + rad[i]
        o[PW_DEOL] = dax_eol + rad[i]
        o[PW_WDP_MAX] = wear_frac * h_dp[i]
        o[PW_WES_MAX] = wear_frac * h_es[i]


@njit(cache=True, error_model="numpy")
def _wear_total(tt_s, rate, c_dp, c_es, f0):
    """The screening model's closed-form wear ``F0/R (1 - e^{-aRt})`` (``plastic_wear``'s ``wear_total``) [mm]."""
    x = (c_dp + c_es) * rate * tt_s
    if x > _EPS:
        phi = -np.expm1(-x) / x
    else:
        phi = 1.0 - 0.5 * x
    return f0 * (c_dp + c_es) * tt_s * phi



_MIX = np.uint64(0x9E3779B97F4A7C15)
_SHIFT = np.uint64(29)


@njit(cache=True, error_model="numpy")
def distinct_rows(cols, keep, back):
    """The distinct rows of the columns ``cols`` (a tuple of ``uint64`` views of float columns of one length), bit
    for bit, in one pass (open addressing on a hash of each row's bits, every match compared in full): ``keep[:k]``
    the first row of each, in order, ``back[i]`` the position in ``keep`` of row ``i``'s equal; returns ``k``. For
    :func:`synth.kernels.axial.distinct_rows`."""
    n = back.shape[0]
    size = 1
    while size < 2 * n:
        size *= 2
    mask = np.uint64(size - 1)
    table = np.full(size, -1, np.int64)
    k = 0
    for i in range(n):
        h = np.uint64(0)
        for c in range(len(cols)):
            h = (h ^ cols[c][i]) * _MIX
            h ^= h >> _SHIFT
        s = h & mask
        while True:
            r = table[s]
            if r < 0:
                table[s] = k
                keep[k] = i
                back[i] = k
                k += 1
                break
            j = keep[r]
            same = True
            for c in range(len(cols)):
                if cols[c][i] != cols[c][j]:
                    same = False
                    break
            if same:
                back[i] = r
                break
            s = (s + np.uint64(1)) & mask
    return k
