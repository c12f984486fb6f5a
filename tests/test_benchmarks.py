"""The benchmarks still run (a smoke test of their small sizes: an API change must not leave them broken).

No timing is asserted: the benchmarks print the speed tables (README, "Benchmarks"); here the bulk benchmark's
own check must hold: the fast engine equals the reference on the applications it compares.
"""

from __future__ import annotations

import importlib.util
from pathlib import Path

BENCH = Path(__file__).resolve().parents[1] / "benchmarks"


def _module(name: str):
    spec = importlib.util.spec_from_file_location(name, BENCH / f"{name}.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


def test_bench_assessment_runs_and_leaves_the_functions_it_times(capsys):
    from synth.design import evaluate
    ok = evaluate.Group.ok
    assert _module("bench_assessment").main(["--n", "30", "--runs", "1"]) == 0
    assert "| Group.ok |" in capsys.readouterr().out
    assert evaluate.Group.ok is ok


def test_bench_bulk_quick_runs_and_the_engine_equals_the_reference(capsys):
    assert _module("bench_bulk").main(["--quick", "--no-command"]) == 0
    out = capsys.readouterr().out
    assert "equals the reference on the first 4 applications: yes" in out
    assert "One optimum inside a process" in out


def test_bench_kernels_sample_is_the_engines_keys():
    """The kernel benchmark's sample: keys of feasible cores, each with a cost-ordered list of its range."""
    mod = _module("bench_kernels")
    keys, options, lists, groups, _, app = mod.sample(6, 0)
    assert len(keys) == len(groups) == len(app) > 0 and len(options) >= 10000
    assert all(0 <= g < len(lists) for g in groups)
    r = mod.main_spring.first_feasible(keys, options, lists, key_group=groups, tol=mod.FEAS_TOL, engine="numpy")
    assert (r.index >= 0).any()


def test_bench_robust_quick_runs(capsys):
    """The capability benchmark's tables (a smoke test: one repeat, 12 applications)."""
    import os

    import pytest
    if not os.environ.get("SYNTH_SLOW"):
        pytest.skip("about 10 s: set SYNTH_SLOW=1 to run")
    assert _module("bench_robust").main(["--quick"]) == 0
    out = capsys.readouterr().out
    assert "capability, 10000 samples" in out and "FORM + importance sampling" in out
def test_bench_blackbox_runs_and_is_reproducible(capsys):
    """The black-box benchmark's cases table at a small budget, and its seeded-reproducibility check."""
    _module("bench_blackbox").main(["--apps", "0", "--budgets", "10"])
    out = capsys.readouterr().out
    # issue 34's friction 0.10: thesis case 3's nearest design needs more spring torque for its damping window (its
    # spring yield -6.4 %, was -4.3 % at 0.15); the default case free reaches the standard pivot class 19 with the
    # M6 hex 12.9 on its ISO 7089 washer (1 non-standard part, 1.744 EUR: see test_control)
    assert "| thesis case 3 | nearest -0.0641 |" in out and "| default case | 1 / 1.744 |" in out
    assert out.count("| yes |") == 4
