"""Made parts: material mass x material price plus a process term, each with its stated basis.

=============== ======================================================== =================================
part            material mass                                            process term
=============== ======================================================== =================================
main spring     wire length x section x density; the length per unit     per spring (``process:main_
                compliance ``L k = pi E I / 180`` (thesis eq. 64-65)      spring``) and per metre of wire
                does not depend on the mean diameter, so the spring's    coiled (``process:main_spring_
                price per unit compliance is one number per material     coiling``: the machine's time is
                and wire (a rectangular wire: ``cost_wire_rectangular_   the length over its feed rate)
                factor`` on its material price)
cone spring     annulus ``pi/4 (De^2 - Di^2) t`` of the nominal cone     per part (``process:cone_spring``)
                spring (Table 7's middle ratios: about 5 % of its price)
damper pad,     contact area x axial height x the compound's density     per part (``process:damper_pad``,
endcap spacer   (``cost_plastic_density_kg_m3``)                         ``process:endcap_spacer``)
pivot bushing   wrapped wall ``pi D t L`` at the nominal pivot diameter  per part (``process:pivot_bushing``)
                (``cost_bushing_nominal_diameter_mm``), per kg of the
                supplier's bushing (``material:pivot_bushing_<supplier>``)
=============== ======================================================== =================================

>>> round(float(spring_length_times_stiffness_m(206000.0, np.pi * 3.0 ** 4 / 64)), 5)
0.01431
>>> round(float(annulus_mass_kg(30.0, 15.0, 1.0)) * 1000, 2)
4.16
"""

from __future__ import annotations

import numpy as np

__all__ = ["spring_length_times_stiffness_m", "annulus_mass_kg", "moulded_mass_kg", "wrapped_bushing_mass_kg"]


def spring_length_times_stiffness_m(E_mpa, second_moment_mm4):
    """Active wire length x stiffness [m Nm/deg] of a torsion spring: ``L k = pi E I / 180`` (thesis eq. 64-65:
    ``k = E I / (L)`` per radian, ``L = pi Dm n_a``), ``E`` [MPa], ``I`` [mm^4]; the wire length of a spring of
    stiffness ``k`` [Nm/deg] is this over ``k``.

    >>> round(float(spring_length_times_stiffness_m(206000.0, 3.976)) / 0.02, 3)
    0.715
    """
    return np.pi * np.asarray(E_mpa, float) * np.asarray(second_moment_mm4, float) / (180.0 * 1000.0) / 1000.0


def annulus_mass_kg(outer_mm, inner_mm, thickness_mm, density_kg_m3=7850.0):
    """Mass [kg] of a flat annulus ``rho pi/4 (De^2 - Di^2) t`` (a cone spring's blank)."""
    return density_kg_m3 * np.pi / 4.0 * (np.asarray(outer_mm, float) ** 2 - np.asarray(inner_mm, float) ** 2) \
        * np.asarray(thickness_mm, float) * 1e-9


def moulded_mass_kg(area_mm2, height_mm, density_kg_m3):
    """Mass [kg] of a moulded friction element: its contact area x its axial height x the compound's density.

    >>> round(float(moulded_mass_kg(290.0, 2.5, 1350.0)) * 1000, 3)
    0.979
    """
    return density_kg_m3 * np.asarray(area_mm2, float) * np.asarray(height_mm, float) * 1e-9


def wrapped_bushing_mass_kg(diameter_mm, wall_mm, length_mm, density_kg_m3=7850.0):
    """Mass [kg] of a wrapped bushing ``rho pi D t L`` (``D`` its mean diameter, ``t`` its wall)."""
    return density_kg_m3 * np.pi * np.asarray(diameter_mm, float) * np.asarray(wall_mm, float) \
        * np.asarray(length_mm, float) * 1e-9
