"""Shared fixtures: the thesis case files shipped in synth/data/cases, their inputs and flowchart results."""

from functools import lru_cache

import pytest
import yaml

from synth.data import CASES_DIR as CASES


def load_case(name: str) -> dict:
    """The whole case file ``name`` (``inputs``, ``thesis_tool``, ``real_tensioner``)."""
    path = CASES / f"{name}.yaml"
    return yaml.safe_load(path.read_text())


def case_input(name: str, **changes):
    """The validated :class:`synth.schema.DesignInput` of case ``name``, with ``changes`` to its inputs."""
    from synth.io.documents import load_input
    from synth.schema import validate
    if not changes:
        return load_input(CASES / f"{name}.yaml")
    return validate({**load_case(name)["inputs"], **changes})


@lru_cache(maxsize=None)
def case_flowchart(name: str):
    """The flowchart :class:`synth.design.result.Result` of case ``name`` (default settings; do not mutate)."""
    from synth import flowchart
    return flowchart.run(case_input(name))


#: the plastic elements the thesis tool printed for case 1 (Table 10: class 2 of Tables 3-4 and a 30 mm cone spring);
#: the text's index gives class 3 for its 1.71 N m axial damping (docs/sections/flowchart_rules.md), so the flowchart's
#: own design differs: tests of eq. (50)-(53) and of steps 5 and 8 on Table 10's numbers verify the printed elements
CASE1_TOOL_AXIAL = {"damper_pad_class": "DP2", "endcap_spacer_class": "ES2", "cone_spring_external_diameter_mm": 30.0}


def tool_parts(name: str) -> dict:
    """Case ``name``'s flowchart design with the thesis tool's printed plastic elements (case 1; case 3 has none)."""
    parts = dict(case_flowchart(name).parts)
    return {**parts, **CASE1_TOOL_AXIAL} if name.startswith("case1") else parts


@lru_cache(maxsize=None)
def tool_design(name: str):
    """:func:`tool_parts` of case ``name`` verified (default settings; do not mutate)."""
    from synth.design.verify import verify
    return verify(case_input(name), tool_parts(name))


@pytest.fixture(params=["case1_as_run", "case3"])
def case(request):
    return load_case(request.param)


def shrink_fit_case(model="paper", initial_rz=4.8, **overrides):
    """The shrink-fit case of the paper (``shrink_fit_kia_ceed``) with its modelling choices (``model: paper``).

    ``initial_rz``: the initial journal roughness Rz [um] of the paper's sec. 3.3 (None: the measured one).
    """
    from synth.shrink_fit.inputs import case_from_dict

    data = load_case("shrink_fit_kia_ceed")
    inputs = dict(data["inputs"])
    inputs["roughness"] = dict(inputs["roughness"])
    if initial_rz is not None:
        inputs["roughness"]["journal_initial"] = {"Rz": initial_rz}
    inputs.update(overrides)
    return case_from_dict({"name": data["name"], "inputs": inputs, "model": model})


def shrink_fit_row(table, state, level):
    """The row of a shrink-fit result table for ``state`` (new/worn) and ``level`` (min/max interference)."""
    return next(r for r in table if r["state"] == state and r["interference"] == level)
# the corpus generator is a script, not a test module (it rewrites tests/bad_inputs/files when run)
collect_ignore = ["bad_inputs/make_corpus.py"]


# ---------------------------------------------------------------- numba's kernels compiled once per run, not per worker
# Under xdist every worker met an empty kernel cache (a fresh clone, CI) at about the same time and compiled the same
# kernels (measured: 2 workers on tests/test_kernels.py and test_axial_kernels.py, 37 s of CPU compiling of 62 s).
# The controller starts one process that compiles the bulk path's kernels into synth's cache while the workers
# collect; a worker waits for it before its first test, then loads them from the cache. numba's cache is keyed by
# source and signature, so a warm cache makes this a 3-5 s load.

_WARM_ENV = "SYNTH_TEST_KERNELS_WARMED"
_WARM = """
import sys
try:
    from synth.bulk.engine import screen_applications
    from synth.data.generated_applications import generate
    screen_applications(generate(12, seed=1, vary=True))
    screen_applications(generate(12, seed=2, vary=True), fidelity="full")
    import numpy as np
    from synth.design import evaluate
    from synth.design.applications import Applications
    from synth.design.space import core_rows, space
    from synth.kernels import main_spring
    sp, inputs = space(), generate(2, seed=3)
    per = [core_rows(sp, d) for d in inputs]
    a = np.concatenate([np.full(len(c), i) for i, c in enumerate(per)]).astype(np.int64)
    apps, settings = Applications.of(inputs), evaluate.Settings(fidelity="screening")
    with np.errstate(all="ignore"):
        cg = evaluate.core(apps, a, sp.rows("core", np.concatenate(per)), settings)
    keys = main_spring.keys_of_rows(apps, evaluate.spring_keys(cg, np.arange(len(a))), np.arange(4))
    opts = main_spring.options_of_space().take(np.arange(0, 11000, 500))
    for parallel in (False, True):
        main_spring.margins(keys, opts, parallel=parallel)
        for scan in (main_spring.first_feasible, main_spring.max_min_margin, main_spring.any_feasible):
            scan(keys, opts, [np.arange(len(opts))], key_group=np.zeros(len(keys), dtype=np.int64), parallel=parallel)
finally:
    open(sys.argv[1], "w").close()
"""


# ---------------------------------------------------------------------------- one BLAS thread, as every scene runs
# The command line runs every scene on one BLAS thread (synth.threads.scene); the API leaves the library's default
# (a thread per processor). Under xdist each worker's BLAS threads spun against the other worker's: measured on 2
# loaded cores, tests/test_capability_independent.py took 65 s of CPU and 147 s wall with two, 36 s and 83 s with
# one. The tests run the API under the command line's setting (a variable set by the user or CI is kept).

def _one_blas_thread():
    import os
    from threadpoolctl import threadpool_limits
    from synth.threads import THREAD_ENV
    for name in THREAD_ENV:  # the libraries not loaded yet, and child processes
        os.environ.setdefault(name, "1")
    if os.environ["OPENBLAS_NUM_THREADS"] == "1":  # and those a plugin loaded already, for the session
        threadpool_limits(1, user_api="blas")


# ------------------------------------------------------------------- work stealing: no worker idle while another queues
# xdist's default ``--dist load`` hands each worker a queue of tests up front and refills it in halves; on the suite's
# mix (2,900 tests, most of a few milliseconds, a few hundred of 5-90 s) one worker ended with a queue of heavy tests
# while the other sat idle: measured on a 2-core machine, worker 0 busy 1,024 s and worker 1 650 s of a 1,064 s run.
# ``worksteal`` lets an idle worker take half of the other's queue. Only where the user did not choose ``--dist``.

def _steal_work(config):
    args = config.invocation_params.args
    if config.getoption("numprocesses", None) and config.getoption("dist", "no") == "load" and \
            not any(str(a).startswith(("--dist", "-d")) for a in args):
        config.option.dist = "worksteal"


def pytest_configure(config):
    import os
    import subprocess
    import sys
    import tempfile
    _one_blas_thread()
    if not hasattr(config, "workerinput"):
        _steal_work(config)
    if hasattr(config, "workerinput") or not config.getoption("numprocesses", None) or os.environ.get(_WARM_ENV):
        return
    marker = os.path.join(tempfile.mkdtemp(prefix="synth-warm-"), "done")
    os.environ[_WARM_ENV] = marker  # inherited by the workers, started after this hook
    config._synth_warm = subprocess.Popen([sys.executable, "-c", _WARM, marker], stdout=subprocess.DEVNULL)


def pytest_collection_finish(session):
    import os
    import time
    marker = os.environ.get(_WARM_ENV)
    if not marker or not hasattr(session.config, "workerinput"):
        return
    deadline = time.monotonic() + 300
    while not os.path.exists(marker) and time.monotonic() < deadline:
        time.sleep(0.2)


def pytest_unconfigure(config):
    proc = getattr(config, "_synth_warm", None)
    if proc is not None:
        proc.wait()
