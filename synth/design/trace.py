"""How a derivation sees an evaluation (:mod:`synth.design.derivation`): the physics calls recorded by a profiler
hook while the one evaluator runs (:func:`traced`: every :mod:`synth.model` function, :func:`synth.catalog.constant`
and :func:`synth.parts.mu`, with arguments, result and nesting), and the evaluator's own lines read from its source
(:func:`evaluator_lines`) for a value a group computes without a physics call.
"""

from __future__ import annotations

import ast
import functools
import inspect
import sys
import threading
from dataclasses import dataclass

import numpy as np

__all__ = ["Call", "scalar", "outputs", "Tracer", "traced", "evaluator_lines", "referenced"]


# --------------------------------------------------------------------------------------------- the trace
@dataclass
class Call:
    index: int
    module: str
    name: str
    args: dict
    depth: int
    start: int
    end: int = -1
    result: object = None

    @property
    def qualname(self) -> str:
        return f"{self.module}.{self.name}"

    @functools.cached_property
    def outputs(self) -> list:
        """:func:`outputs` of the call's result (read once the call has returned: a derivation asks it many times)."""
        return outputs(self.result)


def scalar(x):
    """A traced value as a plain scalar (an array of one value: its value), else None (not shown as a number)."""
    if isinstance(x, (bool, np.bool_)):
        return bool(x)
    if isinstance(x, (int, float, np.integer, np.floating)):
        return float(x)
    if isinstance(x, str):
        return x
    if isinstance(x, np.ndarray) and x.size == 1 and x.dtype.kind in "biuf":
        v = x.reshape(-1)[0]
        return bool(v) if x.dtype.kind == "b" else float(v)
    return None


def outputs(result) -> list:
    """``[(name or None, value)]`` of a call's result: a scalar, a dict's scalar items, a tuple's scalars."""
    if isinstance(result, dict):
        return [(k, v) for k, v in ((k, scalar(x)) for k, x in result.items()) if isinstance(v, float)]
    if isinstance(result, tuple):
        return [(None, v) for v in map(scalar, result) if isinstance(v, float)]
    v = scalar(result)
    return [(None, v)] if isinstance(v, float) else []


def _recorded(fn) -> bool:
    """Whether ``fn`` is a call a derivation records: a :mod:`synth.model` function, :func:`synth.catalog.constant`
    or :func:`synth.parts.mu`."""
    mod, name = getattr(fn, "__module__", None) or "", getattr(fn, "__name__", "")
    return (mod.startswith("synth.model.") and not name.startswith("<")) or \
        (mod == "synth.catalog" and name == "constant") or (mod == "synth.parts" and name == "mu")


class Tracer:
    """The recorder of every call of a :mod:`synth.model` function, of :func:`synth.catalog.constant` and of
    :func:`synth.parts.mu` (arguments at the call, defaults applied; result at the return; nesting depth and event
    order), through a wrapper put in the place of each such function in synth's modules while :func:`traced` runs.

    A wrapper, not a profiler hook: a hook sees every Python and C call of the evaluation (numpy, pandas) and made a
    traced evaluation about 30 times slower than the evaluation; the wrappers cost only the recorded calls."""

    def __init__(self):
        self.calls: list[Call] = []
        self.depth = 0
        self.t = 0
        self.thread = threading.get_ident()  # the traced call's thread: another thread's calls pass unrecorded

    def wrap(self, fn):
        code = fn.__code__
        names = code.co_varnames[:code.co_argcount + code.co_kwonlyargcount]
        signature = inspect.signature(fn)

        @functools.wraps(fn)
        def recording(*args, **kw):
            if threading.get_ident() != self.thread:
                return fn(*args, **kw)
            bound = signature.bind(*args, **kw)
            bound.apply_defaults()
            given = bound.arguments
            c = Call(len(self.calls), fn.__module__, fn.__name__,
                     {k: scalar(given.get(k)) if scalar(given.get(k)) is not None else given.get(k) for k in names},
                     self.depth, self.t)
            self.calls.append(c)
            self.t += 1
            self.depth += 1
            try:
                out = fn(*args, **kw)
            finally:
                self.depth -= 1
            c.result, c.end = out, self.t
            self.t += 1
            return out
        return recording


def traced(fn, *args, **kw):
    """``(fn(*args, **kw), tracer)`` with every recorded function (:class:`Tracer`) wrapped, in every loaded
    ``synth`` module's namespace, for the call (the originals restored after, also on an exception)."""
    tracer = Tracer()
    wrappers: dict = {}
    swapped: list = []
    for name, module in list(sys.modules.items()):
        if not (name == "synth" or name.startswith("synth.")) or module is None:
            continue
        namespace = vars(module)
        for attr, value in list(namespace.items()):
            if inspect.isfunction(value) and _recorded(value):
                if value not in wrappers:
                    wrappers[value] = tracer.wrap(value)
                swapped.append((namespace, attr, value))
                namespace[attr] = wrappers[value]
    try:
        out = fn(*args, **kw)
    finally:
        for namespace, attr, value in swapped:
            namespace[attr] = value
    return out, tracer


# --------------------------------------------------------------------------------------------- the evaluator's lines
@functools.lru_cache(maxsize=1)
def evaluator_lines() -> dict:
    """``{value key: (group function, source text of its expression, module file)}`` of the evaluator's own
    assignments (``v["k"] = ...``, ``v.update(k=...)``, dict literals of ``v``), read from :mod:`synth.design.evaluate`
    and its group modules."""
    from synth.design import axial_group, bolt_group, evaluate, spring_group
    out: dict = {}
    for module in (evaluate, axial_group, spring_group, bolt_group):
        module_lines(module, out)
    return out


def _segment(lines: list, node) -> str:
    """The source text of ``node`` (:func:`ast.get_source_segment`, from the module's ``lines`` split once; the
    column offsets are UTF-8 byte offsets)."""
    first, last = node.lineno - 1, node.end_lineno - 1
    if first == last:
        return lines[first].encode()[node.col_offset:node.end_col_offset].decode()
    head = lines[first].encode()[node.col_offset:].decode()
    tail = lines[last].encode()[:node.end_col_offset].decode()
    return head + "".join(lines[first + 1:last]) + tail


def module_lines(module, out: dict) -> None:
    """:func:`evaluator_lines` of one module, added to ``out`` (the first assignment of a key kept)."""
    src = inspect.getsource(module)
    tree = ast.parse(src)
    lines = src.splitlines(keepends=True)  # once: ast.get_source_segment splits the whole module on every call
    path = "synth/" + module.__name__.split(".", 1)[1].replace(".", "/") + ".py"
    for fn in (n for n in tree.body if isinstance(n, ast.FunctionDef)):
        for node in ast.walk(fn):
            pairs = []
            if isinstance(node, ast.Assign) and len(node.targets) == 1:
                t = node.targets[0]
                if isinstance(t, ast.Subscript) and isinstance(t.value, ast.Name) and t.value.id == "v" \
                        and isinstance(t.slice, ast.Constant) and isinstance(t.slice.value, str):
                    pairs.append((t.slice.value, node.value))
                if isinstance(t, ast.Tuple) and isinstance(node.value, ast.Tuple) \
                        and len(t.elts) == len(node.value.elts):  # v["a"], v["b"] = x, y
                    pairs += [(e.slice.value, x) for e, x in zip(t.elts, node.value.elts)
                              if isinstance(e, ast.Subscript) and isinstance(e.value, ast.Name) and e.value.id == "v"
                              and isinstance(e.slice, ast.Constant) and isinstance(e.slice.value, str)]
                if isinstance(t, ast.Name) and t.id == "v" and isinstance(node.value, ast.Dict):
                    pairs += [(k.value, v) for k, v in zip(node.value.keys, node.value.values)
                              if isinstance(k, ast.Constant) and isinstance(k.value, str)]
            if isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute) and node.func.attr == "update" \
                    and isinstance(node.func.value, ast.Name) and node.func.value.id == "v":
                pairs += [(k.arg, k.value) for k in node.keywords if k.arg]
                for a in node.args:
                    if isinstance(a, ast.Dict):
                        pairs += [(k.value, v) for k, v in zip(a.keys, a.values)
                                  if isinstance(k, ast.Constant) and isinstance(k.value, str)]
            for key, expr in pairs:
                text = " ".join(_segment(lines, expr).split())
                out.setdefault(key, (fn.name, text, path))


def referenced(text: str) -> list:
    """The keys an evaluator expression reads (``f["x"]``, ``v["x"]``, ``c["x"]``...) and the named constants it
    reads (``_const("x")``: the group modules' name of :func:`synth.design.group.const`), in order.

    >>> referenced('_const("bolt_yield_utilisation_max") * np.asarray(o["rp02_mpa"], dtype=float)')
    ['bolt_yield_utilisation_max', 'rp02_mpa']
    """
    import re
    return list(dict.fromkeys(re.findall(r'(?:_const\(\s*|\[\s*)"([A-Za-z_][A-Za-z_0-9]*)"\s*[\])]', text)))
