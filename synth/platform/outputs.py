"""Files of a platform result: ``platform.csv``, ``assignment.csv``, ``summary.md``,
``tradeoff.csv`` and ``tradeoff.png``.

* ``platform.csv``: family, part, applications using it (one row per platform part); with annual volumes, the
  part's pooled volume and its volume saving (:mod:`synth.platform.volume`).
* ``assignment.csv``: one row per application: id, feasible, the part key of every family
  (``none``: no part of that family), unit cost, smallest margin and its binding
  constraint, and for an application no platform serves, the reason.
* ``summary.md``: the price of standardisation (platform parts and cost against the
  per-application optima), the volume saving, the feasibility data (time, applications), the solve
  (status, gap, the limits and whether one bound, MILP size, times), the reductions.
* :func:`report_section`: the same for the HTML report, one self-contained ``<section>``
  (tables and the plots embedded as base64 PNG).
"""

from __future__ import annotations

import base64
import html
import io
from pathlib import Path

import numpy as np
import pandas as pd

from synth.platform.assign import platform_parts_used
from synth.errors import InputError, Problem
from synth.io.files import read_text
from synth.platform.data import FAMILIES
from synth.platform.volume import price_curves, saving_text, volume_saving
from synth.io.outputs import write_figure, output_file, output_folder, write_csv, write_text
from synth.bulk.portfolio import CSV_FLOAT

__all__ = ["platform_table", "gap_text", "solve_text", "limits_text", "assignment_table", "price_of_standardisation", "summary_markdown",
           "volume_markdown",
           "tradeoff_table", "plot_tradeoff", "plot_families", "write_all", "report_section"]


def platform_table(pf, result) -> pd.DataFrame:
    """``platform.csv``: each platform part and the applications using it; with annual volumes also its pooled
    volume (pieces a year) and what buying it in that volume saves against each application's own
    (:func:`synth.platform.volume.volume_saving`)."""
    use = platform_parts_used(pf, result.records)
    rows = [{"family": f, "part": pf.part_key(f, c), "applications": use[f].get(pf.part_key(f, c), 0)}
            for f in FAMILIES for c in sorted(result.platform[f])]
    cols = ["family", "part", "applications"]
    vs = result.price.get("volume") if result.price else volume_saving(pf, result.records, _curves(pf, result))
    if vs is not None:
        by = {(r["family"], r["part"]): r for r in vs["per_part"]}
        for r in rows:
            hit = by.get((r["family"], r["part"]), {})
            r["annual_volume"] = hit.get("pooled_volume", 0.0)
            r["volume_saving_eur"] = hit.get("saving_eur", 0.0)
        cols += ["annual_volume", "volume_saving_eur"]
    return pd.DataFrame(rows, columns=cols)


def assignment_table(result) -> pd.DataFrame:
    rows = []
    # with a capability target (synth.platform.capable): each design's smallest Ppk, its verdict, the failing checks
    targeted = any("capability" in r for r in result.records)
    for r in result.records:
        row = {"application_id": r["app_id"], "feasible": r["feasible"]}
        row.update({f: r["parts"].get(f, "") for f in FAMILIES})
        row.update({"unit_cost_eur": r["unit_cost_eur"], "margin": r["margin"], "binding_constraint": r["binding"],
                    "verdict": r.get("verdict", ""), "reason": r["reason"]})
        if targeted:
            c = r.get("capability") or {}
            row.update({"capability_min_ppk": c.get("min_ppk", float("nan")),
                        "capability_verdict": ("PASS" if c["meets"] else "FAIL") if c else "",
                        "capability_failing": " ".join(c.get("failing", []))})
        rows.append(row)
    return pd.DataFrame(rows)


def _curves(pf, result):
    """The price curves ``result`` was priced by, else those of ``pf`` (:func:`synth.platform.volume.price_curves`)."""
    c = getattr(result, "curves", None)
    return c if c is not None else price_curves(pf)


def price_of_standardisation(pf, result) -> dict:
    """Parts and cost of the platform against each application's own optimum (cheapest design on the full catalog)."""
    vol = {a.app_id: a.volume for a in pf.apps}
    both = [(r, o) for r, o in zip(result.records, result.per_app_optima) if r["feasible"] and o["feasible"]]
    cost_p = sum(r["unit_cost_eur"] * vol[r["app_id"]] for r, _ in both)
    cost_o = sum(o["unit_cost_eur"] * vol[o["app_id"]] for _, o in both)
    union = {f: set() for f in FAMILIES}
    for _, o in both:
        for f, c in o["codes"].items():
            if c >= 0:
                union[f].add(c)
    fixed = lambda plat: sum(float(pf.part_cost_eur[f][c]) for f, cs in plat.items() for c in cs)  # noqa: E731
    return {"applications_served": len(both),
            "parts_platform": result.n_parts, "parts_union_of_optima": sum(len(v) for v in union.values()),
            "parts_by_family": {f: (len(result.platform[f]), len(union[f])) for f in FAMILIES},
            "unit_cost_volume_platform_eur": cost_p, "unit_cost_volume_optima_eur": cost_o,
            "fixed_cost_platform_eur": fixed(result.platform), "fixed_cost_union_of_optima_eur": fixed(union),
            "unit_cost_increase": (cost_p - cost_o) / cost_o if cost_o else 0.0,
            "volume": volume_saving(pf, result.records, _curves(pf, result))}


def volume_markdown(vs: dict | None, top: int = 10) -> str:
    """The volume saving for ``summary.md``: the total, and the parts that save most."""
    if vs is None:
        return ("No annual volumes (no `annual_volume` column): every application counts one unit, and no part is "
                "priced at a pooled volume.\n")
    out = [f"Each platform part is priced at the quantity break of the summed annual volume of the applications it "
           f"serves: {saving_text(vs)}, against each application buying its parts in its own volume "
           f"({vs['own_eur']:,.0f} EUR/year pooled to {vs['pooled_eur']:,.0f}; `docs/model.md`, \"Platform "
           "rationalisation\").", ""]
    saving = [r for r in vs["per_part"] if r["saving_eur"] > 0.005]
    if saving:
        out += ["| family | part | applications | annual volume | own volumes [EUR/year] | pooled [EUR/year] | "
                "saving [EUR/year] |", "|---|---|---|---|---|---|---|"]
        out += [f"| {r['family']} | {r['part']} | {r['applications']} | {r['pooled_volume']:,.0f} | "
                f"{r['own_eur']:,.0f} | {r['pooled_eur']:,.0f} | {r['saving_eur']:,.0f} |"
                for r in saving[:top]]
    return "\n".join(out) + "\n"


def gap_text(x: float, digits: int = 1) -> str:
    """A relative gap, or "n/a (caps)" where there is none (the greedy baseline ignores --max-variants)."""
    return "n/a (caps)" if not np.isfinite(x) else f"{x:+.{digits}%}"


def solve_text(result, digits: int = 2) -> str:
    """How the MILP of ``result`` ended, as every output says it: ``optimal, gap 0.00%``; ``stopped at the node limit
    (N nodes): reproducible, gap X%``; ``stopped at the time limit (S s): not reproducible, gap X%`` (the wall-clock
    safety net: where the search stopped depends on the machine and its load).

    >>> from types import SimpleNamespace as NS
    >>> solve_text(NS(status="time_limit", gap=0.075, limits={"time_limit_s": 600.0, "milp_status": "time_limit"}))
    'stopped at the time limit (600 s): not reproducible, gap 7.50%'
    >>> solve_text(NS(status="node_limit", gap=0.01, limits={"node_limit": 10000, "milp_status": "node_limit"}))
    'stopped at the node limit (10,000 nodes): reproducible, gap 1.00%'
    """
    lim = result.limits
    gap = f"gap {result.gap:.{digits}%}" if np.isfinite(result.gap) else "gap unknown (no bound)"
    milp = lim.get("milp_status", result.status)
    if result.status == "node_limit":
        return f"stopped at the node limit ({lim['node_limit']:,} nodes): reproducible, {gap}"
    if milp == "time_limit":
        what = "" if result.status == "time_limit" else " without a platform, the greedy one reported"
        return f"stopped at the time limit ({lim['time_limit_s']:g} s){what}: not reproducible, {gap}"
    return f"{result.status}, {gap}"


def limits_text(result) -> str:
    """The MILP's limits in ``result`` and the nodes it took (``summary.md``)."""
    lim = result.limits
    node = "no node limit" if lim.get("node_limit") is None else f"node limit {lim['node_limit']:,} (deterministic)"
    took = f"; {lim['nodes']:,} nodes taken" if lim.get("nodes", -1) >= 0 else ""
    return f"{node}, time limit {lim.get('time_limit_s', float('nan')):g} s (wall-clock safety net){took}"


def summary_markdown(pf, result) -> str:
    p = price_of_standardisation(pf, result)
    n_bad = sum(not r["feasible"] for r in result.records)
    t = result.times
    lines = [f"# Platform ({result.objective} objective)", "",
             f"{p['applications_served']} of {len(result.records)} applications served; {n_bad} not "
             "(`assignment.csv` says why).", "",
             "## Price of standardisation", "",
             "| | platform | per-application optima | |", "|---|---|---|---|",
             f"| distinct parts | {p['parts_platform']} | {p['parts_union_of_optima']} (union) | |",
             f"| unit cost x volume [EUR] | {p['unit_cost_volume_platform_eur']:,.0f} | "
             f"{p['unit_cost_volume_optima_eur']:,.0f} | {p['unit_cost_increase']:+.2%} |",
             f"| per-variant fixed cost [EUR] | {p['fixed_cost_platform_eur']:,.0f} | "
             f"{p['fixed_cost_union_of_optima_eur']:,.0f} | |", "",
             "| family | platform | union of optima |", "|---|---|---|"]
    lines += [f"| {f} | {a} | {b} |" for f, (a, b) in p["parts_by_family"].items()]
    rules = getattr(getattr(pf, "settings", None), "rules", None)
    if rules is not None and not rules.empty():  # what every option was judged by, as the command line echoed it
        lines += ["", "## Design rules", "", *[f"- {ln.strip()}" for ln in rules.lines()]]
    lines += ["", "## Volume", "", volume_markdown(p.get("volume"))]
    s = result.size
    st = getattr(pf, "stats", {}) or {}
    if "feasibility_s" in st:
        lines += ["", "## Feasibility data", "",
                  f"- {len(pf.apps)} applications through the evaluator in {st['feasibility_s']:.1f} s "
                  f"({st.get('engine', '')}, {st.get('chunks', 0)} chunks); "
                  f"{sum(a.n_cores > 0 for a in pf.apps)} with a feasible core, "
                  f"{sum(not r['feasible'] for r in result.per_app_optima)} with no feasible design"]
        pairs = {k[:-6]: v for k, v in st.items() if k.endswith("_pairs") and v}
        if pairs:
            lines.append("- evaluated rows: " + ", ".join(f"{k} {v:,}" for k, v in pairs.items()))
    lines += ["", "## Solve", "",
              f"- MILP: {solve_text(result, 3)}; objective {result.objective_value:,.6g}, bound {result.bound:,.6g}",
              f"- limits: {limits_text(result)}",
              f"- greedy baseline: {result.greedy_value:,.6g} ({gap_text(result.greedy_gap, 2)} against the MILP)",
              f"- size: {s.get('variables', 0):,} variables ({s.get('binaries', 0)} binary), "
              f"{s.get('constraints', 0):,} constraints, {s.get('nonzeros', 0):,} non-zeros",
              f"- times [s]: compile {t['compile_s']:.2f}, reductions {t['prune_s']:.2f}, greedy {t['greedy_s']:.2f}, "
              f"model build {t['build_s']:.2f}, solve {t['solve_s']:.2f}, verification {t.get('verify_s', 0.0):.2f}, "
              f"total {t['total_s']:.2f}",
              "- weights: " + ", ".join(f"{f} {w:g}" for f, w in result.weights.items())]
    if result.max_variants:
        lines.append("- max variants: " + ", ".join(f"{f} {n}" for f, n in result.max_variants.items()))
    lines += ["", "## Reductions (R1-R5, `docs/model.md`)", "",
              "| round | " + " | ".join(k for k in result.prune_log[-1] if k != "round") + " |",
              "|---" * len(result.prune_log[-1]) + "|"]
    keys = list(result.prune_log[-1])
    for row in result.prune_log:
        lines.append("| " + " | ".join(str(row.get(k, "")) for k in keys) + " |")
    lines += ["", *[f"- {n}" for n in result.notes]]
    return "\n".join(lines) + "\n"


def tradeoff_table(rows: list) -> str:
    if not rows:
        return ""
    keys = [k for k in ("margin_floor", "budget", "parts", "weighted_parts", "cost_eur", "worst_margin", "served",
                        "status") if k in rows[0]]
    out = ["| " + " | ".join(keys) + " |", "|---" * len(keys) + "|"]
    fmt = lambda v: f"{v:,.4g}" if isinstance(v, (float, np.floating)) else str(v)  # noqa: E731
    out += ["| " + " | ".join(fmt(r[k]) for k in keys) + " |" for r in rows]
    return "\n".join(out) + "\n"


def plot_tradeoff(rows: list, path, kind: str) -> Path:
    """Platform size against worst margin or total cost (matplotlib, Agg)."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(6, 4))
    x = [r["parts"] for r in rows]
    if kind == "margin":
        ax.plot([100 * r["margin_floor"] for r in rows], x, "o-")
        ax.set_xlabel("margin floor (every design's smallest margin) [%]")
        ax.set_ylabel("distinct parts in the platform")
        ax.set_title(f"Platform size against the worst margin ({rows[0]['served']} applications)")
        ax.yaxis.get_major_locator().set_params(integer=True)
    else:
        ax.plot(x, [r["cost_eur"] / 1e6 for r in rows], "o-")
        ax.set_xlabel("distinct parts in the platform (weighted)")
        ax.set_ylabel("total cost [MEUR] (unit x volume + per-variant)")
        ax.set_title("What each extra variant buys")
    ax.grid(True, alpha=0.3)
    fig.tight_layout()
    if hasattr(path, "write"):
        fig.savefig(path, dpi=110, format="png")
        plt.close(fig)
        return path
    return write_figure(fig, path, dpi=110, format="png")


def plot_families(result, path=None, price: dict | None = None):
    """Distinct parts per family: the platform against the union of the per-application optima (PNG bytes, or the
    file ``path``)."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    counts = (price or result.price)["parts_by_family"]
    fams = list(counts)
    x = np.arange(len(fams))
    fig, ax = plt.subplots(figsize=(7, 3.6))
    union, plat = [counts[f][1] for f in fams], [counts[f][0] for f in fams]
    ax.bar(x - 0.2, union, 0.4, label="union of per-application optima", color="#bbbbbb")
    ax.bar(x + 0.2, plat, 0.4, label="platform", color="#1f77b4")
    for xi, (u, p) in enumerate(zip(union, plat)):
        ax.text(xi - 0.2, max(u, 0.9), str(u), ha="center", va="bottom", fontsize=8)
        ax.text(xi + 0.2, max(p, 0.9), str(p), ha="center", va="bottom", fontsize=8)
    ax.set_xticks(x, [f.replace("_diameter_mm", "").replace("_class", "") for f in fams], rotation=30, ha="right")
    ax.set_ylabel("distinct parts (log scale)")
    ax.set_ylim(0.8, 3.0 * max(union + plat + [1]))  # before the log scale: no bar of a served part may be 0
    ax.set_yscale("log")
    ax.legend(frameon=False, loc="upper left")
    ax.grid(True, axis="y", alpha=0.3)
    fig.tight_layout()
    buf = io.BytesIO()
    fig.savefig(buf if path is None else path, dpi=110, format="png")
    plt.close(fig)
    return buf.getvalue() if path is None else Path(path)


def _png_tag(png: bytes, alt: str, caption: str) -> str:
    b64 = base64.b64encode(png).decode("ascii")
    return (f'<figure><img alt="{html.escape(alt)}" src="data:image/png;base64,{b64}">'
            f"<figcaption>{html.escape(caption)}</figcaption></figure>")


def _html_table(header: list, rows: list) -> str:
    head = "".join(f"<th>{html.escape(str(h))}</th>" for h in header)
    body = "".join("<tr>" + "".join(f"<td>{html.escape(str(c))}</td>" for c in r) + "</tr>" for r in rows)
    return f"<table><tr>{head}</tr>{body}</table>"


#: What a saved ``section.html`` may hold when it is read back into a report: the elements and attributes
#: :func:`report_section` writes, images only as embedded ``data:`` PNG. Anything else (scripts, event handlers,
#: styles, links, frames) is removed by nh3 (the maintained binding of the Rust ``ammonia`` sanitiser).
_SECTION_TAGS = {"section", "h2", "h3", "p", "code", "table", "tr", "th", "td", "figure", "figcaption", "img"}
_SECTION_ATTRIBUTES = {"*": {"id", "class"}, "img": {"src", "alt", "title"}}


def saved_section(text: str) -> str:
    """A ``section.html`` read from a folder, reduced to what :func:`report_section` writes.

    The folder is user-supplied: a hand-edited or hostile file must not put script into the report.

    >>> saved_section('<section id="platform"><p onclick="x()">ok</p><script>alert(1)</script>'
    ...               '<img src="javascript:alert(1)"></section>')
    '<section id="platform"><p>ok</p><img></section>'
    """
    import nh3
    return nh3.clean(text, tags=_SECTION_TAGS, attributes=_SECTION_ATTRIBUTES, url_schemes={"data"},
                     link_rel=None, strip_comments=True)


def report_section(result, tradeoff_png: bytes | None = None) -> str:
    """The platform for the HTML report: one self-contained ``<section id="platform">`` (the price of
    standardisation, the platform's parts and their use, the solve, and the plots embedded as base64 PNG: parts
    per family, and the trade-off curve when ``result.tradeoff`` holds one).

    >>> from synth.platform.rationalise import rationalise
    >>> from synth.platform.synthetic import synthetic_portfolio
    >>> sec = report_section(rationalise(synthetic_portfolio(6, seed=1), time_limit=30))
    >>> sec.startswith('<section id="platform">'), sec.count("data:image/png;base64,")
    (True, 1)

    ``result`` may also be the folder :func:`write_all` wrote (``synth rationalise --out``): its ``section.html``.
    ``tradeoff_png``: the trade-off plot already drawn (:func:`write_all` draws it once for both files).
    """
    if isinstance(result, (str, Path)):
        f = Path(result) / "section.html"
        if not f.is_file():
            raise InputError(Problem("--platform", str(result), "a folder written by synth rationalise --out "
                                     "(with section.html)"))
        return saved_section(read_text(f, "--platform", accepted="the section.html synth rationalise --out wrote"))
    p = result.price
    n_bad = len(result.records) - p["applications_served"]
    out = ['<section id="platform">', "<h2>Platform rationalisation</h2>",
           f"<p>{p['applications_served']} of {len(result.records)} applications served by "
           f"{result.n_parts} distinct parts ({result.objective} objective, MILP {html.escape(solve_text(result))}"
           f"); {n_bad} not served (see <code>assignment.csv</code>). "
           f"The union of the applications' own optimal designs uses {p['parts_union_of_optima']} parts; "
           f"standardising changes the unit cost x volume by {p['unit_cost_increase']:+.2%}; "
           f"{html.escape(saving_text(p.get('volume')))}.</p>",
           _html_table(["family", "platform", "union of per-application optima"],
                       [(f, a, b) for f, (a, b) in p["parts_by_family"].items()]),
           _png_tag(plot_families(result), "parts per family", "Distinct parts per family: platform against the "
                    "union of the per-application optima"),
           "<h3>Platform parts</h3>",
           _html_table(["family", "part", "applications"], [(r["family"], r["part"], r["applications"])
                                                              for r in result.table])]
    rows = getattr(result, "tradeoff", None)
    if rows:
        kind = "margin" if "margin_floor" in rows[0] else "cost"
        if tradeoff_png is None:
            buf = io.BytesIO()
            plot_tradeoff(rows, buf, kind)
            tradeoff_png = buf.getvalue()
        out += [f"<h3>Trade-off ({kind})</h3>", _png_tag(tradeoff_png, "trade-off", "Platform size against "
                                                           + ("the worst margin" if kind == "margin" else "total cost")),
                _html_table(list(k for k in rows[0] if k != "status") + ["status"],
                            [[f"{r[k]:,.4g}" if isinstance(r[k], (float, np.floating)) else r[k]
                              for k in rows[0] if k != "status"] + [r["status"]] for r in rows])]
    s, t = result.size, result.times
    out.append(f"<p class='small'>MILP: {s.get('variables', 0):,} variables ({s.get('binaries', 0)} binary), "
               f"{s.get('constraints', 0):,} constraints, {s.get('nonzeros', 0):,} non-zeros; solved in "
               f"{t['solve_s']:.2f} s (total {t['total_s']:.2f} s); greedy baseline {gap_text(result.greedy_gap)}.</p>")
    out.append("</section>")
    return "\n".join(out)


def write_all(pf, result, out, tradeoff_rows: list | None = None, kind: str = "margin") -> list:
    """Write every output file into ``out`` through the output gate (:mod:`synth.io.outputs`); returns the paths."""
    out = output_folder(out)
    paths = [out / "platform.csv", out / "assignment.csv", out / "summary.md"]
    write_csv(platform_table(pf, result), paths[0], float_format=CSV_FLOAT)
    write_csv(assignment_table(result), paths[1], float_format=CSV_FLOAT)
    text = summary_markdown(pf, result)
    png = None
    if tradeoff_rows:
        text += f"\n## Trade-off ({kind})\n\n" + tradeoff_table(tradeoff_rows)
        write_csv(pd.DataFrame(tradeoff_rows), out / "tradeoff.csv", float_format=CSV_FLOAT)
        buf = io.BytesIO()   # drawn once: the file and the report section's embedded copy
        png = plot_tradeoff(tradeoff_rows, buf, kind).getvalue()
        with output_file(out / "tradeoff.png") as tmp:
            Path(tmp).write_bytes(png)
        paths += [out / "tradeoff.csv", out / "tradeoff.png"]
    write_text(paths[2], text)
    if tradeoff_rows and not getattr(result, "tradeoff", None):
        result.tradeoff = tradeoff_rows
    if png is not None and result.tradeoff is not tradeoff_rows:
        png = None            # the section shows the result's own rows
    paths.append(write_text(out / "section.html", report_section(result, png)))  # synth report --platform DIR
    return paths
