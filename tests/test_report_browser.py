"""The design report looked at in a real browser (headless Chromium), and printed to PDF (issue 15).

Chromium computes the background colour of every output-table row and every check row; each must be
the colour of its own verdict, computed here from the Result (``row_verdict`` for an output row, the
check's verdict for a check row). Skips only where no Chromium binary exists (Debian ``chromium``:
``.ci/run`` installs it).
"""

from __future__ import annotations

import html.parser
import json
import re
import subprocess
import tempfile
from pathlib import Path

import pytest

from conftest import CASES
from synth.design.result import FAIL, NOT_APPLICABLE, PASS, WARNING, row_verdict
from synth.output_table import ROWS
from synth.report.html import VERDICT_COLOURS
from synth.report.pdf import chromium_binary, page_count, write_pdf
from synth.scenes.report import make_report

CHROMIUM = chromium_binary()
needs_browser = pytest.mark.skipif(CHROMIUM is None, reason="no chromium binary (apt-get install chromium)")

#: appended to a copy of the report: writes each row's effective cell colours (a cell's own background, else
#: its row's) into ``data-bg`` for --dump-dom to carry out
_PROBE = """<script>
for (const tr of document.querySelectorAll("tr[data-verdict]")) {
  const row = getComputedStyle(tr).backgroundColor;
  const cells = [...tr.children].map(td => {
    const own = getComputedStyle(td).backgroundColor;
    return own === "rgba(0, 0, 0, 0)" ? row : own;
  });
  tr.setAttribute("data-bg", JSON.stringify(cells));
}
</script>"""


def _rgb(hex_colour: str) -> str:
    h = hex_colour.lstrip("#")
    return "rgb({}, {}, {})".format(*(int(h[i:i + 2], 16) for i in (0, 2, 4)))


class _Rows(html.parser.HTMLParser):
    """Every ``<tr>`` with ``data-bg``: its section, data-key / data-check, verdict and cell colours."""

    def __init__(self):
        super().__init__()
        self.rows, self.section = [], None

    def handle_starttag(self, tag, attrs):
        a = dict(attrs)
        if tag == "section":
            self.section = a.get("id")
        if tag == "tr" and "data-bg" in a:
            self.rows.append({"section": self.section, "key": a.get("data-key"), "check": a.get("data-check"),
                              "verdict": a.get("data-verdict"), "bg": json.loads(a["data-bg"])})


def computed_rows(report_html: Path) -> list:
    """The rows of the report as Chromium computes them (screen media)."""
    with tempfile.TemporaryDirectory() as tmp:
        probe = Path(tmp) / "probe.html"
        probe.write_text(report_html.read_text(encoding="utf-8").replace("</body>", _PROBE + "</body>"),
                         encoding="utf-8")
        out = subprocess.run([CHROMIUM, "--headless", "--no-sandbox", "--disable-gpu", f"--user-data-dir={tmp}/p",
                              "--dump-dom", probe.as_uri()], capture_output=True, timeout=120, check=True)
    parser = _Rows()
    parser.feed(out.stdout.decode("utf-8"))
    return parser.rows


@pytest.fixture(scope="module")
def case1(tmp_path_factory):
    out = tmp_path_factory.mktemp("browser1")
    return make_report(CASES / "case1.yaml", out, show_progress=False, author="A. Engineer", revision="B")


@pytest.fixture(scope="module")
def case3(tmp_path_factory):
    out = tmp_path_factory.mktemp("browser3")
    return make_report(CASES / "case3.yaml", out, show_progress=False, cad_pictures=False, pdf=False)


def _check_colours(report: dict) -> dict:
    result = report["result"]
    rows = computed_rows(report["html"])
    output = [r for r in rows if r["section"] == "output"]
    checks = [r for r in rows if r["section"] == "checks"]
    # every row is there (the test cannot pass on an empty page)
    assert [r["key"] for r in output] == [key for _, _, key, _ in ROWS]
    assert sorted(r["check"] for r in checks) == sorted(c.id for c in result.checks if c.verdict != NOT_APPLICABLE)
    for r in output:
        want = row_verdict(result, r["key"])
        assert r["verdict"] == (want or "")
        assert set(r["bg"]) == {_rgb(VERDICT_COLOURS[want])}, (r["key"], want, r["bg"])
    for r in rows:
        if r["check"] is None:
            continue
        want = result.check(r["check"]).verdict
        assert r["verdict"] == want
        assert set(r["bg"]) == {_rgb(VERDICT_COLOURS[want])}, (r["section"], r["check"], want, r["bg"])
    return {"output": output, "checks": checks, "all": rows}


@needs_browser
def test_case1_every_row_has_its_own_verdict_colour(case1):
    rows = _check_colours(case1)
    result = case1["result"]
    # case 1's synthesis fails three or more checks: red rows, but only where a failing check reads the value
    red = {r["key"] for r in rows["output"] if r["bg"][0] == _rgb(VERDICT_COLOURS[FAIL])}
    failing_keys = {k for c in result.failed() for k in (c.constraint.value, c.constraint.limit)}
    assert red and red <= failing_keys
    green = [r for r in rows["output"] if r["bg"][0] == _rgb(VERDICT_COLOURS[PASS])]
    assert len(green) >= 10 and len(red) < len(green)
    # the digest lists the failing checks first, worst first, in red; then the warnings in amber
    digest = [r for r in rows["all"] if r["section"] == "digest"]
    failed = [r["check"] for r in digest if r["verdict"] == FAIL]
    assert failed == [c.id for c in sorted(result.failed(), key=lambda c: c.margin)]
    assert [r["check"] for r in digest if r["verdict"] == WARNING] and digest[0]["verdict"] == FAIL


@needs_browser
def test_case3_every_row_has_its_own_verdict_colour(case3):
    rows = _check_colours(case3)
    # no axial damping: the cone spring and plastic-element rows do not apply (grey), they are not "missing"
    grey = {r["key"] for r in rows["output"] if r["bg"][0] == _rgb(VERDICT_COLOURS[NOT_APPLICABLE])}
    assert {"cone_spring_fax_max_tolerance_n", "damper_pad_contact_area_mm2", "axial_damping_nm"} <= grey


def test_report_structure_digest_first_metadata_and_cad(case1):
    text = case1["html"].read_text(encoding="utf-8")
    order = [text.index(f'id="{s}"') for s in ("digest", "contents", "metadata", "design", "output", "checks",
                                              "cad", "graphs", "inputs")]
    assert order == sorted(order)
    for a in re.findall(r'<a href="#([\w-]+)">', text):          # the table of contents links resolve
        assert f'id="{a}"' in text
    assert "A. Engineer" in text and "revision B" in text
    from synth.fingerprint import version_text
    assert version_text() in text
    import hashlib
    sha = hashlib.sha256((CASES / "case1.yaml").read_bytes()).hexdigest()
    assert sha in text
    # the 3D model's section and exploded pictures, embedded (data: URIs only)
    assert len(re.findall(r'<figure id="fig-cad_\d+" class="cad"[^>]*>\s*<img[^>]*src="data:image/png;base64,', text)) == 2
    assert not re.search(r'src="(?!data:)', text)
    # the model settings in words, not "friction circle True"
    assert "friction circle r_p sin(atan mu)" in text and "friction circle True" not in text
    # print layout: A4, title block margin boxes, page breaks, repeated headers, rows kept whole
    for css in ("size: A4 landscape", "@bottom-left", 'counter(page) " of " counter(pages)',
                "section.page{break-before:page}", "thead{display:table-header-group}", "break-inside:avoid"):
        assert css in text


def test_pdf_beside_the_html_has_pages(case1):
    pdf = case1["pdf"]
    assert pdf is not None, case1["pdf_note"]
    assert pdf == case1["html"].with_suffix(".pdf") and pdf.read_bytes()[:5] == b"%PDF-"
    # digest, document, design, output table, checks, 3D model, graphs, input: at least one page each
    assert page_count(pdf) >= 8


@needs_browser
def test_chromium_prints_the_same_report(case1, tmp_path):
    path, engine, note = write_pdf(case1["html"], tmp_path / "chromium.pdf", engine="chromium")
    assert engine == "chromium" and note == "" and page_count(path) >= 8


def test_pdf_engine_errors_are_reported_not_raised(tmp_path, monkeypatch):
    monkeypatch.setenv("PATH", str(tmp_path))                      # no browser on the PATH
    html = tmp_path / "r.html"
    html.write_text("<p>x</p>")
    path, engine, note = write_pdf(html, engine="chromium")
    assert path is None and engine == "" and "chromium" in note


def test_report_of_an_input_shows_the_design_synth_design_finds(case1, tmp_path, capsys):
    from synth import cli
    cli.main(["design", str(CASES / "case1.yaml"), "--json"])
    printed = json.loads(capsys.readouterr().out)
    assert case1["result"].parts == printed["parts"]          # same design, same (default) fidelity
    assert case1["result"].settings == printed["settings"]
    saved = tmp_path / "design.json"
    saved.write_text(json.dumps(printed))
    again = make_report(saved, tmp_path / "rep", show_progress=False, cad_pictures=False, pdf=False)
    assert again["result"].parts == printed["parts"]
    assert [c.margin for c in again["result"].checks] == [c.margin for c in case1["result"].checks]
    assert str(saved) in again["html"].read_text(encoding="utf-8")   # the document block names the result file


def test_platform_section_hook(case1, tmp_path):
    """``synth report --platform DIR``: the section the rationalisation wrote, in the report and its contents."""
    from synth.errors import InputError
    from synth.platform.outputs import write_all
    from synth.platform.rationalise import rationalise
    from synth.platform.synthetic import synthetic_portfolio
    from synth.report.html import render_html
    pf = synthetic_portfolio(6, seed=1)
    r = rationalise(pf, time_limit=30)
    write_all(pf, r, tmp_path / "platform-out")
    text = render_html(case1["result"], [], [], platform=tmp_path / "platform-out")
    assert 'id="platform"' in text and 'href="#platform"' in text
    assert f"{r.n_parts} distinct parts" in text and text.count("data:image/png;base64,") >= 1
    assert 'id="platform"' not in render_html(case1["result"], [], [])
    with pytest.raises(InputError, match="--platform"):
        render_html(case1["result"], [], [], platform=tmp_path)   # a folder without section.html
    # the folder is the user's: a section.html edited to carry script reaches the report without it, while
    # what synth rationalise wrote passes through whole (same text, same tables, same embedded pictures)
    from synth.platform.outputs import report_section, saved_section
    written = report_section(r)
    assert saved_section(written).count("<td>") == written.count("<td>")
    assert saved_section(written).count("data:image/png;base64,") == written.count("data:image/png;base64,")
    hostile = tmp_path / "hostile"
    hostile.mkdir()
    (hostile / "section.html").write_text(
        '<section id="platform"><script>alert(1)</script><p onmouseover="alert(2)">served</p>'
        '<img src="javascript:alert(3)"><iframe src="https://example.org"></iframe>'
        '<style>body{display:none}</style><a href="javascript:alert(4)">x</a></section>', encoding="utf-8")
    text = render_html(case1["result"], [], [], platform=hostile)
    section = text[text.index('<section id="platform">'):]
    section = section[:section.index("</section>")]
    assert "served" in section
    for live in ("<script", "onmouseover", "javascript:", "<iframe", "<style", "<a "):
        assert live not in section.lower(), live
