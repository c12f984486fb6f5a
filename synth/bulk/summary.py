"""Portfolio summary of a bulk result table: what is feasible, which parts, what binds.

:func:`summarise` reads a result table (the output of
:func:`synth.bulk.run.run_portfolio`) and counts:

* ``overall``: applications, input errors, evaluated, feasible and the feasible
  share (of the evaluated applications: rows with input errors are not counted);
* ``by_group``: the feasible share by ``application_type`` and by
  ``damping_typology`` (an empty cell is the field's default);
* ``parts``: how often each catalog part is chosen, per part family, over the
  feasible applications (an infeasible application's nearest design is not a choice);
* ``binding``: how often each constraint is the binding one of a feasible design;
* ``violated``: how often each constraint is violated by the nearest design of an
  infeasible application, and by how much (median of the normalised margin);
* ``relaxed``: which inputs the smallest relaxations change, and how often.

:func:`write_summary` writes them as ``summary.md``, one CSV per table and
PNG bar charts (matplotlib, Agg); :func:`text` is the short summary printed at
the end of ``synth bulk``. :func:`fidelity_agreement` compares two result
tables of the same portfolio (screening against full fidelity).

>>> t = pd.DataFrame({"status": ["optimal", "infeasible", "error"], "feasible": [True, False, False],
...                   "application_type": ["dry", "dry", "dry"], "binding_constraint": ["pivot_bore", "spring_yield", ""],
...                   "binding_margin": [0.1, -0.2, float("nan")], "violated": ["", "spring_yield:-0.200", ""],
...                   "relaxation": ["", "", ""], "part_bearing": ["6006", "6006", None]})
>>> s = summarise(t)
>>> s.overall["evaluated"], s.overall["feasible"], s.overall["feasible_share"]
(2, 1, 0.5)
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import pandas as pd

from synth import schema
from synth.design.space import PART_KEYS
from synth.bulk.portfolio import CSV_FLOAT
from synth.design.constraints import words
from synth.io.outputs import output_folder, write_csv, write_figure, write_text

__all__ = ["Summary", "summarise", "write_summary", "text", "markdown_table", "fidelity_agreement", "GROUPS",
           "COLUMNS"]

#: input columns the feasible share is broken down by
GROUPS = ("application_type", "damping_typology")
#: every column :func:`summarise` reads
COLUMNS = (("status", "feasible") + GROUPS + tuple(f"part_{k}" for k in PART_KEYS)
           + ("binding_constraint", "binding_margin", "violated", "relaxation"))
_VIOL = re.compile(r"([A-Za-z_0-9]+):([-+]?[0-9.eE+-]+)")
_RELAX = re.compile(r"([A-Za-z_][A-Za-z_0-9]*)\s+[-+0-9.eE]+\s*->")


@dataclass
class Summary:
    """The tables of a portfolio summary (see the module docstring)."""

    overall: dict
    by_group: pd.DataFrame
    parts: pd.DataFrame
    binding: pd.DataFrame
    violated: pd.DataFrame
    relaxed: pd.DataFrame


def _group_values(table: pd.DataFrame, name: str) -> pd.Series:
    """The normalised input value of field ``name`` per row (empty: the field's default, else ``(empty)``)."""
    default = schema.field_by_name(name).default
    raw = table[name] if name in table.columns else pd.Series([None] * len(table), index=table.index)

    def norm(v):
        if v is None or (isinstance(v, float) and np.isnan(v)) or (isinstance(v, str) and not v.strip()):
            return default or "(empty)"
        return str(v).strip().lower().replace(" ", "_").replace("-", "_")
    return raw.map(norm)


def _text(col: pd.Series) -> pd.Series:
    """A text column with missing cells as ``""`` (a CSV read back turns empty text into NaN)."""
    return pd.Series(["" if v is None or (isinstance(v, float) and np.isnan(v)) else str(v) for v in col],
                     index=col.index, dtype=object)


def summarise(table: pd.DataFrame) -> Summary:
    """Count feasibility, chosen parts, binding and violated constraints of a bulk result table."""
    status = _text(table["status"])
    evaluated = status != "error"
    feasible = table["feasible"].astype(bool) & evaluated
    n_eval, n_feas = int(evaluated.sum()), int(feasible.sum())
    overall = {"applications": int(len(table)), "input_errors": int((~evaluated).sum()), "evaluated": n_eval,
               "feasible": n_feas, "infeasible": n_eval - n_feas,
               "feasible_share": (n_feas / n_eval) if n_eval else float("nan")}
    groups = []
    for g in GROUPS:
        vals = _group_values(table, g)[evaluated]
        for v in sorted(vals.unique()):
            sel = vals == v
            n = int(sel.sum())
            f = int(feasible[evaluated][sel].sum())
            groups.append({"group": g, "value": v, "evaluated": n, "feasible": f, "feasible_share": f / n})
    by_group = pd.DataFrame(groups, columns=["group", "value", "evaluated", "feasible", "feasible_share"])
    parts = []
    for k in PART_KEYS:
        col = f"part_{k}"
        if col not in table.columns:
            continue
        chosen = table.loc[feasible, col].map(lambda v: "(none)" if v is None or (isinstance(v, float) and np.isnan(v))
                                              else (f"{v:g}" if isinstance(v, float) else str(v)))
        for v, c in chosen.value_counts().items():
            parts.append({"family": k, "part": v, "count": int(c), "share": int(c) / n_feas})
    parts = pd.DataFrame(parts, columns=["family", "part", "count", "share"])
    if len(parts):
        parts = parts.sort_values(["family", "count", "part"], ascending=[True, False, True],
                                  key=lambda s: s.map(PART_KEYS.index) if s.name == "family" else s).reset_index(drop=True)
    b = table.loc[feasible & (_text(table["binding_constraint"]) != "")]
    binding = (b.groupby("binding_constraint")["binding_margin"].agg(count="size", median_margin="median")
               .reset_index().rename(columns={"binding_constraint": "constraint"}))
    binding["share"] = binding["count"] / n_feas if n_feas else np.nan
    binding = binding.sort_values(["count", "constraint"], ascending=[False, True]).reset_index(drop=True)
    binding = binding[["constraint", "count", "share", "median_margin"]]
    viol: dict[str, list[float]] = {}
    relaxed: dict[str, int] = {}
    infeasible = evaluated & ~feasible
    for s in _text(table.loc[infeasible, "violated"]):
        for name, m in _VIOL.findall(s):
            viol.setdefault(name, []).append(float(m))
    n_inf = int(infeasible.sum())
    violated = pd.DataFrame([{"constraint": k, "count": len(v), "share": len(v) / n_inf, "median_margin": float(np.median(v))}
                             for k, v in viol.items()], columns=["constraint", "count", "share", "median_margin"])
    violated = violated.sort_values(["count", "constraint"], ascending=[False, True]).reset_index(drop=True)
    if "relaxation" in table.columns:
        for s in _text(table.loc[infeasible, "relaxation"]):
            for name in dict.fromkeys(_RELAX.findall(s)):
                relaxed[name] = relaxed.get(name, 0) + 1
    relaxed = pd.DataFrame([{"input": k, "count": v, "share": v / n_inf} for k, v in relaxed.items()],
                           columns=["input", "count", "share"])
    relaxed = relaxed.sort_values(["count", "input"], ascending=[False, True]).reset_index(drop=True)
    return Summary(overall, by_group, parts, binding, violated, relaxed)


def _cell(v) -> str:
    if isinstance(v, float):
        return "" if np.isnan(v) else f"{v:.4g}"
    return str(v)


def markdown_table(df: pd.DataFrame) -> str:
    """A pipe table of ``df`` (floats to 4 significant digits).

    >>> print(markdown_table(pd.DataFrame({"a": [1], "b": [0.123456]})))
    | a | b |
    |---|---|
    | 1 | 0.1235 |
    """
    lines = ["| " + " | ".join(map(str, df.columns)) + " |", "|" + "---|" * len(df.columns)]
    lines += ["| " + " | ".join(_cell(v) for v in row) + " |" for row in df.itertuples(index=False)]
    return "\n".join(lines)


def _pct(x: float) -> str:
    return "n/a" if x != x else f"{100 * x:.1f} %"


def text(s: Summary, n_top: int = 3) -> str:
    """A short plain-text summary (a few lines) for the terminal."""
    o = s.overall
    lines = [f"portfolio: {o['applications']} applications, {o['input_errors']} with input errors, "
             f"{o['evaluated']} evaluated",
             f"feasible: {o['feasible']} of {o['evaluated']} ({_pct(o['feasible_share'])})"
             + "".join(f" | {r.value} {_pct(r.feasible_share)}" for r in s.by_group.itertuples()
                       if r.group == "application_type")]
    if len(s.binding):
        lines.append("binds most (feasible): " + ", ".join(f"{r.constraint} {r.count}" for r in s.binding.head(n_top).itertuples()))
    if len(s.violated):
        lines.append("violated most (infeasible): " + ", ".join(f"{r.constraint} {r.count}" for r in s.violated.head(n_top).itertuples()))
    if len(s.relaxed):
        lines.append("relaxed most: " + ", ".join(f"{r.input} {r.count}" for r in s.relaxed.head(n_top).itertuples()))
    if len(s.parts):
        top = s.parts.groupby("family", sort=False).head(1)
        lines.append("most chosen: " + ", ".join(f"{r.family} {r.part} ({_pct(r.share)})"
                                                 for r in top.head(4).itertuples()))
    return "\n".join(lines)


def _bar(ax, labels, values, title, xlabel):
    y = np.arange(len(labels))
    ax.barh(y, values, color="#4477aa")
    ax.set_yticks(y, labels=labels, fontsize=8)
    ax.invert_yaxis()
    ax.set_title(title, fontsize=10)
    ax.set_xlabel(xlabel)


def write_summary(s: Summary, folder, rules=None) -> list[Path]:
    """Write ``summary.md``, one CSV per table and PNG bar charts into ``folder``; returns the paths written.
    ``rules``: the design rules the applications were judged by (:class:`synth.design.rules.Rules`), echoed."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    d = output_folder(folder, "--summary")
    written = []
    tables = {"by_group": s.by_group, "parts": s.parts, "binding": s.binding, "violated": s.violated,
              "relaxed": s.relaxed}
    overall = pd.DataFrame([{"quantity": k, "value": v} for k, v in s.overall.items()])
    for name, df in {"overall": overall, **tables}.items():
        written.append(write_csv(df, d / f"summary_{name}.csv", "--summary", float_format=CSV_FLOAT))
    md = ["## Portfolio summary", "", text(s).replace("\n", "  \n"), "", "### Overall", "", markdown_table(overall)]
    if rules is not None and rules.lines():
        # a code block, one line per rule: a name holding a newline cannot leave it
        md[3:3] = ["", "### Design rules", "", *("    " + " ".join(line.splitlines()) for line in rules.lines())]
    titles = {"by_group": "Feasible share by group", "parts": "Parts chosen (feasible applications)",
              "binding": "Binding constraints (feasible applications)",
              "violated": "Violated constraints (infeasible applications, nearest design)",
              "relaxed": "Inputs changed by the smallest relaxation"}
    for name, df in tables.items():
        md += ["", f"### {titles[name]}", "", markdown_table(df) if len(df) else "(none)"]
    written.append(write_text(d / "summary.md", "\n".join(md) + "\n", "--summary"))

    plots = []
    if len(s.by_group):
        plots.append(("feasible_by_group.png", [f"{r.group}={r.value} (n={r.evaluated})" for r in s.by_group.itertuples()],
                      100 * s.by_group["feasible_share"].to_numpy(), "Feasible share by group", "feasible [%]"))
    for name, df, title in (("binding.png", s.binding, "Binding constraint of feasible designs"),
                            ("violated.png", s.violated, "Violated constraints of infeasible applications")):
        if len(df):
            plots.append((name, [words(c, 48) for c in df["constraint"].head(15)], df["count"].head(15).to_numpy(),
                          title, "applications"))
    for name, labels, values, title, xlabel in plots:
        fig, ax = plt.subplots(figsize=(7, 0.35 * len(labels) + 1.2), layout="constrained")
        _bar(ax, labels, values, title, xlabel)
        written.append(write_figure(fig, d / name, "--summary", dpi=110))
    if len(s.parts):
        fams = list(dict.fromkeys(s.parts["family"]))
        ncol = 3
        nrow = int(np.ceil(len(fams) / ncol))
        fig, axes = plt.subplots(nrow, ncol, figsize=(11, 2.4 * nrow), layout="constrained", squeeze=False)
        for ax, fam in zip(axes.flat, fams):
            sub = s.parts[s.parts["family"] == fam].head(8)
            _bar(ax, list(sub["part"]), 100 * sub["share"].to_numpy(), fam, "chosen [%]")
        for ax in list(axes.flat)[len(fams):]:
            ax.set_visible(False)
        fig.suptitle("Catalog parts chosen (share of feasible applications)")
        written.append(write_figure(fig, d / "parts.png", "--summary", dpi=110))
    return written


def fidelity_agreement(a: pd.DataFrame, b: pd.DataFrame) -> dict:
    """Compare two result tables of the same portfolio (e.g. screening ``a`` and full ``b`` fidelity).

    Over the rows evaluated in both: ``rows``, ``verdicts_differ`` (count and
    ``verdict_share``), ``designs_differ`` (a different part in any family,
    count and share) and ``margin_min_max_abs_diff``.

    >>> x = pd.DataFrame({"status": ["optimal", "optimal"], "feasible": [True, True], "margin_min": [0.1, 0.2], "part_bearing": ["6006", "6006"]})
    >>> y = pd.DataFrame({"status": ["optimal", "infeasible"], "feasible": [True, False], "margin_min": [0.1, -0.1], "part_bearing": ["6006", "6006"]})
    >>> r = fidelity_agreement(x, y)
    >>> r["verdicts_differ"], r["verdict_share"], round(r["margin_min_max_abs_diff"], 3)
    (1, 0.5, 0.3)
    """
    if len(a) != len(b):
        raise ValueError(f"tables of different lengths: {len(a)} and {len(b)}")
    a, b = a.reset_index(drop=True), b.reset_index(drop=True)
    both = (_text(a["status"]) != "error") & (_text(b["status"]) != "error")
    n = int(both.sum())
    diff = (a["feasible"].astype(bool) != b["feasible"].astype(bool)) & both
    pcols = [c for c in a.columns if c.startswith("part_") and c in b.columns]
    ne = pd.Series(False, index=a.index)
    for c in pcols:
        ne |= _text(a[c]) != _text(b[c])
    ne &= both
    dm = (a["margin_min"].astype(float) - b["margin_min"].astype(float)).abs()[both]
    dm = dm[np.isfinite(dm)]
    return {"rows": n, "verdicts_differ": int(diff.sum()), "verdict_share": (int(diff.sum()) / n) if n else float("nan"),
            "designs_differ": int(ne.sum()), "design_share": (int(ne.sum()) / n) if n else float("nan"),
            "margin_min_max_abs_diff": float(dm.max()) if len(dm) else 0.0}
