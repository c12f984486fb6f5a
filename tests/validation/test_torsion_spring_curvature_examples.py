"""Published worked values of the torsion-spring curvature (stress correction) factor, eq. (74).

Source: engineeringprep.com problem 484 "Correction Factor" (helical torsion spring, d = 5 mm,
D = 50 mm: C = 10, Ki = (4C^2 - C - 1)/(4C(C - 1)) = 389/360 = 1.08). Tolerance: the exact fraction of
its solution, and its printed 1.08 to half a unit of the last digit. (neutrondb.com's calculator notes
print "For C = 8, KB = 1.106" for the same formula, which gives 247/224 = 1.103: a misprint, not used.) No published
EN 13906-3 worked example of a whole torsion spring (stress, active coils, stiffness) was found; the
stiffness and coil formulas are checked by hand calculations in tests/test_torsion_spring.py.
"""

import pytest

from synth.model import torsion_spring as ts


def test_engineeringprep_problem_484():
    c = float(ts.spring_index(50.0, 5.0, 5.0, True))
    assert c == 10.0
    assert float(ts.curvature_factor(c)) == pytest.approx(389 / 360, rel=1e-12)   # exact fraction of the solution
    assert float(ts.curvature_factor(c)) == pytest.approx(1.08, abs=0.005)

