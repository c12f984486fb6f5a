"""The readers against the hostile files of issue 20: time and peak memory of each, within the documented limits.

Run: ``.venv/bin/python benchmarks/bench_readers.py [--naive-timeout S]`` (prints a markdown table).

Each hostile file is small enough to pass the file-size limit of its reader (that is the point: they took
minutes before): an 8 MB flat YAML list, a 4 MB one, a JSON and a TOML of as many values, an .xlsx whose shared
strings unpack to 63 MB, one whose ``styles.xml`` unpacks to 38 MB, an .ods whose ``content.xml`` unpacks to 59 MB,
a user catalog of 50,000 wires and one of 1,600. Each is read in a fresh process through synth's gate (A) and,
side by side in the same run, by the plain parser synth used before (B: ``yaml.safe_load``, openpyxl, odfpy, the
design on the catalog), stopped at ``--naive-timeout`` seconds; the table gives wall time and peak resident
memory (``VmHWM``) of each, the outcome, and the ratio B/A of the times. The promise: A under 5 s and 1 GB
for every file.
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile
import textwrap
import zipfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))
MB = 1024 * 1024
_DESIGN = (ROOT / "synth" / "data" / "default_case.yaml").read_text(encoding="utf-8")
_ODS = ROOT / "tests" / "bad_inputs" / "files" / "lo_case3.ods"


def _rezip(src: Path, dst: Path, replace: dict) -> Path:
    with zipfile.ZipFile(src) as zin, zipfile.ZipFile(dst, "w", zipfile.ZIP_DEFLATED) as z:
        for i in zin.infolist():
            if i.filename not in replace:
                z.writestr(i, zin.read(i.filename))
        for name, data in replace.items():
            z.writestr(name, data)
    return dst


def _template(folder: Path) -> Path:
    from synth.excel.template import write_template
    p = folder / "template.xlsx"
    if not p.exists():
        write_template(p)
    return p


def yaml_flat_list(folder: Path, mb: float = 7.9) -> Path:
    """A design input whose ``inputs`` block ends with a flat list of ``mb`` MB (1.3 million values)."""
    p = folder / f"flat_{mb:g}MB.yaml"
    n = int(mb * MB / 6)
    p.write_text(_DESIGN + "  notes:\n" + "  - 1\n" * n, encoding="utf-8")
    return p


def json_flat_list(folder: Path, mb: float = 7.9) -> Path:
    p = folder / f"flat_{mb:g}MB.json"
    n = int(mb * MB / 2)
    p.write_text('{"inputs": {"notes": [' + ",".join(["1"] * n) + "]}}", encoding="utf-8")
    return p


def toml_many_keys(folder: Path, mb: float = 7.9) -> Path:
    p = folder / f"keys_{mb:g}MB.toml"
    n = int(mb * MB / 12)
    p.write_text("[inputs]\n" + "".join(f"k{i:07d} = 1\n" for i in range(n)), encoding="utf-8")
    return p


def xlsx_shared_strings(folder: Path, mb: float = 63) -> Path:
    """The template with ``mb`` MB of tiny shared strings (a 156 kB file)."""
    src = _template(folder)
    n = int(mb * MB / 17)
    sst = ('<?xml version="1.0" encoding="UTF-8"?><sst xmlns="http://schemas.openxmlformats.org/spreadsheetml/2006/'
           f'main" count="{n}" uniqueCount="{n}">' + "<si><t>a</t></si>" * n + "</sst>").encode()
    with zipfile.ZipFile(src) as z:
        ct = z.read("[Content_Types].xml").decode()
        rels = z.read("xl/_rels/workbook.xml.rels").decode()
    ct = ct.replace("</Types>", '<Override PartName="/xl/sharedStrings.xml" ContentType="application/vnd.openxmlformats-'
                                'officedocument.spreadsheetml.sharedStrings+xml"/></Types>')
    rels = rels.replace("</Relationships>", '<Relationship Id="rIdSS" Type="http://schemas.openxmlformats.org/'
                                            'officeDocument/2006/relationships/sharedStrings" Target="sharedStrings.xml"'
                                            "/></Relationships>")
    return _rezip(src, folder / f"shared_strings_{mb:g}MB.xlsx", {"[Content_Types].xml": ct.encode(),
                                                                  "xl/_rels/workbook.xml.rels": rels.encode(),
                                                                  "xl/sharedStrings.xml": sst})


def xlsx_styles(folder: Path, mb: float = 38) -> Path:
    """The template with a ``styles.xml`` of ``mb`` MB of fonts (a 120 kB file)."""
    n = int(mb * MB / 49)
    styles = ('<?xml version="1.0" encoding="UTF-8"?><styleSheet xmlns="http://schemas.openxmlformats.org/'
              f'spreadsheetml/2006/main"><fonts count="{n}">' + '<font><sz val="11"/><name val="Arial"/></font>' * n
              + '</fonts><fills count="1"><fill><patternFill patternType="none"/></fill></fills><borders count="1">'
              "<border/></borders><cellStyleXfs count=\"1\"><xf/></cellStyleXfs><cellXfs count=\"1\"><xf/></cellXfs>"
              "</styleSheet>").encode()
    return _rezip(_template(folder), folder / f"styles_{mb:g}MB.xlsx", {"xl/styles.xml": styles})


def ods_content(folder: Path, mb: float = 59) -> Path:
    """The LibreOffice template (.ods) with a sheet of ``mb`` MB of paragraphs in ``content.xml`` (176 kB)."""
    with zipfile.ZipFile(_ODS) as z:
        c = z.read("content.xml").decode()
    n = int(mb * MB / 18)
    i = c.index("</office:spreadsheet>")
    c = (c[:i] + '<table:table table:name="Junk"><table:table-row><table:table-cell office:value-type="string">'
         + "<text:p>x</text:p>" * n + "</table:table-cell></table:table-row></table:table>" + c[i:])
    return _rezip(_ODS, folder / f"content_{mb:g}MB.ods", {"content.xml": c.encode()})


def wire_catalog(folder: Path, n: int = 50_000) -> Path:
    """A user catalog folder whose ``spring_wires.csv`` has ``n`` wires (short sources: 2.6 MB for 50,000)."""
    d = folder / f"wires_{n}"
    d.mkdir(exist_ok=True)
    lines = (ROOT / "catalogs" / "spring_wires.csv").read_text().splitlines()
    head, rows = lines[0], [r.split(",") for r in lines[1:]]
    src = head.split(",").index("source")
    out = [head] + [",".join([f"U{i:05d}"] + r[1:src] + ["mine"]) for i, r in
                    ((i, rows[i % len(rows)]) for i in range(n))]
    (d / "spring_wires.csv").write_text("\n".join(out) + "\n")
    return d


#: hostile design inputs (read by ``synth.io.documents.load_input``), by name: a function of a folder -> the file
HOSTILE = {"yaml_flat_list": yaml_flat_list, "json_flat_list": json_flat_list, "toml_many_keys": toml_many_keys,
           "xlsx_shared_strings": xlsx_shared_strings, "xlsx_styles": xlsx_styles, "ods_content": ods_content}

_GATE = "from synth.io.documents import load_input\ntry:\n    load_input({path!r})\n    print('read')\nexcept Exception as e:\n    print('refused: ' + str(e).splitlines()[0][:90])\n"
_NAIVE = {
    ".yaml": "import yaml\nyaml.safe_load(open({path!r}).read())\nprint('read')\n",
    ".json": "import json\njson.load(open({path!r}))\nprint('read')\n",
    ".toml": "import tomllib\ntomllib.loads(open({path!r}).read())\nprint('read')\n",
    ".xlsx": ("from openpyxl import load_workbook\nfor d in (True, False):\n    wb = load_workbook({path!r}, read_only=True,"
              " data_only=d)\n    [r for r in wb.worksheets[0].iter_rows(max_row=2000, max_col=64)]\nprint('read')\n"),
    ".ods": "from odf.opendocument import load\nload({path!r})\nprint('read')\n",
}
_DESIGN_ON = ("import sys\nfrom synth.cli import main\ntry:\n    code = main(['--catalogs', {path!r}, 'design', "
              f"{str(ROOT / 'synth' / 'data' / 'default_case.yaml')!r}])\nexcept BaseException as e:\n    code = type(e).__name__\n"
              "print('exit', code)\n")


def _measure(code: str, timeout: float) -> tuple[str, float, float]:
    """(outcome, wall s, peak resident MB) of ``code`` in a fresh interpreter (killed after ``timeout`` s)."""
    # VmHWM (peak resident set of this process image): ru_maxrss would keep the forking parent's size
    wrapper = textwrap.dedent("""
        import sys, time
        t = time.perf_counter()
        exec(compile(sys.argv[1], "bench", "exec"))
        hwm = [ln for ln in open("/proc/self/status") if ln.startswith("VmHWM")][0].split()[1]
        print("@@", time.perf_counter() - t, int(hwm) / 1024)
    """)
    env = {**os.environ, "PYTHONPATH": str(ROOT), "SYNTH_CACHE_DIR": os.environ.get("SYNTH_CACHE_DIR", "")}
    try:
        p = subprocess.run([sys.executable, "-c", wrapper, code], capture_output=True, text=True, timeout=timeout,
                           env=env, cwd=str(ROOT))
    except subprocess.TimeoutExpired:
        return f"stopped after {timeout:g} s", timeout, float("nan")
    lines = p.stdout.strip().splitlines()
    stats = [ln for ln in lines if ln.startswith("@@")]
    if not stats:
        return f"crashed ({(p.stderr.strip().splitlines() or ['?'])[-1][:60]})", float("nan"), float("nan")
    _, t, mb = stats[-1].split()
    outcome = next((ln for ln in lines if not ln.startswith("@@")), "")
    return outcome, float(t), float(mb)


def main(naive_timeout: float = 60.0) -> None:
    folder = Path(tempfile.mkdtemp(prefix="synth-bench-readers-"))
    rows = []
    files = {name: fn(folder) for name, fn in HOSTILE.items()}
    files["yaml_flat_list_4MB"] = yaml_flat_list(folder, 4.0)
    for name, path in files.items():
        a = _measure(_GATE.format(path=str(path)), 120)
        b = _measure(_NAIVE[path.suffix].format(path=str(path)), naive_timeout)
        rows.append((name, path.stat().st_size, a, b))
    for n in (50_000, 1_600):
        d = wire_catalog(folder, n)
        a = _measure(_DESIGN_ON.format(path=str(d)), 120)
        rows.append((f"user catalog, {n} wires", (d / "spring_wires.csv").stat().st_size, a, ("(the gate is the design "
                                                                                                 "itself)", None, None)))
    print(f"machine: {os.cpu_count()} cores; naive readers stopped after {naive_timeout:g} s\n")
    print("| file | size | synth (A): outcome | A s | A peak MB | plain parser (B): outcome | B s | B peak MB | B/A |")
    print("|---|---|---|---|---|---|---|---|---|")
    for name, size, (oa, ta, ma), (ob, tb, mb) in rows:
        ratio = f"{tb / ta:.0f}" if tb and ta and tb == tb and ta == ta else "-"
        fmt = (lambda x: "-" if x is None or x != x else f"{x:.2f}")  # noqa: E731
        fmtm = (lambda x: "-" if x is None or x != x else f"{x:.0f}")  # noqa: E731
        print(f"| {name} | {size / 1024:.0f} kB | {oa[:70]} | {fmt(ta)} | {fmtm(ma)} | {ob[:40]} | {fmt(tb)} | "
              f"{fmtm(mb)} | {ratio} |")
    print("\n" + json.dumps({"folder": str(folder), "limits_s": 5, "limits_mb": 1024}))


if __name__ == "__main__":
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--naive-timeout", type=float, default=60.0)
    main(ap.parse_args().naive_timeout)
