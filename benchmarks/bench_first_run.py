"""The first run of a fresh install against the second (issue 36): ``synth bulk`` with an empty cache, then again.

Run: ``.venv/bin/python benchmarks/bench_first_run.py [--n 2000] [--pairs 2]`` (prints a markdown table).

Each pair starts from an empty cache folder (``SYNTH_CACHE_DIR`` a new temporary folder, ``NUMBA_CACHE_DIR``
unset): the first ``synth bulk`` of a generated portfolio of ``--n`` applications builds synth's cached design
space, parts and constants and compiles the numba kernels into ``numba-VERSION`` there
(:mod:`synth.kernels.numba_setup`); the second loads both. Whole processes, wall and CPU seconds (``os.wait4``);
the ratio first/second is taken pair by pair. The table also says whether the first run printed the compile
notice and the second did not, and how many compiled kernels the cache holds.

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


def run_bulk(portfolio: Path, out: Path, env: dict) -> tuple[float, float, int, str]:
    """(wall s, CPU s, exit code, stderr) of ``python -m synth bulk PORTFOLIO --out OUT``."""
    t = time.perf_counter()
    proc = subprocess.Popen([sys.executable, "-m", "synth", "bulk", str(portfolio), "--out", str(out)], env=env,
                            stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    err = proc.stderr.read()
    _, status, ru = os.wait4(proc.pid, 0)
    proc.returncode = os.waitstatus_to_exitcode(status)
    proc.stderr.close()
    return time.perf_counter() - t, ru.ru_utime + ru.ru_stime, proc.returncode, err


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--n", type=int, default=2000, help="applications (default 2000)")
    ap.add_argument("--pairs", type=int, default=2, help="first/second pairs, each from an empty cache (default 2)")
    a = ap.parse_args(argv)
    env = {**os.environ, "PYTHONPATH": str(ROOT) + os.pathsep + os.environ.get("PYTHONPATH", "")}
    env.pop("NUMBA_CACHE_DIR", None)
    env.pop("PYTHONDONTWRITEBYTECODE", None)
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        portfolio = Path(tmp) / "p.parquet"
        subprocess.run([sys.executable, "-m", "synth", "portfolio-sample", str(a.n), "--out", str(portfolio)],
                       env={**env, "SYNTH_CACHE_DIR": "off"}, stdout=subprocess.DEVNULL, check=True)
        for k in range(a.pairs):
            cache = Path(tmp) / f"cache{k}"
            e = {**env, "SYNTH_CACHE_DIR": str(cache)}
            first = run_bulk(portfolio, Path(tmp) / f"first{k}.parquet", e)
            second = run_bulk(portfolio, Path(tmp) / f"second{k}.parquet", e)
            kernels = len(list(cache.glob("numba-*/**/*.nbi")))
            rows.append((k + 1, first, second, kernels))
            print(f"  pair {k + 1}: first {first[0]:.1f} s, second {second[0]:.1f} s (load "
                  f"{os.getloadavg()[0]:.1f})", file=sys.stderr, flush=True)
    print(f"synth bulk of {a.n:,} generated applications, each pair from an empty cache\n")
    print("| pair | first wall [s] | first CPU [s] | second wall [s] | second CPU [s] | first / second (wall) | "
          "first / second (CPU) | compile notice first / second | kernels cached | exit |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for k, f, s, kernels in rows:
        notice = f"{'yes' if NOTICE in f[3] else 'no'} / {'yes' if NOTICE in s[3] else 'no'}"
        print(f"| {k} | {f[0]:.1f} | {f[1]:.1f} | {s[0]:.1f} | {s[1]:.1f} | {f[0] / s[0]:.2f} | {f[1] / s[1]:.2f} | "
              f"{notice} | {kernels} | {f[2]}, {s[2]} |")
    if len(rows) > 1:
        print(f"| median | | | | | {statistics.median(f[0] / s[0] for _, f, s, _ in rows):.2f} | "
              f"{statistics.median(f[1] / s[1] for _, f, s, _ in rows):.2f} | | | |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
