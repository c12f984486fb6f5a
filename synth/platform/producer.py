"""Where ``synth rationalise`` gets its feasibility data.

``PORTFOLIO`` is either a portfolio table (``.csv``, ``.xlsx``, ``.parquet``; its
feasibility comes from the vectorised evaluator, which fills
:class:`~synth.platform.data.PortfolioFeasibility`) or ``synthetic:N[:SEED]``
(:func:`synth.platform.synthetic.synthetic_portfolio`, illustrative data for trying the
command and for benchmarks).

The evaluator's producer is wired in by :data:`PRODUCER`: a callable
``(path) -> PortfolioFeasibility``. Until the evaluator provides it, a table path gives a
clear input error.
"""

from __future__ import annotations

from synth.errors import InputError, Problem
from synth.platform.data import PortfolioFeasibility, validate

__all__ = ["load_feasibility", "PRODUCER"]

#: ``(portfolio path) -> PortfolioFeasibility``; set by the evaluator's module when it exists
PRODUCER = None


def load_feasibility(portfolio: str) -> PortfolioFeasibility:
    """The feasibility data of ``portfolio`` (see the module docstring), validated.

    >>> len(load_feasibility("synthetic:3:1").apps)
    3
    >>> load_feasibility("synthetic:many")
    Traceback (most recent call last):
    ...
    synth.errors.InputError: PORTFOLIO: got 'synthetic:many'; accepted: synthetic:N[:SEED] with whole numbers N >= 1, SEED >= 0
    """
    if portfolio.startswith("synthetic:"):
        from synth.platform.synthetic import synthetic_portfolio
        parts = portfolio.split(":")[1:]
        try:
            n, seed = int(parts[0]), int(parts[1]) if len(parts) > 1 else 0
        except (ValueError, IndexError):
            n, seed = -1, -1
        if len(parts) > 2 or n < 1 or seed < 0:
            raise InputError(Problem("PORTFOLIO", portfolio, "synthetic:N[:SEED] with whole numbers N >= 1, SEED >= 0"))
        return validate(synthetic_portfolio(n, seed=seed))
    if PRODUCER is None:
        raise InputError(Problem("PORTFOLIO", portfolio,
                                 "synthetic:N[:SEED] (the evaluator's portfolio feasibility producer is not wired yet)"))
    return validate(PRODUCER(portfolio))
