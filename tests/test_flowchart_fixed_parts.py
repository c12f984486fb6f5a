"""The flowchart's fixed-parts mode: ``run(d, parts=...)`` verifies a given design.

Two independent paths evaluate a design: the flowchart's steps (scalar, in the
thesis's order, with report records) and the optimiser's vectorised
``evaluate``/``verify``. Fed the same parts at the same fidelity, they must
agree on every derived value and on the verdict; that pins the optimiser's
arrangement of the physics against the flowchart's.
"""

from __future__ import annotations

import math

import pytest

from synth.checks import FAIL
from synth.data import case_path
from synth.data.generated_applications import generate
from synth.errors import InputError
from synth.flowchart import PART_KEYS, Settings, run
from synth.optimise import solve
from synth.optimise.evaluate import FEAS_TOL
from synth.optimise.result import PART_KEYS as OPT_PART_KEYS, verify
from synth.schema import validate

from conftest import load_case

FULL = Settings(fidelity="full", bushing_length_scheme="catalog")

#: flowchart check name -> optimiser constraint, where both use the same normalised margin
SAME_MARGIN = {
    "cone spring De/t <= Table 7 max": "cone_thinness",
    "cone spring deflection at maximum material <= h0": "cone_not_flattened",
    "end-of-life damping": "damping_eol",
    "damper pad class carries the axial damping": "damper_pad_capacity",
    "main spring outer contact with housing": "spring_outer_contact",
    "main spring yield at installation": "spring_yield",
    "pivot bushing pressure": "bushing_p",
    "pivot bushing p*v": "bushing_pv",
    "thread bearing stress": "thread",
    "arm free to move (no self-locking)": "self_locking",
}

VALUES = ("cone_spring_thickness_mm", "cone_spring_fax_nominal_n", "cone_spring_cone_height_mm", "damping_eol_nm",
          "main_spring_active_coils_free", "main_spring_safety_factor", "main_spring_sigma_inst_mpa",
          "spring_housing_height_mm", "spring_housing_outer_diameter_mm", "pivot_diameter_mm",
          "pivot_bushing_p_mpa", "bolt_tightening_torque_nm", "bolt_axial_force_n", "spring_torque_nominal_nm")


@pytest.fixture(scope="module")
def designs():
    """Optimiser designs (optimum or nearest) of 6 generated applications, with both evaluations."""
    out = []
    for d in generate(6, seed=3):
        r = solve(d, "standard", "enumerate", relax=False)
        out.append((d, r, verify(d, r.parts, fidelity="full"), run(d, FULL, parts=r.parts)))
    return out


def test_part_keys_are_the_optimisers():
    assert PART_KEYS == OPT_PART_KEYS


def test_mix_of_feasible_and_infeasible(designs):
    # the sample must exercise both verdicts, else the agreement test below proves little
    verdicts = {f.verdict for *_, f in designs}
    assert verdicts == {"pass", "fail"}


def test_values_agree(designs):
    for d, r, v, f in designs:
        for k in VALUES:
            if v.values.get(k) is None or f.values.get(k) is None:
                continue
            assert f.values[k] == pytest.approx(v.values[k], rel=1e-9, abs=1e-12), k


def test_verdicts_and_margins_agree(designs):
    for d, r, v, f in designs:
        assert (f.verdict == "pass") == v.passes, (r.parts, [c.name for c in f.failed()], v.failed())
        for c in f.checks:
            name = SAME_MARGIN.get(c.name)
            if name in v.margins and c.margin is not None:
                assert c.margin == pytest.approx(v.margins[name], abs=1e-9), c.name


def test_flowchart_design_round_trip():
    """The flowchart's own choices, fed back as fixed parts, give the same values (case 1 as run)."""
    d = validate(load_case("case1_as_run")["inputs"])
    s = Settings(fidelity="full", bushing_length_scheme="catalog")
    free = run(d, s)
    parts = free.parts
    assert parts is not None and parts["bearing"] == "6006" and parts["damper_pad"] == free.values["damper_pad_class"]
    fixed = run(d, s, parts=parts)
    for k in VALUES + ("damper_pad_class", "endcap_spacer_class", "main_spring_material", "bolt_format"):
        a, b = free.values.get(k), fixed.values.get(k)
        if isinstance(a, float):
            assert b == pytest.approx(a, rel=1e-12), k
        else:
            assert a == b, k
    assert [c.name for c in fixed.failed()] == [c.name for c in free.failed()]


def test_bearing_over_its_table1_range_fails():
    d = validate(load_case("case1_as_run")["inputs"])
    parts = run(d, FULL).parts
    # 6006 carries up to 1000 N (gasoline, Table 1); case 1's hubload is ~ 590 N, so it passes here
    ok = run(d, FULL, parts=parts).check("hubload within the bearing's Table 1 range")
    assert ok.verdict == "pass" and ok.limit == 1000.0
    heavy = validate({**vars(d), "calculated_torque_target_nm": 6.0})  # hubload ~ 2x
    hl = run(heavy, FULL, parts=parts)
    c = hl.check("hubload within the bearing's Table 1 range")
    assert c.value > 1000.0 and c.verdict == FAIL


def test_axial_split_without_pad_is_a_failed_check():
    d = validate(load_case("case1_as_run")["inputs"])
    parts = {**run(d, FULL).parts, "damper_pad": "none", "endcap_spacer": "none"}
    r = run(d, FULL, parts=parts)
    assert r.check("axial damping group in the parts").verdict == FAIL


def test_incomplete_parts_name_the_missing_keys():
    d = validate(load_case("case1_as_run")["inputs"])
    with pytest.raises(InputError, match="bolt_property_class"):
        run(d, FULL, parts={"bearing": "6006"})
    parts = {**run(d, FULL).parts, "supplier": "Z"}
    with pytest.raises(InputError, match="parts.supplier"):
        run(d, FULL, parts=parts)


def test_stopped_flowchart_has_no_parts():
    d = validate(load_case("case1_as_run")["inputs"])
    # working arm 0.3 mm: lever ratio 1.47 > 1 (r_p sin(atan mu) exceeds the lever), the arm self-locks
    locked = validate({**vars(d), "working_arm_mm": 0.3})
    r = run(locked, FULL)
    assert r.check("arm free to move (no self-locking)").verdict == FAIL
    assert r.parts is None
    assert not math.isnan(r.values["lever_ratio"])


def test_cli_verifies_a_saved_design(tmp_path, capsys):
    """``synth design --json`` then ``synth flowchart --parts``: the flowchart checks the optimiser's design."""
    import json

    from synth.cli import main
    case = str(case_path("case3"))
    main(["design", case, "--json"])
    saved = tmp_path / "design.json"
    saved.write_text(capsys.readouterr().out)
    parts = json.loads(saved.read_text())["parts"]
    code = main(["flowchart", case, "--parts", str(saved), "--json", "--fidelity", "screening"])
    out = json.loads(capsys.readouterr().out)
    assert out["ball_bearing"] == parts["bearing"] and out["main_spring_mean_body_diameter_mm"] == parts["spring_mbd_mm"]
    assert out["bolt_format"] == parts["bolt_format"] and out["pivot_bushing_length_mm"] == parts["bushing_length_mm"]
    assert code == (0 if out["verdict"] == "pass" else 1)
    assert main(["flowchart", case, "--parts", str(tmp_path / "missing.json")]) == 2
    assert "--parts" in capsys.readouterr().err
