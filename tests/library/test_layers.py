"""The house's import structure, computed from the source with ``ast``: no import circle among
wheelkin's modules, and no import from a lower layer to a higher one.

The layers are ``wheelkin._registry.LAYERS``, bottom first: the formula modules (numpy only,
with their private support modules), the figure style, the sandbox, and the book's modules
(animation, display, widgets, exercises). Every ``import`` statement counts, wherever it is:
at the top of a module, inside a function (a lazy import is still a dependency, and a lazy
import was how the one circle of the first edition hid), or under ``TYPE_CHECKING``. Only the
two registries' chapter modules, which ``wheelkin._registry.load_chapter_modules`` imports by
name at lookup time, are not edges: that is a plugin registry, not an import.

Each check is a function of a source directory, so the self-tests at the end plant an import
in a copy of the library and see the check fail.
"""

from __future__ import annotations

import ast
import shutil
from pathlib import Path

import pytest

import wheelkin
from wheelkin._registry import LAYERS

SRC = Path(wheelkin.__file__).resolve().parent


def modules(src: Path = SRC) -> dict[str, Path]:
    """Dotted name -> file, for every module of the package in ``src``."""
    out = {}
    for path in sorted(src.rglob("*.py")):
        parts = list(path.relative_to(src.parent).with_suffix("").parts)
        if parts[-1] == "__init__":
            parts.pop()
        out[".".join(parts)] = path
    return out


def imports(src: Path = SRC) -> dict[str, set[str]]:
    """The import graph: each module -> the package's modules it imports (anywhere in it).

    ``from a.b import c`` is an edge to ``a.b.c`` when that is a module, else to ``a.b``;
    ``import a.b.c`` is an edge to ``a.b.c``; relative imports are resolved.
    """
    known = modules(src)
    graph: dict[str, set[str]] = {}
    for name, path in known.items():
        package = name if path.name == "__init__.py" else name.rpartition(".")[0]
        targets: set[str] = set()
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"), filename=str(path))):
            if isinstance(node, ast.Import):
                targets |= {alias.name for alias in node.names}
            elif isinstance(node, ast.ImportFrom):
                base = node.module or ""
                if node.level:
                    anchor = package.split(".")
                    anchor = anchor[:len(anchor) - node.level + 1]
                    base = ".".join([*anchor, base] if base else anchor)
                for alias in node.names:
                    full = f"{base}.{alias.name}"
                    targets.add(full if full in known else base)
        graph[name] = {_owner(t, known) for t in targets} - {None, name}
    return graph


def _owner(target: str, known: dict[str, Path]) -> str | None:
    """The longest prefix of ``target`` that is a module of the package (None: not ours)."""
    parts = target.split(".")
    for k in range(len(parts), 0, -1):
        if ".".join(parts[:k]) in known:
            return ".".join(parts[:k])
    return None


def circles(graph: dict[str, set[str]]) -> list[list[str]]:
    """The strongly connected components with more than one module (Tarjan), sorted."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on_stack: set[str] = set()
    found: list[list[str]] = []

    def visit(v: str) -> None:
        index[v] = low[v] = len(index)
        stack.append(v)
        on_stack.add(v)
        for w in sorted(graph.get(v, ())):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on_stack:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            component = []
            while True:
                w = stack.pop()
                on_stack.discard(w)
                component.append(w)
                if w == v:
                    break
            if len(component) > 1:
                found.append(sorted(component))

    for v in sorted(graph):
        if v not in index:
            visit(v)
    return sorted(found)


def layer_of(module: str, layers=LAYERS) -> int:
    """The index of ``module``'s layer (the package root counts as the bottom)."""
    parts = module.split(".")
    if len(parts) == 1:
        return 0
    for i, (_, names) in enumerate(layers):
        if parts[1] in names:
            return i
    raise KeyError(f"{module} is in no layer of wheelkin._registry.LAYERS")


def upward(graph: dict[str, set[str]], layers=LAYERS) -> list[str]:
    """Every import from a module to one in a higher layer, as 'a (layer) -> b (layer)'."""
    out = []
    for a in sorted(graph):
        for b in sorted(graph[a]):
            la, lb = layer_of(a, layers), layer_of(b, layers)
            if lb > la:
                out.append(f"{a} ({layers[la][0]}) -> {b} ({layers[lb][0]})")
    return out


# ------------------------------------------------------------------------------ the house

def test_no_import_circle():
    assert circles(imports()) == []


def test_no_import_from_a_lower_layer_to_a_higher_one():
    assert upward(imports()) == []


def test_no_formula_module_imports_the_sandbox_or_the_book():
    graph = imports()
    formula = [m for m in graph if layer_of(m) == 0]
    assert len(formula) >= 15
    for m in formula:
        assert all(layer_of(t) == 0 for t in graph[m]), (m, graph[m])


def test_the_graph_sees_every_kind_of_import():
    """Not vacuous: the graph holds the edges the house is built on."""
    graph = imports()
    assert "wheelkin.waypoints" in graph["wheelkin.follower"]  # from wheelkin.waypoints import
    assert "wheelkin._validate" in graph["wheelkin.frames"]  # from wheelkin import _validate
    assert "wheelkin.sources" in graph["wheelkin.frames"]  # the old paths' re-export
    assert "wheelkin.sandbox.render" in graph["wheelkin.widgets.mecanum"]
    assert "wheelkin.exercises" in graph["wheelkin.exercises.rover"]  # the package itself
    assert "wheelkin.style" in graph["wheelkin.animation"]  # a lazy import in a function
    assert sum(len(targets) for targets in graph.values()) > 100


# ------------------------------------------------------------------------------ self-tests

@pytest.fixture
def copy(tmp_path: Path) -> Path:
    dest = tmp_path / "wheelkin"
    shutil.copytree(SRC, dest, ignore=shutil.ignore_patterns("__pycache__"))
    return dest


def _plant(path: Path, code: str) -> None:
    path.write_text(path.read_text(encoding="utf-8") + "\n\n" + code + "\n", encoding="utf-8")


def test_self_test_the_first_editions_circle_is_found(copy):
    # what waypoints.py held before: a lazy re-export of the names that moved to follower
    _plant(copy / "waypoints.py", (
        "def __getattr__(name):\n"
        "    if name == 'PathFollower':\n"
        "        from wheelkin import follower\n"
        "        return follower.PathFollower\n"
        "    raise AttributeError(name)"))
    assert circles(imports(copy)) == [["wheelkin.follower", "wheelkin.waypoints"]]
    assert upward(imports(copy)) == []


def test_self_test_an_upward_import_is_found(copy):
    _plant(copy / "frames.py", "from wheelkin.sandbox.world import World  # noqa")
    found = upward(imports(copy))
    assert found == ["wheelkin.frames (formula) -> wheelkin.sandbox.world (sandbox)"]


def test_self_test_a_relative_import_in_a_package_is_resolved(copy):
    _plant(copy / "sandbox" / "sensors.py", "from ..widgets import sandbox as panel  # noqa")
    assert upward(imports(copy)) == [
        "wheelkin.sandbox.sensors (sandbox) -> wheelkin.widgets.sandbox (book)"]


def test_self_test_a_module_in_no_layer_is_refused():
    with pytest.raises(KeyError, match="no layer"):
        layer_of("wheelkin.teleport")
