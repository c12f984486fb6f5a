"""``python -m synth``: the same as the ``synth`` command (:func:`synth.cli.main`)."""

import sys

from synth.cli import main

sys.exit(main())
