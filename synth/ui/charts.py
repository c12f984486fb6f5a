"""The page's interactive charts as ECharts options (NiceGUI's ``ui.echart``, served by the server itself).

Each function turns numbers synth computed into a chart's options: no physics here, no rule. A category axis keeps
its labels whole (``containLabel``: a bearing ``6006`` is never clipped to ``06``), every line is in the legend, and
the design point is marked where a chart has one.

>>> o = bars(["6006", "6205"], [75.0, 25.0], "Ball bearing", "chosen [%]")
>>> o["yAxis"]["data"], o["grid"]["containLabel"], o["series"][0]["data"]
(['6006', '6205'], True, [75.0, 25.0])
>>> h = histogram([1.0, 2.0, 2.5, 3.0], (1.5, None), "Damping", "N m", bins=2)
>>> h["series"][0]["data"], [m["xAxis"] for m in h["series"][0]["markLine"]["data"]]
([[1.5, 1], [2.5, 3]], [1.5])
"""

from __future__ import annotations

import math

__all__ = ["bars", "histogram", "sweep", "PALETTE"]

#: line colours of the sweep (matplotlib's tab10, the report's graphs' colours)
PALETTE = ("#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd", "#8c564b", "#e377c2", "#7f7f7f", "#bcbd22",
           "#17becf")
_FAIL = "#c62828"


def _finite(x) -> bool:
    return isinstance(x, (int, float)) and not isinstance(x, bool) and math.isfinite(x)


def bars(labels: list[str], values: list[float], title: str, unit: str, *, colour: str = "#1f5fbf") -> dict:
    """A horizontal bar chart, the first label on top, every label whole."""
    return {"title": {"text": title, "textStyle": {"fontSize": 13}},
            "grid": {"containLabel": True, "left": 8, "right": 24, "top": 36, "bottom": 8},
            "tooltip": {"trigger": "axis", "axisPointer": {"type": "shadow"}},
            "xAxis": {"type": "value", "name": unit, "nameLocation": "middle", "nameGap": 22},
            "yAxis": {"type": "category", "data": [str(x) for x in labels], "inverse": True,
                      "axisLabel": {"interval": 0}},
            "series": [{"type": "bar", "data": [float(v) for v in values], "itemStyle": {"color": colour},
                        "label": {"show": True, "position": "right", "formatter": "{c}"}}]}


def histogram(values, window: tuple | None, title: str, unit: str, *, bins: int = 40) -> dict:
    """The samples' histogram (bin centres and counts) with the window's limits as dashed red lines."""
    import numpy as np
    v = np.asarray([x for x in values if _finite(x)], dtype=float)
    counts, edges = np.histogram(v, bins=bins) if len(v) else (np.zeros(0, int), np.zeros(1))
    centres = 0.5 * (edges[:-1] + edges[1:])
    marks = [{"xAxis": float(x), "name": name} for x, name in zip(window or (), ("lower limit", "upper limit"))
             if _finite(x)]
    series = {"type": "bar", "name": "samples", "barCategoryGap": "0%", "itemStyle": {"color": "#1f5fbf"},
              "data": [[round(float(c), 6), int(n)] for c, n in zip(centres, counts)],
              "markLine": {"symbol": "none", "lineStyle": {"color": _FAIL, "type": "dashed"},
                           "label": {"formatter": "{b}"}, "data": marks}}
    span = [float(x) for x in (*(v[[0]] if len(v) else ()), *(m["xAxis"] for m in marks))]
    lo, hi = (min(span + [float(edges[0])]), max(span + [float(edges[-1])])) if span else (0.0, 1.0)
    pad = 0.05 * (hi - lo or 1.0)
    return {"title": {"text": title, "textStyle": {"fontSize": 13}},
            "grid": {"containLabel": True, "left": 8, "right": 16, "top": 36, "bottom": 8},
            "tooltip": {"trigger": "axis"},
            "xAxis": {"type": "value", "name": unit, "nameLocation": "middle", "nameGap": 22, "scale": True,
                      "min": round(lo - pad, 6), "max": round(hi + pad, 6)},
            "yAxis": {"type": "value", "name": "samples"}, "series": [series]}


def sweep(data: dict, labels: dict[str, str], *, show: int = 6, unit: str = "") -> dict:
    """A what-if sweep (:meth:`synth.ui.session.DesignSession.sweep`): the margins [%] of the checks that fail
    somewhere in the range, then those that come closest to their limit, advisory ones last (``show`` of them),
    against the input; the limit (0 %) and the design point (a vertical line at the input's value) marked; every
    line in the legend.

    >>> d = {"field": "k", "x": [1.0, 2.0, 3.0], "design_x": 2.0, "margins": {"a": [0.3, 0.1, -0.1],
    ...      "b": [0.5, 0.5, 0.5], "c": [None, None, None]}}
    >>> o = sweep(d, {"a": "check a", "b": "check b"})
    >>> o["legend"]["data"], o["series"][0]["data"]
    (['check a', 'check b'], [[1.0, 30.0], [2.0, 10.0], [3.0, -10.0]])
    """
    xs = data["x"]
    ranked = []
    verdicts = data.get("verdicts") or {}
    for cid, ms in data["margins"].items():
        vals = [m for m in ms if _finite(m)]
        if vals:
            seen = set(verdicts.get(cid) or ())
            fails = "fail" in seen or (not seen and min(vals) < 0)
            advisory = "warning" in seen and not fails  # an advisory check: after the ones that decide the verdict
            ranked.append((not fails, advisory, min(vals), cid))
    ranked.sort()
    chosen = [r[-1] for r in ranked[:show]]
    series = []
    for i, cid in enumerate(chosen):
        pts = [[float(x), round(100.0 * m, 4) if _finite(m) else None] for x, m in zip(xs, data["margins"][cid])]
        series.append({"type": "line", "name": labels.get(cid, cid), "data": pts, "showSymbol": False,
                       "lineStyle": {"color": PALETTE[i % len(PALETTE)]},
                       "itemStyle": {"color": PALETTE[i % len(PALETTE)]}})
    if series:
        series[0]["markLine"] = {"symbol": "none", "silent": True, "data": [
            {"xAxis": float(data["design_x"]), "name": "design point", "lineStyle": {"color": "#000", "type": "solid"},
             "label": {"formatter": "design point", "position": "end"}},
            {"yAxis": 0, "name": "limit", "lineStyle": {"color": _FAIL, "type": "dashed"},
             "label": {"formatter": "limit (margin 0 %)", "position": "insideEndTop"}}]}
    name = data["field"] + (f" [{unit}]" if unit and unit != "-" else "")
    return {"title": {"text": f"Margins against {data['field']}", "textStyle": {"fontSize": 13}},
            "legend": {"data": [s["name"] for s in series], "type": "scroll", "bottom": 0},
            "tooltip": {"trigger": "axis", ":valueFormatter": "(v) => v == null ? '-' : v.toFixed(1) + ' %'"},
            "grid": {"containLabel": True, "left": 8, "right": 24, "top": 40, "bottom": 48},
            "xAxis": {"type": "value", "name": name, "nameLocation": "middle", "nameGap": 24, "scale": True,
                      "min": float(xs[0]), "max": float(xs[-1])},
            "yAxis": {"type": "value", "name": "margin [%]"}, "series": series}
