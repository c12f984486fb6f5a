"""Start-up time of the ``synth`` command against ``python -c "import numpy"`` (whole processes).

Run: ``.venv/bin/python benchmarks/bench_cli.py [--runs N]`` (default 7; prints a markdown table).
Each command runs as a fresh process, the reference A (``python -c "import numpy"``) and the
command B in turn, A B A B ..., after one warm-up of each; the table gives the median wall time
of each and the median of the pair-by-pair ratio B/A, so a drift of the machine's speed cancels.
The aims (issue 13): ``synth --help`` under 0.3 s; ``synth design`` within 0.5 s of the reference
(the column "difference": median of the pair-by-pair differences B - A). The processes may write
byte-code (``PYTHONDONTWRITEBYTECODE`` is removed), as pip's install of the wheel compiles it; the design
space, parts and constants come from synth's on-disk cache after the warm-up run (:mod:`synth.fingerprint`).
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
REFERENCE = [sys.executable, "-c", "import numpy"]
COMMANDS = {
    "synth --help": ["-m", "synth", "--help"],
    "synth --version": ["-m", "synth", "--version"],
    "synth flowchart --help (imports the scene)": ["-m", "synth", "flowchart", "--help"],
    "synth design (embedded default application, whole command)":
        ["-m", "synth", "design", str(ROOT / "synth" / "data" / "default_case.yaml")],
}


def _wall(cmd: list[str], env: dict) -> float:
    t = time.perf_counter()
    subprocess.run(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, env=env, check=False)
    return time.perf_counter() - t


def main(runs: int = 7) -> None:
    env = {**os.environ, "PYTHONPATH": str(ROOT) + os.pathsep + os.environ.get("PYTHONPATH", "")}
    env.pop("PYTHONDONTWRITEBYTECODE", None)  # byte-compiled modules, as an installed package has them
    print("| command | median wall [s] | reference `python -c \"import numpy\"` [s] | ratio to reference | "
          "difference [s] | runs |")
    print("|---|---|---|---|---|---|")
    for label, args in COMMANDS.items():
        cmd = [sys.executable, *args]
        _wall(REFERENCE, env), _wall(cmd, env)  # warm-up (file cache, .pyc)
        a, b = [], []
        for _ in range(runs):
            a.append(_wall(REFERENCE, env))
            b.append(_wall(cmd, env))
        ratio = statistics.median(y / x for x, y in zip(a, b))
        diff = statistics.median(y - x for x, y in zip(a, b))
        print(f"| {label} | {statistics.median(b):.3f} | {statistics.median(a):.3f} | {ratio:.2f} | {diff:.3f} | "
              f"{runs} |")


if __name__ == "__main__":
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--runs", type=int, default=7)
    main(ap.parse_args().runs)
