"""Export of a :class:`~synth.cad.assembly.TensionerModel`: STEP assembly, STL per part, pictures.

* ``tensioner.step``: one STEP assembly, every part a named, coloured child
  (read back with ``cadquery.Assembly.importStep``);
* ``stl/<part>.stl``: one binary STL per part (tessellation tolerance
  ``cad_helix_tolerance_mm``);
* ``exploded.png`` and ``section.png``: the thesis's Fig. 75 (parts pulled
  apart along the pivot axis) and Fig. 76 (the half of the model behind the
  plane through the pivot and bearing axes, seen square to the cut), drawn
  with matplotlib from the tessellation (no screen needed, ~50-150 kB);
* ``cad_report.json``: result status, geometry, checks and timings.

>>> from synth.cad.assembly import build
>>> from synth.cad.dimensions import geometry_from, _example_values, _example_inputs
>>> m = build(geometry_from(_example_values(), inputs=_example_inputs()))
>>> ex = exploded_parts(m)
>>> round(ex["endcap"].BoundingBox().zmin - m.parts["endcap"].BoundingBox().zmin, 1)   # level 10 x 9 mm
90.0
"""

from __future__ import annotations

import json
import time
from pathlib import Path

import numpy as np

from synth import catalog
from synth.cad.assembly import TensionerModel, colour_of

__all__ = ["export_step", "export_stl", "render_png", "exploded_parts", "section_parts", "export_model"]


def export_step(model: TensionerModel, path: str | Path) -> Path:
    """Write the STEP assembly (names and colours kept)."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    model.assembly().export(str(path), exportType="STEP")
    return path


def export_stl(model: TensionerModel, folder: str | Path) -> list[Path]:
    """One STL per part in ``folder``."""
    import cadquery as cq
    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    tol = catalog.constant("cad_helix_tolerance_mm")
    out = []
    for name, shape in model.parts.items():
        p = folder / f"{name}.stl"
        cq.exporters.export(shape, str(p), tolerance=tol, angularTolerance=0.2)
        out.append(p)
    return out


#: exploded-view level of each part, spring side first (the stack order of Fig. 75)
EXPLODE_LEVEL = {"support_plate": 0, "pivot": 0, "spring_bushing": 1, "main_spring": 2, "cone_spring": 3,
                 "damper_pad": 4, "pivot_bushing": 5, "arm": 6, "ball_bearing": 7, "pulley": 8, "endcap_spacer": 9,
                 "endcap": 10}


def exploded_parts(model: TensionerModel) -> dict:
    """Parts pulled apart along the pivot axis by stack level (Fig. 75); the bolt lifted above everything.

    Standard layout: the spring side (support plate) stays, the rest rises; reverse layout: the spring side is on
    top, so the levels rise from the endcap (housing cover) downwards and the support plate end moves down.
    """
    import cadquery as cq
    step = catalog.constant("cad_explode_step_mm")
    sign = 1.0 if model.geometry.layout == "standard" else -1.0
    out = {}
    for n, s in model.parts.items():
        if n == "fixation_bolt":
            continue
        level = EXPLODE_LEVEL.get(n, 0)
        if model.geometry.layout == "reverse" and n in ("support_plate", "endcap"):
            level = 0 if n == "endcap" else 10
        out[n] = s.translate(cq.Vector(0, 0, sign * level * step))
    if "fixation_bolt" in model.parts:
        up = 12 * step if sign > 0 else 2 * step
        out["fixation_bolt"] = model.parts["fixation_bolt"].translate(cq.Vector(0, 0, up))
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


def _view_axes(view: str):
    v = {"iso": np.array([1.0, -1.6, 0.9]), "section": np.array([0.0, -1.0, 0.0])}[view]
    v = v / np.linalg.norm(v)
    f = -v
    right = np.cross(f, [0.0, 0.0, 1.0])
    right /= np.linalg.norm(right)
    up = np.cross(right, f)
    return v, right, up


def render_png(shapes: dict, path: str | Path, *, view: str = "iso", title: str = "", size_in: float = 6.0,
               dpi: int = 110) -> Path:
    """Shaded orthographic picture of ``{name: shape}`` (colours from the catalog), painter's algorithm."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.collections import PolyCollection

    v, right, up = _view_axes(view)
    light = np.array([0.4, -0.6, 0.7])
    light /= np.linalg.norm(light)
    tol = catalog.constant("cad_helix_tolerance_mm") * 4
    polys, depth, colours = [], [], []
    for name, shape in shapes.items():
        verts, tris = shape.tessellate(tol, 0.3)
        if not tris:
            continue
        P = np.array([[p.x, p.y, p.z] for p in verts])
        T = np.asarray(tris, dtype=int)
        a, b, c = P[T[:, 0]], P[T[:, 1]], P[T[:, 2]]
        n = np.cross(b - a, c - a)
        n /= np.maximum(np.linalg.norm(n, axis=1, keepdims=True), 1e-12)
        shade = 0.35 + 0.65 * np.abs(n @ light)
        base = np.array(colour_of(name)[:3])
        col = np.clip(base[None, :] * shade[:, None], 0, 1)
        tri = P[T]
        xy = np.stack([tri @ right, tri @ up], axis=-1)
        polys.append(xy)
        depth.append((tri @ v).mean(axis=1))
        colours.append(col)
    xy = np.concatenate(polys)
    order = np.argsort(np.concatenate(depth))
    col = np.concatenate(colours)[order]
    fig, ax = plt.subplots(figsize=(size_in, size_in), dpi=dpi)
    ax.add_collection(PolyCollection(xy[order], facecolors=col, edgecolors=col, linewidths=0.2))
    lo, hi = xy.reshape(-1, 2).min(axis=0), xy.reshape(-1, 2).max(axis=0)
    pad = 0.05 * (hi - lo).max()
    ax.set_xlim(lo[0] - pad, hi[0] + pad)
    ax.set_ylim(lo[1] - pad, hi[1] + pad)
    ax.set_aspect("equal")
    ax.axis("off")
    if title:
        ax.set_title(title, fontsize=9)
    fig.tight_layout()
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(path)
    plt.close(fig)
    return path


def export_model(model: TensionerModel, out_dir: str | Path, *, checks=None, step: bool = True, stl: bool = True,
                 pictures: bool = True) -> dict:
    """Write everything to ``out_dir``; returns ``{"files": [...], "timings_s": {...}}`` and writes ``cad_report.json``."""
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    files, times = [], {"build": model.build_s}
    g = model.geometry
    label = f"{g.name} | {g.layout} | {g.status}" + ("" if g.feasible else " (INFEASIBLE: nearest design)")
    if step:
        t = time.perf_counter()
        files.append(export_step(model, out / "tensioner.step"))
        times["step"] = time.perf_counter() - t
    if stl:
        t = time.perf_counter()
        files += export_stl(model, out / "stl")
        times["stl"] = time.perf_counter() - t
    if pictures:
        t = time.perf_counter()
        files.append(render_png(exploded_parts(model), out / "exploded.png", view="iso", title="exploded view | " + label))
        files.append(render_png(section_parts(model), out / "section.png", view="section",
                                title="section through the pivot axis | " + label))
        times["pictures"] = time.perf_counter() - t
    report = {"status": g.status, "feasible": g.feasible, "geometry": g.as_dict(),
              "parts": list(model.parts), "files": [str(f.relative_to(out)) for f in files], "timings_s": times,
              "checks": [c.as_dict() for c in (checks or [])]}
    (out / "cad_report.json").write_text(json.dumps(report, indent=2, default=str), encoding="utf-8")
    files.append(out / "cad_report.json")
    return {"files": files, "timings_s": times}
