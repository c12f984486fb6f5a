"""The design page of ``synth ui`` (``/``): the input form, the checks, the design and what can be made of it.

Left, the input form (:mod:`synth.ui.form`); right, the verdict digest and tabs: every check coloured by its verdict;
the design (parts, what binds, diagnosis, notes); the ranked alternatives side by side, one of which can be applied;
a what-if sweep of one input against the margins; the production capability (Ppk and ppm per check, histograms,
what drives each check's scatter); the thesis's graphs; the 3D model. Editing a field re-validates the input and
re-verifies the current design at once (:class:`synth.ui.session.DesignSession`), in the server's process: nothing
else runs there. The 3D model, the graphs, the report and the capability are made by worker processes
(:mod:`synth.ui.worker`, :mod:`synth.ui.work`) when their tab or a download asks, and kept: the model by the
design's hash (an edit that leaves the geometry as it is reuses it), the graphs by the result.

This module lays the page out, shows the result (status, digest, checks, the design tab), switches the tabs and
writes the downloads; the form is :mod:`synth.ui.design_form`, the alternatives, what-if, capability and graphs tabs
:mod:`synth.ui.design_tabs`, the 3D model :mod:`synth.ui.model_view` (mixins of :class:`DesignPage`).

The page's session belongs to the browser tab (:mod:`synth.ui.tabs`): leaving for the portfolio and coming back
shows the design as it was left.
"""

from __future__ import annotations

import html
from pathlib import Path

from nicegui import ui

from synth.errors import InputError, Problem
from synth.io.limits import short
from synth.ui import jobs, views, worker
from synth.ui.design_form import DESIGN_UPLOAD_LIMIT, InputForm
from synth.ui.design_tabs import ALTERNATIVES, CAPABILITY, CHECKS, DESIGN, GRAPHS, MODEL, TABS, WHATIF, ResultTabs
from synth.ui.model_view import ModelView
from synth.ui.session import FIDELITIES, TOP_MAX, DesignSession, offered_objectives
from synth.ui.trace import mark
from synth.ui.widgets import count, download, header, in_page, refused, stem

__all__ = ["DesignPage", "DESIGN_UPLOAD_LIMIT", "TABS"]


class DesignPage(InputForm, ResultTabs, ModelView):
    """One page showing a tab's design session (see the module docstring): the form (:class:`InputForm`), the
    results and their tabs (:class:`ResultTabs`, :class:`ModelView`), the downloads; ``launch``: the server's
    :class:`synth.ui.launch.Launch` (not imported here: the launch imports this module while the browser loads)."""

    def __init__(self, session: DesignSession, root: Path, host: str, port: int, *, launch=None):
        self.root, self.s, self.launch = root, session, launch
        self.widgets: dict = {}
        self.graphs_key = self.capability_key = None
        self.model_key: str | None = None   # the model shown in the 3D view (the design's hash)
        self.details_key: tuple | None = None
        self.view: dict | None = None        # the 3D view's framing (views.fit_view)
        self._reports: dict[tuple, dict] = {}
        self.design_seq: int | None = None  # the evaluation the design tab shows
        self.tab = CHECKS
        header(host, port)
        pane = "height:calc(100vh - 64px);overflow-y:auto;flex-wrap:nowrap"  # form and results scroll apart
        with ui.row().classes("full-width no-wrap items-start synth-ui"):
            with ui.column().classes("q-pa-sm").style(f"width:34%;min-width:330px;{pane}"):
                self.build_form()
            with ui.column().classes("q-pa-sm").style(f"width:66%;{pane}"):
                self._results()
        mark("design page built")
        self.show_problems()
        self.show_result()
        if self.s.result is None and self.s.input is not None:
            self.status.text = "synthesising..."
            in_page(self.status, self.first_design)

    async def first_design(self) -> None:
        """The page's first design: the launch's result when the input is the launch's, else a synthesis."""
        result = await self.launch.result_for(self.s) if self.launch is not None else None
        if result is not None:
            self.s.adopt(result)
            mark("design page: the launch's result shown")
            if not self.launch.warmed:  # the first page shows its checks: the workers import what comes next,
                self.launch.warmed = True  # and this process what an edit verifies with
                parts = dict(result.parts or {})
                ui.timer(1.0, lambda: (worker.warm("cad"), worker.warm("design"), self.launch.warm_server(parts)),
                         once=True)
        else:
            await self.call_api(self.s.synthesise)
        self.show_result()

    # --- the result ------------------------------------------------------------------------------------------
    def _results(self) -> None:
        with ui.row().classes("items-center"):
            ui.select(list(offered_objectives()), value=self.s.objective, label="objective",
                      on_change=self.on_objective).props("dense").style("width:8em")
            ui.select(list(FIDELITIES), value=self.s.fidelity, label="fidelity",
                      on_change=self.on_fidelity).props("dense").style("width:8em")
            self.top = ui.number("alternatives K", value=self.s.top, min=1, max=TOP_MAX, precision=0) \
                .props("dense data-testid=top").style("width:8em")
            ui.button("Synthesise", icon="auto_fix_high", on_click=self.on_synthesise).props("data-testid=synthesise")
            ui.separator().props("vertical")
            for label, kind in (("STEP", "step"), ("Report HTML", "html"), ("Report PDF", "pdf"),
                                ("Workbook", "xlsx"), ("Input YAML", "yaml")):
                ui.button(label, icon="download", on_click=lambda _, k=kind: self.download(k)) \
                    .props(f"outline dense data-testid=download-{kind}")
        self.status = ui.label().classes("text-caption")
        self.digest_css = ui.html("", sanitize=False).style("display:none")  # the digest's style sheet, sent once
        self.seq = ui.label().props("data-testid=seq").classes("text-caption text-grey")
        self.digest = ui.html("", sanitize=False).classes("full-width")
        with ui.tabs().classes("full-width").props("dense") as tabs:
            made = {name: ui.tab(name).props(f"data-testid=tab-{name.replace(' ', '-').lower()}") for name in TABS}
        with ui.tab_panels(tabs, value=made[CHECKS], on_change=self.on_tab).classes("full-width").props("keep-alive"):
            self.panels = {name: ui.tab_panel(made[name]) for name in TABS}
            with self.panels[CHECKS]:
                self.checks = ui.html("", sanitize=False).classes("full-width")
            with self.panels[DESIGN]:
                ui.label("Parts").classes("text-subtitle1")
                self.parts = ui.html("", sanitize=False)
                ui.label("What binds (smallest margins)").classes("text-subtitle1")
                self.binding = ui.html("", sanitize=False)
                ui.label("Diagnosis and relaxations").classes("text-subtitle1")
                self.diagnosis = ui.html("", sanitize=False)
                ui.label("Notes").classes("text-subtitle1")
                self.notes = ui.html("", sanitize=False)
        self._built = {CHECKS, DESIGN}  # the other tabs are built when first opened: the first page is light

    def _build(self, name: str) -> None:
        """Build tab ``name``'s panel the first time it is opened."""
        if name in self._built or name not in self.panels:
            return
        self._built.add(name)
        with self.panels[name]:
            {ALTERNATIVES: self.build_alternatives_panel, WHATIF: self.build_whatif_panel,
             CAPABILITY: self.build_capability_panel, GRAPHS: self.build_graphs_panel,
             MODEL: self.build_model_panel}[name]()

    def show_result(self) -> None:
        r = self.s.result
        if r is None:
            self.status.text = "no design yet: complete the input" if self.s.input is None else "synthesising..."
            return
        how = f" ({r.solver}, objective {r.objective})" if r.solver else " (the current design, for the input as edited)"
        if r.solver and self.s.applied and self.s.applied > 1:
            how = f" (alternative #{self.s.applied} of the {r.objective or self.s.objective} ranking, verified)"
        self.status.text = (f"{r.status} design{how}, fidelity {r.settings.get('fidelity', self.s.fidelity)}: "
                            f"verdict {r.verdict}")
        self.status.classes(replace="text-positive" if r.verdict == "pass" else "text-negative")
        css, self.digest.content = views.digest(r)
        self.digest_css.content = f"<style>{css}</style>"  # the same text every time: NiceGUI sends it once
        self.checks.content = views.checks_table(r)
        if self.tab == DESIGN:  # the design tab's tables when it is in view (on_tab draws them when opened)
            self.show_design()
        if ALTERNATIVES in self._built:
            self.show_alternatives()
        if CAPABILITY in self._built:
            self.show_capability()
        self.seq.text = f"evaluation {self.s.seq}"
        self.seq.props["data-seq"] = str(self.s.seq)
        self.seq.update()
        if self.tab == GRAPHS:  # drawn for the tab in view only: an edit stays a 5 ms round trip
            in_page(self.graphs, self.draw_graphs)
        elif self.tab == MODEL:
            self.follow_edit()
        elif self.tab == WHATIF and self.sweep_field.value and self.sweep_note.text:
            self.sweep_note.text = "the design changed: run the sweep again for this one"

    def show_design(self) -> None:
        """The design tab's tables (parts, what binds, diagnosis, notes) of the result in view, once per result."""
        r = self.s.result
        if r is None or self.design_seq == self.s.seq:
            return
        self.design_seq = self.s.seq
        self.parts.content = views.parts_table(r)
        self.binding.content = views.binding_table(r)
        self.diagnosis.content = views.diagnosis_html(r)
        self.notes.content = "<ul>" + "".join(f"<li>{html.escape(str(n))}</li>" for n in r.notes) + "</ul>"

    async def on_tab(self, e) -> None:
        self.tab = e.value
        self._build(self.tab)
        if self.tab == DESIGN:
            self.show_design()
        elif self.tab == ALTERNATIVES:
            self.show_alternatives()
        elif self.tab == CAPABILITY:
            self.show_capability()
        elif self.tab == GRAPHS:
            await self.draw_graphs()
        elif self.tab == MODEL:
            self.wake()
            await self.draw_model()
        elif self.tab == WHATIF:
            self.fill_sweep_fields()

    def on_objective(self, e) -> None:
        if e.value not in offered_objectives():  # a value no option of the drop-down sends
            e.sender.value = self.s.objective
            raise InputError(Problem("objective", short(e.value), "one of " + ", ".join(offered_objectives())))
        self.s.objective = e.value

    async def on_fidelity(self, e) -> None:
        if e.value not in FIDELITIES:
            e.sender.value = self.s.fidelity
            raise InputError(Problem("fidelity", short(e.value), "one of " + ", ".join(FIDELITIES)))
        self.s.fidelity = e.value
        if self.s.input is not None and self.s.result is not None:
            self.s.verify()
            self.show_result()

    async def call_api(self, fn, *args) -> bool:
        """``fn(*args)`` in a job's thread; an error is shown as the command line words it."""
        try:
            await jobs.run(fn, *args)
            return True
        except Exception as exc:  # noqa: BLE001 - every error a message in the page
            refused(exc)
            return False

    async def on_synthesise(self) -> None:
        if self.s.input is None:
            ui.notify("complete the input first: the marked fields", type="warning")
            return
        self.s.top = count(self.top.value, "alternatives K", TOP_MAX)
        self.status.text = "synthesising..."
        await self.call_api(self.s.synthesise)
        self.show_result()

    # --- downloads --------------------------------------------------------------------------------------------------------
    async def download(self, kind: str) -> None:
        if kind == "yaml":
            return self.save_yaml()
        r = self.s.result
        if r is None:
            ui.notify("no design to export yet", type="warning")
            return
        note = ui.notification("writing the " + ("3D model" if kind == "step" else "report") + "...",
                               spinner=True, timeout=None)
        try:
            if kind == "step":
                path = (await worker.lane("cad").call("step", r, str(self.root), self.s.application()))["path"]
            else:
                files = await self.report(kind == "pdf")
                path = files.get(kind)
                if not path or not Path(path).is_file():
                    ui.notify(files.get("pdf_note") or f"no {kind} written", type="warning")
                    return
        finally:
            note.dismiss()
        download(path, stem(self.s.source) + "_" + Path(path).name)

    async def report(self, pdf: bool) -> dict:
        """The report of the result in view (the ``design`` worker: :func:`synth.ui.work.report`), with the 3D
        model's pictures when CadQuery can draw them (the ``cad`` worker, at the same time: the pictures only, not the
        geometric checks the 3D tab shows); once per result in this page, and its PDF once per document in the
        worker (a design edited and back is not printed again)."""
        r, key = self.s.result, self.result_key()
        hit = self._reports.get((key, pdf)) or (self._reports.get((key, True)) if not pdf else None)
        if hit is not None:
            return hit
        pictures = worker.lane("cad").submit("pictures", r, str(self.root))
        graphs = worker.lane("design").submit("graphs", r)  # drawn while the pictures are
        try:
            det = await pictures
            shown = (det["section"], det["exploded"])
        except InputError:  # no CadQuery, or a design it cannot draw: the report says so
            shown = ()
        await graphs
        folder = self.s.workdir / f"report-{key}{'-pdf' if pdf else ''}"
        files = await worker.lane("design").call("report", r, str(folder), pdf=pdf, source=self.s.source,
                                                 pictures=shown, root=str(self.root))
        self._reports[(key, pdf)] = files
        return files
