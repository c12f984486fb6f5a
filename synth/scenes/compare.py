"""``synth compare CASE.yaml``: ours, the thesis tool's and the real tensioner's values side by side."""

from __future__ import annotations

from synth.compare import compare_case
from synth.io.outputs import json_text
from synth.output_table import format_value
from synth.scenes._options import add_model_options, settings_from_args

__all__ = ["register"]


def register(sub) -> None:
    p = sub.add_parser("compare", help="compare the flowchart with a case file's thesis-tool and real values")
    p.add_argument("case", help="case YAML with inputs:, thesis_tool: and real_tensioner: blocks")
    p.add_argument("--json", action="store_true")
    add_model_options(p)
    p.set_defaults(func=_main)


def _pct(e):
    if e is None:
        return ""
    return f"{100 * e:+.1f} %"


def _main(args) -> int:
    out = compare_case(args.case, settings_from_args(args))
    rows = out["rows"]
    if args.json:
        print(json_text({"name": out["name"], "rows": rows}, indent=2))
        return 0
    print(f"{out['name']}: synth against the thesis tool and the real tensioner\n")
    print(f"{'key':<40} {'synth':>12} {'thesis':>12} {'err':>9} {'real':>12} {'err':>9}")
    for r in rows:
        flag = ""
        if r.get("match") is not None:
            flag = "  same" if r["match"] else "  DIFFERENT"
        print(f"{r['key']:<40} {format_value(r['ours']):>12} {format_value(r['thesis_tool']):>12} "
              f"{_pct(r['err_thesis']):>9} {format_value(r['real']):>12} {_pct(r['err_real']):>9}{flag}")
    errs = [abs(r["err_thesis"]) for r in rows if r["err_thesis"] is not None]
    within = sum(e <= 0.03 for e in errs)
    print(f"\n{within} of {len(errs)} numeric outputs within 3 % of the thesis tool; "
          f"{sum(r['ours'] is None for r in rows)} not produced")
    return 0
