"""The portfolio page's state: a portfolio table, its screening, the summary and the platform, and their files.

The screening is :func:`synth.screen` (what ``synth bulk`` computes) called on consecutive slices of the
table, so the page can move a progress bar between them: every application is screened on its own, so
the slices' rows are the rows of one call. The summary (feasible share, what binds) is
:func:`synth.bulk.summary.summarise`; the platform rationalisation is :mod:`synth.platform` (``synth rationalise``)
on the same file. The state belongs to the browser tab, not to the page (:mod:`synth.ui.tabs`): a screening goes on
while the tab shows another page, and the portfolio page shows it again when it comes back.

Every file the page names can be downloaded (:meth:`PortfolioSession.files`): the screening's table
(``results.csv``, ``synth bulk``'s columns), the summary (``summary.md`` and its tables, ``write_summary``'s) and the
platform's files (``platform.csv``, ``assignment.csv``, ``summary.md``, ``section.html``: ``synth rationalise
--out``'s).

The table shows each row's verdict in the design page's words (PASS, INCOMPLETE, FAIL: ``synth bulk``'s
``verdict`` column, the one judgement of :mod:`synth.design.assessment`), what binds in words, margins in percent.
A row opens on the design page at the fidelity it was screened at and under the portfolio's design rules
(:meth:`PortfolioSession.set_rules`: every row, the platform and the opened application are judged by them), so the
page's verdict is the row's.

>>> p = PortfolioSession()
>>> p.sample(4, seed=0)
4
>>> t = p.run(slices=2, min_slice=1)
>>> len(t), 0.0 <= p.summary.overall["feasible_share"] <= 1.0
(4, True)
>>> sorted(p.application(0))[:2]
['application_type', 'belt_loading_type']
>>> [c["label"] for c in p.columns()][:4]
['#', 'application', 'verdict', 'what binds']
"""

from __future__ import annotations

import math
import tempfile
from pathlib import Path

from synth import formatting as fmt

__all__ = ["PortfolioSession", "COLUMNS", "verdict_word", "check_words"]

#: the smallest slice screened in one call: the engine batches its work per call (the diagnosis's relaxation probes
#: above all run in rounds over every infeasible application of the call), so small slices multiply it. Measured
#: (issue 36) on 1,000 generated applications (seed 0), CPU seconds: one call 15.7, 4 slices 24.8, 10 slices 38.5
#: (the page's 100-application slices gave 2.5x the API's cost). 500: two slices at 1,000, ten at 5,000 and above
MIN_SLICE = 500

#: the page's table: (``synth bulk``'s column, the column's label); margins are shown in percent
COLUMNS = (("application_id", "application"), ("verdict", "verdict"), ("binding_constraint", "what binds"),
           ("binding_margin", "its margin [%]"), ("violated", "violated checks (margin)"), ("relaxation", "smallest input relaxation"),
           ("application_type", "application type"), ("error", "input error"))


#: the columns sorted by a number the row keeps beside its text (a margin's percent text does not sort as text)
_SORT = {"binding_margin": {":sort": "(a, b, ra, rb) => (ra.binding_margin_value === null) - (rb.binding_margin_value "
                                    "=== null) || (ra.binding_margin_value ?? 0) - (rb.binding_margin_value ?? 0)"}}


def verdict_word(v) -> str:
    """A verdict as the design page's banner says it (``pass`` -> ``PASS``)."""
    return str(v or "").upper()


def check_words(cid) -> str:
    """A check id in words (its registry label), the id itself when the registry has none."""
    from synth.design.constraints import REGISTRY
    c = REGISTRY.get(str(cid))
    return c.label if c is not None else str(cid or "")


def _violated_words(text) -> str:
    """``synth bulk``'s ``violated`` (``id:+0.123;...``) in words and percent."""
    out = []
    for item in str(text or "").split(";"):
        cid, _, m = item.partition(":")
        if not cid:
            continue
        try:
            out.append(f"{check_words(cid)} {fmt.percent(float(m))}")
        except ValueError:
            out.append(check_words(cid))
    return "; ".join(out)


class PortfolioSession:
    """A portfolio being screened (see the module docstring)."""

    def __init__(self, workdir: str | Path | None = None):
        self.workdir = Path(workdir) if workdir else Path(tempfile.mkdtemp(prefix="synth-ui-portfolio-"))
        from synth.design.rules import NONE
        self.rules = NONE      # the design rules every application is judged by (synth bulk --rules)
        self.table = None      # the portfolio as read
        self.path: Path | None = None
        self.source = ""
        self.results = None    # synth.screen's table
        self.fidelity = "screening"  # of the screening in self.results
        self.summary = None
        self.platform = None   # synth.platform.rationalise's result
        self.platform_html = ""
        self.platform_fidelity = ""  # the model fidelity of the platform
        self.progress = (0, 0)  # (done, total) of the job running
        self.running = ""       # the job running ("screening", "platform"), "" none
        self.version = 0        # +1 whenever the table, the results or the platform change (the page redraws)
        self._files: dict[str, Path] = {}

    def load(self, path: str | Path, name: str | None = None) -> int:
        """Read a portfolio file (CSV, Excel, .ods, Parquet: ``synth bulk``'s reader); returns its row count."""
        from synth.bulk.portfolio import read_portfolio
        self.table = read_portfolio(Path(path)).reset_index(drop=True)
        self.path, self.source = Path(path), name or Path(path).name
        self.results = self.summary = self.platform = None
        self.platform_html = ""
        self._files = {}
        self.version += 1
        return len(self.table)

    def set_rules(self, path: str | Path | None) -> str:
        """Judge every application by the design rules of file ``path`` (``synth bulk --rules``, ``synth rationalise
        --rules``; None: no rules); a screening or platform made under other rules is dropped. Returns the rules in
        words."""
        from synth.design.rules import NONE, read_rules
        self.rules = NONE if path is None else read_rules(Path(path), "design rules")
        self.results = self.summary = self.platform = None
        self.platform_html = ""
        self._files = {}
        self.version += 1
        return "\n".join(self.rules.lines())

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
        self.running, self.progress = "screening", (0, n)
        try:
            for a in range(0, n, size):
                if check is not None:
                    check()
                parts.append(synth.screen(self.table.iloc[a:a + size], fidelity=fidelity, progress=False,
                                          rules=self.rules))
                self.progress = (min(n, a + size), n)
                if progress is not None:
                    progress(min(n, a + size), n)
            self.results = pd.concat(parts, ignore_index=True)
            self.fidelity = fidelity
            self.summary = summarise(self.results)
            self._files = {k: v for k, v in self._files.items() if k.startswith("platform/")}
        finally:
            self.running = ""
            self.version += 1
        return self.results

    def columns(self) -> list[dict]:
        """The table's columns for the page (``name``, ``label``): ``#`` the row, then :data:`COLUMNS` present."""
        have = set(self.results.columns) if self.results is not None else {c for c, _ in COLUMNS}
        return [{"name": "#", "label": "#"}] + [{"name": c, "label": lab, **_SORT.get(c, {})} for c, lab in COLUMNS
                                                if c in have]

    def rows(self) -> list[dict]:
        """The result table as rows for the page: ``#`` the row, the verdict as the design page says it, what binds
        in words, margins in percent as every output writes them (:func:`synth.formatting.percent`; the number
        itself in ``binding_margin_value``, which the column sorts by), the violated checks in words."""
        t = self.results
        cols = [c for c, _ in COLUMNS if c in t.columns]
        out = []
        for i, rec in enumerate(t[cols].to_dict(orient="records")):
            row = {"#": i}
            for k, v in rec.items():
                if isinstance(v, float) and not math.isfinite(v):
                    v = None
                if k == "verdict":
                    v = verdict_word(v)
                elif k == "binding_constraint":
                    v = check_words(v) if v else ""
                elif k == "binding_margin":
                    row["binding_margin_value"] = None if v is None else float(v)
                    v = fmt.percent(v) if v is not None else None
                elif k == "violated":
                    v = _violated_words(v)
                row[k] = "" if v is None else (v if isinstance(v, (bool, int, float)) else str(v))
            out.append(row)
        return out

    def verdicts(self) -> dict[str, int]:
        """How many rows have each verdict (``{"PASS": n, "INCOMPLETE": m, ...}``)."""
        return {verdict_word(k): int(v) for k, v in self.results["verdict"].value_counts().items()}

    # --- files ------------------------------------------------------------------------------------------------------
    def files(self) -> dict[str, Path]:
        """Every file the page names, by the name shown: ``results.csv`` (the screening's table, ``synth bulk``'s
        columns) once screened; ``summary/...`` (:func:`synth.bulk.summary.write_summary`) once asked for
        (:meth:`write_summary`); ``platform/...`` (``synth rationalise --out``'s files) once rationalised."""
        return dict(self._files)

    def write_results(self) -> Path:
        """The screening's table as ``results.csv`` (``synth bulk``'s file)."""
        from synth.bulk.portfolio import CSV_FLOAT, write_table
        path = write_table(self.results, self.workdir / "files" / "results.csv", float_format=CSV_FLOAT)
        self._files["results.csv"] = path
        return path

    def write_summary(self) -> dict[str, Path]:
        """The summary's files (``summary.md``, one CSV per table, the bar charts): ``synth bulk --summary``'s."""
        from synth.bulk.summary import write_summary
        folder = self.workdir / "files" / "summary"
        for p in write_summary(self.summary, folder):
            self._files[f"summary/{p.name}"] = p
        return {k: v for k, v in self._files.items() if k.startswith("summary/")}

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

    def rationalise(self, progress=None, *, fidelity: str = "full", time_limit: float | None = None) -> str:
        """The platform of the portfolio (``synth rationalise``, variants objective) at model ``fidelity`` (the page
        passes the one chosen beside its buttons, and says it): its files (``platform/...``, :meth:`files`) and its
        report section (HTML), which names ``assignment.csv`` and says how the MILP ended. The MILP's limits are the
        command's defaults (:data:`formulations.platform.NODE_LIMIT`; ``time_limit``: the wall-clock safety net,
        default :data:`formulations.platform.TIME_LIMIT_S`)."""
        from synth.design.evaluate import Settings
        from synth.platform.outputs import report_section
        from synth.platform.capable import choose, rules_capability
        from synth.platform.portfolio_feasibility import load_feasibility
        from synth.platform.rationalise import rationalise
        from synth.platform.outputs import write_all
        self.running, self.progress = "platform", (0, 1)

        def step(done, total):
            self.progress = (done, total)
            if progress is not None:
                progress(done, total)
        try:
            settings = Settings(fidelity=fidelity, rules=self.rules, capability=rules_capability(self.rules))
            pf = load_feasibility(str(self.path), settings, progress=step)
            self.platform, pf = choose(pf, lambda x: rationalise(x, "variants", **(
                {} if time_limit is None else {"time_limit": time_limit})), settings)  # the rules' targets too
            self._files = {k: v for k, v in self._files.items() if not k.startswith("platform/")}
            for p in write_all(pf, self.platform, self.workdir / "files" / "platform"):
                self._files[f"platform/{p.name}"] = p
            self.platform_html = report_section(self.platform)
            self.platform_fidelity = fidelity
        finally:
            self.running = ""
            self.version += 1
        return self.platform_html
