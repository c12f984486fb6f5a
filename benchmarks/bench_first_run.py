"""The first run of a fresh install against the second (issue 36): whole commands with an empty cache, then again.

Run: ``.venv/bin/python benchmarks/bench_first_run.py [--n 1000] [--pairs 1] [--tree PATH ...]`` (prints markdown
tables).

The commands: ``synth design`` and ``synth robust`` of the embedded default application
(``synth/data/default_case.yaml``), and ``synth bulk`` of the README's sample (``synth portfolio-sample N --broken
10``, ``--summary``). Each pair starts from an empty cache folder (``SYNTH_CACHE_DIR`` a new temporary folder per
command, tree and pair; ``NUMBA_CACHE_DIR`` unset, so the kernels go to ``numba-VERSION-DIGEST`` inside it): the first run
builds synth's cached design space, parts and constants and compiles the numba kernels it calls
(:mod:`synth.kernels.numba_setup`); the second loads both. Whole processes, wall and CPU seconds (``os.wait4``); the
ratio first/second is taken pair by pair. The table also says whether the first run printed the compile notice and
the second did not, and how many compiled kernels (``.nbc`` entries: one per function and signature) the cache
holds. Each ``--tree`` (a checkout of synth; default this one) runs every command in turn, the trees interleaved, so
that a before/after comparison shares the machine's load. A last table gives the cold start: ``import synth`` and
``synth --help`` (median of 5 processes).

``--compile-profile``: instead, one ``synth bulk`` of the sample in a process of its own with an empty cache, and
per kernel the CPU seconds of its compile (numba's ``numba:compile`` events, the outermost ones: a kernel's time
includes the helpers it compiles; one row per signature).

Target (issue 36): the first run within 1.3x of the second.
"""

from __future__ import annotations

import argparse
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
NOTICE = "compiling synth's kernels"


def run(args: list, env: dict) -> tuple[float, float, int, str]:
    """(wall s, CPU s, exit code, stderr) of ``python -m synth ARGS``."""
    t = time.perf_counter()
    proc = subprocess.Popen([sys.executable, "-m", "synth", *args], env=env, stdout=subprocess.DEVNULL,
                            stderr=subprocess.PIPE, text=True)
    err = proc.stderr.read()
    _, status, ru = os.wait4(proc.pid, 0)
    proc.returncode = os.waitstatus_to_exitcode(status)
    proc.stderr.close()
    return time.perf_counter() - t, ru.ru_utime + ru.ru_stime, proc.returncode, err


HEADER = ("Whole commands, each pair from an empty cache; bulk: the README's sample (10 rows broken, --summary)\n\n"
          "| command | tree | pair | first wall [s] | first CPU [s] | second wall [s] | second CPU [s] | "
          "first / second (wall) | first / second (CPU) | compile notice first / second | kernels cached | exit | "
          "load |\n|---|---|---|---|---|---|---|---|---|---|---|---|---|")


def row(name, tree, k, f, s, kernels) -> str:
    """A row of the table (without the load column)."""
    notice = f"{'yes' if NOTICE in f[3] else 'no'} / {'yes' if NOTICE in s[3] else 'no'}"
    return (f"| {name} | {tree.name} | {k} | {f[0]:.1f} | {f[1]:.1f} | {s[0]:.1f} | {s[1]:.1f} | {f[0] / s[0]:.2f} | "
            f"{f[1] / s[1]:.2f} | {notice} | {kernels} | {f[2]}, {s[2]} |")


def cold(code: list, env: dict, k: int = 5) -> float:
    """Median wall seconds of ``k`` processes ``python CODE``."""
    out = []
    for _ in range(k):
        t = time.perf_counter()
        subprocess.run([sys.executable, *code], env=env, stdout=subprocess.DEVNULL, check=True)
        out.append(time.perf_counter() - t)
    return statistics.median(out)


PROFILE = """
import sys, time
from synth.kernels import numba_setup
from numba.core import event
spans, stack = [], []
class Timer(event.Listener):
    def on_start(self, ev):
        stack.append(time.process_time())
    def on_end(self, ev):
        d = ev.data["dispatcher"].py_func
        spans.append((stack.pop(), time.process_time(), d.__module__.rsplit(".", 1)[-1] + "." + d.__name__))
event.register("numba:compile", Timer())
from synth.cli import main
try:
    main(sys.argv[1:])
except SystemExit:
    pass
for a, b, name in spans:  # the outermost compiles: those inside no other
    if not any(a2 <= a and b <= b2 and (a2, b2) != (a, b) for a2, b2, _ in spans):
        print(f"{name}\t{b - a:.2f}", file=sys.stderr)
"""


def compile_profile(tree: Path, portfolio: Path, tmp: Path, env: dict) -> None:
    """Print the table of ``--compile-profile``."""
    e = {**env, "PYTHONPATH": str(tree), "SYNTH_CACHE_DIR": str(tmp / f"cache-profile-{tree.name}")}
    proc = subprocess.run([sys.executable, "-c", PROFILE, "bulk", str(portfolio), "--out", str(tmp / "profile.csv")],
                          env=e, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    rows = [ln.split("\t") for ln in proc.stderr.splitlines() if "\t" in ln]
    print(f"\nCompile CPU per kernel signature, `synth bulk` of the sample, empty cache ({tree.name}, load "
          f"{os.getloadavg()[0]:.1f})\n\n| kernel | compile CPU [s] |\n|---|---|")
    for name, dt in rows:
        print(f"| {name} | {dt} |")
    print(f"| **total ({len(rows)} compiles)** | **{sum(float(dt) for _, dt in rows):.2f}** |")


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--n", type=int, default=1000, help="applications of the bulk portfolio (default 1000, README's)")
    ap.add_argument("--pairs", type=int, default=1, help="first/second pairs, each from an empty cache (default 1)")
    ap.add_argument("--tree", action="append", type=Path, help="a checkout of synth (repeat to compare; default this)")
    ap.add_argument("--compile-profile", action="store_true", help="per kernel, its compile CPU seconds (bulk)")
    ap.add_argument("--only", nargs="+", choices=("design", "bulk", "robust"), default=("design", "bulk", "robust"))
    a = ap.parse_args(argv)
    trees = [t.resolve() for t in a.tree or [ROOT]]
    base = {**os.environ}
    for var in ("NUMBA_CACHE_DIR", "PYTHONDONTWRITEBYTECODE", "XDG_CACHE_HOME"):
        base.pop(var, None)

    def env_of(tree: Path, cache) -> dict:
        return {**base, "PYTHONPATH": str(tree), "SYNTH_CACHE_DIR": str(cache)}

    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(tmp)
        portfolio = tmp / "portfolio.parquet"
        subprocess.run([sys.executable, "-m", "synth", "portfolio-sample", str(a.n), "--out", str(portfolio),
                        "--broken", "10"], env=env_of(trees[0], "off"), stdout=subprocess.DEVNULL, check=True)
        if a.compile_profile:
            for tree in trees:
                compile_profile(tree, portfolio, tmp, base)
            return 0
        default = ROOT / "synth" / "data" / "default_case.yaml"
        commands = {"design": ["design", str(default)],
                    "bulk": ["bulk", str(portfolio), "--out", "{out}.csv", "--summary", "{out}-summary"],
                    "robust": ["robust", str(default)]}
        for k in range(a.pairs):
            for name in a.only:
                for i, tree in enumerate(trees):
                    cache = tmp / f"cache-{name}-{i}-{k}"
                    assert not cache.exists()  # an empty cache per command, tree and pair
                    e = env_of(tree, cache)
                    args = [x.format(out=tmp / f"{name}-{i}-{k}") for x in commands[name]]
                    first = run(args, e)
                    second = run([x.replace(str(tmp / f"{name}-{i}-{k}"), str(tmp / f"{name}-{i}-{k}b"))
                                  for x in args], e)
                    kernels = len(list(cache.glob("numba-*/**/*.nbc")))
                    if not rows:
                        print(HEADER, flush=True)
                    rows.append((name, tree, k + 1, first, second, kernels))
                    print(row(*rows[-1]) + f" {os.getloadavg()[0]:.1f} |", flush=True)
        starts = {tree: (cold(["-c", "import synth"], env_of(tree, tmp / "cold")),
                         cold(["-m", "synth", "--help"], env_of(tree, tmp / "cold"))) for tree in trees}
    print("\n| tree | import synth [s] | synth --help [s] |\n|---|---|---|")
    for tree, (imp, hlp) in starts.items():
        print(f"| {tree.name} | {imp:.2f} | {hlp:.2f} |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
