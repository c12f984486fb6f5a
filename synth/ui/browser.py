"""``synth ui`` driven from outside, as its tests and its benchmark do: a server process and a headless Chromium.

The browser is Debian's Chromium (:func:`synth.report.pdf.chromium_binary`), never one Playwright
downloads, started with the flags that keep it from calling home (:data:`CHROMIUM_FLAGS`).

>>> "--disable-background-networking" in CHROMIUM_FLAGS
True
>>> is_local("http://127.0.0.1:8080/_nicegui/x.js", 8080), is_local("https://fonts.example.org/a.css", 8080)
(True, False)
"""

from __future__ import annotations

import os
import socket
import subprocess
import sys
import time
from pathlib import Path
from urllib.parse import urlparse

__all__ = ["CHROMIUM_FLAGS", "free_port", "start_server", "stop_server", "launch_chromium", "goto_when_up",
           "wait_listening", "is_local"]

#: the folder this ``synth`` package was imported from (a clone's checkout, or site-packages): the server process
#: is given it first on its path so that it runs this same code, never another installed copy
PACKAGE_HOME = Path(sys.modules["synth"].__file__).resolve().parent.parent

#: ``python -P`` (3.11+): the working folder is not put first on the path, so a ``synth`` folder there (another
#: checkout) is never the one that runs
SAFE_PATH = ["-P"] if sys.version_info >= (3, 11) else []

#: headless, no GPU, no sandbox (containers), and none of Chromium's own traffic (updates, sync, first run)
CHROMIUM_FLAGS = ["--headless", "--no-sandbox", "--disable-gpu", "--disable-background-networking",
                  "--disable-component-update", "--disable-sync", "--no-first-run"]


def free_port() -> int:
    """A TCP port free on 127.0.0.1 now."""
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def start_server(port: int, *args: str, env: dict | None = None,
                 output: Path | None = None) -> tuple[subprocess.Popen, str]:
    """``python -m synth ui --port PORT ARGS`` as a process; returns it and the first line it printed.

    ``output``: a file the server's output (stdout and stderr) goes to, to be read while it runs (default: a pipe).
    """
    e = {**os.environ, **(env or {}), "PYTHONUNBUFFERED": "1"}
    e["PYTHONPATH"] = str(PACKAGE_HOME) + os.pathsep + e.get("PYTHONPATH", "")
    e.pop("PYTEST_CURRENT_TEST", None)  # NiceGUI would take its own test mode (and port) for a test's child
    cmd = [sys.executable, *SAFE_PATH, "-m", "synth", "ui", "--port", str(port), *args]
    if output is None:
        proc = subprocess.Popen(cmd, env=e, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
        return proc, proc.stdout.readline().strip()
    with open(output, "w", encoding="utf-8") as f:
        proc = subprocess.Popen(cmd, env=e, stdout=f, stderr=subprocess.STDOUT, text=True)
    deadline = time.perf_counter() + 60
    while "\n" not in Path(output).read_text(encoding="utf-8") and proc.poll() is None \
            and time.perf_counter() < deadline:
        time.sleep(0.02)
    return proc, Path(output).read_text(encoding="utf-8").split("\n", 1)[0].strip()


def stop_server(proc: subprocess.Popen) -> None:
    proc.terminate()
    try:
        proc.wait(15)
    except subprocess.TimeoutExpired:
        proc.kill()
        proc.wait(5)
    if proc.stdout:
        proc.stdout.close()


def launch_chromium(playwright, executable: str):
    """Playwright's Chromium driver on the given binary (Debian's), with :data:`CHROMIUM_FLAGS`."""
    return playwright.chromium.launch(executable_path=executable, args=CHROMIUM_FLAGS)


def wait_listening(host: str, port: int, timeout_s: float = 30.0) -> bool:
    """Whether a TCP connection to ``host:port`` is accepted within ``timeout_s`` (tried every 20 ms)."""
    deadline = time.perf_counter() + timeout_s
    while True:
        try:
            socket.create_connection((host, port), timeout=1.0).close()
            return True
        except OSError:
            if time.perf_counter() > deadline:
                return False
            time.sleep(0.02)


def goto_when_up(page, url: str, timeout_s: float = 30.0) -> None:
    """Open ``url`` once its server listens (:func:`wait_listening`: a connection tried, not a page loaded every
    20 ms, whose error pages took the browser a core while the server started), retrying while it does not."""
    deadline = time.perf_counter() + timeout_s
    u = urlparse(url)
    wait_listening(u.hostname or "127.0.0.1", u.port or 80, timeout_s)
    while True:
        try:
            page.goto(url, wait_until="commit", timeout=5000)
            return
        except Exception:  # noqa: BLE001 - connection refused until the server listens
            if time.perf_counter() > deadline:
                raise
            time.sleep(0.02)


def is_local(url: str, port: int) -> bool:
    """Whether a request the page made stays on this server (``data:`` and ``blob:`` URLs never leave)."""
    if url.startswith(("data:", "blob:", "about:")):
        return True
    u = urlparse(url)
    return u.hostname in ("127.0.0.1", "localhost") and (u.port or 80) == port
