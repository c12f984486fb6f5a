"""The relaxation search's reused designs (:func:`synth.optimise.diagnose.probe_batch`'s ``designs``).

Each bisection step first verifies the design its (application, set of inputs) last found feasible at the new
point (:func:`synth.optimise.batch.designs_pass`, the judge); only the probes it fails are searched. A design
that passes the judge proves the search's yes, so the relaxations must be those of the plain probe (every probe
searched): checked on the infeasible applications among 40 generated ones, every relaxable input a candidate.
"""

from __future__ import annotations

from synth.data.generated_applications import generate
from synth.design.evaluate import Settings
from synth.optimise.batch import any_feasible, designs_pass
from synth.optimise.diagnose import probe_batch, relaxable, relaxations_batch

SETTINGS = Settings(fidelity="screening")  # the bulk command's default: screened, judged at full fidelity


def test_reused_designs_give_the_plain_probes_relaxations():
    ds = generate(40, seed=5)
    bad = [d for d, ok in zip(ds, any_feasible(ds, SETTINGS)) if not ok]
    violated = [sorted(set().union(*(r[1] for r in relaxable().values())))] * len(bad)
    fast = probe_batch(SETTINGS)
    plain = probe_batch(SETTINGS)
    got = relaxations_batch(bad, violated, settings=SETTINGS, probe=fast)
    ref = relaxations_batch(bad, violated, settings=SETTINGS, probe=lambda items: plain(items))  # no designs
    assert len(bad) >= 10 and sum(map(len, ref)) >= 10
    assert fast.counts["reused"] > 0  # the shortcut answered some probes
    assert got == ref


def test_a_design_found_passes_its_own_input_and_the_answers_agree():
    ds = generate(12, seed=0)
    found = any_feasible(ds, SETTINGS, designs=True)
    assert [f is not None for f in found] == any_feasible(ds, SETTINGS)
    yes = [i for i, f in enumerate(found) if f is not None]
    assert len(yes) >= 3 and 0 < len(yes) < len(ds)
    assert designs_pass([ds[i] for i in yes], [found[i] for i in yes], SETTINGS).all()
    # the first feasible design of another application does not pass every input: the check is not vacuous
    other = [found[yes[0]]] * len(ds)
    assert not designs_pass(ds, other, SETTINGS).all()
