"""Physics of the tensioner: one module per thing modelled, each naming its thesis step.

============== =========================================== ============
module         what it models                              thesis step
============== =========================================== ============
layout         layout, pulley width, lock-up pin            0, eq. (17)-(27)
ball_bearing   bearing selection by hubload (Table 1)       1
pivot          pivot class, arm and pivot walls (Table 2)   2
damping        lever, friction circle, damping split        3, eq. (7)-(16)
plain_bushing  metal-polymer pivot bushing: p, pv, wear     4, eq. (28)-(42)
friction_wear  plastic friction elements: wear, EOL damping 5, eq. (43)-(49)
stackup        axial tolerance stack of the cone-spring gap 6
packaging      axial stack, spring housing                  7, eq. (50)-(54)
disc_spring    cone (disc) spring, Almen-Laszlo / DIN 2092  8, eq. (55)-(63)
torsion_spring main torsion (leg) spring, EN 13906-3        9, eq. (64)-(93)
bolted_joint   tilting, sliding, fixation bolt (thesis)     10, eq. (94)-(111)
vdi2230        fixation bolt by VDI 2230 Part 1 (2015)      10 (method vdi2230)
input_guards   range checks of the inputs (InputError)      -
============== =========================================== ============

Conventions: pure functions on numpy arrays (scalars broadcast), units in
argument names (``_mm``, ``_n``, ``_nm``, ``_mpa``, ``_deg``), docstrings that
cite the thesis equation (``eq. (n)``) or the standard they implement.
Constants come from :mod:`synth.catalog`, never bare literals. Verdicts are
not made here: :mod:`synth.design` declares the constraints and evaluates them.
"""
