"""The price book: every catalog part's unit price [EUR] at one annual volume, with what it is and its band.

:func:`build` prices the parts of a :class:`synth.parts.Parts` from the price file (:mod:`synth.cost.prices`),
the relations of bought-in parts (:mod:`synth.cost.bought`) and the material and process terms of made parts
(:mod:`synth.cost.made`). Each price is a :class:`Priced`: its euros, whether it is **quoted** (a row of the
price file names the part), **modelled** (a relation from a reference row, or material and process terms) or
**assumed** (the price is an assumed row itself), the basis in words, and its *terms*: ``(euros, ((factor,
sigma), ...))``, each term the product of lognormal factors (a reference row, a material or process row, a
relation's scatter ``fit:<item>``, an assumed factor), which :mod:`synth.cost.decision` samples.

The arrays of the book (``bearing``, ``damper_pad``, ``endcap_spacer``, ``bushing_*``, ``cone_spring``,
``spring_*``, ``bolt``, ``washer``, ``tightening``) are what the design space's cost columns are made of (:mod:`synth.cost.columns`).

>>> from synth.parts import arrays
>>> b = arrays().prices
>>> i = arrays().bearing.code("6006")
>>> float(b.bearing[i]), b.bearing_info[i].status
(1.1, 'assumed')
>>> j = arrays().bearing.code("6007")
>>> b.bearing_info[j].status, round(float(b.bearing[j]), 3)
('modelled', 1.267)
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from synth import catalog
from synth.errors import InputError, Problem
from synth.cost import bought, made
from synth.cost.prices import rows_of

__all__ = ["Priced", "PriceBook", "build", "book_for", "volume_of", "PLASTIC"]

#: the compound of the moulded friction elements (damper pads, endcap spacers): the standard material of
#: ``plastic_wear.csv`` that :mod:`synth.parts` reads
PLASTIC = "PPA_CF10_AR10_PTFE"
WHERE = "catalogs/prices.csv"
#: the process terms of the made parts (``process:<name>`` rows)
PROCESSES = ("main_spring", "main_spring_coiling", "cone_spring", "damper_pad", "endcap_spacer", "pivot_bushing")


@dataclass(frozen=True)
class Priced:
    """One price: ``eur``, ``status`` (quoted, modelled, assumed), ``basis`` (words), ``terms`` (see the module
    docstring)."""

    eur: float
    status: str
    basis: str
    terms: tuple = ()

    def scaled(self, k: float, basis: str | None = None) -> "Priced":
        """This price times ``k`` (every term), with ``basis`` if given."""
        return Priced(self.eur * k, self.status, basis or self.basis, tuple((e * k, f) for e, f in self.terms))


def add_priced(*ps: Priced, status: str, basis: str) -> Priced:
    """The sum of the prices ``ps``: their euros and terms, under ``status`` and ``basis``."""
    return Priced(sum(p.eur for p in ps), status, basis, tuple(t for p in ps for t in p.terms))


@dataclass
class PriceBook:
    """Unit prices of one catalog setting at one annual ``volume`` (see the module docstring)."""

    volume: float
    key: tuple
    bearing: np.ndarray
    bearing_info: tuple
    damper_pad: np.ndarray
    damper_pad_info: tuple
    endcap_spacer: np.ndarray
    endcap_spacer_info: tuple
    bushing_process: Priced
    bushing_per_mm: np.ndarray          # (n_suppliers,) material EUR per mm of length
    bushing_material: tuple             # (n_suppliers,) Priced per kg of the supplier's bushing
    bushing_mass_per_mm: np.ndarray     # (n_suppliers,) kg per mm of length
    bushing_quotes: dict                # (supplier code, length) -> Priced
    cone_spring: Priced
    spring_material: np.ndarray         # (n_materials,) EUR per kg
    spring_material_info: tuple
    wire_factor: np.ndarray             # (n_wires,) section factor on the material price
    coiling: Priced                     # EUR per metre of wire
    spring_piece: Priced                # EUR per spring
    bolt: np.ndarray                    # (n_heads, n_classes)
    bolt_info: dict                     # (head, class) -> Priced
    washer: np.ndarray                  # (n_washers,)
    washer_info: tuple
    tightening: np.ndarray              # (n_methods,) assembly premium per joint over the reference method
    tightening_info: tuple
    notes: tuple = field(default_factory=tuple)

    def bushing_priced(self, supplier: int, length_mm: float) -> Priced:
        """The bushing of ``supplier`` (code) and ``length_mm``: its quote, or material and process terms."""
        for (s, length), p in self.bushing_quotes.items():
            if s == supplier and abs(length - length_mm) < 1e-9:
                return p
        mat = self.bushing_material[supplier].scaled(float(self.bushing_mass_per_mm[supplier]) * length_mm)
        return add_priced(mat, self.bushing_process, status="modelled",
                    basis=f"wall mass {1000 * self.bushing_mass_per_mm[supplier] * length_mm:.1f} g x "
                          f"{self.bushing_material[supplier].eur:.3g} EUR/kg + {self.bushing_process.eur:.3g} EUR "
                          "per part")


def volume_of(d) -> float:
    """The annual volume of design input ``d`` (``annual_volume``), else ``cost_annual_volume_default``."""
    v = getattr(d, "annual_volume", None) if d is not None else None
    return float(v) if v is not None else catalog.constant("cost_annual_volume_default")


def price_rows() -> dict:
    """The price book's rows by part key (the current catalogs, parsed once)."""
    return catalog.parsed("prices", rows_of)


def break_curve() -> tuple:
    """The quantity breaks as sorted (quantity, price factor, scatter) rows of ``price_breaks.csv``."""
    def build_curve(df):
        rows = sorted((float(r["quantity"]), float(r["factor"]), float(r["scatter"])) for _, r in df.iterrows())
        return tuple(rows)
    return catalog.parsed("price_breaks", build_curve)


def _key(rows: dict, curve: tuple, volume: float) -> tuple:
    """What the prices at ``volume`` depend on: each row's break and the volume's break of the curve."""
    bracket = max((q for q, _, _ in curve if q <= volume), default=0.0)
    return (bracket,) + tuple((item, r.at(volume)[1]) for item, r in sorted(rows.items()))


@dataclass
class _Ctx:
    rows: dict
    volume: float
    curve: tuple
    notes: list

    def need(self, item: str, why: str):
        r = self.rows.get(item)
        if r is None:
            raise InputError(Problem(WHERE, item, f"a row for {item} ({why}; a user prices.csv may add it)"))
        return r

    def price(self, item: str, why: str, *, unit: str | None = None) -> Priced:
        """The row ``item`` at the volume, in EUR (its fx row's factor among its terms)."""
        r = self.need(item, why)
        if unit is not None and r.per != unit:
            raise InputError(Problem(f"{WHERE}, item {item}, column per", r.per, unit))
        p, q, below = r.at(self.volume)
        factors = ((item, r.sigma),)
        if r.currency != "EUR":
            fx = self.need(f"fx:{r.currency}", f"the EUR rate of {item}'s currency {r.currency}")
            rate = fx.at(self.volume)[0]
            p, factors = p * rate, factors + ((fx.item, fx.sigma),)
        if below and r.status == "quoted":
            self.notes.append(f"{item}: quoted from {q:,.0f} pieces, above the annual volume {self.volume:,.0f}: its "
                              "smallest break is taken")
        status = "quoted" if r.status == "quoted" else "assumed"
        return Priced(float(p), status, f"{r.words()} at {q:,.0f}", ((float(p), factors),))

    def quantity(self, q_ref: float) -> tuple:
        return bought.quantity_factor(self.volume, q_ref, self.curve)


def _relational(ctx: _Ctx, family: str, table, size: np.ndarray, factor: np.ndarray, exponent: float,
                scatter: float, keys: list, words: str) -> tuple:
    """Prices of a relational family over its catalog rows ``keys`` (size measure ``size``, extra price factors
    ``factor``, their assumed scatter in ``factor[1]``): quotes where the price file names the part, else the
    relation from the family's one reference row."""
    refs = [r for r in ctx.rows.values() if r.family == family and r.reference]
    if len(refs) != 1:
        raise InputError(Problem(f"{WHERE}, column reference", ", ".join(r.item for r in refs) or None,
                                 f"exactly one {family} row with reference true (the part its relation starts "
                                 "from)"))
    ref = refs[0]
    i_ref = table(ref.name)
    for r in ctx.rows.values():  # a quote of a part no catalog has would price nothing: name it
        if r.family == family and r.name not in keys and not r.reference:
            shown = ", ".join(keys[:12]) + (", ..." if len(keys) > 12 else "")
            raise InputError(Problem(f"{WHERE}, item {r.item}", r.name, f"a {family} of the catalogs, as they name "
                                     f"it: {shown}"))
    p_ref = ctx.price(ref.item, f"the {family} reference")
    qf, q_sigma = ctx.quantity(ref.at(ctx.volume)[1])
    f_val, f_sig = factor
    out, info = np.empty(len(keys)), []
    for i, k in enumerate(keys):
        item = f"{family}:{k}"
        if item in ctx.rows and item != ref.item:
            p = ctx.price(item, "a quote")
        else:
            ratio = float(bought.relation_price(1.0, size[i], size[i_ref], exponent)) * f_val[i] / f_val[i_ref]
            extra = (((f"fit:{item}", scatter),) if i != i_ref else ()) \
                + (((f"factor:{family}:{k}", f_sig[i]),) if f_val[i] != f_val[i_ref] else ()) \
                + ((("quantity", q_sigma),) if qf != 1.0 else ())
            terms = tuple((e * ratio * qf, f + extra) for e, f in p_ref.terms)
            if i == i_ref:
                p = Priced(p_ref.eur * qf, p_ref.status, p_ref.basis + ("" if qf == 1.0 else
                           f", x {qf:.3g} to {ctx.volume:,.0f} a year (price_breaks.csv)"), terms)
            else:
                p = Priced(p_ref.eur * ratio * qf, "modelled",
                           f"{words} {ratio:.3g} x reference {ref.item} ({p_ref.eur:.3g} EUR, {ref.status})"
                           + ("" if qf == 1.0 else f" x {qf:.3g} to {ctx.volume:,.0f} a year"), terms)
        out[i] = p.eur
        info.append(p)
    return out, tuple(info)


def _bearings(ctx: _Ctx, p) -> tuple:
    t = p.bearing
    keys = [str(k) for k in t.key]
    mass = bought.bearing_envelope_mass_kg(t.d_mm, t.D_mm, t.B_mm)
    c = catalog.constant
    seal = np.array([c(f"cost_bearing_seal_factor_{bought.seal_variant(k)[1] or '2RS1'}") for k in keys])

    def code(name):
        base = name if name in keys else bought.seal_variant(name)[0]
        if base not in keys:
            raise InputError(Problem(f"{WHERE}, item ball_bearing:{name}", name,
                                     "a bearing of ball_bearings.csv: " + ", ".join(keys)))
        return keys.index(base)
    return _relational(ctx, "ball_bearing", code, mass, (seal, np.full(len(keys), c("cost_bearing_seal_factor_"
                                                                                       "scatter"))),
                       c("cost_bearing_mass_exponent"), c("cost_bearing_fit_scatter"), keys,
                       f"relation (mass/mass_ref)^{c('cost_bearing_mass_exponent'):.3g} x seal:")


def _bolts(ctx: _Ctx, p) -> tuple:
    c = catalog.constant
    bh, bo, cl = p.bolt_head, p.bolt, p.bolt_class
    b = bh.bolt_code
    d = bo.d_mm[b]
    coarse = {dd: max(bo.pitch_mm[bo.d_mm == dd]) for dd in set(bo.d_mm.tolist())}
    fine = np.array([bo.pitch_mm[i] < coarse[bo.d_mm[i]] for i in b])
    mass = bought.bolt_mass_kg(d, c("cost_bolt_nominal_length_mm"), bh.head_outer_mm, bh.head_height_mm,
                               bh.head_type == "hex")
    nh, nc = len(bh), len(cl)
    hh, cc = (x.ravel() for x in np.meshgrid(np.arange(nh), np.arange(nc), indexing="ij"))
    keys = [f"{bh.key[h]} {cl.key[k]}" for h, k in zip(hh, cc)]
    factor = np.where(fine[hh], c("cost_bolt_fine_pitch_factor"), 1.0) * cl.unit_cost_factor[cc]

    def code(name):
        if name not in keys:
            raise InputError(Problem(f"{WHERE}, item bolt:{name}", name, "a bolt '<format> <head> <class>' of "
                                     "bolt_heads.csv and bolt_property_classes.csv, e.g. M8x1.25 hex 8.8"))
        return keys.index(name)
    prices, info = _relational(ctx, "bolt", code, mass[hh], (factor, np.full(len(keys), c("cost_assumed_factor_"
                                                                                           "scatter"))),
                               c("cost_fastener_mass_exponent"), c("cost_fastener_fit_scatter"), keys,
                               f"relation (mass/mass_ref)^{c('cost_fastener_mass_exponent'):.3g} x pitch x class:")
    return prices.reshape(nh, nc), {(int(h), int(k)): info[i] for i, (h, k) in enumerate(zip(hh, cc))}


def _washers(ctx: _Ctx, p) -> tuple:
    """Washers (``washers.csv``) by the fastener relation from the family's reference row, their size measure
    the steel annulus ``rho pi/4 (d2^2 - d1^2) h``."""
    c = catalog.constant
    ws = p.washer
    keys = [str(k) for k in ws.key]
    mass = made.annulus_mass_kg(ws.d2_mm, ws.d1_mm, ws.h_mm, c("cost_steel_density_kg_m3"))

    def code(name):
        if name not in keys:
            raise InputError(Problem(f"{WHERE}, item washer:{name}", name, "a washer of washers.csv: "
                                     + ", ".join(keys)))
        return keys.index(name)
    return _relational(ctx, "washer", code, np.asarray(mass, float), (np.ones(len(keys)), np.zeros(len(keys))),
                       c("cost_fastener_mass_exponent"), c("cost_fastener_fit_scatter"), keys,
                       f"relation (mass/mass_ref)^{c('cost_fastener_mass_exponent'):.3g}:")


def _tightening(ctx: _Ctx, p) -> tuple:
    """The assembly premium per joint of each tightening method over the torque-controlled reference
    (:data:`synth.model.vdi2230.DEFAULT_TIGHTENING_METHOD`, 0): a ``tightening:<method>`` row, required for every
    method the design space offers (``design_option``); a method it does not offer and no row names is 0."""
    from synth.model.vdi2230 import DEFAULT_TIGHTENING_METHOD
    tf = p.tightening
    out, info = np.zeros(len(tf)), []
    for i, k in enumerate(map(str, tf.key)):
        item = f"tightening:{k}"
        if k != DEFAULT_TIGHTENING_METHOD and (item in ctx.rows or tf.design_option[i]):
            pr = ctx.price(item, f"the assembly premium per joint of tightening method {k} over "
                           f"{DEFAULT_TIGHTENING_METHOD}", unit="part")
        else:
            pr = Priced(0.0, "assumed", f"the reference method ({DEFAULT_TIGHTENING_METHOD}): its assembly is in "
                        "the process rows" if k == DEFAULT_TIGHTENING_METHOD else "not offered to the design space")
        out[i] = pr.eur
        info.append(pr)
    return out, tuple(info)


def _moulded(ctx: _Ctx, family: str, table) -> tuple:
    c = catalog.constant
    mat = ctx.price(f"material:{PLASTIC}", f"the compound of the {family}s", unit="kg")
    proc = ctx.price(f"process:{family}", f"moulding one {family}", unit="part")
    out, info = np.empty(len(table)), []
    for i, k in enumerate(table.key):
        item = f"{family}:{k}"
        if item in ctx.rows:
            p = ctx.price(item, "a quote", unit="part")
        else:
            m = float(made.moulded_mass_kg(table.contact_area_mm2[i], table.axial_height_mm[i],
                                           c("cost_plastic_density_kg_m3")))
            p = add_priced(mat.scaled(m), proc, status="modelled",
                     basis=f"{1000 * m:.2f} g x {mat.eur:.3g} EUR/kg ({PLASTIC}) + {proc.eur:.3g} EUR moulding")
        out[i] = p.eur
        info.append(p)
    return out, tuple(info)


def _check_items(ctx: _Ctx, p) -> None:
    """Every part a row names exists in the catalogs (a misspelt quote would otherwise price nothing)."""
    problems = []
    known = {"damper_pad": set(map(str, p.damper_pad.key)), "endcap_spacer": set(map(str, p.endcap_spacer.key)),
             "material": set(map(str, p.spring_material.key)) | set(catalog.keys("plastic_wear"))
             | {"cone_spring_steel"} | {f"pivot_bushing_{k}" for k in p.bushing.key},
             "process": set(PROCESSES), "washer": set(map(str, p.washer.key)),
             "tightening": set(map(str, p.tightening.key))}
    for r in ctx.rows.values():
        if r.family in known and r.name not in known[r.family]:
            problems.append(Problem(f"{WHERE}, item {r.item}", r.name, f"a {r.family} of the catalogs: "
                                    + ", ".join(sorted(known[r.family]))))
        if r.family == "pivot_bushing":
            sup, _, length = r.name.rpartition(" ")
            ok = sup in list(map(str, p.bushing.key))
            try:
                ok = ok and float(length) in p.bushing_lengths[list(map(str, p.bushing.key)).index(sup)]
            except ValueError:
                ok = False
            if not ok:
                problems.append(Problem(f"{WHERE}, item {r.item}", r.name, "'<supplier> <length>' of "
                                        "pivot_bushings.csv (a supplier and one of its lengths_mm), e.g. A 18"))
    if problems:
        raise InputError(problems)


def build(p, volume: float | None = None) -> PriceBook:
    """The :class:`PriceBook` of parts ``p`` (a :class:`synth.parts.Parts`) at annual ``volume`` (default:
    ``cost_annual_volume_default``)."""
    c = catalog.constant
    volume = float(volume if volume is not None else c("cost_annual_volume_default"))
    rows, curve = price_rows(), break_curve()
    ctx = _Ctx(rows, volume, curve, [])
    _check_items(ctx, p)
    bearing, bearing_info = _bearings(ctx, p)
    bolt, bolt_info = _bolts(ctx, p)
    washer, washer_info = _washers(ctx, p)
    tightening, tightening_info = _tightening(ctx, p)
    pad, pad_info = _moulded(ctx, "damper_pad", p.damper_pad)
    spacer, spacer_info = _moulded(ctx, "endcap_spacer", p.endcap_spacer)
    # pivot bushing: wrapped wall at the nominal diameter, per kg of the supplier's bushing, plus the process
    mass_mm = np.array([float(made.wrapped_bushing_mass_kg(c("cost_bushing_nominal_diameter_mm"), t, 1.0,
                                                            c("cost_steel_density_kg_m3")))
                        for t in p.bushing.radial_thickness_mm])
    bush_mat = tuple(ctx.price(f"material:pivot_bushing_{k}", f"the bushings of supplier {k}", unit="kg")
                     for k in p.bushing.key)
    quotes = {}
    for r in rows.values():
        if r.family == "pivot_bushing":
            sup, _, length = r.name.rpartition(" ")
            quotes[(list(map(str, p.bushing.key)).index(sup), float(length))] = ctx.price(r.item, "a quote")
    # cone spring: the nominal blank (Table 7's middle ratios) and the process
    de = c("cost_cone_spring_nominal_outer_mm")
    m_cone = float(made.annulus_mass_kg(de, de / c("cost_cone_spring_nominal_ratio_de_di"),
                                        de / c("cost_cone_spring_nominal_ratio_de_t"), c("cost_steel_density_kg_m3")))
    steel = ctx.price("material:cone_spring_steel", "the cone springs' strip", unit="kg")
    proc = ctx.price("process:cone_spring", "making one cone spring", unit="part")
    cone = add_priced(steel.scaled(m_cone), proc, status="modelled",
                basis=f"nominal blank {1000 * m_cone:.1f} g x {steel.eur:.3g} EUR/kg + {proc.eur:.3g} EUR per part")
    # main spring: material per kg, section factor, coiling per metre, per spring
    mat_info = tuple(ctx.price(f"material:{k}", f"the spring wire {k}", unit="kg") for k in p.spring_material.key)
    wire_factor = np.where(p.spring_wire.round_wire, 1.0, c("cost_wire_rectangular_factor"))
    return PriceBook(
        volume=volume, key=_key(rows, curve, volume), bearing=bearing, bearing_info=bearing_info,
        damper_pad=pad, damper_pad_info=pad_info, endcap_spacer=spacer, endcap_spacer_info=spacer_info,
        bushing_process=ctx.price("process:pivot_bushing", "making one bushing", unit="part"),
        bushing_per_mm=mass_mm * np.array([m.eur for m in bush_mat]), bushing_material=bush_mat,
        bushing_mass_per_mm=mass_mm, bushing_quotes=quotes, cone_spring=cone,
        spring_material=np.array([m.eur for m in mat_info]), spring_material_info=mat_info, wire_factor=wire_factor,
        coiling=ctx.price("process:main_spring_coiling", "coiling a metre of spring wire", unit="m"),
        spring_piece=ctx.price("process:main_spring", "the operations per spring", unit="part"),
        bolt=bolt, bolt_info=bolt_info, washer=washer, washer_info=washer_info, tightening=tightening,
        tightening_info=tightening_info, notes=tuple(dict.fromkeys(ctx.notes)))


_BOOKS: dict = {}


def book_for(p, volume: float | None) -> PriceBook:
    """The book of parts ``p`` at ``volume`` (None: the default volume): ``p.prices`` when the volume selects
    the same breaks, else built once per parts and breaks."""
    if volume is None or p.prices is None:
        return p.prices if p.prices is not None else build(p)
    key = _key(price_rows(), break_curve(), float(volume))
    if key == p.prices.key:
        return p.prices
    hit = _BOOKS.get((id(p), key))
    if hit is None or hit[0] is not p:
        if len(_BOOKS) > 32:
            _BOOKS.clear()
        hit = (p, build(p, volume))
        _BOOKS[(id(p), key)] = hit
    return hit[1]

