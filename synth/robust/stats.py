"""The statistics of capability, written once: process performance indices (ISO 22514-2) and the binomial interval.

Margins ``m`` are the registry's (:func:`synth.design.constraints.margin`): a
linear rescaling of the checked value with the limit at ``m = 0`` and
``m >= 0`` passing, so an index of the margin is the index of the value.

* :func:`ppk_moment`: the moment form, ``mean/(3 sd)`` (ISO 22514-2's index of a
  normal output: ``(USL - mu)/(3 sigma)`` or ``(mu - LSL)/(3 sigma)``);
* :func:`ppk_percentile`: the percentile method of ISO 22514-2 for outputs of any
  distribution: the distance of the median to the limit over the distance of the
  median to the 0.135 % quantile on the limit's side,
  ``(X50 - LSL)/(X50 - X0.135 %)`` (for a normal output it is the moment form);
* :func:`ppm_equivalent`: the one-sided probability a normal output of index
  ``Ppk`` violates its limit, ``Phi(-3 Ppk)`` (1.33: 33 ppm), the figure a bounded
  output is judged by;
* :func:`clopper_pearson`: the exact binomial interval of a violation count.

Every function takes ``(..., N)`` arrays (the last axis the samples; NaN or
inf where a check does not apply in a sample are left out): one design's checks
(:mod:`synth.robust.capability`).

>>> import numpy as np
>>> m = np.linspace(-1.0, 3.0, 100001)   # uniform margin on [-1, 3]: median 1
>>> round(float(ppk_moment(m)), 3), round(float(ppk_percentile(m)), 3)
(0.289, 0.501)
"""

from __future__ import annotations

import contextlib
import warnings

import numpy as np

__all__ = ["SD_FLOOR", "TAIL", "ppk_moment", "ppk_percentile", "ppm_equivalent", "clopper_pearson", "METHODS"]

#: a margin whose standard deviation (or percentile spread) is below this, relative, is a constant: round-off
SD_FLOOR = 1e-9
#: the tail probability of the percentile method (ISO 22514-2: the 0.135 % and 99.865 % quantiles, +/-3 sigma)
TAIL = 0.00135
#: the index forms a capability target may name
METHODS = ("percentile", "moment")


def _finite(m):
    m = np.asarray(m, dtype=float)
    return np.where(np.isfinite(m), m, np.nan)


@contextlib.contextmanager
def _quiet():
    """numpy's warnings of an all-NaN row (a check that applies in no sample) silenced: its index is set apart."""
    with warnings.catch_warnings(), np.errstate(all="ignore"):
        warnings.simplefilter("ignore", RuntimeWarning)
        yield


def _constant(passes_at_centre):
    """The index of a constant margin: +inf where it passes, -inf where it fails."""
    return np.where(passes_at_centre, np.inf, -np.inf)


def ppk_moment(m) -> np.ndarray:
    """``mean / (3 sd)`` of the finite margins along the last axis; +inf for a passing constant, -inf for a
    failing one, +inf with no finite margin (a check that never applies).

    >>> round(float(ppk_moment(np.array([0.3, 0.5, 0.7]))), 4)     # 0.5 / (3 * 0.1633)
    1.0206
    """
    x = _finite(m)
    cnt = np.sum(~np.isnan(x), axis=-1)
    with _quiet():
        mu = np.nanmean(x, axis=-1)
        sd = np.nanstd(x, axis=-1)
        const = ~(sd > SD_FLOOR * np.maximum(1.0, np.abs(mu)))
        out = np.where(const, _constant(mu >= -1e-9), mu / (3.0 * np.where(const, 1.0, sd)))
    out = np.where(cnt == 0, np.inf, out)
    return float(out) if np.ndim(out) == 0 else out


def ppk_percentile(m, tail: float = TAIL) -> np.ndarray:
    """ISO 22514-2's percentile index of the finite margins along the last axis: ``X50 / (X50 - X_tail)`` (the
    limit is 0, the margins' lower tail is the limit's side); +/-inf for a constant as :func:`ppk_moment`.

    The quantiles are the samples' (linear interpolation); with N samples the 0.135 % quantile rests on about
    ``0.00135 N`` of them (11 of 8192), which is the estimate's resolution.

    >>> from scipy.special import ndtri
    >>> normal = 4.0 + ndtri((np.arange(200000) + 0.5) / 200000)    # a normal margin, mean 4 sd 1: Ppk 4/3
    >>> round(float(ppk_percentile(normal)), 3), round(float(ppk_moment(normal)), 3)
    (1.334, 1.333)
    """
    x = _finite(m)
    cnt = np.sum(~np.isnan(x), axis=-1)
    with _quiet():
        q = _nanquantile(x, (0.5, tail))
        med, low = q[0], q[1]
        spread = med - low
        const = ~(spread > SD_FLOOR * np.maximum(1.0, np.abs(med)))
        out = np.where(const, _constant(med >= -1e-9), med / np.where(const, 1.0, spread))
    out = np.where(cnt == 0, np.inf, out)
    return float(out) if np.ndim(out) == 0 else out


def _nanquantile(x: np.ndarray, qs: tuple) -> np.ndarray:
    """``np.nanquantile(x, qs, axis=-1)``, the rows without NaN by ``np.quantile`` at once (the same values: numpy
    loops over the rows of a NaN-aware quantile one by one)."""
    if x.ndim < 2:
        return np.nanquantile(x, qs, axis=-1)
    ok = ~np.isnan(x).any(axis=-1)
    if ok.all():
        return np.quantile(x, qs, axis=-1)
    out = np.empty((len(qs),) + x.shape[:-1])
    out[:, ok] = np.quantile(x[ok], qs, axis=-1)
    out[:, ~ok] = np.nanquantile(x[~ok], qs, axis=-1)
    return out


def ppm_equivalent(ppk: float) -> float:
    """The one-sided probability of violation of a normal output of index ``ppk``: ``Phi(-3 ppk)`` [-].

    >>> round(ppm_equivalent(1.33) * 1e6, 1), round(ppm_equivalent(1.0) * 1e6)
    (33.0, 1350)
    """
    from scipy.special import ndtr
    return float(ndtr(-3.0 * float(ppk)))


def clopper_pearson(k, n: int, level: float = 0.95) -> tuple:
    """``(lo, hi)``: the exact binomial interval of ``k`` successes in ``n`` trials (``k`` an array: arrays).

    >>> [round(x, 5) for x in clopper_pearson(0, 10000)]
    [0.0, 0.00037]
    """
    from scipy.special import betaincinv
    a = (1.0 - level) / 2.0
    kk = np.asarray(k, dtype=float)
    with np.errstate(all="ignore"):
        lo = np.where(kk == 0, 0.0, betaincinv(np.maximum(kk, 1e-300), n - kk + 1, a))
        hi = np.where(kk >= n, 1.0, betaincinv(kk + 1, np.maximum(n - kk, 1e-300), 1.0 - a))
    if np.ndim(k) == 0:
        return float(lo), float(hi)
    return lo, hi
