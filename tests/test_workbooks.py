"""Every workbook synth writes: text stays text, significant figures, verdict colours as conditional formats,
page setup; and the same workbooks opened by LibreOffice headless (colours evaluated by a real spreadsheet
program, an edited value recolours, formats and validations kept in a round trip, printed page counts).

The LibreOffice tests skip only where ``soffice`` is absent (Debian: ``apt-get install libreoffice-calc-nogui``;
``.ci/run`` installs it).
"""

from __future__ import annotations

import math
import re
import shutil
import subprocess
import zipfile
from html.parser import HTMLParser
from pathlib import Path

import pandas as pd
import pytest
from hypothesis import given, strategies as st
from openpyxl import load_workbook

from synth import flowchart
from synth.io import documents
from synth.bulk.portfolio import write_table
from synth.design.result import FAIL, NOT_VERIFIED, PASS, WARNING
from synth.data import CASES_DIR
from synth.excel import template
from synth.excel.cells import FORMULA_LEADS, put, sig_format
from synth.excel.results_workbook import row_verdict, write_results
from synth.excel.template import FILLS
from synth.output_table import ROWS

SOFFICE = shutil.which("soffice") or shutil.which("libreoffice")
needs_lo = pytest.mark.skipif(SOFFICE is None, reason="LibreOffice (soffice) not installed")

EVIL = ['=HYPERLINK("http://example.invalid","click")', "+1+2", "-3+4", "@SUM(A1)", "=1+1"]


@pytest.fixture(scope="module")
def case1_result():
    return flowchart.run(documents.load_input(CASES_DIR / "case1.yaml"))


@pytest.fixture(scope="module")
def results_xlsx(tmp_path_factory, case1_result):
    path = tmp_path_factory.mktemp("wb") / "results.xlsx"
    optimum = {"name": EVIL[0], "note": EVIL[1], "cost_eur": 1.71334077115234, "verdict": "fail"}
    return write_results(path, case1_result, source=str(CASES_DIR / "case1.yaml"),
                         scenes={"Optimum": optimum, "Pareto": [{"label": s, "margin": 0.1} for s in EVIL]})


@pytest.fixture(scope="module")
def template_xlsx(tmp_path_factory):
    return template.write_template(tmp_path_factory.mktemp("tpl") / "template.xlsx")


def _formula_elements(path: Path) -> int:
    with zipfile.ZipFile(path) as z:
        return sum(z.read(n).count(b"<f>") + z.read(n).count(b"<f ") for n in z.namelist()
                   if n.startswith("xl/worksheets/"))


# --- text is text --------------------------------------------------------------------------------------------

def test_text_from_scene_results_never_becomes_a_formula(results_xlsx):
    wb = load_workbook(results_xlsx)
    cells = [c for ws in wb for row in ws.iter_rows() for c in row if c.value in EVIL]
    assert len(cells) == len(EVIL) + 2  # every evil string of the Pareto rows, and two of the optimum
    for c in cells:
        assert c.data_type == "s" and c.quotePrefix, c.coordinate
    assert _formula_elements(results_xlsx) == 0


def test_bulk_tables_write_text_as_text(tmp_path):
    df = pd.DataFrame({"application": EVIL, "working_arm_mm": [5.0, 6.25, 7.0, 1.71334077115234, 8.0],
                       "n": [1, 2, 3, 4, 5]})
    p = write_table(df, tmp_path / "portfolio.xlsx")
    assert _formula_elements(p) == 0
    ws = load_workbook(p).active
    assert [ws.cell(row=r, column=1).value for r in range(2, 7)] == EVIL
    assert ws["B5"].number_format == "0.000" and ws["B5"].value == 1.71334077115234
    assert ws.page_setup.orientation == "landscape" and ws.print_title_rows.replace("$", "") == "1:1"
    back = pd.read_excel(p, engine="openpyxl")
    assert back["application"].tolist() == EVIL


@pytest.mark.parametrize("value", ["=1", "+x", "-", "@a", "\tx", "\rx", "plain", "a=b"])
def test_put_quote_prefix_only_where_a_spreadsheet_would_read_a_formula(value):
    from openpyxl import Workbook
    c = put(Workbook().active, 1, 1, value)
    assert c.data_type == "s" and c.value == value
    assert bool(c.quotePrefix) == value.startswith(FORMULA_LEADS)


# --- numbers: significant figures ---------------------------------------------------------------------------

@given(st.floats(min_value=1e-4, max_value=9.99e6, allow_nan=False))
def test_sig_format_shows_four_significant_figures(v):
    fmt = sig_format(v)
    decimals = len(fmt.split(".")[1]) if "." in fmt else 0
    decade = math.floor(math.log10(v))
    assert decade + 1 + decimals == max(4, decade + 1)  # 4 figures, or every integer digit of a large number


@given(st.one_of(st.floats(min_value=1e7, max_value=1e300), st.floats(min_value=1e-300, max_value=9.9e-5)))
def test_sig_format_scientific_outside_the_fixed_range(v):
    assert sig_format(v) == "0.000E+00" and sig_format(-v) == "0.000E+00"


def test_sig_format_edges():
    assert sig_format(0.0) == "0" and sig_format(7) == "0" and sig_format(True) == "General"
    assert sig_format(float("inf")) == "General" and sig_format("x") == "General"
    assert sig_format(-1.71334077115234) == "0.000"


def test_results_numbers_have_significant_figure_formats(results_xlsx, case1_result):
    ws = load_workbook(results_xlsx)["Output"]
    for i, (_, _, key, _) in enumerate(ROWS, start=5):
        v = ws[f"D{i}"].value
        if isinstance(v, float):
            assert ws[f"D{i}"].number_format == sig_format(v), key
            assert v == pytest.approx(case1_result.values[key], rel=1e-12)  # the full value is stored


# --- conditional formats, page setup ------------------------------------------------------------------------

def _rules(ws) -> list[tuple[str, str, str]]:
    return [(str(cf.sqref), r.formula[0], r.dxf.fill.bgColor.rgb[-6:]) for cf in ws.conditional_formatting
            for r in cf.rules]


def test_verdict_colours_are_conditional_formats(results_xlsx):
    wb = load_workbook(results_xlsx)
    out = _rules(wb["Output"])
    last = 4 + len(ROWS)
    for verdict in (PASS, FAIL, NOT_VERIFIED, WARNING):
        assert (f"D5:E{last}", f'$E5="{verdict}"', FILLS[verdict]) in out
    checks = {f: colour for cells, f, colour in _rules(wb["Checks"]) if cells.startswith("D5:")}
    assert checks['$I5="not verified"'] == FILLS[NOT_VERIFIED]
    assert checks['$I5="warning"'] == FILLS[WARNING]   # an advisory range left is amber, never red
    # a yes/no check (its value the text yes or no: nothing to compare) is coloured by its verdict
    assert checks['AND(NOT(ISNUMBER($D5)),$I5="fail")'] == FILLS[FAIL]
    assert checks['AND(NOT(ISNUMBER($D5)),$I5="pass")'] == FILLS[PASS]
    assert sorted(checks.values()) == sorted([FILLS[NOT_VERIFIED], FILLS[WARNING], FILLS[FAIL], FILLS[PASS],
                                              FILLS[FAIL], FILLS[PASS]])
    assert any("$D5" in f and "$F5" in f for f in checks)  # the colour follows value against limit
    assert {f: c for s, f, c in _rules(wb["Output"]) if s == "A2"}['ISNUMBER(SEARCH("FAIL",$A$2))'] == FILLS[FAIL]
    assert any(s.startswith("D") for s, *_ in _rules(wb["Optimum"]))  # the optimum's verdict column


def test_page_setup_of_every_sheet(results_xlsx, template_xlsx):
    for path in (results_xlsx, template_xlsx):
        wb = load_workbook(path)
        for ws in wb:
            if ws.sheet_state == "hidden":
                continue
            assert ws.page_setup.orientation == "landscape" and ws.page_setup.fitToWidth == 1, ws.title
            assert ws.page_setup.fitToHeight == 0 and ws.sheet_properties.pageSetUpPr.fitToPage
            assert ws.oddHeader.left.text and "&P of &N" in ws.oddFooter.right.text
    assert load_workbook(results_xlsx)["Checks"].print_title_rows.replace("$", "") == "4:4"
    assert load_workbook(template_xlsx)["Input"].print_title_rows.replace("$", "") == "4:4"


# --- LibreOffice headless ------------------------------------------------------------------------------------

def _soffice(args: list[str], out: Path) -> None:
    profile = out / "lo_profile"  # a private profile: parallel runs and a user's LibreOffice do not collide
    subprocess.run([SOFFICE, f"-env:UserInstallation=file://{profile}", "--headless", *args, "--outdir", str(out)],
                   check=True, capture_output=True, timeout=180)


def _convert(path: Path, fmt: str, out: Path) -> Path:
    out.mkdir(parents=True, exist_ok=True)
    _soffice(["--convert-to", fmt, str(path)], out)
    result = out / f"{path.stem}.{fmt.split(':')[0]}"
    assert result.is_file(), f"LibreOffice wrote no {result}"
    return result


class _Tables(HTMLParser):
    """Cells of LibreOffice's HTML export: tables -> rows -> (text, background colour)."""

    def __init__(self):
        super().__init__()
        self.tables: list[list[list[tuple[str, str | None]]]] = []
        self._cell = None

    def handle_starttag(self, tag, attrs):
        a = dict(attrs)
        if tag == "table":
            self.tables.append([])
        elif tag == "tr":
            self.tables[-1].append([])
        elif tag == "td":
            self._cell = ["", (a.get("bgcolor") or "").lstrip("#").upper() or None]

    def handle_data(self, data):
        if self._cell is not None:
            self._cell[0] += data

    def handle_endtag(self, tag):
        if tag == "td" and self._cell is not None:
            self.tables[-1][-1].append((self._cell[0].strip(), self._cell[1]))
            self._cell = None


def _rendered(path: Path, out: Path) -> list:
    parser = _Tables()
    parser.feed(_convert(path, "html", out).read_text(encoding="utf-8", errors="replace"))
    return parser.tables


@needs_lo
def test_libreoffice_evaluates_each_rows_colour_from_its_own_verdict(results_xlsx, case1_result, tmp_path):
    output, checks = _rendered(results_xlsx, tmp_path)[:2]
    r = case1_result
    for i, (section, label, key, _) in enumerate(ROWS, start=4):  # row 5 of the sheet is the 5th <tr>
        text, colour = output[i][4]
        verdict = row_verdict(r, key)
        assert (output[i][1][0], text or None) == (label, verdict)  # a row no check reads: blank
        assert colour == FILLS.get(verdict), (label, verdict, colour)
    # the sheet lists what applies, in the flowchart's step order
    listed = sorted((c for c in r.checks if c.verdict != "not applicable"), key=lambda c: c.constraint.step)
    assert len(checks) - 4 == len(listed)
    for i, c in enumerate(listed, start=4):
        assert checks[i][2][0] == c.label and checks[i][8][0] == c.verdict
        assert checks[i][8][1] == FILLS.get(c.verdict), (c.id, checks[i][8])
    assert {c.verdict for c in r.checks} >= {PASS, FAIL}


@needs_lo
def test_libreoffice_recolours_an_edited_value(results_xlsx, case1_result, tmp_path):
    failing = next(c for c in case1_result.checks if c.verdict == FAIL)
    passing = next(c for c in case1_result.checks if c.verdict == PASS and c.limit)
    wb = load_workbook(results_xlsx)
    ws = wb["Checks"]
    rows = {ws[f"C{r}"].value: r for r in range(5, ws.max_row + 1)}
    ws[f"D{rows[failing.label]}"] = failing.limit  # edited to the limit: passes
    ws[f"D{rows[passing.label]}"] = passing.limit + (1 if passing.constraint.sense == "<=" else -1) * abs(passing.limit)
    edited = tmp_path / "edited.xlsx"
    wb.save(edited)
    checks = _rendered(edited, tmp_path / "html")[1]
    assert checks[rows[failing.label] - 1][3][1] == FILLS[PASS]
    assert checks[rows[passing.label] - 1][3][1] == FILLS[FAIL]


@needs_lo
def test_libreoffice_round_trip_keeps_formats_validations_and_text(results_xlsx, template_xlsx, tmp_path):
    back = load_workbook(_convert(results_xlsx, "xlsx", tmp_path / "r"))
    ws = back["Output"]
    orig = load_workbook(results_xlsx)["Output"]
    formats = [(orig[f"D{i}"].number_format, ws[f"D{i}"].number_format) for i in range(5, 5 + len(ROWS))
               if isinstance(orig[f"D{i}"].value, float)]
    assert formats and all(a == b for a, b in formats), formats
    assert any('"fail"' in f for _, f, _ in _rules(ws))
    assert ws.page_setup.orientation == "landscape" and ws.page_setup.fitToWidth == 1
    pareto = back["Pareto"]
    assert [pareto.cell(row=r, column=1).value for r in range(4, 4 + len(EVIL))] == EVIL
    assert _formula_elements(tmp_path / "r" / "results.xlsx") == 0

    tpl = load_workbook(_convert(template_xlsx, "xlsx", tmp_path / "t"))["Input"]
    orig = load_workbook(template_xlsx)["Input"]
    def lists(ws):
        return sorted((dv.type, re.sub(r"^=", "", dv.formula1 or "").replace("'", ""), str(dv.sqref))
                      for dv in ws.data_validations.dataValidation)
    assert lists(tpl) == lists(orig) and len(lists(tpl)) > 10


@needs_lo
def test_printed_page_counts(results_xlsx, template_xlsx, tmp_path):
    """Before this change: the template printed as 23 portrait pages, the results as 9."""
    def pages(path):
        pdf = _convert(path, "pdf", tmp_path / path.stem).read_bytes()
        return len(re.findall(rb"/Type\s*/Page[^s]", pdf))
    assert pages(template_xlsx) <= 4  # measured 3: two of the table, one of the legend
    # measured 8 with the two scene sheets of this fixture (the Checks sheet lists every registry constraint,
    # about 70, on 3 pages)
    assert pages(results_xlsx) <= 8
