"""The command line: scene table, fast start, version, "did you mean", per-scene usage, exit codes."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

import synth
from synth import fingerprint
from synth.cli import EX_SOFTWARE, JSON_HELP, SCENES, main, scene_parser

ROOT = Path(synth.__file__).resolve().parents[1]
HEAVY = ("pandas", "scipy", "matplotlib", "cadquery", "pyomo", "dask", "numba", "openpyxl")


def _run(*args: str, env: dict | None = None) -> subprocess.CompletedProcess:
    e = {**os.environ, "PYTHONPATH": str(ROOT) + os.pathsep + os.environ.get("PYTHONPATH", ""), **(env or {})}
    return subprocess.run([sys.executable, *args], capture_output=True, text=True, env=e, timeout=120)


def test_python_m_synth_version():
    r = _run("-m", "synth", "--version")
    assert r.returncode == 0, r.stderr
    first = r.stdout.split()
    assert first[:2] == ["synth", synth.__version__]
    assert "catalogs sha256" in r.stdout


def test_version_matches_pyproject():
    text = (ROOT / "pyproject.toml").read_text() if (ROOT / "pyproject.toml").is_file() else None
    if text is None:
        pytest.skip("installed without pyproject.toml")
    assert f'version = "{synth.__version__}"' in text


def test_catalog_hash_follows_user_catalogs(tmp_path):
    base = fingerprint.version_text()
    (tmp_path / "ball_bearings.csv").write_text("ball_bearing,source\nX,mine\n")
    assert fingerprint.version_text([tmp_path]) != base
    assert str(tmp_path) in fingerprint.version_text([tmp_path])
    assert fingerprint.version_text() == base


def test_help_imports_no_heavy_library():
    code = ("import sys\nfrom synth.cli import main\ntry:\n    main(['--help'])\nexcept SystemExit:\n    pass\n"
            f"print([m for m in {HEAVY!r} if m in sys.modules])")
    r = _run("-c", code)
    assert r.returncode == 0, r.stderr
    assert r.stdout.strip().splitlines()[-1] == "[]"
    assert "shrink-fit-select" in r.stdout and "exit codes" in r.stdout


@pytest.mark.parametrize("name", list(SCENES))
def test_every_table_entry_registers_its_own_scene(name):
    p = scene_parser(name)
    assert p.prog == f"synth {name}"
    assert p.description == SCENES[name].help  # one help line, the same in the table and in the scene


@pytest.mark.parametrize("name", list(SCENES))
def test_every_json_flag_has_help(name):
    for action in scene_parser(name)._actions:
        if "--json" in action.option_strings:
            assert action.help and action.help.strip()


@pytest.mark.parametrize("name", list(SCENES))
def test_every_option_says_what_it_does(name):
    """``synth NAME --help`` describes every argument and option (issue 35: ``rationalise --help`` had three
    options without a description)."""
    import argparse
    bare = [a.option_strings or [a.dest] for a in scene_parser(name)._actions
            if a.help != argparse.SUPPRESS and len((a.help or "").split()) < 3]
    assert not bare, bare


def test_json_help_default_only_where_the_scene_gives_none():
    flags = {n: next((a.help for a in scene_parser(n)._actions if "--json" in a.option_strings), None) for n in SCENES}
    # the scenes that return a Result say their exit code does not change with --json; compare keeps the default
    assert flags["compare"] == JSON_HELP
    assert flags["design"] == flags["flowchart"] == "print the result as one JSON object (exit code as without)"


def test_misspelt_scene_did_you_mean(capsys):
    assert main(["flowchat", "x.yaml"]) == 2
    err = capsys.readouterr().err
    assert "did you mean 'flowchart'?" in err
    assert main(["nonsense"]) == 2
    assert "unknown command 'nonsense'" in capsys.readouterr().err


def test_bad_flag_prints_the_scene_usage(capsys):
    with pytest.raises(SystemExit) as e:
        main(["flowchart", "case.yaml", "--bogus"])
    assert e.value.code == 2
    err = capsys.readouterr().err
    assert err.startswith("usage: synth flowchart")
    assert "unrecognized arguments: --bogus" in err


def test_top_level_options_before_the_scene(tmp_path, capsys):
    with pytest.raises(SystemExit) as e:
        main(["--catalogs"])
    assert e.value.code == 2
    assert main([]) == 2
    assert "commands" in capsys.readouterr().out


def test_internal_error_is_one_line_exit_70(monkeypatch, capsys):
    from synth.scenes import template

    def boom(args):
        raise ZeroDivisionError("division by zero\nsecond line")

    monkeypatch.setattr(template, "_main", boom)
    monkeypatch.delenv("SYNTH_DEBUG", raising=False)
    assert main(["template", "x.xlsx"]) == EX_SOFTWARE
    err = capsys.readouterr().err
    assert err == ("synth: internal error in template: ZeroDivisionError: division by zero second line; "
                   "please report (SYNTH_DEBUG=1 shows the traceback)\n")
    monkeypatch.setenv("SYNTH_DEBUG", "1")
    with pytest.raises(ZeroDivisionError):
        main(["template", "x.xlsx"])


def test_input_error_keeps_exit_2_in_a_subprocess(tmp_path):
    bad = tmp_path / "bad.yaml"
    bad.write_text("inputs: [1, 2\n")
    r = _run("-m", "synth", "flowchart", str(bad))
    assert r.returncode == 2
    assert "Traceback" not in r.stderr and "invalid input" in r.stderr
