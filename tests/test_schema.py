"""Design-input validation: case files load, bad input gets one message per field."""

import json

import pytest

from synth import schema
from synth.io import documents
from synth.cli import main
from synth.errors import InputError
from tests.conftest import CASES, load_case


@pytest.mark.parametrize("name", ["case1", "case1_as_run", "case3"])
def test_case_files_are_valid_inputs(name):
    d = documents.load_input(CASES / f"{name}.yaml")
    raw = load_case(name)["inputs"]
    assert d.differential_angle_deg == pytest.approx(raw["differential_angle_deg"])
    assert d.application_type == raw["application_type"]
    assert d.main_spring_mode == "automatic" and d.bolt_mode == "automatic"  # defaults of the selectors


def test_json_and_toml_load_the_same(tmp_path):
    raw = load_case("case3")["inputs"]
    j = tmp_path / "in.json"
    j.write_text(json.dumps(raw))
    t = tmp_path / "in.toml"
    t.write_text("\n".join(f"{k} = {json.dumps(v)}" for k, v in raw.items() if v is not None))
    assert documents.load_input(j) == documents.load_input(t)


def test_every_problem_reported_once_with_field_value_and_accepted():
    raw = dict(load_case("case3")["inputs"])
    raw.update(differential_angle_deg=180, working_arm_mm=-4, belt_widht_mm=26, engine_fuel="kerosene")
    with pytest.raises(InputError) as err:
        schema.validate(raw)
    by_field = {p.field: p for p in err.value.problems}
    assert set(by_field) == {"differential_angle_deg", "working_arm_mm", "belt_widht_mm", "engine_fuel"}
    assert "[0.1, 180)" in by_field["differential_angle_deg"].accepted
    assert "did you mean belt_width_mm" in by_field["belt_widht_mm"].accepted
    assert "gasoline, diesel" in by_field["engine_fuel"].accepted


def test_inconsistent_fields():
    raw = dict(load_case("case1")["inputs"])
    raw.update(engine_support_external_diameter_mm=8.0, lockup_pin_diameter_mm=None, damping_eol_limit_nm=2.5)
    with pytest.raises(InputError) as err:
        schema.validate(raw)
    fields = {p.field for p in err.value.problems}
    assert {"engine_support_external_diameter_mm", "lockup_pin_diameter_mm", "damping_eol_limit_nm"} <= fields


def test_manual_spring_needs_its_part():
    raw = dict(load_case("case3")["inputs"], main_spring_mode="manual", main_spring_wire_section="round")
    with pytest.raises(InputError, match="main_spring_wire_size_mm: missing"):
        schema.validate(raw)


def test_cli_bad_input_exit_2_no_traceback(tmp_path, capsys):
    bad = tmp_path / "bad.yaml"
    bad.write_text("inputs:\n  differential_angle_deg: abc\n  working_arm_mm: -1\n")
    assert main(["flowchart", str(bad)]) == 2
    err = capsys.readouterr().err
    assert "differential_angle_deg: got 'abc'" in err and "working_arm_mm: got -1" in err
    assert "Traceback" not in err


def test_cli_missing_file_and_bad_yaml(tmp_path, capsys):
    assert main(["flowchart", str(tmp_path / "nope.yaml")]) == 2
    broken = tmp_path / "broken.yaml"
    broken.write_text("inputs: [unclosed\n")
    assert main(["flowchart", str(broken)]) == 2
    err = capsys.readouterr().err
    assert "input file" in err and "valid YAML" in err
