"""The portfolio page of ``synth ui`` (``/portfolio``): screen a portfolio, read its summary, rationalise its platform.

A portfolio file (or a synthetic sample), the screening with a progress bar, the verdicts and the feasible share,
what binds and the parts chosen as charts (labels whole, in words), the filterable table (verdicts as the design
page says them, margins in percent; a row opens that application on the design page), the platform
rationalisation, and a download for every file the page names.

The page shows the tab's :class:`~synth.ui.portfolio.PortfolioSession` (:mod:`synth.ui.tabs`): its jobs run for the
session, not for the page, so a screening goes on while the tab shows an application, and Back shows it again.
"""

from __future__ import annotations

import secrets
from pathlib import Path

from nicegui import background_tasks, ui

from synth.errors import InputError, Problem
from synth.io.limits import LIMITS, short
from synth.ui import charts, jobs
from synth.ui.portfolio import PortfolioSession, check_words
from synth.ui.session import FIDELITIES
from synth.ui.views import part_label, part_value
from synth.ui.widgets import count, download, header, refused, upload_box

__all__ = ["PortfolioPage", "PORTFOLIO_UPLOAD_LIMIT", "HANDOFF"]

#: the largest portfolio a page opens (a CSV; an .xlsx or .ods one is bounded by its unpacked size)
PORTFOLIO_UPLOAD_LIMIT = LIMITS.portfolio_bytes

#: token -> (input mapping, source, fidelity, design rules): an application of the portfolio page opened on the
#: design page, judged as its row was
HANDOFF: dict[str, tuple] = {}


class PortfolioPage:
    """One page showing a tab's portfolio session."""

    #: the most applications the sample box makes
    SAMPLE_MAX = 100_000

    def __init__(self, session: PortfolioSession, host: str, port: int):
        self.p = session
        self.shown_version = -1
        self._rows: list[dict] = []
        header(host, port)
        with ui.column().classes("full-width q-pa-md synth-ui"):
            with ui.row().classes("items-center full-width"):
                upload_box("Open a portfolio (CSV, Excel, .ods, Parquet)", ".csv,.xlsx,.xlsm,.ods,.parquet",
                           PORTFOLIO_UPLOAD_LIMIT, self.p.workdir, "portfolio", self.on_file)
                ui.label("or")
                self.n = ui.number("applications", value=200, min=1, max=self.SAMPLE_MAX, precision=0) \
                    .style("width:9em").props("data-testid=sample-n")
                ui.button("Synthetic sample", on_click=self.on_sample).props("outline data-testid=sample")
            self.loaded = ui.label().props("data-testid=loaded")
            with ui.row().classes("items-center"):
                upload_box("Design rules (YAML, TOML, JSON): every application is judged by them",
                           ".yaml,.yml,.toml,.json", LIMITS.text_input_bytes, self.p.workdir, "design rules",
                           self.on_rules)
                ui.button("No rules", on_click=self.on_no_rules).props("flat dense data-testid=no-rules")
                self.rules = ui.label().classes("text-caption").style("white-space: pre-line") \
                    .props("data-testid=rules")
            with ui.row().classes("items-center"):
                self.fidelity = ui.select(list(FIDELITIES), value=self.p.fidelity, label="fidelity").style("width:9em")
                self.run_button = ui.button("Screen the portfolio", icon="play_arrow", on_click=self.on_run) \
                    .props("data-testid=run")
                self.rat_button = ui.button("Rationalise (platform)", icon="category", on_click=self.on_rationalise) \
                    .props("outline data-testid=rationalise")
            self.bar = ui.linear_progress(value=0, show_value=False).classes("full-width")
            self.progress = ui.label().classes("text-caption").props("data-testid=progress")
            self.share = ui.label().classes("text-h6").props("data-testid=feasible-share")
            self.verdicts = ui.label().classes("text-caption").props("data-testid=verdicts")
            self.files = ui.row().classes("items-center").props("data-testid=files")
            self.plots = ui.row().classes("full-width")
            self.filter = ui.input("filter the table").props("clearable dense").style("width:24em")
            self.table = ui.table(rows=[], columns=[], row_key="#", pagination=15).classes("full-width")
            self.table.bind_filter_from(self.filter, "value")
            self.table.on("rowClick", self.on_row)
            ui.label("A row opens that application on the design page, at the fidelity it was screened at; Back "
                     "returns here.").classes("text-caption")
            self.platform_note = ui.label().classes("text-caption").props("data-testid=platform-fidelity")
            self.platform = ui.html("", sanitize=False).classes("full-width")
        self._tick()
        ui.timer(0.2, self._tick)

    # --- the session's state, shown -------------------------------------------------------------------------------
    def _tick(self) -> None:
        done, total = self.p.progress
        if self.p.running and total:
            self.bar.value = done / total
            what = "applications" if self.p.running == "screening" else "platform steps"
            self.progress.text = f"{self.p.running}: {done} of {total} {what}"
        self.run_button.set_enabled(not self.p.running)
        self.rat_button.set_enabled(not self.p.running)
        if self.p.version != self.shown_version:
            self.shown_version = self.p.version
            self.show()

    def show(self) -> None:
        p = self.p
        self.loaded.text = f"{len(p.table)} applications from {p.source}" if p.table is not None else ""
        self.rules.text = "\n".join(p.rules.lines()) or "design rules: none"
        self.fidelity.value = p.fidelity if p.results is not None else self.fidelity.value
        self.plots.clear()
        self.platform_note.text = (f"platform rationalised at {p.platform_fidelity} fidelity (the fidelity chosen "
                                   "beside the buttons)") if p.platform_html else ""
        self.platform.content = p.platform_html
        self.show_files()
        if p.results is None:
            self.share.text = self.verdicts.text = ""
            self.table.rows = self._rows = []
            if not p.running:
                self.bar.value, self.progress.text = 0, ""
            return
        n = len(p.results)
        self.bar.value, self.progress.text = 1, f"{n} of {n} applications screened ({p.fidelity} fidelity)"
        o = p.summary.overall
        self.share.text = (f"feasible share: {100 * o['feasible_share']:.1f} % ({o['feasible']} of {o['evaluated']} "
                           f"evaluated; {o['input_errors']} input errors)")
        counts = p.verdicts()
        self.verdicts.text = ("verdicts as the design page gives them: "
                              + ", ".join(f"{k} {v}" for k, v in sorted(counts.items()))
                              + (". INCOMPLETE: no check fails, but some could not be verified (the notes column of "
                                 "results.csv says which and why, e.g. the lock-up pin's data missing); feasible "
                                 "counts them." if counts.get("INCOMPLETE") else ""))
        with self.plots:
            summary, parts = self.charts()
            for opts in summary:
                _chart(opts)
            if parts:
                with ui.expansion(f"Parts chosen ({len(parts)} families)").classes("full-width") \
                        .props("dense header-class=text-weight-bold"):
                    with ui.row().classes("full-width"):
                        for opts in parts:
                            _chart(opts)
        self.table.columns = [{**c, "field": c["name"], "sortable": True, "align": "left"} for c in p.columns()]
        self.table.rows = self._rows = p.rows()

    def charts(self) -> tuple[list[dict], list[dict]]:
        """The summary as bar charts: feasible share by group, what binds, what is violated; and the parts chosen,
        one chart per family (labels whole: ``6006``, ``none`` for a class a design does not have)."""
        s, out, parts = self.p.summary, [], []
        if len(s.by_group):
            out.append(charts.bars([f"{r.group} = {r.value} (n={r.evaluated})" for r in s.by_group.itertuples()],
                                   [round(100 * x, 1) for x in s.by_group["feasible_share"]],
                                   "Feasible share by group", "feasible [%]"))
        for df, title in ((s.binding, "What binds the feasible designs"),
                          (s.violated, "Violated checks of infeasible applications (nearest design)")):
            if len(df):
                top = df.head(15)
                out.append(charts.bars([check_words(c) for c in top["constraint"]], [int(x) for x in top["count"]],
                                       title, "applications"))
        if len(s.parts):
            for fam in dict.fromkeys(s.parts["family"]):
                sub = s.parts[s.parts["family"] == fam].head(8)
                parts.append(charts.bars([part_value(x) for x in sub["part"]],
                                         [round(100 * x, 1) for x in sub["share"]],
                                         part_label(str(fam)), "share of feasible applications [%]"))
        return out, parts

    def show_files(self) -> None:
        """A download for every file the page names: the screening's table, the summary, the platform's files."""
        self.files.clear()
        with self.files:
            if self.p.results is None and not self.p.files():
                return
            ui.label("Files:").classes("text-caption")
            if self.p.results is not None:
                ui.button("results.csv", icon="download", on_click=self.get_results) \
                    .props("outline dense data-testid=file-results.csv")
                if not any(k.startswith("summary/") for k in self.p.files()):
                    ui.button("summary (summary.md, tables, charts)", icon="download", on_click=self.get_summary) \
                        .props("outline dense data-testid=file-summary")
            for name, path in self.p.files().items():
                if name == "results.csv":
                    continue
                ui.button(name, icon="download", on_click=lambda _, q=path: download(q)) \
                    .props(f"outline dense data-testid=file-{Path(name).name}")

    async def get_results(self) -> None:
        path = self.p.files().get("results.csv") or await jobs.run(self.p.write_results)
        download(path)

    async def get_summary(self) -> None:
        await jobs.run(self.p.write_summary)
        self.show_files()
        ui.notify("the summary's files are listed under Files", type="positive")

    # --- actions ---------------------------------------------------------------------------------------------------
    async def on_file(self, path: Path, name: str) -> None:
        """A portfolio received (:mod:`synth.ui.uploads`); the previous one's file is removed (the platform reads
        the file of the portfolio in view)."""
        import shutil
        old = self.p.path
        try:
            await jobs.run(self.p.load, path, name)
        except InputError as exc:
            shutil.rmtree(path.parent, ignore_errors=True)
            refused(exc, "synth: invalid portfolio")
            return
        if old is not None and old.parent.name.startswith("upload-") and old.parent != path.parent:
            shutil.rmtree(old.parent, ignore_errors=True)

    async def on_rules(self, path: Path, name: str) -> None:
        """A design rules file received: every application is judged by it from now on (a screening or platform
        made under other rules is dropped)."""
        if self._running():
            return
        try:
            await jobs.run(self.p.set_rules, path)
        except InputError as exc:
            refused(exc, "synth: invalid design rules")

    async def on_no_rules(self) -> None:
        if not self._running():
            await jobs.run(self.p.set_rules, None)

    def _running(self) -> bool:
        if self.p.running:
            ui.notify(f"the {self.p.running} is still running", type="warning")
        return bool(self.p.running)

    async def on_sample(self) -> None:
        n = count(self.n.value, "applications", self.SAMPLE_MAX)
        await jobs.run(self.p.sample, n)

    def _busy(self) -> bool:
        if self._running():
            return True
        if self.p.table is None:
            ui.notify("open a portfolio or make a sample first", type="warning")
            return True
        return False

    def _fidelity(self) -> str:
        """The model fidelity chosen beside the buttons (the screening's and the platform's)."""
        fidelity = self.fidelity.value
        if fidelity not in FIDELITIES:
            raise InputError(Problem("fidelity", short(fidelity), "one of " + ", ".join(FIDELITIES)))
        return fidelity

    async def on_run(self) -> None:
        fidelity = self._fidelity()
        if self._busy():
            return
        self.p.running, self.p.progress = "screening", (0, len(self.p.table))  # at once: a second click is refused
        background_tasks.create(_job(self.p, "screening", self.p.run, fidelity=fidelity, check=jobs.check),
                                name="synth ui: screening")
        self._tick()

    async def on_rationalise(self) -> None:
        fidelity = self._fidelity()
        if self._busy():
            return
        self.p.running, self.p.progress = "platform", (0, 1)
        background_tasks.create(_job(self.p, "platform", self.p.rationalise, fidelity=fidelity),
                                name="synth ui: platform")
        self._tick()

    def on_row(self, e) -> None:
        """A row clicked: ``e.args`` is Quasar's ``[event, row, index]``; the row's ``#`` names the application
        (anything else the page could not have sent is refused with what is accepted)."""
        args = e.args
        row = args[1] if isinstance(args, list) and len(args) > 1 else None
        if not isinstance(row, dict):
            raise InputError(Problem("row", short(args), "a row of the table, as the page sends a click"))
        i = self.p.row(row.get("#"))
        token = secrets.token_urlsafe(8)
        label = self._rows[i].get("application_id") if i < len(self._rows) else None
        HANDOFF[token] = (self.p.application(i), f"{self.p.source}: {label or f'row {i + 1}'}", self.p.fidelity,
                          self.p.rules)
        ui.navigate.to(f"/?open={token}")


def _chart(opts: dict) -> None:
    height = 70 + 26 * len(opts["yAxis"]["data"])
    ui.echart(opts).style(f"width:48%;height:{height}px")


async def _job(p: PortfolioSession, what: str, fn, **kw) -> None:
    """Run ``fn`` for the session (not for a page: the tab may show another page meanwhile); its error is shown by
    every page of the session's tab that is open, and logged."""
    try:
        await jobs.run(fn, **kw)
    except Exception as exc:  # noqa: BLE001 - every error a message in the page
        p.running = ""
        p.version += 1
        from nicegui import Client
        from synth.ui.messages import message_of
        import logging
        logging.getLogger("synth.ui").warning("%s: %s", what, message_of(exc))
        for client in list(Client.instances.values()):
            page = getattr(client, "_synth_portfolio", None)
            if page is not None and page.p is p and not client.is_deleted:
                with client:
                    refused(exc, f"synth: {what}" if isinstance(exc, InputError) else "synth ui")
