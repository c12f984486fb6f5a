r"""YAML, TOML and JSON documents, parsed within the gate's limits.

:func:`parse` turns the text of a document into plain Python data (dicts,
lists, str, int, float, bool, None) or raises one
:class:`~synth.errors.InputError`. Before a YAML document is built, its node
graph is measured: aliases are counted as often as they would be expanded,
so a "billion laughs" alias bomb is refused in milliseconds, and the message
does not print the expanded value. After parsing, :func:`check_values` walks
the data once (iteratively) and reports, with the path of each offending
value as the user wrote it (``roughness.journal.Ra``):

* nesting deeper than :attr:`Limits.depth`, more than :attr:`Limits.nodes` values;
* text longer than :attr:`Limits.string_chars`;
* integers of more than :attr:`Limits.integer_digits` digits (a 400-digit
  integer would overflow a float: ``OverflowError``);
* non-finite numbers (``.inf``, ``NaN``, ``1e400``) unless allowed.

>>> parse("a: 1\nb: [2, 3.5]\n", "yaml", "x.yaml")
{'a': 1, 'b': [2, 3.5]}
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
from typing import Any

from synth.errors import InputError, Problem
from synth.io.limits import LIMITS, Limits, short

__all__ = ["parse", "check_values", "FORMAT_OF_SUFFIX"]

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
            data = _yaml(text, doc, limits)
        elif fmt == "toml":
            import tomllib
            data = tomllib.loads(text)
        elif fmt == "json":
            data = json.loads(text)
        else:
            raise InputError(Problem("format", fmt, "yaml, toml or json"))
    except InputError:
        raise
    except RecursionError:
        raise InputError(Problem(doc, "nesting", f"a document nested at most {limits.depth} levels deep")) from None
    except ValueError as exc:  # json.JSONDecodeError, tomllib.TOMLDecodeError, int() digit limit
        raise InputError(Problem(doc, f"not valid {fmt.upper()}", _reason(exc))) from None
    except Exception as exc:  # yaml.YAMLError and its marks (line, column)
        raise InputError(Problem(doc, f"not valid {fmt.upper()}", _reason(exc))) from None
    check_values(data, where, limits=limits, allow_nonfinite=allow_nonfinite, doc=doc)
    return data


def _reason(exc: Exception) -> str:
    text = " ".join(str(exc).split())
    if "integer string conversion" in text:
        return f"numbers of at most {LIMITS.integer_digits} digits (a number in the file has thousands)"
    return f"valid syntax ({short(text, 300)})"


def _yaml(text: str, where: str, limits: Limits) -> Any:
    import yaml

    loader = yaml.SafeLoader(text)
    try:
        node = loader.get_single_node()
        if node is None:
            return None
        _measure_yaml(node, where, limits)
        return loader.construct_document(node)
    finally:
        loader.dispose()


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
