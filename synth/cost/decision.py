"""How much the cheapest design depends on the prices: its probability of being cheapest, and the price ranges
that keep it so.

Every price carries a band (:mod:`synth.cost.book`): a quote its own ``band_pct``, a modelled price the
scatter of its relation's fit and its reference's band, an assumption a wide stated one. :func:`decide` samples
them (lognormal factors, each shared by every price it enters: one reference row moves every bearing the
relation prices from it, one material row every spring of that wire; seeded, so the same seed gives the same
numbers) over a *pool* of designs, the cheapest ones (``cost_sensitivity_pool``), and reports

* per design, its cost band (the 5 % and 95 % quantiles) and the share of the samples in which it is the
  cheapest of the pool;
* per part of the pool, the range of its price (the others at their nominal values) over which the optimum
  stays the cheapest of the pool: up to the price at which the cheapest design without that part overtakes it
  (a part of the optimum), down to the price at which the cheapest design with it does (a part of another
  design). Over the pool, the range is exact while the change stays below the pool's cost spread.

>>> from synth.scenes.demo import default_input
>>> from synth.optimise import solve
>>> d = default_input()
>>> r = solve(d, "cost")
>>> pool, rivals = price_pool(d, r, 4)
>>> out = decide(d, pool, rivals=rivals, samples=2000, seed=1)
>>> round(sum(x["p_cheapest"] for x in out["designs"]), 6), out["designs"][0]["cost_eur"] == r.objectives["cost"]
(1.0, True)
"""

from __future__ import annotations

import numpy as np

from synth import catalog
from synth.cost.breakdown import attributes, lines, summary
from synth.cost.book import volume_of

__all__ = ["decide", "sample_costs", "cost_report", "band_of", "price_pool", "PRICE_KEYS"]


def sample_costs(designs_lines: list, samples: int, seed: int) -> np.ndarray:
    """``(samples, n_designs)`` costs of designs given by their price lines, their factors sampled once per
    sample (a factor shared by several lines moves them together); nominal prices are the medians."""
    ids = sorted({f for ls in designs_lines for x in ls for _, fs in x.priced.terms for f, _ in fs})
    col = {f: i for i, f in enumerate(ids)}
    z = np.random.default_rng(seed).standard_normal((samples, max(len(ids), 1)))
    out = np.zeros((samples, len(designs_lines)))
    for j, ls in enumerate(designs_lines):
        for x in ls:
            for eur, fs in x.priced.terms:
                expo = np.zeros(samples)
                for f, s in fs:
                    expo += s * z[:, col[f]]
                out[:, j] += eur * np.exp(expo)
    return out


def _settings():
    c = catalog.constant
    return int(c("cost_sensitivity_samples")), int(c("cost_sensitivity_seed"))


def band_of(d, parts: dict, *, samples: int | None = None, seed: int | None = None) -> list:
    """``[5 %, 95 %]`` quantiles [EUR] of the cost of design ``parts`` under the price bands."""
    n, s = _settings()
    c = sample_costs([lines(d, parts)], samples or n, s if seed is None else seed)[:, 0]
    return [round(float(np.quantile(c, 0.05)), 6), round(float(np.quantile(c, 0.95)), 6)]


def decide(d, designs: list, *, rivals: list = (), samples: int | None = None, seed: int | None = None) -> dict:
    """The price sensitivity of the cheapest of ``designs`` (parts dicts, the optimum first, the others the next
    cheapest): see the module docstring. Returns ``{"samples", "seed", "pool", "designs": [{"rank", "cost_eur",
    "band_eur", "p_cheapest"}], "ranges": [{"part", "label", "price_eur", "in_optimum", "low_eur", "high_eur"}]}``
    (``None``: no bound over the pool). ``rivals``: further designs (parts) that bound the price ranges only (the
    cheapest without a part the whole pool shares)."""
    n, s = _settings()
    samples, seed = samples or n, s if seed is None else seed
    ls = [lines(d, parts) for parts in designs]
    cost = np.array([sum(x.eur for x in one) for one in ls])
    sim = sample_costs(ls, samples, seed)
    wins = np.bincount(np.argmin(sim, axis=1), minlength=len(ls)) / samples
    out = {"samples": samples, "seed": seed, "pool": len(ls), "designs": [
        {"rank": j + 1, "cost_eur": round(float(cost[j]), 6),
         "band_eur": [round(float(np.quantile(sim[:, j], q)), 6) for q in (0.05, 0.95)],
         "p_cheapest": round(float(wins[j]), 4)} for j in range(len(ls))]}
    every = ls + [lines(d, parts) for parts in rivals]
    c_all = np.array([sum(x.eur for x in one) for one in every])
    has = [{x.key: x for x in one} for one in every]
    ranges, seen = [], set()
    for j, one in enumerate(ls):
        for x in one:
            if x.key in seen:
                continue
            seen.add(x.key)
            gap_without = [c_all[i] - c_all[0] for i in range(1, len(every)) if x.key not in has[i]]
            gap_with = [c_all[i] - c_all[0] for i in range(1, len(every)) if x.key in has[i]]
            mine = x.key in has[0]
            if mine:
                low, high = 0.0, (x.eur + min(gap_without)) if gap_without else None
            else:
                low, high = (max(x.eur - min(gap_with), 0.0) if gap_with else None), None
            ranges.append({"part": x.key, "label": x.label, "price_eur": round(x.eur, 6), "in_optimum": mine,
                           "low_eur": None if low is None else round(float(low), 6),
                           "high_eur": None if high is None else round(float(high), 6)})
    out["ranges"] = ranges
    return out


#: the columns of each table of the design space that set its price (the other columns of a row change no price)
PRICE_KEYS = {"core": ("bearing_code", "pad_code"), "bushing": ("supplier_code", "pivot_bushing_length_mm"),
              "axial": ("spacer_code",), "spring": ("material_code", "wire_code"), "bolt": ("head_code", "class_code", "washer_code",
                                                                                       "tightening_code")}


def _key_codes(table: dict, names: tuple) -> np.ndarray:
    """One integer per row of ``table``, equal for rows of equal price key (``names``)."""
    cols = [np.asarray(table[n]) for n in names]
    return np.unique(np.stack([np.round(c.astype(float), 6) for c in cols], axis=1), axis=0, return_inverse=True)[1] \
        .reshape(-1)


def _space_of(d, r, settings):
    """The evaluated design space of ``d`` that ``r``'s synthesis searched (the parts it honoured kept) and the
    price-key codes of its tables."""
    from synth.optimise.product import evaluate
    from synth.design.evaluate import Settings
    ctl = r.control or {}
    keep = tuple(x for x in list(ctl.get("fixed", [])) + list(ctl.get("kept_when_possible", []))
                 if x not in ctl.get("freed", []))
    settings = settings or Settings(**{f: v for f, v in (r.settings or {}).items() if f in Settings.__dataclass_fields__})
    ev = evaluate(d, settings, pin_inputs=keep)
    return ev, {t: _key_codes(ev.space.tables[t], PRICE_KEYS[t]) for t in PRICE_KEYS}


def _search(ev, codes: dict, n: int, exclude: tuple | None = None) -> list:
    """The ``n`` cheapest feasible price sets of evaluation ``ev``: ``[(cost, key, (core position, option, ...))]``
    by cost, one design each (the largest-margin option of each priced part); ``exclude``: ``(table, mask)``, the
    rows of a table (a boolean mask over it) no design may use."""
    from synth.optimise.alternatives import best_combinations as _best
    from synth.design.space import SUBSYSTEMS
    core_code = codes["core"][ev.cores]
    ok_core = ev.core_feasible()[ev.rows]
    if exclude and exclude[0] == "core":
        ok_core = ok_core & ~exclude[1][ev.cores[ev.rows]]
    found = {}
    for i, pos in enumerate(ev.rows):
        if not ok_core[i]:
            continue
        lists = [[((float(ev.score_core["cost"][pos]), (int(core_code[pos]),)), int(pos))]]
        for s in SUBSYSTEMS:
            f = np.flatnonzero(ev.subs[s].feasible[i])
            if exclude and exclude[0] == s:
                f = f[~exclude[1][f]]
            if not len(f):
                break
            k = codes[s][f]
            order = np.lexsort((-ev.subs[s].margin[i, f], k))  # per price key, its largest-margin option first
            _, first = np.unique(k[order], return_index=True)
            rep = f[order[first]]
            cost = np.asarray(ev.score[s]["cost"], float)[rep]
            top = np.argsort(cost, kind="stable")[:n]
            lists.append([((float(cost[j]), (int(codes[s][rep[j]]),)), int(rep[j])) for j in top])
        else:
            for (cost, key), idx in _best(lists, n, lambda a, b: (a[0] + b[0], a[1] + b[1]), False):
                if key not in found or cost < found[key][0]:
                    found[key] = (cost, idx)
    return sorted(((c, k, idx) for k, (c, idx) in found.items()), key=lambda x: x[0])[:n]


def _parts(ev, idx) -> dict:
    from synth.design.space import SUBSYSTEMS
    return ev.parts(idx[0], dict(zip(SUBSYSTEMS, idx[1:])))


def _rows_with(tables: dict, attrs: dict, family: str):
    """``(table, mask)``: the rows of the design space that carry the priced part ``family`` of the one-row
    attributes ``attrs`` (a design's), None for a part every design has (the main spring's per-spring term)."""
    def same(t, *cols):
        m = np.ones(len(tables[t][cols[0]]), dtype=bool)
        for c in cols:
            m &= np.isclose(np.asarray(tables[t][c], float), float(attrs[t][c][0]))
        return t, m
    return {"ball_bearing": lambda: same("core", "bearing_code"), "damper_pad": lambda: same("core", "pad_code"),
            "pivot_bushing": lambda: same("bushing", "supplier_code", "pivot_bushing_length_mm"),
            "endcap_spacer": lambda: same("axial", "spacer_code"),
            "cone_spring": lambda: ("axial", np.asarray(tables["axial"]["spacer_code"]) >= 0),
            "main_spring": lambda: same("spring", "material_code", "wire_code"),
            "bolt": lambda: same("bolt", "head_code", "class_code"), "washer": lambda: same("bolt", "washer_code"),
            "tightening": lambda: same("bolt", "tightening_code")}[family]()


def price_pool(d, r, n: int, *, settings=None) -> tuple:
    """``(pool, rivals)``: the parts of the ``n`` cheapest feasible designs of input ``d`` that differ in price (one
    design per set of priced parts: designs that differ only in what changes no price, a mean diameter, a
    cone-spring variant, a pivot class, are one), the design of result ``r`` first, searched in the space ``r``'s
    synthesis kept (the parts it honoured); and, for every priced part of ``r`` that the whole pool shares, the
    cheapest feasible design without it (none where no design goes without it)."""
    ev, codes = _space_of(d, r, settings)
    mine = lines(d, r.parts)
    own = {x.key for x in mine}
    pool = [dict(r.parts)] + [p for p in (_parts(ev, idx) for _, _, idx in _search(ev, codes, n))
                              if {x.key for x in lines(d, p)} != own][: n - 1]
    shared = set.intersection(*({x.key for x in lines(d, p)} for p in pool))
    attrs = ev.space.design_attributes(r.parts)
    rivals = []
    for x in mine:
        if x.key in shared:
            best = _search(ev, codes, 1, exclude=_rows_with(ev.space.tables, attrs, x.key.split(":")[0]))
            if best:
                rivals.append(_parts(ev, best[0][2]))
    return pool, rivals


def cost_report(d, r, *, sensitivity: bool = False, settings=None) -> dict:
    """The ``cost`` of result ``r`` for input ``d``: the annual volume, the design's price lines and what they are,
    and with ``sensitivity`` (a feasible optimum of the cost objective) the decision's dependence on the prices
    over the cheapest designs that differ in price (:func:`price_pool`, :func:`decide`)."""
    if not r.parts:
        return {}
    out = {"volume": volume_of(d), **summary(lines(d, r.parts))}
    notes = list(attributes(d, r.parts)[0].notes)
    if notes:
        out["notes"] = notes
    if sensitivity and r.status in ("optimal", "feasible") and not r.failed():
        pool, rivals = price_pool(d, r, int(catalog.constant("cost_sensitivity_pool")), settings=settings)
        if len(pool) > 1:
            out["decision"] = dec = decide(d, pool, rivals=rivals)
            sets = [frozenset(x.key for x in lines(d, p)) for p in pool]
            dec["alternatives"] = []  # the --top K designs: each one's set of priced parts in the pool, if it is
            for a in r.alternatives[1:]:
                keys = frozenset(x.key for x in lines(d, a["parts"]))
                j = sets.index(keys) if keys in sets else None
                dec["alternatives"].append({"rank": a["rank"], "pool_rank": None if j is None else j + 1,
                                            "p_cheapest": None if j is None else dec["designs"][j]["p_cheapest"]})
    return out
