"""The capability settings: targets and estimators, plain values in one place.

:class:`RobustSettings` is what ``--capability``, ``--ppm``, ``--samples`` and
``--seed`` set, and what a later design-rules input (a ``rules:`` section) can
fill from a mapping with :meth:`RobustSettings.from_mapping`: every field is a
plain number with its accepted range, checked here.

* ``capability``: the smallest process performance index Ppk every checked
  constraint must reach (1.33 is the usual automotive target: the nearest
  limit 4 standard deviations from the mean); None: no index target;
* ``method``: how the index is computed (ISO 22514-2): ``"percentile"`` (the
  default: ``(X50 - LSL)/(X50 - X0.135 %)``, for outputs of any distribution)
  or ``"moment"`` (``(mu - LSL)/(3 sigma)``, a normal output's); either way a
  bounded output (its scatter from uniform quantities only) is judged by its
  probability of violation against the ppm a normal output of the target's
  index has (1.33: 33 ppm);
* ``ppm``: the largest probability of violation per check, in parts per
  million (the upper end of its 95 % interval must be below it); None: no ppm
  target;
* ``samples``: Monte Carlo samples per design (scrambled Sobol points; a power
  of two keeps their balance), ``seed``: the seed of every random stream (the
  same seed gives the same numbers);
* ``rare_samples``: importance samples per check for probabilities the Monte
  Carlo does not resolve (fewer than ``rare_min_failures`` violations among
  the samples).

>>> RobustSettings.from_mapping({"capability": 1.33, "samples": 4096}).capability
1.33
>>> RobustSettings(capability=None, ppm=None).targets()
'none'
"""

from __future__ import annotations

from dataclasses import dataclass, fields

from synth.errors import InputError, Problem
from synth.io.limits import COUNTS  # one bound for the command line's --samples and the Python API
from synth.robust.stats import METHODS, ppm_equivalent

__all__ = ["RobustSettings", "DEFAULT_SAMPLES", "SEARCH_SAMPLES", "BULK_SAMPLES"]

#: Monte Carlo samples of one design's capability (2^13)
DEFAULT_SAMPLES = 8192
#: Monte Carlo samples per candidate in the robust synthesis and the bulk capability (2^11): every candidate and
#: the design reported are judged by the same estimator
SEARCH_SAMPLES = 2048
#: Monte Carlo samples per candidate in ``synth bulk --capability`` (2^10): each row's robust synthesis (``synth
#: design --capability --samples 1024`` gives the same row)
BULK_SAMPLES = 1024

_RANGES = {
    "capability": (0.0, 10.0, "a process performance index Ppk in (0, 10] (1.33 is the usual target)"),
    "ppm": (0.0, 1e6, "parts per million in (0, 1000000]"),
    "samples": (64, COUNTS["--samples"].hi, f"an integer from 64 to {COUNTS['--samples'].hi} (a power of two keeps the Sobol balance)"),
    "seed": (0, 2**32 - 1, "an integer from 0 to 4294967295"),
    "rare_samples": (100, 1_000_000, "an integer from 100 to 1000000"),
    "rare_min_failures": (1, 10_000, "an integer from 1 to 10000"),
}


@dataclass(frozen=True)
class RobustSettings:
    """Capability targets and estimator settings (see the module docstring)."""

    capability: float | None = 1.33
    ppm: float | None = None
    method: str = "percentile"
    samples: int = DEFAULT_SAMPLES
    seed: int = 20240601
    rare_samples: int = 2000
    rare_min_failures: int = 10

    def __post_init__(self):
        for f in fields(self):
            v = getattr(self, f.name)
            if v is None and f.name in ("capability", "ppm"):
                continue
            if f.name == "method":
                if v not in METHODS:
                    raise InputError(Problem("method", v, " or ".join(METHODS) + " (ISO 22514-2 index forms)"))
                continue
            lo, hi, accepted = _RANGES[f.name]
            ok = isinstance(v, (int, float)) and not isinstance(v, bool) and lo < v <= hi if f.name in (
                "capability", "ppm") else isinstance(v, int) and not isinstance(v, bool) and lo <= v <= hi
            if not ok:
                raise InputError(Problem(f.name, v, accepted))

    @classmethod
    def from_mapping(cls, data: dict, where: str = "robust") -> "RobustSettings":
        """Settings from a mapping of the field names (unknown names are an error naming them)."""
        known = {f.name for f in fields(cls)}
        bad = [k for k in data if k not in known]
        if bad:
            raise InputError(Problem(f"{where}.{bad[0]}", data[bad[0]], "one of " + ", ".join(sorted(known))))
        return cls(**data)

    def targets(self) -> str:
        """The targets in words, naming the index's method: ``Ppk >= 1.33 (percentile method, ...)``,
        ``P(violation) <= 10 ppm``, both, or ``none``."""
        out = []
        if self.capability is not None:
            out.append(f"Ppk >= {self.capability:g} ({self.method} method, ISO 22514-2; bounded outputs: "
                       f"P(violation) <= {ppm_equivalent(self.capability) * 1e6:.3g} ppm)")
        if self.ppm is not None:
            out.append(f"P(violation) <= {self.ppm:g} ppm")
        return " and ".join(out) or "none"
