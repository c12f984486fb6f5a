"""The production-scatter section: capability table, histograms against their windows, contributors, assumptions.

Reads ``result.robust`` (:meth:`synth.robust.capability.Capability.to_dict`, plus
the assumptions' flips of :func:`synth.robust.assumptions.flips` under
``"assumptions"``); computes nothing: every number is the capability's.

* :func:`capability_rows`: one row per check (the table of the HTML section,
  the ``Capability`` sheet of the results workbook and the JSON's columns);
* :func:`text_lines`: the same for the text report;
* :func:`robust_section`: the HTML fragment (every string escaped), with the
  histograms of damping, spring torque, hubload and the end-of-life damping
  against their windows.
"""

from __future__ import annotations

import base64
import io
import math

from synth import formatting as fmt

__all__ = ["capability_rows", "text_lines", "robust_section", "histogram_png", "HISTOGRAM_TITLES"]

#: value key -> (title, unit) of the histograms
HISTOGRAM_TITLES = {"damping_nm": ("Damping at new", "N m"), "damping_eol_nm": ("Damping at end of life", "N m"),
                    "spring_torque_nominal_nm": ("Spring torque at the nominal position", "N m"),
                    "hubload_nominal_n": ("Hubload", "N"), "cone_spring_fax_nominal_n": ("Cone spring force", "N"),
                    "main_spring_sigma_inst_mpa": ("Main spring stress at installation", "MPa"),
                    "main_spring_safety_factor": ("Main spring Goodman safety factor", "-"),
                    "sliding_safety_factor": ("Sliding safety factor", "-")}


def _f(x, pattern="{:.3g}") -> str:
    if x is None or (isinstance(x, float) and not math.isfinite(x)):
        return "inf" if x is not None and x > 0 else ("-inf" if x is not None else "-")
    return pattern.format(x)


def _p(c: dict) -> str:
    """A probability of violation and its 95 % interval for people (:func:`synth.formatting.probability`)."""
    if c.get("p_violation") is None:
        return "-"
    return f"{fmt.probability(c['p_violation'])} [{fmt.probability(c['p_lo'])}, {fmt.probability(c['p_hi'])}]"


def _m(x) -> str:
    """A margin (a fraction in the data) in percent, as every other table shows it (:func:`synth.formatting.percent`);
    ``inf`` for a check that cannot fail."""
    if x is not None and isinstance(x, float) and math.isinf(x):
        return _f(x)
    return fmt.percent(x)


def capability_rows(robust: dict) -> list:
    """One dict per check: id, label, target, nominal/centre/worst-case/RSS margins, Ppk, P(violation) with its
    95 % interval and ppm, method, contributors, note (plain values: JSON, workbook and HTML read the same)."""
    rows = []
    for c in robust.get("checks", []):
        rows.append({"check": c["id"], "label": c["label"], "target": "yes" if c["target"] else "",
                     "nominal_margin": c["nominal_margin"], "worst_case_margin": c["worst_case_margin"],
                     "rss_margin": c["rss_margin"], "centre_margin": c["centre_margin"], "ppk": c["ppk"],
                     "p_violation": c["p_violation"], "p_lo": c["p_lo"], "p_hi": c["p_hi"], "ppm": c["ppm"],
                     "method": c["method"],
                     "contributors": ", ".join(f"{q} {s:.0%}" for q, s in c.get("contributors", [])[:3]),
                     "note": c.get("note", "")})
    return rows


def _flip_lines(robust: dict) -> list:
    from synth.robust.assumptions import flip_lines
    return flip_lines(robust.get("assumptions") or [])


def text_lines(robust: dict) -> list:
    """The production-scatter block of the text report (and the verdicts resting on illustrative limits)."""
    if not robust:
        return []
    if not robust.get("checks"):
        return _flips_block(robust)
    lines = ["", f"Production scatter ({robust['targets']}; {robust['settings']['samples']} samples, seed "
                 f"{robust['settings']['seed']})", "-" * 78]
    lines.append(f"  {'meets the target' if robust['meets'] else 'MISSES the target'}: smallest Ppk "
                 f"{_f(robust['min_ppk'])}, largest P(violation) {fmt.probability(robust['max_p_violation'])}"
                 + (f"; failing: {', '.join(robust['failing'])}" if robust["failing"] else ""))
    lines.append(f"  {'check':<28} {'nominal':>8} {'worst':>8} {'RSS':>8} {'Ppk':>7}  P(violation) [95 %]")
    for c in robust["checks"]:
        if c["method"] == "deterministic" and not c["target"]:
            continue
        mark = "*" if c["target"] else " "
        lines.append(f" {mark}{c['id']:<28} {_m(c['nominal_margin']):>8} "
                     f"{_m(c['worst_case_margin']):>8} {_m(c['rss_margin']):>8} "
                     f"{_f(c['ppk']):>7}  {_p(c)} {c['method'] if c['method'] != 'monte carlo' else ''}".rstrip())
        if c.get("contributors") and c["target"] and c["ppk"] is not None and c["ppk"] < 3:
            lines.append("      scatter from " + ", ".join(f"{q} {s:.0%}" for q, s in c["contributors"][:3]))
    lines.append("  (* counted in the target; margins in percent of the limit, >= 0 passes)")
    return lines + _flips_block(robust)


def _flips_block(robust: dict) -> list:
    if "assumptions" not in robust:
        return []
    flips = _flip_lines(robust)
    head = ["", "Verdicts that rest on an illustrative limit (they flip inside its plausible range)", "-" * 78]
    return head + ([f"  - {x}" for x in flips] or ["  none: no verdict flips inside the ranges of "
                                                   "catalogs/assumption_ranges.csv"])


def histogram_png(values, window, title: str, unit: str) -> bytes:
    """A histogram of the samples with its window's limits (dashed): PNG bytes."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np
    v = np.asarray(values, dtype=float)
    fig, ax = plt.subplots(figsize=(5.2, 3.0), dpi=110)
    ax.hist(v, bins=40, color="#1f5fbf", alpha=0.8)
    lo, hi = window if window else (float("nan"), float("nan"))
    for x, name in ((lo, "lower limit"), (hi, "upper limit")):
        if x is not None and math.isfinite(x):
            ax.axvline(x, color="#c62828", linestyle="--", label=name)
    ax.set_xlabel(f"{title} [{unit}]")
    ax.set_ylabel("samples")
    ax.set_title(title, fontsize=10)
    if ax.get_legend_handles_labels()[0]:
        ax.legend(fontsize=7)
    ax.grid(True, alpha=0.3)
    buf = io.BytesIO()
    fig.tight_layout()
    fig.savefig(buf, format="png")
    plt.close(fig)
    return buf.getvalue()


def robust_section(result):
    """The HTML fragment of the production-scatter section, or None without ``result.robust``."""
    robust = getattr(result, "robust", None) or {}
    if not robust.get("checks") and "assumptions" not in robust:
        return None
    from markupsafe import Markup, escape
    if not robust.get("checks"):
        return Markup(_flips_html(robust))
    out = [f"<p><b>{escape('Meets' if robust['meets'] else 'Misses')} the target</b> "
           f"({escape(robust['targets'])}; {robust['settings']['samples']} scrambled Sobol samples, seed "
           f"{robust['settings']['seed']}): smallest Ppk {escape(_f(robust['min_ppk']))}, largest probability of "
           f"violation {escape(fmt.probability(robust['max_p_violation']))}"
           + (f"; failing: {escape(', '.join(robust['failing']))}" if robust["failing"] else "") + ".</p>"]
    out.append("<p>Per check: the nominal margin (the registry's verdict, with the thesis's worst-case stacks), "
               "the worst case and the RSS of the tolerance model's bands, the process performance index Ppk and the "
               "probability of violation with its 95 % interval (Monte Carlo, or importance sampling around the FORM "
               "design point below what the samples resolve), and the quantities that drive the scatter "
               "(standardised regression coefficients). Checks marked * count in the target.</p>")
    head = ("check", "nominal", "worst case", "RSS", "Ppk", "P(violation) [95 %]", "method", "scatter from")
    out.append("<table><thead><tr>" + "".join(f"<th>{h}</th>" for h in head) + "</tr></thead><tbody>")
    for row, c in zip(capability_rows(robust), robust["checks"]):
        if c["method"] == "deterministic" and not c["target"]:
            continue
        cls = "" if not c["target"] else (' class="v-pass"' if c.get("meets", True) else ' class="v-fail"')
        cells = [f"{'* ' if c['target'] else ''}{row['label']}", _m(row["nominal_margin"]),
                 _m(row["worst_case_margin"]), _m(row["rss_margin"]), _f(row["ppk"]), _p(c),
                 row["method"], row["contributors"]]
        out.append(f"<tr{cls}>" + "".join(f"<td>{escape(x)}</td>" for x in cells) + "</tr>")
    out.append("</tbody></table>")
    hist = robust.get("histograms") or {}
    limits = robust.get("limits") or {}
    figs = []
    for key in ("damping_nm", "damping_eol_nm", "spring_torque_nominal_nm", "hubload_nominal_n",
                "cone_spring_fax_nominal_n"):
        if key in hist and hist[key]:
            title, unit = HISTOGRAM_TITLES[key]
            png = histogram_png(hist[key], limits.get(key), title, unit)
            figs.append(f'<figure><img alt="{escape(title)}" src="data:image/png;base64,'
                        f'{base64.b64encode(png).decode()}"><figcaption>{escape(title)}'
                        f'{escape(" against its window") if key in limits else ""}</figcaption></figure>')
    if figs:
        out.append("<h3>Histograms against their windows</h3>" + "".join(figs))
    out.append("<h3>Tolerance model</h3><table><thead><tr><th>quantity</th><th>distribution</th><th>band</th>"
               "<th>source</th><th>why</th></tr></thead><tbody>")
    for t in robust.get("tolerances", []):
        band = f"{t['lo']:+.4g} .. {t['hi']:+.4g} {t['unit']}"
        kind = "normal (band = +/-3 sigma)" if t["kind"] == "normal" else "uniform"
        out.append("<tr>" + "".join(f"<td>{escape(x)}</td>" for x in (t["quantity"], kind, band, t["source"],
                                                                       t["note"])) + "</tr>")
    out.append("</tbody></table>")
    if robust.get("not_sampled"):
        out.append("<p>Not sampled for this design: " + escape("; ".join(f"{q} ({why})" for q, why in
                                                                        robust["not_sampled"])) + ".</p>")
    out.append(_flips_html(robust))
    return Markup("\n".join(out))


def _flips_html(robust: dict) -> str:
    from markupsafe import escape
    if "assumptions" not in robust:
        return ""
    flips = _flip_lines(robust)
    if flips:
        return ("<h3>Verdicts that rest on an illustrative limit</h3><ul>"
                + "".join(f"<li>{escape(x)}</li>" for x in flips) + "</ul>")
    return ("<p>No verdict flips inside the plausible ranges of the illustrative limits "
            "(catalogs/assumption_ranges.csv).</p>")
