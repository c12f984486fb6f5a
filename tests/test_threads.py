"""Thread pools owned by synth (issue 36): the usable cores (affinity, cgroup quota), ``--threads`` /
``SYNTH_THREADS``, one BLAS thread for the small dense algebra, the settings children inherit, and numba's compile
cache in synth's cache folder with a notice when a kernel compiles."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import numpy as np  # noqa: F401 - its BLAS, loaded for the pool tests
import pytest
import scipy.linalg  # noqa: F401 - its own BLAS too
from threadpoolctl import threadpool_info, threadpool_limits

from synth import threads
from synth.errors import InputError

ROOT = Path(__file__).resolve().parents[1]


def _blas_threads() -> set:
    return {lib["num_threads"] for lib in threadpool_info() if lib["user_api"] == "blas"}


# ------------------------------------------------------------------------------------------- usable cores


def _cgroup(tmp_path, proc_line: str, files: dict) -> tuple[Path, Path]:
    root = tmp_path / "cg"
    for rel, text in files.items():
        (root / rel).parent.mkdir(parents=True, exist_ok=True)
        (root / rel).write_text(text)
    root.mkdir(exist_ok=True)
    proc = tmp_path / "cgroup"
    proc.write_text(proc_line)
    return root, proc


def test_cgroup_v2_quota_of_the_group_and_its_parents(tmp_path):
    root, proc = _cgroup(tmp_path, "0::/user.slice/job\n", {
        "cgroup.controllers": "cpu memory", "user.slice/job/cpu.max": "150000 100000",
        "user.slice/cpu.max": "max 100000"})
    assert threads.cgroup_cpu_limit(root, proc) == 1.5
    (root / "user.slice/cpu.max").write_text("100000 100000")  # a parent's tighter limit binds
    assert threads.cgroup_cpu_limit(root, proc) == 1.0
    (root / "user.slice/cpu.max").write_text("max 100000")
    (root / "user.slice/job/cpu.max").write_text("max 100000")
    assert threads.cgroup_cpu_limit(root, proc) is None


def test_cgroup_v1_quota_and_a_container_whose_path_names_the_host(tmp_path):
    root, proc = _cgroup(tmp_path, "12:memory:/docker/abc\n4:cpu,cpuacct:/docker/abc\n", {
        "cpu,cpuacct/cpu.cfs_quota_us": "250000", "cpu,cpuacct/cpu.cfs_period_us": "100000"})
    assert threads.cgroup_cpu_limit(root, proc) == 2.5  # /docker/abc is not in the container's mount: its root is
    (root / "cpu,cpuacct/cpu.cfs_quota_us").write_text("-1")
    assert threads.cgroup_cpu_limit(root, proc) is None


def test_cgroup_v2_on_a_hybrid_system_and_no_cgroup_at_all(tmp_path):
    root, proc = _cgroup(tmp_path, "1:name=systemd:/\n0::/\n", {"unified/cpu.max": "50000 100000"})
    assert threads.cgroup_cpu_limit(root, proc) == 0.5
    assert threads.cgroup_cpu_limit(root, tmp_path / "missing") is None


@pytest.mark.parametrize("quota, affinity, cores", [(None, 4, 4), (1.5, 4, 2), (0.5, 4, 1), (8.0, 2, 2)])
def test_usable_cores_is_the_affinity_capped_by_the_quota(monkeypatch, quota, affinity, cores):
    monkeypatch.setattr(threads, "cgroup_cpu_limit", lambda *a, **k: quota)
    monkeypatch.setattr(threads, "affinity_cores", lambda: affinity)
    assert threads.usable_cores() == cores


# ------------------------------------------------------------------------------------------- the setting


@pytest.mark.parametrize("bad", ["0", "-1", "2.5", "two", "", True])
def test_a_bad_thread_count_names_the_field_and_what_is_accepted(bad):
    with pytest.raises(InputError, match=r"SYNTH_THREADS: got .*a whole number of threads, 1 or more, or 'auto'"):
        threads.parse_threads(bad, "SYNTH_THREADS")


def test_the_budget_is_never_more_than_the_usable_cores_and_the_option_wins(monkeypatch):
    monkeypatch.setattr(threads, "usable_cores", lambda: 2)
    monkeypatch.delenv(threads.ENV, raising=False)
    assert threads.budget() == 2 and threads.budget(64) == 2 and threads.budget("1") == 1 and threads.budget("auto") == 2
    monkeypatch.setenv(threads.ENV, "1")
    assert threads.budget() == 1 and threads.budget(2) == 2
    assert threads.threads_for("small", 2) == 1 and threads.threads_for("batch", 2) == 2
    with pytest.raises(ValueError, match="unknown task 'huge'"):
        threads.threads_for("huge")


def test_a_bad_threads_option_or_variable_exits_2_with_one_line(capsys, monkeypatch):
    from synth.cli import main
    drive = str(ROOT / "synth" / "data" / "drives" / "example_timing_drive.yaml")
    assert main(["--threads", "0", "drive", drive]) == 2
    err = capsys.readouterr().err
    assert "--threads: got '0'; accepted: a whole number of threads" in err and "Traceback" not in err
    monkeypatch.setenv("SYNTH_THREADS", "many")
    assert main(["drive", drive]) == 2
    assert "SYNTH_THREADS: got 'many'" in capsys.readouterr().err


# ------------------------------------------------------------------------------------------- the pools


def test_a_scene_runs_on_one_blas_thread_and_restores_the_process_after(monkeypatch):
    monkeypatch.delenv("OPENBLAS_NUM_THREADS", raising=False)
    with threadpool_limits(2, user_api="blas"):
        outside = _blas_threads()
        with threads.scene(threads=1) as n:
            assert n == 1 and _blas_threads() == {1}
            assert os.environ["OPENBLAS_NUM_THREADS"] == "1" and os.environ["SYNTH_THREADS"] == "1"
        assert _blas_threads() == outside and "OPENBLAS_NUM_THREADS" not in os.environ


def test_a_child_process_of_a_scene_inherits_its_settings():
    code = "import os; print(os.environ['SYNTH_THREADS'], os.environ['OPENBLAS_NUM_THREADS'], os.environ['OMP_NUM_THREADS'])"
    with threads.scene(threads=1):
        out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
    assert out.split() == ["1", "1", "1"]


def test_the_drive_solves_on_one_blas_thread_through_the_api(monkeypatch):
    """``synth.drive``'s entry points hold BLAS to one thread even outside the command line (notebooks, the API):
    its dense solves are small, and a second thread only waits for a core."""
    from synth.drive import analysis
    from synth.drive.inputs import example_drive
    seen = []
    real = analysis.speed_response

    def spy(*a, **k):
        seen.append(_blas_threads())
        return real(*a, **k)
    monkeypatch.setattr(analysis, "speed_response", spy)
    with threadpool_limits(2, user_api="blas"):
        before = _blas_threads()
        point = analysis.durability_point(example_drive())
        assert _blas_threads() == before  # restored after
    assert seen == [{1}] and point["frequency_hz"] == pytest.approx(50.0, abs=0.05)


def test_limits_is_a_decorator_and_a_context_manager():
    @threads.limits("small")
    def inner():
        return _blas_threads()
    with threadpool_limits(2, user_api="blas"):
        assert inner() == {1}
        with threads.limits("batch", threads=1) as n:
            assert n == 1 and _blas_threads() == {1}


def test_dask_workers_start_as_one_thread_processes(monkeypatch):
    """The local cluster's workers are one-thread processes, whatever the command's own budget."""
    from synth.bulk.run import dask_client
    monkeypatch.setenv("SYNTH_THREADS", "2")
    monkeypatch.setenv("NUMBA_NUM_THREADS", "2")
    with dask_client(None, 1) as client:
        env = next(iter(client.run(lambda: {k: os.environ.get(k) for k in
                                            ("OPENBLAS_NUM_THREADS", "NUMBA_NUM_THREADS", "SYNTH_THREADS")}).values()))
    assert env == {"OPENBLAS_NUM_THREADS": "1", "NUMBA_NUM_THREADS": "1", "SYNTH_THREADS": "1"}


# ------------------------------------------------------------------------------------------- compiled once

_KERNEL = """
import os, sys, numpy as np
import synth.kernels
assert "numba" not in sys.modules  # configuring the cache does not load numba
print(os.environ["NUMBA_CACHE_DIR"], os.environ["NUMBA_NUM_THREADS"])
from synth.kernels import _bitsets_jit
bits = np.zeros((2, 1), np.uint64)
_bitsets_jit.set_bits(np.array([0, 1], np.int64), np.array([3, 5], np.int64), bits)
print(int(bits[0, 0]), int(bits[1, 0]))
"""


def _kernel_process(env: dict) -> subprocess.CompletedProcess:
    e = {k: v for k, v in os.environ.items() if k not in ("NUMBA_CACHE_DIR", "NUMBA_NUM_THREADS")}
    e.update(PYTHONPATH=str(ROOT), **env)
    return subprocess.run([sys.executable, "-c", _KERNEL], capture_output=True, text=True, env=e, timeout=300)


def test_kernels_compile_once_into_the_versioned_cache_folder_saying_so(tmp_path):
    from synth.kernels.numba_setup import sources_digest
    from synth.version import __version__
    first = _kernel_process({"SYNTH_CACHE_DIR": str(tmp_path), "SYNTH_THREADS": "1"})
    assert first.returncode == 0, first.stderr
    folder, pool = first.stdout.split("\n")[0].split()
    assert Path(folder) == tmp_path / f"numba-{__version__}-{sources_digest()}" and pool == "1"
    assert first.stdout.split("\n")[1].split() == ["8", "32"]
    assert first.stderr.count("synth: compiling synth's kernels (first run after install") == 1
    assert list(Path(folder).rglob("_bitsets_jit.set_bits-*.nbi"))
    second = _kernel_process({"SYNTH_CACHE_DIR": str(tmp_path)})
    assert second.returncode == 0 and "compiling" not in second.stderr  # loaded from the cache


def test_a_numba_cache_folder_the_user_set_is_kept(tmp_path):
    r = _kernel_process({"SYNTH_CACHE_DIR": str(tmp_path / "synth"), "NUMBA_CACHE_DIR": str(tmp_path / "mine")})
    assert r.returncode == 0, r.stderr
    assert r.stdout.split()[0] == str(tmp_path / "mine") and list((tmp_path / "mine").rglob("*.nbi"))


def test_an_api_call_runs_blas_on_one_thread_as_a_scene_does(monkeypatch):
    """Issue 36: the command line ran every scene on one BLAS thread, the Python API on the library's pool (a
    thread per processor, spinning against other work). Every API call now runs under :func:`synth.threads.call`."""
    import numpy  # noqa: F401 - its BLAS loaded
    from threadpoolctl import threadpool_info, threadpool_limits

    import synth
    from synth.data import CASES_DIR
    from synth.optimise import honour

    seen = []

    def record(*args, **kw):
        seen.append({lib["num_threads"] for lib in threadpool_info() if lib["user_api"] == "blas"})
        raise RuntimeError("recorded")
    monkeypatch.setattr(honour, "solve_honouring", record)
    with threadpool_limits(2, user_api="blas"):
        outside = {lib["num_threads"] for lib in threadpool_info() if lib["user_api"] == "blas"}
        with pytest.raises(RuntimeError, match="recorded"):
            synth.synthesise(CASES_DIR.parent / "default_case.yaml")
        after = {lib["num_threads"] for lib in threadpool_info() if lib["user_api"] == "blas"}
    # a library loaded at one thread (OPENBLAS_NUM_THREADS=1: the conftest's) stays at one; numpy's goes to two
    assert max(outside) == 2 and after == outside and seen == [{1}]


def test_kernel_cache_folder_changes_with_any_kernel_source(tmp_path, monkeypatch):
    """numba does not notice an edit of a file its kernel calls into (the scans call ``_main_spring_jit``'s pair
    physics), so the folder is named by a digest of every kernel source: an edit of one starts a new folder."""
    import shutil

    import synth.kernels.numba_setup as ns
    here = Path(ns.__file__).parent
    copy = tmp_path / "kernels"
    copy.mkdir()
    for f in here.glob("_*.py"):
        shutil.copy(f, copy / f.name)
    shutil.copy(ns.__file__, copy / "numba_setup.py")
    monkeypatch.setattr(ns, "__file__", str(copy / "numba_setup.py"))
    before = ns.sources_digest()
    assert len(before) == 12 and before == ns.sources_digest()
    (copy / "_main_spring_jit.py").write_text((copy / "_main_spring_jit.py").read_text() + "\n# an edit\n")
    assert ns.sources_digest() != before
    monkeypatch.setenv("SYNTH_CACHE_DIR", str(tmp_path / "cache"))
    assert ns.kernel_cache_dir().name.endswith("-" + ns.sources_digest())
