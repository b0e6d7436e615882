"""A submitted notebook, read statically: its cells as Python, the ``check(...)`` calls, the
statements that ran, and the slice of them that an exercise's function needs.

The notebook's own run (in its sandbox, ``inside_run.py``) reports, cell by cell, whether it
ran to its end, stopped at an error (and on which line), or did not compile. Only what ran
counts: the check of an exercise that counts is the last ``check("name", f)`` statement, at
the top level of a cell, that ran; ``check`` calls in dead code (``if False:``, a function
never called), in a cell that stopped before them, or for an exercise the assignment does not
name are not graded.
"""

from __future__ import annotations

import ast
from dataclasses import dataclass

from tools.grading.source import (
    Statement,
    expression_names,
    needed_statements,
    statements_of,
)

#: The name of the exercises' check function (``from wheelkin.exercises import check``).
CHECK = "check"


def python_source(cell_source: str) -> str:
    """A code cell's source as the Python IPython runs (magics turned into calls)."""
    from IPython.core.inputtransformer2 import TransformerManager

    return TransformerManager().transform_cell(cell_source)


@dataclass
class Cell:
    index: int                       # its index among the notebook's cells
    source: str                      # as the student wrote it
    python: str | None               # as Python, or None if it does not compile
    statements: list[Statement]


def code_cells(nb) -> list[Cell]:
    """The notebook's code cells, each as Python and split into top-level statements."""
    out = []
    for index, cell in enumerate(nb.cells):
        if cell.get("cell_type") != "code":
            continue
        source = cell.get("source", "")
        source = "".join(source) if isinstance(source, list) else str(source)
        try:
            python = python_source(source)
            statements = statements_of(python, index)
        except (SyntaxError, ValueError, RecursionError, MemoryError, TypeError):
            python, statements = None, []
        out.append(Cell(index, source, python, statements))
    return out


@dataclass
class Check:
    """One ``check("name", expr)`` statement."""

    name: str
    expr: str
    statement: Statement


def checks(cells: list[Cell]) -> list[Check]:
    """Every top-level ``check("name", expr)`` statement, in notebook order."""
    found = []
    for cell in cells:
        for statement in cell.statements:
            node = statement.node
            if not (isinstance(node, ast.Expr) and isinstance(node.value, ast.Call)):
                continue
            call = node.value
            func = call.func
            name = func.id if isinstance(func, ast.Name) else (
                func.attr if isinstance(func, ast.Attribute) else None)
            if (name == CHECK and len(call.args) == 2 and not call.keywords
                    and isinstance(call.args[0], ast.Constant)
                    and isinstance(call.args[0].value, str)):
                found.append(Check(call.args[0].value, ast.unparse(call.args[1]), statement))
    return found


def ran(cells: list[Cell], report: dict[int, int | str]) -> list[Statement]:
    """The statements that ran to their end, in order. ``report`` maps a cell's index to
    ``"all"`` (the cell ran to its end) or to the line (of its Python) where it stopped at an
    error; a cell not in it did not run."""
    out = []
    for cell in cells:
        how = report.get(cell.index)
        if how == "all":
            out.extend(cell.statements)
        elif isinstance(how, int) and not isinstance(how, bool):
            out.extend(s for s in cell.statements if s.last_line < how)
    return out


def counted_checks(cells: list[Cell], ran_statements: list[Statement]) -> dict[str, Check]:
    """For each exercise name, the check that counts: the last one that ran."""
    done = {id(s.node) for s in ran_statements}
    out: dict[str, Check] = {}
    for found in checks(cells):
        if id(found.statement.node) in done:
            out[found.name] = found
    return out


def function_slice(check: Check, ran_statements: list[Statement]) -> list[str]:
    """The sources, in order, of the statements that ran before ``check`` and that its
    function needs."""
    before = []
    for statement in ran_statements:
        if statement.node is check.statement.node:
            break
        before.append(statement)
    return [source for _, source in needed_statements(before, expression_names(check.expr))]


def _tags(cell) -> set[str]:
    return set(cell.get("metadata", {}).get("tags", []))


def checked_names(cell) -> list[str]:
    """The exercises a single cell checks (``check("name", f)`` at its top level)."""
    import nbformat

    return [c.name for c in checks(code_cells(nbformat.v4.new_notebook(cells=[cell])))]


def with_solutions(student, book) -> object:
    """``student`` (a student edition of the notebook ``book``) with each exercise stub
    (tagged ``exercise``) replaced by ``book``'s solution (tagged ``solution``) of the same
    exercise: the notebook a student who solved everything hands in."""
    import copy

    solutions = {name: cell.source for cell in book.cells if "solution" in _tags(cell)
                 for name in checked_names(cell)}
    out = copy.deepcopy(student)
    for cell in out.cells:
        names = checked_names(cell) if "exercise" in _tags(cell) else []
        if names and names[0] in solutions:
            cell.source = solutions[names[0]]
    return out
