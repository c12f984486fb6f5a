"""The design page's input form (the left column of :class:`synth.ui.design_page.DesignPage`): a box per field of
:mod:`synth.schema` (:mod:`synth.ui.form`), each edit validated and the current design re-verified at once
(:class:`synth.ui.session.DesignSession`), its problems shown under the field; an input file opened, the input saved
as YAML or as the Excel template.
"""

from __future__ import annotations

from pathlib import Path

from nicegui import ui

from synth import schema
from synth.errors import InputError
from synth.io.limits import LIMITS
from synth.ui import form, jobs
from synth.ui.trace import mark
from synth.ui.widgets import in_page, refused, stem, upload_box

__all__ = ["InputForm", "DESIGN_UPLOAD_LIMIT", "FIRST_FIELDS", "drawn"]

#: the largest design input a page opens: the Excel template's limit (a YAML, TOML or JSON one is at most 8 MB)
DESIGN_UPLOAD_LIMIT = max(LIMITS.workbook_bytes, LIMITS.text_input_bytes)

#: the boxes of the page's first render: the form's sections in order until this many fields (about what a window
#: 900 px high shows: the first four sections), the others built once the browser has drawn the page
#: (:meth:`InputForm.build_rest`). The browser's first render is the cold start's last step, and its time goes with
#: the number of Quasar fields: all 54 of them made it 0.35-0.4 s longer (``benchmarks/bench_ui.py``, docs/sections/ui.md)
FIRST_FIELDS = 15


async def drawn(timeout_s: float = 10.0) -> None:
    """Return once the page has drawn what was sent before (its next frame, asked of the page), or after
    ``timeout_s`` without an answer (a page that is slow, or a client that runs no script)."""
    try:
        await ui.run_javascript("new Promise(r => requestAnimationFrame(() => setTimeout(r)))", timeout=timeout_s)
    except Exception:  # noqa: BLE001 - no answer in time: go on all the same
        pass


class InputForm:
    """The form's part of the design page (a mixin of :class:`synth.ui.design_page.DesignPage`, whose session ``s``,
    ``status`` line and ``show_result`` it uses)."""

    _loading = False  # the boxes are being filled from the session: their change events are not edits

    def build_form(self) -> None:
        with ui.row().classes("items-center"):
            upload_box("Open an input (YAML, TOML, JSON, Excel)", ".yaml,.yml,.toml,.json,.xlsx,.ods",
                       DESIGN_UPLOAD_LIMIT, self.s.workdir, "input file", self.on_file).classes("full-width")
            ui.button("Save YAML", icon="download", on_click=self.save_yaml).props("outline dense")
            ui.button("Excel template", icon="grid_on", on_click=self.save_template).props("outline dense")
        self.source_label = ui.label().classes("text-caption")
        self.rules_label = ui.label().classes("text-caption").props("data-testid=rules")
        self.other_box = ui.label().classes("text-negative text-caption")
        self._later: list = []  # (section's element, its fields) built after the first render
        n = 0
        for section, fields in form.sections():
            with ui.expansion(section, value=True).classes("full-width") \
                    .props("dense header-class=text-weight-bold") as box:
                if n < FIRST_FIELDS:
                    self._fields(fields)
                else:
                    self._later.append((box, fields))
            n += len(fields)
        if self._later:
            in_page(self.source_label, self.build_rest)

    def _fields(self, fields) -> None:
        for f in fields:
            with ui.element("div").classes("full-width").props(f"data-field={f.name}"):
                self.widgets[f.name] = self._widget(f)

    async def build_rest(self) -> None:
        """The sections after the first :data:`FIRST_FIELDS` fields, once the browser has drawn the page (their boxes
        show the session's values as they are then, and their problems)."""
        await drawn()
        rest, self._later = self._later, []
        for box, fields in rest:
            if box.is_deleted:
                return  # a page built ahead and not shown (synth.ui.app)
            with box:
                self._fields(fields)
        self.show_problems()

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
                el, text = self.widgets.get(f.name), self.s.texts[f.name]
                if el is None:
                    continue  # built after the first render (build_rest), from the session as it is then
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
            await self.call_api(self.s.synthesise)
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
