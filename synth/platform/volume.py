"""A platform part's unit price at the volume of every application it serves: the volume saving of a common part.

A part bought for several applications is bought in their summed annual volume ``V_j = sum_a V_a``, so its unit
price is taken at the quantity break of ``V_j`` (the price book of :mod:`synth.cost.book` at that volume: the
distributor's break curve of the bought-in parts, the breaks of a company's price file), not at each application's
own volume. :func:`price_curves` tabulates every platform part's unit price at each break quantity (a step
function of the volume, non-increasing: a larger order is never priced above a smaller one, so a price that rises
with the quantity is held at the smaller break's); :func:`volume_saving` prices the parts of the assigned designs
both ways and reports the difference.

What each family's part price is (:mod:`synth.cost.columns`): the bearing; the damper pad; the bushing (supplier
and length); the endcap spacer; the cone spring; the main spring's per-spring term (its wire and coiling per
metre follow each application's stiffness and stay in the application's own price); the bolt with its washer and
tightening premium. The pivot class is no bought or made part of its own (its price is in the bushing's and the
bearing's).

The pooled prices apply only when the portfolio gives annual volumes (a volume column): without one every
application counts one unit in the cost objective, and no pooled volume is meaningful.

>>> import numpy as np
>>> c = PriceCurves(np.array([1.0, 1000.0]), {"bolt": np.array([[0.10, 0.05]])})
>>> float(c.price("bolt", np.array([0]), np.array([999.0]))[0]), float(c.price("bolt", np.array([0]),
...                                                                             np.array([1500.0]))[0])
(0.1, 0.05)
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from synth.platform.data import FAMILIES, PortfolioFeasibility

__all__ = ["PriceCurves", "price_curves", "volume_saving", "saving_text", "app_volumes"]


@dataclass
class PriceCurves:
    """``quantity``: ``(K,)`` break quantities ascending (the first at most every volume); ``prices[f]``:
    ``(n_f, K)`` unit price [EUR] of every part of family ``f`` from each break on (non-increasing along ``K``);
    a family without an entry has no price of its own."""

    quantity: np.ndarray
    prices: dict

    def price(self, family: str, codes, volume) -> np.ndarray:
        """Unit price [EUR] of parts ``codes`` of ``family`` bought in ``volume`` pieces a year (0 for none)."""
        codes = np.asarray(codes, np.int64)
        if family not in self.prices:
            return np.zeros(len(codes))
        k = np.maximum(np.searchsorted(self.quantity, np.asarray(volume, float), side="right") - 1, 0)
        return self.prices[family][codes, k]


def _quantities() -> np.ndarray:
    """Every quantity at which some price of the current catalogs breaks (the curve's and each price row's)."""
    from synth.cost.book import _curve, _rows
    qs = {1.0} | {float(q) for q, _, _ in _curve()}
    for r in _rows().values():
        qs |= {float(q) for q, _ in r.breaks}
    return np.array(sorted(qs))


def _family_prices(book, cat) -> dict:
    """``{family: (n_f,) unit price}`` of the platform's parts in ``book`` (see the module docstring)."""
    from synth.cost import columns
    sp = cat.space
    out = {"ball_bearing": np.asarray(book.bearing, float), "damper_pad_class": np.asarray(book.damper_pad, float),
           "endcap_spacer_class": np.asarray(book.endcap_spacer, float),
           "cone_spring": np.full(len(cat.pf_parts["cone_spring"]), float(book.cone_spring.eur)),
           "main_spring": np.full(len(cat.pf_parts["main_spring"]), float(book.spring_piece.eur))}
    for s, f, price in (("bushing", "pivot_bushing",
                         lambda t, rows: columns.bushing_eur(book, t["supplier_code"][rows],
                                                             t["pivot_bushing_length_mm"][rows])),
                        ("bolt", "bolt", lambda t, rows: columns.bolt_eur(book, t["head_code"][rows],
                                                                         t["class_code"][rows], t["washer_code"][rows],
                                                                         t["tightening_code"][rows]))):
        codes = np.asarray(cat.options[s][f])
        first = np.unique(codes, return_index=True)[1]          # one option row per part (its price is the part's)
        p = np.zeros(len(cat.pf_parts[f]))
        p[codes[first]] = price(sp.tables[s], np.asarray(cat.option_row[s])[first])
        out[f] = p
    return out


def price_curves(pf: PortfolioFeasibility) -> PriceCurves | None:
    """The :class:`PriceCurves` of ``pf``'s parts under its catalog setting, or None where no price depends on
    the volume of one part (synthetic data: no catalogs; no volume column in the portfolio)."""
    cat = getattr(pf, "catalogue", None)
    if cat is None or not getattr(pf, "volumes_given", False):
        return None
    from synth import catalog
    from synth.cost.book import book_for
    with catalog.using(getattr(pf.settings, "catalogs", None)):
        q = _quantities()
        per_q = [_family_prices(book_for(cat.space.parts, float(v)), cat) for v in q]
    prices = {f: np.minimum.accumulate(np.stack([d[f] for d in per_q], axis=1), axis=1) for f in per_q[0]}
    return PriceCurves(q, prices)


def app_volumes(pf: PortfolioFeasibility) -> dict:
    """``{application id: annual volume}``."""
    return {a.app_id: float(a.volume) for a in pf.apps}


def volume_saving(pf: PortfolioFeasibility, records: list, curves: PriceCurves | None) -> dict | None:
    """What buying each platform part in the summed volume of the applications it serves saves against each
    application buying it in its own volume, over the served ``records`` (:func:`synth.platform.assign.assign`):
    ``{"saving_eur", "saving_pct", "own_eur", "pooled_eur", "per_part"}`` (EUR a year; the percent of ``own_eur``,
    what the served designs' volume-priced parts cost at each application's own volume; ``per_part``: per platform
    part in use, family, part, applications, pooled volume, own and pooled spend and their difference, the largest
    saving first); None without ``curves``."""
    if curves is None:
        return None
    vol = app_volumes(pf)
    ok = [r for r in records if r["feasible"]]
    own, pooled, rows = 0.0, 0.0, []
    for f in FAMILIES:
        pairs = [(int(r["codes"][f]), vol[r["app_id"]]) for r in ok if int(r["codes"].get(f, -1)) >= 0]
        if not pairs:
            continue
        code, v = (np.array(x) for x in zip(*pairs))
        parts, inv = np.unique(code, return_inverse=True)
        pooled_v = np.bincount(inv, weights=v)
        spend_own = np.bincount(inv, weights=v * curves.price(f, code, v))
        spend_pool = pooled_v * curves.price(f, parts, pooled_v)
        own += float(spend_own.sum())
        pooled += float(spend_pool.sum())
        for i, c in enumerate(parts):
            rows.append({"family": f, "part": pf.part_key(f, int(c)), "applications": int(np.sum(inv == i)),
                         "pooled_volume": float(pooled_v[i]), "own_eur": float(spend_own[i]),
                         "pooled_eur": float(spend_pool[i]), "saving_eur": float(spend_own[i] - spend_pool[i])})
    saving = own - pooled
    rows.sort(key=lambda r: -r["saving_eur"])
    return {"saving_eur": saving, "saving_pct": saving / own if own else 0.0, "own_eur": own, "pooled_eur": pooled,
            "per_part": rows}


def saving_text(s: dict | None) -> str:
    """The volume saving in a few words (the command line's and the summary's).

    >>> saving_text({"saving_eur": 3875.8, "saving_pct": 0.0295}), saving_text(None)
    ('volume saving 3,876 EUR/year (2.95%)', 'volume saving n/a (no annual_volume column)')
    """
    if s is None:
        return "volume saving n/a (no annual_volume column)"
    return f"volume saving {s['saving_eur']:,.0f} EUR/year ({s['saving_pct']:.2%})"
