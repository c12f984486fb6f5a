"""Regenerate the README's pictures (docs/img/*.png) from their commands, and docs/img/pictures.json.

Run ``python docs/build_pictures.py`` (about 2 minutes on a shared 2-core machine: two syntheses, a 200-application
rationalisation, the 3D model with CadQuery, Chromium through Playwright for the report and the web page) after a
change that alters what a picture shows; ``python docs/build_pictures.py NAME...`` regenerates only those pictures
(``report_case1``...). ``python docs/build_pictures.py --check`` recomputes every fact by the pictures' own
commands (nothing drawn) and exits 1 on a drift the fast test cannot see (another design synthesised, another
rationalisation).

``pictures.json`` gives, per picture, the command that made it and the facts it shows that the code decides: the
design's parts, its verdict, the failing checks and their margins, a graph's plotted data, the 3D model's key
dimensions, the platform's trade-off. Not pixel hashes: those differ between machines and library versions.
``tests/test_pictures.py`` recomputes the facts with today's code by the cheap paths of :data:`FACTS` (a stored
design re-verified, the flowchart, no CadQuery or Chromium) and fails with "run python docs/build_pictures.py" when
they drift.
"""

from __future__ import annotations

import json
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
IMG = ROOT / "docs" / "img"
MANIFEST = IMG / "pictures.json"
CASE1 = "synth/data/cases/case1.yaml"
CASE1_AS_RUN = "synth/data/cases/case1_as_run.yaml"
#: the README's web example: the default application with this stiffness typed into the design page
UI_EDIT = {"spring_stiffness_nm_per_deg": 0.02}
CHROMIUM = "/usr/bin/chromium"

COMMANDS = {
    "report_case1": f'synth report {CASE1} --out DIR --no-cad --no-pdf --author "A. Engineer" --revision B; '
                    "Chromium headless, 1280x920 viewport, DIR/report.html's first screen",
    "hysteresis_case1": f"synth report {CASE1}'s graph hysteresis_torque (Fig. 16) of the same design "
                        '(synth.report.plots.graph_png("hysteresis_torque", result))',
    "ui_design": "synth ui; Chromium, 1400x860 viewport: the default application's design page after "
                 "spring_stiffness_nm_per_deg is typed as 0.02 (the page re-verifies the synthesised design)",
    "cad_section_case1": f"synth flowchart {CASE1_AS_RUN} --json R.json; synth cad R.json --out DIR --no-stl "
                         '(application named "thesis case 1 as run"): DIR/section.png',
    "cad_exploded_case1": "the same: DIR/exploded.png",
    "platform_tradeoff": "synth portfolio-sample 200 --out portfolio.csv; "
                         "synth rationalise portfolio.csv --out platform/: platform/tradeoff.png",
}


def sig(x, n: int = 4):
    """``x`` to ``n`` significant figures (a float; None and strings as they are)."""
    if x is None or isinstance(x, (str, bool)):
        return x
    x = float(x)
    return float(f"{x:.{n}g}") if x == x else None


def _plain(v):
    if hasattr(v, "item"):
        v = v.item()
    return sig(v) if isinstance(v, float) else v


def _exact(v):
    return v.item() if hasattr(v, "item") else v


def design_facts(d, parts: dict) -> dict:
    """The verdict, failing checks (margin, 3 significant figures) and parts of ``parts`` verified for input ``d``."""
    import synth
    r = synth.verify(d, parts)
    return {"parts": {k: _exact(v) for k, v in sorted(parts.items())}, "verdict": r.verdict,
            "failing": {c.id: sig(c.margin, 3) for c in r.checks if c.verdict == "fail"}}


def series_facts(series: dict) -> dict:
    """Each plotted series: its length, first, last, smallest and largest value (4 significant figures)."""
    import numpy as np
    out = {}
    for k, v in sorted(series.items()):
        a = np.asarray(v, float)
        out[k] = [int(a.size), sig(a[0]), sig(a[-1]), sig(a.min()), sig(a.max())]
    return out


def _report_case1(parts):
    import synth
    return design_facts(synth.load(ROOT / CASE1), parts)


def _hysteresis_case1(parts):
    import synth
    from synth.report.plots import graph_png
    r = synth.verify(synth.load(ROOT / CASE1), parts)
    g = graph_png("hysteresis_torque", r)
    return {"parts": design_facts(synth.load(ROOT / CASE1), parts)["parts"], "colour_of_verdict": g.verdict,
            "series": series_facts(g.series)}


def _ui_design(parts):
    from synth.ui.session import default_values
    d = default_values()
    before = design_facts(d, parts)
    after = design_facts({**d, **UI_EDIT}, parts)
    return {**after, "edit": UI_EDIT, "failing_before_the_edit": before["failing"],
            "turned_red": sorted(set(after["failing"]) - set(before["failing"]))}


def _ui_design_synthesised(_parts=None):
    """The web picture's facts from the default application synthesised now (2-3 s: the page's first design)."""
    import synth
    from synth.ui.session import default_values
    return _ui_design(dict(synth.synthesise(default_values()).parts))


def flowchart_case1():
    import synth
    from synth import flowchart
    return flowchart.run(synth.load(ROOT / CASE1_AS_RUN))


def _cad_case1(_parts=None):
    from synth.cad import geometry_from
    r = flowchart_case1()
    g = geometry_from(r, None).as_dict()
    return {"parts": {k: _exact(v) for k, v in sorted(r.parts.items())}, "verdict": r.verdict,
            "failing": {c.id: sig(c.margin, 3) for c in r.checks if c.verdict == "fail"},
            "geometry": {k: _plain(v) for k, v in sorted(g.items())}}


#: picture -> its facts from today's code; the argument is the design the manifest stores: case 1's synthesis (18 s)
#: is re-verified instead of repeated; the default application's (the web picture's) and the flowchart are rerun
FACTS = {"report_case1": _report_case1, "hysteresis_case1": _hysteresis_case1, "ui_design": _ui_design_synthesised,
         "cad_section_case1": _cad_case1, "cad_exploded_case1": _cad_case1}


def tradeoff_facts(rows: list) -> dict:
    """The platform trade-off: per margin floor, the parts and the applications served."""
    keep = ("margin_floor", "parts", "served", "worst_margin", "status")
    return {"rows": [{k: (sig(round(v, 6)) if isinstance(v, float) else v) for k, v in row.items() if k in keep}
                     for row in rows]}


# --- the pictures ------------------------------------------------------------------------------------------------

def _run(cmd: list, cwd: Path) -> str:
    import os
    env = {**os.environ, "PYTHONPATH": str(ROOT) + os.pathsep + os.environ.get("PYTHONPATH", "")}
    p = subprocess.run([sys.executable, "-m", "synth", *cmd], cwd=cwd, env=env, capture_output=True, text=True)
    if p.returncode not in (0, 1):
        raise RuntimeError(f"synth {' '.join(cmd)}: exit {p.returncode}\n{p.stdout}\n{p.stderr}")
    return p.stdout


def _screenshot(url: str, out: Path, width: int, height: int, action=None) -> None:
    from playwright.sync_api import sync_playwright
    from synth.ui.browser import launch_chromium
    with sync_playwright() as p:
        b = launch_chromium(p, CHROMIUM)
        try:
            pg = b.new_page(viewport={"width": width, "height": height})
            pg.set_default_timeout(300_000)
            if action is None:
                pg.goto(url)
            else:
                action(pg, url)
            pg.screenshot(path=str(out))
        finally:
            b.close()


def build_report_and_hysteresis(tmp: Path, draw: bool = True) -> dict:
    import synth
    from synth.report.plots import graph_png
    from synth.scenes.report import result_for_report
    r, _, _ = result_for_report(str(ROOT / CASE1), None)  # what `synth report case1.yaml` synthesises
    if draw:
        out = tmp / "report"
        synth.write_report(r, out, pdf=False, cad_pictures=False, author="A. Engineer", revision="B")
        _screenshot((out / "report.html").as_uri(), IMG / "report_case1.png", 1280, 920)
        (IMG / "hysteresis_case1.png").write_bytes(graph_png("hysteresis_torque", r).png)
    parts = dict(r.parts)
    shown = {"verdict": r.verdict, "failing": {c.id: sig(c.margin, 3) for c in r.checks if c.verdict == "fail"}}
    facts = _report_case1(parts)
    if {k: facts[k] for k in shown} != shown:  # the cheap path must tell what the picture shows
        raise RuntimeError(f"re-verified design differs from the report's: {facts} against {shown}")
    return {"report_case1": facts, "hysteresis_case1": _hysteresis_case1(parts)}


def build_ui(tmp: Path, draw: bool = True) -> dict:
    import synth
    from synth.ui.browser import free_port, goto_when_up, start_server, stop_server
    from synth.ui.session import default_values
    parts = dict(synth.synthesise(default_values()).parts)  # the page's first design
    if not draw:
        return {"ui_design": _ui_design(parts)}
    port = free_port()
    proc, _ = start_server(port)

    def edit(pg, url):
        goto_when_up(pg, url)
        pg.locator("table.checks tr[data-check]").first.wait_for()
        seq = int(pg.locator("[data-testid=seq]").get_attribute("data-seq") or 0)
        (field, value), = UI_EDIT.items()
        pg.locator(f"[data-field={field}] input").fill(str(value))
        pg.wait_for_function(f"Number(document.querySelector('[data-testid=seq]').dataset.seq) > {seq}")
        pg.locator(f"[data-field={field}]").evaluate("e => e.scrollIntoView({block: 'center'})")  # the edit in view
        pg.wait_for_timeout(1500)

    try:
        _screenshot(f"http://127.0.0.1:{port}/", IMG / "ui_design.png", 1400, 860, edit)
    finally:
        stop_server(proc)
    return {"ui_design": _ui_design(parts)}


def build_cad(tmp: Path, draw: bool = True) -> dict:
    from synth.cad import export_result
    r = flowchart_case1()
    if draw:
        export_result(r, tmp / "cad", stl=False, application="thesis case 1 as run")
        shutil.copyfile(tmp / "cad" / "section.png", IMG / "cad_section_case1.png")
        shutil.copyfile(tmp / "cad" / "exploded.png", IMG / "cad_exploded_case1.png")
    f = _cad_case1()
    return {"cad_section_case1": f, "cad_exploded_case1": f}


def _number(text: str):
    try:
        return float(text)
    except ValueError:
        return text


def build_platform(tmp: Path, draw: bool = True) -> dict:
    import csv
    _run(["portfolio-sample", "200", "--out", "portfolio.csv"], tmp)
    line = _run(["rationalise", "portfolio.csv", "--out", "platform/"], tmp).strip().splitlines()[0]
    if draw:
        shutil.copyfile(tmp / "platform" / "tradeoff.png", IMG / "platform_tradeoff.png")
    with open(tmp / "platform" / "tradeoff.csv", encoding="utf-8") as fh:
        rows = [{k: _number(v) for k, v in row.items()} for row in csv.DictReader(fh)]
    return {"platform_tradeoff": {"summary_line": line, **tradeoff_facts(rows)}}


BUILDERS = {"report_case1": build_report_and_hysteresis, "hysteresis_case1": build_report_and_hysteresis,
            "ui_design": build_ui, "cad_section_case1": build_cad, "cad_exploded_case1": build_cad,
            "platform_tradeoff": build_platform}


def read_manifest() -> dict:
    return json.loads(MANIFEST.read_text(encoding="utf-8")) if MANIFEST.exists() else {}


def main(argv: list[str]) -> int:
    """Regenerate the named pictures (all by default) and their facts; ``--check``: recompute every fact by the
    pictures' own commands (the syntheses and the rationalisation, not the test's cheap paths), draw nothing, and
    exit 1 naming each picture whose facts drifted."""
    import time
    check = "--check" in argv
    names = [a for a in argv if a != "--check"] or list(COMMANDS)
    unknown = sorted(set(names) - set(COMMANDS))
    if unknown:
        print(f"build_pictures: unknown picture(s) {unknown}; one of {sorted(COMMANDS)}", file=sys.stderr)
        return 2
    manifest = read_manifest()
    new, done = {}, set()
    with tempfile.TemporaryDirectory(prefix="synth-pictures-") as t:
        for name in names:
            builder = BUILDERS[name]
            if builder in done:
                continue
            done.add(builder)
            t0 = time.perf_counter()
            for pic, facts in builder(Path(t), draw=not check).items():
                new[pic] = {"command": COMMANDS[pic], "facts": json.loads(json.dumps(facts))}
            print(f"{builder.__name__}: {time.perf_counter() - t0:.1f} s", flush=True)
    if check:
        drifted = [p for p in new if manifest.get(p) != new[p]]
        for p in drifted:
            print(f"{p}: stored {manifest.get(p)}\n{' ' * len(p)}  today  {new[p]}")
        print(f"drifted: {', '.join(drifted)}: run python docs/build_pictures.py" if drifted else
              "every picture's facts are current")
        return 1 if drifted else 0
    manifest.update(new)
    ordered = {k: manifest[k] for k in COMMANDS if k in manifest}
    MANIFEST.write_text(json.dumps(ordered, indent=1, sort_keys=False) + "\n", encoding="utf-8")
    print(f"wrote {MANIFEST.relative_to(ROOT)}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
