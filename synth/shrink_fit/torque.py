"""Torque the joint carries and torque that loads the crankshaft pulley.

* friction torque of the fit, paper eq. (1) of sec. 3.3 (after [5]):
  ``M = 0.5 pi d^2 L mu p`` (the tangential friction stress ``mu p`` on the
  cylinder ``pi d L`` at the lever arm ``d/2``);
* load torque on the crankshaft pulley from the camshaft friction torque.

Load rules (named choice, see ``docs/sections/shrink_fit.md``):

* ``"power_balance"`` (default): the belt carries the camshaft torque to a
  pulley ``u`` times smaller, ``M_h = n_cam M_c / u`` (power balance
  ``M_h omega_crank = n_cam M_c omega_cam``, ``omega_crank = u omega_cam``);
* ``"paper"``: ``M_h = M_c u``, what the paper's sec. 3.1 does
  (0.8 * 60 Nm * 2 = 96 Nm).
"""

from __future__ import annotations

import numpy as np

from synth.design.constraints import REGISTRY, margin

__all__ = ["LOAD_RULES", "friction_torque_nm", "pulley_load_torque_nm", "slip_margin"]

LOAD_RULES = ("power_balance", "paper")


def friction_torque_nm(journal_outer_diameter_mm, bore_length_mm, mu, pressure_mpa):
    """Friction torque ``M = 0.5 pi d^2 L mu p`` [Nm] the fit carries (paper eq. 1, sec. 3.3).

    d [mm], L [mm], mu [-], p [MPa]; N mm converted to N m. Table 4, new,
    47.73 MPa, mu(2) = 0.441004: 446.36 Nm.

    >>> round(float(friction_torque_nm(30, 15, 0.441004, 47.73)), 2)
    446.37
    """
    d, length = np.asarray(journal_outer_diameter_mm, dtype=float), np.asarray(bore_length_mm, dtype=float)
    p = np.clip(np.asarray(pressure_mpa, dtype=float), 0.0, None)
    return 0.5 * np.pi * d**2 * length * np.asarray(mu, dtype=float) * p * 1e-3


def pulley_load_torque_nm(camshaft_torque_nm, gear_ratio, camshafts=1, rule="power_balance"):
    """Torque [Nm] loading the crankshaft pulley from the camshaft friction torque.

    ``rule="power_balance"``: ``camshafts * M_c / u`` (physically correct);
    ``rule="paper"``: ``M_c * u`` (paper sec. 3.1, ``camshafts`` ignored).
    The paper's 1500 rpm point (M_c = 0.8 * 60 Nm, u = 2):

    >>> float(pulley_load_torque_nm(48.0, 2, rule="paper")), float(pulley_load_torque_nm(48.0, 2))
    (96.0, 24.0)
    """
    mc, u = np.asarray(camshaft_torque_nm, dtype=float), np.asarray(gear_ratio, dtype=float)
    if rule == "paper":
        return mc * u
    if rule == "power_balance":
        return np.asarray(camshafts, dtype=float) * mc / u
    raise ValueError(f"load rule {rule!r}: expected one of {LOAD_RULES}")


def slip_margin(friction_torque_nm, load_torque_nm, slip_safety=1.0):
    """Normalised slip margin ``(M - S M_h) / (S M_h)`` [-] (>= 0: the pulley does not slip): the margin of the
    registry's slip check (``shrink_fit_slip_worn``, :func:`synth.design.constraints.margin`).

    >>> round(float(slip_margin(150.0, 96.0, 1.5)), 4)
    0.0417
    """
    return margin(REGISTRY["shrink_fit_slip_worn"], friction_torque_nm,
                  np.asarray(slip_safety, dtype=float) * np.asarray(load_torque_nm, dtype=float))
