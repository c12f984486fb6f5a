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

__all__ = ["PriceCurves", "price_curves", "pool_prices", "volume_saving", "saving_text", "app_volumes"]


@dataclass
class PriceCurves:
    """``quantity``: ``(K,)`` break quantities ascending (the first at most every volume); ``prices[f]``:
    ``(n_f, K)`` unit price [EUR] of every part of family ``f`` from each break on (non-increasing along ``K``);
    a family without an entry has no price of its own. ``included[f]``: the unit price of each part that the
    feasibility data's core and option costs already hold (the default volume's, :func:`price_curves`), which
    :func:`pool_prices` replaces."""

    quantity: np.ndarray
    prices: dict
    included: dict | None = None   # family -> (n_f,) the price the feasibility data's unit costs hold (None: 0)

    def price(self, family: str, codes, volume) -> np.ndarray:
        """Unit price [EUR] of parts ``codes`` of ``family`` bought in ``volume`` pieces a year (0 for none)."""
        codes = np.asarray(codes, np.int64)
        if family not in self.prices:
            return np.zeros(len(codes))
        k = np.maximum(np.searchsorted(self.quantity, np.asarray(volume, float), side="right") - 1, 0)
        return self.prices[family][codes, k]


def _quantities() -> np.ndarray:
    """Every quantity at which some price of the current catalogs breaks (the curve's and each price row's)."""
    from synth.cost.book import break_curve, price_rows
    qs = {1.0} | {float(q) for q, _, _ in break_curve()}
    for r in price_rows().values():
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
        default = _family_prices(cat.space.parts.prices, cat)     # what the design space's cost columns hold
    prices = {f: np.minimum.accumulate(np.stack([d[f] for d in per_q], axis=1), axis=1) for f in per_q[0]}
    return PriceCurves(q, prices, default)


def pool_prices(work, curves: PriceCurves) -> int:
    """Price the parts of ``work`` (:class:`synth.platform.compile.Work`, cost objective) at the summed volume of
    the applications they serve, exactly, in the MILP of :mod:`formulations.platform`; returns the number of
    volume breaks left to the MILP.

    Part ``j``'s unit price is the step function ``p_j(V)`` of :class:`PriceCurves`, ``V_j`` the summed volume of
    the applications whose design holds it. A served application's volume is at least the smallest positive volume
    ``v_j`` among the applications that can use ``j``, so every break up to ``v_j`` is always reached: the unit
    costs of the cores and options get ``p_j(v_j)`` in place of the price they held (``included``). Each break
    ``q`` with ``v_j < q <= sum of those volumes`` becomes one break of the MILP, the price falling by the step
    ``p_j(q^-) - p_j(q)`` once ``V_j >= q``; a break above every volume the part can reach is dropped."""
    from synth.platform.data import FAMILIES as FAMS
    pf = work.pf
    J = work.n_parts
    vol = np.array([float(pf.apps[i].volume) for i in work.app_index])
    fam = work.part_family
    code = np.arange(J) - np.array([work.part_offset[FAMS[f]] for f in fam])
    K = len(curves.quantity)
    price = np.zeros((J, K))
    inc = np.zeros(J)
    for fi, f in enumerate(FAMS):
        sel = np.flatnonzero(fam == fi)
        if f in curves.prices and len(sel):
            price[sel] = curves.prices[f][code[sel]]
            if curves.included is not None and f in curves.included:
                inc[sel] = curves.included[f][code[sel]]
    plen = np.array([len(p) for p in work.patterns], np.int64)
    pparts = np.concatenate(work.patterns).astype(np.int64) if len(work.patterns) else np.zeros(0, np.int64)
    pid = np.repeat(np.arange(len(plen)), plen)
    # (application, part) pairs that can occur: the cores' and the rows' patterns
    live = np.flatnonzero(work.core_alive)
    rows = [i for i, a in enumerate(work.row_alive) if a]
    app_pat = [np.stack([work.core_app[live], work.core_pattern[live]], 1)]
    app_pat += [np.stack([np.full(len(work.row_pats[i]), work.row_app[i]), work.row_pats[i]], 1) for i in rows]
    ap = np.unique(np.concatenate(app_pat).astype(np.int64), axis=0)
    n = plen[ap[:, 1]]
    start = np.repeat(np.r_[0, np.cumsum(plen)][ap[:, 1]], n)
    j_of = pparts[start + np.arange(int(n.sum())) - np.repeat(np.cumsum(n) - n, n)]
    pair = np.unique(np.repeat(ap[:, 0], n) * J + j_of)
    pa, pj = pair // J, pair % J
    v = vol[pa]
    vmin = np.full(J, np.inf)
    np.minimum.at(vmin, pj[v > 0], v[v > 0])
    vmax = np.bincount(pj, weights=v, minlength=J)
    k_min = np.maximum(np.searchsorted(curves.quantity, np.where(np.isfinite(vmin), vmin, 0.0), side="right") - 1, 0)
    base = price[np.arange(J), k_min]
    delta = base - inc                                     # per piece, on every core and option holding the part
    d_pat = np.bincount(pid, weights=delta[pparts], minlength=len(plen))
    work.core_cost = work.core_cost + d_pat[work.core_pattern] * vol[work.core_app]
    for i in rows:
        work.row_cost[i] = work.row_cost[i] + d_pat[work.row_pats[i]] * vol[work.row_app[i]]
    ptr, qty, step = [0], [], []
    for j in range(J):
        prev = base[j]
        for k in range(k_min[j] + 1, K):
            q = curves.quantity[k]
            if q > vmax[j]:
                break
            if prev - price[j, k] > 1e-12:
                qty.append(q)
                step.append(prev - price[j, k])
                prev = price[j, k]
        ptr.append(len(qty))
    work.breaks = (vol, np.array(ptr, np.int64), np.array(qty, float), np.array(step, float))
    return len(qty)


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
