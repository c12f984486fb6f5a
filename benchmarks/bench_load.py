"""Every scene beside a competing load (issue 36): whole commands quiet and with busy processes, in turn.

Run: ``.venv/bin/python benchmarks/bench_load.py [--busy 2] [--runs 1] [--only NAME ...] [--base CHECKOUT]
[--same-session]`` (prints a markdown table). Each command runs as a fresh process, first on the machine as it is
("quiet": other users' work shows, so the load average is printed), then with ``--busy`` processes ``python -c
"while 1: pass"`` started just before it and killed just after. They start in a session of their own, as another
program's would (Linux's autogroup then schedules them as a group of their own, beside the command's);
``--same-session`` starts them in the benchmark's session, so that they share the command's group. ``--runs``
such pairs, the ratio loaded/quiet taken pair by pair (median), so a drift of the machine's speed between pairs
cancels. Wall seconds, and the command's own CPU seconds (``os.wait4``: the process and the children it waited
for): a CPU ratio near 1 says the command waited for a core and wasted nothing; above 1, threads that spin or
fight (the drive's BLAS before issue 36). ``--base CHECKOUT`` runs each command of the checkout too
(``PYTHONPATH=CHECKOUT``, e.g. a worktree of the commit before a change), in the same turn.

Commands (:data:`COMMANDS`): ``synth drive`` of the example drive; ``synth design`` of thesis case 3 with that
drive (``--drive``); ``synth design`` and ``synth robust`` of the embedded default application; ``synth bulk`` of a
generated portfolio of ``--n-bulk`` applications (default 10,000) with and without the diagnosis; ``synth
rationalise`` of ``--n-rationalise`` (default 1,000); and the web application's cold start: from spawning ``python
-m synth ui`` to its design page served (``GET /`` answered: the default application synthesised and its checks
built on the server; no browser, ``benchmarks/bench_ui.py`` has the browser's share). One warm-up first (a small
``synth bulk``: the compiled kernels and synth's cache are then on disk, as after a first run).

Target (issue 36): every loaded figure within 2.5x of its quiet figure.
"""

from __future__ import annotations

import argparse
import os
import statistics
import subprocess
import sys
import tempfile
import time
import urllib.request
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from synth.ui.browser import stop_server  # noqa: E402
DRIVE = ROOT / "synth" / "data" / "drives" / "example_timing_drive.yaml"
DEFAULT = ROOT / "synth" / "data" / "default_case.yaml"
CASE3 = ROOT / "synth" / "data" / "cases" / "case3.yaml"
BUSY = [sys.executable, "-c", "while 1: pass"]
#: the commands' working folder: ``python -m`` puts it first on the path, so it must hold no synth (PYTHONPATH
#: then says which tree runs)
NEUTRAL = tempfile.gettempdir()

#: name -> the command's arguments after ``python -m synth`` ({bulk}, {rat}, {out}: the run's files)
COMMANDS = {
    "drive": ["drive", str(DRIVE)],
    "design --drive": ["design", str(CASE3), "--drive", str(DRIVE)],
    "design": ["design", str(DEFAULT)],
    "robust": ["robust", str(DEFAULT)],
    "bulk (diagnosis)": ["bulk", "{bulk}", "--out", "{out}/bulk.parquet"],
    "bulk --no-diagnose": ["bulk", "{bulk}", "--out", "{out}/bulk.parquet", "--no-diagnose"],
    "rationalise": ["rationalise", "{rat}", "--out", "{out}/platform"],
    "web cold start": None,  # web_cold_start
}


def _env(tree: Path) -> dict:
    env = {**os.environ, "PYTHONPATH": str(tree) + os.pathsep + os.environ.get("PYTHONPATH", "")}
    env.pop("PYTHONDONTWRITEBYTECODE", None)
    return env


def _proc_cpu_s(pid: int) -> float:
    """User + system CPU seconds of a running process and its reaped children (Linux ``/proc``)."""
    try:
        f = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()
        return sum(int(x) for x in f[11:15]) / os.sysconf("SC_CLK_TCK")
    except (OSError, IndexError, ValueError):
        return float("nan")


def run_command(args: list[str], env: dict) -> tuple[float, float, int]:
    """(wall s, CPU s, exit code) of ``python -m synth ARGS`` as a whole process."""
    t = time.perf_counter()
    proc = subprocess.Popen([sys.executable, "-m", "synth", *args], env=env, cwd=NEUTRAL, stdout=subprocess.DEVNULL,
                            stderr=subprocess.DEVNULL)
    _, status, ru = os.wait4(proc.pid, 0)
    wall = time.perf_counter() - t
    proc.returncode = os.waitstatus_to_exitcode(status)
    return wall, ru.ru_utime + ru.ru_stime, proc.returncode


def web_cold_start(env: dict, timeout_s: float = 300.0) -> tuple[float, float, int]:
    """(wall s, server CPU s, 0 or 1) from spawning ``python -m synth ui --port P`` to ``GET /`` answered."""
    import socket
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        port = s.getsockname()[1]
    t = time.perf_counter()
    proc = subprocess.Popen([sys.executable, "-m", "synth", "ui", "--port", str(port)], env=env, cwd=NEUTRAL,
                            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    ok = 1
    try:
        while True:
            try:
                with urllib.request.urlopen(f"http://127.0.0.1:{port}/", timeout=timeout_s) as r:
                    r.read()
                    ok = 0 if r.status == 200 else 1
                break
            except OSError:
                if proc.poll() is not None or time.perf_counter() - t > timeout_s:
                    break
                time.sleep(0.05)
        wall, cpu = time.perf_counter() - t, _proc_cpu_s(proc.pid)
    finally:
        stop_server(proc)
    return wall, cpu, ok


class Busy:
    """``n`` busy processes for the span of a ``with`` block (started before, killed and reaped after), in a session
    of their own (``same_session=False``: as another program, under Linux's autogroup a scheduling group of their
    own) or in the benchmark's (sharing the command's group)."""

    def __init__(self, n: int, same_session: bool = False):
        self.n, self.same, self.procs = n, same_session, []

    def __enter__(self):
        self.procs = [subprocess.Popen(BUSY, start_new_session=not self.same) for _ in range(self.n)]
        time.sleep(0.2)  # running before the command starts
        return self

    def __exit__(self, *exc):
        for p in self.procs:
            p.kill()
        for p in self.procs:
            p.wait()


def measure(name: str, env: dict, files: dict) -> tuple[float, float, int]:
    args = COMMANDS[name]
    if args is None:
        return web_cold_start(env)
    out = tempfile.mkdtemp(dir=files["out"])  # a new output folder each run
    return run_command([a.format(**{**files, "out": out}) for a in args], env)


def _load() -> str:
    try:
        return " / ".join(f"{x:.1f}" for x in os.getloadavg())
    except OSError:  # pragma: no cover
        return "?"


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--busy", type=int, default=2, help="competing busy processes (default 2)")
    ap.add_argument("--runs", type=int, default=1, help="quiet/loaded pairs per command (default 1)")
    ap.add_argument("--only", nargs="*", default=None, choices=list(COMMANDS), metavar="NAME",
                    help=f"commands to run (default all): {', '.join(COMMANDS)}")
    ap.add_argument("--n-bulk", type=int, default=10000)
    ap.add_argument("--n-rationalise", type=int, default=1000)
    ap.add_argument("--base", type=Path, default=None, help="a second checkout measured in the same turns")
    ap.add_argument("--same-session", action="store_true",
                    help="start the busy processes in the benchmark's session (one scheduling group with the command)")
    a = ap.parse_args(argv)
    trees = {"this tree": ROOT} | ({f"base {a.base.name}": a.base.resolve()} if a.base else {})
    names = a.only or list(COMMANDS)
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        files = {"bulk": f"{tmp}/bulk_{a.n_bulk}.parquet", "rat": f"{tmp}/rat_{a.n_rationalise}.parquet", "out": tmp}
        env0 = _env(ROOT)
        for key, n in (("bulk", a.n_bulk), ("rat", a.n_rationalise)):
            subprocess.run([sys.executable, "-m", "synth", "portfolio-sample", str(n), "--out", files[key]], env=env0,
                           stdout=subprocess.DEVNULL, check=True)
        subprocess.run([sys.executable, "-m", "synth", "portfolio-sample", "100", "--out", f"{tmp}/warm.parquet"],
                       env=env0, stdout=subprocess.DEVNULL, check=True)
        for tree in trees.values():  # warm-up: compiled kernels, synth's cache, byte-code
            run_command(["bulk", f"{tmp}/warm.parquet", "--out", f"{tempfile.mkdtemp(dir=tmp)}/w.parquet"], _env(tree))
        print(f"bulk: {a.n_bulk:,} applications, rationalise: {a.n_rationalise:,}; {a.busy} busy processes; "
              f"{a.runs} pair(s) per command; load average before: {_load()}", flush=True)
        for name in names:
            for label, tree in trees.items():
                env = _env(tree)
                quiet, loaded = [], []
                for _ in range(a.runs):
                    quiet.append(measure(name, env, files))
                    with Busy(a.busy, a.same_session):
                        loaded.append(measure(name, env, files))
                ratio = statistics.median(lo[0] / q[0] for q, lo in zip(quiet, loaded))
                cpu_ratio = statistics.median(lo[1] / q[1] for q, lo in zip(quiet, loaded))
                row = (name, label, statistics.median(q[0] for q in quiet), statistics.median(q[1] for q in quiet),
                       statistics.median(lo[0] for lo in loaded), statistics.median(lo[1] for lo in loaded), ratio,
                       cpu_ratio, sorted({q[2] for q in quiet + loaded}))
                rows.append(row)
                print(f"  {name} ({label}): quiet {row[2]:.1f} s, loaded {row[4]:.1f} s, {ratio:.2f}x "
                      f"(load {_load()})", file=sys.stderr, flush=True)
    print(f"load average after: {_load()}")
    print()
    print("| command | tree | quiet wall [s] | quiet CPU [s] | loaded wall [s] | loaded CPU [s] | loaded / quiet "
          "(wall) | loaded / quiet (CPU) | exit |")
    print("|---|---|---|---|---|---|---|---|---|")
    for name, label, qw, qc, lw, lc, ratio, cpu_ratio, codes in rows:
        print(f"| {name} | {label} | {qw:.1f} | {qc:.1f} | {lw:.1f} | {lc:.1f} | {ratio:.2f} | {cpu_ratio:.2f} | "
              f"{', '.join(map(str, codes))} |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
