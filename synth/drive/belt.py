"""The belt's named defaults: EA per rib (spans, elongation), the length-measuring tension, the elongation.

A poly-V (PK) belt is specified by its effective length, measured on a
two-pulley fixture under a measuring tension; installed at the drive's
tension ``T`` it is longer by its elastic elongation

    dL = L (T / n - t_m) / EA_rib                       [mm]

(``n`` ribs, ``t_m`` the measuring tension per rib and strand, ``EA_rib``
its quasi-static stiffness per rib per unit strain). The spans of the
rotational model (:mod:`synth.drive.modes`) have the stiffness ``EA / L_span``,
``EA = n EA_rib``.

The reports imply two stiffnesses, and synth keeps both (sources in
docs/sections/drive.md, "EA per rib"):

* :data:`EA_PER_RIB_N` -- the spans' stiffness in the rotational model
  (modes, the periodic response), fitted on the first system mode of one drive
  design report (Gates AG00686, 8PK1475, "System Vibration Analysis", Mode 1
  12.61 Hz; transcribed in the public repository ``kaydgn/MFSim``,
  ``tests/fixtures/fead-validation.js``, indexed by
  ``docs/gates-reports/README.md``). The belt literature's values (Hwang,
  Perkins, Ulsoy 1994; Beikmann et al. 1996; Kong and Parker 2003) could not
  be reached beyond their abstracts with the search tools: the number is the
  report's, said so. :data:`EA_PER_RIB_RANGE_N` is the range the reports
  imply: the first-mode fits of the six drives whose vibration inputs are
  transcribed, 7.6 kN (AG00810) to 13.5 kN (AG0868 8PK).
* :data:`ELONGATION_EA_PER_RIB_N` and :data:`MEASURING_TENSION_PER_RIB_N` --
  the reports print the drive length and the required belt length at every
  arm position; their difference is the belt's elongation at the design
  tension. Over the fourteen drives of the repository above (4 to 10 ribs,
  258-766 N, 1013-1739 mm) it fits ``dL = L (T/n - t_m) / EA_rib`` with
  ``t_m = 50.3 N`` and ``EA_rib = 19.2 kN``, every drive within 0.06 mm (the
  columns print 0.1 mm): 50 N per rib and strand (a measuring force of 100 N
  per rib) and a quasi-static stiffness almost twice the rotational model's.
  The rotational model's span stiffness lumps what it leaves out (the belt's
  compliance in the grooves and on the arcs), so the two are kept apart.

>>> round(elongation_mm(1475.0, 765.7, 8, ELONGATION_EA_PER_RIB_N), 1)  # AG00686 prints 1478.5 - 1475.0 mm
3.5
"""

from __future__ import annotations

__all__ = ["EA_PER_RIB_N", "EA_PER_RIB_RANGE_N", "ELONGATION_EA_PER_RIB_N", "MEASURING_TENSION_PER_RIB_N",
           "elongation_mm"]

#: the spans' stiffness EA per rib in the rotational model [N per unit strain]: Gates AG00686's first mode (module)
EA_PER_RIB_N = 10_700.0
#: the range of the rotational model's EA per rib over the reports' first-mode fits [N]
EA_PER_RIB_RANGE_N = (7_600.0, 13_500.0)
#: the belt's quasi-static EA per rib from the measuring tension to the drive's [N] (fourteen reports' fit)
ELONGATION_EA_PER_RIB_N = 19_200.0
#: the belt's tension per rib and strand on the length-measuring fixture [N] (fourteen reports' fit)
MEASURING_TENSION_PER_RIB_N = 50.0


def elongation_mm(length_mm, tension_n, ribs, ea_per_rib_n, measuring_tension_per_rib_n=MEASURING_TENSION_PER_RIB_N):
    """Elastic elongation of a belt of measured length ``length_mm`` at the span tension ``tension_n`` [mm].

    ``dL = L (T / n - t_m) / EA_rib``; negative below the measuring tension.
    """
    return length_mm * (tension_n / ribs - measuring_tension_per_rib_n) / ea_per_rib_n
