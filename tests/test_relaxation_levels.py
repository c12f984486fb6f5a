"""The levels of :func:`synth.optimise.diagnose.relaxations_batch` (alone, pairs, all) overlapped in probe rounds.

Hand calculation with a stand-in probe on case 1 (no physics): a specification value alone relaxes the
application from 0.45 of its far move on, and the pair of the tensioner designer's own inputs (pivot height, active threads)
from 0.3 of the pair's joint far move on; nothing else does. The sequential order is 1 + 7 rounds for the inputs
alone, then 1 + 7 for the designer's one pair (no designer relaxation alone): 16 probe rounds. Overlapped, the pairs'
far probes go with the first bisection step of the inputs alone: 9 rounds, the same probes and relaxations.
Bisection (7 steps between the far probe, good, and the input's value, bad): 0.5 T, 0.25 F, 0.375 F, 0.4375 F,
0.46875 T, 0.453125 T, 0.4453125 F -> 0.453125; and 0.5 T, 0.25 F, 0.375 T, 0.3125 T, 0.28125 F, 0.296875 F,
0.3046875 T -> 0.3046875.
"""

from __future__ import annotations

from synth.data import case_path
from synth.io.documents import load_input
from synth.optimise.diagnose import _entry, _far, _far_joint, relaxations_batch

VIOLATED = ["thread", "spring_coil_gap", "pivot_wall"]
SPEC, PAIR = "tilting_safety_factor", ("max_pivot_height_mm", "number_of_active_threads")


def test_levels_overlap_with_the_sequential_answer():
    d = load_input(case_path("case1"))
    far_spec = {SPEC: _far(d, SPEC, -1)}
    far_pair = _far_joint(d, {n: 1 for n in PAIR})

    def fraction(changes, far):
        n = next(iter(far))
        return (changes[n] - getattr(d, n)) / (far[n] - getattr(d, n))
    rounds = []

    def probe(items):
        rounds.append(len(items))
        out = []
        for x, ch in items:
            assert x is d
            if set(ch) == {SPEC}:
                out.append(fraction(ch, far_spec) >= 0.45)
            elif set(ch) == set(PAIR):
                out.append(fraction(ch, far_pair) >= 0.3)
            else:
                out.append(False)
        return out
    got = relaxations_batch([d], [VIOLATED], probe=probe)[0]
    assert got == [_entry(d, PAIR, far_pair, 0.3046875, VIOLATED), _entry(d, (SPEC,), far_spec, 0.453125, VIOLATED)]
    assert got[0]["owner"] == "designer" and got[1]["owner"] == "specification"
    # 8 inputs alone; then their bisection (1 live) with the designer pair's far probe; then both bisections
    assert rounds == [8, 1 + 1] + [2] * 6 + [1]
