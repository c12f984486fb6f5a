"""The thesis's graphs of one design, drawn with matplotlib (Agg) from the evaluator's data.

The catalogue of the graphs of one design (:data:`CATALOG`: id, title, thesis figure), the checks whose verdict
colours each (:data:`GRAPH_CHECKS`) and the drawing of them: :func:`build_graphs` draws every graph that applies,
:func:`graph_png` one, each by its function of :mod:`synth.report.thesis_graphs` (:data:`FUNCS`) from the result's
data (:class:`synth.report.graph_data.Data`). The scenes' standalone figures are :mod:`synth.report.figures`
(re-exported here).

Each graph's verdict colour is the verdict of the result's own checks
(:data:`GRAPH_CHECKS`, registry ids): green pass, red fail, amber warning, and
the neutral blue where the check was not evaluated. A graph whose data the
result lacks (a step that does not apply, an input not given) is listed with
the reason, never drawn empty and never filled in by re-running a step's
selection.

Every :class:`Graph` carries its data (``series``: named 1-D arrays, the
plotted lines) and the PNG, so tests assert on the numbers and the report
embeds the picture.

>>> [g[0] for g in CATALOG][:3]
['hysteresis_load', 'hysteresis_torque', 'sensitivity_differential_angle']
>>> GRAPH_CHECKS["bushing_wear"]
('bushing_wear',)
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from synth.design.constraints import REGISTRY
from synth.design.result import FAIL, PASS, WARNING
from synth.progress import progress
from synth.report import thesis_graphs
from synth.report.figures import drive_figure, pareto_figure
from synth.report.graph_data import COLOURS, Data, Skip, new_figure, png_bytes

__all__ = ["Graph", "Skipped", "CATALOG", "GRAPH_CHECKS", "build_graphs", "graph_png", "COLOURS", "graph_verdict",
           "drive_figure", "pareto_figure", "ON_REQUEST"]

#: graphs drawn only from a file the user gives (``synth report --pareto/--solvers``): without it nothing is missing,
#: so a review document does not list them as not drawn
ON_REQUEST = ("pareto", "solvers")

#: (id, title, thesis figure)
CATALOG: tuple[tuple[str, str, str], ...] = (
    ("hysteresis_load", "Hysteresis cycle in hubload", "Fig. 15"),
    ("hysteresis_torque", "Hysteresis cycle in torque", "Fig. 16"),
    ("sensitivity_differential_angle", "Sensitivity to the differential angle", "Fig. 17"),
    ("sensitivity_mu_pivot_bushing", "Sensitivity to the pivot-bushing friction", "Fig. 18"),
    ("sensitivity_mu_plastic", "Sensitivity to the plastic-element friction", "Fig. 19"),
    ("bushing_wear", "Pivot bushing wear against time", "Fig. 39"),
    ("pulley_parallelism", "Pulley parallelism against time", "Fig. 40"),
    ("damping_decay", "Damping decay over the durability test", "Fig. 42"),
    ("cone_spring_characteristic", "Cone spring characteristic", "Fig. 43"),
    ("plastic_wear", "Plastic friction elements wear against time", "Fig. 44"),
    ("cone_spring_force_time", "Cone spring axial force against time", "Fig. 45"),
    ("cone_spring_tolerance_band", "Cone spring force tolerance band", "Fig. 68"),
    ("goodman", "Smith-Goodman diagram of the main spring", "Fig. 71"),
    ("pivot_base_pressure", "Pivot base contact pressure against contact angle", "Fig. 74"),
    ("drive_arm_amplitude", "Tensioner arm amplitude against engine speed", "drive"),
    ("drive_span_tension", "Span tensions against engine speed", "drive"),
    ("drive_hysteresis_loop", "Arm friction loop at the durability speed", "drive"),
    ("pareto", "Pareto front", "optimiser"),
    ("solvers", "Solver comparison", "optimiser"),
)
_TITLES = {i: (t, f) for i, t, f in CATALOG}

#: graph id -> the registry checks whose verdict colours the graph (the worst of them)
GRAPH_CHECKS: dict[str, tuple[str, ...]] = {
    "hysteresis_load": ("self_locking",),
    "hysteresis_torque": ("damping_upper", "damping_lower"),
    "bushing_wear": ("bushing_wear",),
    "pulley_parallelism": ("bushing_parallelism",),
    "damping_decay": ("damping_eol",),
    "cone_spring_characteristic": ("cone_not_flattened",),
    "plastic_wear": ("damper_pad_wear", "endcap_spacer_wear"),
    "cone_spring_force_time": ("damping_eol",),
    "cone_spring_tolerance_band": ("cone_force_band",),
    "goodman": ("spring_fatigue",),
    "pivot_base_pressure": ("tilting", "pivot_base_pressure"),
    "drive_arm_amplitude": ("drive_arm_lock",),
    "drive_span_tension": ("drive_belt_slack",),
    "drive_hysteresis_loop": ("drive_arm_lock",),
}
_UNKNOWN = sorted({c for ids in GRAPH_CHECKS.values() for c in ids} - set(REGISTRY))
if _UNKNOWN:  # pragma: no cover - a renamed registry id must not silently leave a graph uncoloured
    raise ImportError(f"synth.report.plots: GRAPH_CHECKS names checks the registry does not hold: {_UNKNOWN}")

@dataclass
class Graph:
    """One drawn graph: id, title, thesis figure, data series, verdict and PNG bytes."""

    id: str
    title: str
    figure: str
    series: dict = field(default_factory=dict)
    verdict: str | None = None
    caption: str = ""
    png: bytes = b""


@dataclass
class Skipped:
    id: str
    title: str
    reason: str


def graph_verdict(result, gid: str) -> str | None:
    """The verdict of graph ``gid``: the worst verdict of its :data:`GRAPH_CHECKS` among the result's checks.

    ``fail`` before ``warning`` before ``pass``; None when none of them was evaluated.

    >>> from synth.design.result import Check, Result
    >>> r = Result("verified", checks=[Check("tilting", 3.8, 3.5, 0.09, "pass"),
    ...                                Check("pivot_base_pressure", 500.0, 400.0, -0.25, "fail")])
    >>> graph_verdict(r, "pivot_base_pressure"), graph_verdict(r, "goodman")
    ('fail', None)
    """
    ids = GRAPH_CHECKS.get(gid, ())
    hits = {c.verdict for c in result.checks if c.id in ids}
    for v in (FAIL, WARNING, PASS):
        if v in hits:
            return v
    return None


#: graph id -> its drawing function ``g_<id>(data, ax, verdict)`` of :mod:`synth.report.thesis_graphs`
FUNCS = {gid: getattr(thesis_graphs, f"g_{gid}") for gid, _, _ in CATALOG}


def graph_png(graph_id: str, result, extra: dict | None = None) -> Graph:
    """Draw one graph; raises ``LookupError`` with the reason when it does not apply."""
    dt = Data(result, extra)
    g = _draw(graph_id, dt)
    if isinstance(g, Skipped):
        raise LookupError(f"{graph_id}: {g.reason}")
    return g


def _draw(gid: str, dt: Data):
    title, figure = _TITLES[gid]
    fig, ax = new_figure(f"{title} ({figure})")
    verdict = graph_verdict(dt.r, gid)
    try:
        series = FUNCS[gid](dt, ax, verdict)
    except Skip as why:
        import matplotlib.pyplot as plt
        plt.close(fig)
        return Skipped(gid, title, str(why))
    series = {k: np.atleast_1d(np.asarray(v, float)) for k, v in series.items()}
    if ax.get_legend_handles_labels()[0]:
        ax.legend(fontsize=8, loc="best")
    return Graph(gid, title, figure, series, verdict, png=png_bytes(fig))


_CAD_TITLES = {"section": "3D model: section through the pivot axis", "exploded": "3D model: exploded view"}


def _cad_graphs(dt: Data) -> list[Graph]:
    return cad_graphs(list(dt.extra.get("cad") or []) + list((dt.r.curves or {}).get("cad_images") or []))


def cad_graphs(paths) -> list[Graph]:
    """The 3D model's pictures (PNG paths: ``section.png``, ``exploded.png``) as graphs (Fig. 75-76)."""
    out = []
    for i, p in enumerate(paths):
        p = Path(p)
        if p.is_file() and p.suffix.lower() == ".png":
            title = _CAD_TITLES.get(p.stem, f"3D model: {p.stem}")
            out.append(Graph(f"cad_{i + 1}", title, "Fig. 75-76", {}, None, png=p.read_bytes()))
    return out


def build_graphs(result, extra: dict | None = None, *, show_progress: bool = True):
    """Every graph of :data:`CATALOG` that applies, and the skipped ones with the reason.

    ``extra``: ``{"pareto": rows, "solvers": rows, "cad": [png paths]}`` from
    other scenes. Returns ``(graphs, skipped)``.
    """
    dt = Data(result, extra)
    graphs, skipped = [], []
    ids = [gid for gid, _, _ in CATALOG if not gid.startswith("drive_") or dt.settings.drive is not None]
    for gid in (progress(ids, "report graphs") if show_progress else ids):
        g = _draw(gid, dt)
        (skipped if isinstance(g, Skipped) else graphs).append(g)
    graphs.extend(_cad_graphs(dt))
    return graphs, skipped
