"""Crankshaft toothed-pulley shrink fit (issue 3).

After Siczek, Rylski, Wozniak, Stachurski, "The effect of operating factors on
the behavior of the combustion engine valve timing system", Combustion
Engines 2025 (``shared/seeds/shrink_fit_pulley_paper.md``, "the paper").

One idea per module:

* :mod:`~synth.shrink_fit.roughness` -- single and equivalent roughness
  parameters, asperity radius, Komalov parameter (paper eq. 3-16);
* :mod:`~synth.shrink_fit.pressure` -- Lame contact pressure, smoothing after
  each assembly or disassembly (eq. 17-19), plasticisation limits;
* :mod:`~synth.shrink_fit.friction` -- penetration depth, coefficient k
  (Fig. 3), friction coefficient for elastic (eq. 1) and plastic-saturated
  (eq. 2) contact;
* :mod:`~synth.shrink_fit.torque` -- friction torque of the joint (eq. 1 of
  sec. 3.3), load torque on the pulley, slip margin;
* :mod:`~synth.shrink_fit.fits` -- ISO 286 fits (``30H7/u6``);
* :mod:`~synth.shrink_fit.inputs` -- validated input case;
* :mod:`~synth.shrink_fit.analysis` -- the paper's Tables 1-4 and the verdict;
* :mod:`~synth.shrink_fit.selection` -- best fit class, margin versus
  re-assembly count.
"""
