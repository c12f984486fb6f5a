"""The README's examples run as written, so a drift between the README and synth fails CI (issue 35).

Every ``sh`` block's ``synth ...`` lines run in a fresh folder (the README's paths ``synth/data/...`` reach the
repository's own through a link), with the optional ``[...]`` groups left out; a command must end with a verdict
(exit 0, 1 or 3), never an input error (2: an option the README names that synth no longer takes) or a traceback.
Where an output block follows, each of its lines must be printed, with its timings (``5.1 s``, ``197
applications/s``) masked. The Python block runs with the portfolio its ``synth.screen`` line reads.
The install lines (``python3 -m venv ...``) are what CI itself runs, and are not repeated here.
"""

from __future__ import annotations

import os
import re
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
README = (ROOT / "README.md").read_text(encoding="utf-8")


def _blocks() -> list[tuple[str, str]]:
    """The fenced blocks as (language, text), in order."""
    return [(m.group(1), m.group(2)) for m in re.finditer(r"^```(\w*)\n(.*?)^```", README, re.M | re.S)]


def _commands(text: str) -> list[str]:
    """The ``synth`` command lines of an sh block, continuations joined and ``[...]`` groups left out."""
    out = []
    for line in text.replace("\\\n", " ").splitlines():
        line = line.strip()
        if re.match(r"synth [a-z][a-z-]*( |$)", line):  # not an output line ("synth rationalise: 736 of ...")
            out.append(re.sub(r"\s*\[[^\]]*\]", "", line))
    return out


def _examples() -> list[tuple[list[str], str | None]]:
    """Each sh block with synth commands, with the plain output block that follows it (None: no output shown)."""
    blocks, out = _blocks(), []
    for i, (lang, text) in enumerate(blocks):
        cmds = _commands(text) if lang == "sh" else []
        if cmds:
            nxt = blocks[i + 1] if i + 1 < len(blocks) else None
            shown = nxt[1] if nxt and nxt[0] == "" and not _commands(nxt[1]) else None
            out.append((cmds, shown))
    return out


def _env() -> dict:
    return {**os.environ, "PYTHONPATH": str(ROOT) + os.pathsep + os.environ.get("PYTHONPATH", ""),
            "COLUMNS": "200"}


def _link_data(folder: Path) -> None:
    """The README's paths ``synth/data/...`` in ``folder``: a plain folder ``synth`` holding a link to the
    repository's data. Not a link to the whole package: run from ``folder`` (``python -m synth``, a script there),
    Python would import synth through the link, a new path each run, and numba would compile every kernel again
    into a new cache folder (its cache is per source path): 12 s of CPU per command on an idle machine, 30-40 s in
    the loaded suite. A folder without ``__init__.py`` is passed over for the repository's package (PYTHONPATH)."""
    (folder / "synth").mkdir()
    (folder / "synth" / "data").symlink_to(ROOT / "synth" / "data", target_is_directory=True)


def _mask(line: str) -> str:
    """A printed line with its timings masked (they change from run to run)."""
    line = re.sub(r"\d+(\.\d+)? s\b", "<t> s", line)
    return re.sub(r"\d+(\.\d+)? applications/s", "<n> applications/s", line).strip()


def test_the_readme_has_the_examples_this_test_runs():
    ex = _examples()
    assert len(ex) >= 3, ex
    assert any("rationalise" in c for cmds, _ in ex for c in cmds)
    assert sum(shown is not None for _, shown in ex) >= 2


@pytest.mark.parametrize("cmds,shown", _examples(), ids=lambda x: x[0].split()[1] if isinstance(x, list) else "")
def test_a_readme_example_runs_as_written(cmds, shown, tmp_path):
    _link_data(tmp_path)
    printed = []
    for cmd in cmds:
        argv = [sys.executable, "-m", "synth", *cmd.split()[1:]]
        r = subprocess.run(argv, cwd=tmp_path, env=_env(), capture_output=True, text=True, timeout=600)
        assert r.returncode in (0, 1, 3), f"{cmd}: exit {r.returncode}\n{r.stderr[-2000:]}"
        assert "Traceback" not in r.stderr and "internal error" not in r.stderr, r.stderr[-2000:]
        printed += [_mask(x) for x in (r.stdout + r.stderr).splitlines()]
    if shown is not None:
        missing = [x for x in (_mask(y) for y in shown.splitlines()) if x and x not in printed]
        assert not missing, "README lines not printed:\n" + "\n".join(missing) + "\n--- printed:\n" + "\n".join(printed)


def test_the_readme_python_example_runs(tmp_path):
    code = next(text for lang, text in _blocks() if lang == "python")
    _link_data(tmp_path)
    # the portfolio its synth.screen line reads, written in this process (the block runs in its own); 10
    # applications, not 50: the block's screening is one row per application whatever their number
    from synth.cli import main
    assert main(["portfolio-sample", "10", "--out", str(tmp_path / "portfolio.parquet")]) == 0
    script = tmp_path / "example.py"
    script.write_text(code + "\nprint('verdict', r.verdict, len(r5.alternatives), len(table))\n"
                      "print('package', synth.__file__)\n", encoding="utf-8")
    r = subprocess.run([sys.executable, str(script)], cwd=tmp_path, env=_env(), capture_output=True, text=True,
                       timeout=600)
    assert r.returncode == 0, r.stderr[-3000:]
    assert re.search(r"verdict \w+ 5 10", r.stdout), r.stdout[-2000:]
    assert f"package {ROOT / 'synth' / '__init__.py'}" in r.stdout  # the repository's (its numba cache), not a copy
    assert (tmp_path / "out" / "report.html").exists() and (tmp_path / "out" / "results.xlsx").exists()
