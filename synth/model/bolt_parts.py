"""Step 10's parts from the catalogs: bolt formats, head forms and property classes (the candidates of the
escalation, :func:`bolt_candidates`), washers, and the head's bearing on the support (the screw's own head, a
washer, the seat).

Thread data ``catalogs/bolts.csv`` (ISO 261/262/724, ISO 898-1 A_s), head forms ``catalogs/bolt_heads.csv``,
washers ``catalogs/washers.csv`` (ISO 7089, ISO 7093-1), classes ``catalogs/bolt_property_classes.csv``
(ISO 898-1).
"""

from __future__ import annotations

import numpy as np

from synth import catalog as _catalog
from synth.catalog import load
from synth.errors import CatalogError, InputError, Problem
from synth.model.input_guards import as_array as _arr
from synth.model.vdi2230 import HEAD_TYPES

__all__ = ["bolt_head", "bolt_candidates", "NO_WASHER", "washer_series", "washer_dimensions",
           "head_bearing_diameter_mm", "head_friction_diameter_mm"]


def bolt_head(bolt_format: str, head_type: str = "hex"):
    """The ``catalogs/bolt_heads.csv`` row of a thread format in a head form (a pandas Series).

    Head forms: ``hex`` (ISO 4017, fine pitch ISO 8676), ``flange`` (ISO 4162 /
    ISO 15071), ``socket`` (ISO 4762 / ISO 12474). Columns ``dw_min_mm``
    (bearing-face diameter), ``head_outer_mm`` (s, dc or dk), ``head_height_mm``,
    ``product_standard`` (prices: :mod:`synth.cost`).

    >>> float(bolt_head("M8x1.25", "flange")["dw_min_mm"]), str(bolt_head("M8x1", "socket")["product_standard"])
    (14.9, 'ISO 12474')
    """
    if head_type not in HEAD_TYPES:
        raise InputError(Problem("head_type", head_type, "one of " + ", ".join(HEAD_TYPES)))
    heads = load("bolt_heads")
    hit = heads[(heads["bolt_format"] == str(bolt_format).strip()) & (heads["head_type"] == head_type)]
    if hit.empty:
        raise CatalogError(Problem("bolt_format", bolt_format, f"a format with a {head_type} head: "
                                   + ", ".join(heads.loc[heads["head_type"] == head_type, "bolt_format"])))
    return hit.iloc[0].copy()


_NUMERIC_BOLT_COLUMNS = ("d_mm", "pitch_mm", "d2_mm", "d3_mm", "D1_mm", "stress_area_mm2", "pivot_bore_min_mm")


def bolt_candidates(bolt_format: str | None = None, property_class: str | None = None, head_type: str = "hex"):
    """The (format, property class) pairs in the flowchart's escalation order, in one head form.

    Automatic mode (``None``): formats with an ``escalation_rank`` in
    ``bolts.csv`` (M8x1.25, M10x1.5, M12x1.75), and for each format the
    classes 8.8, 9.8, 10.9, 12.9 in rank order (thesis section 10: the class
    is raised first, the format when the strongest class yields). Classes not
    defined for the format's diameter (9.8 above 16 mm) are skipped. Naming a
    format or class restricts the list (manual verification). ``head_type``
    (``hex``, ``flange``, ``socket``) picks the head row of
    ``bolt_heads.csv``. Returns a list of dicts with the thread geometry, the
    head (``head_type``, ``dw_min_mm``, ``head_outer_mm``, ``head_height_mm``,
    ``head_product_standard``), ``rp02_mpa`` and ``rm_mpa`` (prices: :mod:`synth.cost`).

    >>> [(c["bolt_format"], c["bolt_property_class"]) for c in bolt_candidates()][:3]
    [('M8x1.25', '8.8'), ('M8x1.25', '9.8'), ('M8x1.25', '10.9')]
    >>> len(bolt_candidates("M10x1.25", "10.9")), bolt_candidates("M8x1.25", "8.8", "socket")[0]["dw_min_mm"]
    (1, 12.33)
    """
    key = (None if bolt_format is None else str(bolt_format).strip(),
           None if property_class is None else str(property_class).strip(), head_type)
    return [dict(c) for c in _candidates_memo(key, (bolt_format, property_class, head_type))]


_CANDIDATES: dict = {}


def _candidates_memo(key, args) -> tuple:
    """:func:`bolt_candidates` memoised per arguments and catalog tables (a user catalog folder, or a cleared
    catalog cache, gives new tables and so a new list). A named format and class is read from the table of every
    (format, class) of its head form, built in one pass; anything else (automatic mode, an unknown name: its
    error) by :func:`_bolt_candidates`."""
    dirs = tuple(_catalog.user_dirs())
    tables = tuple(_catalog.load_cached(n, dirs) for n in ("bolts", "bolt_property_classes", "bolt_heads"))
    hit = _CANDIDATES.get((key, dirs))
    if hit is not None and all(a is b for a, b in zip(hit[0], tables)):
        return hit[1]
    if len(_CANDIDATES) > 4096:
        _CANDIDATES.clear()
    fmt, cls, head = key
    out = None
    if fmt is not None and cls is not None and head in HEAD_TYPES:
        every = _CANDIDATES.get((("*", "*", head), dirs))
        if every is None or not all(a is b for a, b in zip(every[0], tables)):
            every = (tables, _every_candidate(head))
            _CANDIDATES[(("*", "*", head), dirs)] = every
        if (fmt, cls) in every[1]:
            out = (every[1][(fmt, cls)],)
    if out is None:
        out = tuple(_bolt_candidates(*args))
    _CANDIDATES[(key, dirs)] = (tables, out)
    return out


def _every_candidate(head_type) -> dict:
    """``{(format, class): candidate}`` of every defined pair in one head form (one pass over the catalogs)."""
    bolts, classes, heads = load("bolts"), load("bolt_property_classes"), load("bolt_heads")
    key_b, key_c = bolts.columns[0], classes.columns[0]
    head_of = {str(h["bolt_format"]).strip(): h for _, h in heads[heads["head_type"] == head_type].iterrows()}
    out = {}
    for _, b in bolts.iterrows():
        head = head_of.get(str(b[key_b]))
        if head is None:
            continue
        for _, c in classes.iterrows():
            cand = _candidate(b, c, head, head_type, key_b, key_c)
            if cand is not None:
                out[(cand["bolt_format"], cand["bolt_property_class"])] = cand
    return out


def _candidate(b, c, head, head_type, key_b, key_c) -> dict | None:
    """The candidate dict of one bolt row, class row and head row; None for a class not defined at the diameter."""
    if not np.isnan(float(c["d_max_mm"])) and float(b["d_mm"]) > float(c["d_max_mm"]):
        return None
    big = float(b["d_mm"]) > 16.0
    rp = float(c["rp02_min_d_gt16_mpa"] if big else c["rp02_min_mpa"])
    rm = float(c["rm_min_d_gt16_mpa"] if big else c["rm_min_mpa"])
    return {
        "bolt_format": str(b[key_b]), "bolt_property_class": str(c[key_c]),
        **{k: float(b[k]) for k in _NUMERIC_BOLT_COLUMNS},
        "head_type": head_type, "dw_min_mm": float(head["dw_min_mm"]),
        "head_outer_mm": float(head["head_outer_mm"]), "head_height_mm": float(head["head_height_mm"]),
        "head_product_standard": str(head["product_standard"]),
        "rp02_mpa": rp, "rm_mpa": rm,
    }


def _bolt_candidates(bolt_format, property_class, head_type):
    if head_type not in HEAD_TYPES:
        raise InputError(Problem("head_type", head_type, "one of " + ", ".join(HEAD_TYPES)))
    bolts = load("bolts")
    classes = load("bolt_property_classes")
    key_b, key_c = bolts.columns[0], classes.columns[0]
    if bolt_format is None:
        bolts = bolts[bolts["escalation_rank"].notna()].sort_values("escalation_rank")
    else:
        hit = bolts[bolts[key_b] == str(bolt_format).strip()]
        if hit.empty:
            raise CatalogError(Problem("bolt_format", bolt_format, "one of " + ", ".join(load("bolts")[key_b])))
        bolts = hit
    if property_class is None:
        classes = classes.sort_values("escalation_rank")
    else:
        hit = classes[classes[key_c] == str(property_class).strip()]
        if hit.empty:
            raise CatalogError(Problem("bolt_property_class", property_class,
                                       "one of " + ", ".join(load("bolt_property_classes")[key_c])))
        classes = hit
    out = []
    for _, b in bolts.iterrows():
        head = bolt_head(str(b[key_b]), head_type)
        for _, c in classes.iterrows():
            cand = _candidate(b, c, head, head_type, key_b, key_c)
            if cand is not None:
                out.append(cand)
    if not out:
        raise InputError(Problem("bolt_property_class", property_class,
                                 f"a class defined for {bolt_format} (ISO 898-1: 9.8 only up to 16 mm)"))
    return out


# ----------------------------------------------------------------------------------------------
# the head's bearing on the support: the screw's own head, a washer, the seat
# ----------------------------------------------------------------------------------------------

NO_WASHER = "none"


def washer_series() -> tuple:
    """The washer series of ``catalogs/washers.csv`` (its ``product_standard`` column), ``"none"`` first.

    >>> washer_series()
    ('none', 'ISO 7089', 'ISO 7093-1')
    """
    ws = load("washers")
    return (NO_WASHER, *dict.fromkeys(ws["product_standard"].astype(str).str.strip()))


def washer_dimensions(series, d_mm) -> dict:
    """``{"d1_mm", "d2_mm", "h_mm"}``: the bore, outer diameter and thickness of the ``series`` washer
    (``catalogs/washers.csv``) for each bolt diameter ``d_mm`` (arrays; ``"none"``: no washer, NaN
    diameters and 0 thickness). A series without a washer for a diameter is an error naming both.

    >>> w = washer_dimensions("ISO 7089", [8.0, 10.0])
    >>> w["d2_mm"].tolist(), w["h_mm"].tolist()
    ([16.0, 20.0], [1.6, 2.0])
    """
    d = np.atleast_1d(np.asarray(d_mm, dtype=float))
    series = str(series).strip()
    if series == NO_WASHER:
        return {"d1_mm": np.full(d.shape, np.nan), "d2_mm": np.full(d.shape, np.nan), "h_mm": np.zeros(d.shape)}
    by_d = _catalog.parsed("washers", _washers_by_series).get(series)  # read once per loaded table (a hot path)
    if by_d is None:
        raise InputError(Problem("bolt_washer", series, "one of " + ", ".join(washer_series())))
    out = {k: np.empty(d.shape) for k in ("d1_mm", "d2_mm", "h_mm")}
    for di in np.unique(d):  # per distinct diameter (a production sample's rows share a few)
        r = by_d.get(float(di))
        if r is None:
            raise InputError(Problem("bolt_washer", series, f"a series with a washer for M{di:g} "
                                     f"(catalogs/washers.csv has {', '.join(f'M{x:g}' for x in sorted(by_d))})"))
        at = d == di
        for k in out:
            out[k][at] = float(r[k])
    return out


def _washers_by_series(ws) -> dict:
    """``{series: {bolt diameter: {"d1_mm", "d2_mm", "h_mm"}}}`` of ``washers.csv`` (the last row of a diameter
    wins)."""
    out: dict = {}
    for _, r in ws.iterrows():
        out.setdefault(str(r["product_standard"]).strip(), {})[float(r["d_mm"])] = \
            {k: float(r[k]) for k in ("d1_mm", "d2_mm", "h_mm")}
    return out


def head_bearing_diameter_mm(head_dw_mm, washer_d2_mm=np.nan, washer_h_mm=0.0, seat_mm=None):
    """Outer diameter of the head's bearing on the support [mm]: the screw's own, a washer's, within the seat.

    Without a washer (``washer_d2_mm`` NaN) the head's bearing-face diameter
    ``dw`` (``bolt_heads.csv`` ``dw_min_mm``, ISO 4017 / 4162 / 4762). A
    washer under the head spreads the head's load at 45 deg through its
    thickness ``h``: it bears on ``min(d2, dw + 2 h)`` (a thin washer does
    not carry its whole face; synth assumption, the washer being hardened,
    300 HV, so that the head does not indent it). ``seat_mm`` (the
    application's ``bolt_head_contact_external_diameter_mm``, NaN or None:
    no seat) is the support's bearing face: the contact ends there.

    An ISO 4017 M6 head on the default 11 mm seat bears on its own 8.88 mm;
    an M8 flange head (14.9 mm) on it on the seat's 11 mm; an M8 hex head on
    an ISO 7089 washer (16 x 1.6 mm) with no seat on 11.63 + 3.2 = 14.83 mm:

    >>> [float(x) for x in head_bearing_diameter_mm([8.88, 14.9], seat_mm=11.0)]
    [8.88, 11.0]
    >>> round(float(head_bearing_diameter_mm(11.63, 16.0, 1.6)), 2)
    14.83
    """
    dw = _arr(head_dw_mm)
    d2 = _arr(washer_d2_mm)
    out = np.where(np.isfinite(d2), np.minimum(d2, dw + 2.0 * _arr(washer_h_mm)), dw)
    if seat_mm is not None:
        seat = _arr(seat_mm)
        out = np.where(np.isfinite(seat), np.minimum(out, seat), out)
    return out


def head_friction_diameter_mm(head_dw_mm, washer_d2_mm=np.nan, seat_mm=None):
    """Outer diameter of the face the head turns on while tightened [mm] (the under-head friction of eq. (101),
    VDI 2230 D_Km): the head's own face on a washer, or on the support within its seat.

    >>> float(head_friction_diameter_mm(11.63, seat_mm=11.0)), float(head_friction_diameter_mm(11.63, 16.0, 11.0))
    (11.0, 11.63)
    """
    dw = _arr(head_dw_mm)
    if seat_mm is None:
        return dw + 0.0 * np.nan_to_num(_arr(washer_d2_mm))
    seat = _arr(seat_mm)
    return np.where(np.isfinite(_arr(washer_d2_mm)) | ~np.isfinite(seat), dw, np.minimum(dw, seat))
