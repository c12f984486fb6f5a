"""The design page's result tabs that study the design beyond its checks: the ranked alternatives (one can be
applied), the what-if sweep of one input, the production capability and the thesis's graphs, each panel built when
its tab is first opened (the tab names: :data:`TABS`).
"""

from __future__ import annotations

import html

from nicegui import ui

from synth import schema
from synth.errors import InputError, Problem
from synth.ui import charts, form, jobs, views, worker
from synth.ui.widgets import count, number, png

__all__ = ["ResultTabs", "TABS", "CHECKS", "DESIGN", "ALTERNATIVES", "WHATIF", "CAPABILITY", "GRAPHS", "MODEL"]

CHECKS, DESIGN, ALTERNATIVES, WHATIF, CAPABILITY, GRAPHS, MODEL = (
    "Checks", "Design", "Alternatives", "What if", "Capability", "Graphs", "3D model")
#: the tabs of the results, in order
TABS = (CHECKS, DESIGN, ALTERNATIVES, WHATIF, CAPABILITY, GRAPHS, MODEL)


class ResultTabs:
    """The alternatives, what-if, capability and graphs tabs of the design page (a mixin of
    :class:`synth.ui.design_page.DesignPage`, whose session ``s``, ``call_api`` and ``show_result`` they use)."""

    # --- alternatives ---------------------------------------------------------------------------------------------
    def build_alternatives_panel(self) -> None:
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
        await self.call_api(self.s.apply, rank)
        self.show_result()

    # --- what if ----------------------------------------------------------------------------------------------------
    def build_whatif_panel(self) -> None:
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
    def build_capability_panel(self) -> None:
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
    def build_graphs_panel(self) -> None:
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
