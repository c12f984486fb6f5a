"""The Python API honours the capability targets of the design rules, as the command line does (issue 35: "a
verdict includes every target the user set"; before, ``synth.synthesise(d, rules={"capability": {...}})`` and
``synth.screen`` judged nominally and dropped the target, while ``synth design --rules`` ran the robust synthesis).

The robust search itself is pinned elsewhere (``tests/test_robust*.py``, ``tests/test_bulk_capability.py``); here
it is replaced by a stand-in that records the target it is handed, so each test shows the target arriving where
the command line sends it.
"""

from __future__ import annotations

import pytest

import synth
from synth.data import CASES_DIR

DEFAULT = CASES_DIR.parent / "default_case.yaml"
TARGETS = {"capability": {"ppk_min": 1.5, "ppm_max": 60.0}}


HANDED: list = []


class Handed(Exception):
    """What the stand-in was handed."""


def _stand_in(monkeypatch, module: str, name: str):
    import importlib
    mod = importlib.import_module(module)

    def record(*args, **kw):
        HANDED.append(kw["rs"] if "rs" in kw else args[2])  # robust_solve's rs, screen_robust's settings
        raise Handed(HANDED[-1])
    monkeypatch.setattr(mod, name, record)


def test_synthesise_runs_the_robust_synthesis_for_the_rules_targets(monkeypatch):
    _stand_in(monkeypatch, "synth.robust.synthesis", "robust_solve")
    with pytest.raises(Handed) as got:
        synth.synthesise(DEFAULT, rules=TARGETS)
    rs = got.value.args[0]
    assert (rs.capability, rs.ppm) == (1.5, 60.0)


def test_an_explicit_capability_setting_wins_over_the_rules(monkeypatch):
    from synth.robust.settings import RobustSettings
    _stand_in(monkeypatch, "synth.robust.synthesis", "robust_solve")
    with pytest.raises(Handed) as got:
        synth.synthesise(DEFAULT, rules=TARGETS, capability=RobustSettings(capability=1.0, samples=256))
    assert (got.value.args[0].capability, got.value.args[0].ppm, got.value.args[0].samples) == (1.0, None, 256)


def test_screen_reselects_every_row_for_the_rules_targets_with_the_bulks_samples(monkeypatch):
    from synth.robust.settings import BULK_SAMPLES
    _stand_in(monkeypatch, "synth.bulk.capability", "screen_robust")
    row = synth.screen([DEFAULT], rules=TARGETS, diagnose=False, progress=False).iloc[0]
    assert row["status"] == "error" and row["error"].startswith("engine: Handed: ")  # a row's error is its own
    rs = HANDED[-1].capability
    assert (rs.capability, rs.ppm, rs.samples) == (1.5, 60.0, BULK_SAMPLES)


def test_without_targets_nothing_is_robust(monkeypatch):
    _stand_in(monkeypatch, "synth.robust.synthesis", "robust_solve")
    assert synth.synthesise(DEFAULT, rules={"min_margins": {"spring_yield": 0.01}}).parts
