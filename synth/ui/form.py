"""The design input as a form: one widget per field of :data:`synth.schema.FIELDS`, in its sections.

Nothing here knows a field by name: the widget, its options, label, unit and the accepted values shown
under it come from the field's declaration (:class:`synth.schema.Field`), so a field added to the
schema appears in ``synth ui`` by itself.

A text box holds what the user typed; :func:`value_of` reads it as one YAML scalar, as the same text in
an input file would be read, so :func:`synth.schema.validate` reports exactly the message the command
line gives for that file (``pulley_diameter_mm: got 500; accepted: a number in [10, 200] mm``).

>>> f = schema.field_by_name("pulley_diameter_mm")
>>> widget(f), label(f), hint(f)
('text', 'Pulley diameter [mm]', 'a number in [10, 200] mm')
>>> value_of("62,5"), value_of(" "), value_of("[2.3, 2.3]")
('62,5', None, [2.3, 2.3])
>>> options(schema.field_by_name("belt_loading_type"))["single_eccentric"]
'single_eccentric (Autosetting)'
>>> problems_by_field(InputError(Problem("pulley_diameter_mm", 500, "a number in [10, 200] mm")))
({'pulley_diameter_mm': ['pulley_diameter_mm: got 500; accepted: a number in [10, 200] mm']}, [])
"""

from __future__ import annotations

import copy
import functools
import math
from typing import Any

import yaml

from synth import catalog, schema
from synth.errors import InputError, Problem

__all__ = ["widget", "options", "label", "hint", "text_of", "shown", "value_of", "mapping", "problems_by_field", "to_yaml",
           "sections", "MAX_TEXT"]

#: longest text a box accepts (a value, never a document: the input gate's limits stay with files)
MAX_TEXT = 200


def sections() -> list[tuple[str, list[schema.Field]]]:
    """``[(section, [fields])]`` in the schema's order (the thesis's input table)."""
    return [(s, [f for f in schema.FIELDS if f.section == s]) for s in schema.SECTIONS]


def widget(f: schema.Field) -> str:
    """``select`` for a field with choices or a catalog (a drop-down), else ``text``."""
    return "select" if f.choices or f.catalog else "text"


def options(f: schema.Field) -> dict[str, str]:
    """A drop-down's ``{value: shown text}``: the choices with the thesis's first word for each, or the catalog keys."""
    if f.choices:
        words: dict[str, str] = {}
        for word, choice in f.words:
            if word.lower().replace(" ", "_") != choice:
                words.setdefault(choice, word)
        return {c: f"{c} ({words[c]})" if c in words else c for c in f.choices}
    return {k: k for k in catalog_keys(f.catalog)} if f.catalog else {}


#: what the form shows of the catalogs, per (what, user catalog folders), read once: the designations a drop-down of
#: catalog ``name`` lists (key ``name``) and what a catalog field accepts (``hint:FIELD``). The server's launch
#: hands over those its worker read (:class:`synth.ui.launch.Launch`): the first page reads no catalog
KEYS: dict[tuple, list[str] | str] = {}


def catalog_texts() -> dict[str, list[str] | str]:
    """Every entry of :data:`KEYS` the form reads under the user catalog folders in use (what a worker hands over)."""
    fields = [f for f in schema.FIELDS if f.catalog]
    for f in fields:
        catalog_keys(f.catalog), hint(f)
    dirs = tuple(catalog.user_dirs())
    return {k: v for (k, d), v in KEYS.items() if d == dirs}


def catalog_keys(name: str) -> list[str]:
    """The designations of catalog ``name`` under the user catalog folders in use (:func:`synth.catalog.keys`)."""
    key = (name, tuple(catalog.user_dirs()))
    if key not in KEYS:
        KEYS[key] = catalog.keys(name)
    return KEYS[key]


def label(f: schema.Field) -> str:
    """The field's label and unit (``Pulley diameter [mm]``)."""
    unit = "" if f.unit in ("-", "") else f" [{f.unit}]"
    return f"{f.label or f.name}{unit}"


def hint(f: schema.Field) -> str:
    """What the field accepts (:meth:`synth.schema.Field.accepted`), and ``optional`` for an optional one."""
    if f.catalog:  # the catalog's designations: read once per catalog and user folders (see KEYS)
        key = ("hint:" + f.name, tuple(catalog.user_dirs()))
        if key not in KEYS:
            KEYS[key] = f.accepted()
        return KEYS[key] + ("" if f.required else "; optional")
    return f.accepted() + ("" if f.required else "; optional")


def text_of(value: Any) -> str:
    """A value as the text a box keeps (``62``, ``0.5``, ``[2.3, 2.3]``; None empty): every digit of a number, in a
    form YAML reads back as the same number (``1.0e-05``, not ``1e-05``, which YAML reads as text).

    >>> text_of(62.96956885569824), text_of(1e-05), value_of(text_of(1e-05)) == 1e-05, text_of([2.3, 2])
    ('62.96956885569824', '1.0e-05', True, '[2.3, 2]')
    """
    if value is None:
        return ""
    if isinstance(value, float) and not isinstance(value, bool) and math.isfinite(value):
        t = repr(float(value))
        mantissa, e, exponent = t.partition("e")
        return f"{mantissa}.0e{exponent}" if e and "." not in mantissa else t
    if isinstance(value, (list, tuple)):
        return "[" + ", ".join(text_of(v) for v in value) + "]"
    return str(value)


#: significant digits a box shows of a number that has more (the box keeps them all until it is edited)
SHOWN_DIGITS = 5


def shown(text: str) -> str:
    """What a box shows of the ``text`` it keeps: a number with more than :data:`SHOWN_DIGITS` significant digits
    rounded to them (a portfolio's ``62.96956885569824`` shows ``62.97``), anything else as it is.

    >>> shown("62.96956885569824"), shown("0.0164"), shown("7"), shown("abc"), shown("0.034669964285953515")
    ('62.97', '0.0164', '7', 'abc', '0.03467')
    """
    v = value_of(text)
    if not isinstance(v, float) or not math.isfinite(v):
        return text
    short = text_of(float(f"{v:.{SHOWN_DIGITS}g}"))
    return short if len(short) < len(text.strip()) else text


def value_of(text: Any) -> Any:
    """The value a box's text means: the text read as one YAML scalar (or flow list), as in an input file.

    Empty is None (not given); text YAML cannot read stays the text, for the validator to report.
    """
    if text is None:
        return None
    if not isinstance(text, str):
        return text
    t = text.strip()
    if not t:
        return None
    v = _scalar(t)
    return copy.deepcopy(v) if isinstance(v, list) else v


@functools.lru_cache(maxsize=4096)
def _scalar(t: str) -> Any:
    """:func:`value_of` of stripped, non-empty text, read once per text (an edit re-reads every box: 40 YAML parses
    were a quarter of an edit's time in the server)."""
    try:
        v = yaml.safe_load(t)
    except yaml.YAMLError:
        return t
    return v if isinstance(v, (int, float, str, list)) and not isinstance(v, bool) else t


def mapping(texts: dict[str, Any]) -> dict[str, Any]:
    """The input mapping of the form's boxes (``{field: value}``, the given ones only)."""
    out = {}
    for name, text in texts.items():
        if isinstance(text, str) and len(text) > MAX_TEXT:
            raise InputError(Problem(name, text[:40] + "...", f"at most {MAX_TEXT} characters"))
        v = value_of(text)
        if v is not None:
            out[name] = v
    return out


def problems_by_field(exc: InputError) -> tuple[dict[str, list[str]], list[str]]:
    """``({field: [messages]}, [messages about no one field])``: each problem's text as the command line prints it."""
    known = {f.name for f in schema.FIELDS}
    by_field: dict[str, list[str]] = {}
    other = []
    for p in exc.problems:
        if p.field in known:
            by_field.setdefault(p.field, []).append(str(p))
        else:
            other.append(str(p))
    return by_field, other


def to_yaml(values: dict[str, Any], source: str = "", rules=None) -> str:
    """The input as a YAML design-input file (fields in the schema's order, then the design ``rules:`` section when
    ``rules`` (:class:`synth.design.rules.Rules`) has any), loadable by every scene."""
    order = [f.name for f in schema.FIELDS]
    data = {k: values[k] for k in order if values.get(k) is not None}
    data.update({k: v for k, v in values.items() if k not in data and v is not None})
    if rules is not None and not rules.empty():
        data["rules"] = {k: v for k, v in rules.as_dict().items() if v and k != "source"}
    source = " ".join(str(source).split())  # one comment line, whatever the file name holds
    head = "# synth design input" + (f" (from {source})" if source else "") + ", saved by synth ui\n"
    return head + yaml.safe_dump(data, sort_keys=False, allow_unicode=True)
