"""``synth ui`` without a browser: the form from the schema, the design session on the API, the HTML, the scene.

The browser tests (``tests/test_ui_browser.py``) drive the pages; here the pieces under them are checked
against the paths they stand for: the command line's messages, :func:`synth.verify`, :func:`synth.load`
of the files the page saves, the report's rows.
"""

from __future__ import annotations

import socket

import pytest

import synth
from synth import catalog, formatting as fmt, schema
from synth.cli import main
from synth.design.result import Check, Result
from synth.report.palette import VERDICT_FILLS
from synth.errors import InputError
from synth.ui import form, views
from synth.ui.session import DesignSession, default_values


@pytest.fixture(scope="module")
def designed():
    s = DesignSession(default_values(), source="default")
    s.synthesise()
    return s


def test_every_schema_field_has_its_widget_options_and_accepted_values():
    for f in schema.FIELDS:
        if f.choices or f.catalog:
            assert form.widget(f) == "select"
            assert list(form.options(f)) == list(f.choices or catalog.keys(f.catalog))
        else:
            assert form.widget(f) == "text"
        assert form.hint(f).startswith(f.accepted())
    assert [s for s, _ in form.sections()] == list(schema.SECTIONS)
    assert sum(len(fs) for _, fs in form.sections()) == len(schema.FIELDS)


def test_a_box_is_read_as_the_same_text_in_a_yaml_file_would_be():
    assert [form.value_of(t) for t in ("62", "62.5", "2,5", "", "[2.3, 2.3]", "Autosetting", "yes")] == \
        [62, 62.5, "2,5", None, [2.3, 2.3], "Autosetting", "yes"]
    with pytest.raises(InputError, match="at most 200 characters"):
        form.mapping({"pulley_diameter_mm": "9" * 201})


def test_an_edit_reverifies_the_design_as_synth_verify_does(designed):
    s = DesignSession(default_values())
    s.synthesise()
    parts = dict(s.result.parts)
    assert s.edit("spring_stiffness_nm_per_deg", "1.5")
    ref = synth.verify({**default_values(), "spring_stiffness_nm_per_deg": 1.5}, parts)
    assert s.result.parts == parts and s.result.status == "verified"
    assert [(c.id, c.verdict, c.value) for c in s.result.checks] == [(c.id, c.verdict, c.value) for c in ref.checks]
    assert s.result.check("spring_yield").verdict == "fail"


def test_a_bad_value_gets_the_command_lines_message_and_keeps_the_last_result(designed, tmp_path, capsys):
    import yaml
    s = DesignSession(default_values())
    s.synthesise()
    before = s.seq
    assert not s.edit("working_arm_mm", "abc")
    bad = tmp_path / "bad.yaml"
    bad.write_text(yaml.safe_dump({**default_values(), "working_arm_mm": "abc"}), encoding="utf-8")
    assert main(["flowchart", str(bad)]) == 2
    err = capsys.readouterr().err
    assert s.problems == {"working_arm_mm": [err.splitlines()[1].strip()[2:]]}
    assert s.seq == before and s.result is not None


def test_the_saved_yaml_and_excel_template_load_back_to_the_same_input(designed, tmp_path):
    y = tmp_path / "in.yaml"
    y.write_text(designed.yaml_text(), encoding="utf-8")
    assert synth.load(y) == designed.input
    x = designed.write_template(tmp_path / "in.xlsx")
    assert synth.load(x) == designed.input
    other = DesignSession()
    assert other.load(x) and other.input == designed.input and other.result.parts == designed.result.parts


def test_a_file_in_the_thesiss_words_fills_the_drop_downs_with_their_choices(tmp_path):
    import yaml
    f = tmp_path / "words.yaml"
    f.write_text(yaml.safe_dump({**default_values(), "belt_loading_type": "Autosetting", "loading_arm_mm": None}),
                 encoding="utf-8")
    s = DesignSession()
    assert s.load(f)
    assert s.texts["belt_loading_type"] == "single_eccentric"


def test_the_checks_table_is_the_reports_rows_in_the_verdict_palette(designed):
    html = views.checks_table(designed.result)
    shown = [c for c in designed.result.checks if c.verdict != "not applicable"]
    assert html.count("data-check=") == len(shown)
    for c in shown:
        assert f'data-check="{c.id}" data-verdict="{c.verdict}" style="background:#{VERDICT_FILLS[c.verdict].lower()}"' in html


def test_every_text_of_a_result_is_escaped_for_html():
    r = Result("verified", parts={"ball_bearing": "<b>6006</b>"}, notes=["a < b"],
               checks=[Check("bearing_load", None, None, None, "not verified", note="<script>x</script>")],
               diagnosis={"message": "<i>binds</i>", "relaxations": []})
    out = views.checks_table(r) + views.parts_table(r) + views.diagnosis_html(r)
    assert "<script>" not in out and "&lt;script&gt;" in out
    assert "<b>6006" not in out and "<i>binds" not in out


def test_alternatives_list_the_ranked_designs_a_result_carries(designed):
    assert "No alternatives" in views.alternatives_html(Result("optimal"))
    r = Result("optimal", alternatives=[
        {"rank": 1, "objectives": {"standard": 2.0, "cost": 1.5723}, "margin": 0.0003, "binding": "coil gap",
         "differs": {}},
        {"rank": 2, "objectives": {"standard": 2.0, "cost": 1.5723}, "margin": 0.0109, "binding": "Goodman",
         "differs": {"main_spring_mean_body_diameter_mm": [32.0, 36.0]}}])
    html = views.alternatives_html(r)
    assert "<td>1</td><td>non-standard parts 2 (weighted count), cost 1.572 EUR</td><td>+0.03 %</td>" in html
    assert "main_spring_mean_body_diameter_mm 32 -&gt; 36" in html


def test_the_scene_refuses_a_bad_input_and_a_busy_port_before_serving(tmp_path, capsys):
    bad = tmp_path / "bad.yaml"
    bad.write_text("pulley_diameter_mm: 500\n", encoding="utf-8")
    assert main(["ui", str(bad)]) == 2
    assert "pulley_diameter_mm: got 500; accepted: a number in [10, 200] mm" in capsys.readouterr().err
    assert main(["ui", "--port", "0"]) == 2
    assert "--port: got 0; accepted: a TCP port in [1, 65535]" in capsys.readouterr().err
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        s.listen()
        port = s.getsockname()[1]
        assert main(["ui", "--port", str(port)]) == 2
    assert f"--port: got {port}; accepted: a free port on 127.0.0.1" in capsys.readouterr().err


def test_a_portfolio_row_opens_as_the_input_synth_bulk_read():
    from synth.bulk.portfolio import records
    from synth.ui.portfolio import PortfolioSession
    p = PortfolioSession()
    p.sample(5, seed=2)
    assert len(p.run(slices=2, min_slice=1)) == 5
    table_rows, cols = p.rows(), [c["name"] for c in p.columns()]
    assert cols[:3] == ["#", "application_id", "verdict"] and [r["#"] for r in table_rows] == list(range(5))
    assert p.application(3) == records(p.table)[3]
    whole = synth.screen(p.table, progress=False)
    assert list(whole["feasible"]) == list(p.results["feasible"])  # slices give the rows of one call


def _ruled(tmp_path, name="ACME rev C", margin="50 %"):
    import yaml
    path = tmp_path / "ruled.yaml"
    path.write_text(yaml.safe_dump({**default_values(), "rules": {"name": name, "min_margins": {"spring_yield": margin}}}),
                    encoding="utf-8")
    return path


def test_an_inputs_rules_judge_the_sessions_design_and_travel_with_its_yaml(tmp_path):
    """Issue 39: the page said "Verdict: PASS" for an input whose rules the command line judges infeasible."""
    path = _ruled(tmp_path)
    s = DesignSession()
    assert s.load(path)
    api = synth.synthesise(path)  # the input file's rules: section, as synth design reads it
    assert api.verdict == "fail" and s.result.verdict == "fail"
    assert s.result.status == api.status and s.result.rules == api.rules
    assert s.rule_lines()[0] == "design rules: ACME rev C (ruled.yaml: rules)"
    assert s.edit("spring_stiffness_nm_per_deg", "0.0164") and s.result.rules["name"] == "ACME rev C"  # verify too
    saved = tmp_path / "saved.yaml"
    saved.write_text(s.yaml_text(), encoding="utf-8")
    again = DesignSession()
    assert again.load(saved) and again.rules.min_margins == {"spring_yield": 0.5}
    plain = DesignSession(default_values())
    assert plain.synthesise().verdict == "pass" and plain.result.rules == {}  # no rules: none leak from the other


def test_bad_rules_in_an_input_are_refused_as_the_command_line_refuses_them(tmp_path, capsys):
    path = _ruled(tmp_path, margin="150 %")
    with pytest.raises(InputError) as e:
        DesignSession().read(path)
    assert main(["design", str(path)]) == 2
    cli = capsys.readouterr().err
    assert all(str(p) in cli for p in e.value.problems)
    assert main(["ui", str(path)]) == 2  # refused before serving


def test_the_servers_policy_host_origin_and_token():
    from synth.ui.guard import Policy, is_loopback

    def scope(**headers):
        return {"type": "http", "method": "GET", "path": "/", "query_string": b"",
                "headers": [(k.replace("_", "-").encode(), v.encode()) for k, v in headers.items()]}
    local = Policy.of("127.0.0.1", 8080)
    assert local.token is None and local.token_state(scope(host="127.0.0.1:8080")) == "ok"
    assert local.refusal(scope(host="[::1]:8080")) is None and local.refusal(scope(host="LOCALHOST:8080")) is None
    assert local.refusal(scope(host="127.0.0.1:8080", origin="http://localhost:8080"))[0] == 403  # not its Host
    assert local.refusal(scope(host="user@127.0.0.1:8080"))[0] == 403
    assert local.refusal(scope())[0] == 400
    assert local.origins() == ["http://127.0.0.1:8080", "http://[::1]:8080", "http://localhost:8080"]
    wide = Policy.of("0.0.0.0", 8080)
    assert not is_loopback("0.0.0.0") and wide.token and len(wide.token) >= 40
    assert wide.token_state(scope(host="127.0.0.1:8080")) == "missing"
    assert wide.token_state(scope(host="127.0.0.1:8080", cookie=f"{wide.cookie}={wide.token}")) == "ok"
    assert wide.token_state(scope(host="127.0.0.1:8080", authorization=f"token {wide.token}")) == "ok"
    assert wide.token_state({**scope(), "query_string": f"token={wide.token}".encode()}) == "query"
    assert wide.token_state(scope(cookie=f"{wide.cookie}=x{wide.token}")) == "missing"
    assert Policy.of("0.0.0.0", 8080).token != wide.token  # one per launch


# --- issue 35: what the pages show and what they keep ----------------------------------------------------------------
def test_a_portfolio_rows_verdict_is_the_design_pages_for_that_application():
    """Issue 35: a row marked feasible opened as "Verdict: INCOMPLETE". The screening's verdict column already said
    INCOMPLETE (a check not verified: the sample has no lock-up pin data); the table showed `feasible` instead, and
    the row opened at full fidelity whatever the screening's. Now the table shows the verdict in the design page's
    words and a row opens at the screening's fidelity."""
    from synth.ui.portfolio import PortfolioSession
    p = PortfolioSession()
    p.sample(12, seed=3)
    p.run(slices=1, min_slice=1, fidelity="screening")
    rows = p.rows()
    assert {r["verdict"] for r in rows} <= {"PASS", "INCOMPLETE", "FAIL"} and "INCOMPLETE" in {r["verdict"] for r in rows}
    for i in range(len(rows)):
        s = DesignSession(p.application(i), source="row")
        s.fidelity = p.fidelity
        assert s.synthesise().verdict.upper() == rows[i]["verdict"], i
    feasible_but_incomplete = [r for r, f in zip(rows, p.results["feasible"]) if f and r["verdict"] == "INCOMPLETE"]
    assert feasible_but_incomplete  # what the issue saw: feasible, yet INCOMPLETE (and now shown as such)


def test_the_table_says_what_binds_in_words_and_margins_in_percent():
    from synth.design.constraints import REGISTRY
    from synth.ui.portfolio import PortfolioSession
    p = PortfolioSession()
    p.sample(6, seed=1)
    p.run(slices=1, min_slice=1)
    labels = {c["name"]: c["label"] for c in p.columns()}
    assert labels["binding_margin"] == "its margin [%]" and labels["binding_constraint"] == "what binds"
    for row, (cid, m) in zip(p.rows(), zip(p.results["binding_constraint"], p.results["binding_margin"])):
        assert row["binding_constraint"] == REGISTRY[cid].label
        assert row["binding_margin"] == fmt.percent(m) and row["binding_margin_value"] == m  # as the design page
    assert ":sort" in next(c for c in p.columns() if c["name"] == "binding_margin")  # by the number, not the text


def test_a_portfolio_writes_every_file_the_page_names(tmp_path):
    """Issue 35: the rationalisation cites assignment.csv with no download."""
    import pandas as pd

    from synth.ui.portfolio import PortfolioSession
    p = PortfolioSession(tmp_path)
    p.sample(8, seed=4)
    p.run(slices=1, min_slice=1)
    assert pd.read_csv(p.write_results())["verdict"].tolist() == p.results["verdict"].tolist()
    assert "summary/summary.md" in p.write_summary()
    html = p.rationalise(time_limit=30)
    assert "assignment.csv" in html
    files = p.files()
    assert {"platform/assignment.csv", "platform/platform.csv", "results.csv"} <= set(files)
    assignment = pd.read_csv(files["platform/assignment.csv"])
    assert len(assignment) == 8


def test_a_box_keeps_every_digit_of_a_number_and_shows_it_rounded():
    """Issue 35: the pulley diameter showed 62.96956885569824; rounding the kept value instead would judge another
    application than the portfolio's row."""
    d = {**default_values(), "pulley_diameter_mm": 62.96956885569824, "spring_stiffness_nm_per_deg": 1.0e-2}
    s = DesignSession(d)
    assert s.input.pulley_diameter_mm == 62.96956885569824 and s.input.spring_stiffness_nm_per_deg == 0.01
    assert form.shown(s.texts["pulley_diameter_mm"]) == "62.97"


def test_the_objectives_offered_are_the_optimisers():
    from synth.optimise.objectives import OBJECTIVES as optimiser
    from synth.ui.session import offered_objectives
    assert offered_objectives() == tuple(optimiser) == ("standard", "cost", "margin")


def test_an_alternative_applied_is_that_design_verified_for_the_input(designed):
    s = DesignSession(default_values())
    s.top = 4
    best = s.synthesise()
    assert [a["rank"] for a in s.alternatives] == [1, 2, 3, 4] and s.applied == 1
    alt = s.alternatives[2]
    r = s.apply(3)
    ref = synth.verify(default_values(), alt["parts"])
    assert r.parts == alt["parts"] and s.applied == 3
    assert [(c.id, c.verdict, c.value) for c in r.checks] == [(c.id, c.verdict, c.value) for c in ref.checks]
    with pytest.raises(InputError, match="alternative: got 9; accepted: the rank of an alternative on offer: 1, 2, 3, 4"):
        s.apply(9)
    html = views.compare_alternatives(s.alternatives, s.applied)
    assert "#3 (in view)" in html and html.count("<th data-rank=") == 4
    assert best.parts == s.alternatives[0]["parts"]


def test_a_what_if_sweep_is_the_designs_verification_at_each_value():
    s = DesignSession(default_values())
    s.synthesise()
    data = s.sweep("spring_stiffness_nm_per_deg", 0.016, 0.024, 5)
    assert data["x"] == pytest.approx([0.016, 0.018, 0.020, 0.022, 0.024]) and data["design_x"] == 0.0164
    ref = synth.verify({**default_values(), "spring_stiffness_nm_per_deg": 0.022}, s.result.parts)
    assert data["margins"]["spring_yield"][3] == pytest.approx(ref.check("spring_yield").margin)
    m = data["margins"]["spring_yield"]  # a stiffer spring at the same travel: more stress, less margin
    assert all(a > b for a, b in zip(m, m[1:])) and m[0] > 0 > m[-1]  # the sweep crosses the limit
    from synth.ui import charts
    opts = charts.sweep(data, {c.id: c.label for c in s.result.checks})
    assert opts["series"][0]["name"] in ("main spring stress at installation within the permissible bending stress",
                                         "main spring Smith-Goodman safety factor")
    marks = opts["series"][0]["markLine"]["data"]
    assert marks[0]["xAxis"] == 0.0164 and marks[1]["yAxis"] == 0
    with pytest.raises(InputError, match="sweep range"):
        s.sweep("spring_stiffness_nm_per_deg", 0.02, 0.01)


def test_the_capability_panel_shows_every_figure_a_record_carries():
    """The robust API grows (the ISO 22514-2 percentile method, ppm for bounded outputs): a figure the panel does not
    know is shown in a column of its own, not dropped."""
    robust = {"targets": "Ppk >= 1.33", "meets": False, "min_ppk": 0.9, "max_p_violation": 1e-3,
              "failing": ["spring_yield"], "settings": {"samples": 4096, "seed": 1},
              "checks": [{"id": "spring_yield", "label": "main spring stress", "target": True, "meets": False,
                          "ppk": 0.9, "ppm": 1000.0, "p_violation": 1e-3, "p_lo": 5e-4, "p_hi": 2e-3,
                          "method": "percentile", "ppk_percentile": 0.95, "contributors": [["wire", 0.6]],
                          "nominal_margin": 0.05},
                         {"id": "bolt_yield", "label": "bolt", "target": False, "method": "deterministic"}]}
    table = views.capability_table(robust)
    assert "<th>ppk percentile</th>" in table and ">0.95<" in table and "wire 60 %" in table and "1000" in table and "bolt" not in table
    assert f'data-check="spring_yield" style="background:#{VERDICT_FILLS["fail"].lower()}"' in table
    summary = views.capability_summary(robust)
    assert "MISSES the target" in summary and "failing: main spring stress" in summary
    assert views.contributors(robust) == {"spring_yield": [("wire", 0.6)]}


def test_the_launchs_worker_opens_the_input_as_the_page_would_and_the_first_page_reads_no_catalog(tmp_path):
    """Issue 35 (cold start): the server's first page takes the state its design worker opened (the same gate, the
    same problems, the drop-downs' designations and hints) instead of validating, so its process loads neither pandas
    nor a catalog before the first checks."""
    import pickle
    import subprocess
    import sys

    from synth.ui import work
    bad = {**default_values(), "pulley_diameter_mm": 500}
    for values in (default_values(), bad):
        got = work.open_input(values, "x.yaml", None, [])
        mine = DesignSession(values, source="x.yaml")
        theirs = DesignSession(values, source="x.yaml", opened=got["opened"])
        assert theirs.opened_state() == mine.opened_state()
        assert theirs.opened_state() is not got["opened"] and theirs.texts is not got["opened"]["texts"]
    assert theirs.input is None and theirs.problems["pulley_diameter_mm"] == [
        "pulley_diameter_mm: got 500; accepted: a number in [10, 200] mm"]
    fields = [f for f in schema.FIELDS if f.catalog]
    assert got["keys"] == {**{f.catalog: catalog.keys(f.catalog) for f in fields},
                           **{"hint:" + f.name: f.accepted() for f in fields}}
    state = tmp_path / "opened.pickle"
    state.write_bytes(pickle.dumps(work.open_input(default_values(), "x.yaml", None, [])))
    code = f"""
import pickle, sys
from synth.ui import form
from synth.ui.session import DesignSession, default_values
got = pickle.loads(open({str(state)!r}, "rb").read())
form.KEYS.update({{(k, ()): v for k, v in got["keys"].items()}})
s = DesignSession(default_values(), opened=got["opened"])
texts = [(form.options(f), form.hint(f)) for _, fs in form.sections() for f in fs]
print(s.input is not None, "pandas" in sys.modules)
"""
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
    assert out.stdout.split() == ["True", "False"], out.stderr
