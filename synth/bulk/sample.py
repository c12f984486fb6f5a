"""Synthetic portfolios for tests, demos and benchmarks.

:func:`sample_portfolio` turns :func:`synth.data.generated_applications.generate`
(two thesis families, inputs drawn over the ranges of the thesis's
applications) into a portfolio table with an ``application_id`` column, and
can break ``broken`` rows on purpose, cycling through the kinds of bad data
a real portfolio holds (:data:`BREAKAGES`): a missing required field, an
out-of-range number, an unknown choice and non-numeric text.

>>> t = sample_portfolio(6, seed=2, broken=2)
>>> len(t), list(t.columns[:2]), int(t["application_id"].str.startswith("APP-").sum())
(6, ['application_id', 'application_type'], 6)
"""

from __future__ import annotations

import numpy as np
import pandas as pd

from synth.bulk.portfolio import to_table
from synth.data.generated_applications import generate
from synth.io.limits import check_count

__all__ = ["BREAKAGES", "sample_portfolio", "break_rows"]

#: kind -> (field, bad cell value); the error each gives names that field
BREAKAGES = {
    "missing_required": ("differential_angle_deg", None),
    "out_of_range": ("working_arm_mm", 45.0),
    "unknown_choice": ("application_type", "wet"),
    "non_numeric": ("calculated_torque_target_nm", "three"),
}


def break_rows(table: pd.DataFrame, k: int, seed: int = 0) -> tuple[pd.DataFrame, dict[int, str]]:
    """A copy of ``table`` with ``k`` distinct rows broken (kinds of :data:`BREAKAGES` in turn).

    Returns the table and ``{row position: kind}``.
    """
    k = check_count("--broken", k, hi=len(table))
    rng = np.random.default_rng(seed + 7919)
    rows = sorted(int(i) for i in rng.choice(len(table), size=k, replace=False))
    out = table.astype(object).copy()
    kinds = list(BREAKAGES)
    broken = {}
    for j, i in enumerate(rows):
        kind = kinds[j % len(kinds)]
        name, value = BREAKAGES[kind]
        out.at[i, name] = value
        broken[i] = kind
    return out, broken


def sample_portfolio(n: int, seed: int = 0, broken: int = 0) -> pd.DataFrame:
    """A synthetic portfolio of ``n`` applications (seeded), ``broken`` of them with bad data.

    Columns: ``application_id`` (``APP-00001``...) then every design-input
    field. The same ``(n, seed, broken)`` gives the same table.
    """
    n, seed = check_count("N", n), check_count("--seed", seed)
    table = to_table(generate(n, seed=seed))
    table.insert(0, "application_id", [f"APP-{i + 1:05d}" for i in range(len(table))])
    if broken:
        table, _ = break_rows(table, broken, seed=seed)
    return table
