"""The standalone figures of the scenes (``synth drive --plot``, ``synth pareto``): whole figures drawn from a
scene's own data, not from a design result, in the report's colours.
"""

from __future__ import annotations

import numpy as np

from synth.report.graph_data import COLOURS

__all__ = ["drive_figure", "pareto_figure", "line_styles", "plain"]


def plain(x) -> str:
    """A number as the outputs write it (:func:`synth.formatting.number`), for a legend."""
    from synth import formatting as fmt
    return fmt.number(x)


def line_styles(ax, durability_speed_rpm=None) -> None:
    """What the span-tension plots' line styles mean, in the legend (each span keeps one colour: solid its largest
    tension over a revolution, dotted its smallest), and the durability speed marked."""
    ax.plot([], [], color="0.3", lw=1, label="solid: largest tension")
    ax.plot([], [], color="0.3", lw=1, ls=":", label="dotted: smallest tension")
    if durability_speed_rpm is not None:
        ax.axvline(durability_speed_rpm, color=COLOURS["limit"], ls="--", lw=0.8,
                   label=f"durability speed ({plain(durability_speed_rpm)} rpm)")


def drive_figure(res: dict):
    """Arm amplitude and the lowest span tension against speed, from :func:`synth.drive.analysis.analyse`."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    sw = res["sweep"]
    fig, (a1, a2) = plt.subplots(2, 1, figsize=(7, 6), sharex=True)
    a1.plot(sw["speed_rpm"], sw["theta_pp_deg"], color=COLOURS["nominal"], label="arm peak-to-peak angle")
    a1.set(ylabel="arm peak-to-peak [deg]", title=res["name"])
    t_min, t_max = np.asarray(sw["tension_min_n"]), np.asarray(sw["tension_max_n"])
    for j, name in enumerate(res["spans"]):
        line, = a2.plot(sw["speed_rpm"], t_max[:, j], lw=1, label=name)
        a2.plot(sw["speed_rpm"], t_min[:, j], lw=1, ls=":", color=line.get_color())
    a2.axhline(res["slack"]["limit_n"], color=COLOURS["limit"], lw=1, label="slack limit")
    durability = (res.get("durability") or {}).get("speed_rpm")
    if durability is not None:
        a1.axvline(durability, color=COLOURS["limit"], ls="--", lw=0.8, label=f"durability speed ({plain(durability)} rpm)")
    line_styles(a2, durability)
    a2.set(xlabel="engine speed [rpm]", ylabel="span tension [N]")
    a1.legend(fontsize=7)
    a2.legend(fontsize=7)
    fig.tight_layout()
    return fig


def pareto_figure(front: list, path, *, y: str = "margin", ylabel: str = "smallest margin [%]",
                  title: str = "cost against margin: Pareto front", note=None) -> None:
    """Save a Pareto front (cost against ``y``; a margin, a fraction in the data, in percent) to ``path``: each
    point numbered, and under the plot one line per number saying which design it is
    (:func:`synth.formatting.design_label`), what it scores and ``note(point)`` (default: what binds), so no label
    is clipped and every point names its design."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import textwrap

    from synth import formatting as fmt
    from synth.design.constraints import words
    from synth.io.outputs import write_figure
    note = note or (lambda p: "binds: " + words(p["binding"]))
    scale = 100.0 if y == "margin" else 1.0
    lines = []
    for i, p in enumerate(front, start=1):
        score = fmt.percent(p[y]) if y == "margin" else f"{y} {fmt.number(p[y], 3)}"
        text = f"{i}: {fmt.number(p['cost_eur'])} EUR, {score}; {note(p)}; {fmt.design_label(p.get('parts') or {})}"
        lines += textwrap.wrap(text, 125, subsequent_indent="     ")
    fig = plt.figure(figsize=(8.5, 4.6 + 0.16 * len(lines)))
    height = 4.1 / (4.6 + 0.16 * len(lines))
    ax = fig.add_axes((0.1, 1.0 - height - 0.02, 0.86, height - 0.09))
    c = [p["cost_eur"] for p in front]
    m = [scale * p[y] for p in front]
    ax.step(c, m, where="post", color="0.6", label="front (cheapest design at each level)")
    ax.plot(c, m, "o", color=COLOURS["nominal"], label="design on the front (numbered below)")
    for i, (x, v) in enumerate(zip(c, m), start=1):
        ax.annotate(str(i), (x, v), fontsize=8, xytext=(4, 4), textcoords="offset points")
    ax.set_xlabel("cost [EUR] (catalog unit costs)")
    ax.set_ylabel(ylabel)
    ax.set_title(title)
    ax.grid(True, alpha=0.3)
    ax.margins(x=0.08, y=0.12)
    ax.legend(fontsize=7, loc="lower right")
    fig.text(0.02, 1.0 - height - 0.1, "\n".join(lines), fontsize=6.5, va="top", family="monospace")
    write_figure(fig, path, dpi=120)
