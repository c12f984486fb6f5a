"""The pages of ``synth ui`` (NiceGUI): the design page ``/`` and the portfolio page ``/portfolio``.

The design page: the input form (:mod:`synth.ui.form`), the verdict digest and every check coloured by
its verdict, the design (parts, what binds, diagnosis, alternatives), the thesis's graphs
(:func:`synth.report.plots.build_graphs`), the 3D model (the STL parts in NiceGUI's three.js scene,
served by this server) and the section picture, and the downloads. Editing a field re-validates the
input and re-verifies the current design at once (:class:`synth.ui.session.DesignSession`).

The portfolio page: a portfolio file (or a synthetic sample), the screening with a progress bar, the
feasible share and what binds as plots, the filterable table (a row opens that application on the design
page), and the platform rationalisation.

Everything the page loads comes from this server: NiceGUI ships Vue, Quasar, three.js and its fonts;
the graphs are PNG data, the 3D parts and downloads are files under the server's own folder.

The server trusts nothing it did not serve (:mod:`synth.ui.guard`: Host, Origin, token, body size); files
are received as they stream (:mod:`synth.ui.uploads`); the long work runs in threads that end with the server
(:mod:`synth.ui.jobs`); every error, and every event the page sends that is not one it could send, becomes a
message in the page (:mod:`synth.ui.messages`), never a traceback.
"""

from __future__ import annotations

import base64
import html
import inspect
import logging
import math
import secrets
import shutil
import tempfile
import threading
from pathlib import Path

from nicegui import app, background_tasks, ui

from synth import schema
from synth.errors import InputError, Problem
from synth.io.limits import LIMITS, short
from synth.ui import form, jobs, uploads, views
from synth.ui.guard import BODY_LIMIT, Guard, Policy, is_loopback
from synth.ui.messages import message_of, quiet_tracebacks
from synth.ui.portfolio import PortfolioSession
from synth.ui.session import FIDELITIES, OBJECTIVES, DesignSession
from synth.report.html import digest_html
from synth.report.plots import build_graphs

__all__ = ["setup", "FILES_URL"]

#: the URL under which the server serves its own folder (3D parts, pictures)
FILES_URL = "/synth-files"

_CSS = """
.synth-ui table{border-collapse:collapse;font-size:.85em;width:100%}
.synth-ui th,.synth-ui td{border:1px solid #c8c8c8;padding:2px 6px;text-align:left;vertical-align:top}
.synth-ui thead th{background:#d9e2ec}
.synth-ui td.num{text-align:right;font-variant-numeric:tabular-nums;white-space:nowrap}
.synth-ui tr.group td{background:#bdd7ee;font-weight:bold}
.synth-ui table.kv th{background:#eef2f6;width:45%}
.synth-ui figure{display:inline-block;margin:.4em;border:3px solid #bbb;padding:4px;vertical-align:top;width:47%}
.synth-ui figure[data-verdict=pass]{border-color:#2e7d32} .synth-ui figure[data-verdict=fail]{border-color:#c62828}
.synth-ui figure[data-verdict=warning]{border-color:#ef6c00}
.synth-ui figure img{width:100%} .synth-ui figcaption{font-size:.85em}
.synth-ui .small{font-size:.85em;color:#555}
.synth-ui h2{font-size:1.4em;line-height:1.6;margin:.6em 0 .2em;font-weight:500}
.synth-ui h3{font-size:1.15em;line-height:1.5;margin:.5em 0 .2em;font-weight:500}
"""

GRAPHS, MODEL = "Graphs", "3D model"  # the tabs drawn when they come into view

#: token -> (input mapping, source): an application of the portfolio page opened on the design page
_HANDOFF: dict[str, tuple[dict, str]] = {}


_DRAW = threading.Lock()  # matplotlib's pyplot is not thread-safe: one drawing job at a time, whatever the tab

#: the largest design input a page opens: the Excel template's limit (a YAML, TOML or JSON one is at most 8 MB)
DESIGN_UPLOAD_LIMIT = max(LIMITS.workbook_bytes, LIMITS.text_input_bytes)
#: the largest portfolio a page opens (a CSV; an .xlsx or .ods one is bounded by its unpacked size)
PORTFOLIO_UPLOAD_LIMIT = LIMITS.portfolio_bytes

_log = logging.getLogger("synth.ui")


def _drawing(fn, *args, **kw):
    """``fn(*args, **kw)`` holding the drawing lock (run in a job's thread, :func:`synth.ui.jobs.run`)."""
    with _DRAW:
        return fn(*args, **kw)


def _refused(exc: BaseException, what: str = "synth: invalid input") -> None:
    """``exc`` worded as the command line words it (:func:`synth.ui.messages.message_of`), in a notification that
    stays until closed."""
    if not isinstance(exc, InputError):
        what = "synth ui"
        _log.warning("%s", message_of(exc), exc_info=exc)
    ui.notify(what + ": " + message_of(exc), type="negative", multi_line=True, timeout=0, close_button=True)


def _in_page(element, work, *args) -> None:
    """Schedule ``await work(*args)`` in ``element``'s page (a route's work shown there); an error is a message."""
    async def task():
        with element:
            try:
                await work(*args)
            except Exception as exc:  # noqa: BLE001 - every error a message in the page
                _refused(exc)
    background_tasks.create(task(), name=f"synth ui: {getattr(work, '__name__', 'work')}")


def _upload_box(label: str, accept: str, limit: int, folder: Path, what: str, done) -> "ui.upload":
    """An upload box posting to its own streaming URL (:mod:`synth.ui.uploads`), never NiceGUI's route (which reads
    the whole request before a handler sees it). ``done(path, name)``: a coroutine function run in the page."""
    box = ui.upload(label=label, auto_upload=True, max_file_size=limit,
                    on_rejected=lambda: ui.notify(f"synth: {what}: a file of at most {limit / 2**20:g} MB",
                                                  type="negative", multi_line=True, timeout=0, close_button=True))
    box.props(f"accept={accept} flat bordered")
    target = uploads.Target(folder, limit, what, done=lambda path, name: _in_page(box, done, path, name),
                            refused=lambda exc: _in_page(box, _refuse_async, exc, "synth: " + what + " refused"))
    app.remove_route(box.props["url"])  # NiceGUI's own route for this box: nothing posts there
    box.props["url"] = uploads.register(target)
    box._synth_target = target  # the page holds its upload target (the registry holds it weakly)
    return box


async def _refuse_async(exc: InputError, what: str) -> None:
    _refused(exc, what)


def _count(value, field: str, hi: int) -> int:
    """A count from a number box (NaN, 2.5, 1e300, text refused with what is accepted)."""
    ok = (isinstance(value, (int, float)) and not isinstance(value, bool) and math.isfinite(value)
          and float(value).is_integer() and 1 <= value <= hi)
    if not ok:
        raise InputError(Problem(field, short(value), f"an integer in [1, {hi}]"))
    return int(value)


def _page_errors() -> None:
    """Every error of this page's handlers a message in the page (NiceGUI's per-page exception handler)."""
    ui.on_exception(lambda exc: _refused(exc))


def _png(path_or_bytes) -> str:
    data = path_or_bytes if isinstance(path_or_bytes, bytes) else Path(path_or_bytes).read_bytes()
    return "data:image/png;base64," + base64.b64encode(data).decode("ascii")


def _header(host: str, port: int) -> None:
    with ui.header().classes("items-center bg-blue-10 q-py-xs"):
        ui.label("synth").classes("text-h6 text-weight-bold")
        ui.link("Design", "/").classes("text-white")
        ui.link("Portfolio", "/portfolio").classes("text-white")
        ui.space()
        where = "local only" if is_loopback(host) else "REACHABLE FROM THE NETWORK, with its token"
        shown = f"[{host}]" if ":" in host else host
        ui.label(f"serving http://{shown}:{port}/ ({where}: bound to {host})").classes("text-caption")


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


class DesignPage:
    """One browser tab's design page (its :class:`DesignSession` and the elements showing it)."""

    def __init__(self, values: dict, source: str, root: Path, host: str, port: int, rules=None):
        workdir = Path(tempfile.mkdtemp(prefix="design-", dir=root))
        ui.context.client.on_delete(lambda: shutil.rmtree(workdir, ignore_errors=True))  # the tab's files
        self.root, self.s = root, DesignSession(values, source=source, workdir=workdir, rules=rules)
        self.widgets: dict = {}
        self.graphs_seq = self.model_seq = -1
        self._loading = False
        self.tab = "Checks"
        _header(host, port)
        pane = "height:calc(100vh - 64px);overflow-y:auto;flex-wrap:nowrap"  # form and results scroll apart
        with ui.row().classes("full-width no-wrap items-start synth-ui"):
            with ui.column().classes("q-pa-sm").style(f"width:34%;min-width:330px;{pane}"):
                self._form()
            with ui.column().classes("q-pa-sm").style(f"width:66%;{pane}"):
                self._results()
        if self.s.input is not None:
            try:
                self.s.synthesise()
            except InputError as exc:
                _refused(exc)
        self.show_problems()
        self.show_result()

    # --- the form -------------------------------------------------------------------------------------------
    def _form(self) -> None:
        with ui.row().classes("items-center"):
            _upload_box("Open an input (YAML, TOML, JSON, Excel)", ".yaml,.yml,.toml,.json,.xlsx,.ods",
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
            el = ui.input(form.label(f), value=text).classes("full-width").props("dense")
        el.props["hint"] = form.hint(f)
        el.props["bottom-slots"] = True
        el.props["hide-bottom-space"] = True  # a long hint or message grows the field, never overlaps the next
        el.without_auto_validation()  # synth.schema validates, not NiceGUI
        el.on_value_change(lambda e, name=f.name: self.on_edit(name, e.value))
        return el

    def fill_form(self) -> None:
        """The boxes from the session (after a file is opened)."""
        self._loading = True
        try:
            for f in schema.FIELDS:
                el, text = self.widgets[f.name], self.s.texts[f.name]
                if form.widget(f) == "select":
                    _select_value(el, form.options(f), text)
                else:
                    el.value = text
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
        valid = self.s.edit(name, "" if value is None else str(value))
        self.show_problems()
        if valid:
            self.show_result()
        else:
            self.status.text = ("input not valid (see the marked fields): the checks shown are those of the last "
                                "valid input")
            self.status.classes(replace="text-negative")

    async def on_file(self, path: Path, name: str) -> None:
        """An input file received (:mod:`synth.ui.uploads`): read it (values and design rules), then synthesise."""
        try:
            values, rules = await jobs.run(self.s.read, path)
        except InputError as exc:
            _refused(exc)
            return
        finally:
            shutil.rmtree(path.parent, ignore_errors=True)  # read: the copy is not kept
        if self.s.open(values, rules, name):
            self.status.text = "synthesising..."
            try:
                await jobs.run(self.s.synthesise)
            except InputError as exc:
                _refused(exc)
        self.fill_form()
        self.show_problems()
        self.show_result()

    def save_yaml(self) -> None:
        ui.download.content(self.s.yaml_text(), _stem(self.s.source) + ".yaml", "application/x-yaml")

    def save_template(self) -> None:
        try:
            path = self.s.write_template(self.s.workdir / (_stem(self.s.source) + ".xlsx"))
        except InputError as exc:
            _refused(exc, "the template needs a valid input")
            return
        if not self.s.rules.empty():
            ui.notify("the Excel template holds no design rules: " + (self.s.rules.name or "the input's rules")
                      + " are not in it (Save YAML keeps them)", type="warning", multi_line=True)
        ui.download.file(path)

    # --- the result ------------------------------------------------------------------------------------------
    def _results(self) -> None:
        with ui.row().classes("items-center"):
            ui.select(list(OBJECTIVES), value=self.s.objective, label="objective",
                      on_change=self.on_objective).props("dense").style("width:9em")
            ui.select(list(FIDELITIES), value=self.s.fidelity, label="fidelity",
                      on_change=self.on_fidelity).props("dense").style("width:9em")
            ui.button("Synthesise", icon="auto_fix_high", on_click=self.on_synthesise).props("data-testid=synthesise")
            ui.separator().props("vertical")
            for label, kind in (("STEP", "step"), ("Report HTML", "html"), ("Report PDF", "pdf"),
                                ("Workbook", "xlsx"), ("Input YAML", "yaml")):
                ui.button(label, icon="download", on_click=lambda _, k=kind: self.download(k)) \
                    .props(f"outline dense data-testid=download-{kind}")
        self.status = ui.label().classes("text-caption")
        self.seq = ui.label().props("data-testid=seq").classes("text-caption text-grey")
        self.digest = ui.html("", sanitize=False).classes("full-width")
        with ui.tabs().classes("full-width") as tabs:
            t_checks = ui.tab("Checks")
            t_design = ui.tab("Design")
            ui.tab(GRAPHS)
            ui.tab(MODEL)
        with ui.tab_panels(tabs, value=t_checks, on_change=self.on_tab).classes("full-width").props("keep-alive"):
            with ui.tab_panel(t_checks):
                self.checks = ui.html("", sanitize=False).classes("full-width")
            with ui.tab_panel(t_design):
                ui.label("Parts").classes("text-subtitle1")
                self.parts = ui.html("", sanitize=False)
                ui.label("What binds (smallest margins)").classes("text-subtitle1")
                self.binding = ui.html("", sanitize=False)
                ui.label("Diagnosis and relaxations").classes("text-subtitle1")
                self.diagnosis = ui.html("", sanitize=False)
                ui.label("Alternatives").classes("text-subtitle1")
                self.alternatives = ui.html("", sanitize=False)
                ui.label("Notes").classes("text-subtitle1")
                self.notes = ui.html("", sanitize=False)
            with ui.tab_panel(GRAPHS):
                self.graphs = ui.column().classes("full-width")
            with ui.tab_panel(MODEL):
                with ui.row().classes("items-start"):
                    self.scene = ui.scene(width=640, height=480, grid=False).props("data-testid=scene")
                    self.section = ui.image().style("width:520px")
                self.model_note = ui.label().classes("text-caption")

    def show_result(self) -> None:
        r = self.s.result
        if r is None:
            self.status.text = "no design yet: complete the input"
            return
        how = f" ({r.solver}, objective {r.objective})" if r.solver else " (the current design, for the input as edited)"
        self.status.text = (f"{r.status} design{how}, fidelity {r.settings.get('fidelity', self.s.fidelity)}: "
                            f"verdict {r.verdict}")
        self.status.classes(replace="text-positive" if r.verdict == "pass" else "text-negative")
        self.digest.content = digest_html(r)
        self.checks.content = views.checks_table(r)
        self.parts.content = views.parts_table(r)
        self.binding.content = views.binding_table(r)
        self.diagnosis.content = views.diagnosis_html(r)
        self.alternatives.content = views.alternatives_html(r)
        self.notes.content = "<ul>" + "".join(f"<li>{html.escape(str(n))}</li>" for n in r.notes) + "</ul>"
        self.seq.text = f"evaluation {self.s.seq}"
        self.seq.props["data-seq"] = str(self.s.seq)
        self.seq.update()
        if self.tab == GRAPHS:  # drawn for the tab in view only: an edit stays a 5 ms round trip
            _in_page(self.graphs, self.draw_graphs)
        elif self.tab == MODEL:
            _in_page(self.model_note, self.draw_model)

    async def on_tab(self, e) -> None:
        self.tab = e.value
        if self.tab == GRAPHS:
            await self.draw_graphs()
        elif self.tab == MODEL:
            await self.draw_model()

    def on_objective(self, e) -> None:
        if e.value not in OBJECTIVES:  # a value no option of the drop-down sends
            e.sender.value = self.s.objective
            raise InputError(Problem("objective", short(e.value), "one of " + ", ".join(OBJECTIVES)))
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
            _refused(exc)
            return False

    async def on_synthesise(self) -> None:
        if self.s.input is None:
            ui.notify("complete the input first: the marked fields", type="warning")
            return
        self.status.text = "synthesising..."
        await self._api(self.s.synthesise)
        self.show_result()

    async def draw_graphs(self) -> None:
        seq, r = self.s.seq, self.s.result
        if r is None or seq == self.graphs_seq:
            return
        self.graphs_seq = seq
        graphs, skipped = await jobs.run(_drawing, build_graphs, r, show_progress=False)
        if seq != self.s.seq:
            return
        self.graphs.clear()
        with self.graphs:
            figs = "".join(f'<figure data-graph="{html.escape(g.id)}" data-verdict="{html.escape(g.verdict or "")}">'
                           f'<img alt="{html.escape(g.title)}" src="{_png(g.png)}"><figcaption>'
                           f"{html.escape(g.title)} ({html.escape(g.figure)})</figcaption></figure>" for g in graphs)
            ui.html(figs, sanitize=False).classes("full-width")
            if skipped:
                ui.html("<p class='small'>Not drawn: " + "; ".join(f"{html.escape(k.title)} ({html.escape(k.reason)})"
                                                                 for k in skipped) + "</p>", sanitize=False)

    async def draw_model(self) -> None:
        from synth.cad.assembly import colour_of
        seq = self.s.seq
        if self.s.result is None or seq == self.model_seq:
            return
        self.model_seq = seq
        self.model_note.text = "building the 3D model..."
        files = await jobs.run(_drawing, self.s.cad)
        if seq != self.s.seq:
            return
        rel = files["folder"].relative_to(self.root).as_posix()
        self.scene.clear()
        with self.scene:
            with self.scene.group().scale(0.04):  # millimetres to scene units: the tensioner about 4 units wide
                for name, path in files["stl"].items():
                    r, g, b, a = colour_of(name)
                    colour = "#{:02x}{:02x}{:02x}".format(*(round(255 * x) for x in (r, g, b)))
                    self.scene.stl(f"{FILES_URL}/{rel}/stl/{path.name}").material(colour, opacity=a)
        self.scene.move_camera(x=3.5, y=-4.5, z=4.0, look_at_x=0, look_at_y=0, look_at_z=1.0, duration=0)
        if files["section"].is_file():
            self.section.set_source(f"{FILES_URL}/{rel}/section.png")
        failed = [c.label for c in files["checks"] if c.verdict == "fail"]
        self.model_note.text = (f"{len(files['stl'])} parts (STL, millimetres); geometric checks (step 11): "
                                + ("all pass" if not failed else "failing: " + ", ".join(failed)))

    async def download(self, kind: str) -> None:
        if kind == "yaml":
            return self.save_yaml()
        if self.s.result is None:
            ui.notify("no design to export yet", type="warning")
            return
        note = ui.notification("writing the " + ("3D model" if kind == "step" else "report") + "...",
                               spinner=True, timeout=None)
        try:
            if kind == "step":
                path = (await jobs.run(_drawing, self.s.cad))["step"]
            else:
                files = await jobs.run(_drawing, self.s.report, kind == "pdf")
                path = files.get(kind)
                if not path or not Path(path).is_file():
                    ui.notify(files.get("pdf_note") or f"no {kind} written", type="warning")
                    return
        finally:
            note.dismiss()
        ui.download.file(path, _stem(self.s.source) + "_" + Path(path).name)


def _stem(source: str) -> str:
    stem = Path(source or "design").stem or "design"
    return "".join(c if c.isalnum() or c in "-_." else "_" for c in stem)[:60]


class PortfolioPage:
    """One browser tab's portfolio page."""

    #: the most applications the sample box makes
    SAMPLE_MAX = 100_000

    def __init__(self, root: Path, host: str, port: int):
        workdir = Path(tempfile.mkdtemp(prefix="portfolio-", dir=root))
        ui.context.client.on_delete(lambda: shutil.rmtree(workdir, ignore_errors=True))  # the tab's files
        self.p = PortfolioSession(workdir)
        self.done = (0, 0)
        self._rows: list[dict] = []
        _header(host, port)
        with ui.column().classes("full-width q-pa-md synth-ui"):
            with ui.row().classes("items-center full-width"):
                _upload_box("Open a portfolio (CSV, Excel, .ods, Parquet)", ".csv,.xlsx,.xlsm,.ods,.parquet",
                            PORTFOLIO_UPLOAD_LIMIT, workdir, "portfolio", self.on_file)
                ui.label("or")
                self.n = ui.number("applications", value=200, min=1, max=self.SAMPLE_MAX, precision=0) \
                    .style("width:9em")
                ui.button("Synthetic sample", on_click=self.on_sample).props("outline")
            self.loaded = ui.label().props("data-testid=loaded")
            with ui.row().classes("items-center"):
                self.fidelity = ui.select(list(FIDELITIES), value="screening", label="fidelity").style("width:9em")
                self.run_button = ui.button("Screen the portfolio", icon="play_arrow", on_click=self.on_run) \
                    .props("data-testid=run")
                self.rat_button = ui.button("Rationalise (platform)", icon="category", on_click=self.on_rationalise) \
                    .props("outline")
            self.bar = ui.linear_progress(value=0, show_value=False).classes("full-width")
            self.progress = ui.label().classes("text-caption")
            self.share = ui.label().classes("text-h6").props("data-testid=feasible-share")
            self.plots = ui.row().classes("full-width")
            self.filter = ui.input("filter the table").props("clearable dense").style("width:24em")
            self.table = ui.table(rows=[], columns=[], row_key="#", pagination=15).classes("full-width")
            self.table.bind_filter_from(self.filter, "value")
            self.table.on("rowClick", self.on_row)
            ui.label("A row opens that application on the design page.").classes("text-caption")
            self.platform = ui.html("", sanitize=False).classes("full-width")
        ui.timer(0.2, self._tick)

    def _tick(self) -> None:
        done, total = self.done
        if total:
            self.bar.value = done / total
            self.progress.text = f"{done} of {total} applications"

    def _loaded(self, n: int) -> None:
        self.loaded.text = f"{n} applications from {self.p.source}"
        self.share.text = ""
        self.table.rows = self._rows = []
        self.plots.clear()
        self.platform.content = ""

    async def on_file(self, path: Path, name: str) -> None:
        """A portfolio received (:mod:`synth.ui.uploads`); the previous one's file is removed (the platform reads
        the file of the portfolio in view)."""
        old = self.p.path
        try:
            self._loaded(await jobs.run(self.p.load, path, name))
        except InputError as exc:
            shutil.rmtree(path.parent, ignore_errors=True)
            _refused(exc, "synth: invalid portfolio")
            return
        if old is not None and old.parent.name.startswith("upload-") and old.parent != path.parent:
            shutil.rmtree(old.parent, ignore_errors=True)

    async def on_sample(self) -> None:
        try:
            n = _count(self.n.value, "applications", self.SAMPLE_MAX)
            self._loaded(await jobs.run(self.p.sample, n))
        except InputError as exc:
            _refused(exc)

    def _progress(self, done: int, total: int) -> None:
        self.done = (done, total)

    async def on_run(self) -> None:
        if self.p.table is None:
            ui.notify("open a portfolio or make a sample first", type="warning")
            return
        fidelity = self.fidelity.value
        if fidelity not in FIDELITIES:
            raise InputError(Problem("fidelity", short(fidelity), "one of " + ", ".join(FIDELITIES)))
        self.run_button.disable()
        self.done = (0, len(self.p.table))
        try:
            await jobs.run(self.p.run, self._progress, fidelity=fidelity, check=jobs.check)
            pngs = await jobs.run(_drawing, self.p.plots)
        except Exception as exc:  # noqa: BLE001 - every error a message in the page
            _refused(exc)
            return
        finally:
            self.run_button.enable()
        self._tick()
        o = self.p.summary.overall
        self.share.text = (f"feasible share: {100 * o['feasible_share']:.1f} % ({o['feasible']} of {o['evaluated']} "
                           f"evaluated; {o['input_errors']} input errors)")
        self.plots.clear()
        with self.plots:
            for p in pngs:
                ui.image(_png(p)).style("width:48%").props(f"alt={p.stem}")
        rows, cols = self.p.rows()
        self.table.columns = [{"name": c, "label": c, "field": c, "sortable": True, "align": "left"} for c in cols]
        self.table.rows = self._rows = rows

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
        _HANDOFF[token] = (self.p.application(i), f"{self.p.source}: {label or f'row {i + 1}'}")
        ui.navigate.to(f"/?open={token}")

    async def on_rationalise(self) -> None:
        if self.p.path is None:
            ui.notify("open a portfolio or make a sample first", type="warning")
            return
        self.rat_button.disable()
        self.done = (0, 1)
        try:
            section = await jobs.run(_drawing, self.p.rationalise, self._progress)
        except Exception as exc:  # noqa: BLE001 - every error a message in the page
            _refused(exc, "synth rationalise")
            return
        finally:
            self.rat_button.enable()
        self.platform.content = section


def _page(build) -> None:
    """Build a page; an error is a message in it, not NiceGUI's error page with a traceback in the log."""
    _page_errors()
    try:
        build()
    except Exception as exc:  # noqa: BLE001 - every error a message in the page
        ui.label("synth ui could not build this page: " + message_of(exc)).classes("text-negative q-pa-md")
        _log.warning("page: %s", message_of(exc), exc_info=exc)


def setup(values: dict, source: str, *, policy: Policy, root: Path, rules=None) -> None:
    """Register the pages, the upload route and the server's guard; ``values``/``source``/``rules``: the input the
    design page opens with."""
    app.add_static_files(FILES_URL, root)
    ui.add_css(_CSS, shared=True)
    app.add_route(uploads.UPLOAD_URL + "/{key}", _upload_route, methods=["POST"])
    app.add_middleware(Guard, policy=policy, body_limit=lambda path: uploads.body_limit(path) or BODY_LIMIT)
    from nicegui import core
    core.sio.eio.cors_allowed_origins = policy.origins()  # NiceGUI's is "*": any site's page
    _check_socket_messages(core.sio)
    quiet_tracebacks()
    app.on_shutdown(jobs.STOP.set)
    host, port = policy.host, policy.port

    @ui.page("/", title="synth: design")
    def design_page(open: str | None = None) -> None:  # noqa: A002 - the query parameter's name
        handed = _HANDOFF.get(open or "")  # a portfolio's application: its own input, no rules
        v, src, r = (*handed, None) if handed else (values, source, rules)
        _page(lambda: DesignPage(v, src, root, host, port, rules=r))

    @ui.page("/portfolio", title="synth: portfolio")
    def portfolio_page() -> None:
        _page(lambda: PortfolioPage(root, host, port))


async def _upload_route(request):
    from starlette.responses import PlainTextResponse
    status, text = await uploads.receive(request)
    return PlainTextResponse(text, status_code=status, headers={} if status == 200 else {"connection": "close"})


# --- the socket: every message the page sends is one it could send ---------------------------------------------------
_SOCKET_EVENTS = ("connect", "handshake", "event", "javascript_response", "ack", "log")


def _check_socket_messages(sio) -> None:
    """Wrap NiceGUI's socket.io handlers: a message that is not one its page could send (a wrong shape, an unknown
    element or listener, an argument no widget of that kind sends) is refused with a message in the page it names,
    and one line in the server's output, never a traceback."""
    handlers = sio.handlers.setdefault("/", {})
    for name in _SOCKET_EVENTS:
        h = handlers.get(name)
        if h is not None and not getattr(h, "_synth_checked", False):
            handlers[name] = _checked(name, h)


def _checked(name: str, handler):
    import socketio

    async def checked(sid, *args):
        msg = args[0] if args else None
        try:
            if name == "event":
                _check_event(msg)
            out = handler(sid, *args)
            return (await out) if inspect.isawaitable(out) else out
        except socketio.exceptions.ConnectionRefusedError:
            raise
        except Exception as exc:  # noqa: BLE001 - a crafted message: refused, said in the page
            text = message_of(exc) if isinstance(exc, InputError) else f"{type(exc).__name__}: {short(str(exc), 200)}"
            _log.warning("refused a %r message from a page: %s", name, text)
            _tell(msg, f"synth ui refused a message from this page ({name}): {text}")
            if name == "connect":
                raise socketio.exceptions.ConnectionRefusedError("refused") from None
            return False if name == "handshake" else None
    checked._synth_checked = True
    return checked


def _tell(msg, text: str) -> None:
    from nicegui import Client
    cid = msg.get("client_id") if isinstance(msg, dict) else None
    client = Client.instances.get(cid) if isinstance(cid, str) else None
    if client is not None and not client.is_deleted:
        with client:
            ui.notify(text, type="negative", multi_line=True, timeout=0, close_button=True)


def _check_event(msg) -> None:
    """An element event as NiceGUI's page sends it: ``{"id", "client_id", "listener_id", "args": [JSON text]}`` for a
    listener the element has, with arguments its kind of widget sends."""
    import json

    from nicegui import Client
    if not isinstance(msg, dict) or not isinstance(msg.get("client_id"), str):
        raise InputError(Problem("event", short(msg), "a mapping with the page's client_id"))
    client = Client.instances.get(msg["client_id"])
    if client is None:
        return  # NiceGUI ignores it
    if isinstance(msg.get("id"), bool) or not isinstance(msg.get("id"), int):
        raise InputError(Problem("event id", short(msg.get("id")), "the id of an element of the page"))
    el = client.elements.get(msg["id"])
    if el is None:
        return  # an element just removed (a notification dismissed, a plot replaced): NiceGUI ignores its events
    listener = getattr(el, "_event_listeners", {}).get(msg.get("listener_id"))
    if listener is None:
        raise InputError(Problem("event listener_id", short(msg.get("listener_id")), "a listener of that element"))
    raw = msg.get("args", [])
    if not isinstance(raw, list) or not all(a is None or isinstance(a, str) for a in raw):
        raise InputError(Problem("event args", short(raw), "a list of JSON texts"))
    try:
        args = [None if a is None else json.loads(a) for a in raw]
    except ValueError:
        raise InputError(Problem("event args", short(raw), "a list of JSON texts")) from None
    value = args[0] if len(args) == 1 else args
    if listener.type.startswith("update:") and isinstance(el, ui.select):
        ok = value is None or isinstance(value, str) or (
            isinstance(value, dict) and isinstance(value.get("value"), int) and not isinstance(value["value"], bool)
            and 0 <= value["value"] < len(el.options))
        if not ok:
            raise InputError(Problem(f"{el.props.get('label') or 'drop-down'}", short(value),
                                     f"an option of the drop-down (index 0 to {len(el.options) - 1})"))
    elif listener.type.startswith("update:") and isinstance(el, ui.number):
        try:
            ok = value is None or value == "" or math.isfinite(float(value))
        except (TypeError, ValueError):
            ok = False
        if not ok:
            raise InputError(Problem(f"{el.props.get('label') or 'number'}", short(value), "a finite number"))
