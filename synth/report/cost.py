"""The cost of a design in words: its price lines (quoted, modelled, assumed) and how much the choice depends on
the prices (:attr:`synth.design.result.Result.cost`, :func:`synth.cost.decision.cost_report`).

>>> cost = {"volume": 1000.0, "cost_eur": 1.5, "counts": {"quoted": 1, "modelled": 1, "assumed": 0},
...         "lines": [{"part": "ball_bearing:6006", "label": "ball bearing 6006", "price_eur": 1.0,
...                    "status": "quoted", "basis": "quoted by ACME 2026-01-05 at 1,000", "band_pct": 5.0},
...                   {"part": "cone_spring", "label": "cone spring", "price_eur": 0.5, "status": "modelled",
...                    "basis": "blank + process", "band_pct": 40.0}]}
>>> text_lines(cost)[3]
'  ball bearing 6006                               1.0000  quoted    +/- 5 %  quoted by ACME 2026-01-05 at 1,000'
"""

from __future__ import annotations

__all__ = ["text_lines", "tables"]


def _eur(v) -> str:
    return "-" if v is None else f"{v:.4f}"


def text_lines(cost: dict) -> list:
    """The terminal lines of a result's ``cost`` (none when it has none)."""
    if not cost:
        return []
    c = cost["counts"]
    out = ["", f"Cost: {cost['cost_eur']:.4f} EUR a tensioner at {cost['volume']:,.0f} a year (parts quoted "
               f"{c['quoted']}, modelled {c['modelled']}, assumed {c['assumed']}; band: one standard deviation)",
           "-" * 78]
    for x in cost["lines"]:
        out.append(f"  {x['label']:<46} {x['price_eur']:7.4f}  {x['status']:<9} +/- {x['band_pct']:g} %  {x['basis']}")
    out += [f"  note: {n}" for n in cost.get("notes", [])]
    dec = cost.get("decision")
    if dec:
        out += ["", f"Cheapest under the price bands ({dec['samples']:,} samples, seed {dec['seed']}, among the "
                    f"{dec['pool']} cheapest designs)", "-" * 78]
        for x in dec["designs"]:
            lo, hi = x["band_eur"]
            out.append(f"  #{x['rank']:<2} {x['cost_eur']:.4f} EUR (90 % band {lo:.4f}-{hi:.4f})  "
                       f"P(cheapest) {x['p_cheapest']:.3f}")
        for a in dec.get("alternatives", []):
            where = f"the priced parts of #{a['pool_rank']} above: P(cheapest) {a['p_cheapest']:.3f}" \
                if a["pool_rank"] else "priced parts outside the pool above"
            out.append(f"  --top alternative #{a['rank']}: {where}")
        out += ["", "Price ranges over which #1 stays the cheapest (the other prices as they are)", "-" * 78]
        for r in dec["ranges"]:
            if r["in_optimum"]:
                hi = "any price" if r["high_eur"] is None else \
                    f"up to {r['high_eur']:.4f} EUR ({100 * (r['high_eur'] / r['price_eur'] - 1):+.1f} %)"
                out.append(f"  {r['label']:<46} {r['price_eur']:7.4f}  {hi}")
            elif r["low_eur"] is not None:
                out.append(f"  {r['label']:<46} {r['price_eur']:7.4f}  (not in #1) down to {r['low_eur']:.4f} EUR "
                           f"({100 * (r['low_eur'] / r['price_eur'] - 1):+.1f} %)")
    return out


def tables(cost: dict) -> dict:
    """The report's tables of a result's ``cost``: ``{title: rows}`` (none when it has none)."""
    if not cost:
        return {}
    out = {f"Cost at {cost['volume']:,.0f} a year": [
        {"part": x["label"], "price [EUR]": x["price_eur"], "what it is": x["status"], "band (1 sd) [%]": x["band_pct"],
         "basis": x["basis"]} for x in cost["lines"]]}
    dec = cost.get("decision")
    if dec:
        out["Cost: probability of being cheapest"] = [
            {"#": x["rank"], "cost [EUR]": x["cost_eur"], "5 % [EUR]": x["band_eur"][0],
             "95 % [EUR]": x["band_eur"][1], "P(cheapest)": x["p_cheapest"]} for x in dec["designs"]]
        out["Cost: price ranges keeping #1 the cheapest"] = [
            {"part": r["label"], "price [EUR]": r["price_eur"], "in #1": r["in_optimum"],
             "from [EUR]": _eur(r["low_eur"]), "to [EUR]": "any" if r["high_eur"] is None else _eur(r["high_eur"])}
            for r in dec["ranges"]]
    return out
