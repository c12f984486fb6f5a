"""Which web framework for ``synth ui``: NiceGUI, Panel and Streamlit serving the same one-field calculator.

Run: ``python benchmarks/bench_ui_frameworks.py [--updates N] [--rounds R]`` with a Python that has
``playwright`` and any of ``nicegui``, ``panel``, ``streamlit`` installed (a framework that is not
installed is listed as such; the project itself needs only NiceGUI). Chromium is Debian's
(``/usr/bin/chromium``, or ``SYNTH_CHROMIUM``); no browser is downloaded.

Each framework serves the same app: a text field (a spring stiffness in Nm/deg) and an output line (the
torque at 30 deg, ``k * 30``). Per framework and round, in turn (N P S N P S ..., so a drift of the shared
machine's speed falls on all of them alike):

* **cold start**: from spawning the server process to the output line being visible in Chromium (the
  interpreter starts, imports the framework, serves, the page loads and renders);
* **update**: from filling the field with a new value and pressing Enter (every framework commits a text
  field on Enter) until the output line shows the new torque: the browser -> server -> browser round trip
  of one edit, N times; the median and the 90th percentile;
* **external requests**: requests the page made to any host other than 127.0.0.1 (aborted: the machine
  has no network; counted, because ``synth ui`` must work offline).

The table prints the medians over the rounds and the ratio of each to NiceGUI's, measured side by side.
"""

from __future__ import annotations

import argparse
import importlib.util
import os
import statistics
import subprocess
import sys
import tempfile
import textwrap
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))  # synth.ui.browser needs only the standard library: any Python with Playwright runs this

from synth.ui.browser import free_port, goto_when_up, is_local, launch_chromium  # noqa: E402

CHROMIUM = os.environ.get("SYNTH_CHROMIUM", "/usr/bin/chromium")

APPS = {
    "nicegui": textwrap.dedent("""
        from nicegui import ui

        @ui.page("/")
        def index():
            k = ui.input("stiffness [Nm/deg]", value="2")
            out = ui.label("torque = 60 Nm")
            def show():
                try:
                    out.set_text(f"torque = {float(k.value) * 30:g} Nm")
                except ValueError:
                    out.set_text("not a number")
            k.on("keydown.enter", show)

        ui.run(host="127.0.0.1", port=PORT, reload=False, show=False, show_welcome_message=False)
        """),
    "panel": textwrap.dedent("""
        import panel as pn

        k = pn.widgets.TextInput(name="stiffness [Nm/deg]", value="2")
        def torque(v):
            try:
                return f"torque = {float(v) * 30:g} Nm"
            except ValueError:
                return "not a number"
        pn.Column(k, pn.pane.Str(pn.bind(torque, k))).servable()
        """),
    "streamlit": textwrap.dedent("""
        import streamlit as st

        v = st.text_input("stiffness [Nm/deg]", value="2")
        try:
            st.text(f"torque = {float(v) * 30:g} Nm")
        except ValueError:
            st.text("not a number")
        """),
}


def _command(name: str, script: Path, port: int) -> list[str]:
    if name == "nicegui":
        return [sys.executable, str(script)]
    if name == "panel":
        return [sys.executable, "-m", "panel", "serve", str(script), "--address", "127.0.0.1", "--port", str(port),
                "--allow-websocket-origin", f"127.0.0.1:{port}"]
    return [sys.executable, "-m", "streamlit", "run", str(script), "--server.address", "127.0.0.1",
            "--server.port", str(port), "--server.headless", "true", "--browser.gatherUsageStats", "false"]


def _url(name: str, port: int, script: Path) -> str:
    return f"http://127.0.0.1:{port}/" + (script.stem if name == "panel" else "")


def one_round(browser, name: str, folder: Path, updates: int) -> dict:
    port = free_port()
    script = folder / f"app_{name}.py"
    script.write_text(APPS[name].replace("PORT", str(port)), encoding="utf-8")
    env = {**os.environ, "PYTHONUNBUFFERED": "1"}
    t0 = time.perf_counter()
    proc = subprocess.Popen(_command(name, script, port), cwd=folder, env=env, stdout=subprocess.DEVNULL,
                            stderr=subprocess.DEVNULL)
    external: list[str] = []
    try:
        page = browser.new_page()

        def route(r):
            if not is_local(r.request.url, port):
                external.append(r.request.url)
                return r.abort()
            return r.continue_()
        page.route("**/*", route)
        goto_when_up(page, _url(name, port, script), 60)
        page.get_by_text("torque = 60 Nm").wait_for(timeout=60000)
        cold = time.perf_counter() - t0
        box = page.locator("input").first
        times = []
        for i in range(updates):
            value = 3 + i
            t = time.perf_counter()
            box.fill(str(value))
            box.press("Enter")
            page.get_by_text(f"torque = {value * 30:g} Nm").wait_for(timeout=20000)
            times.append(time.perf_counter() - t)
        page.close()
    finally:
        proc.terminate()
        try:
            proc.wait(10)
        except subprocess.TimeoutExpired:
            proc.kill()
    times.sort()
    return {"cold": cold, "median": statistics.median(times), "p90": times[int(0.9 * (len(times) - 1))],
            "external": len(external)}


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--updates", type=int, default=15)
    ap.add_argument("--rounds", type=int, default=3)
    a = ap.parse_args(argv)
    from playwright.sync_api import sync_playwright
    names = [n for n in APPS if importlib.util.find_spec(n)]
    missing = [n for n in APPS if n not in names]
    rows: dict = {n: [] for n in names}
    with tempfile.TemporaryDirectory() as tmp, sync_playwright() as p:
        browser = launch_chromium(p, CHROMIUM)
        for _ in range(a.rounds):
            for n in names:
                rows[n].append(one_round(browser, n, Path(tmp), a.updates))
        browser.close()
    med = {n: {k: statistics.median(r[k] for r in rows[n]) for k in ("cold", "median", "p90", "external")}
           for n in names}
    ref = med.get("nicegui")
    print(f"Same one-field calculator in each framework; {a.rounds} rounds, {a.updates} updates each, "
          "interleaved; medians over the rounds.\n")
    print("| framework | version | cold start to rendered page [s] | update median [ms] | update p90 [ms] | "
          "update / NiceGUI | external requests |")
    print("|---|---|---|---|---|---|---|")
    from importlib.metadata import version
    for n in names:
        m = med[n]
        ratio = f"{m['median'] / ref['median']:.2f}" if ref else "-"
        print(f"| {n} | {version(n)} | {m['cold']:.2f} | {1000 * m['median']:.0f} | {1000 * m['p90']:.0f} | "
              f"{ratio} | {m['external']:.0f} |")
    for n in missing:
        print(f"| {n} | not installed | - | - | - | - | - |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
