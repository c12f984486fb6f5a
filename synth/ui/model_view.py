"""The design page's 3D model tab: the design's STL parts in a NiceGUI scene (built by the ``cad`` worker once per
design's hash and framed to fit), its geometric checks and pictures, redrawn when the edits pause, and the view's frame
rate kept low unless it is turned or zoomed.
"""

from __future__ import annotations

import asyncio
import time
from pathlib import Path

from nicegui import ui

from synth.errors import InputError
from synth.ui import views, worker
from synth.ui.design_tabs import MODEL
from synth.ui.widgets import FILES_URL, in_page

__all__ = ["ModelView", "SCENE_W", "SCENE_H", "FPS_ACTIVE", "FPS_REST", "FPS_HIDDEN", "AWAKE_S", "REDRAW_PAUSE_S"]

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


class ModelView:
    """The 3D model tab of the design page (a mixin of :class:`synth.ui.design_page.DesignPage`, whose session ``s``,
    ``root`` and ``tab`` it reads)."""

    _edited_at = 0.0     # the last edit's time (time.monotonic) while the 3D view is open
    _redrawing = False   # a redraw of the 3D view waits for the edits to pause

    def build_model_panel(self) -> None:
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

    def follow_edit(self) -> None:
        """An edit while the 3D view is open: one waiting redraw (:meth:`redraw_model`) follows every edit."""
        self._edited_at = time.monotonic()
        if not self._redrawing:
            self._redrawing = True
            in_page(self.model_note, self.redraw_model)

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
