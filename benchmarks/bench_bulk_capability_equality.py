"""Every ``synth bulk --capability`` row against ``synth design --capability`` for its application (issue 34).

The real commands, in this process (``synth.cli.main``): ``synth portfolio-sample N`` writes N generated
applications (``synth.data.generated_applications.generate``, seed ``--seed``), ``synth bulk PORTFOLIO
--capability T`` screens them (its defaults: fidelity ``screening``, 1024 samples per candidate, the diagnosis;
the result in Parquet, numbers exact), then ``synth design INPUT --capability T --samples 1024 --json`` runs on each
application as the bulk read it (the portfolio row validated by the bulk's own reader, written as JSON with exact
floats). Each row is compared on: every part id of the chosen design, the verdict, feasible, the capability
verdict (``PASS`` when the design meets the target), the smallest Ppk of the targeted checks and the failing
checks. Prints the timings (wall and CPU), a table of the rows that differ with the fields that differ and the
two values, and the count.

    PYTHONPATH=. python benchmarks/bench_bulk_capability_equality.py --apps 50

``--fidelity``: the bulk runs, one per fidelity (default: the bulk's default, screening, then full), each against
the one design run per application (``--design-fidelity``, default the design's default, full); ``--samples`` is
passed to both commands; ``--rows``: only those rows of the portfolio.
"""

from __future__ import annotations

import argparse
import contextlib
import io
import json
import math
import sys
import tempfile
import time
import warnings
from pathlib import Path


def _cli(argv: list) -> tuple[int, str]:
    """``synth ARGV`` in this process: (exit code, stdout)."""
    from synth.cli import main
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        code = main([str(a) for a in argv])
    if code not in (0, 1, 3):  # not a verdict: what the command said
        print(f"synth {' '.join(map(str, argv))}: exit {code}\n{err.getvalue()[-3000:]}", file=sys.stderr)
    return code, out.getvalue()


def _same_ppk(a, b) -> bool:
    """Equal to the JSON's 6 significant figures (both empty: equal)."""
    a = math.nan if a is None else float(a)
    b = math.nan if b is None else float(b)
    if math.isnan(a) or math.isnan(b):
        return math.isnan(a) and math.isnan(b)
    if math.isinf(a) or math.isinf(b):
        return a == b
    return abs(a - b) <= 1e-5 * max(abs(a), abs(b), 1e-12)


def compare(row: dict, res: dict) -> list:
    """``[(field, bulk value, design value)]`` for the fields where bulk row ``row`` and ``synth design --json``
    output ``res`` differ."""
    from synth.design.space import PART_KEYS
    out = []
    parts = res.get("parts") or {}
    for k in PART_KEYS:
        b, d = row.get(f"part_{k}"), parts.get(k)
        if isinstance(b, float) and isinstance(d, (int, float)):
            same = (math.isnan(b) and d is None) or b == d
        else:
            same = (b is None or (isinstance(b, float) and math.isnan(b))) and d is None or b == d
        if not same:
            out.append((f"part {k}", b, d))
    if row["verdict"] != res["verdict"]:
        out.append(("verdict", row["verdict"], res["verdict"]))
    feasible = res["status"] in ("optimal", "feasible") and not any(
        c.get("verdict") == "fail" for c in res["checks"])
    if bool(row["feasible"]) != feasible:
        out.append(("feasible", bool(row["feasible"]), feasible))
    rob = res.get("robust") or {}
    found = bool((res.get("stats") or {}).get("robust_found"))
    if row["capability_verdict"] != ("PASS" if found else "FAIL"):
        out.append(("capability verdict", row["capability_verdict"], "PASS" if found else "FAIL"))
    if not _same_ppk(row["capability_min_ppk"], rob.get("min_ppk")):
        out.append(("smallest Ppk", row["capability_min_ppk"], rob.get("min_ppk")))
    failing = " ".join(rob.get("failing", []))
    if (row["capability_failing"] or "") != failing:
        out.append(("failing checks", row["capability_failing"] or "", failing))
    return out


def main(argv=None) -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--apps", type=int, default=50)
    p.add_argument("--seed", type=int, default=0)
    p.add_argument("--capability", type=float, default=1.33)
    p.add_argument("--samples", type=int, default=1024)
    p.add_argument("--fidelity", default="default,full",
                   help="the bulk runs' --fidelity, comma-separated ('default': without the option, the bulk's "
                        "default, screening)")
    p.add_argument("--design-fidelity", default="full", help="the design's --fidelity (default: its default, full)")
    p.add_argument("--rows", default=None, help="only these rows (comma-separated, 0-based) of the portfolio")
    a = p.parse_args(argv)
    warnings.simplefilter("ignore")
    import pandas as pd

    from synth.bulk.portfolio import read_portfolio, validate_table
    fidelities = [x.strip() for x in a.fidelity.split(",") if x.strip()]
    rows_wanted = [int(x) for x in a.rows.split(",")] if a.rows else None
    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(tmp)
        portfolio = tmp / "portfolio.csv"
        code, _ = _cli(["portfolio-sample", a.apps, "--out", portfolio, "--seed", a.seed])
        assert code == 0, code
        if rows_wanted is not None:  # the portfolio of those rows alone (each row is its application's own)
            read_portfolio(portfolio).iloc[rows_wanted].to_csv(portfolio, index=False)
        frames, timing = {}, {}
        for fid in fidelities:
            out = tmp / f"result-{fid}.parquet"
            argv = ["bulk", portfolio, "--out", out, "--capability", a.capability, "--samples", a.samples]
            if fid != "default":
                argv += ["--fidelity", fid]
            t0, c0 = time.perf_counter(), time.process_time()
            code, _ = _cli(argv)
            timing[fid] = (time.perf_counter() - t0, time.process_time() - c0)
            assert code == 0, f"synth bulk exit {code}"
            frames[fid] = pd.read_parquet(out).to_dict(orient="records")
        apps, errors = validate_table(read_portfolio(portfolio))
        assert not any(errors), errors
        differ = {fid: [] for fid in fidelities}
        design_wall = design_cpu = 0.0
        kinds: dict = {}
        for i, d in enumerate(apps):
            f = tmp / f"app{i}.json"
            f.write_text(json.dumps({k: v for k, v in d.as_dict().items() if v is not None}))
            t0, c0 = time.perf_counter(), time.process_time()
            code, text = _cli(["design", f, "--capability", a.capability, "--samples", a.samples,
                               "--fidelity", a.design_fidelity, "--json"])
            design_wall += time.perf_counter() - t0
            design_cpu += time.process_time() - c0
            res = json.loads(text)
            label = rows_wanted[i] if rows_wanted else i
            status = "shortcut" if (res.get("stats") or {}).get("robust_candidates", 0) == 0 else "searched"
            found = "PASS" if (res.get("stats") or {}).get("robust_found") else "FAIL"
            kinds[(found, status)] = kinds.get((found, status), 0) + 1
            words = []
            for fid in fidelities:
                got = compare(frames[fid][i], res)
                words.append(f"{fid}: {'same' if not got else 'DIFFERS ' + ', '.join(x[0] for x in got)}")
                if got:
                    differ[fid].append((label, res["verdict"], f"{found}, {status}", got))
            print(f"row {label}: design {found} {res['verdict']} ({status}); " + "; ".join(words), file=sys.stderr)
    n = len(apps)
    print(f"| {n} applications (seed {a.seed}), Ppk >= {a.capability:g}, {a.samples} samples | wall [s] | CPU [s] |")
    print("|---|---|---|")
    for fid in fidelities:
        print(f"| synth bulk --capability, fidelity {fid} (the whole portfolio) | {timing[fid][0]:.0f} | "
              f"{timing[fid][1]:.0f} |")
    print(f"| synth design --capability --json, fidelity {a.design_fidelity} (each application) | {design_wall:.0f} "
          f"| {design_cpu:.0f} |")
    for (found, status), k in sorted(kinds.items()):
        print(f"| design rows {found} ({status}: {'no candidate' if status == 'shortcut' else 'robust search'}) "
              f"| {k} | |")
    for fid in fidelities:
        print(f"\nbulk fidelity {fid} against design fidelity {a.design_fidelity}:\n")
        print("| row | design verdict | design capability | field | bulk | design |")
        print("|---|---|---|---|---|---|")
        for label, verdict, status, got in differ[fid]:
            for field, b, d in got:
                print(f"| {label} | {verdict} | {status} | {field} | {_short(b)} | {_short(d)} |")
        print(f"\nrows differing: {len(differ[fid])} of {n}")
    return 0


def _short(v) -> str:
    s = f"{v:.4g}" if isinstance(v, float) else str(v)
    return s if len(s) <= 60 else s[:57] + "..."


if __name__ == "__main__":
    sys.exit(main())
