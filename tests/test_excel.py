"""The Excel input template and its reader (issue 6): template -> filled workbook -> same input as YAML."""

from __future__ import annotations

import re

import pytest
from openpyxl import load_workbook

from conftest import load_case
from synth import cli, flowchart, schema
from synth.io import documents
from synth.errors import InputError
from synth.excel import reader, template


def _rows(ws) -> dict[str, int]:
    """Field key (column B) -> row, found like a user would: below the 'Field' header."""
    out, started = {}, False
    for r in range(1, ws.max_row + 1):
        v = ws[f"B{r}"].value
        if v == "Field":
            started = True
        elif started and v:
            out[v] = r
    return out


def _fill(path, values: dict) -> None:
    """Type ``values`` into the template at ``path`` as an engineer would (selectors included)."""
    wb = load_workbook(path)
    ws = wb["Input"]
    rows = _rows(ws)
    for f in schema.FIELDS:
        r = rows[f.name]
        v = values.get(f.name)
        cell = template.format_cell_value(f, v)
        if f.name in template.STANDARD_CUSTOM:
            ws[f"D{r}"] = "standard" if v is None else "custom"
            ws[f"E{r}"] = cell
        elif f.choices:
            ws[f"D{r}"] = cell if v is not None else f.default
        else:
            ws[f"E{r}"] = cell
    wb.save(path)


@pytest.fixture
def blank(tmp_path):
    path = tmp_path / "input.xlsx"
    assert cli.main(["template", str(path)]) == 0
    return path


def test_template_shape(blank):
    wb = load_workbook(blank)
    ws = wb["Input"]
    rows = _rows(ws)
    # every schema field has its row, in the schema's sections order
    assert set(rows) == {f.name for f in schema.FIELDS}
    assert [ws[f"A{r}"].value for r in range(1, ws.max_row + 1) if ws[f"A{r}"].value in schema.SECTIONS] \
        == list(schema.SECTIONS)
    headers = [ws.cell(row=4, column=j).value for j in range(1, 9)]
    assert headers == ["Parameter", "Field", "Unit", "Selector", "Value", "Required", "Data read",
                       "Suggested correction"]
    # units and optional marks
    r = rows["differential_angle_deg"]
    assert ws[f"C{r}"].value == "deg" and ws[f"F{r}"].value == "required" and ws[f"E{r}"].value == 85
    assert ws[f"F{rows['wrap_angle_deg']}"].value == "optional"
    # a drop-down on every field with choices or a catalog, listing exactly those choices
    lists = wb["Lists"]
    covered = {}
    for dv in ws.data_validations.dataValidation:
        if dv.type == "list":
            col = re.search(r"\$([A-Z]+)\$2", dv.formula1).group(1)
            items = [c.value for c in lists[col][1:] if c.value is not None]
            for rng in dv.sqref.ranges:
                covered[rng.coord] = items
    for f in schema.FIELDS:
        if f.choices or f.catalog:
            cell = f"{template.value_column(f)}{rows[f.name]}"
            assert cell in covered, f.name
            expected = list(f.choices) if f.choices else schema.catalog.keys(f.catalog)
            assert covered[cell] == [str(x) for x in expected]
    assert covered[f"D{rows['pivot_class_diameter_mm']}"] == ["standard", "custom"]
    # the colour legend
    legend = [ws[f"K{r}"].value for r in range(5, 5 + len(template.LEGEND))]
    assert legend == [m for _, m in template.LEGEND]
    assert ws["J5"].fill.start_color.rgb.endswith(template.FILLS["required"])


def test_template_example_is_case1(blank):
    assert documents.load_input(blank) == schema.validate(load_case("case1")["inputs"])


def test_filled_with_case3_gives_case3(blank):
    case3 = load_case("case3")["inputs"]
    _fill(blank, case3)
    from_xlsx = documents.load_input(blank)
    assert from_xlsx == schema.validate(case3)
    assert from_xlsx.wrap_angle_deg is None and from_xlsx.pivot_class_diameter_mm == 20
    r1 = flowchart.run(from_xlsx).to_dict()
    r2 = flowchart.run(schema.validate(case3)).to_dict()
    assert r1 == r2
    assert r1["values"]["pivot_diameter_mm"] == pytest.approx(21.0)   # case 3 Table 14


def test_standard_selector_reads_empty(blank):
    wb = load_workbook(blank)
    ws = wb["Input"]
    r = _rows(ws)["pivot_class_diameter_mm"]
    ws[f"D{r}"] = "standard"   # the value 16 in E is then ignored: Table 2 standard
    wb.save(blank)
    assert documents.load_input(blank).pivot_class_diameter_mm is None


def _set(path, field, value, col=None):
    wb = load_workbook(path)
    ws = wb["Input"]
    r = _rows(ws)[field]
    cell = f"{col or template.value_column(schema.field_by_name(field))}{r}"
    ws[cell] = value
    wb.save(path)
    return cell


def test_invalid_cell_is_named(blank):
    cell = _set(blank, "differential_angle_deg", 200)
    with pytest.raises(InputError, match=rf"differential_angle_deg \(sheet Input, cell {cell}\): got 200"):
        documents.load_input(blank)


def test_text_in_number_cell_and_bad_choice_all_reported(blank):
    c1 = _set(blank, "working_arm_mm", "five")
    c2 = _set(blank, "application_type", "wet")
    with pytest.raises(InputError) as exc:
        documents.read_mapping(blank)
    fields = [p.field for p in exc.value.problems]
    assert f"working_arm_mm (sheet Input, cell {c1})" in fields
    assert f"application_type (sheet Input, cell {c2})" in fields
    assert c2.startswith("D") and c1.startswith("E")


def test_missing_required_and_custom_without_value(blank):
    _set(blank, "belt_width_mm", None)
    _set(blank, "loading_arm_mm", None)   # selector stays 'custom'
    with pytest.raises(InputError) as exc:
        documents.read_mapping(blank)
    msgs = [str(p) for p in exc.value.problems]
    assert any(re.match(r"belt_width_mm \(sheet Input, cell E\d+\): missing", m) for m in msgs)
    assert any(re.match(r"loading_arm_mm \(sheet Input, cell E\d+\): missing; expected a value \(the selector", m)
               for m in msgs)


def test_unknown_key_named_with_its_cell(blank):
    wb = load_workbook(blank)
    ws = wb["Input"]
    r = _rows(ws)["working_arm_mm"]
    ws[f"B{r}"] = "working_arm_lenght_mm"
    wb.save(blank)
    with pytest.raises(InputError, match=rf"working_arm_lenght_mm \(sheet Input, cell B{r}\)"):
        documents.read_mapping(blank)


def test_cli_reports_the_cell(blank, capsys):
    cell = _set(blank, "differential_angle_deg", 0)
    assert cli.main(["flowchart", str(blank)]) == 2
    assert f"differential_angle_deg (sheet Input, cell {cell})" in capsys.readouterr().err


def test_cli_template_refuses_overwrite_and_fills_from(blank, tmp_path, capsys):
    assert cli.main(["template", str(blank)]) == 2
    out = tmp_path / "case3.xlsx"
    src = tmp_path / "case3.yaml"
    import yaml
    src.write_text(yaml.safe_dump({"inputs": load_case("case3")["inputs"]}))
    assert cli.main(["template", str(out), "--from", str(src)]) == 0
    assert documents.load_input(out) == schema.validate(load_case("case3")["inputs"])


def test_wire_size_list_round_trip(blank):
    _set(blank, "main_spring_wire_size_mm", "2.3 x 2.3")
    assert reader.read_workbook(blank)["main_spring_wire_size_mm"] == [2.3, 2.3]
    _set(blank, "main_spring_wire_size_mm", "2.3 x abc")
    with pytest.raises(InputError, match=r"main_spring_wire_size_mm \(sheet Input, cell E\d+\)"):
        reader.read_workbook(blank)


def test_not_a_workbook(tmp_path):
    bad = tmp_path / "x.xlsx"
    bad.write_text("not a zip")
    with pytest.raises(InputError, match="a valid .xlsx workbook"):
        documents.read_mapping(bad)
    with pytest.raises(InputError, match="an existing .xlsx"):
        documents.read_mapping(tmp_path / "missing.xlsx")
