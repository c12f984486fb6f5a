"""The design page of ``synth ui`` (``/``): the input form, the checks, the design and what can be made of it.

Left, the input form (:mod:`synth.ui.form`); right, the verdict digest and tabs: every check coloured by its verdict;
the design (parts, what binds, diagnosis, notes); the ranked alternatives side by side, one of which can be applied;
a what-if sweep of one input against the margins; the production capability (Ppk and ppm per check, histograms,
what drives each check's scatter); the thesis's graphs; the 3D model. Editing a field re-validates the input and
re-verifies the current design at once (:class:`synth.ui.session.DesignSession`), in the server's process: nothing
else runs there. The 3D model, the graphs, the report and the capability are made by worker processes
(:mod:`synth.ui.worker`, :mod:`synth.ui.work`) when their tab or a download asks, and kept: the model by the
design's hash (an edit that leaves the geometry as it is reuses it), the graphs by the result.

The page's session belongs to the browser tab (:mod:`synth.ui.tabs`): leaving for the portfolio and coming back
shows the design as it was left.
"""

from __future__ import annotations

import asyncio
import html
import time
from pathlib import Path

from nicegui import ui

from synth import schema
from synth.errors import InputError, Problem
from synth.io.limits import LIMITS, short
from synth.ui import charts, form, jobs, views, worker
from synth.ui.session import FIDELITIES, TOP_MAX, DesignSession, offered_objectives
from synth.ui.trace import mark
from synth.ui.widgets import FILES_URL, count, download, header, in_page, number, png, refused, stem, upload_box

__all__ = ["DesignPage", "DESIGN_UPLOAD_LIMIT", "TABS"]

#: the largest design input a page opens: the Excel template's limit (a YAML, TOML or JSON one is at most 8 MB)
DESIGN_UPLOAD_LIMIT = max(LIMITS.workbook_bytes, LIMITS.text_input_bytes)

CHECKS, DESIGN, ALTERNATIVES, WHATIF, CAPABILITY, GRAPHS, MODEL = (
    "Checks", "Design", "Alternatives", "What if", "Capability", "Graphs", "3D model")
#: the tabs of the results, in order
TABS = (CHECKS, DESIGN, ALTERNATIVES, WHATIF, CAPABILITY, GRAPHS, MODEL)

#: the 3D view's canvas [px]
SCENE_W, SCENE_H = 860, 540
#: frames per second of the 3D view: while it is turned or zoomed (and 3 s after), at rest in view, out of view.
#: NiceGUI's scene draws at a fixed rate whatever happens; in a browser drawing WebGL on the CPU (no GPU: headless,
#: a remote desktop) 20 frames a second of the model took 0.6 of a core and an edit's checks waited 0.9 s behind them
FPS_ACTIVE, FPS_REST, FPS_HIDDEN = 20, 2, 0.5
#: seconds the view keeps its full rate after the last turn or zoom
AWAKE_S = 3.0
#: seconds without an edit before the 3D view follows the design (the model of a design being typed is not built:
#: each build is seconds of a worker's CPU, which the next edit's checks would wait behind on a busy machine)
REDRAW_PAUSE_S = 0.6


class DesignPage:
    """One page showing a tab's design session (see the module docstring); ``launch``: the server's
    :class:`synth.ui.launch.Launch` (not imported here: the launch imports this module while the browser loads)."""

    def __init__(self, session: DesignSession, root: Path, host: str, port: int, *, launch=None):
        self.root, self.s, self.launch = root, session, launch
        self.widgets: dict = {}
        self.graphs_key = self.capability_key = None
        self.model_key: str | None = None   # the model shown in the 3D view (the design's hash)
        self.details_key: tuple | None = None
        self.view: dict | None = None        # the 3D view's framing (views.fit_view)
        self._reports: dict[tuple, dict] = {}
        self._loading = False
        self.design_seq: int | None = None  # the evaluation the design tab shows
        self._edited_at = 0.0               # the last edit's time (time.monotonic) while the 3D view is open
        self._redrawing = False             # a redraw of the 3D view waits for the edits to pause
        self.tab = CHECKS
        header(host, port)
        pane = "height:calc(100vh - 64px);overflow-y:auto;flex-wrap:nowrap"  # form and results scroll apart
        with ui.row().classes("full-width no-wrap items-start synth-ui"):
            with ui.column().classes("q-pa-sm").style(f"width:34%;min-width:330px;{pane}"):
                self._form()
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
            await self._api(self.s.synthesise)
        self.show_result()

    # --- the form -------------------------------------------------------------------------------------------
    def _form(self) -> None:
        with ui.row().classes("items-center"):
            upload_box("Open an input (YAML, TOML, JSON, Excel)", ".yaml,.yml,.toml,.json,.xlsx,.ods",
                       DESIGN_UPLOAD_LIMIT, self.s.workdir, "input file", self.on_file).classes("full-width")
            ui.button("Save YAML", icon="download", on_click=self.save_yaml).props("outline dense")
            ui.button("Excel template", icon="grid_on", on_click=self.save_template).props("outline dense")
        self.source_label = ui.label().classes("text-caption")
        self.rules_label = ui.label().classes("text-caption").props("data-testid=rules")
        self.other_box = ui.label().classes("text-negative text-caption")
        for section, fields in form.sections():
            with ui.expansion(section, value=True).classes("full-width").props("dense header-class=text-weight-bold"):
                for f in fields:
                    with ui.element("div").classes("full-width").props(f"data-field={f.name}"):
                        self.widgets[f.name] = self._widget(f)

    def _widget(self, f: schema.Field):
        text = self.s.texts[f.name]
        if form.widget(f) == "select":
            opts = form.options(f)
            el = ui.select(opts, label=form.label(f), clearable=not f.required).classes("full-width").props("dense")
            _select_value(el, opts, text)
        else:
            el = ui.input(form.label(f), value=form.shown(text)).classes("full-width").props("dense")
        el.props["bottom-slots"] = True
        el.props["hide-bottom-space"] = True  # a long hint or message grows the field, never overlaps the next
        el.without_auto_validation()  # synth.schema validates, not NiceGUI
        el.on_value_change(lambda e, name=f.name: self.on_edit(name, e.value))
        self._hint(f, el)
        return el

    def _hint(self, f: schema.Field, el) -> None:
        text = self.s.texts[f.name]
        kept = form.shown(text) != text
        hint = form.hint(f) + (f"; the value kept is {text} (shown rounded)" if kept else "")
        if el.props.get("hint") != hint:
            el.props["hint"] = hint
            el.update()

    def fill_form(self) -> None:
        """The boxes from the session (after a file is opened)."""
        self._loading = True
        try:
            for f in schema.FIELDS:
                el, text = self.widgets[f.name], self.s.texts[f.name]
                if form.widget(f) == "select":
                    _select_value(el, form.options(f), text)
                else:
                    el.value = form.shown(text)
                    self._hint(f, el)
        finally:
            self._loading = False

    def show_problems(self) -> None:
        for name, el in self.widgets.items():
            _messages(el, self.s.problems.get(name, []))
        self.other_box.text = "; ".join(self.s.other_problems)
        self.source_label.text = f"input: {self.s.source}" if self.s.source else ""
        lines = self.s.rule_lines()
        self.rules_label.text = (lines[0] + ": " + "; ".join(x.strip() for x in lines[1:])) if lines else ""

    def on_edit(self, name: str, value) -> None:
        if self._loading:
            return
        mark("edit received")
        text = "" if value is None else str(value)
        if text == form.shown(self.s.texts[name]) and text != self.s.texts[name]:
            return  # the rounded number the box shows: the value kept is unchanged
        valid = self.s.edit(name, text)
        self._hint(schema.field_by_name(name), self.widgets[name])
        self.show_problems()
        if valid:
            self.show_result()
            mark("edit shown")
        else:
            self.status.text = ("input not valid (see the marked fields): the checks shown are those of the last "
                                "valid input")
            self.status.classes(replace="text-negative")

    async def on_file(self, path: Path, name: str) -> None:
        """An input file received (:mod:`synth.ui.uploads`): read it (values and design rules), then synthesise."""
        import shutil
        try:
            values, rules = await jobs.run(self.s.read, path)
        except InputError as exc:
            refused(exc)
            return
        finally:
            shutil.rmtree(path.parent, ignore_errors=True)  # read: the copy is not kept
        if self.s.open(values, rules, name):
            self.status.text = "synthesising..."
            await self._api(self.s.synthesise)
        self.fill_form()
        self.show_problems()
        self.show_result()

    def save_yaml(self) -> None:
        ui.download.content(self.s.yaml_text(), stem(self.s.source) + ".yaml", "application/x-yaml")

    def save_template(self) -> None:
        try:
            path = self.s.write_template(self.s.workdir / (stem(self.s.source) + ".xlsx"))
        except InputError as exc:
            refused(exc, "the template needs a valid input")
            return
        if not self.s.rules.empty():
            ui.notify("the Excel template holds no design rules: " + (self.s.rules.name or "the input's rules")
                      + " are not in it (Save YAML keeps them)", type="warning", multi_line=True)
        ui.download.file(path)

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
            {ALTERNATIVES: self._alternatives_panel, WHATIF: self._whatif_panel, CAPABILITY: self._capability_panel,
             GRAPHS: self._graphs_panel, MODEL: self._model_panel}[name]()

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
            self._edited_at = time.monotonic()
            if not self._redrawing:  # one waiting redraw follows every edit
                self._redrawing = True
                in_page(self.model_note, self.redraw_model)
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

    async def _api(self, fn, *args) -> bool:
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
        await self._api(self.s.synthesise)
        self.show_result()

    # --- alternatives ---------------------------------------------------------------------------------------------
    def _alternatives_panel(self) -> None:
        ui.label("The K best designs of the last synthesis in objective order (set K beside Synthesise); a part "
                 "that differs from #1 is marked. Apply one to make it the current design (verified for the input "
                 "as it is now).").classes("text-caption")
        self.apply_row = ui.row().classes("items-center")
        self.alternatives = ui.html("", sanitize=False).classes("full-width")

    def show_alternatives(self) -> None:
        self.alternatives.content = views.compare_alternatives(self.s.alternatives, self.s.applied)
        self.apply_row.clear()
        with self.apply_row:
            for a in self.s.alternatives:
                rank = a["rank"]
                ui.button(f"Apply #{rank}", on_click=lambda _, k=rank: self.on_apply(k)) \
                    .props(f"dense {'outline' if rank != self.s.applied else ''} data-testid=apply-{rank}")

    async def on_apply(self, rank: int) -> None:
        if self.s.input is None:
            ui.notify("complete the input first: the marked fields", type="warning")
            return
        await self._api(self.s.apply, rank)
        self.show_result()

    # --- what if ----------------------------------------------------------------------------------------------------
    def _whatif_panel(self) -> None:
        ui.label("One input swept across a range with the current design's parts kept: every check's margin at each "
                 "value (synth.verify), the checks that fail or come closest drawn, the design point and the limit "
                 "marked.").classes("text-caption")
        with ui.row().classes("items-center"):
            self.sweep_field = ui.select({}, label="input", with_input=True, on_change=self.on_sweep_field) \
                .props("dense data-testid=sweep-field").style("width:22em")
            self.sweep_lo = ui.number("from", format="%.6g").props("dense data-testid=sweep-lo").style("width:9em")
            self.sweep_hi = ui.number("to", format="%.6g").props("dense data-testid=sweep-hi").style("width:9em")
            self.sweep_n = ui.number("points", value=21, min=3, max=101, precision=0).props("dense") \
                .style("width:6em")
            ui.button("Sweep", icon="show_chart", on_click=self.on_sweep).props("data-testid=sweep")
        self.sweep_note = ui.label().classes("text-caption")
        self.sweep_chart = ui.echart({"series": []}).classes("full-width").style("height:440px") \
            .props("data-testid=sweep-chart")

    def fill_sweep_fields(self) -> None:
        fields = self.s.sweep_fields()
        opts = {n: form.label(schema.field_by_name(n)) for n in fields}
        if self.sweep_field.options != opts:
            self.sweep_field.set_options(opts, value=self.sweep_field.value if self.sweep_field.value in opts
                                         else ("spring_stiffness_nm_per_deg" if "spring_stiffness_nm_per_deg" in opts
                                               else next(iter(opts), None)))

    def on_sweep_field(self, e) -> None:
        if e.value and self.s.input is not None and e.value in self.s.sweep_fields():
            lo, hi = self.s.sweep_range(e.value)
            self.sweep_lo.value, self.sweep_hi.value = float(f"{lo:.6g}"), float(f"{hi:.6g}")

    async def on_sweep(self) -> None:
        name = self.sweep_field.value
        if not name:
            raise InputError(Problem("sweep input", None, "an input of the list"))
        lo, hi = number(self.sweep_lo.value, "from"), number(self.sweep_hi.value, "to")
        n = count(self.sweep_n.value, "points", 101, lo=3)
        self.sweep_note.text = "sweeping..."
        data = await jobs.run(self.s.sweep, name, lo, hi, n)
        labels = {c.id: c.label for c in self.s.result.checks}
        f = schema.field_by_name(name)
        self.sweep_chart.options.clear()
        self.sweep_chart.options.update(charts.sweep(data, labels, unit=f.unit))
        self.sweep_chart.update()
        failing = sorted({labels.get(c, c) for c, ms in data["margins"].items()
                          if any(m is not None and m < 0 for m in ms)})
        self.sweep_note.text = (f"{len(data['x'])} points of {name} from {views.eng(data['x'][0])} to "
                                f"{views.eng(data['x'][-1])}, the design at {views.eng(data['design_x'])}; "
                                + (f"fails somewhere in the range: {', '.join(failing)}" if failing
                                   else "every check passes across the range"))

    # --- capability ---------------------------------------------------------------------------------------------------
    def _capability_panel(self) -> None:
        ui.label("The production capability of the current design (synth.capability, as synth robust): each check's "
                 "process performance Ppk and share out of limits (ppm) under the catalog's tolerance model, "
                 "histograms of the scattered values against their windows, and what drives each check's scatter. "
                 "A Monte Carlo study: seconds to a minute.").classes("text-caption")
        with ui.row().classes("items-center"):
            self.cap_target = ui.number("target Ppk", value=1.33, min=0, format="%.3g") \
                .props("dense data-testid=cap-target").style("width:8em")
            self.cap_ppm = ui.number("ppm limit (optional)", min=0).props("dense data-testid=cap-ppm") \
                .style("width:11em")
            ui.button("Study the capability", icon="insights", on_click=self.on_capability) \
                .props("data-testid=capability")
        self.cap_note = ui.label().classes("text-caption")
        self.cap_summary = ui.html("", sanitize=False).classes("full-width")
        self.cap_table = ui.html("", sanitize=False).classes("full-width")
        self.cap_hist = ui.row().classes("full-width")
        with ui.row().classes("items-center"):
            self.cap_check = ui.select({}, label="what drives the scatter of", on_change=self.show_contributors) \
                .props("dense").style("width:26em")
        self.cap_contrib = ui.echart({"series": []}).classes("full-width").style("height:300px")

    async def on_capability(self) -> None:
        r, seq = self.s.result, self.s.seq
        if r is None or not r.parts:
            raise InputError(Problem("design", None, "a design to study (synthesise first)"))
        target = number(self.cap_target.value, "target Ppk", optional=True)
        ppm = number(self.cap_ppm.value, "ppm limit", optional=True)
        self.cap_note.text = "studying the capability (a Monte Carlo over the tolerance model)..."
        robust = await worker.lane("design").call("capability", r, target, ppm)
        if seq != self.s.seq:
            self.cap_note.text = "the design changed while it was studied: study it again"
            return
        self.s.result.robust = robust  # the result's own record, as synth.capability sets it: digest and report read it
        self.cap_note.text = ""
        self.show_result()

    def show_capability(self) -> None:
        robust = (self.s.result.robust if self.s.result is not None else None) or {}
        key = (self.s.seq, id(robust))
        if key == self.capability_key:
            return
        self.capability_key = key
        self.cap_summary.content = views.capability_summary(robust)
        self.cap_table.content = views.capability_table(robust) if robust.get("checks") else ""
        self.cap_hist.clear()
        if robust.get("histograms"):
            from synth.report.robust import HISTOGRAM_TITLES
            with self.cap_hist:
                for k, values in robust["histograms"].items():
                    title, unit = HISTOGRAM_TITLES.get(k, (k.replace("_", " "), ""))
                    ui.echart(charts.histogram(values, (robust.get("limits") or {}).get(k), title, unit)) \
                        .style("width:48%;height:260px").props(f"data-histogram={k}")
        drivers = views.contributors(robust)
        labels = {c["id"]: c.get("label", c["id"]) for c in robust.get("checks") or []}
        worst = sorted(drivers, key=lambda c: next((x.get("ppk") or 0 for x in robust["checks"] if x["id"] == c), 0))
        self.cap_check.set_options({c: labels.get(c, c) for c in drivers}, value=worst[0] if worst else None)
        if not drivers:
            self.cap_contrib.options.clear()
            self.cap_contrib.options.update({"series": []})
            self.cap_contrib.update()

    def show_contributors(self, e=None) -> None:
        robust = (self.s.result.robust if self.s.result is not None else None) or {}
        cid = self.cap_check.value
        drivers = views.contributors(robust).get(cid)
        if not drivers:
            return
        label = next((c.get("label", cid) for c in robust["checks"] if c["id"] == cid), cid)
        self.cap_contrib.options.clear()
        self.cap_contrib.options.update(charts.bars([q for q, _ in drivers], [round(100 * s, 1) for _, s in drivers],
                                                    f"What drives the scatter of: {label}", "share of variance [%]"))
        self.cap_contrib.update()

    # --- graphs ---------------------------------------------------------------------------------------------------------
    def _graphs_panel(self) -> None:
        self.graphs = ui.column().classes("full-width")

    def result_key(self) -> str:
        """The worker's name for the result in view (its capability study included)."""
        r = self.s.result
        return self.s.key() + (f"-cap{id(r.robust)}" if r is not None and r.robust else "")

    async def draw_graphs(self) -> None:
        r, key = self.s.result, self.result_key()
        if r is None or key == self.graphs_key:
            return
        self.graphs_key = key
        graphs, skipped = await worker.lane("design").call("graphs", r, coalesce=f"graphs-{id(self)}")
        if key != self.result_key():
            return
        self.graphs.clear()
        with self.graphs:
            figs = "".join(f'<figure data-graph="{html.escape(g.id)}" data-verdict="{html.escape(g.verdict or "")}">'
                           f'<img alt="{html.escape(g.title)}" src="{png(g.png)}"><figcaption>'
                           f"{html.escape(g.title)} ({html.escape(g.figure)})</figcaption></figure>" for g in graphs)
            ui.html(figs, sanitize=False).classes("full-width")
            if skipped:
                ui.html("<p class='small'>Not drawn: " + "; ".join(f"{html.escape(k.title)} ({html.escape(k.reason)})"
                                                                 for k in skipped) + "</p>", sanitize=False)

    # --- the 3D model ---------------------------------------------------------------------------------------------------
    def _model_panel(self) -> None:
        with ui.row().classes("items-center"):
            ui.button("Reset view", icon="center_focus_strong", on_click=self.reset_view) \
                .props("dense outline data-testid=reset-view")
            self.model_note = ui.label().classes("text-caption")
        self.scene = ui.scene(width=SCENE_W, height=SCENE_H, grid=False, fps=FPS_HIDDEN).props("data-testid=scene")
        self._awake_until = 0.0
        for event in ("pointerdown", "wheel"):
            self.scene.on(event, self.wake, [])
        self.scene.on("pointermove", self.wake, [], throttle=1.0)
        ui.timer(1.0, self._rest)
        self.model_checks = ui.label().classes("text-caption")
        with ui.row().classes("items-start"):
            self.section = ui.image().style("width:49%").props("alt=section")
            self.exploded = ui.image().style("width:49%").props("alt=exploded")

    def model_key_now(self) -> str:
        """The hash of the design in view (:func:`synth.ui.work.model_key` of its geometry); an
        :class:`~synth.errors.InputError` for a design the CAD model cannot draw."""
        from synth.cad.dimensions import geometry_from
        from synth.ui.work import model_key
        return model_key(geometry_from(self.s.result))

    async def redraw_model(self) -> None:
        """:meth:`draw_model` after an edit, once the edits pause (:data:`REDRAW_PAUSE_S`): the checks of each edit
        go first, and only the design the engineer stopped at is hashed (its geometry, 20 to 40 ms of this process on
        a loaded machine), built and shipped; the view says meanwhile that it shows the design before the edit."""
        try:
            if self.model_key is not None:
                self.model_note.text = "the design changed: the 3D view follows when the edits pause"
            while True:
                wait = self._edited_at + REDRAW_PAUSE_S - time.monotonic()
                if wait <= 0:
                    break
                await asyncio.sleep(wait)
        finally:
            self._redrawing = False
        if self.tab == MODEL:
            await self.draw_model()

    async def draw_model(self) -> None:
        """The 3D view of the design in view: its STL parts (built once per design's hash, by the ``cad`` worker),
        framed to fit; then its geometric checks and pictures."""
        r = self.s.result
        if r is None or not r.parts:
            return
        try:
            key = self.model_key_now()
        except InputError as exc:
            self.model_note.text = f"3D model not drawn: {exc}"
            return
        cad = worker.lane("cad")
        if key != self.model_key:
            self.model_note.text = "building the 3D model..."
            files = await cad.call("model", r, str(self.root), coalesce=f"model-{id(self)}")
            if files is None or self.s.result is None or files["key"] != self._key_or_none():
                return  # a newer design is being drawn
            self.show_model(files)
        else:
            self.model_note.text = self._shown_note
        details_key = (key, r.status, r.verdict, self.s.source)
        if details_key == self.details_key:
            return
        self.details_key = details_key
        det = await cad.call("model_details", r, str(self.root), coalesce=f"details-{id(self)}")
        if det is None or det["key"] != self._key_or_none():
            return
        failed = [c["label"] for c in det["checks"] if c["verdict"] == "fail"]
        self.model_checks.text = ("geometric checks (step 11): " + ("all pass" if not failed
                                                                    else "failing: " + ", ".join(failed)))
        for img, path in ((self.section, det["section"]), (self.exploded, det["exploded"])):
            if Path(path).is_file():
                img.set_source(f"{FILES_URL}/{Path(path).relative_to(self.root).as_posix()}")

    def _key_or_none(self) -> str | None:
        try:
            return self.model_key_now()
        except InputError:
            return None

    def show_model(self, files: dict) -> None:
        self.model_key = files["key"]
        self.view = views.fit_view(files["bbox"])
        self.scene.clear()
        with self.scene:
            with self.scene.group().move(*self.view["offset"]).scale(self.view["scale"]):
                for name, path in files["stl"].items():
                    r, g, b, a = files["colours"][name]
                    colour = "#{:02x}{:02x}{:02x}".format(*(round(255 * x) for x in (r, g, b)))
                    rel = Path(path).relative_to(self.root).as_posix()
                    self.scene.stl(f"{FILES_URL}/{rel}").material(colour, opacity=a)
        self._frame()
        self._shown_note = f"{len(files['stl'])} parts (STL, millimetres); drag to turn, scroll to zoom"
        self.model_note.text = self._shown_note

    def _fps(self, fps: float) -> None:
        if self.scene.props.get("fps") != fps:
            self.scene.props["fps"] = fps
            self.scene.update()

    def wake(self, *_) -> None:
        """The view is turned, zoomed or changed: its full frame rate for :data:`AWAKE_S` seconds."""
        self._awake_until = time.monotonic() + AWAKE_S
        self._fps(FPS_ACTIVE)

    def _rest(self) -> None:
        if self.tab != MODEL:
            self._fps(FPS_HIDDEN)
        elif time.monotonic() > self._awake_until:
            self._fps(FPS_REST)

    def reset_view(self) -> None:
        """The camera back to the view that frames the whole model (the button: drawn at the full frame rate)."""
        if self.view is not None:
            self.wake()
            self._frame()

    def _frame(self) -> None:
        """The camera on the view that frames the model; a new model is drawn at the rate in force (at rest: the
        next frame, without the 3 s of full rate that would take the CPU the next edit's checks need)."""
        if self.view is not None:
            x, y, z = self.view["camera"]
            self.scene.move_camera(x=x, y=y, z=z, look_at_x=0, look_at_y=0, look_at_z=0, up_x=0, up_y=0, up_z=1,
                                   duration=0)

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


def _messages(el, msgs: list[str]) -> None:
    """Show a field's problems under it (Quasar's error line, NiceGUI's ``error``), or its hint again."""
    text = "; ".join(msgs) or None
    if el.error != text:
        el.error = text
        el.update()


def _select_value(el, options: dict, text: str):
    """Set a drop-down to ``text``; a value outside its options (a bad file) is shown as it is, with the error."""
    value = text or None
    if value is not None and value not in options:
        el.set_options({**options, value: value})
    el.value = value
