"""The report as PDF, written beside its HTML: WeasyPrint (pip only), else headless Chromium's print-to-PDF.

WeasyPrint is pure Python (a wheel from PyPI) over Pango, which the Debian
image has; it honours the report's print CSS (``@page`` size and margin boxes:
the title block on every page, page breaks, repeated table headers, rows never
split). Where it cannot load (no Pango on the machine), a ``chromium`` (or
``chromium-browser``, ``google-chrome``) binary on the PATH prints the same
HTML with ``--print-to-pdf`` (Chromium 131 and later also draw the page
margin boxes). Neither: no PDF, and the reason is returned, never raised.

>>> page_count(b"%PDF-1.7 1 0 obj <</Type /Pages /Count 2>> <</Type /Page>> <</Type /Page>>")
2
"""

from __future__ import annotations

import re
import shutil
import subprocess
import tempfile
import zlib
from pathlib import Path
from synth.io.outputs import output_file

__all__ = ["write_pdf", "page_count", "chromium_binary", "ENGINES"]

ENGINES = ("auto", "weasyprint", "chromium")
_BROWSERS = ("chromium", "chromium-browser", "google-chrome", "google-chrome-stable")


def chromium_binary() -> str | None:
    """The path of a Chromium (or Chrome) binary on the PATH, or None."""
    for name in _BROWSERS:
        path = shutil.which(name)
        if path:
            return path
    return None


def page_count(pdf: bytes | str | Path) -> int:
    """The number of pages of a PDF (bytes or a path): its ``/Type /Page`` objects, also inside compressed
    object streams (WeasyPrint writes them)."""
    data = pdf if isinstance(pdf, bytes) else Path(pdf).read_bytes()
    pattern = re.compile(rb"/Type\s*/Page(?![a-zA-Z])")
    n = len(pattern.findall(data))
    for m in re.finditer(rb"/Type\s*/ObjStm.*?stream\r?\n", data, re.S):
        end = data.find(b"endstream", m.end())
        try:
            n += len(pattern.findall(zlib.decompress(data[m.end():end])))
        except zlib.error:
            continue
    return n


def _weasyprint(html: Path, pdf: Path) -> None:
    import logging

    import weasyprint
    logging.getLogger("weasyprint").setLevel(logging.ERROR)
    logging.getLogger("fontTools").setLevel(logging.ERROR)
    weasyprint.HTML(filename=str(html)).write_pdf(str(pdf))


def _chromium(html: Path, pdf: Path, timeout_s: float = 120.0) -> None:
    exe = chromium_binary()
    if exe is None:
        raise FileNotFoundError("no chromium binary on the PATH")
    with tempfile.TemporaryDirectory() as profile:
        subprocess.run([exe, "--headless", "--no-sandbox", "--disable-gpu", "--no-pdf-header-footer",
                        f"--user-data-dir={profile}", f"--print-to-pdf={pdf}", html.resolve().as_uri()],
                       check=True, capture_output=True, timeout=timeout_s)
    if not pdf.is_file():
        raise RuntimeError("chromium wrote no PDF")


def write_pdf(html_path: str | Path, pdf_path: str | Path | None = None, *, engine: str = "auto") -> tuple:
    """Print ``html_path`` to ``pdf_path`` (default: the same name, ``.pdf``).

    Returns ``(path, engine used, "")`` or ``(None, "", reason)`` when no engine could write it.
    """
    html = Path(html_path)
    pdf = Path(pdf_path) if pdf_path else html.with_suffix(".pdf")
    if engine not in ENGINES:
        from synth.errors import InputError, Problem
        raise InputError(Problem("--pdf-engine", engine, "one of " + ", ".join(ENGINES)))
    from synth.errors import InputError
    tried = []
    for name, fn in (("weasyprint", _weasyprint), ("chromium", _chromium)):
        if engine not in ("auto", name):
            continue
        try:
            with output_file(pdf) as tmp:  # a temporary file renamed when complete (never through a link)
                fn(html, tmp)
            return pdf, name, ""
        except InputError:  # the folder refuses the file (read-only, full): the user's to fix, not an engine's
            raise
        except Exception as exc:  # noqa: BLE001 - an engine that cannot run here: the next one, then the reason
            tried.append(f"{name}: {type(exc).__name__}: {str(exc).splitlines()[0] if str(exc) else ''}".rstrip(": "))
    return None, "", "; ".join(tried)
