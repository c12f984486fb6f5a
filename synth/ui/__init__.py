"""``synth ui``: a local web application for the design loop (NiceGUI), on the public API only.

* :mod:`synth.ui.form` - the design input as a form generated from :mod:`synth.schema`;
* :mod:`synth.ui.session` - one design's state: input, design rules, current design, result, its files;
* :mod:`synth.ui.portfolio` - a portfolio's screening, summary and platform;
* :mod:`synth.ui.views` - the result's HTML fragments (the report's rows, the verdict palette);
* :mod:`synth.ui.app` - the NiceGUI pages;
* :mod:`synth.ui.guard` - which requests the server answers (Host, Origin, token, body size);
* :mod:`synth.ui.uploads` - files received as they stream, their size and name checked;
* :mod:`synth.ui.jobs` - the long work in threads that end with the server;
* :mod:`synth.ui.messages` - every error a message in the page, one line in the server's output.

:func:`serve` starts the server (``synth ui``); NiceGUI is the optional dependency ``synth[ui]``.
Why NiceGUI: ``docs/sections/ui.md`` (measured by ``benchmarks/bench_ui_frameworks.py``).
"""

from __future__ import annotations

from pathlib import Path

__all__ = ["serve", "LOCAL_HOSTS"]

LOCAL_HOSTS = ("127.0.0.1", "localhost", "::1")

#: seconds the server waits for open requests when it stops (SIGTERM, Ctrl-C) before it ends them
STOP_GRACE_S = 1.0

#: seconds a page's state outlives a lost connection to its browser (NiceGUI's ``reconnect_timeout``; its socket's
#: ping interval and timeout are 0.8 and 0.4 of it). NiceGUI's 3 s drops the connection when the browser or the
#: server does not answer for 2 s and deletes the page 3 s later: on a busy machine a 10 s stall of the browser's
#: script reloaded the page, its design, alternatives and screening lost (a CI run of the browser test lost an
#: applied alternative so). A closed tab's state is freed this long after it closed.
RECONNECT_S = 30.0

#: packages the server never uses that NiceGUI's socket.io loads when it is imported: aiohttp for engineio's *client*
#: classes, tornado for its tornado driver (NiceGUI serves socket.io over ASGI). Both imports are optional there
#: (``try: import ... except ImportError``); :func:`serve` marks them absent, 0.3 s of the cold start's CPU (a fifth of
#: NiceGUI's import), measured by ``benchmarks/bench_ui.py``
UNUSED = ("aiohttp", "tornado")


def _keep_compiled_templates() -> None:
    """NiceGUI's page template compiled once per install, kept in synth's cache folder (Jinja's bytecode cache,
    checked against the template's source): a server's first page compiled it anew, 0.05-0.08 s before the browser
    had its HTML."""
    from jinja2 import FileSystemBytecodeCache
    from nicegui import client

    from synth.fingerprint import cache_dir
    folder = cache_dir()
    if folder is None:
        return
    try:
        (folder / "templates").mkdir(parents=True, exist_ok=True)
    except OSError:
        return
    client.templates.env.bytecode_cache = FileSystemBytecodeCache(str(folder / "templates"))


def compression(host: str) -> dict:
    """NiceGUI's ``ui.run`` arguments for compressing responses served on ``host``. NiceGUI compresses every
    response (Starlette's ``GZipMiddleware`` at level 9) on the server's one event loop: 0.10 s of CPU for
    ``quasar.umd.prod.js`` alone (0.017 s sent as it is), every other file of the page waiting behind it on a
    browser's first visit. On the loopback nothing is gained by it: sent as they are there, compressed when the
    server is reached over a network.

    >>> compression("127.0.0.1"), compression("0.0.0.0")
    ({'gzip_middleware_factory': None}, {})
    """
    return {"gzip_middleware_factory": None} if host in LOCAL_HOSTS else {}


def serve(values: dict, source: str, *, host: str = "127.0.0.1", port: int = 8080, root: str | Path | None = None,
          rules=None, policy=None) -> None:
    """Serve the pages on ``host:port`` until interrupted; ``values``: the design input the design page opens,
    ``rules`` its design rules (:class:`synth.design.rules.Rules`), ``policy`` what the server accepts
    (:class:`synth.ui.guard.Policy`; default: :meth:`~synth.ui.guard.Policy.of` ``host, port``, with a new token
    when ``host`` is beyond the loopback).

    The synthesis of ``values`` is made in a worker process while NiceGUI is imported and the browser loads the page
    (:class:`synth.ui.launch.Launch`)."""
    import shutil
    import tempfile

    import sys

    from synth.ui.launch import Launch
    from synth.ui.trace import mark
    launch = Launch(values, source, rules)
    launch.submit()  # synthesised in the design worker while NiceGUI is imported here
    for name in UNUSED:  # the server process is ours until it ends: nothing in it asks for them later
        sys.modules.setdefault(name, None)
    mark("serving: importing NiceGUI")
    from nicegui import app, ui

    from synth.ui.app import setup
    from synth.ui.guard import Policy
    policy = policy or Policy.of(host, port)
    folder = Path(root) if root else Path(tempfile.mkdtemp(prefix="synth-ui-"))
    mark("NiceGUI and the server's modules imported")
    _keep_compiled_templates()
    app.on_startup(launch.start)
    setup(values, source, policy=policy, root=folder, rules=rules, launch=launch)
    if root is None:  # the uploads, 3D models and reports of every tab: gone with the server
        app.on_shutdown(lambda: shutil.rmtree(folder, ignore_errors=True))
    ui.run(host=host, port=port, title="synth", reload=False, show=False, show_welcome_message=False,
           uvicorn_logging_level="warning", favicon="⚙", tailwind=False,  # Quasar classes only: no Tailwind runtime
           timeout_graceful_shutdown=STOP_GRACE_S, reconnect_timeout=RECONNECT_S,
           **compression(host))
