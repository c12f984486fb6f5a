"""The drive's layout drawn: pulleys (pitch circles), the belt's spans, and the tensioner arm at each position.

Presentation only: it reads :func:`synth.drive.positions.arm_state` and the
position table of :func:`synth.drive.analysis.analyse`.
"""

from __future__ import annotations

import numpy as np

__all__ = ["layout_figure"]


def layout_figure(drive, res: dict):
    """A matplotlib figure of the layout at the nominal arm angle and the arm at every position of ``res``."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.patches import Circle

    from synth.drive.positions import frame_of, arm_state

    fr = frame_of(drive)
    ten = drive.tensioner
    st = arm_state(fr, ten.arm_angle_deg, strict=True)
    g = st["geometry"]
    centres = st["centres"][0]
    fig, ax = plt.subplots(figsize=(7.5, 7.5))
    for i, p in enumerate(drive.pulleys):
        colour = "tab:red" if p.role == "crank" else ("tab:green" if p.role == "tensioner" else "tab:blue")
        ax.add_patch(Circle(centres[i], p.radius_mm, fill=False, lw=1.5, color=colour,
                            ls="--" if p.backside else "-"))
        ax.annotate(p.name, centres[i], ha="center", va="center", fontsize=8)
    for j in range(len(drive.pulleys)):
        a, b = g["start_mm"][0, j], g["end_mm"][0, j]
        ax.plot([a[0], b[0]], [a[1], b[1]], color="black", lw=1.2)
    pivot = np.array([ten.pivot_x_mm, ten.pivot_y_mm])
    ax.plot(*pivot, "k^", ms=7)
    rows = [r for r in res.get("positions", {}).get("rows", []) if r.get("found")]
    if not rows:
        rows = [{"position": "nominal", "arm_angle_deg": ten.arm_angle_deg}]
    cmap = plt.get_cmap("viridis")
    for k, r in enumerate(rows):
        phi = np.radians(r["arm_angle_deg"])
        tip = pivot + ten.arm_length_mm * np.array([np.cos(phi), np.sin(phi)])
        colour = cmap(k / max(len(rows) - 1, 1))
        ax.plot([pivot[0], tip[0]], [pivot[1], tip[1]], color=colour, lw=2 if r["position"] == "nominal" else 1,
                label=f"{r['position']} {r['arm_angle_deg']:.1f} deg")
        ax.plot(*tip, "o", color=colour, ms=3)
    ax.set_aspect("equal")
    ax.autoscale_view()
    ax.set(xlabel="x [mm]", ylabel="y [mm]", title=f"{res['name']}: layout, arm at each position")
    ax.legend(fontsize=7, loc="best")
    ax.grid(True, lw=0.3)
    fig.tight_layout()
    return fig
