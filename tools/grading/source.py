"""Reading Python statically: what a top-level statement binds, uses and changes, and the
slice of a notebook (or a module) that a function needs.

The grader never runs a student's function where the notebook ran. It takes the
``check("name", function)`` statement that ran, and the statements of the notebook before it
that the function needs (transitively: the ``def`` of the function, the ``import numpy as
np`` it uses, a helper it calls and that helper's constants), and runs only those in a fresh
interpreter. :func:`needed_statements` computes that slice. The library's tree shaker
(``library_parts.py``) uses the same analysis on wheelkin's own modules.

What is found: names bound at the top level (``def``, ``class``, ``import``, assignments,
``for``/``with`` targets, also inside top-level ``if``/``try``/``for`` blocks), names a
statement uses (in its own code and, as globals, in the functions, lambdas and classes it
defines), and names it changes in place (``d[k] = v``, ``obj.attr = v``, ``lst.append(x)``).
What is not: names made by strings (``globals()[...]``, ``exec``) or by a star import of a
module whose names are not known; a function that needs those raises ``NameError`` when
graded.
"""

from __future__ import annotations

import ast
import copy
import symtable
from dataclasses import dataclass, field


@dataclass
class Statement:
    """One top-level statement of a cell (or a module)."""

    cell: int                 # the notebook cell it is in (0 for a module)
    position: int             # its place among the cell's statements
    source: str               # its Python source
    first_line: int           # its lines in the cell's Python source (1-based)
    last_line: int
    node: ast.stmt
    binds: frozenset[str] = frozenset()
    kills: frozenset[str] = frozenset()      # bound unconditionally: earlier bindings are dead
    loads: frozenset[str] = frozenset()      # read when it runs
    deferred: frozenset[str] = frozenset()   # read when a function it defines is called
    mutates: frozenset[str] = frozenset()
    methods: frozenset[str] = frozenset()    # names it calls a method of
    globals_set: frozenset[str] = frozenset()  # globals its functions assign when called
    calls: frozenset[str] = frozenset()      # names it calls at the top level
    star: bool = False


@dataclass
class Analysis:
    """The symbols of one statement."""

    binds: set[str] = field(default_factory=set)
    loads: set[str] = field(default_factory=set)      # read when the statement runs
    deferred: set[str] = field(default_factory=set)   # read when a function it defines runs
    globals_set: set[str] = field(default_factory=set)


class _StripAnnotations(ast.NodeTransformer):
    """Annotations removed (they are strings under ``from __future__ import annotations``,
    never evaluated, so they need nothing)."""

    def visit_FunctionDef(self, node):
        node.returns = None
        self.generic_visit(node)
        return node

    visit_AsyncFunctionDef = visit_FunctionDef

    def visit_arg(self, node):
        node.annotation = None
        return node

    def visit_AnnAssign(self, node):
        node.annotation = ast.Constant("")
        self.generic_visit(node)
        return node


def analyse(node: ast.stmt, *, annotations: bool = True) -> Analysis:
    """The names ``node`` binds at the top level, the global names it (or anything it
    defines) reads, and the globals its functions assign."""
    if not annotations:
        node = _StripAnnotations().visit(copy.deepcopy(node))
    source = ast.unparse(ast.Module(body=[node], type_ignores=[]))
    table = symtable.symtable(source, "<statement>", "exec")
    out = Analysis()
    for sym in table.get_symbols():
        if sym.is_assigned() or sym.is_imported():
            out.binds.add(sym.get_name())
        if sym.is_referenced():
            out.loads.add(sym.get_name())

    def walk(tab, deferred: bool) -> None:
        for child in tab.get_children():
            # A def's or a lambda's body runs later; a class body or a comprehension now.
            later = deferred or (child.get_type() == "function"
                                 and child.get_name() not in _COMPREHENSIONS)
            for sym in child.get_symbols():
                if sym.is_global() and sym.is_referenced():
                    (out.deferred if later else out.loads).add(sym.get_name())
                if sym.is_declared_global() and sym.is_assigned():
                    out.globals_set.add(sym.get_name())
            walk(child, later)

    walk(table, False)
    return out


_COMPREHENSIONS = {"listcomp", "setcomp", "dictcomp", "genexpr",
                   "<listcomp>", "<setcomp>", "<dictcomp>", "<genexpr>"}


def _base_name(node: ast.AST) -> str | None:
    """``x`` for ``x``, ``x.a.b``, ``x[i].c`` ..."""
    while isinstance(node, (ast.Attribute, ast.Subscript)):
        node = node.value
    return node.id if isinstance(node, ast.Name) else None


def _module_level(node: ast.AST):
    """The nodes of ``node`` that run when it runs at the top level: not the body of a def
    or a lambda (a class body does run, its methods' bodies do not)."""
    def children(item: ast.AST):
        if isinstance(item, (ast.FunctionDef, ast.AsyncFunctionDef)):
            return [*item.decorator_list, *item.args.defaults,
                    *(d for d in item.args.kw_defaults if d is not None)]
        if isinstance(item, ast.Lambda):
            return [*item.args.defaults, *(d for d in item.args.kw_defaults if d is not None)]
        return list(ast.iter_child_nodes(item))

    stack = [node]
    while stack:
        item = stack.pop()
        yield item
        stack.extend(children(item))


def mutations_and_calls(node: ast.stmt) -> tuple[set[str], set[str], set[str]]:
    """Names ``node`` changes in place at the top level (attribute or item assignment,
    ``del x[i]``), names it calls a method of (``lst.append(x)``, ``np.sin(x)``: a change
    only if the name is not a module), and plain names it calls (``f(...)``)."""
    mutated, methods, called = set(), set(), set()
    for item in _module_level(node):
        targets = []
        if isinstance(item, ast.Assign):
            targets = item.targets
        elif isinstance(item, (ast.AugAssign, ast.AnnAssign)):
            targets = [item.target]
        elif isinstance(item, ast.Delete):
            targets = item.targets
        for target in targets:
            for sub in ast.walk(target):
                if isinstance(sub, (ast.Attribute, ast.Subscript)):
                    base = _base_name(sub)
                    if base:
                        mutated.add(base)
        if isinstance(item, ast.Call):
            if isinstance(item.func, ast.Attribute):
                base = _base_name(item.func)
                if base:
                    methods.add(base)
            elif isinstance(item.func, ast.Name):
                called.add(item.func.id)
    return mutated, methods, called


def _kills(node: ast.stmt) -> set[str]:
    """Names ``node`` rebinds whatever happens (so earlier bindings of them are dead)."""
    if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)):
        return {node.name}
    if isinstance(node, (ast.Import, ast.ImportFrom)):
        return {bound_name(a) for a in node.names if a.name != "*"}
    if isinstance(node, ast.Assign):
        return {t.id for t in node.targets if isinstance(t, ast.Name)}
    if isinstance(node, ast.AnnAssign) and node.value is not None and isinstance(
            node.target, ast.Name):
        return {node.target.id}
    return set()


def bound_name(alias: ast.alias) -> str:
    """The name an import binds: ``np`` for ``import numpy as np``, ``os`` for
    ``import os.path``."""
    return alias.asname or alias.name.split(".")[0]


def statements_of(source: str, cell: int = 0, *, annotations: bool = True) -> list[Statement]:
    """The top-level statements of ``source`` (raises ``SyntaxError``)."""
    tree = ast.parse(source)
    lines = source.splitlines(keepends=True)
    out = []
    for position, node in enumerate(tree.body):
        first = min([node.lineno] + [d.lineno for d in getattr(node, "decorator_list", [])])
        text = "".join(lines[first - 1: node.end_lineno])
        found = analyse(node, annotations=annotations)
        mutated, methods, called = mutations_and_calls(node)
        star = isinstance(node, ast.ImportFrom) and any(a.name == "*" for a in node.names)
        out.append(Statement(cell, position, _single(text, node), first, node.end_lineno,
                             node, frozenset(found.binds), frozenset(_kills(node)),
                             frozenset(found.loads), frozenset(found.deferred),
                             frozenset(mutated), frozenset(methods),
                             frozenset(found.globals_set), frozenset(called), star))
    return out


def _single(text: str, node: ast.stmt) -> str:
    """The statement's text; a statement that shares its first line with another (``a = 1;
    b = 2``) is given as its unparsed form instead."""
    try:
        compiled = ast.parse(text)
    except SyntaxError:
        return ast.unparse(node)
    if len(compiled.body) != 1:
        return ast.unparse(node)
    return text


def filtered_import(statement: Statement, wanted: set[str]) -> str:
    """The source of an import statement reduced to the names in ``wanted`` (``from m import
    a, b, c`` -> ``from m import b``), so that one missing name does not lose the others."""
    node = statement.node
    if not isinstance(node, (ast.Import, ast.ImportFrom)):
        return statement.source
    keep = [a for a in node.names if a.name == "*" or bound_name(a) in wanted]
    if len(keep) == len(node.names):
        return statement.source
    new = copy.copy(node)
    new.names = keep
    return ast.unparse(new) + "\n"


def needed_statements(statements: list[Statement],
                      needed: set[str]) -> list[tuple[Statement, str]]:
    r"""The statements (in order, with the source to run) that bind, change or define what
    ``needed`` names, transitively; ``statements`` are those that ran before the point of
    use, in order.

    >>> code = "import math, os\nK = 2\nJ = 3\ndef f(x):\n    return K * math.sqrt(x)\nK = 4\n"
    >>> [src.strip() for _, src in needed_statements(statements_of(code), {"f"})]
    ['import math', 'def f(x):\n    return K * math.sqrt(x)', 'K = 4']
    """
    # A call of a function that assigns globals (``global K``) changes those globals.
    setters = {s.node.name: s.globals_set for s in statements
               if isinstance(s.node, (ast.FunctionDef, ast.AsyncFunctionDef)) and s.globals_set}
    # A method call changes its object, unless the object is a module (``np.sin(x)``) or
    # a name imported from one (``RADON_ULZER.replace(...)`` makes a new spec): names that
    # only imports bind are not changed by calling their methods.
    imported = set().union(*(s.binds for s in statements
                             if isinstance(s.node, (ast.Import, ast.ImportFrom))))
    assigned = set().union(*(s.binds for s in statements
                             if not isinstance(s.node, (ast.Import, ast.ImportFrom))))
    modules = imported - assigned
    effects = {id(s): set(s.mutates) | (s.methods - modules)
               | set().union(*(setters[f] for f in s.calls & setters.keys()))
               for s in statements}
    at_end = set(needed)  # names whose value when the function is called matters
    while True:
        chosen, deferred = _scan(statements, at_end, effects)
        if deferred <= at_end:
            return chosen
        at_end |= deferred


def _scan(statements, at_end, effects):
    """One backward pass from the point of use: the statements chosen, and the globals that
    the functions they define read when called (needed at the point of use)."""
    needed = set(at_end)
    deferred: set[str] = set()
    chosen: list[tuple[Statement, str]] = []
    for statement in reversed(statements):
        if not (statement.star or statement.binds & needed or effects[id(statement)] & needed
                or statement.globals_set & needed):
            continue
        wanted = set(needed)
        chosen.append((statement, filtered_import(statement, wanted)))
        deferred |= statement.deferred
        if isinstance(statement.node, (ast.Import, ast.ImportFrom)):
            needed -= statement.kills & wanted
            continue
        needed -= statement.kills - statement.loads
        needed |= set(statement.loads)
    chosen.reverse()
    return chosen, deferred


def expression_names(expr: str) -> set[str]:
    """The global names an expression (a check's function argument) reads."""
    node = ast.parse(expr, mode="eval")
    found = analyse(ast.Expr(node.body))
    return found.loads | found.deferred
