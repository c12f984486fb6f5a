"""The pages of ``synth ui`` (NiceGUI), the server's routes and its checks on what the pages send.

* ``/``: the design page (:mod:`synth.ui.design_page`): the form, the checks, the design, alternatives, what-if,
  capability, graphs, the 3D model, downloads;
* ``/portfolio``: the portfolio page (:mod:`synth.ui.portfolio_page`): screening, summary, table, platform, files.

A page is built once its browser tab has connected (NiceGUI's tab id): the tab's design and portfolio are kept
across its pages (:mod:`synth.ui.tabs`), so Back from an application opened on the design page shows the screening
again. Everything the page loads comes from this server: NiceGUI ships Vue, Quasar, three.js, ECharts and its fonts;
the graphs are PNG data, the 3D parts and downloads are files under the server's own folder.

The server trusts nothing it did not serve (:mod:`synth.ui.guard`: Host, Origin, token, body size); files
are received as they stream (:mod:`synth.ui.uploads`); the long work runs in worker processes
(:mod:`synth.ui.worker`) or in threads that end with the server (:mod:`synth.ui.jobs`); every error, and every
event the page sends that is not one it could send, becomes a message in the page (:mod:`synth.ui.messages`),
never a traceback.
"""

from __future__ import annotations

import inspect
import logging
import math
from pathlib import Path

from nicegui import app, ui

from synth.errors import InputError, Problem
from synth.io.limits import short
from synth.ui import jobs, tabs, uploads, worker
from synth.ui.guard import BODY_LIMIT, Guard, Policy
from synth.ui.messages import message_of, quiet_tracebacks
from synth.ui.trace import mark
from synth.ui.widgets import CSS, FILES_URL

__all__ = ["setup", "FILES_URL", "CONNECT_S"]

#: seconds a page waits for its browser tab to connect (the page's scripts load first; a loaded machine is slow)
CONNECT_S = 60.0

_log = logging.getLogger("synth.ui")


def _page_errors() -> None:
    """Every error of this page's handlers a message in the page (NiceGUI's per-page exception handler)."""
    from synth.ui.widgets import refused
    ui.on_exception(lambda exc: refused(exc))


def _page(build) -> None:
    """Build a page; an error is a message in it, not NiceGUI's error page with a traceback in the log."""
    try:
        build()
    except Exception as exc:  # noqa: BLE001 - every error a message in the page
        ui.label("synth ui could not build this page: " + message_of(exc)).classes("text-negative q-pa-md")
        _log.warning("page: %s", message_of(exc), exc_info=exc)


async def _tab() -> str | None:
    """This page's tab id, once the tab has connected (None: it went away first)."""
    client = ui.context.client
    try:
        await client.connected(timeout=CONNECT_S)
    except Exception:  # noqa: BLE001 - NiceGUI's ClientConnectionTimeout: the tab went away
        return None
    if client.is_deleted or client.tab_id is None:
        return None
    return client.tab_id


def setup(values: dict, source: str, *, policy: Policy, root: Path, rules=None, launch=None) -> None:
    """Register the pages, the upload route and the server's guard; ``values``/``source``/``rules``: the input the
    design page opens with; ``launch``: its synthesis, started in a worker (:class:`synth.ui.launch.Launch`)."""
    app.add_static_files(FILES_URL, root)
    ui.add_css(CSS, shared=True)
    ui.add_head_html(_preloads(), shared=True)
    app.add_route(uploads.UPLOAD_URL + "/{key}", _upload_route, methods=["POST"])
    app.add_middleware(Guard, policy=policy, body_limit=lambda path: uploads.body_limit(path) or BODY_LIMIT)
    from nicegui import core
    core.sio.eio.cors_allowed_origins = policy.origins()  # NiceGUI's is "*": any site's page
    _check_socket_messages(core.sio)
    quiet_tracebacks()
    app.on_shutdown(jobs.STOP.set)
    app.on_shutdown(worker.stop_all)
    app.on_shutdown(tabs.forget_all)
    host, port = policy.host, policy.port

    @ui.page("/", title="synth: design")
    async def design_page(open: str | None = None) -> None:  # noqa: A002 - the query parameter's name
        mark("design page requested")
        _page_errors()
        tab_id = await _tab()  # the page's HTML is sent now: its modules are imported after, by then the launch's
        if tab_id is None:     # thread has imported them while the browser loaded the page (else the HTML waited)
            return
        from synth.ui.design_page import DesignPage
        from synth.ui.portfolio_page import HANDOFF
        from synth.ui.session import DesignSession
        mark("design page connected")
        tab = tabs.state(tab_id, root)
        handed = HANDOFF.pop(open or "", None)  # a portfolio's application: its input, fidelity and rules
        # the server's input as the launch's worker opened it (validated, its drop-downs read): none read here
        opened = await launch.opened() if launch is not None and handed is None and tab.design is None else None

        def build():
            if handed is not None or tab.design is None:
                v, src, r = (handed[0], handed[1], handed[3]) if handed else (values, source, rules)
                s = DesignSession(v, source=src, workdir=tab.folder / "design", rules=r, opened=opened)
                if handed:
                    s.fidelity = handed[2]
                tab.design = s
            DesignPage(tab.design, root, host, port, launch=launch)
        _open(tab, build)

    @ui.page("/portfolio", title="synth: portfolio")
    async def portfolio_page() -> None:
        _page_errors()
        from synth.ui.portfolio import PortfolioSession
        from synth.ui.portfolio_page import PortfolioPage
        tab_id = await _tab()
        if tab_id is None:
            return
        tab = tabs.state(tab_id, root)

        def build():
            if tab.portfolio is None:
                tab.portfolio = PortfolioSession(tab.folder / "portfolio")
            ui.context.client._synth_portfolio = PortfolioPage(tab.portfolio, host, port)
        _open(tab, build)


#: the elements of the pages whose Vue component is a script of its own (NiceGUI's ``component``)
PRELOADED = ("header", "link", "upload", "expansion", "select", "input", "html")


def _preloads() -> str:
    """``<link rel="modulepreload">`` of the :data:`PRELOADED` elements' scripts: the browser fetches them with the
    page's own scripts. A page is built once its tab has connected, so NiceGUI names them only in that update, and
    each was a request more, after the connection, before the first checks could be drawn."""
    from html import escape

    from nicegui import __version__
    urls = [f"/_nicegui/{__version__}/components/{c.key}" for c in
            (getattr(getattr(ui, name), "component", None) for name in PRELOADED) if c is not None]
    return "".join(f'<link rel="modulepreload" href="{escape(u)}">' for u in urls)


def _open(tab, build) -> None:
    tab.opened()
    ui.context.client.on_delete(tab.closed)
    _page(build)


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
