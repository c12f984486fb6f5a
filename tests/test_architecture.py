"""The package's shape (issues 21, 33): no import circle, imports pointing down the layers, few private names used
across modules, the linter clean.

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
#: the layers, lowest first (issue 33): a module is in the layer of the longest prefix naming it; an import of a
#: higher layer runs back up. Within a layer, imports go either way (the circle tests keep them a tree).
LAYERS = (
    # foundations: no physics and no catalog: errors, version, plug-ins, threads, text, files and numbers read and written
    ("formulations", "synth.version", "synth.errors", "synth.plugins", "synth.fingerprint", "synth.threads", "synth.progress",
     "synth.display", "synth.formatting", "synth.output_table", "synth.io", "synth.excel.cells"),
    # the data: catalogs, the input schema, the generated applications
    ("synth.catalog", "synth.schema", "synth.data"),
    # the physics, the parts' arrays and prices, the compiled twins of the physics (numba set up once)
    ("synth.model", "synth.parts", "synth.cost", "synth.drive", "synth.kernels"),
    # the core: the registry, the configuration, the one evaluator and result
    ("synth.design",),
    # the searches over the core: the flowchart, the optimisers, the compiled scans, the shrink fit, the cost decision
    ("synth.flowchart", "synth.optimise", "synth.kernels.main_spring", "synth.kernels.spring_tables",
     "synth.kernels.engines", "synth.shrink_fit",
     "synth.compare", "synth.cost.breakdown", "synth.cost.decision"),
    # the runs built on the searches: production scatter, bulk, the platform
    ("synth.robust", "synth.bulk", "synth.platform"),
    # presentation and the readers of the user's documents
    ("synth.report", "synth.excel", "synth.cad", "synth.io.documents", "synth.io.saved_results"),
    # the Python API (synth/__init__.py only), the web UI on it, the command line's scenes
    ("synth",),
    ("synth.ui",),
    ("synth.scenes", "synth.cli", "synth.__main__"),
)
#: imports running back up the layers allowed (issue 33: 5 under these layers before it, 0 after: the API's
#: write_report reads its source through synth.report.source, as `synth report FILE` does)
MAX_BACK_ARROWS = 0
#: private names (``_name``) of one module used in another (issue 33: 23 before it, 0 after: a name another module
#: needs is a public seam)
MAX_PRIVATE_NAMES = 0
#: the longest a module may be (issue 33: "no file over 600 lines holding more than one idea")
MAX_LINES = 600
#: the modules over :data:`MAX_LINES` and why (each must still be over it: a module split leaves the list)
LONG_MODULES = {
    # one idea each, its declarations or its one model at length
    "synth/design/constraints.py": "the registry: the Constraint type and its entries (data, one per check)",
    "synth/schema.py": "the design input: its field table (one declaration per field) and its one validator",
    "synth/design/space.py": "the catalog design space: the part tables of the product and their decomposition",
    "synth/model/disc_spring.py": "one model: the cone spring of step 8 (Almen-Laszlo, DIN EN 16984) and its sizing",
    "formulations/platform.py": "one mathematical program: the platform MILP and its data (no synth import)",
}


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


def layer_of(module: str) -> int:
    """The index in :data:`LAYERS` of the longest prefix naming ``module`` (``synth`` names the package's top only)."""
    best, at = -1, None
    for i, names in enumerate(LAYERS):
        for p in names:
            if (module == p or (p != "synth" and module.startswith(p + "."))) and len(p) > best:
                best, at = len(p), i
    if at is None:
        raise AssertionError(f"{module} is in no layer: add its package to LAYERS")
    return at


def with_packages(graph: dict) -> dict:
    """Every import with the packages it initialises (importing ``a.b.c`` runs ``a.b``'s ``__init__``, lazily or
    not) where that ``__init__`` imports a module, except the importer's own packages."""
    out = {}
    for m, ts in graph.items():
        own = m.split(".")
        out[m] = set(ts) | {p for t in ts for i in range(1, t.count(".") + 1)
                            if t.split(".")[:i] != own[:i] and graph.get(p := ".".join(t.split(".")[:i]))}
    return out


def back_arrows(graph: dict) -> list:
    """``[(importer, imported), ...]``: the imports from a lower layer to a higher one, lazy ones included, and the
    packages they initialise (a package counted apart only where no module of it is a back arrow already)."""
    up = {(m, t) for m, ts in with_packages(graph).items() for t in ts if layer_of(t) > layer_of(m)}
    return sorted((m, t) for m, t in up if not any(m == a and b.startswith(t + ".") for a, b in up))


def private_names() -> dict:
    """``{"module.name": [modules using it]}``: the private names (``_name``, not dunder) of one of the packages'
    modules that another module imports or reads as an attribute, and the private modules imported from outside
    their package (an import inside a function or a ``module._name`` read counts as much as a top import)."""
    mods = _modules()
    uses: dict = {}
    for m, p in mods.items():
        pkg = m if p.name == "__init__.py" else m.rpartition(".")[0]
        tree = ast.parse(p.read_text(encoding="utf-8"))
        alias = {}
        for node in ast.walk(tree):
            if isinstance(node, ast.Import):
                for a in node.names:
                    if a.name in mods:
                        alias[a.asname or a.name.split(".")[0]] = a.name if a.asname else a.name.split(".")[0]
            elif isinstance(node, ast.ImportFrom):
                base = node.module or ""
                if node.level:
                    up = pkg.split(".")[: len(pkg.split(".")) - (node.level - 1)]
                    base = ".".join(up + ([node.module] if node.module else []))
                if base not in mods:
                    continue
                for a in node.names:
                    full, private = f"{base}.{a.name}", a.name.startswith("_") and not a.name.startswith("__")
                    if full in mods:
                        alias[a.asname or a.name] = full
                        if private and base != pkg:
                            uses.setdefault(full, set()).add(m)
                    elif private and base != m:
                        uses.setdefault(full, set()).add(m)
        for node in ast.walk(tree):
            if isinstance(node, ast.Attribute) and node.attr.startswith("_") and not node.attr.startswith("__"):
                chain, v = [], node.value
                while isinstance(v, ast.Attribute):
                    chain.append(v.attr)
                    v = v.value
                if isinstance(v, ast.Name) and v.id in alias:
                    target = ".".join([alias[v.id], *chain[::-1]])
                    if target in mods and target != m:
                        uses.setdefault(f"{target}.{node.attr}", set()).add(m)
    return {k: sorted(v) for k, v in sorted(uses.items())}


def test_layers_find_a_back_arrow():
    assert layer_of("synth") == layer_of("synth.ui") - 1 and layer_of("synth.design.evaluate") == layer_of("synth.design")
    assert layer_of("synth.kernels.axial") < layer_of("synth.design") < layer_of("synth.kernels.main_spring")
    graph = {"synth.design.evaluate": {"synth.kernels.axial"}, "synth.kernels.axial": set(),
             "synth.kernels": {"synth.kernels.main_spring"}, "synth.kernels.main_spring": {"synth.design.evaluate"},
             "synth.design": set()}
    # importing synth.kernels.axial initialises synth.kernels, which imports the scans above the core
    assert back_arrows(graph) == [("synth.kernels", "synth.kernels.main_spring")]


def test_imports_point_down_the_layers():
    """At most :data:`MAX_BACK_ARROWS` imports run from a lower layer to a higher one (issue 33)."""
    found = back_arrows(import_graph())
    assert len(found) <= MAX_BACK_ARROWS, f"{len(found)} imports run back up the layers: {found}"


def test_private_names_used_across_modules():
    """A name another module needs is a public seam; at most :data:`MAX_PRIVATE_NAMES` private names are shared."""
    found = private_names()
    assert len(found) <= MAX_PRIVATE_NAMES, f"{len(found)} private names used across modules: {found}"


def test_no_long_module():
    """No module of the packages is over :data:`MAX_LINES` lines, but those of :data:`LONG_MODULES` (which still are:
    a module that shrinks leaves the list)."""
    lines = {str(p.relative_to(ROOT)): len(p.read_text(encoding="utf-8").splitlines()) for p in _modules().values()}
    long = {k: n for k, n in lines.items() if n > MAX_LINES}
    assert sorted(set(long) - set(LONG_MODULES)) == [], f"modules over {MAX_LINES} lines: " + ", ".join(
        f"{k} ({n})" for k, n in sorted(long.items()) if k not in LONG_MODULES)
    assert sorted(set(LONG_MODULES) - set(long)) == [], "no longer over the limit (remove from LONG_MODULES): " + \
        ", ".join(f"{k} ({lines.get(k, 'absent')})" for k in sorted(set(LONG_MODULES) - set(long)))
