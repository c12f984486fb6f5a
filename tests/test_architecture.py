"""The package's shape (issue 21): no import circle, the core below presentation, the linter clean.

The import graph is read from the source (every ``import`` and ``from ... import``, at module top or inside a
function: a lazy import is still a dependency), so it needs no import of synth and takes well under a second.
"""

from __future__ import annotations

import ast
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
PACKAGES = ("synth", "formulations")
#: the core: the physics, the input schema, the registry and evaluator (issue 21: they import no presentation)
CORE = ("synth.design", "synth.model", "synth.schema", "synth.kernels")
#: what the core must not import: presentation and the readers of the user's documents
PRESENTATION = ("synth.report", "synth.excel", "synth.io.documents", "synth.scenes", "synth.ui", "synth.cli",
                "synth.cad")


def _modules() -> dict:
    """``{dotted name: path}`` of every module of the packages."""
    out = {}
    for pkg in PACKAGES:
        for p in (ROOT / pkg).rglob("*.py"):
            parts = list(p.relative_to(ROOT).with_suffix("").parts)
            if parts[-1] == "__init__":
                parts = parts[:-1]
            out[".".join(parts)] = p
    return out


def import_graph(at_import: bool = False) -> dict:
    """``{module: {imported module, ...}}`` over the packages' own modules (``from a import b`` names ``a.b`` when
    it is a module, else ``a``).

    ``at_import``: only what runs when the module is imported (statements outside functions), with the packages
    an import initialises on the way (importing ``a.b.c`` runs ``a/__init__`` and ``a/b/__init__``, except the
    importer's own packages, initialised before it). A circle there is a partially initialised module at run time,
    one the lazy imports of the whole graph can hide (its ``a.b.c`` edge never names ``a.b``).
    """
    mods = _modules()

    def resolve(name: str):
        while name and name not in mods:
            name = name.rpartition(".")[0]
        return name or None

    graph = {}
    for m, p in mods.items():
        pkg = m if p.name == "__init__.py" else m.rpartition(".")[0]
        out = set()
        tree = ast.parse(p.read_text(encoding="utf-8"))
        for node in (_at_import(tree) if at_import else ast.walk(tree)):
            if isinstance(node, ast.Import):
                names = [a.name for a in node.names]
            elif isinstance(node, ast.ImportFrom):
                base = node.module or ""
                if node.level:
                    up = pkg.split(".")[: len(pkg.split(".")) - (node.level - 1)]
                    base = ".".join(up + ([node.module] if node.module else []))
                names = [f"{base}.{a.name}" for a in node.names]
            else:
                continue
            found = {r for r in map(resolve, names) if r and r != m}
            if at_import:
                own = m.split(".")
                found |= {".".join(r.split(".")[:i]) for r in found for i in range(1, r.count(".") + 1)
                          if r.split(".")[:i] != own[:i]}
            out |= found
        graph[m] = out
    return graph


def _at_import(tree):
    """The nodes that run when the module is imported: everything outside function bodies."""
    todo = list(tree.body)
    while todo:
        node = todo.pop()
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef, ast.Lambda)):
            continue
        yield node
        todo.extend(ast.iter_child_nodes(node))


def circles(graph: dict) -> list:
    """The strongly connected components of more than one module (Tarjan, iterative)."""
    index, low, on, stack, out = {}, {}, set(), [], []
    counter = 0
    for root in graph:
        if root in index:
            continue
        work = [(root, iter(sorted(graph[root])))]
        index[root] = low[root] = counter
        counter += 1
        stack.append(root)
        on.add(root)
        while work:
            v, it = work[-1]
            w = next(it, None)
            if w is not None:
                if w not in index:
                    index[w] = low[w] = counter
                    counter += 1
                    stack.append(w)
                    on.add(w)
                    work.append((w, iter(sorted(graph.get(w, ())))))
                elif w in on:
                    low[v] = min(low[v], index[w])
                continue
            work.pop()
            if work:
                low[work[-1][0]] = min(low[work[-1][0]], low[v])
            if low[v] == index[v]:
                comp = []
                while True:
                    w = stack.pop()
                    on.discard(w)
                    comp.append(w)
                    if w == v:
                        break
                if len(comp) > 1:
                    out.append(sorted(comp))
    return out


def test_circles_finds_a_loop():
    assert circles({"a": {"b"}, "b": {"c"}, "c": {"a"}, "d": {"a"}}) == [["a", "b", "c"]]
    assert circles({"a": {"b"}, "b": set()}) == []


def test_no_import_circle():
    found = circles(import_graph())
    assert not found, f"import circles (module-level or inside functions): {found}"


def test_no_circle_when_imported():
    """What runs at import, package initialisation included, has no circle (a module would be read half-made)."""
    graph = import_graph(at_import=True)
    assert "synth.kernels" in graph["synth.optimise.batch"]  # its `from synth.kernels import ...` runs the package
    assert "synth.design" not in graph["synth.design.evaluate"]  # its own package is initialised before it
    found = circles(graph)
    assert not found, f"import circles at import time (package __init__ included): {found}"


def _under(name: str, prefixes) -> bool:
    return any(name == p or name.startswith(p + ".") for p in prefixes)


def test_core_imports_no_presentation():
    graph = import_graph()
    bad = sorted((m, t) for m, ts in graph.items() if _under(m, CORE) for t in ts if _under(t, PRESENTATION))
    assert not bad, f"the core imports presentation: {bad}"


def test_the_version_is_a_leaf():
    """The version is a leaf; the package's top (the public API) is imported only by its client, the web UI."""
    graph = import_graph()
    assert graph["synth.version"] == set()
    importers = sorted(m for m, ts in graph.items() if "synth" in ts and not _under(m, ("synth.ui",)))
    assert importers == [], f"modules importing the package's top: {importers}"


@pytest.mark.skipif(shutil.which("ruff") is None and not (Path(sys.executable).parent / "ruff").exists(),
                    reason="ruff not installed (pip install ruff)")
def test_ruff_is_clean():
    """The linter configured in pyproject.toml ([tool.ruff]) finds nothing."""
    ruff = shutil.which("ruff") or str(Path(sys.executable).parent / "ruff")
    res = subprocess.run([ruff, "check", "--no-cache", "--quiet", str(ROOT)], capture_output=True, text=True,
                         timeout=120)
    assert res.returncode == 0, res.stdout[-4000:] + res.stderr[-2000:]
