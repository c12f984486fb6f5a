"""``--top K`` (issue 35): alternatives that a buyer or designer would call different, and for an infeasible input
its ranked near misses, each judged by the one evaluator (:func:`synth.verify` gives the same margins)."""

from __future__ import annotations

import io
import itertools
import json
import math
from contextlib import redirect_stdout
from pathlib import Path

import pytest

import synth
from synth.cli import main
from synth.data import case_path
from synth.design.space import PART_KEYS
from synth.optimise.alternatives import DIMENSION_KEYS, DISTINCT_KEYS
from synth.optimise.product import design_scores

ROOT = Path(__file__).resolve().parents[1]
DEFAULT = ROOT / "synth" / "data" / "default_case.yaml"
CASE1 = case_path("case1")  # thesis case 1: infeasible with synth's defaults (every bolt fails the under-head)
#: --json writes numbers to 6 significant digits (Result.as_dict)
JSON_REL = 1e-5
#: the catalog parts a buyer or designer calls different parts (the brief of issue 35)
CATALOG_KEYS = ("ball_bearing", "pivot_class_diameter_mm", "pivot_bushing_supplier", "pivot_bushing_length_mm",
                "damper_pad_class", "endcap_spacer_class", "main_spring_material", "main_spring_wire",
                "bolt_format", "bolt_head_type", "bolt_property_class", "bolt_washer", "bolt_tightening")


def _design(*argv) -> tuple[int, dict]:
    buf = io.StringIO()
    with redirect_stdout(buf):
        code = main(["design", *map(str, argv), "--json"])
    return code, json.loads(buf.getvalue())


def _before(a: tuple, b: tuple) -> bool:
    """Whether objective key ``a`` ranks strictly before ``b`` (equal within the JSON's rounding: not before)."""
    for x, y in zip(a, b):
        if not math.isclose(x, y, rel_tol=JSON_REL, abs_tol=1e-9):
            return x < y
    return False


@pytest.fixture(scope="module")
def default_top5():
    return _design(DEFAULT, "--top", "5")


@pytest.fixture(scope="module")
def case1_top5():
    return _design(CASE1, "--top", "5")


def test_the_distinct_keys_are_the_catalog_parts():
    assert set(DISTINCT_KEYS) == set(CATALOG_KEYS)
    assert set(DISTINCT_KEYS) | set(DIMENSION_KEYS) == set(PART_KEYS) and not set(DISTINCT_KEYS) & set(DIMENSION_KEYS)


def test_top5_of_the_default_case_differ_pairwise_in_a_catalog_part(default_top5):
    code, r = default_top5
    alts = r["alternatives"]
    assert code == 0 and r["verdict"] == "pass" and len(alts) == 5
    assert alts[0]["parts"] == r["parts"] and alts[0]["differs"] == {}  # the first is the optimum
    assert [a["kind"] for a in alts] == ["alternative"] * 5 and all(a["verdict"] == "pass" for a in alts)
    for a, b in itertools.combinations(alts, 2):  # d4b9b72: five designs differing only in the spring's Dm
        assert any(a["parts"][k] != b["parts"][k] for k in CATALOG_KEYS), (a["rank"], b["rank"])
    keys = [(a["objectives"]["standard"], a["objectives"]["cost"], -a["margin"]) for a in alts]
    assert keys == sorted(keys)  # objective order: standard, cost, then the larger margin
    assert alts[0]["objectives"] == {"standard": 2.0, "cost": pytest.approx(1.74435, abs=1e-4), "margin": pytest.approx(
        0.0, abs=1e-6)}


def test_each_alternative_is_the_best_of_its_parts_and_verify_agrees(default_top5):
    """Each listed design's margin and binding check are synth.verify's on the same parts (a second path), and
    the neighbouring mean diameters of its parts rank no higher (it is its parts' best representative)."""
    _, r = default_top5
    for a in r["alternatives"]:
        v = synth.verify(str(DEFAULT), a["parts"])
        assert v.verdict == "pass"
        assert a["margin"] == pytest.approx(float(v.assessment().objective_margin[0]), rel=JSON_REL)
        assert a["binding_id"] == str(v.assessment().binding_ids()[0])
    d = synth.load(str(DEFAULT))
    for a in r["alternatives"]:  # the neighbouring mean diameters of the same parts do not rank higher
        key = (a["objectives"]["standard"], a["objectives"]["cost"], -a["margin"])
        for step in (-1.0, 1.0):
            parts = {**a["parts"], "main_spring_mean_body_diameter_mm": a["parts"]["main_spring_mean_body_diameter_mm"]
                     + step}
            other = synth.verify(d, parts)
            if other.verdict == "pass":
                s = design_scores(d, parts)
                assert not _before((s["standard"], s["cost"], -float(other.assessment().objective_margin[0])),
                                   key), (a["rank"], step)


def test_case1_lists_its_five_nearest_designs_by_decreasing_margin(case1_top5):
    code, r = case1_top5
    near = r["alternatives"]
    assert code == 1 and r["status"] == "infeasible" and len(near) == 5
    assert [a["kind"] for a in near] == ["near miss"] * 5 and all(a["verdict"] == "fail" for a in near)
    margins = [a["margin"] for a in near]
    assert margins == sorted(margins, reverse=True) and all(m < 0 for m in margins)
    # every catalog bolt leaves the under-head pressure 35.2 % above the support's 400 MPa (the diagnosis's)
    assert near[0]["binding_id"] == "under_head" and near[0]["margin"] == pytest.approx(-0.3522, abs=5e-5)
    assert r["diagnosis"]["violated"][0]["constraint"] == "under_head"
    assert near[0]["margin"] == pytest.approx(r["diagnosis"]["violated"][0]["margin"], rel=JSON_REL)
    for a, b in itertools.combinations(near, 2):
        assert any(a["parts"][k] != b["parts"][k] for k in CATALOG_KEYS)


def test_case1_near_misses_have_the_margins_of_synth_verify(case1_top5):
    """The cross-check between paths: each near miss verified alone gives the same smallest margin, binding check
    and failing checks."""
    _, r = case1_top5
    assert len(r["alternatives"]) == 5
    for a in r["alternatives"]:
        v = synth.verify(str(CASE1), a["parts"])
        asm = v.assessment()
        assert a["margin"] == pytest.approx(float(asm.margin_min[0]), rel=JSON_REL)
        assert a["binding_id"] == str(asm.binding_ids()[0])
        assert [(f["id"], f["margin"]) for f in a["failed"]] == \
            [(c.id, pytest.approx(c.margin, rel=JSON_REL)) for c in sorted(v.failed(), key=lambda c: c.margin)]
        assert math.isclose(a["failed"][0]["margin"], a["margin"], rel_tol=JSON_REL)


def test_case1_prints_near_misses_not_none(capsys):
    code = main(["design", str(CASE1), "--top", "2"])
    out = capsys.readouterr().out
    assert code == 1 and "Alternatives: none" not in out
    assert "Near misses (no feasible design): the 2 nearest distinct designs" in out
    block = out.split("Near misses")[1].split("\n\n")[0]
    assert "#1  margin -35.2 % (under-head pressure within the support's compressive strength)" in block
    assert "fails: under-head pressure within the support's compressive strength by 35.2 %" in block


def test_distinct_says_what_counts_as_different(capsys):
    r = synth.synthesise(str(DEFAULT), top=4, distinct=("ball_bearing", "bolt_format"))
    sig = [(a["parts"]["ball_bearing"], a["parts"]["bolt_format"]) for a in r.alternatives]
    assert len(sig) == 4 and len(set(sig)) == 4 and r.alternatives[0]["parts"] == r.parts
    code = main(["design", str(DEFAULT), "--top", "3", "--distinct", "bolt_format", "bolt_colour"])
    err = capsys.readouterr().err
    assert code == 2 and "--distinct: got 'bolt_colour'" in err


def test_a_failing_flowchart_design_gets_the_catalogs_best_not_near_misses():
    """The thesis procedure fails the default case with pivot class 26 kept (its arm wall fails) where the catalog
    holds feasible designs: --top lists the catalog's best distinct designs, the first the exhaustive optimum, each
    differing from the flowchart's design (before: 'none', or near misses that pass). (The default case itself
    served until the dry friction 0.10, at which its pivot class 20 passes.)"""
    from synth import schema
    values = {k: v for k, v in synth.load(str(DEFAULT)).as_dict().items() if v is not None}
    d = schema.validate({**values, "pivot_class_diameter_mm": 26.0})
    best = synth.synthesise(d)
    flow = synth.synthesise(d, solver="flowchart", top=3)
    assert flow.failed() and [a["kind"] for a in flow.alternatives] == ["alternative"] * 3
    assert best.feasible and flow.alternatives[0]["parts"] == best.parts
    assert all(a["verdict"] == "pass" and a["differs"] for a in flow.alternatives)


def _key(a: dict) -> tuple:
    """A near miss's second-level rank, recomputed by synth.verify (a second path): (smallest margin, second
    smallest margin of the counted checks, number of failing checks)."""
    import numpy as np
    asm = synth.verify(str(CASE1), a["parts"]).assessment()
    m = np.sort(asm.margins[0][asm.counted[0]])
    return float(m[0]), float(m[1]), int(asm.failed[0].sum())


def test_case1_near_misses_that_tie_on_the_binding_check_are_ordered_by_the_next(case1_top5):
    """Case 1's near misses all miss the under-head pressure by 35.2 % (every bolt on that seat; 246 million designs
    tie there). They are ranked by the one key (synth.design.combine.near_key): the second smallest margin, then the
    fewer failing checks; the first is the diagnosis's nearest design, the best under that key: it fails 3 checks,
    the next-worst by 4.1 % (on 7820e8c the diagnosis showed a design failing 5, the bolt's equivalent stress
    33.2 % over, which no near-miss list put first)."""
    _, r = case1_top5
    keys = [_key(a) for a in r["alternatives"]]
    assert all(k[0] == pytest.approx(-0.35216, abs=5e-5) for k in keys)  # one tie on the binding check
    assert keys[0][1:] == (pytest.approx(-0.0408, abs=5e-4), 3)
    for a, b in zip(keys, keys[1:]):  # by the second margin, then the fewer failing checks
        assert a[1] > b[1] + 1e-9 or (a[1] == pytest.approx(b[1], abs=1e-9) and a[2] <= b[2]), (a, b)
    assert any(a[1] > b[1] + 1e-3 for a, b in zip(keys, keys[1:]))  # two ties on the binding check, ordered
    assert r["alternatives"][0]["parts"] == r["parts"] and _key({"parts": r["parts"]}) == keys[0]


def test_case1_near_miss_one_is_the_diagnosis_nearest_design_for_every_k(case1_top5):
    """Near miss #1 is the design the diagnosis names, whatever K (on 7820e8c: K=1 gave class 9.8, K=2 and 5 class
    10.9, the diagnosis class 8.8)."""
    from synth.optimise.alternatives import ranked
    from synth.optimise.diagnose import diagnose
    _, five = case1_top5
    d = synth.load(str(CASE1))
    r = diagnose(d, relax=False)
    assert r.parts == five["parts"] == five["alternatives"][0]["parts"]
    assert [ranked(d, r, k)[0]["parts"] for k in (1, 2)] == [r.parts] * 2
    assert r.parts["bolt_property_class"] == "10.9"


def test_a_generated_infeasible_application_has_the_same_nearest_design_in_every_list():
    """The same on a generated infeasible application: the diagnosis's nearest design (found by the bulk's
    Batch.nearest) is near miss #1 for K = 1 and 5, which the exhaustive evaluation ranks (on 7820e8c near miss #1
    for K=1 and K=5 was not the diagnosis's design)."""
    from synth.data.generated_applications import generate
    from synth.optimise.alternatives import ranked
    from synth.optimise.diagnose import diagnose
    d = generate(2, seed=7)[1]
    r = diagnose(d, relax=False)
    assert [ranked(d, r, k)[0]["parts"] for k in (1, 5)] == [r.parts] * 2


def test_alternatives_say_their_cost_against_the_optimum(default_top5):
    """Each alternative after the optimum says its cost difference in EUR and percent (issue 35), the optimum
    none; the words are synth.formatting.difference's."""
    from types import SimpleNamespace
    from synth.report.advice import alternative_rows
    _, r = default_top5
    rows = alternative_rows(SimpleNamespace(alternatives=r["alternatives"], objectives=r["objectives"]))
    best = r["alternatives"][0]["objectives"]["cost"]
    assert rows[0]["cost_change"] == "" and "against" not in rows[0]["objectives"]
    for a, row in zip(r["alternatives"][1:], rows[1:]):
        d = a["objectives"]["cost"] - best
        eur, pct = row["cost_change"].split(" EUR (")
        assert float(eur) == pytest.approx(d, rel=2e-3, abs=1e-4)
        assert float(pct.removesuffix(" %)")) == pytest.approx(100 * d / best, abs=0.06)
        assert row["objectives"].endswith(f", {row['cost_change']} against the optimum")
