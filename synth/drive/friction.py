"""The tensioner's dry friction: a regularised Coulomb torque, the locking limit, Den Hartog's closed form.

The friction the synthesised tensioner is designed for is the thesis's
damping ``D`` (eq. (9)-(13): half the width of the hysteresis loop, the same
torque in loading and unloading, N m about the pivot). In the drive it is a
Coulomb torque opposing the arm's speed, regularised so that a smooth
periodic solution exists:

    T_f(psi') = D tanh(psi' / eps),      eps = eps_rel * V

with ``V`` the arm's peak speed in the periodic solution itself (a fixed
point the solver reaches in a few passes), so ``eps_rel`` is a fraction of
the motion's own scale. ``eps -> 0`` is
Coulomb's law; the drive's tolerance check halves ``eps_rel`` and doubles the
harmonics and says whether the answer moved (:mod:`synth.drive.response`).
Limits: the friction is rate-independent and symmetric; the radial part of
``D`` is taken at the nominal hub load (it follows the hub load in reality);
a regularised arm that should stick creeps at speeds of order ``eps``.

The arm locks when its friction can hold every torque the belt puts on it
with the arm held still (Zhu and Parker 2008, J. Vib. Acoust. 130 011002:
"the critical amplitude of the dry friction torque beyond which the system
operates with a locked arm is determined analytically"): with the arm's
degree of freedom removed, the belt's torque on the arm is
``-sum_j g_j dT_j(t)`` and the critical friction torque is its peak
(:func:`critical_friction_torque_nm`); it does not depend on the spring.

:func:`den_hartog_amplitude` is the exact steady amplitude of a single mass
on a spring with Coulomb friction under a harmonic force, for motion without
stops (J. P. Den Hartog, "Forced vibrations with combined viscous and Coulomb
damping", Phil. Mag. S. 7, Vol. 9, No. 59 (1930) 801-817, section II "Only
Coulomb damping"):

    x0 / (P/k) = sqrt( V^2 - (F/P)^2 U^2 ),   V = 1 / (1 - b^2),
    U = sin(pi/b) / (b (1 + cos(pi/b))),      b = w / w_n,

which the tests use to check the harmonic-balance solution and the
time integration of the regularised model.
"""

from __future__ import annotations

import numpy as np

__all__ = ["friction_torque_nm", "friction_slope", "den_hartog_amplitude", "critical_friction_torque_nm"]


def friction_torque_nm(speed_rad_s, friction_nm, eps_rad_s):
    """Regularised Coulomb torque ``D tanh(psi'/eps)`` [N m] (opposes the speed when subtracted).

    >>> [round(float(t), 4) for t in friction_torque_nm(np.array([-1.0, 0.0, 1.0]), 2.0, 0.01)]
    [-2.0, 0.0, 2.0]
    """
    return friction_nm * np.tanh(np.asarray(speed_rad_s, dtype=float) / eps_rad_s)


def friction_slope(speed_rad_s, friction_nm, eps_rad_s):
    """``dT_f/dpsi' = D / eps / cosh^2(psi'/eps)`` [N m s/rad] (the harmonic balance's Jacobian)."""
    x = np.clip(np.asarray(speed_rad_s, dtype=float) / eps_rad_s, -350.0, 350.0)
    return friction_nm / eps_rad_s / np.cosh(x) ** 2


def den_hartog_amplitude(force_amplitude, friction_force, stiffness, frequency_ratio):
    """Den Hartog's exact amplitude of Coulomb-damped forced motion without stops (units of force/stiffness).

    ``frequency_ratio`` is ``w / w_n``. Returns NaN where the motion has stops (the root is imaginary).

    >>> round(float(den_hartog_amplitude(1.0, 0.0, 1.0, 0.5)), 6)  # undamped: 1 / (1 - b^2)
    1.333333
    >>> round(float(den_hartog_amplitude(100.0, 20.0, 4000.0, 0.6) * 1000), 3)  # [mm]
    38.765
    """
    b = np.asarray(frequency_ratio, dtype=float)
    v = 1.0 / (1.0 - b ** 2)
    u = np.sin(np.pi / b) / (b * (1.0 + np.cos(np.pi / b)))
    root = v ** 2 - (np.asarray(friction_force, float) / np.asarray(force_amplitude, float)) ** 2 * u ** 2
    with np.errstate(invalid="ignore"):
        return np.where(root > 0, np.asarray(force_amplitude, float) / stiffness * np.sqrt(root), np.nan)


def critical_friction_torque_nm(locked_arm_torque_nm) -> float:
    """The friction torque above which the arm stays locked: the peak of the belt's torque on the held arm.

    ``locked_arm_torque_nm``: samples over one period of ``-sum_j g_j dT_j(t)`` with the arm held (its mean is
    the spring's nominal torque and is taken off).

    >>> critical_friction_torque_nm(1.5 * np.cos(np.linspace(0, 2 * np.pi, 64, endpoint=False)))
    1.5
    """
    t = np.asarray(locked_arm_torque_nm, dtype=float)
    return float(np.max(np.abs(t - t.mean())))
