"""``synth ui`` in Debian's Chromium: cold start, an edit with the 3D view open, the first 3D view, STEP and PDF.

Run: ``.venv/bin/python benchmarks/bench_ui.py [--starts N] [--edits M] [--tree PATH ...]`` (needs ``synth[ui]``,
CadQuery and ``playwright``; the browser is ``/usr/bin/chromium``, never a downloaded one). Prints one markdown
table, a column per tree (``--tree``: checkouts of synth to compare in one run, each served by its own code; default
this one), and the machine's load average before and after. A benchmark, not a test: nothing is asserted.

* **cold start**: from spawning ``python -m synth ui --port P`` to the design page showing the checks of the embedded
  default application in Chromium (interpreter, imports, the synthesis, serving, the page's scripts, its first
  render); one warm-up start first (byte-code, numba's cache), then N. The end is the frame the page drew its first
  checks, by the page's own clock (the first animation frame after the checks table's rows were inserted; the
  browser and this script read the same system clock); the moment Playwright's polling noticed it, 0.1-0.25 s
  later, is printed too. The server's CPU time by then (``/proc``) too:
  on a loaded machine the wall time includes waiting for a core, the CPU time does not; and with its worker
  processes' (a first start's synthesis runs in the design worker, on the second core). The warm-up start also leaves
  synth's disk cache (``synth.fingerprint.cached``: the catalogs' arrays, the launch's opening and synthesis of the
  default application, ``synth.ui.work``) as a second start of the same version, catalogs and input finds it (the
  server then reads them itself, :func:`synth.ui.work.launch_on_disk`);
  ``--fresh-cache`` gives every start an empty cache folder instead (a first start after an upgrade or a catalog edit).
  Each start's page is a new browser context: the browser's first visit, every script fetched and compiled.
* **cold start, returning browser** (``--returning``): after each such start, a second one, the server started anew
  on the tree's own port (the same every time) and the page opened as a new tab of one browser context kept for the
  tree: an engineer who runs ``synth ui`` again and opens it in the browser that showed it before. NiceGUI serves
  its scripts as immutable for a year (``Cache-Control``), so the browser takes them from its cache instead of the
  server (the origin, host and port, must be the same: ``synth ui`` serves on 8080 unless told otherwise).
* **first 3D view**: from the 3D tab clicked to every part's STL loaded by the page, on the page of the last cold
  start: right after its checks appeared ("at once"), and on a second page of the same server after 10 s
  ("after a pause": what the server prepares while the engineer reads the checks).
* **edit to checks, 3D open**: with the 3D view shown, from the support's strength typed into its box to the new checks
  table painted (measured inside the page: the ``evaluation`` counter the server sets with the same update, then the
  next animation frame); M edits alternating between two values that leave the geometry as it is, and M of the pulley
  diameter, which changes it (the model is rebuilt meanwhile); median and 90th percentile.
  The server's CPU time from the edit typed to the checks painted too (``/proc``: what the server's part of an edit
  comes to on an idle machine; the browser's drawing is not in it).
* **STEP, PDF**: from the button clicked to the browser's download, after the 3D view was shown (its model built):
  the first of each; after an edit of the support's strength (a new result, the same geometry: STEP written from the
  kept model, the report a new document, drawn and printed); and **after the first build**: the design edited away and
  back, so the page asks its workers again and they answer from their caches (the model by the design's hash, the
  STEP by its header, the graphs by the result's hash, the PDF by the document's hash).

The issue's four figures (edit with the 3D view open, STEP and PDF after the first build, cold start) are the table's
first rows; ``uptime``'s load is printed with it (the targets are for an idle 2-core machine).
"""

from __future__ import annotations

import argparse
import os
import statistics
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]

_EDIT_JS = """async ([field, v]) => {
  const box = document.querySelector(`[data-field=${field}] input`);
  const seq = document.querySelector('[data-testid=seq]');
  const before = seq.dataset.seq;
  const t0 = performance.now();
  const done = new Promise(res => {
    const o = new MutationObserver(() => { if (seq.dataset.seq !== before) { o.disconnect(); res(); } });
    o.observe(seq, {attributes: true});
  });
  box.value = v;
  box.dispatchEvent(new Event('input', {bubbles: true}));
  await done;
  await new Promise(r => requestAnimationFrame(() => r()));
  return performance.now() - t0;
}"""

#: (field, two values) of the edits: the support's strength keeps the geometry (new checks, the same parts; a
#: stiffness edit changes the spring's coils), a pulley diameter changes it; both verify
EDITS = {"support": ("support_yield_strength_compression_mpa", ("380", "400")),
         "pulley": ("pulley_diameter_mm", ("66", "65.5"))}


def cpu_s(pid: int) -> float:
    """User + system CPU seconds of process ``pid`` so far (Linux ``/proc``; NaN elsewhere)."""
    try:
        fields = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()
        return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")
    except (OSError, IndexError, ValueError):
        return float("nan")


def children(pid: int) -> list[int]:
    """The live child processes of ``pid`` (Linux ``/proc``: every thread's ``children``; empty elsewhere)."""
    out: list[int] = []
    try:
        for task in Path(f"/proc/{pid}/task").iterdir():
            out += [int(c) for c in (task / "children").read_text().split()]
    except (OSError, ValueError):
        pass
    return out


def tree_cpu_s(pid: int) -> float:
    """:func:`cpu_s` of ``pid`` and of its child processes (the server and its workers), now."""
    return cpu_s(pid) + sum(tree_cpu_s(c) for c in children(pid))


class Tree:
    """A checkout of synth, served by its own code (``synth.ui.browser`` of this one starts it)."""

    def __init__(self, path: Path, fresh_cache: bool = False):
        self.path = path
        self.fresh_cache = fresh_cache
        self.cache_dirs: list[str] = []  # the empty cache folders made (--fresh-cache), removed at the end
        self.figures: dict[str, list[float]] = {}
        self.port: int | None = None  # --returning: the tree's own port, the same at every start
        self.kept = None  # --returning: the browser context kept across starts (its cache, as a user's browser)

    def add(self, name: str, value: float) -> None:
        self.figures.setdefault(name, []).append(value)

    def start(self, port: int):
        import subprocess
        env = {**os.environ, "PYTHONUNBUFFERED": "1", "PYTHONPATH": str(self.path)}
        env.pop("PYTEST_CURRENT_TEST", None)
        env.pop("PYTHONDONTWRITEBYTECODE", None)  # the warm-up start writes the byte-code, as an installed synth has it
        if self.fresh_cache:  # synth's disk cache empty at each start (numba's stays where it was)
            import tempfile

            from synth.kernels.numba_setup import kernel_cache_dir
            kernels = kernel_cache_dir()  # numba's compiled kernels: those of the usual cache folder
            env["SYNTH_CACHE_DIR"] = tempfile.mkdtemp(prefix="bench-ui-cache-")
            self.cache_dirs.append(env["SYNTH_CACHE_DIR"])
            if kernels is not None:
                env.setdefault("NUMBA_CACHE_DIR", str(kernels))
        return subprocess.Popen([sys.executable, "-P", "-m", "synth", "ui", "--port", str(port)], env=env,
                                stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, cwd=str(self.path))


#: the page's own clock at the frame it drew its first checks (the first animation frame after the checks table's
#: rows were inserted): ``window.__synthDrawn``, ms since the epoch (the machine's clock, the one ``time.time`` reads)
_DRAWN_JS = """new MutationObserver((_, o) => {
  if (document.querySelector('table.checks tr[data-check]')) {
    o.disconnect();
    requestAnimationFrame(() => { window.__synthDrawn = Date.now(); });
  }
}).observe(document, {subtree: true, childList: true});"""


def _drawn_s(page, t0_epoch: float) -> float:
    """Seconds from ``t0_epoch`` to the frame the page drew its first checks (:data:`_DRAWN_JS`)."""
    page.wait_for_function("window.__synthDrawn !== undefined")
    return page.evaluate("window.__synthDrawn") / 1000.0 - t0_epoch


def _page(browser, port: int, stl: list):
    ctx = browser.new_context(accept_downloads=True, viewport={"width": 1400, "height": 900})
    ctx.add_init_script(_DRAWN_JS)
    page = ctx.new_page()
    page.set_default_timeout(600_000)
    page.on("requestfinished", lambda r: stl.append(r.url) if r.url.endswith(".stl") else None)
    return ctx, page


def _checks_shown(browser, port: int, stl: list, kept=None):
    """A new page of the server on ``port``, once it shows the checks: ``(context, page)``; ``kept``: a browser
    context to open it in as a new tab (the context is then not the caller's to close: None is returned for it)."""
    from synth.ui.browser import goto_when_up
    if kept is None:
        ctx, page = _page(browser, port, stl)
    else:
        ctx, page = None, kept.new_page()
        page.set_default_timeout(600_000)
    goto_when_up(page, f"http://127.0.0.1:{port}/", 300)
    page.locator("table.checks tr[data-check]").first.wait_for()
    return ctx, page


def _first_view(page, stl: list) -> float:
    """Seconds from the 3D tab clicked to every part's STL loaded (the model note names how many)."""
    import re
    n0 = len(stl)
    t = time.perf_counter()
    page.get_by_role("tab", name="3D model").click()
    note = page.get_by_text(re.compile(r"\d+ parts \(STL"))
    note.wait_for()
    parts = int(re.match(r"(\d+)", note.inner_text()).group(1))
    while len(stl) - n0 < parts:
        page.wait_for_timeout(20)
    return time.perf_counter() - t


def _download(page, kind: str) -> float:
    t = time.perf_counter()
    with page.expect_download(timeout=600_000) as dl:
        page.locator(f"[data-testid=download-{kind}]").click()
    dl.value.path()
    return time.perf_counter() - t


def _edits(tree: Tree, page, edits: int, pid: int) -> None:
    """``edits`` edits of each kind (:data:`EDITS`) after two warm-up ones, with the 3D view shown; the server's CPU
    per edit (what an idle machine's server part of an edit approaches)."""
    for kind, (field, values) in EDITS.items():
        cpu = 0.0
        for k in range(edits + 2):
            c0 = cpu_s(pid)
            ms = page.evaluate(_EDIT_JS, [field, values[k % 2]])
            if k >= 2:  # two warm-up edits
                tree.add(f"edit_{kind}", ms)
                cpu += cpu_s(pid) - c0
            page.wait_for_timeout(150)
        tree.add(f"edit_{kind}_cpu", 1000 * cpu / max(edits, 1))  # the mean: /proc counts in 10 ms ticks


def measure_edits(tree: Tree, browser, edits: int) -> None:
    """The edits alone (``--only-edits``): one server, its page's 3D view shown, then :func:`_edits`."""
    from synth.ui.browser import free_port, stop_server
    port = free_port()
    proc = tree.start(port)
    stl: list = []
    ctx = None
    try:
        ctx, page = _checks_shown(browser, port, stl)
        _first_view(page, stl)
        page.wait_for_timeout(3000)  # the view at rest, the model's details made
        _edits(tree, page, edits, proc.pid)
    finally:
        if ctx is not None:
            ctx.close()
        stop_server(proc)


def _returning_start(tree: Tree, browser, first: bool) -> None:
    """One cold start on the tree's own port, its page a new tab of the tree's kept browser context (``first``: the
    start that fills the context's cache, not counted)."""
    from synth.ui.browser import free_port, stop_server
    if tree.kept is None:
        tree.port = free_port()
        tree.kept = browser.new_context(viewport={"width": 1400, "height": 900})
        tree.kept.add_init_script(_DRAWN_JS)
    t0, t0_epoch = time.perf_counter(), time.time()
    proc = tree.start(tree.port)
    page = None
    try:
        _, page = _checks_shown(browser, tree.port, [], kept=tree.kept)
        if not first:
            tree.add("cold_returning_noticed", time.perf_counter() - t0)
            tree.add("cold_returning", _drawn_s(page, t0_epoch))
            tree.add("cold_returning_cpu", cpu_s(proc.pid))
    finally:
        if page is not None:
            page.close()
        stop_server(proc)


def measure(tree: Tree, browser, starts: int, edits: int, only_cold: bool = False, returning: bool = False) -> None:
    from synth.ui.browser import free_port, stop_server
    for i in range(starts + 1):
        if returning:
            _returning_start(tree, browser, first=i == 0 and tree.kept is None)
        port = free_port()
        t0, t0_epoch = time.perf_counter(), time.time()
        proc = tree.start(port)
        stl: list = []
        ctx = None
        try:
            ctx, page = _checks_shown(browser, port, stl)
            if i == 0:
                continue  # the warm-up start
            tree.add("cold_noticed", time.perf_counter() - t0)
            tree.add("cold", _drawn_s(page, t0_epoch))
            tree.add("cold_cpu", cpu_s(proc.pid))
            tree.add("cold_cpu_all", tree_cpu_s(proc.pid))
            if i < starts or only_cold:
                continue
            tree.add("view_at_once", _first_view(page, stl))
            time.sleep(10)
            ctx2, page2 = _checks_shown(browser, port, stl)
            tree.add("view_after_pause", _first_view(page2, stl))
            ctx2.close()
            _edits(tree, page, edits, proc.pid)
            page.wait_for_timeout(3000)  # the last model rebuilt
            tree.add("step_first", _download(page, "step"))
            tree.add("pdf_first", _download(page, "pdf"))
            support = "support_yield_strength_compression_mpa"
            page.evaluate(_EDIT_JS, [support, "390"])  # a new result, the geometry kept: a new document
            tree.add("step_after_edit", _download(page, "step"))
            tree.add("pdf_after_edit", _download(page, "pdf"))
            page.evaluate(_EDIT_JS, [support, "395"])
            page.evaluate(_EDIT_JS, [support, "390"])  # and back: the design whose files were made
            tree.add("step_again", _download(page, "step"))
            tree.add("pdf_again", _download(page, "pdf"))
        finally:
            if ctx is not None:
                ctx.close()
            stop_server(proc)


#: (key, label, unit, target): the issue's four first (issue 35), then what else was measured
ROWS = (("edit_support", "edit to checks, 3D open, geometry kept (support strength) [ms]", "ms", "< 200"),
        ("edit_pulley", "edit to checks, 3D open, geometry changed (pulley diameter) [ms]", "ms", "< 200"),
        ("edit_support_cpu", "of which the server's CPU time, mean (geometry kept) [ms]", "ms", ""),
        ("edit_pulley_cpu", "of which the server's CPU time, mean (geometry changed) [ms]", "ms", ""),
        ("step_again", "STEP download after the first build (the design edited and back) [s]", "s", "< 3"),
        ("pdf_again", "PDF download after the first build (the design edited and back) [s]", "s", "< 3"),
        ("cold", "cold start to the checks of the default application drawn in the page [s]", "s", "< 3 (idle)"),
        ("cold_noticed", "the same, as Playwright noticed it (its polling round trip included) [s]", "s", ""),
        ("cold_cpu", "of which the server's CPU time by then [s]", "s", ""),
        ("cold_cpu_all", "the server's and its worker processes' CPU time by then [s]", "s", ""),
        ("cold_returning", "cold start, returning browser (its cache from an earlier start; --returning) [s]", "s",
         "< 3 (idle)"),
        ("cold_returning_noticed", "the same, as Playwright noticed it [s]", "s", ""),
        ("cold_returning_cpu", "of which the server's CPU time by then [s]", "s", ""),
        ("view_at_once", "first 3D view, tab clicked as the checks appear [s]", "s", ""),
        ("view_after_pause", "first 3D view, tab clicked 10 s later (a second page) [s]", "s", ""),
        ("step_first", "STEP download, first build (model built for the view) [s]", "s", ""),
        ("pdf_first", "PDF download, first build (model built for the view) [s]", "s", ""),
        ("step_after_edit", "STEP download after an edit (a new result, the same geometry) [s]", "s", ""),
        ("pdf_after_edit", "PDF download after an edit (a new document: drawn and printed) [s]", "s", ""))


def _uptime() -> str:
    import subprocess
    try:
        return subprocess.run(["uptime"], capture_output=True, text=True, timeout=5).stdout.strip()
    except (OSError, subprocess.SubprocessError):
        return "load average %.2f, %.2f, %.2f" % os.getloadavg()


def _p90(xs: list[float]) -> float:
    """The 90th percentile, nearest rank (of 2 values the larger)."""
    import math
    xs = sorted(xs)
    return xs[max(0, math.ceil(0.9 * len(xs)) - 1)]


def _cell(xs: list[float] | None, unit: str) -> str:
    if not xs:
        return "-"
    fmt = (lambda x: f"{x:.0f}") if unit == "ms" else (lambda x: f"{x:.2f}")
    if len(xs) == 1:
        return fmt(xs[0])
    return f"{fmt(statistics.median(xs))} (p90 {fmt(_p90(xs))}, n={len(xs)})"


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--starts", type=int, default=3, help="cold starts after the warm-up one (default 3)")
    ap.add_argument("--edits", type=int, default=20, help="edits of each kind (default 20)")
    ap.add_argument("--tree", action="append", default=[], help="a checkout of synth to measure (repeatable)")
    ap.add_argument("--only-cold", action="store_true", help="the cold starts only")
    ap.add_argument("--only-edits", action="store_true", help="the edits with the 3D view open only (one start)")
    ap.add_argument("--rounds", type=int, default=1, help="rounds over the trees (default 1)")
    ap.add_argument("--fresh-cache", action="store_true",
                    help="an empty synth disk cache (SYNTH_CACHE_DIR) at every start: a first start of a version")
    ap.add_argument("--returning", action="store_true",
                    help="each cold start also as a returning browser's: the tree's own port, one kept context")
    a = ap.parse_args(argv)
    sys.path.insert(0, str(ROOT))
    from synth.report.pdf import chromium_binary
    from synth.ui.browser import launch_chromium
    chromium = chromium_binary()
    if chromium is None:
        print("no chromium binary (apt-get install chromium): nothing measured")
        return 0
    from playwright.sync_api import sync_playwright
    trees = [Tree(Path(t).resolve(), a.fresh_cache) for t in (a.tree or [str(ROOT)])]
    load0 = os.getloadavg()
    print("uptime before:", _uptime())
    with sync_playwright() as p:
        browser = launch_chromium(p, chromium)
        for _ in range(a.rounds):  # the trees in turn, so that a change of the machine's load hits each alike
            for tree in trees:
                if a.only_edits:
                    measure_edits(tree, browser, a.edits)
                else:
                    measure(tree, browser, a.starts, a.edits, a.only_cold, a.returning)
        for tree in trees:
            if tree.kept is not None:
                tree.kept.close()
        browser.close()
    import shutil
    for tree in trees:
        for folder in tree.cache_dirs:
            shutil.rmtree(folder, ignore_errors=True)
    load1 = os.getloadavg()
    print("uptime after: ", _uptime())
    print(f"synth ui on this machine ({os.cpu_count()} cores, shared); load average {load0[0]:.1f} before, "
          f"{load1[0]:.1f} after; {a.starts} cold starts after a warm-up, {a.edits} edits of each kind.\n")
    print("| measurement | " + " | ".join(t.path.name for t in trees) + " | target |")
    print("|---|" + "---|" * len(trees) + "---|")
    for key, label, unit, target in ROWS:
        print(f"| {label} | " + " | ".join(_cell(t.figures.get(key), unit) for t in trees) + f" | {target} |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
