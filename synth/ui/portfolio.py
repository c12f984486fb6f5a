"""The portfolio page's state: a portfolio table, its screening, the summary and the platform.

The screening is :func:`synth.screen` (what ``synth bulk`` computes) called on consecutive slices of the
table, so the page can move a progress bar between them: every application is screened on its own, so
the slices' rows are the rows of one call. The summary (feasible share, what binds) is
:func:`synth.bulk.summary.summarise` and its plots :func:`synth.bulk.summary.write_summary`'s; the
platform rationalisation is :mod:`synth.platform` (``synth rationalise``) on the same file.

>>> p = PortfolioSession()
>>> p.sample(4, seed=0)
4
>>> t = p.run(slices=2, min_slice=1)
>>> len(t), 0.0 <= p.summary.overall["feasible_share"] <= 1.0
(4, True)
>>> sorted(p.application(0))[:2]
['application_type', 'belt_loading_type']
"""

from __future__ import annotations

import math
import tempfile
from pathlib import Path

__all__ = ["PortfolioSession", "TABLE_COLUMNS"]

#: the smallest slice screened in one call: the engine's batch work per call (its diagnosis probes above all) costs
#: 0.3-0.7 s whatever the slice's size, so 200 applications took 3.2 s in one call, 5.9 s in 4 and 9.3 s in 10
MIN_SLICE = 100

#: the result columns the page's table shows after the application's id (``synth bulk``'s names)
TABLE_COLUMNS = ("application_type", "status", "feasible", "binding_constraint", "binding_margin", "violated",
                 "relaxation", "error")


class PortfolioSession:
    """A portfolio being screened (see the module docstring)."""

    def __init__(self, workdir: str | Path | None = None):
        self.workdir = Path(workdir) if workdir else Path(tempfile.mkdtemp(prefix="synth-ui-portfolio-"))
        self.table = None      # the portfolio as read
        self.path: Path | None = None
        self.source = ""
        self.results = None    # synth.screen's table
        self.summary = None
        self.platform = None   # synth.platform.rationalise's result

    def load(self, path: str | Path, name: str | None = None) -> int:
        """Read a portfolio file (CSV, Excel, .ods, Parquet: ``synth bulk``'s reader); returns its row count."""
        from synth.bulk.portfolio import read_portfolio
        self.table = read_portfolio(Path(path)).reset_index(drop=True)
        self.path, self.source = Path(path), name or Path(path).name
        self.results = self.summary = self.platform = None
        return len(self.table)

    def sample(self, n: int, seed: int = 0) -> int:
        """A synthetic portfolio of ``n`` applications (``synth portfolio-sample``), kept as a CSV for the platform."""
        from synth.bulk.portfolio import write_table
        from synth.bulk.sample import sample_portfolio
        path = write_table(sample_portfolio(n, seed=seed), self.workdir / f"sample_{n}_{seed}.csv")
        return self.load(path, f"sample of {n} (seed {seed})")

    def run(self, progress=None, *, fidelity: str = "screening", slices: int = 10, min_slice: int = MIN_SLICE,
            check=None):
        """Screen every application (:func:`synth.screen`); ``progress(done, total)`` after each slice.

        ``slices`` slices, none smaller than ``min_slice`` applications (the last one aside); ``check()`` is called
        before each slice (:func:`synth.ui.jobs.check`: it raises to end the screening when the server stops)."""
        import pandas as pd

        import synth
        from synth.bulk.summary import summarise
        n = len(self.table)
        size = max(1, min_slice, math.ceil(n / max(1, slices)))
        parts = []
        for a in range(0, n, size):
            if check is not None:
                check()
            parts.append(synth.screen(self.table.iloc[a:a + size], fidelity=fidelity, progress=False))
            if progress is not None:
                progress(min(n, a + size), n)
        self.results = pd.concat(parts, ignore_index=True)
        self.summary = summarise(self.results)
        return self.results

    def plots(self) -> list[Path]:
        """The summary's bar charts (feasible share by group, binding and violated constraints, parts)."""
        from synth.bulk.summary import write_summary
        folder = self.workdir / "summary"
        return [p for p in write_summary(self.summary, folder) if p.suffix == ".png"]

    def rows(self) -> tuple[list[dict], list[str]]:
        """The result table as rows for the page (``#`` the row, the application id, :data:`TABLE_COLUMNS`)."""
        t = self.results
        cols = [c for c in ("application_id", *TABLE_COLUMNS) if c in t.columns]
        out = []
        for i, rec in enumerate(t[cols].to_dict(orient="records")):
            row = {"#": i}
            for k, v in rec.items():
                if isinstance(v, float):
                    v = None if not math.isfinite(v) else round(v, 4)
                row[k] = "" if v is None else (v if isinstance(v, (bool, int, float)) else str(v))
            out.append(row)
        return out, ["#", *cols]

    def row(self, value) -> int:
        """``value`` (what the page sent for a row) as a row of the screened table, or an
        :class:`~synth.errors.InputError` saying what is accepted (a row number in [0, n - 1]).

        >>> p = PortfolioSession()
        >>> p.row(0)
        Traceback (most recent call last):
        ...
        synth.errors.InputError: row: got 0; accepted: a row of a screened portfolio (none is screened yet)
        """
        from synth.errors import InputError, Problem
        from synth.io.limits import short
        if self.table is None or self.results is None:
            raise InputError(Problem("row", short(value), "a row of a screened portfolio (none is screened yet)"))
        n = len(self.results)
        if isinstance(value, bool) or not isinstance(value, int) or not 0 <= value < n:
            raise InputError(Problem("row", short(value), f"a row number of the table, an integer in [0, {n - 1}]"))
        return value

    def application(self, i: int) -> dict:
        """The design input of row ``i`` (the portfolio's field columns, as ``synth bulk`` reads them)."""
        from synth.bulk.portfolio import row_record
        return row_record(self.table.iloc[int(i)].to_dict())

    def rationalise(self, progress=None, *, fidelity: str = "full", time_limit: float = 60.0) -> str:
        """The platform of the portfolio (``synth rationalise``, variants objective); its report section (HTML)."""
        from synth.design.evaluate import Settings
        from synth.platform.outputs import report_section
        from synth.platform.producer import load_feasibility
        from synth.platform.rationalise import rationalise
        pf = load_feasibility(str(self.path), Settings(fidelity=fidelity), progress=progress)
        self.platform = rationalise(pf, "variants", time_limit=time_limit)
        return report_section(self.platform)
