"""``synth ui``: cold start to a usable page, and the re-verification after an edit, in Debian's Chromium.

Run: ``.venv/bin/python benchmarks/bench_ui.py [--starts N] [--edits M]`` (needs ``synth[ui]`` and
``playwright``; the browser is ``/usr/bin/chromium``, never a downloaded one). Prints a markdown table.

* **cold start**: from spawning ``python -m synth ui --port P`` to the design page showing the checks of
  the embedded default application in Chromium (interpreter, imports, the synthesis, serving, the page's
  scripts and its first render). One warm-up start first (byte-code, synth's on-disk cache), then N.
  The server's CPU time by then (``/proc``) is printed too: on a loaded machine the wall time includes
  waiting for a core, the CPU time does not.
* **re-verification after an edit**: measured inside the page: from the spring stiffness typed into its
  box (an ``input`` event) to the browser having the new checks table (the ``evaluation`` counter the
  server sets with the same update) and the next animation frame: browser -> server (validate, verify,
  render the rows) -> browser. M edits alternating between values; median and 90th percentile.
* **of which in the server**: the same edits through :class:`synth.ui.session.DesignSession` and the
  HTML it renders, in this process (no browser, no network).
* **reference: the command line**: ``synth design`` on the same input as a whole process, the answer to
  one edit before ``synth ui`` (median of N), measured in the same run; and ``python -c "import pandas,
  nicegui"``, the imports any start of the server pays (the machine's load shows in both).

Targets (issue 25): cold start under 3 s, re-verification under 200 ms (median).
"""

from __future__ import annotations

import argparse
import os
import statistics
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from synth.report.pdf import chromium_binary  # noqa: E402
from synth.ui.browser import free_port, goto_when_up, launch_chromium, start_server, stop_server  # noqa: E402

_EDIT_JS = """async (v) => {
  const box = document.querySelector('[data-field=spring_stiffness_nm_per_deg] input');
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

_VALUES = ("0.0170", "0.0164")  # the default application's stiffness and a neighbour: both verify


def cpu_s(pid: int) -> float:
    """User + system CPU seconds of process ``pid`` so far (Linux ``/proc``; NaN elsewhere)."""
    try:
        fields = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()
        return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")
    except (OSError, IndexError, ValueError):
        return float("nan")


def cold_start(browser) -> tuple[float, float, object, object]:
    """Seconds from spawning the server to the checks in the page, and the server's CPU seconds by then;
    returns (wall, cpu, server process, page)."""
    port = free_port()
    t0 = time.perf_counter()
    proc, _ = start_server(port)
    page = browser.new_page()
    goto_when_up(page, f"http://127.0.0.1:{port}/")
    page.locator("table.checks tr[data-check]").first.wait_for(timeout=60000)
    return time.perf_counter() - t0, cpu_s(proc.pid), proc, page


def server_side(edits: int) -> list[float]:
    from synth.report.html import digest_html
    from synth.ui import views
    from synth.ui.session import DesignSession, default_values
    s = DesignSession(default_values())
    s.synthesise()
    out = []
    for i in range(edits):
        t = time.perf_counter()
        s.edit("spring_stiffness_nm_per_deg", _VALUES[i % 2])
        digest_html(s.result), views.checks_table(s.result), views.parts_table(s.result), views.binding_table(s.result)
        out.append(1000 * (time.perf_counter() - t))
    return out


#: the references, whole processes: one edit's answer on the command line, and the imports a server needs
REFERENCES = {"design": ["-m", "synth", "design", str(ROOT / "synth" / "data" / "default_case.yaml")],
              "imports": ["-c", "import pandas, nicegui"]}


def command_line(runs: int, which: str = "design") -> list[float]:
    env = {**os.environ, "PYTHONPATH": str(ROOT) + os.pathsep + os.environ.get("PYTHONPATH", "")}
    cmd = [sys.executable, *REFERENCES[which]]
    subprocess.run(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, env=env, check=False)  # warm-up
    out = []
    for _ in range(runs):
        t = time.perf_counter()
        subprocess.run(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, env=env, check=False)
        out.append(time.perf_counter() - t)
    return out


def _p90(xs: list[float]) -> float:
    xs = sorted(xs)
    return xs[int(0.9 * (len(xs) - 1))]


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--starts", type=int, default=5)
    ap.add_argument("--edits", type=int, default=40)
    a = ap.parse_args(argv)
    chromium = chromium_binary()
    if chromium is None:
        print("no chromium binary (apt-get install chromium): nothing measured")
        return 0
    from playwright.sync_api import sync_playwright
    starts, cpus, edits = [], [], []
    with sync_playwright() as p:
        browser = launch_chromium(p, chromium)
        for i in range(a.starts + 1):
            s, cpu, proc, page = cold_start(browser)
            try:
                if i > 0:  # the first start is the warm-up
                    starts.append(s)
                    cpus.append(cpu)
                if i == a.starts:
                    for k in range(a.edits + 2):
                        ms = page.evaluate(_EDIT_JS, _VALUES[k % 2])
                        if k >= 2:  # two warm-up edits
                            edits.append(ms)
            finally:
                page.close()
                stop_server(proc)
        browser.close()
    server = server_side(a.edits)
    cli = command_line(a.starts)
    imports = command_line(a.starts, "imports")
    print(f"synth ui on this machine ({os.cpu_count()} cores, shared); {a.starts} cold starts after one warm-up, "
          f"{a.edits} edits after two warm-up edits.\n")
    print("| measurement | median | p90 | target | n |")
    print("|---|---|---|---|---|")
    print(f"| cold start to the checks of the default application in the page [s] | {statistics.median(starts):.2f} | "
          f"{_p90(starts):.2f} | < 3 | {len(starts)} |")
    print(f"| of which the server's CPU time by then [s] | {statistics.median(cpus):.2f} | {_p90(cpus):.2f} | | "
          f"{len(cpus)} |")
    print(f"| re-verification after an edit, in the page [ms] | {statistics.median(edits):.0f} | {_p90(edits):.0f} | "
          f"< 200 | {len(edits)} |")
    print(f"| of which in the server: validate, verify, render [ms] | {statistics.median(server):.1f} | "
          f"{_p90(server):.1f} | | {len(server)} |")
    print(f"| reference: `synth design` on the same input, whole command [s] | {statistics.median(cli):.2f} | "
          f"{_p90(cli):.2f} | | {len(cli)} |")
    print(f"| reference: `python -c \"import pandas, nicegui\"` [s] | {statistics.median(imports):.2f} | "
          f"{_p90(imports):.2f} | | {len(imports)} |")
    print(f"\nAn edit in the page answers {statistics.median(cli) * 1000 / statistics.median(edits):.0f} times faster "
          "than the command line's whole run (medians of this run).")
    return 0


if __name__ == "__main__":
    sys.exit(main())
