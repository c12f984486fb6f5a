"""``synth rationalise`` as a whole command, this tree against another, at 1,000 and 10,000 applications (issue 36).

Run: ``.venv/bin/python benchmarks/bench_rationalise.py [--sizes 1000 10000] [--base CHECKOUT] [--seed 0]
[--repeat R] [--volumes] [--args ...]`` (prints markdown tables). ``--repeat R``: R turns (base, then this tree,
each turn), the ratios taken turn by turn and their median printed; ``--volumes``: the portfolio gets an
``annual_volume`` column (lognormal, median 3,000 pieces a year, seeded: :func:`add_volumes`), so the platform
prices each part at its pooled volume (:mod:`synth.platform.volume`). The portfolio of each size is ``synth portfolio-sample N --seed S`` (written
once, read by both trees). Each tree runs ``python -m synth rationalise PORTFOLIO --out DIR`` as a fresh process
(``PYTHONPATH=TREE``; ``--base CHECKOUT``, e.g. a worktree of main, runs first in the same turn, then this tree): wall
seconds, the process's CPU seconds and its peak resident memory (``os.wait4``), and the seconds of each stage, read
from the progress lines the command draws with ``SYNTH_PROGRESS=1`` (feasibility, the platform's stages of
:data:`synth.platform.rationalise.STAGES`, the trade-off curve, the outputs; a base without those lines shows what
it draws). One warm-up run of each tree first (20 applications: its compiled kernels on disk, as after a first run).
Then whether the two trees wrote the same files (byte for byte, the figures' PNG included; for a text file that
differs, the lines: the timings ``summary.md`` and ``section.html`` print differ from run to run).

``--memory-stages PORTFOLIO``: instead, one process runs the command's steps on PORTFOLIO and prints each stage's
CPU seconds, wall seconds, resident memory after it and peak within it (Linux: the peak reset through
``/proc/self/clear_refs`` as each stage starts), where the memory goes (:func:`memory_stages`).

The machine is shared: the load average is printed with each table; compare the trees by their ratios in one run.
Targets (issue 36): 10,000 applications < 60 s and < 2 GB; 1,000 < 15 s.
"""

from __future__ import annotations

import argparse
import filecmp
import os
import re
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
#: the commands' working folder: ``python -m`` puts it first on the path, so it must hold no synth
NEUTRAL = tempfile.gettempdir()
_LINE = re.compile(r"^synth rationalise: (?P<stage>.+?): .*?(?P<s>\d+\.\d) s(?:\s+(?:done|running))?$")


def _env(tree: Path) -> dict:
    env = {**os.environ, "PYTHONPATH": str(tree), "SYNTH_PROGRESS": "1"}
    env.pop("PYTHONDONTWRITEBYTECODE", None)
    return env


def stage_seconds(stderr: str) -> dict:
    """``{stage: seconds}`` from the progress lines of a run (the last figure each stage drew).

    >>> stage_seconds("\\rsynth rationalise: platform, prune (9 applications):    1.0 s running"
    ...               "\\rsynth rationalise: platform, prune (9 applications):    2.5 s done  \\n")
    {'platform, prune': 2.5}
    """
    out: dict = {}
    for piece in stderr.replace("\r", "\n").splitlines():
        m = _LINE.match(piece.strip())
        if m:
            out[m["stage"].split(" (")[0]] = float(m["s"])
    return out


def run(tree: Path, args: list) -> dict:
    """Wall and CPU seconds, peak RSS [MiB], exit code and stage seconds of ``python -m synth ARGS`` under ``tree``."""
    with tempfile.TemporaryFile("w+") as err:
        t = time.perf_counter()
        proc = subprocess.Popen([sys.executable, "-m", "synth", *args], env=_env(tree), cwd=NEUTRAL,
                                stdout=subprocess.DEVNULL, stderr=err)
        _, status, ru = os.wait4(proc.pid, 0)
        wall = time.perf_counter() - t
        err.seek(0)
        text = err.read()
    return {"wall": wall, "cpu": ru.ru_utime + ru.ru_stime, "rss_mib": ru.ru_maxrss / 1024,
            "code": os.waitstatus_to_exitcode(status), "stages": stage_seconds(text), "stderr": text}


def same_files(a: Path, b: Path) -> str:
    """``identical`` or the files that differ (or are missing on one side)."""
    names = sorted({p.name for p in a.iterdir()} | {p.name for p in b.iterdir()}) if a.is_dir() and b.is_dir() else []
    if not names:
        return "no output to compare"
    bad = [n for n in names if not ((a / n).is_file() and (b / n).is_file() and filecmp.cmp(a / n, b / n, shallow=False))]
    if not bad:
        return "identical (" + ", ".join(names) + ")"
    same = [n for n in names if n not in bad]
    return "identical: " + ", ".join(same) + "; differ: " + ", ".join(f"{n} ({_lines_differing(a / n, b / n)})" for n in bad)


def _lines_differing(a: Path, b: Path) -> str:
    """The lines of two text files that differ, shortened (the timings summary.md and section.html print)."""
    try:
        x, y = a.read_text().splitlines(), b.read_text().splitlines()
    except (OSError, UnicodeDecodeError):
        return "binary"
    diff = [f"{u[:60]!r} -> {v[:60]!r}" for u, v in zip(x, y) if u != v]
    return (f"{len(diff)} lines: " + "; ".join(diff[:3]) if len(x) == len(y) else f"{len(x)} against {len(y)} lines")


def add_volumes(path: Path, seed: int) -> None:
    """Give the portfolio table ``path`` an ``annual_volume`` column: lognormal, median 3,000, sigma 1.3, rounded to
    10, within 10-500,000 pieces a year (an engine programme's tensioners, from niche to volume cars)."""
    import numpy as np
    import pandas as pd
    t = pd.read_parquet(path)
    rng = np.random.default_rng(seed)
    t["annual_volume"] = np.round(rng.lognormal(np.log(3000), 1.3, len(t)), -1).clip(10, 500_000).astype(int)
    t.to_parquet(path)


def memory_stages(portfolio: str) -> None:
    """Print per stage of ``synth rationalise PORTFOLIO`` (feasibility, :data:`synth.platform.rationalise.STAGES`,
    the margin trade-off curve, the outputs) its CPU and wall seconds, the resident memory after it and the peak
    within it [MiB], in this process (Linux only: ``/proc/self/status`` and ``clear_refs``)."""
    import resource
    from contextlib import contextmanager
    from synth.design.evaluate import Settings
    from synth.platform.outputs import write_all
    from synth.platform.portfolio_feasibility import load_feasibility
    from synth.platform.rationalise import rationalise, tradeoff

    def rss():
        d = dict(line.split(":", 1) for line in Path("/proc/self/status").read_text().splitlines() if ":" in line)
        return int(d["VmRSS"].split()[0]) / 1024, int(d["VmHWM"].split()[0]) / 1024

    def cpu():
        r = resource.getrusage(resource.RUSAGE_SELF)
        return r.ru_utime + r.ru_stime

    @contextmanager
    def stage(name):
        Path("/proc/self/clear_refs").write_text("5")   # the peak (VmHWM) from here
        c, t = cpu(), time.perf_counter()
        yield
        now, peak = rss()
        print(f"| {name} | {cpu() - c:.1f} | {time.perf_counter() - t:.1f} | {now:,.0f} | {peak:,.0f} |", flush=True)

    print(f"Stages of `synth rationalise` in one process (load average {os.getloadavg()[0]:.1f})\n\n"
          "| stage | CPU [s] | wall [s] | RSS after [MiB] | peak in stage [MiB] |\n|---|---|---|---|---|")
    with stage("feasibility"):
        pf = load_feasibility(portfolio, Settings())
    r = rationalise(pf, "variants", stage=stage)
    with stage("trade-off curve (margin)"):
        r.tradeoff = tradeoff(pf, "margin", points=5)
    with stage("outputs"), tempfile.TemporaryDirectory() as d:
        write_all(pf, r, d, r.tradeoff, "margin")


def main(argv: list | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--sizes", type=int, nargs="+", default=[1000, 10000])
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--base", type=Path, help="another checkout (e.g. a worktree of main) run in the same turn")
    ap.add_argument("--repeat", type=int, default=1, help="turns of base then this tree (median ratios)")
    ap.add_argument("--volumes", action="store_true", help="an annual_volume column in the portfolio")
    ap.add_argument("--memory-stages", metavar="PORTFOLIO",
                    help="instead: each stage's CPU, wall and peak memory on PORTFOLIO, in this process")
    ap.add_argument("--args", nargs=argparse.REMAINDER, default=[], help="more arguments for synth rationalise")
    a = ap.parse_args(argv)
    if a.memory_stages:
        memory_stages(a.memory_stages)
        return 0
    trees = ([("base", a.base.resolve())] if a.base else []) + [("this tree", ROOT)]
    with tempfile.TemporaryDirectory(prefix="bench_rationalise_") as tmp:
        rows, stages, checks = [], [], []
        for n in a.sizes:
            port = Path(tmp) / f"portfolio_{n}.parquet"
            subprocess.run([sys.executable, "-m", "synth", "portfolio-sample", str(n), "--seed", str(a.seed),
                            "--out", str(port)], env=_env(ROOT), cwd=NEUTRAL, check=True, stdout=subprocess.DEVNULL)
            if a.volumes:
                add_volumes(port, a.seed)
            res = {}
            turns = []
            if n == a.sizes[0]:   # each tree's compiled kernels loaded (or compiled) once before the timed runs
                warm = Path(tmp) / "warm_up.parquet"
                subprocess.run([sys.executable, "-m", "synth", "portfolio-sample", "20", "--out", str(warm)],
                               env=_env(ROOT), cwd=NEUTRAL, check=True, stdout=subprocess.DEVNULL)
                for _, tree in trees:
                    run(tree, ["rationalise", str(warm), "--out", str(Path(tmp) / "warm_up"), "--tradeoff", "none"])
            for turn in range(max(1, a.repeat)):
                for name, tree in trees:
                    out = Path(tmp) / f"out_{n}_{name.replace(' ', '_')}"
                    res[name] = r = run(tree, ["rationalise", str(port), "--out", str(out), *a.args])
                    if r["code"] != 0:
                        print(f"{name}, {n:,}: exit {r['code']}\n{r['stderr'][-2000:]}", file=sys.stderr)
                    ref = res[trees[0][0]]
                    rows.append(f"| {n:,} | {name} | {turn + 1} | {r['wall']:.1f} | {r['cpu']:.1f} "
                                f"| {r['rss_mib']:,.0f} | {r['wall'] / ref['wall']:.2f} | {r['cpu'] / ref['cpu']:.2f} "
                                f"| {r['rss_mib'] / ref['rss_mib']:.2f} | {r['code']} |")
                    for st, s in r["stages"].items():
                        stages.append(f"| {n:,} | {name} | {st} | {s:.1f} |")
                turns.append((res[trees[-1][0]]["wall"] / res[trees[0][0]]["wall"],
                              res[trees[-1][0]]["cpu"] / res[trees[0][0]]["cpu"]))
            if a.base:
                import statistics
                checks.append(f"* {n:,} applications, this tree / base over {len(turns)} turns: median wall "
                              f"{statistics.median(t[0] for t in turns):.3f}, median CPU "
                              f"{statistics.median(t[1] for t in turns):.3f}")
            if a.base:
                checks.append(f"* {n:,} applications, outputs of the base and this tree: "
                              + same_files(*(Path(tmp) / f"out_{n}_{k.replace(' ', '_')}" for k, _ in trees)))
        print(f"`synth rationalise` (portfolio-sample, seed {a.seed}; load average {os.getloadavg()[0]:.1f}, "
              f"{os.cpu_count()} cores)\n")
        print(f"`{' '.join(['rationalise', 'PORTFOLIO', '--out', 'DIR', *a.args])}`"
              + (", with an annual_volume column" if a.volumes else "") + "\n")
        print("| applications | tree | turn | wall [s] | CPU [s] | peak RSS [MiB] | wall / first | CPU / first "
              "| RSS / first | exit |\n|---|---|---|---|---|---|---|---|---|---|")
        print("\n".join(rows))
        print("\nStages (seconds the progress lines drew; wall):\n\n| applications | tree | stage | s |\n|---|---|---|---|")
        print("\n".join(stages))
        if checks:
            print("\n" + "\n".join(checks))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
