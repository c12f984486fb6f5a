"""The belt drive around the tensioner: layout, statics, modes, periodic response with the arm's dry friction.

See ``docs/sections/drive.md`` for the equations. The API:

* :func:`synth.drive.inputs.load_drive` -- a drive file through the input gate;
* :func:`analyse` -- statics, natural frequencies, the speed sweep, theta_pp and f at the durability speed,
  whether the arm locks or the belt goes slack, and the tolerance check of the periodic solution.
"""

from synth.drive.analysis import analyse, durability_point, tensioner_checks
from synth.drive.inputs import Drive, example_drive, load_drive

__all__ = ["Drive", "load_drive", "example_drive", "analyse", "durability_point", "tensioner_checks"]
