"""Data shipped with synth: the embedded default case, the thesis case studies, generated applications.

``cases/`` holds thesis case studies 1 (as printed and as run) and 3 and the
shrink-fit paper's case, transcribed from the sources (see ``cases/README.md``
and ``cases/NOTES.md``); a case file is a valid design input.

>>> case_path("case3").name
'case3.yaml'
"""

from __future__ import annotations

from pathlib import Path

__all__ = ["CASES_DIR", "case_path"]

CASES_DIR = Path(__file__).resolve().parent / "cases"


def case_path(name: str) -> Path:
    """The file of the shipped case ``name`` (``case1``, ``case1_as_run``, ``case3``, ``shrink_fit_kia_ceed``)."""
    path = CASES_DIR / f"{name}.yaml"
    if not path.is_file():
        from synth.errors import InputError, Problem
        names = sorted(p.stem for p in CASES_DIR.glob("*.yaml"))
        raise InputError(Problem("case", name, "one of " + ", ".join(names)))
    return path
