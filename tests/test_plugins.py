"""An installed plug-in's declarations judge in every process (issue 33): the command line, ``--version``, a worker
that receives the configuration, and a broken plug-in is an error that names it.

The fixture installs a toy distribution on a folder put on ``PYTHONPATH`` (its ``*.dist-info`` with an entry point
of group ``synth.plugins`` and the module it names). The module registers one bolt check, ``acme_bolt``: ``value =
|tilting safety factor| + 1`` against ``limit = 2 (|tilting safety factor| + 1)``, a margin of exactly 0.5 (``(limit -
value) / |limit|``) wherever the bolt group runs; and one objective, ``acme_support``, that prefers the longest pivot
bushing (no built-in objective does). Each test runs a fresh interpreter: the plug-in must arrive by
its entry point, not by this process's imports.
"""

from __future__ import annotations

import json
import os
import pickle
import subprocess
import sys
import textwrap

import pytest

from synth.data import CASES_DIR, case_path

DEFAULT = CASES_DIR.parent / "default_case.yaml"

CHECK = '''
import numpy as np
from synth.design.constraints import Constraint, register


def physics(*, tilting_safety_factor):
    a = np.abs(np.asarray(tilting_safety_factor, dtype=float)) + 1.0
    return {"acme_value": a, "acme_limit": 2.0 * a}


register(Constraint(id="acme_bolt", label="ACME's own bolt check", step=0, equation="ACME spec 7.1", unit="-",
                    group="bolt", value="acme_value", limit="acme_limit", sense="<=", physics=physics))


def _zero(sp, cores, core_values):
    return np.zeros(len(np.atleast_1d(cores)))


def _support(sp, table, options, stiffness_nm_per_deg):
    idx = slice(None) if options is None else options
    if table == "bushing":
        return -np.asarray(sp.tables[table]["pivot_bushing_length_mm"], float)[idx]
    return np.zeros(sp.n(table))[idx]


from synth.optimise import objectives  # noqa: E402

objectives.declare(objectives.Goal(name="acme_support", words="bushing support", unit="-mm", sense=+1, additive=True,
                                   tiebreak=("acme_support", "cost"), scores="minus the pivot bushing's length",
                                   core=_zero, option=_support))
'''


def _install(root, module: str, body: str) -> dict:
    """A distribution ``acme-checks 1.0`` on ``root`` whose entry point ``acme`` names ``module``; the environment
    of a process that has it installed."""
    (root / f"{module}.py").write_text(textwrap.dedent(body), encoding="utf-8")
    info = root / "acme_checks-1.0.dist-info"
    info.mkdir()
    (info / "METADATA").write_text("Metadata-Version: 2.1\nName: acme-checks\nVersion: 1.0\n", encoding="utf-8")
    (info / "entry_points.txt").write_text(f"[synth.plugins]\nacme = {module}\n", encoding="utf-8")
    path = os.pathsep.join(p for p in (str(root), os.environ.get("PYTHONPATH", "")) if p)
    return {**os.environ, "PYTHONPATH": path, "SYNTH_PROGRESS": "0"}


def _synth(env, *argv, **kw):
    return subprocess.run([sys.executable, "-m", "synth", *argv], env=env, capture_output=True, text=True,
                          timeout=300, **kw)


@pytest.fixture
def installed(tmp_path):
    return _install(tmp_path, "acme_checks", CHECK)


def test_an_installed_plugins_check_judges_synth_design_and_version_names_it(installed):
    r = _synth(installed, "design", str(DEFAULT), "--json")
    assert r.returncode in (0, 1), r.stderr
    margins = {c["id"]: c["margin"] for c in json.loads(r.stdout)["checks"]}
    assert margins["acme_bolt"] == 0.5
    longest = _synth(installed, "design", str(DEFAULT), "--objective", "acme_support", "--json")
    assert longest.returncode in (0, 1), longest.stderr  # the plug-in's objective is a choice of --objective
    length = {k: json.loads(out.stdout)["parts"]["pivot_bushing_length_mm"] for k, out in (("standard", r),
                                                                                          ("support", longest))}
    assert length["support"] > length["standard"], length
    v = _synth(installed, "--version")
    assert v.returncode == 0 and "; plug-ins: acme = acme_checks (acme-checks 1.0)" in v.stdout


def test_a_worker_that_receives_the_configuration_judges_with_the_plugin(installed):
    """A Dask task or a process pool's worker gets the run's Settings pickled with its chunk: unpickling them
    declares the plug-ins there before the chunk is judged."""
    from synth.design.settings import Settings
    worker = textwrap.dedent("""
        import pickle, sys
        from synth.design.constraints import REGISTRY
        before = "acme_bolt" in REGISTRY
        settings = pickle.loads(sys.stdin.buffer.read())
        from synth.bulk.execution import compute_chunk
        from synth.data import case_path
        from synth.io.documents import load_input
        import dataclasses
        rec = {k: v for k, v in dataclasses.asdict(load_input(case_path("case3"))).items() if v is not None}
        row = compute_chunk([rec], diagnose=False, settings=settings).iloc[0]
        print(before, "acme_bolt" in REGISTRY, row["margin_acme_bolt"])
    """)
    r = subprocess.run([sys.executable, "-c", worker], input=pickle.dumps(Settings(fidelity="screening")),
                       env=installed, capture_output=True, timeout=300)
    assert r.returncode == 0, r.stderr.decode()
    assert r.stdout.decode().split() == ["False", "True", "0.5"]


def test_a_plugin_that_does_not_import_is_an_input_error_naming_it(tmp_path):
    env = _install(tmp_path, "acme_broken", "raise ImportError('acme_tools 2 is required')\n")
    r = _synth(env, "design", str(case_path("case3")))
    assert r.returncode == 2
    assert r.stderr.splitlines() == [
        "synth: invalid input",
        "  - plug-in acme (entry point 'acme_broken' of group synth.plugins): got 'ImportError: acme_tools 2 is "
        "required'; accepted: a module that imports without error (fix or uninstall the package that declares it)"]
    v = _synth(env, "--version")
    assert v.returncode == 0 and "plug-ins: not loaded: plug-in acme" in v.stdout
