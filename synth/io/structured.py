r"""YAML, TOML and JSON documents, parsed within the gate's limits, in time as well as memory.

:func:`parse` turns the text of a document into plain Python data (dicts,
lists, str, int, float, bool, None) or raises one
:class:`~synth.errors.InputError`. Nothing big is built before it is counted:

* YAML is first *streamed* (libyaml's event parser, about 1 s per million
  values) and refused as soon as it holds more than :attr:`Limits.nodes`
  values or nests deeper than :attr:`Limits.depth` (PyYAML would build the
  whole document first: an 8 MB flat list took 225 s and 3.5 GB); then its
  node graph is measured: aliases are counted as often as they would be
  expanded, so a "billion laughs" alias bomb is refused in milliseconds, and
  the message does not print the expanded value;
* TOML (a pure-Python parser, about 5 us a value) and JSON are pre-scanned:
  more value separators (commas; in TOML lines too) than :attr:`Limits.nodes`
  is refused before parsing (a JSON list of four million numbers took 2.7 s
  and 0.75 GB to build); JSON is then parsed by the C parser and counted.

YAML is read with the YAML 1.2 core schema's scalars (:class:`Yaml12Loader`):
numbers are decimal (``65``, ``6.5``, ``6.5e1``, ``.inf``), booleans are
``true``/``false`` and null is ``null``/``~``; the YAML 1.1 forms PyYAML would
read as numbers or booleans (sexagesimal ``1:05``, hexadecimal ``0x41``, octal
``0o101``, ``6_5``, ``yes``/``no``/``on``/``off``, dates) stay text, which a
number field then refuses naming the field and the text. A key given twice
in one mapping (YAML, JSON or TOML) is refused naming both lines: the
parsers would silently keep the last value.

After parsing, :func:`check_values` walks
the data once (iteratively) and reports, with the path of each offending
value as the user wrote it (``roughness.journal.Ra``):

* nesting deeper than :attr:`Limits.depth`, more than :attr:`Limits.nodes` values;
* text longer than :attr:`Limits.string_chars`;
* integers of more than :attr:`Limits.integer_digits` digits (a 400-digit
  integer would overflow a float: ``OverflowError``);
* non-finite numbers (``.inf``, ``NaN``, ``1e400``) unless allowed.

>>> parse("a: 1\nb: [2, 3.5]\n", "yaml", "x.yaml")
{'a': 1, 'b': [2, 3.5]}
>>> parse("a: 1:05\nb: 0x41\nc: 6_5\nd: yes\ne: 65\n", "yaml", "x.yaml")
{'a': '1:05', 'b': '0x41', 'c': '6_5', 'd': 'yes', 'e': 65}
>>> try:
...     parse('{"a": 1,\n "b": 2,\n "a": 3}', "json", "x.json")
... except InputError as exc:
...     print(exc.problems[0])
a (x.json): got 'given twice'; accepted: each key once in a mapping (lines 1 and 3 both give it; the parser would keep the last silently)
>>> lol = "a: &a [lol, lol, lol, lol, lol, lol, lol, lol, lol, lol]\n" + "".join(
...     f"{c}: &{c} [" + ", ".join([f"*{p}"] * 10) + "]\n" for p, c in zip("abcdefgh", "bcdefghi"))
>>> try:
...     parse(lol, "yaml", "bomb.yaml")
... except InputError as exc:
...     print(exc.problems[0])
bomb.yaml: got 'YAML aliases'; accepted: a document of at most 200000 values once its aliases are expanded (this one expands to more than 200000: an alias bomb?)
"""

from __future__ import annotations

import json
import math
import re
from pathlib import Path
from typing import Any

from synth.errors import InputError, Problem
from synth.io.files import kind_of_file, read_text, suffix_of
from synth.io.limits import LIMITS, Limits, short

__all__ = ["parse", "check_values", "read_document", "FORMAT_OF_SUFFIX"]

#: file suffix -> document format
FORMAT_OF_SUFFIX = {".yaml": "yaml", ".yml": "yaml", ".toml": "toml", ".json": "json"}


def parse(text: str, fmt: str, where: str, *, limits: Limits = LIMITS, allow_nonfinite: bool = False,
          what: str = "") -> Any:
    """The data of document ``text`` in format ``fmt`` (``yaml``, ``toml``, ``json``).

    ``where`` names the file in messages, ``what`` the option or role of the
    file (``--parts``, ``input file``): a problem with the whole document is
    reported as ``what (where)``. Raises :class:`InputError` for a
    syntax error (with the parser's line and column), a document beyond the
    limits, or a bad value (see :func:`check_values`).
    """
    doc = f"{what} ({where})" if what else where
    try:
        if fmt == "yaml":
            data = _yaml(text, doc, limits, where)
        elif fmt == "toml":
            import tomllib
            _prescan_separators(text, doc, limits, "toml")
            data = tomllib.loads(text)
        elif fmt == "json":
            _prescan_separators(text, doc, limits, "json")
            data = json.loads(text, object_pairs_hook=_json_object)
        else:
            raise InputError(Problem("format", fmt, "yaml, toml or json"))
    except InputError:
        raise
    except _Duplicate as dup:
        raise InputError(_duplicate_problem(dup.key, where, _json_key_lines(text, dup.key))) from None
    except RecursionError:
        raise InputError(Problem(doc, "nesting", f"a document nested at most {limits.depth} levels deep")) from None
    except ValueError as exc:  # json.JSONDecodeError, tomllib.TOMLDecodeError, int() digit limit
        if fmt == "toml" and "Cannot overwrite a value" in str(exc):
            raise InputError(_toml_duplicate(text, str(exc), where)) from None
        raise InputError(Problem(doc, f"not valid {fmt.upper()}", _reason(exc))) from None
    except Exception as exc:  # yaml.YAMLError and its marks (line, column)
        if "nesting depth" in str(exc):  # libyaml's own limit (1000 levels), reached before ours while streaming
            raise InputError(Problem(doc, "nesting", f"a document nested at most {limits.depth} levels "
                                                     "deep")) from None
        raise InputError(Problem(doc, f"not valid {fmt.upper()}", _reason(exc))) from None
    check_values(data, where, limits=limits, allow_nonfinite=allow_nonfinite, doc=doc)
    return data


def _reason(exc: Exception) -> str:
    text = " ".join(str(exc).split())
    if "integer string conversion" in text:
        return f"numbers of at most {LIMITS.integer_digits} digits (a number in the file has thousands)"
    return f"valid syntax ({short(text, 300)})"


def _yaml(text: str, where: str, limits: Limits, name: str = "document") -> Any:
    """``where`` names the document in messages (``--parts (r.json)``), ``name`` the file (a duplicate key)."""
    _prescan_yaml(text, where, limits)
    loader = Yaml12Loader(text)
    loader.where = name
    try:
        node = loader.get_single_node()
        if node is None:
            return None
        _measure_yaml(node, where, limits)
        return loader.construct_document(node)
    finally:
        loader.dispose()


def _yaml_base():
    import yaml
    return getattr(yaml, "CSafeLoader", yaml.SafeLoader)  # libyaml when installed (PyYAML wheels have it)


def _prescan_yaml(text: str, where: str, limits: Limits) -> None:
    """Stream the YAML events; refuse more than ``limits.nodes`` values or ``limits.depth`` levels before
    anything is built (aliases count once here; their expansion is measured by :func:`_measure_yaml`)."""
    import yaml

    n = depth = 0
    for event in yaml.parse(text, Loader=_yaml_base()):
        if isinstance(event, (yaml.ScalarEvent, yaml.AliasEvent)):
            n += 1
        elif isinstance(event, yaml.CollectionStartEvent):
            n += 1
            depth += 1
            if depth > limits.depth:
                raise InputError(Problem(where, "nesting", f"a document nested at most {limits.depth} levels deep"))
        elif isinstance(event, yaml.CollectionEndEvent):
            depth -= 1
        if n > limits.nodes:
            raise InputError(Problem(where, "size", f"a document of at most {limits.nodes} values (this one has "
                                                    "more; refused before it is built)"))


def _prescan_separators(text: str, where: str, limits: Limits, fmt: str) -> None:
    """Refuse a TOML or JSON text with more value separators than ``limits.nodes`` before parsing it: commas
    (and, in TOML, lines); every value but the first of a list or mapping follows one (a JSON list of four
    million numbers took 2.7 s and 0.75 GB to build)."""
    n = text.count(",") + (text.count("\n") if fmt == "toml" else 0)
    if n > limits.nodes:
        raise InputError(Problem(where, "size", f"a document of at most {limits.nodes} values (this one has more "
                                                "separators; refused before it is parsed)"))


class _Duplicate(ValueError):
    def __init__(self, key):
        super().__init__(str(key))
        self.key = key


def _duplicate_problem(key, where: str, lines) -> Problem:
    shown = " and ".join(str(n) for n in lines) if lines else ""
    return Problem(f"{short(str(key))} ({where})", "given twice",
                   "each key once in a mapping (" + (f"lines {shown} both give it; " if shown else "")
                   + "the parser would keep the last silently)")


def _json_object(pairs):
    out = {}
    for k, v in pairs:
        if k in out:
            raise _Duplicate(k)
        out[k] = v
    return out


def _json_key_lines(text: str, key) -> list[int]:
    """The lines of the first two occurrences of ``key`` in one mapping of JSON ``text`` (its node positions,
    from the YAML parser: JSON is YAML 1.2 flow style), or ``[]`` when they cannot be told."""
    try:
        _yaml(text, "json", LIMITS, "json")
    except InputError as exc:
        m = re.search(r"lines (\d+) and (\d+)", str(exc))
        if m:
            return [int(m.group(1)), int(m.group(2))]
    except Exception:  # noqa: BLE001 - a JSON text libyaml does not read: the key is still named
        pass
    return []


def _toml_duplicate(text: str, message: str, where: str) -> Problem:
    """tomllib's "Cannot overwrite a value (at line N, ...)" as a Problem naming the key and both lines."""
    m = re.search(r"line (\d+)", message)
    second = int(m.group(1)) if m else None
    lines = text.splitlines()
    key = None
    if second and second <= len(lines):
        km = re.match(r"\s*([^=\s]+)\s*=", lines[second - 1])
        key = km.group(1).strip("\"'") if km else None
    first = None
    if key:
        pat = re.compile(r"\s*[\"']?" + re.escape(key) + r"[\"']?\s*=")
        first = next((i for i, line in enumerate(lines[:second - 1], start=1) if pat.match(line)), None)
    return _duplicate_problem(key or "a key", where, [n for n in (first, second) if n])


def _yaml12_loader():
    class Loader(_yaml_base()):
        """PyYAML's safe loader (libyaml) with YAML 1.2 core-schema scalars and duplicate keys refused."""

        where = "document"

        def construct_mapping(self, node, deep=False):
            seen: dict = {}
            for key_node, _ in node.value:
                if key_node.tag == "tag:yaml.org,2002:merge":
                    continue
                key = self.construct_object(key_node, deep=True)
                try:
                    hash(key)
                except TypeError:
                    continue  # an unhashable key: SafeConstructor reports it
                if key in seen:
                    raise InputError(_duplicate_problem(key, self.where, [seen[key] + 1,
                                                                          key_node.start_mark.line + 1]))
                seen[key] = key_node.start_mark.line
            return super().construct_mapping(node, deep=deep)

    Loader.yaml_implicit_resolvers = {}
    resolvers = [
        ("tag:yaml.org,2002:bool", r"^(?:true|True|TRUE|false|False|FALSE)$", list("tTfF")),
        ("tag:yaml.org,2002:null", r"^(?:~|null|Null|NULL|)$", ["~", "n", "N", ""]),
        ("tag:yaml.org,2002:int", r"^[-+]?[0-9]+$", list("-+0123456789")),
        ("tag:yaml.org,2002:float", r"^(?:[-+]?(?:\.[0-9]+|[0-9]+(?:\.[0-9]*)?)(?:[eE][-+]?[0-9]+)?"
                                    r"|[-+]?\.(?:inf|Inf|INF)|\.(?:nan|NaN|NAN))$", list("-+.0123456789")),
        ("tag:yaml.org,2002:merge", r"^(?:<<)$", ["<"]),
    ]
    for tag, rx, first in resolvers:
        Loader.add_implicit_resolver(tag, re.compile(rx), first)
    return Loader


class _LazyLoader:
    """:func:`_yaml12_loader`, built on first use (``yaml`` is imported only when a YAML file is read)."""

    _cls = None

    def __call__(self, text):
        if _LazyLoader._cls is None:
            _LazyLoader._cls = _yaml12_loader()
        return _LazyLoader._cls(text)


#: ``Yaml12Loader(text)``: the loader of every YAML file synth reads
Yaml12Loader = _LazyLoader()


def _measure_yaml(root, where: str, limits: Limits) -> None:
    """Count the values of a composed YAML node graph as if its aliases were expanded; check depth.

    An alias is the *same* node object as its anchor, so the count is
    memoised by node identity: linear in the document's size whatever the
    expansion, and stopped as soon as the limit is passed.
    """
    import yaml

    size: dict[int, int] = {}
    depth_of: dict[int, int] = {}
    # iterative post-order walk
    stack = [(root, False)]
    on_path: set[int] = set()
    shared = False
    seen: set[int] = set()
    while stack:
        node, done = stack.pop()
        key = id(node)
        if done:
            on_path.discard(key)
            kids = _yaml_children(node, yaml)
            n = 1 + sum(size[id(k)] for k in kids)
            d = 1 + max((depth_of[id(k)] for k in kids), default=0)
            if n > limits.nodes:
                raise InputError(Problem(where, "YAML aliases" if shared else "size",
                                         f"a document of at most {limits.nodes} values once its aliases are "
                                         f"expanded (this one expands to more than {limits.nodes}: an alias bomb?)"))
            if d > limits.depth:
                raise InputError(Problem(where, "nesting", f"a document nested at most {limits.depth} levels deep"))
            size[key], depth_of[key] = n, d
            continue
        if key in size:
            continue
        if key in on_path:  # a recursive structure (an alias inside its own anchor)
            raise InputError(Problem(where, "recursive YAML alias", "a document without self-referencing anchors"))
        on_path.add(key)
        stack.append((node, True))
        for k in _yaml_children(node, yaml):
            if id(k) in seen:
                shared = True
            seen.add(id(k))
            if id(k) not in size:
                stack.append((k, False))


def _yaml_children(node, yaml) -> list:
    if isinstance(node, yaml.MappingNode):
        return [x for pair in node.value for x in pair]
    if isinstance(node, yaml.SequenceNode):
        return list(node.value)
    return []


def check_values(data: Any, where: str, *, limits: Limits = LIMITS, allow_nonfinite: bool = False,
                 prefix: str = "", doc: str | None = None) -> None:
    """Walk ``data`` once; raise one :class:`InputError` listing every value beyond the limits.

    Each problem names the value's path in the document (``inputs.working_arm_mm``,
    ``rows[3].cost``) and the file ``where``.
    """
    problems: list[Problem] = []
    count = 0
    doc = doc or where
    stack: list[tuple[Any, str, int]] = [(data, prefix, 0)]
    while stack:
        value, path, depth = stack.pop()
        count += 1
        if count > limits.nodes:
            raise InputError(Problem(doc, "size", f"a document of at most {limits.nodes} values"))
        if depth > limits.depth:
            raise InputError(Problem(f"{path} ({where})" if path else doc, "nesting",
                                     f"a document nested at most {limits.depth} levels deep"))
        label = f"{path or 'document'} ({where})"
        if isinstance(value, dict):
            for k, v in value.items():
                if not isinstance(k, str):
                    if isinstance(k, (int, float, bool)) or k is None:
                        k_text = str(k)
                    else:
                        problems.append(Problem(label, short(k), "text keys (field names)"))
                        continue
                else:
                    k_text = k
                if len(k_text) > 200:
                    problems.append(Problem(label, short(k_text), "field names of at most 200 characters"))
                    continue
                stack.append((v, f"{path}.{k_text}" if path else k_text, depth + 1))
        elif isinstance(value, (list, tuple)):
            for i, v in enumerate(value):
                stack.append((v, f"{path}[{i}]", depth + 1))
        elif isinstance(value, bool) or value is None:
            continue
        elif isinstance(value, int):
            if value.bit_length() > limits.integer_digits * 3.33:
                problems.append(Problem(label, short(value), f"a number of at most {limits.integer_digits} digits"))
        elif isinstance(value, float):
            if not allow_nonfinite and not math.isfinite(value):
                problems.append(Problem(label, value, "a finite number (not infinity or NaN; a number beyond "
                                                      "1.8e308 reads as infinity)"))
        elif isinstance(value, str):
            if len(value) > limits.string_chars:
                problems.append(Problem(label, short(value), f"a text of at most {limits.string_chars} characters"))
        if len(problems) >= 50:
            break
    if problems:
        raise InputError(problems)


def read_document(path, what: str, *, accepted: str = "an existing .yaml, .yml, .toml or .json file",
                  allow_nonfinite: bool = False) -> Any:
    """The data of a YAML, TOML or JSON file (by extension), within the gate's limits."""
    fmt = FORMAT_OF_SUFFIX.get(suffix_of(path))
    if fmt is None:
        kind = kind_of_file(path)  # by content: a workbook, a PDF... named where a document is expected
        raise InputError(Problem(what, str(path), accepted + (f"; this is {kind}" if kind else " (by its extension)")))
    text = read_text(path, what, accepted=accepted)
    return parse(text, fmt, Path(path).name, allow_nonfinite=allow_nonfinite, what=what)
