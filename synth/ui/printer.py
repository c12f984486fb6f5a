"""The report's PDF printed by one headless Chromium kept running, over its DevTools pipe.

``synth report`` prints with WeasyPrint, else a Chromium started for the one file (:mod:`synth.report.pdf`):
4.5 s of CPU for WeasyPrint, 1.6 s for Chromium's start, on the default application's 19-page report. A page's
"Report PDF" asks again after every edit, so ``synth ui`` keeps one Chromium for the worker's life and sends it
``Page.printToPDF`` over ``--remote-debugging-pipe`` (file descriptors 3 and 4: no port is opened, nothing else
on the machine can talk to it). The same engine (Chromium 131 and later draw the report's page margin boxes),
the same HTML: the PDF is the one ``synth report --pdf-engine chromium`` writes. Without a Chromium, or when it
fails, :func:`synth.report.pdf.write_pdf` prints as the command line does.

No request leaves the machine: every host name resolves to nothing (the report is self-contained).
"""

from __future__ import annotations

import base64
import json
import os
import select
import shutil
import subprocess
import tempfile
import time
from pathlib import Path

__all__ = ["Printer", "print_pdf"]

#: seconds one print may take before the browser is restarted and the command line's engines are used
PRINT_TIMEOUT_S = 60.0

_FLAGS = ["--headless", "--no-sandbox", "--disable-gpu", "--remote-debugging-pipe", "--no-first-run",
          "--disable-background-networking", "--disable-component-update", "--disable-sync",
          "--disable-extensions", "--host-resolver-rules=MAP * ~NOTFOUND", "about:blank"]


class Printer:
    """One headless Chromium driven over its DevTools pipe (see the module docstring)."""

    def __init__(self, executable: str, folder: str | Path | None = None):
        self.profile = tempfile.mkdtemp(prefix="chromium-", dir=folder)
        to_r, to_w = os.pipe()      # we write, Chromium reads on fd 3
        from_r, from_w = os.pipe()  # Chromium writes on fd 4, we read

        def fds():  # in the child: the pipe's ends as fds 3 and 4, inheritable (dup first: 3 may be one of them)
            a, b = os.dup(to_r), os.dup(from_w)
            os.dup2(a, 3)
            os.dup2(b, 4)

        self.proc = subprocess.Popen([executable, f"--user-data-dir={self.profile}", *_FLAGS], preexec_fn=fds,
                                     close_fds=False, stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL,
                                     stderr=subprocess.DEVNULL)
        os.close(to_r)
        os.close(from_w)
        self._w, self._r = to_w, from_r
        self._buf = b""
        self._id = 0

    def _send(self, method: str, params: dict | None = None, session: str | None = None, timeout: float = 30.0):
        self._id += 1
        msg = {"id": self._id, "method": method, "params": params or {}}
        if session:
            msg["sessionId"] = session
        data = json.dumps(msg).encode() + b"\0"
        while data:
            data = data[os.write(self._w, data):]
        n = self._id
        out = self._until(lambda m: m.get("id") == n, timeout)
        if "error" in out:
            raise RuntimeError(f"Chromium: {method}: {out['error'].get('message', out['error'])}")
        return out.get("result", {})

    def _until(self, pred, timeout: float) -> dict:
        deadline = time.monotonic() + timeout
        while True:
            while b"\0" in self._buf:
                raw, self._buf = self._buf.split(b"\0", 1)
                m = json.loads(raw)
                if pred(m):
                    return m
            left = deadline - time.monotonic()
            if left <= 0 or not select.select([self._r], [], [], left)[0]:
                raise TimeoutError("Chromium did not answer in time")
            chunk = os.read(self._r, 1 << 20)
            if not chunk:
                raise EOFError("Chromium ended")
            self._buf += chunk

    def alive(self) -> bool:
        return self.proc.poll() is None

    def pdf(self, html: Path, timeout: float = PRINT_TIMEOUT_S) -> bytes:
        """The PDF of ``html`` (a file): the report's print CSS, its page size, backgrounds."""
        target = self._send("Target.createTarget", {"url": "about:blank"})["targetId"]
        try:
            s = self._send("Target.attachToTarget", {"targetId": target, "flatten": True})["sessionId"]
            self._send("Page.enable", session=s)
            self._send("Page.navigate", {"url": Path(html).resolve().as_uri()}, session=s)
            self._until(lambda m: m.get("method") == "Page.loadEventFired" and m.get("sessionId") == s, timeout)
            data = self._send("Page.printToPDF", {"printBackground": True, "preferCSSPageSize": True},
                              session=s, timeout=timeout)["data"]
        finally:
            try:
                self._send("Target.closeTarget", {"targetId": target}, timeout=5)
            except (OSError, EOFError, TimeoutError, RuntimeError):
                pass
        return base64.b64decode(data)

    def close(self) -> None:
        for fd in (self._w, self._r):
            try:
                os.close(fd)
            except OSError:
                pass
        if self.proc.poll() is None:
            self.proc.terminate()
            try:
                self.proc.wait(5)
            except subprocess.TimeoutExpired:
                self.proc.kill()
        shutil.rmtree(self.profile, ignore_errors=True)


_PRINTER: Printer | None = None


def print_pdf(html: str | Path, pdf: str | Path | None = None, *, folder: str | Path | None = None) -> tuple:
    """Print ``html`` to ``pdf`` (default: beside it, ``.pdf``) with the kept Chromium; ``(path, engine, note)`` as
    :func:`synth.report.pdf.write_pdf` returns (its engines when no Chromium can print). ``folder``: where the
    browser's profile goes (the server's folder, removed with it)."""
    global _PRINTER
    from synth.io.outputs import output_file
    from synth.report.pdf import chromium_binary, write_pdf
    html = Path(html)
    pdf = Path(pdf) if pdf else html.with_suffix(".pdf")
    exe = chromium_binary()
    if exe is not None and os.name == "posix":
        for _ in range(2):  # a browser that died since the last print is started again, once
            try:
                if _PRINTER is None or not _PRINTER.alive():
                    _PRINTER = Printer(exe, folder)
                data = _PRINTER.pdf(html)
            except (OSError, EOFError, TimeoutError, RuntimeError, json.JSONDecodeError, KeyError):
                if _PRINTER is not None:
                    _PRINTER.close()
                _PRINTER = None
                continue
            with output_file(pdf) as tmp:  # the output gate: a folder that refuses is the user's message
                Path(tmp).write_bytes(data)
            return pdf, "chromium", ""
    return write_pdf(html, pdf)


def close() -> None:
    global _PRINTER
    if _PRINTER is not None:
        _PRINTER.close()
        _PRINTER = None
