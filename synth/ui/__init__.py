"""``synth ui``: a local web application for the design loop (NiceGUI), on the public API only.

* :mod:`synth.ui.form` - the design input as a form generated from :mod:`synth.schema`;
* :mod:`synth.ui.session` - one design's state: input, current design, result, its files;
* :mod:`synth.ui.portfolio` - a portfolio's screening, summary and platform;
* :mod:`synth.ui.views` - the result's HTML fragments (the report's rows, the verdict palette);
* :mod:`synth.ui.app` - the NiceGUI pages.

:func:`serve` starts the server (``synth ui``); NiceGUI is the optional dependency ``synth[ui]``.
Why NiceGUI: ``docs/sections/ui.md`` (measured by ``benchmarks/bench_ui_frameworks.py``).
"""

from __future__ import annotations

from pathlib import Path

__all__ = ["serve", "LOCAL_HOSTS"]

LOCAL_HOSTS = ("127.0.0.1", "localhost", "::1")


def serve(values: dict, source: str, *, host: str = "127.0.0.1", port: int = 8080, root: str | Path | None = None) -> None:
    """Serve the pages on ``host:port`` until interrupted; ``values``: the design input the design page opens."""
    import shutil
    import tempfile

    from nicegui import app, ui

    from synth.ui.app import setup
    folder = Path(root) if root else Path(tempfile.mkdtemp(prefix="synth-ui-"))
    setup(values, source, host=host, port=port, root=folder)
    if root is None:  # the uploads, 3D models and reports of every tab: gone with the server
        app.on_shutdown(lambda: shutil.rmtree(folder, ignore_errors=True))
    ui.run(host=host, port=port, title="synth", reload=False, show=False, show_welcome_message=False,
           uvicorn_logging_level="warning", favicon="⚙", tailwind=False)  # Quasar classes only: no Tailwind runtime
