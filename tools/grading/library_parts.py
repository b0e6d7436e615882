"""The parts of wheelkin an exercise may use, and nothing else: a package written for the
exercise's grading sandbox.

An exercise declares ``library=("wheelkin.carlike.linkage_error", ...)``. :func:`build`
writes a package ``wheelkin`` that holds those names and what they need to run (the helpers,
constants and classes of their modules that they use, and, through the imports they use,
the same for other wheelkin modules), copied from the library's own source, and nothing else:
no other function of those modules, no other module. A name that is not needed is not
there, so the library's answer to an exercise (``carlike.optimal_arm_angle``,
``wheelkin.exercises``' references) cannot be imported or read where the student's function
is graded.

Only top-level statements are kept or dropped, whole; annotations are not followed (the
library's modules use ``from __future__ import annotations``, so they are strings that are
never evaluated).
"""

from __future__ import annotations

import ast
from pathlib import Path

from tools.grading.source import (
    Statement,
    bound_name,
    filtered_import,
    needed_statements,
    statements_of,
)

PACKAGE = "wheelkin"


def _module_file(src: Path, module: str) -> Path:
    parts = module.split(".")
    base = src.joinpath(*parts)
    if (base / "__init__.py").is_file():
        return base / "__init__.py"
    if base.with_suffix(".py").is_file():
        return base.with_suffix(".py")
    raise ValueError(f"no module {module} under {src}")


def _split(part: str, src: Path) -> tuple[str, str]:
    """``("wheelkin.carlike", "linkage_error")`` from ``"wheelkin.carlike.linkage_error"``."""
    module, _, name = part.rpartition(".")
    _module_file(src, module)  # raises if there is no such module
    return module, name


def _absolute(module: str, is_package: bool, node: ast.ImportFrom) -> str | None:
    """The absolute module an ``ImportFrom`` in ``module`` names (relative ones resolved)."""
    if node.level == 0:
        return node.module
    package = module.split(".") if is_package else module.split(".")[:-1]
    package = package[: len(package) - (node.level - 1)]
    return ".".join(package + ([node.module] if node.module else []))


class _Module:
    def __init__(self, src: Path, name: str) -> None:
        self.name = name
        path = _module_file(src, name)
        self.is_package = path.name == "__init__.py"
        self.text = path.read_text(encoding="utf-8")
        self.statements = statements_of(self.text, annotations=False)
        self.future = any(isinstance(s.node, ast.ImportFrom) and s.node.module == "__future__"
                          for s in self.statements)


def _wheelkin_imports(module: _Module, statement: Statement, wanted: set[str]):
    """(module, name or None for the whole module) that ``statement`` imports from wheelkin
    for the names in ``wanted``; a whole module also gives the attributes used on it."""
    node = statement.node
    if isinstance(node, ast.ImportFrom):
        source = _absolute(module.name, module.is_package, node)
        if source and (source == PACKAGE or source.startswith(PACKAGE + ".")):
            for alias in node.names:
                if bound_name(alias) in wanted:
                    yield source, alias.name
    elif isinstance(node, ast.Import):
        for alias in node.names:
            if alias.name.startswith(PACKAGE) and bound_name(alias) in wanted:
                yield alias.name, None


def _attributes_used(statements: list[Statement], alias: str) -> set[str] | None:
    """The attributes read on ``alias`` (``V.positive`` -> ``positive``) in ``statements``,
    or None if ``alias`` is used other than as ``alias.attribute``."""
    used: set[str] = set()
    for statement in statements:
        parents: dict[int, ast.AST] = {}
        for node in ast.walk(statement.node):
            for child in ast.iter_child_nodes(node):
                parents[id(child)] = node
        for node in ast.walk(statement.node):
            if isinstance(node, ast.Name) and node.id == alias and isinstance(node.ctx,
                                                                              ast.Load):
                parent = parents.get(id(node))
                if isinstance(parent, ast.Attribute) and parent.value is node:
                    used.add(parent.attr)
                else:
                    return None
    return used


def closure(parts: list[str], src: Path) -> dict[str, tuple[_Module, list[tuple[Statement,
                                                                                    str]]]]:
    """For each wheelkin module needed, the statements to keep (with their filtered source)."""
    wanted: dict[str, set[str] | None] = {}
    for part in parts:
        module, name = _split(part, src)
        wanted.setdefault(module, set()).add(name)
    modules: dict[str, _Module] = {}
    kept: dict[str, list[tuple[Statement, str]]] = {}
    changed = True
    while changed:
        changed = False
        for module_name in list(wanted):
            if module_name not in modules:
                modules[module_name] = _Module(src, module_name)
            module = modules[module_name]
            names = wanted[module_name]
            body = [s for s in module.statements if not (
                isinstance(s.node, ast.ImportFrom) and s.node.module == "__future__")]
            if names is None:  # the whole module (used other than by attribute)
                chosen = [(s, s.source) for s in body]
            else:
                chosen = needed_statements(body, set(names))
                missing = set(names) - set().union(*(s.binds for s, _ in chosen)) \
                    if chosen else set(names)
                missing -= {m for m in missing if _is_submodule(src, module_name, m)}
                if missing:
                    raise ValueError(f"{module_name} has no top-level {', '.join(sorted(missing))}")
            kept[module_name] = chosen
            for statement, _ in chosen:
                for alias_node in _aliases(statement):
                    for other, name in _wheelkin_imports(module, statement, {alias_node}):
                        if name is None or _is_submodule(src, other, name):
                            target = other if name is None else f"{other}.{name}"
                            attrs = _attributes_used([s for s, _ in chosen], alias_node)
                            changed |= _want(wanted, target, attrs)
                        else:
                            changed |= _want(wanted, other, {name})
            for name in names or ():  # a submodule asked for by name
                if _is_submodule(src, module_name, name):
                    changed |= _want(wanted, f"{module_name}.{name}", None)
    return {name: (modules[name], kept[name]) for name in kept}


def _aliases(statement: Statement) -> set[str]:
    node = statement.node
    if isinstance(node, (ast.Import, ast.ImportFrom)):
        return {bound_name(a) for a in node.names}
    return set()


def _is_submodule(src: Path, module: str, name: str) -> bool:
    try:
        _module_file(src, f"{module}.{name}")
    except ValueError:
        return False
    return True


def _want(wanted: dict, module: str, names: set[str] | None) -> bool:
    """Add ``names`` (None: the whole module) to what ``module`` must provide; True if that
    changed anything."""
    if module not in wanted:
        wanted[module] = None if names is None else set(names)
        return True
    have = wanted[module]
    if have is None:
        return False
    if names is None:
        wanted[module] = None
        return True
    if names <= have:
        return False
    have |= names
    return True


def build(parts: list[str], src: Path, out: Path, exercise: str = "") -> Path:
    """Write the package holding ``parts`` (dotted names) of the library found in ``src``
    (the folder holding ``wheelkin/``) into ``out/wheelkin``; return ``out``."""
    modules = closure(list(parts), src)
    packages = {PACKAGE}
    for name in modules:
        pieces = name.split(".")
        for k in range(1, len(pieces)):
            packages.add(".".join(pieces[:k]))
    for name in sorted(packages | set(modules)):
        module, chosen = modules.get(name, (None, []))
        is_package = name in packages
        path = out.joinpath(*name.split("."))
        path = path / "__init__.py" if is_package else path.with_suffix(".py")
        path.parent.mkdir(parents=True, exist_ok=True)
        lines = [f'"""{name}: only the parts that {exercise or "this exercise"} may use '
                 f'(written by the grader from the library\'s source)."""', ""]
        if module is not None and module.future:
            lines += ["from __future__ import annotations", ""]
        lines += [source.rstrip("\n") + "\n" for _, source in chosen]
        path.write_text("\n".join(lines), encoding="utf-8")
    return out


__all__ = ["build", "closure", "filtered_import"]
