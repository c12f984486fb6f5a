"""Den Hartog (Phil. Mag. 1930; the file keeps its 1931 name): a mass on a spring with Coulomb friction,
forced harmonically, motion without stops.

Source: J. P. Den Hartog, "Forced vibrations with combined viscous and Coulomb damping", Phil. Mag. S. 7,
Vol. 9, No. 59 (1930) 801-817, section II "Only Coulomb damping": the exact steady amplitude
``x0 = (P/k) sqrt(V^2 - (F/P)^2 U^2)``, ``V = 1/(1 - b^2)``, ``U = sin(pi/b) / (b (1 + cos(pi/b)))``.

The drive's friction model (a regularised Coulomb torque) and both of its solvers (the harmonic balance on
the friction coordinate, :func:`synth.drive.response.harmonic_balance`, and a :func:`scipy.integrate.solve_ivp`
integration) must reproduce the closed form: the harmonic balance within 2 % at the drive's default
regularisation (1 % of the peak speed) and 24 harmonics, and within 1 % when the regularisation is halved
and the harmonics doubled (the drive's tolerance check).

Why this anchor: the published anchors of issue 26 (Beikmann, Perkins, Ulsoy 1996; Zhu and Parker 2008;
Long et al. 2019 and 2025) could not be read beyond their abstracts and the first lines of Long et al. 2025's
Appendix A with the search tools, in two searches; docs/sections/drive.md lists source by source what was reached.
The first page of Den Hartog's paper was reached (a scan): section II, its eq. (1) and the notation used here.
Den Hartog's closed form is the classical exact solution the dry-friction tensioner literature checks against.
"""

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from synth.drive.friction import den_hartog_amplitude
from synth.drive.response import harmonic_balance

M, K, P = 1.0, 4000.0, 100.0
WN = np.sqrt(K / M)


def _hb(friction, b, H, eps_rel):
    w = b * WN
    h = np.arange(H + 1)
    R = 1.0 / (K - M * (h * w) ** 2)
    lin = np.zeros(H + 1, complex)
    lin[1] = P * R[1]
    eps = eps_rel * w * abs(lin[1])
    for _ in range(3):  # the drive's fixed point: eps from the solution's own peak speed
        r = harmonic_balance(lin, R, w, friction, eps)
        phase = np.exp(1j * np.outer(np.linspace(0, 2 * np.pi, 2048, endpoint=False), h))
        x = (phase @ r["psi"]).real
        eps = eps_rel * np.max(np.abs((phase @ (1j * h * w * r["psi"])).real))
    return (x.max() - x.min()) / 2.0, r["converged"]


@pytest.mark.parametrize("friction,b", [(20.0, 0.6), (30.0, 1.5), (10.0, 0.9), (40.0, 2.0)])
def test_harmonic_balance_reproduces_den_hartog(friction, b):
    exact = float(den_hartog_amplitude(P, friction, K, b))
    coarse, ok = _hb(friction, b, 24, 0.01)
    fine, ok2 = _hb(friction, b, 48, 0.005)
    assert ok and ok2
    assert coarse == pytest.approx(exact, rel=0.02)
    assert fine == pytest.approx(exact, rel=0.01)


def test_time_integration_of_the_regularised_model_reproduces_den_hartog():
    friction, b = 20.0, 0.6
    w = b * WN
    eps = 1e-3 * w * 0.0388  # 0.1 % of the peak speed

    def rhs(t, y):
        return [y[1], (P * np.cos(w * t) - K * y[0] - friction * np.tanh(y[1] / eps)) / M]

    T = 2 * np.pi / w
    sol = solve_ivp(rhs, (0, 60 * T), [0.0, 0.0], method="LSODA", rtol=1e-9, atol=1e-12,
                    t_eval=np.linspace(59 * T, 60 * T, 400))
    amp = (sol.y[0].max() - sol.y[0].min()) / 2
    assert amp == pytest.approx(float(den_hartog_amplitude(P, friction, K, b)), rel=0.005)
