"""Pictures of a synthesised tensioner for a design review: the exploded view and the section (Fig. 75-76).

Both are shaded orthographic views drawn with matplotlib from the tessellation
(painter's algorithm; no screen, no OpenGL):

* :func:`exploded_picture`: the parts pulled apart along the pivot axis by
  stack level (:func:`exploded_parts`), each labelled with a leader line;
* :func:`section_picture`: the half of the model behind the plane ``y = 0``
  through the pivot, bearing and bolt axes (:func:`section_parts`), seen square
  to the cut; the cut faces hatched, a legend of the parts, and the key
  dimensions (:func:`section_dimensions`: pulley diameter, belt-plane height,
  pivot height, pivot bushing length, spring housing diameter and height) drawn
  as dimension lines with their values read from the model's geometry.

The title is wrapped to the figure width, so it is never cut.

>>> from synth.cad.assembly import build
>>> from synth.cad.dimensions import geometry_from, _example_values, _example_inputs
>>> m = build(geometry_from(_example_values(), inputs=_example_inputs()))
>>> ex = exploded_parts(m)
>>> bb = {n: s.BoundingBox() for n, s in ex.items()}
>>> round(bb["pulley"].zmin - bb["ball_bearing"].zmax, 1)   # each level one explode step (9 mm) clear of the last
9.0
>>> [(d.label, round(d.value_mm, 2)) for d in section_dimensions(m)][:3]
[('pulley', 66.0), ('belt plane', 29.5), ('pivot height', 39.7)]
"""

from __future__ import annotations

import textwrap
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from synth import catalog
from synth.cad.assembly import TensionerModel, colour_of
from synth.cad.solids import stack
from synth.io.outputs import write_figure

__all__ = ["EXPLODE_LEVEL", "exploded_parts", "section_parts", "Dimension", "section_dimensions", "render_png",
           "exploded_picture", "section_picture"]

#: exploded-view level of each part, spring side first (the stack order of Fig. 75)
EXPLODE_LEVEL = {"support_plate": 0, "pivot": 0, "spring_bushing": 1, "main_spring": 2, "cone_spring": 3,
                 "damper_pad": 4, "pivot_bushing": 5, "arm": 6, "ball_bearing": 7, "pulley": 8, "endcap_spacer": 9,
                 "endcap": 10}

#: text sizes [pt] of the pictures as drawn: dimensions of the section, part labels of the exploded view. The report
#: prints a picture alone across the page, at most synth.report.html.CAD_PRINT_MAX_HEIGHT_MM high: on A4 the text
#: stays at 6 pt or more (tests/test_control.py computes it from these numbers)
DIMENSION_PT = 8.0
LABEL_PT = 9.0

_HATCH = "////"
_CUT_TOL_MM = 1e-3


def exploded_parts(model: TensionerModel) -> dict:
    """Parts pulled apart along the pivot axis by stack level (Fig. 75), each level clear of the one below by the
    explode step (``cad_explode_step_mm``): no part hides inside another (the bearing inside the pulley, the
    bushing inside the arm); the bolt lifted above everything.

    Standard layout: the spring side (support plate) stays, the rest rises; reverse layout: the spring side is on
    top, so the levels rise from the endcap (housing cover) downwards and the support plate end moves down.
    """
    import cadquery as cq
    step = catalog.constant("cad_explode_step_mm")
    sign = 1.0 if model.geometry.layout == "standard" else -1.0
    levels: dict = {}
    for n in model.parts:
        if n == "fixation_bolt":
            continue
        level = EXPLODE_LEVEL.get(n, 0)
        if model.geometry.layout == "reverse" and n in ("support_plate", "endcap"):
            level = 0 if n == "endcap" else 10
        levels.setdefault(level, []).append(n)

    def span(names):  # the parts' extent along the explode direction (sign * z)
        boxes = [model.parts[n].BoundingBox() for n in names]
        z = [v for b in boxes for v in (sign * b.zmin, sign * b.zmax)]
        return min(z), max(z)
    out, end = {}, None
    for level in sorted(levels):
        lo, hi = span(levels[level])
        shift = 0.0 if end is None else max(0.0, end + step - lo)
        for n in levels[level]:
            out[n] = model.parts[n].translate(cq.Vector(0, 0, sign * shift))
        end = hi + shift if end is None else max(end, hi + shift)
    if "fixation_bolt" in model.parts:
        lo, _ = span(["fixation_bolt"])
        shift = max(0.0, (end if end is not None else lo) + step - lo)
        out["fixation_bolt"] = model.parts["fixation_bolt"].translate(cq.Vector(0, 0, sign * shift))
    return out


def section_parts(model: TensionerModel) -> dict:
    """Every part cut by the plane y = 0 through the pivot, bearing and bolt axes; the y >= 0 half kept (Fig. 76)."""
    import cadquery as cq
    bb = model.compound().BoundingBox()
    size = 4 * max(bb.xlen, bb.ylen, bb.zlen) + 100
    half = cq.Solid.makeBox(size, size, size, cq.Vector(-size / 2, 0, -size / 2))
    out = {}
    for n, s in model.parts.items():
        cut = s.intersect(half)
        if cut.Solids():
            out[n] = cut
    return out


@dataclass(frozen=True)
class Dimension:
    """A dimension line in the section plane (x, z in mm): from ``a`` to ``b``, its value and what it measures.

    ``feature`` is where the extension lines run to: the x of the measured edge for a vertical
    dimension, its z for a horizontal one.
    """

    label: str
    value_mm: float
    a: tuple
    b: tuple
    feature: float
    diameter: bool = False

    @property
    def text(self) -> str:
        return f"{'ø' if self.diameter else ''}{self.value_mm:.4g} {self.label}"


def section_dimensions(model: TensionerModel) -> list[Dimension]:
    """The key dimensions of the section view, measured on the built parts (their bounding boxes) in mm.

    Pulley diameter (above everything), belt-plane height above the crankcase face (right of the
    pulley), pivot height and pivot bushing length (left of the housing), spring housing outer
    diameter (under the crankcase face) and housing height (between the bushing flange and the arm).
    Values are the geometry's (the stack-up of :func:`synth.cad.solids.stack`), positions the parts' boxes.
    """
    g = model.geometry
    boxes = {n: s.BoundingBox() for n, s in model.parts.items()}
    whole = model.compound().BoundingBox()
    gap = 0.08 * max(whole.xlen, whole.zlen)
    s = stack(g)
    e, r_pulley = g.working_arm_mm, 0.5 * g.pulley_diameter_mm
    w = 0.5 * g.pulley_width_mm
    pulley_top = max(s.z_span(s.bearing_centre_u - w, s.bearing_centre_u + w))
    pivot_top = max(s.z_span(*s.pivot_u))
    right = boxes["pulley"].xmax + gap
    left = whole.xmin - gap
    bush = s.z_span(s.hub_bottom_u, s.hub_bottom_u + g.pivot_bushing_length_mm)
    housing = s.z_span(s.flange_top_u, s.cavity_top_u)
    rh = 0.5 * g.spring_housing_outer_diameter_mm
    low = min(whole.zmin, 0.0) - 0.5 * gap
    r_pivot = 0.5 * g.pivot_diameter_mm
    return [
        Dimension("pulley", g.pulley_diameter_mm, (e - r_pulley, whole.zmax + 0.5 * gap),
                  (e + r_pulley, whole.zmax + 0.5 * gap), pulley_top, True),
        Dimension("belt plane", g.belt_plane_height_mm, (right, 0.0), (right, g.belt_plane_height_mm), e + r_pulley),
        Dimension("pivot height", pivot_top, (left, 0.0), (left, pivot_top), -r_pivot),
        Dimension("pivot bushing", g.pivot_bushing_length_mm, (left - gap, bush[0]), (left - gap, bush[1]),
                  -r_pivot - g.pivot_bushing_radial_thickness_mm),
        Dimension("spring housing", g.spring_housing_outer_diameter_mm, (-rh, low), (rh, low), 0.0, True),
        Dimension("housing height", housing[1] - housing[0], (left - 2 * gap, housing[0]), (left - 2 * gap, housing[1]),
                  -rh),
    ]


def _view_axes(view: str):
    v = {"iso": np.array([1.0, -1.6, 0.9]), "section": np.array([0.0, -1.0, 0.0])}[view]
    v = v / np.linalg.norm(v)
    f = -v
    right = np.cross(f, [0.0, 0.0, 1.0])
    right /= np.linalg.norm(right)
    up = np.cross(right, f)
    return v, right, up


def _is_cut(face) -> bool:
    """A planar face lying in the section plane y = 0."""
    bb = face.BoundingBox()
    return face.geomType() == "PLANE" and abs(bb.ymin) < _CUT_TOL_MM and abs(bb.ymax) < _CUT_TOL_MM


def _triangles(shape, tol: float):
    verts, tris = shape.tessellate(tol, 0.3)
    if not tris:
        return None
    P = np.array([[p.x, p.y, p.z] for p in verts])
    return P[np.asarray(tris, dtype=int)]


def _draw(ax, shapes: dict, view: str, *, hatch_cut: bool, flat: dict | None = None) -> dict:
    """Shaded triangles of every part (and hatched cut faces); returns ``{name: projected points}``.

    ``flat`` (``{name: rgb}``) paints each part in one unshaded colour instead (a picking image).
    """
    from matplotlib.collections import PolyCollection

    v, right, up = _view_axes(view)
    light = np.array([0.4, -0.6, 0.7])
    light /= np.linalg.norm(light)
    tol = catalog.constant("cad_helix_tolerance_mm") * 4
    polys, depth, colours, cut_polys, projected = [], [], [], [], {}
    for name, shape in shapes.items():
        faces = shape.Faces() if hatch_cut else [shape]
        base = np.array(colour_of(name)[:3])
        for face in faces:
            tri = _triangles(face, tol)
            if tri is None:
                continue
            xy = np.stack([tri @ right, tri @ up], axis=-1)
            projected.setdefault(name, []).append(xy.reshape(-1, 2))
            if hatch_cut and _is_cut(face):
                cut_polys.append((xy, base))
                continue
            n = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
            n /= np.maximum(np.linalg.norm(n, axis=1, keepdims=True), 1e-12)
            shade = 0.35 + 0.65 * np.abs(n @ light)
            polys.append(xy)
            depth.append((tri @ v).mean(axis=1))
            colours.append(np.tile(flat[name], (len(tri), 1)) if flat else np.clip(base[None, :] * shade[:, None], 0, 1))
    if polys:
        xy = np.concatenate(polys)
        order = np.argsort(np.concatenate(depth))
        col = np.concatenate(colours)[order]
        ax.add_collection(PolyCollection(xy[order], facecolors=col, edgecolors=col, linewidths=0.0 if flat else 0.2,
                                         antialiased=not flat, zorder=1))
    for xy, base in cut_polys:  # in the cut plane, the nearest to the viewer: on top, hatched
        face = np.clip(0.55 + 0.45 * base, 0, 1)
        ax.add_collection(PolyCollection(xy, facecolors=[face], edgecolors="none", zorder=2))
        ax.add_collection(PolyCollection(xy, facecolors="none", edgecolors=[np.clip(0.55 * base, 0, 1)],
                                         linewidths=0.0, hatch=_HATCH, zorder=3))
    return {n: np.concatenate(p) for n, p in projected.items()}


def _figure(title: str, size_in: float, dpi: int, legend: bool):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    width = size_in * (1.45 if legend else 1.2)
    fig = plt.figure(figsize=(width, size_in), dpi=dpi)
    ax = fig.add_axes([0.02, 0.02, (0.70 if legend else 0.96), 0.86])
    if title:
        fig.suptitle(textwrap.fill(title, int(width * 11)), fontsize=9, y=0.985, va="top")
    return plt, fig, ax


def _frame(ax, points: np.ndarray, extra: np.ndarray | None = None) -> None:
    pts = points if extra is None else np.vstack([points, extra])
    lo, hi = pts.min(axis=0), pts.max(axis=0)
    pad = 0.04 * (hi - lo).max()
    ax.set_xlim(lo[0] - pad, hi[0] + pad)
    ax.set_ylim(lo[1] - pad, hi[1] + pad)
    ax.set_aspect("equal")
    ax.axis("off")


def _save(plt, fig, path) -> Path:
    return write_figure(fig, path)


def _pretty(name: str) -> str:
    return name.replace("_", " ")


def render_png(shapes: dict, path: str | Path, *, view: str = "iso", title: str = "", size_in: float = 6.0,
               dpi: int = 110) -> Path:
    """Shaded orthographic picture of ``{name: shape}`` (colours from the catalog), no annotations."""
    plt, fig, ax = _figure(title, size_in, dpi, legend=False)
    projected = _draw(ax, shapes, view, hatch_cut=False)
    _frame(ax, np.concatenate(list(projected.values())))
    return _save(plt, fig, path)


def _visible_anchors(shapes: dict, fig, ax, view: str) -> dict:
    """Where each label's leader line ends: the right-most *visible* pixel of the part, in data coordinates.

    The parts are painted again in one flat colour each (same axes, same painter's order) into an
    off-screen image; a part hidden everywhere gets no anchor.
    """
    import matplotlib.pyplot as plt
    names = list(shapes)
    ids = {n: np.array([(i + 1) % 256, (i + 1) // 256, 0]) / 255.0 for i, n in enumerate(names)}
    pick = plt.figure(figsize=fig.get_size_inches(), dpi=fig.dpi)
    pax = pick.add_axes(ax.get_position())
    pax.set_xlim(ax.get_xlim())
    pax.set_ylim(ax.get_ylim())
    pax.set_aspect("equal")
    pax.axis("off")
    _draw(pax, shapes, view, hatch_cut=False, flat=ids)
    pick.canvas.draw()
    img = np.asarray(pick.canvas.buffer_rgba())[..., :3].astype(int)
    height = img.shape[0]
    code = img[..., 0] + 256 * img[..., 1] - 256 * 256 * (img[..., 2] > 0)
    anchors = {}
    for i, n in enumerate(names):
        rows, cols = np.nonzero(code == i + 1)
        if cols.size:
            k = np.argmax(cols)
            anchors[n] = pax.transData.inverted().transform((cols[k] + 0.5, height - rows[k] - 0.5))
    plt.close(pick)
    return anchors


def exploded_picture(model: TensionerModel, path: str | Path, *, title: str = "", size_in: float = 6.5,
                     dpi: int = 110) -> Path:
    """The exploded view (Fig. 75), every part labelled with a leader line to its right-most visible point."""
    plt, fig, ax = _figure(title, size_in, dpi, legend=False)
    shapes = exploded_parts(model)
    projected = _draw(ax, shapes, "iso", hatch_cut=False)
    allpts = np.concatenate(list(projected.values()))
    lo, hi = allpts.min(axis=0), allpts.max(axis=0)
    x_text = hi[0] + 0.12 * (hi[0] - lo[0])
    _frame(ax, allpts, np.array([[x_text + 0.28 * (hi[0] - lo[0]), hi[1]]]))
    anchors = _visible_anchors(shapes, fig, ax, "iso")
    order = sorted(anchors, key=lambda n: anchors[n][1])
    spacing = 0.045 * (hi[1] - lo[1])
    y_prev = -np.inf
    text_y = {}
    for n in order:  # labels at their part's height, pushed apart to keep a line's spacing
        y_prev = max(anchors[n][1], y_prev + spacing)
        text_y[n] = y_prev
    for n in order:
        ax.annotate(_pretty(n), xy=anchors[n], xytext=(x_text, text_y[n]), fontsize=LABEL_PT, va="center", ha="left",
                    arrowprops=dict(arrowstyle="-", lw=0.5, color="0.3", shrinkA=2, shrinkB=0), zorder=5)
    top = max(text_y.values(), default=hi[1])
    if top > hi[1]:  # labels pushed above the parts: make room
        ax.set_ylim(ax.get_ylim()[0], top + 0.04 * (hi[1] - lo[1]))
    return _save(plt, fig, path)


def _dimension(ax, d: Dimension) -> None:
    (x0, y0), (x1, y1) = d.a, d.b
    ax.annotate("", xy=(x0, y0), xytext=(x1, y1), zorder=6,
                arrowprops=dict(arrowstyle="<|-|>", lw=0.6, color="0.1", mutation_scale=6, shrinkA=0, shrinkB=0))
    vertical = abs(x1 - x0) < abs(y1 - y0)
    for x, y in d.a, d.b:  # extension lines to the measured edge
        ax.plot([x, d.feature] if vertical else [x, x], [y, y] if vertical else [y, d.feature],
                color="0.35", lw=0.35, zorder=5)
    kw = dict(fontsize=DIMENSION_PT, zorder=7, color="0.1",
              bbox=dict(boxstyle="round,pad=0.15", fc="white", ec="none", alpha=0.85))
    if vertical:
        ax.text(x0, 0.5 * (y0 + y1), d.text, rotation=90, ha="center", va="center", **kw)
    else:
        ax.text(0.5 * (x0 + x1), y0, d.text, ha="center", va="center", **kw)


def section_picture(model: TensionerModel, path: str | Path, *, title: str = "", size_in: float = 6.5,
                    dpi: int = 110) -> Path:
    """The section (Fig. 76): hatched cut faces, a legend of the parts, the key dimensions, the belt plane."""
    from matplotlib.patches import Patch
    plt, fig, ax = _figure(title, size_in, dpi, legend=True)
    shapes = section_parts(model)
    projected = _draw(ax, shapes, "section", hatch_cut=True)
    dims = section_dimensions(model)
    for d in dims:
        _dimension(ax, d)
    g = model.geometry
    pts = np.concatenate(list(projected.values()))
    ax.plot([pts[:, 0].min(), pts[:, 0].max()], [0.0, 0.0], color="0.25", lw=0.8, zorder=4)  # crankcase face
    ax.plot([pts[:, 0].min(), pts[:, 0].max()], [g.belt_plane_height_mm] * 2, color="0.25", lw=0.5, ls="-.", zorder=4)
    ax.plot([0.0, 0.0], [pts[:, 1].min(), pts[:, 1].max()], color="0.4", lw=0.5, ls="-.", zorder=4)  # pivot axis
    ends = np.array([p for d in dims for p in (d.a, d.b)])
    _frame(ax, pts, ends)
    handles = [Patch(facecolor=colour_of(n)[:3], edgecolor="0.3", label=_pretty(n)) for n in shapes]
    handles.append(Patch(facecolor="white", edgecolor="0.3", hatch=_HATCH, label="cut face"))
    fig.legend(handles=handles, loc="center right", fontsize=7, frameon=False, title="parts", title_fontsize=8,
               bbox_to_anchor=(0.995, 0.5))
    return _save(plt, fig, path)
