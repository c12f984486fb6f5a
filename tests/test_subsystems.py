"""A part family is one declaration (:mod:`synth.design.subsystems`): the design space's part keys and order, the
catalog product (``synth design``) and the Batch scans (``synth bulk``) read it.

The toy re-declares the bushing from its own spec with a narrower availability (only supplier B's bushings for
every core) and checks that ``synth design`` (through :func:`synth.synthesise`) and ``synth bulk`` (through
:func:`synth.screen`, its in-memory twin) both take it, then that withdrawing it restores the answers.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np
import pytest

from synth.design import space as space_module
from synth.design import subsystems
from synth.design.space import space


def test_the_space_reads_the_declarations():
    assert space_module.SUBSYSTEMS == subsystems.names() == ("bushing", "axial", "spring", "bolt")
    for fam in subsystems.declared():
        assert space_module.PART_KEYS_BY_TABLE[fam.name] == fam.part_keys
        assert fam.name in space().tables
    assert space_module.PART_KEYS_BY_TABLE["core"] == subsystems.CORE_PART_KEYS


def test_core_reads_are_derived_from_the_registry():
    cv = ["hubload_nominal_n", "pivot_diameter_mm", "axial_group_present", "loading_arm_mm"]
    assert subsystems.family("bolt").core_reads(cv) == ("pivot_diameter_mm", "loading_arm_mm")
    assert subsystems.family("bushing").core_reads(cv)[:3] == tuple(cv[:3])


@dataclass(frozen=True)
class _OnlyB(subsystems.Subsystem):
    """The bushing, available from supplier B only (whatever the core's supplier)."""

    def available(self, sp, core_values, pos):
        out = super().available(sp, core_values, pos)
        return out & (np.asarray(sp.tables[self.name]["pivot_bushing_supplier"]) == "B")[None, :]


@pytest.fixture
def only_b():
    before = subsystems.family("bushing")
    subsystems.declare(_OnlyB(**{f: getattr(before, f) for f in before.__dataclass_fields__}))
    try:
        yield
    finally:
        subsystems.declare(before)
    assert subsystems.family("bushing") is before


def _apps():
    from synth.data.generated_applications import generate
    return generate(3, seed=0)


def test_a_redeclared_family_is_what_design_and_bulk_search(only_b):
    import synth
    r = synth.synthesise(_apps()[1])
    assert r.status == "optimal" and r.parts["pivot_bushing_supplier"] == "B"
    rows = synth.screen(_apps(), progress=False, diagnose=False)
    assert (rows["error"].fillna("") == "").all()
    assert rows["feasible"].tolist() == [False, True, False]  # the third was feasible with supplier A's bushing
    assert (rows["part_pivot_bushing_supplier"] == "B").all()


def test_withdrawn_redeclaration_restores_the_answers():
    import synth
    rows = synth.screen(_apps(), progress=False, diagnose=False)
    assert rows["feasible"].tolist() == [False, True, True]
    assert rows["part_pivot_bushing_supplier"].tolist() == ["A", "B", "A"]
    fam = subsystems.family("bushing")
    assert replace(fam) == fam  # a declaration is a plain value: re-declared from its spec with replace(...)
